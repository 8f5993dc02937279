"""The side-by-side table of a tower sheet: rocking, belfry, gable, kinematic and LV1 checks.

:func:`checks_table` turns one assess summary row into the rows of the sheet's table
(a_C [g] and I_S of each check, bounds signed, the details of each) and the sentences
under it (the governing check, where the checks disagree and why, the checks not made);
:mod:`rockscreen.pipeline.report.html.adapters.risk` puts them on the sheet. See
docs/code_checks.md for what each check is.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from rockscreen.pipeline.archive.long_schema import CheckColumns
from rockscreen.pipeline.archive.risk_schema import KINEMATIC_PARTS, part_model_names
from rockscreen.pipeline.report.added_checks import (
    added_checks,
    capacity,
    check_details,
    not_made_reason,
)
from rockscreen.pipeline.report.html.adapters.common import num
from rockscreen.pipeline.report.html.i18n import STRINGS
from rockscreen.pipeline.report.html.model import (
    CheckCell,
    CheckRow,
    Key,
    Number,
    Sentence,
    SheetValue,
    finite,
)
from rockscreen.pipeline.report.values import Row
from rockscreen.pipeline.verdict.checks import check_label, loads_not_made
from rockscreen.pipeline.verdict.messages import Message, message
from rockscreen.pipeline.verdict.rules import NotMadeText
from rockscreen.pipeline.verdict.scales import class_marks

__all__ = ["checks_table", "governing_label"]


def _part_rows() -> list[tuple[str, str]]:
    """Return the part models with their own IDA row: (summary prefix, translation key).

    Every part model of the registry
    (:func:`~rockscreen.pipeline.archive.risk_schema.part_model_names`), labelled
    ``c_<model>`` where the report has that entry, else by the model's own label
    (``model_<model>``).
    """
    return [
        (name, f"c_{name}" if f"c_{name}" in STRINGS else f"model_{name}")
        for name in part_model_names()
    ]


def _sign(row: Row, bound_key: str) -> str:
    return {"lower": ">", "upper": "<"}.get(str(row.get(bound_key) or ""), "")


def _pair(row: Row, ac_key: str, si_key: str, bound_key: str) -> tuple[str | Number, str | Number]:
    """Return the a_C [g] and I_S cells of a check (bounds signed), or ``"-"``."""
    sign = _sign(row, bound_key)
    if finite(row.get(ac_key)) is None:
        return "-", "-"
    return num(row.get(ac_key), "g", 3, sign), num(row.get(si_key), "", 3, sign)


def checks_table(
    row: Row, checks: Sequence[CheckColumns] = ()
) -> tuple[list[CheckRow], list[Sentence]]:
    """Return the side-by-side table of one assessed tower and the sentences under it.

    Rows: whole-tower rocking (its IDA: a_C = SLV median / F_C, I_S; the collapse median and
    P50), belfry rocking and bell-gable rocking (each model's own IDA; the belfry's row says
    why when it was not checked), the kinematic checks of each part
    checked (whole tower, belfry, bell gable; linear and non-linear, Circolare 2019
    §C8.7.1), and the LV1 model of the shaft (DPCM 9/2/2011 §5.4.4). A check not made says
    why. Sentences: the governing check, where rocking and the checks disagree and why, the
    checks not made. Empty for an archive without the checks (before issue 22).

    Parameters
    ----------
    row : mapping
        One ``/summary`` row of an assess archive.
    checks : sequence of CheckColumns
        The checks the archive stores (:meth:`~rockscreen.pipeline.archive.kinds.
        AssessReader.checks`): each one the rows above do not show (a check added as a
        module, :func:`~rockscreen.pipeline.report.added_checks.added_checks`) gets its
        row after LV1's, labelled from the catalogue (``check.<id>``), its details or why
        it was not made.

    Returns
    -------
    rows : list of tuple
        ``(label, a_C, I_S, details)`` (label: a translation key ``c_*``; numbers of
        :func:`num` or text).
    text : list of (str, dict)
        Translation keys (``c_governing``, ``c_disagree``, ``c_not_made``) and their values
        (numbers of :func:`num`, or archive text the renderer translates as a note).
    """
    if "governing" not in row:
        return [], []
    rows = [*_rocking_rows(row), *_kinematic_rows(row), _lv1_row(row)]
    rows += [_added_row(row, check) for check in added_checks(checks)]
    return rows, _sentences(row)


def _added_row(row: Row, check: CheckColumns) -> CheckRow:
    """Return the row of a check added as a module: its a_C, I_S and details, or why not."""
    label = check_label(check.check, check.part)
    if capacity(row, check) is None:
        return (label, "-", "-", not_made_reason(row, check))
    ac, si = _pair(row, *check.keys)
    return (label, ac, si, check_details(row, check) or "-")


def _rocking_rows(row: Row) -> list[CheckRow]:
    """Return the rocking rows: the whole tower, then each part model with its own IDA.

    The whole tower: a_C = SLV median / F_C and I_S, with the collapse median and P50; a
    part model (belfry, bell gable): its own IDA's a_C and I_S, fragility median, beta and
    P50, or (the belfry) why it was not checked.
    """
    ac, si = _pair(row, "capacity_pga_g", "safety_index", "slv_bound")
    median = finite(row.get("collapse_median_g"))
    detail: CheckCell = (
        Key(key="c_d_no_fragility")
        if median is None
        else (
            "c_d_fragility",
            {
                "median": num(median, "g", 3, _sign(row, "collapse_bound")),
                "p50": num(row.get("p_overturning_50y"), "", 2),
            },
        )
    )
    rows: list[CheckRow] = [("c_rocking", ac, si, detail)]
    for part, label in _part_rows():
        if finite(row.get(f"{part}_fragility_median_g")) is not None:
            ac, si = _pair(
                row, f"{part}_capacity_ag_g", f"{part}_safety_index", f"{part}_slv_bound"
            )
            sign = _sign(row, f"{part}_fragility_bound")
            detail = (
                "c_d_part",
                {
                    "median": num(row.get(f"{part}_fragility_median_g"), "g", 3, sign),
                    "beta": num(row.get(f"{part}_fragility_beta"), "", 2),
                    "p50": num(row.get(f"{part}_p_overturning_50y"), "", 2),
                },
            )
            rows.append((label, ac, si, detail))
        elif _not_made_check(row, f"{part}.rocking"):  # the belfry: say why not checked
            rows.append((label, "-", "-", _why(row, f"{part}.rocking")))
    return rows


def _kinematic_rows(row: Row) -> list[CheckRow]:
    """Return the kinematic checks' rows of each part checked (Circolare 2019 §C8.7.1).

    Two rows per part (linear: alpha0, e*, a0*, T0; non-linear: d*_u and T at the SLV);
    a part without ``<part>_kinematic_alpha0`` has none.
    """
    rows: list[CheckRow] = []
    # a kinematic part's columns are <part>_kinematic_*; its rows' labels c_<part>_<kind>
    for prefix in (f"{part}_" for part in KINEMATIC_PARTS):
        if finite(row.get(f"{prefix}kinematic_alpha0")) is None:
            continue
        for kind in ("linear", "nonlinear"):
            key = f"{prefix}kinematic_{kind}"
            ac, si = _pair(row, f"{key}_capacity_ag_g", f"{key}_safety_index", f"{key}_bound")
            detail: Sentence = (
                "c_d_kinematic_linear",
                {
                    "alpha0": num(row.get(f"{prefix}kinematic_alpha0"), "", 3),
                    "e_star": num(row.get(f"{prefix}kinematic_e_star"), "", 3),
                    "a0": num(row.get(f"{prefix}kinematic_a0_g"), "g", 3),
                    "t0": num(row.get(f"{prefix}kinematic_t0_s"), "s", 3),
                },
            )
            if kind == "nonlinear":
                detail = (
                    "c_d_kinematic_nonlinear",
                    {
                        "d_slv": num(row.get(f"{prefix}kinematic_du_star_m"), "m", 3),
                        "t_slv": num(row.get(f"{prefix}kinematic_t_slv_s"), "s", 3),
                    },
                )
            rows.append((f"c_{prefix}{kind}", ac, si, detail))
    return rows


def _lv1_row(row: Row) -> CheckRow:
    """Return the row of the shaft's LV1 model (DPCM 9/2/2011 §5.4.4), or why not made."""
    if finite(row.get("lv1_capacity_ag_g")) is None:
        return ("c_lv1", "-", "-", _why(row, "shaft.lv1"))
    ac, si = _pair(row, "lv1_capacity_ag_g", "lv1_safety_index", "lv1_bound")
    values: dict[str, SheetValue] = {"t1": num(row.get("lv1_period_s"), "s", 3)}
    detail: Sentence = ("c_d_lv1", values)
    if finite(row.get("lv1_compression_ratio")) is not None:  # older archives lack it
        values["ratio"] = num(row["lv1_compression_ratio"], "", 2)
        detail = ("c_d_lv1_ratio", values)
    return ("c_lv1", ac, si, detail)


def _sentences(row: Row) -> list[Sentence]:
    """Return the sentences under the table: governing check, disagreement, checks not made."""
    text: list[Sentence] = []
    if row.get("governing"):
        sign = _sign(row, "governing_bound")
        values: dict[str, SheetValue] = {
            "label": governing_label(row),
            "ac": num(row.get("governing_capacity_ag_g"), "g", 3, sign),
            "si": num(row.get("governing_safety_index"), "", 3, sign),
        }
        text.append(("c_governing", values))
    if row.get("checks_disagree"):
        text.append(("c_disagree", {"text": str(row["checks_disagree"])}))
    if str(row.get("checks_not_made") or ""):
        text.append(("c_not_made", {"text": _not_made(row)}))
    return text


def governing_label(row: Mapping[str, object]) -> Message | str:
    """Return the governing check's label, from its id (rendered in the page's language).

    Marked when it is a lower bound not shown to govern; an archive without
    ``governing_check`` shows its stored ``governing`` text.
    """
    check = str(row.get("governing_check") or "")
    if not check:
        return str(row["governing"])
    label = check_label(check, check.split(".")[0])
    if row.get("governing_shown") is False or str(row.get("governing_shown")) == "False":
        return message("check.not_shown_to_govern", label=label)
    return label


def _not_made_check(row: Mapping[str, object], check: str) -> bool:
    """Whether the check ``check`` (an id) is among the row's checks not made.

    An archive written before ``checks_not_made_codes`` names only the belfry's rocking
    check among the part models' (its ``checks_not_made`` text says why).
    """
    codes = row.get("checks_not_made_codes")
    if codes:
        return check in loads_not_made(codes)
    return check == "belfry.rocking"


def _why(row: Mapping[str, object], check: str) -> Message | str | Key:
    """Return why the check ``check`` (an id) was not made (``"not made"`` without a reason).

    Its message, read from ``checks_not_made_codes`` by the check's id (rendered in the
    page's language); an archive written before that column shows its whole
    ``checks_not_made``.
    """
    codes = row.get("checks_not_made_codes")
    if codes:
        reason = loads_not_made(codes).get(check)
        return {"key": "c_d_not_made"} if reason is None else reason
    return str(row.get("checks_not_made") or "") or {"key": "c_d_not_made"}


def _not_made(row: Mapping[str, object]) -> NotMadeText | str:
    """Return the checks not made: from their messages, or (older archives) as stored."""
    codes = row.get("checks_not_made_codes")
    if codes:
        reasons = tuple(loads_not_made(codes).values())
        return NotMadeText(class_marks(row).completeness, reasons)
    return str(row.get("checks_not_made") or "")
