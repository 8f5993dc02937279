"""The screening risk of an assess archive on the report: the ranked list and the sheet's parts.

Issue 31 (RISK_CONTRACT): the screening risk (``risk_*`` columns of ``/summary``, the long
tables ``/risk_fragility``, ``/risk_sensitivity``, ``/risk_top_n``) answers *which towers
first, and how sure is that?* with best estimates; the code's verdict (``risk_class``, the
class of the governing check at the code's strengths) answers *does the tower meet the
code?*. The two are shown beside each other, labelled, never mixed:

- :func:`ranked_list`: the first screen's list, riskiest first (rank, tower, P50 best with
  its 90 % interval, bounds kept as bounds, band, band uncertain, governing mechanism,
  survey first with its expected narrowing), each row with the code's class and governing
  check beside; and the region's "what to survey first" from ``/risk_top_n``, naming the
  tower whose place changes most if its masonry is surveyed;
- :func:`risk_sheet`: a tower's lines, its sensitivity bars (judgement inputs marked) and
  the fragility band's curves for the sheet's fragility figure.

An archive without the screening risk (older, or ``assess`` without it) gives a list that
says so (``computed`` false).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

from rockscreen.pipeline.report.html.adapters.common import num, python_value
from rockscreen.pipeline.report.html.adapters.risk_method import risk_methods
from rockscreen.pipeline.report.html.model import (
    Curve,
    Key,
    Masonry,
    Number,
    RankedList,
    RankedRow,
    RiskValue,
    SensitivityBar,
    Sentence,
    SurveyLine,
    finite,
)
from rockscreen.pipeline.report.values import Attrs, AttrValue, Row
from rockscreen.pipeline.verdict.messages import loads
from rockscreen.pipeline.verdict.screening_risk import RiskBound

__all__ = [
    "MASONRY_INPUTS",
    "SURVEY_SHOWN",
    "band_sign",
    "ranked_list",
    "risk_curves",
    "risk_sheet",
]

#: The inputs that a survey of the masonry measures (its type, its mean strength).
MASONRY_INPUTS = ("masonry_type", "fm_pa")
#: Lines of the region's "what to survey first" list.
SURVEY_SHOWN = 5


def band_sign(flag: AttrValue) -> str:
    """Return the sign of a risk value's bound flag: ``"<="``, ``">="``, ``"both"`` or ``""``.

    ``at_most`` (the value is at most this) prints as ``<=``, ``at_least`` as ``>=``;
    ``both`` is not a value.
    """
    bound = RiskBound.parse(python_value(flag))
    return {
        RiskBound.AT_MOST: "<=",
        RiskBound.AT_LEAST: ">=",
        RiskBound.BOTH: "both",
    }.get(bound, "")


def _value(row: Row, key: str) -> RiskValue:
    """Return one risk value for the page: the number (None when missing) and its sign."""
    return {"value": finite(row.get(key)), "sign": band_sign(row.get(f"{key}_bound"))}


def _text(value: AttrValue) -> str:
    value = python_value(value)
    return "" if value is None else str(value)


def _judged(row: Row) -> set[str]:
    return {name for name in _text(row.get("risk_judgement_inputs")).split(";") if name}


def _has_risk(row: Row) -> bool:
    rank = finite(row.get("risk_rank"))
    return rank is not None and rank >= 1


def ranked_list(
    attrs: Attrs,
    summary: Sequence[Row],
    top_n_rows: Sequence[Row] = (),
    sensitivity_rows: Sequence[Row] = (),
) -> RankedList:
    """Return the first screen's ranked list of an assess archive (plain data for the page).

    Parameters
    ----------
    attrs : mapping
        Root attributes (``risk_methods``, ``risk_top_n``).
    summary : sequence of mapping
        ``/summary`` rows: the ``risk_*`` columns, and the code's ``risk_class`` and
        ``governing_check``.
    top_n_rows : sequence of mapping
        ``/risk_top_n`` rows: ``tower_id``, ``side`` (``in``/``out``), ``input``,
        ``p_crosses`` [1].
    sensitivity_rows : sequence of mapping
        ``/risk_sensitivity`` rows: where no ``/risk_top_n`` line is a masonry input, the
        tower whose masonry narrows its interval most.

    Returns
    -------
    RankedList
        ``computed`` (bool: the archive has the screening risk), ``rows`` (riskiest first:
        ``rank``, ``id``, ``p50`` / ``lo`` / ``hi`` (``{"value", "sign"}``), ``band``,
        ``uncertain``, ``mechanism``, ``share``, ``survey``, ``narrowing``,
        ``survey_judgement``, ``code_class``, ``code_check``), ``unranked`` (ids of the
        towers without a risk), ``top_n``, ``survey`` (the region's lines, most likely to
        change the list first: ``id``, ``side``, ``input``, ``p``, ``judgement``) and
        ``masonry`` (the tower whose place changes most if its masonry is surveyed:
        ``id``, ``input``, ``p`` from ``/risk_top_n``, ``basis`` ``"top_n"``; else the
        one whose interval it narrows most: ``index``, ``narrowing``, ``basis``
        ``"sensitivity"``; or None).
    """
    # what the archive says it computed (``[]``: assess run without the screening risk);
    # an archive without the attribute: whether any tower has a rank
    if "risk_methods" in attrs:
        computed = bool(risk_methods(attrs))
    else:
        computed = any(_has_risk(row) for row in summary)
    ranked = sorted(
        (row for row in summary if _has_risk(row)),
        key=lambda row: (float(row["risk_rank"]), str(row.get("id", ""))),
    )
    rows: list[RankedRow] = [
        {
            "rank": int(float(row["risk_rank"])),
            "id": _text(row.get("id")),
            "p50": _value(row, "risk_p50_best"),
            "lo": _value(row, "risk_p50_lo90"),
            "hi": _value(row, "risk_p50_hi90"),
            "band": _text(row.get("risk_band")),
            "uncertain": _text(row.get("risk_band_uncertain")) == "yes",
            "mechanism": _text(row.get("risk_governing_mechanism")),
            "share": finite(row.get("risk_governing_share")),
            "survey": _text(row.get("risk_survey_first")),
            "narrowing": finite(row.get("risk_survey_first_narrowing")),
            "survey_judgement": _text(row.get("risk_survey_first")) in _judged(row),
            "code_class": row.get("risk_class"),
            "code_check": _text(row.get("governing_check")),
        }
        for row in ranked
    ]
    top_n = python_value(attrs.get("risk_top_n"))
    judged = {_text(row.get("id")): _judged(row) for row in summary}
    lines: list[SurveyLine] = sorted(
        (
            SurveyLine(
                id=_text(r.get("tower_id")),
                side=_text(r.get("side")),
                input=_text(r.get("input")),
                p=p,
                judgement=_text(r.get("input")) in judged.get(_text(r.get("tower_id")), ()),
            )
            for r in top_n_rows
            if (p := finite(r.get("p_crosses")))
        ),
        key=lambda line: (-line["p"], line["id"], line["input"]),
    )
    first = next((line for line in lines if line["input"] in MASONRY_INPUTS), None)
    masonry: Masonry | None
    if first is not None and first["p"] > 0:
        masonry = {**first, "basis": "top_n"}
    else:
        masonry = _masonry_by_index(sensitivity_rows)
    return {
        "computed": computed,
        "rows": rows,
        "unranked": [_text(row.get("id")) for row in summary if not _has_risk(row)],
        "top_n": int(top_n) if top_n is not None else min(10, len(rows)),
        "survey": [line for line in lines if line["p"] > 0][:SURVEY_SHOWN],
        "masonry": masonry,
    }


def _masonry_by_index(sensitivity: Sequence[Row]) -> Masonry | None:
    """Return the tower whose interval a masonry survey narrows most (``/risk_sensitivity``).

    Used when no tower's line of ``/risk_top_n`` is a masonry input (each tower's line names
    the one input most likely to move it across the top-N line): the tower whose masonry
    inputs (:data:`MASONRY_INPUTS`) have the largest first-order index, or None.
    """
    best: Masonry | None = None
    for r in sensitivity:
        index = finite(r.get("index"))
        if _text(r.get("input")) in MASONRY_INPUTS and index and index > 0:
            if best is None or index > best["index"]:
                best = {
                    "id": _text(r.get("tower_id")),
                    "input": _text(r.get("input")),
                    "judgement": _text(r.get("judgement")) == "yes",
                    "index": index,
                    "narrowing": finite(r.get("narrowing")),
                    "basis": "sensitivity",
                }
    return best


def risk_curves(fragility: Sequence[Row]) -> list[Curve]:
    """Return a tower's fragility band as curves: the median and the 5 % and 95 % lines.

    Parameters
    ----------
    fragility : sequence of mapping
        The tower's ``/risk_fragility`` rows: ``ag_g`` [g], ``p_median``, ``p_lo90``,
        ``p_hi90`` [1].
    """
    points = sorted(
        (r for r in fragility if finite(r.get("ag_g")) is not None and float(r["ag_g"]) > 0),
        key=lambda r: float(r["ag_g"]),
    )
    if not points:
        return []
    x = [round(float(r["ag_g"]), 6) for r in points]

    def column(key: str) -> list[float]:
        return [round(finite(r.get(key)) or 0.0, 6) for r in points]

    return [
        Curve("fc_risk_median", x, column("p_median"), "line"),
        Curve("fc_risk_lo", x, column("p_lo90"), "dashed"),
        Curve("fc_risk_hi", x, column("p_hi90"), "dashed"),
    ]


def _sign_of(flag: AttrValue) -> str:
    """Return a bound flag as the sheet's number sign (``<=`` at most, ``>=`` at least)."""
    sign = band_sign(flag)
    return sign if sign in ("<=", ">=") else ""


def risk_sheet(
    row: Row, n_ranked: int, sensitivity: Sequence[Row]
) -> tuple[list[Sentence], list[SensitivityBar]]:
    """Return a tower's screening-risk lines and its sensitivity bars.

    Parameters
    ----------
    row : mapping
        The tower's ``/summary`` row.
    n_ranked : int
        How many towers have a rank.
    sensitivity : sequence of mapping
        The tower's ``/risk_sensitivity`` rows (``input``, ``index``, ``narrowing`` [1],
        ``judgement`` ``yes``/``no``).

    Returns
    -------
    lines : list of (str, dict)
        Translation keys and their values (``s_risk_p50``, ``s_risk_mech``, then one
        ``s_risk_note`` per message of ``risk_note_codes``; or ``s_risk_none``).
    bars : list of SensitivityBar
        ``(input translation key, index, narrowing, judgement)``, largest index first.
    """
    # the risk side's own notes (judgement priors, bounded samples, a mechanism left out,
    # why a tower has no risk), rendered from their codes in the page's language
    notes: list[Sentence] = [
        ("s_risk_note", {"note": note}) for note in loads(_text(row.get("risk_note_codes")))
    ]
    if not _has_risk(row):
        return [("s_risk_none", {}), *notes], []
    best_flag = band_sign(row.get("risk_p50_best_bound"))
    best: Key | Number = (
        {"key": "rk_both"}
        if best_flag == "both"
        else num(row.get("risk_p50_best"), "", 2, _sign_of(row.get("risk_p50_best_bound")))
    )
    lines: list[Sentence] = [
        (
            "s_risk_p50",
            {
                "best": best,
                "lo": num(
                    row.get("risk_p50_lo90"), "", 2, _sign_of(row.get("risk_p50_lo90_bound"))
                ),
                "hi": num(
                    row.get("risk_p50_hi90"), "", 2, _sign_of(row.get("risk_p50_hi90_bound"))
                ),
                "rank": str(int(float(row["risk_rank"]))),
                "n": str(n_ranked),
                "band": {"key": f"band_{_text(row.get('risk_band'))}"},
                "uncertain": {"key": "rk_uncertain_suffix"}
                if _text(row.get("risk_band_uncertain")) == "yes"
                else "",
            },
        ),
        (
            "s_risk_mech",
            {
                "mechanism": {
                    "key": f"mech_{_text(row.get('risk_governing_mechanism'))}",
                    "raw": _text(row.get("risk_governing_mechanism")),
                },
                "share": num(100 * (finite(row.get("risk_governing_share")) or math.nan), "%", 2),
                "beta": num(row.get("risk_beta"), "", 2),
                "source": {
                    "key": f"beta_{_text(row.get('risk_beta_source'))}",
                    "raw": _text(row.get("risk_beta_source")),
                },
            },
        ),
    ]
    lines += notes
    bars: list[SensitivityBar] = [
        (
            f"inp_{_text(r.get('input'))}",
            finite(r.get("index")),
            finite(r.get("narrowing")),
            _text(r.get("judgement")) == "yes",
        )
        for r in sorted(sensitivity, key=lambda r: -(finite(r.get("index")) or 0.0))
    ]
    return lines, bars
