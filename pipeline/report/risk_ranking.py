"""The screening risk in text and JSON: the ranked list the terminal prints, inspect's object.

The screening risk (``risk_*`` columns of an assess summary, docs/risk.md "The screening
risk in assess") is printed beside the code's verdict, never mixed with it: the ranked list
gives each tower's best estimate of P(collapse in 50 years) with its 90 % interval over the
epistemic inputs (a bound printed ``<=`` / ``>=``, a value bounded both ways ``~?``), its band
(``?`` when the interval reaches another band), the mechanism that governs most samples,
what to survey first with the expected narrowing, and the code's class labelled "code
verdict".
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from rockscreen.pipeline.archive.risk_schema import RISK_BOUND_COLUMNS, RISK_SUMMARY_UNITS
from rockscreen.pipeline.report.risk_summary import table_lines
from rockscreen.pipeline.report.values import ColumnValue, JSONValue, Row, RowT
from rockscreen.pipeline.verdict.labels import class_label
from rockscreen.pipeline.verdict.messages import loads, render_all
from rockscreen.pipeline.verdict.scales import class_marks
from rockscreen.pipeline.verdict.screening_risk import RiskBound

__all__ = [
    "DEFAULT_RANKED",
    "RANKING_LEGEND",
    "ranked_rows",
    "ranking_lines",
    "risk_json",
    "signed",
]

#: Towers the terminal lists after ``assess`` (the riskiest first).
DEFAULT_RANKED = 10

RANKING_LEGEND = (
    "screening risk (best estimates: mean strengths, no partial or confidence factor; the "
    "code verdict beside is the code's, unchanged): P50 = P(collapse in 50 years), best = "
    "median over the epistemic samples of what the inventory does not say, [5 %, 95 %] = "
    "their 90 % interval; '<=' / '>=' a bound (samples whose capacity holds at 2475 y or fails "
    "at 30 y), '~?' bounded both ways (not a value); band by rank ('?': the interval reaches "
    "another band); survey first = the input whose exact value narrows the interval most "
    "(expected narrowing); rocking taken at the row's inputs (docs/risk.md)"
)


def _missing(value: ColumnValue) -> bool:
    return value is None or (isinstance(value, float) and math.isnan(value)) or value == ""


def signed(value: ColumnValue, bound: ColumnValue, fmt: str = ".3g") -> str:
    """Return a probability or rate with its bound's sign (``<=0.039``), ``-`` if none."""
    if _missing(value):
        return "-"
    return f"{RiskBound.parse(bound or '').sign}{format(float(value), fmt)}"


def _code_verdict(row: Row) -> str:
    """Return the code's class with its marks but not the list of checks not made."""
    marks = class_marks(row)
    return str(class_label(marks.cls, marks.basis_compliant, "", marks.completeness, marks.bound))


def ranked_rows(rows: Sequence[RowT]) -> list[RowT]:
    """Return the rows that have a risk rank, by rank (then id)."""
    have = [r for r in rows if not _missing(r.get("risk_rank")) and int(r["risk_rank"]) > 0]
    return sorted(have, key=lambda r: (int(r["risk_rank"]), str(r.get("id", ""))))


def ranking_lines(rows: Sequence[Row], top: int = DEFAULT_RANKED) -> list[str]:
    """Return the ranked list of the ``top`` riskiest towers (module docstring), [] if none.

    Parameters
    ----------
    rows : sequence of mapping
        Assess summary rows.
    top : int
        How many towers to list.
    """
    ranked = ranked_rows(rows)
    if not ranked:
        return []
    body = []
    for row in ranked[: max(int(top), 0)]:
        interval = (
            f"[{signed(row['risk_p50_lo90'], row['risk_p50_lo90_bound'])}, "
            f"{signed(row['risk_p50_hi90'], row['risk_p50_hi90_bound'])}]"
        )
        band = f"{row['risk_band']}{'?' if row.get('risk_band_uncertain') == 'yes' else ''}"
        governs = f"{row['risk_governing_mechanism']} ({float(row['risk_governing_share']):.2f})"
        survey = row.get("risk_survey_first") or "-"
        if survey != "-":
            survey = f"{survey} (narrows {float(row['risk_survey_first_narrowing']):.0%})"
        body.append(
            (
                int(row["risk_rank"]),
                row["id"],
                signed(row["risk_p50_best"], row["risk_p50_best_bound"]),
                interval,
                band,
                governs,
                survey,
                _code_verdict(row),
            )
        )
    header = (
        "rank",
        "tower",
        "P50 best",
        "[5 %, 95 %]",
        "band",
        "governs (share)",
        "survey first",
        "code verdict",
    )
    shown = f"the {len(body)} riskiest of {len(ranked)}" if len(ranked) > len(body) else "all"
    return [f"screening risk: {shown} ranked towers", *table_lines(header, body)]


def risk_json(row: Row) -> dict[str, JSONValue]:
    """Return a tower's screening risk for ``inspect --json``: the ``risk`` object.

    The ``risk_*`` columns without their prefix (NaN as null), each bounded value's sign in
    ``<name>_note`` (``"at most"``, ``"at least"``, ``"bounded both ways (not a value)"``), the
    notes rendered (``notes``) and ``available`` (false: the notes say why).
    """
    out: dict[str, JSONValue] = {}
    for column in RISK_SUMMARY_UNITS:
        value = row.get(column)
        if isinstance(value, float) and not math.isfinite(value):
            value = None
        out[column.removeprefix("risk_")] = value
    for column, bound in RISK_BOUND_COLUMNS.items():
        flag = RiskBound.parse(row.get(bound) or "")
        if flag is not RiskBound.NONE and out.get(column.removeprefix("risk_")) is not None:
            out[f"{column.removeprefix('risk_')}_note"] = {
                RiskBound.AT_MOST: "at most",
                RiskBound.AT_LEAST: "at least",
                RiskBound.BOTH: "bounded both ways (not a value)",
            }[flag]
    codes = row.get("risk_note_codes") or "[]"
    out["notes"] = render_all(loads(codes))
    out["available"] = out.get("p50_best") is not None
    return out
