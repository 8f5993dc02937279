"""Text and JSON views of assess and scenario summaries (CLI tables, ``inspect --json``)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, TypeVar

from rockscreen.pipeline.archive.bounds import bounded_columns, relation
from rockscreen.pipeline.archive.risk_schema import EXTRAPOLATION_SHARE_LIMIT
from rockscreen.pipeline.report.added_checks import added_checks, capacity, not_made_reason
from rockscreen.pipeline.report.values import ColumnValue, JSONValue, Row, RowT
from rockscreen.pipeline.verdict.checks import check_label, loads_not_made
from rockscreen.pipeline.verdict.labels import NONCOMPLIANT_MARK, row_class_label
from rockscreen.pipeline.verdict.messages import note_messages, render, render_all
from rockscreen.pipeline.verdict.scales import Completeness, class_marks

if TYPE_CHECKING:  # the archive's long tables import h5py: `rockscreen --help` does not
    from rockscreen.pipeline.archive.long_schema import CheckColumns

__all__ = [
    "ASSESS_LEGEND",
    "SCENARIO_LEGEND",
    "assess_lines",
    "checks_lines",
    "extrapolation_text",
    "interval_text",
    "json_number",
    "not_assessed_line",
    "rank_towers",
    "scenario_lines",
    "table_lines",
    "tower_json",
]


def _bound_group(row: Row) -> int:
    bound = row.get("collapse_bound", row.get("median_is_bound", ""))
    return {"upper": 0, "": 1, "lower": 2}.get(bound, 3)


def rank_towers(rows: Sequence[RowT]) -> list[RowT]:
    """Sort summary rows riskiest first.

    Order: towers that overturned at every stripe (upper-bound median), then the fitted
    ones by decreasing annual rate of overturning ``lambda_C``, then by increasing I_S;
    towers that never overturned (lower-bound median) last, by increasing I_S bound.
    """

    def key(row: Row) -> tuple[int, float, float, str]:
        rate = row.get("annual_rate_overturning_per_y", math.nan)
        index = row.get("safety_index", math.nan)
        return (
            _bound_group(row),
            -rate if math.isfinite(rate) else math.inf,
            index if not math.isnan(index) else math.inf,
            str(row.get("id", "")),
        )

    return sorted(rows, key=key)


ASSESS_LEGEND = (
    "legend: collapse/SLV median, beta = censored lognormal fragilities in the site's ag on "
    "rock from each record's IDA intensity (records of the set at T_R,SLV; record-to-record "
    "variability only): collapse = overturning, SLV = theta_max/alpha >= 0.4 (Circolare 2019 "
    "§C8.7.1.2.1.6); '>' lower bound: too few records reached the level up to their censoring "
    "intensity; '<' upper bound; [lo-hi] = 90 % bootstrap interval over the records; "
    "lambda_C = mean annual frequency of overturning from the collapse fragility; P50 = "
    "probability in 50 years; extrap = share of lambda_C from the hazard "
    "curve extrapolated beyond TR 2475 y or below 30 y ('!' above "
    f"{100 * EXTRAPOLATION_SHARE_LIMIT:.0f} %); a_C = SLV median / F_C (confidence factor "
    "of the knowledge level); T_R,C = its return period; I_S = T_R,C / T_R,SLV (>= 1 meets "
    "the code, MiC 2011); f_a = a_C / a_g,SLV; stripe = median of the stripe fit (a check); "
    "classes on I_S: meets >= 1, moderate >= 0.6, high >= 0.3, "
    "very_high below (0.6 and 0.3 are rockscreen's choice); "
    f"'({NONCOMPLIANT_MARK})': built on record sets that fail NTC 2018 §3.2.3.6 "
    "(assess --allow-noncompliant)"
)
SCENARIO_LEGEND = (
    "legend: PGA = event peak ground acceleration at the tower (ShakeMap, surface); "
    "ag_equiv = PGA / S (soil factor of the tower's site, NTC 2018); "
    "P = Phi(ln(ag_equiv / median) / beta_tot), beta_tot = sqrt(beta^2 + sigma_lnPGA^2); "
    "'>' median: a lower bound (no record overturned the tower up to it), then '<' P: at most "
    "this, with beta taken as 1.0 (the largest record-to-record dispersion of real records); "
    "towers outside the grid are listed, not guessed"
)


def _num(value: object, fmt: str = ".3g") -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    if isinstance(value, float) and math.isinf(value):
        return "inf"
    return format(value, fmt)


def table_lines(header: Sequence[str], rows: Sequence[Sequence[object]]) -> list[str]:
    """Return an aligned text table (two spaces between columns, cells as ``str``)."""
    table = [tuple(header), *[tuple(str(c) for c in row) for row in rows]]
    widths = [max(len(line[i]) for line in table) for i in range(len(header))]
    return [
        "  ".join(c.ljust(w) for c, w in zip(line, widths, strict=True)).rstrip() for line in table
    ]


_Value = TypeVar("_Value")


def json_number(value: _Value) -> _Value | None:
    """Return ``value``, or None for a NaN or infinite float (JSON has neither)."""
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def _bounded(row: Row, value: float, sense: int = 1, key: str = "median_is_bound") -> str:
    """Prefix a bound: sense=+1 for quantities that grow with the median (a_C, T_R,C, I_S).

    ``key`` names the row's bound column (``collapse_bound``, ``slv_bound``, ...).
    """
    bound = row.get(key, "")
    if not bound:
        return _num(value)
    lower = (bound == "lower") == (sense > 0)
    return (">" if lower else "<") + _num(value)


#: Columns of the assess table (:func:`assess_lines`), units in brackets.
ASSESS_HEADER = (
    "tower",
    "class",
    "lambda_C [1/y] [90 %]",
    "P50 [-]",
    "extrap [-]",
    "collapse median [g] [90 %]",
    "beta [-]",
    "SLV median [g]",
    "beta [-]",
    "F_C [-]",
    "a_C [g]",
    "T_R,C [y]",
    "T_R,SLV [y]",
    "I_S [-] [90 %]",
    "f_a [-]",
    "stripe [g]",
    "soil",
)
#: Columns of the scenario table (:func:`scenario_lines`), units in brackets.
SCENARIO_HEADER = (
    "tower",
    "P(overturn) [-]",
    "PGA [g]",
    "ag_equiv [g]",
    "S [-]",
    "median [g]",
    "beta_tot [-]",
    "status",
)


def assess_lines(rows: Sequence[Row], checks: Sequence[CheckColumns] = ()) -> list[str]:
    """Return the ranked assess summary (riskiest first), units in the headers.

    ``checks``: the checks of the rows (:func:`checks_lines`).
    """
    body = []
    for row in rank_towers(rows):
        soil = row["soil_class"] + ("*" if row.get("soil_class_source") == "default" else "")
        collapse, slv = "collapse_bound", "slv_bound"
        body.append(
            (
                row["id"],
                row_class_label(row),
                _num(row["annual_rate_overturning_per_y"])
                + interval_text(row, "annual_rate_lo90_per_y", "annual_rate_hi90_per_y"),
                _num(row["p_overturning_50y"]),
                extrapolation_text(row),
                _bounded(row, row["collapse_median_g"], 1, collapse)
                + interval_text(row, "collapse_median_lo90_g", "collapse_median_hi90_g"),
                _num(row["collapse_beta"], ".2f"),
                _bounded(row, row["slv_median_g"], 1, slv),
                _num(row["slv_beta"], ".2f"),
                _num(row["confidence_factor"], ".2f"),
                _bounded(row, row["capacity_pga_g"], 1, slv),
                _bounded(row, row["capacity_return_period_y"], 1, slv),
                _num(row["tr_slv_y"], ".0f"),
                _bounded(row, row["safety_index"], 1, slv)
                + interval_text(row, "safety_index_lo90", "safety_index_hi90"),
                _bounded(row, row["acceleration_factor"], 1, slv),
                _bounded(row, row["stripe_median_g"], 1, "stripe_bound"),
                soil,
            )
        )
    lines = table_lines(ASSESS_HEADER, body)
    if any(r.get("soil_class_source") == "default" for r in rows):
        lines.append("* soil class assumed (not in the inventory)")
    if any(r.get("rate_extrapolated") for r in rows):
        lines.append(
            f"! more than {100 * EXTRAPOLATION_SHARE_LIMIT:.0f} % of lambda_C from the hazard "
            "curve extrapolated beyond its tabulated return periods (see the note)"
        )
    if any(r.get("basis_compliant") is False for r in rows):
        lines.append(f"({NONCOMPLIANT_MARK}): record sets failing NTC 2018 §3.2.3.6 (see the note)")
    return lines + checks_lines(rows, checks)


#: Columns of the side-by-side table of the checks (:func:`checks_lines`).
CHECKS_HEADER = (
    "tower",
    "governing",
    "I_S gov [-]",
    "rocking a_C [g]",
    "rocking I_S [-]",
    "belfry median [g]",
    "belfry P50 [-]",
    "belfry I_S [-]",
    "kin. mechanism",
    "kin. lin a_C [g]",
    "kin. lin I_S [-]",
    "kin. n-lin a_C [g]",
    "kin. n-lin I_S [-]",
    "LV1 a_C [g]",
    "LV1 I_S [-]",
)


def checks_lines(rows: Sequence[Row], checks: Sequence[CheckColumns] = ()) -> list[str]:
    """Return the checks side by side (rocking, belfry, kinematic, LV1) and where they disagree.

    Empty for summaries without the checks (older archives). Capacities are ag on rock [g]
    divided by F_C; ``>``/``<`` mark lower/upper bounds. ``checks``: the checks of the rows
    (an archive's :meth:`~rockscreen.pipeline.archive.kinds.AssessReader.checks`, or the
    registry's): each one the table's own columns do not show (a check added as a module,
    :func:`~rockscreen.pipeline.report.added_checks.added_checks`) gets its a_C and I_S
    columns, labelled from the catalogue.
    """
    rows = [r for r in rank_towers(rows) if r.get("governing")]
    if not rows:
        return []
    added = added_checks(checks)
    header = list(CHECKS_HEADER)
    for check in added:
        label = render(check_label(check.check, check.part))
        header += [f"{label} a_C [g]", f"{label} I_S [-]"]
    body = []
    for row in rows:
        lv1 = row.get("lv1_safety_index", math.nan)
        made = lv1 is not None and math.isfinite(lv1)
        body.append(
            (
                row["id"],
                row["governing"],
                _bounded(row, row["governing_safety_index"], 1, "governing_bound"),
                _bounded(row, row["capacity_pga_g"], 1, "slv_bound"),
                _bounded(row, row["safety_index"], 1, "slv_bound"),
                _bounded(row, row.get("belfry_fragility_median_g"), 1, "belfry_fragility_bound"),
                _num(row.get("belfry_p_overturning_50y")),
                _bounded(row, row.get("belfry_safety_index"), 1, "belfry_slv_bound"),
                row.get("kinematic_mechanism") or "-",
                _bounded(row, row["kinematic_linear_capacity_ag_g"], 1, "kinematic_linear_bound"),
                _bounded(row, row["kinematic_linear_safety_index"], 1, "kinematic_linear_bound"),
                _bounded(
                    row, row["kinematic_nonlinear_capacity_ag_g"], 1, "kinematic_nonlinear_bound"
                ),
                _bounded(
                    row, row["kinematic_nonlinear_safety_index"], 1, "kinematic_nonlinear_bound"
                ),
                _bounded(row, row.get("lv1_capacity_ag_g"), 1, "lv1_bound") if made else "-",
                _bounded(row, lv1, 1, "lv1_bound") if made else "not made",
                *(cell for check in added for cell in _added_cells(row, check)),
            )
        )
    lines = ["", "the code's checks beside the rocking dynamics (the class: the governing one)"]
    lines += table_lines(header, body)
    lines.append(
        "kinematic: Circolare 2019 §C8.7.1.2.1, the mechanism of lowest non-linear I_S "
        "(§C8.7.1.2.1.8; the linear check of §C8.7.1.2.1.7 beside) among the whole tower, the "
        "belfry and the bell gable; LV1: the Guidelines' tower "
        "model (DPCM 9/2/2011 §5.4.4), made when the inventory has wall_thickness_m and "
        "masonry_type (at LC3 also masonry_strength_mpa); on a church, its floor spectrum"
    )
    for row in rows:
        if row.get("checks_disagree"):
            lines.append(f"{row['id']}: {row['checks_disagree']}")
    missing: dict[str, list[str]] = {}
    for row in rows:
        if class_marks(row).completeness is Completeness.ROCKING_ONLY:
            missing.setdefault(row["checks_not_made"], []).append(str(row["id"]))
    lines += [f"{', '.join(ids)}: {text}" for text, ids in missing.items()]
    return lines


def _added_cells(row: Row, check: CheckColumns) -> tuple[str, str]:
    """Return an added check's a_C [g] and I_S [-] cells (bounds signed), or not made."""
    ag, index, bound = check.keys
    if capacity(row, check) is None:
        return "-", "not made"
    return _bounded(row, row[ag], 1, bound), _bounded(row, row.get(index), 1, bound)


def interval_text(row: Row, lo_key: str, hi_key: str) -> str:
    """Return `` [lo-hi]`` of a 90 % bootstrap interval, ``""`` when there is none."""
    lo, hi = row.get(lo_key), row.get(hi_key)
    if lo is None or hi is None or not (math.isfinite(lo) and math.isfinite(hi)):
        return ""
    return f" [{_num(lo)}-{_num(hi)}]"


def extrapolation_text(row: Row) -> str:
    """Return the extrapolated share of lambda_C [-] as printed, ``!`` when flagged."""
    above = row.get("rate_share_tr_over_2475", math.nan)
    below = row.get("rate_share_tr_under_30", math.nan)
    if above is None or below is None:
        return "-"
    return _num(above + below, ".2f") + ("!" if row.get("rate_extrapolated") else "")


def scenario_lines(rows: Sequence[Row]) -> list[str]:
    """Return the ranked scenario summary (most probable overturning first)."""

    def key(row: Row) -> tuple[bool, float, ColumnValue]:
        p = row["p_overturning"]
        return (math.isnan(p), -p if not math.isnan(p) else 0.0, row["id"])

    body = [
        (
            row["id"],
            relation(row, "p_overturning") + _num(row["p_overturning"]),
            _num(row["event_pga_g"]),
            _num(row["ag_equiv_g"]),
            _num(row["soil_factor"]),
            _bounded(row, row["fragility_median_g"]),
            _num(row["beta_total"], ".2f"),
            row["status"],
        )
        for row in sorted(rows, key=key)
    ]
    return table_lines(SCENARIO_HEADER, body)


#: Keys of every assessed tower in ``inspect --json`` (null with a ``<key>_note`` if undefined).
ASSESS_JSON_KEYS = (
    "collapse_median_g",
    "collapse_beta",
    "slv_median_g",
    "slv_beta",
    "annual_rate_overturning",
    "p_overturning_50y",
    "capacity_pga_g",
    "capacity_return_period_y",
    "safety_index",
    "acceleration_factor",
)


#: The kinematic checks' keys: a null one is explained by the ``kinematic.not_made`` message.
KINEMATIC_CHECKS = "kinematic"
#: Keys of the code's checks of every tower in ``inspect --json`` (issue 22): null with a
#: ``<key>_note`` saying why when the check was not made; bounds noted as above. Each key
#: names the check whose reason explains it (a check id of ``checks_not_made_codes``, or
#: :data:`KINEMATIC_CHECKS`; None: the tower's note), declared here, never read from the key.
CHECKS_JSON_KEYS: dict[str, str | None] = {
    "kinematic_alpha0": KINEMATIC_CHECKS,
    "kinematic_e_star": KINEMATIC_CHECKS,
    "confidence_factor": None,
    "kinematic_a0_g": KINEMATIC_CHECKS,
    "kinematic_linear_capacity_ag_g": KINEMATIC_CHECKS,
    "kinematic_nonlinear_capacity_ag_g": KINEMATIC_CHECKS,
    "kinematic_safety_index": KINEMATIC_CHECKS,
    "lv1_capacity_ag_g": "shaft.lv1",
    "lv1_safety_index": "shaft.lv1",
    "belfry_fragility_median_g": "belfry.rocking",
    "belfry_fragility_beta": "belfry.rocking",
    "belfry_p_overturning_50y": "belfry.rocking",
    "governing": None,
    "governing_kind": None,
}


def _check_reason(row: Row, key: str) -> str:
    """Return why a check's key is null: its check's reason (by id), else the note.

    The reason is read from ``checks_not_made_codes``; an archive written before that
    column gives its whole ``checks_not_made``.
    """
    check = CHECKS_JSON_KEYS.get(key)
    if check is not None and check != KINEMATIC_CHECKS:
        codes = row.get("checks_not_made_codes")
        reason = loads_not_made(codes).get(check) if codes else None
        if reason is not None:
            return render(reason)
        if not codes and row.get("checks_not_made"):
            return str(row["checks_not_made"])
    said = note_messages(row)
    if said is not None:  # the note's codes: the kinematic checks' own message
        if check == KINEMATIC_CHECKS:
            found = [m.render() for m in said if m.code == "kinematic.not_made"]
            if found:
                return found[0]
        return render_all(said) or "undefined"
    # an archive written before the note's codes: its English text (the older archives'
    # adapter: the one place a note is split)
    note = str(row.get("note") or "")
    if check == KINEMATIC_CHECKS and "kinematic checks not made" in note:
        return next(p for p in note.split("; ") if "kinematic checks not made" in p)
    return note or "undefined"


def tower_json(row: Row, checks: Sequence[CheckColumns] = ()) -> dict[str, JSONValue]:
    """Return one assess summary row for ``inspect --json`` (module docstring of the CLI).

    ``checks``: the checks of the row (:func:`checks_lines`); an added check's a_C and I_S
    not made are null with a ``<key>_note`` saying why, as the built-in checks' are.
    """
    out: dict[str, JSONValue] = {key: json_number(value) for key, value in row.items()}
    out["annual_rate_overturning"] = json_number(row["annual_rate_overturning_per_y"])
    for key in ASSESS_JSON_KEYS:
        if out.get(key) is None:
            out[f"{key}_note"] = row.get("note") or "undefined"
    for key, sign in bounded_columns(row).items():  # every bound says so (archive/bounds.py)
        if out.get(key) is not None:
            out[f"{key}_note"] = "lower bound" if sign == ">" else "upper bound"
    for key in CHECKS_JSON_KEYS:  # the code's checks: null, and why, when not made
        out.setdefault(key, None)
        if out[key] in (None, ""):
            out[key] = None
            out[f"{key}_note"] = _check_reason(row, key)
    for check in added_checks(checks):
        if capacity(row, check) is None:
            for key in check.keys[:2]:
                out[key] = None
                out[f"{key}_note"] = render(not_made_reason(row, check))
    return out


def not_assessed_line(failures: Sequence[Row], n_towers: int, archive: str) -> str:
    """Return the one line saying which towers an assessment did not assess, and where to read.

    Parameters
    ----------
    failures : sequence of mapping
        The ``/failures`` rows (``kind``, ``subject``, ``reason``): one per tower not
        assessed (``inventory``: an invalid row skipped with ``--skip-invalid``; ``site``:
        no coordinates; ``hazard``: no site hazard; ``selection``: no record set;
        ``compliance``: its record sets fail NTC 2018 §3.2.3.6/§7.3.5; ``error``: an
        unexpected error in the tower's own computation).
    n_towers : int
        Towers of the inventory (the skipped rows included).
    archive : str
        The archive written.

    Returns
    -------
    str
        E.g. ``"3 of 60 tower(s) not assessed (2 compliance, 1 inventory); each with its
        reason and fix in /failures: rockscreen inspect OUT"``; ``""`` when every tower was
        assessed.
    """
    if not failures:
        return ""
    kinds: dict[str, int] = {}
    for failure in failures:
        kinds[str(failure["kind"])] = kinds.get(str(failure["kind"]), 0) + 1
    counts = ", ".join(f"{n} {kind}" for kind, n in sorted(kinds.items(), key=lambda kv: -kv[1]))
    return (
        f"{len(failures)} of {n_towers} tower(s) not assessed ({counts}); each with its reason "
        f"and fix in /failures: rockscreen inspect {archive}"
    )
