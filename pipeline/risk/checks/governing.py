"""The mechanism that governs a tower's verdict in ``assess`` (issue 22).

Among the capacities a tower's summary row holds (``a_C`` [g], ag on rock, each read on
the same NTC hazard: docs/code_checks.md §8) -- whole-tower rocking (the IDA SLV capacity),
each part model's rocking
(:func:`rockscreen.pipeline.risk.checks.tower_checks.part_fragility_columns`), shaft flexure (LV1,
:mod:`rockscreen.pipeline.risk.checks.tower_lv1_checks`) and the non-linear kinematic checks
(:func:`rockscreen.pipeline.risk.checks.tower_checks.kinematic_columns`) --
:func:`governing_columns` names the lowest, gives the class of its ``I_S``, lists the
checks that could fail earlier and were not made (``checks_not_made``, which
:func:`rockscreen.pipeline.risk.measures.classes.class_label` prints), and says in one sentence
where rocking and the code's checks disagree, and why. The rules are pure functions over
typed check results (:mod:`rockscreen.pipeline.verdict.rules`); this module reads the
results off the row (:func:`tower_check_results`) and writes the verdict's columns back
(:func:`verdict_columns`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import NamedTuple

from rockscreen.pipeline.archive.long_schema import CheckColumns
from rockscreen.pipeline.archive.risk_schema import KINEMATIC_PARTS
from rockscreen.pipeline.risk.checks.registry import CodeCheck, code_check, made_result
from rockscreen.pipeline.risk.checks.tower_checks import part_model_names
from rockscreen.pipeline.risk.checks.tower_code_checks import registered_checks
from rockscreen.pipeline.verdict.checks import (
    CheckResult,
    Family,
    Method,
    Verdict,
    dumps_not_made,
    family_label,
)
from rockscreen.pipeline.verdict.messages import message, render, render_all
from rockscreen.pipeline.verdict.rules import governing_label, not_made_text, verdict
from rockscreen.pipeline.verdict.status import Status

__all__ = [
    "BELFRY_MISSING",
    "GOVERNING_KINDS",
    "MECHANISMS",
    "belfry_not_made",
    "check_columns",
    "governing_columns",
    "tower_check_results",
    "verdict_columns",
]

#: Why the belfry checks are not made (no belfry columns, and no bell gable carrying the
#: bells instead): the whole tower alone was checked.
BELFRY_MISSING = render(message("not_made.belfry"))
#: Mechanism labels of the ``governing`` column (``<part>`` rocking is the part model's name),
#: rendered from the catalogue (``check.*``).
MECHANISMS = {
    "rocking": render(message("check.tower.rocking")),
    "tower_nonlinear": render(message("check.tower.kinematic_nonlinear")),
    "belfry_nonlinear": render(message("check.belfry.kinematic_nonlinear")),
    "gable_nonlinear": render(message("check.gable.kinematic_nonlinear")),
    "lv1": render(message("check.lv1")),
}
#: The family of a part model's checks (its rocking, its kinematic check); others: their
#: own (``<part> rocking``, ``kinematic``).
_PART_FAMILY = {"gable": Family.GABLE}
#: What ``governing_kind`` says: the family of the governing mechanism (``family.*``).
GOVERNING_KINDS = (
    render(family_label(Family.SHAFT_FLEXURE)),
    render(family_label(Family.TOWER_ROCKING)),
    *(
        render(family_label(Family.PART_ROCKING, m))
        for m in part_model_names()
        if m not in _PART_FAMILY
    ),
    render(family_label(Family.KINEMATIC)),
    render(family_label(Family.GABLE)),
)


def belfry_not_made() -> CheckResult:
    """Return the belfry's rocking check, not made: no belfry columns and no bell gable."""
    return CheckResult(
        "belfry.rocking",
        "belfry",
        Family.PART_ROCKING,
        Method.ROCKING,
        Status.NOT_MADE,
        reason=message("not_made.belfry"),
    )


class _Slot(NamedTuple):
    """Where one check's result is in a summary row."""

    check: str
    part: str
    family: Family
    method: Method
    #: The columns of a_C [g], I_S [-] and their bound.
    keys: tuple[str, str, str]
    #: Detail name (:data:`~rockscreen.pipeline.verdict.checks.DETAIL_UNITS`) -> column.
    details: dict[str, str]


def _slots() -> list[_Slot | CodeCheck]:
    """Return the checks a summary row can hold, in tie-breaking order."""
    fragility = ("fragility_median_g", "fragility_beta", "p_overturning_50y")
    slots: list[_Slot | CodeCheck] = [
        _Slot(
            f"{m}.rocking",
            m,
            _PART_FAMILY.get(m, Family.PART_ROCKING),
            Method.ROCKING,
            (f"{m}_capacity_ag_g", f"{m}_safety_index", f"{m}_slv_bound"),
            {name: f"{m}_{name}" for name in fragility},
        )
        for m in part_model_names()
    ]
    slots.append(
        _Slot(
            "tower.rocking",
            "tower",
            Family.TOWER_ROCKING,
            Method.ROCKING,
            ("capacity_pga_g", "safety_index", "slv_bound"),
            {
                "fragility_median_g": "collapse_median_g",
                "fragility_beta": "collapse_beta",
                "p_overturning_50y": "p_overturning_50y",
            },
        )
    )
    # the code's checks, registered (LV1, the non-linear kinematic checks, the modules of
    # risk/checks/code)
    slots.extend(registered_checks())
    return slots


def check_columns() -> list[CheckColumns]:
    """Return where every check's result is in a summary row, for the archive's ``/checks``.

    The checks of :func:`tower_check_results`, in its (tie-breaking) order -- each part
    model's rocking, whole-tower rocking, the registered code checks -- then the linear
    kinematic checks the summary shows beside the non-linear ones (Circolare 2019
    §C8.7.1.2.1.7), which never govern. A new part model or code check is here without
    this function changing (:mod:`rockscreen.pipeline.archive.long_tables`).
    """
    out = []
    for slot in _slots():
        check = slot.id if isinstance(slot, CodeCheck) else slot.check
        out.append(
            CheckColumns(
                check, slot.part, slot.family.value, slot.method.value, slot.keys, slot.details
            )
        )
    for part in KINEMATIC_PARTS:
        key = f"{part}_kinematic_linear"
        # the family of the part's non-linear check (every check of the bell gable: GABLE)
        family = code_check(f"{part}.kinematic_nonlinear").family
        out.append(
            CheckColumns(
                f"{part}.kinematic_linear",
                part,
                family.value,
                Method.KINEMATIC.value,
                (f"{key}_capacity_ag_g", f"{key}_safety_index", f"{key}_bound"),
            )
        )
    return out


def tower_check_results(
    row: Mapping[str, object], not_made: Sequence[CheckResult] = ()
) -> list[CheckResult]:
    """Return the check results of a summary row, in tie-breaking order.

    The part models first (the whole tower's IDA stops at the first model to reach the
    level, so a part whose capacity equals the whole tower's is the one that drove it),
    then whole-tower rocking, the LV1 model and the non-linear kinematic checks (the
    code's verdict; the linear ones stand beside), each with its details (the fragility,
    the kinematic mechanism's alpha0, e*, a0*, d_SLV, T_SLV, T0, LV1's T1). A check without
    a finite capacity is left out unless ``not_made`` gives it with its reason.

    Parameters
    ----------
    row : dict
        A summary row with the rocking, part, LV1 and kinematic columns.
    not_made : sequence of CheckResult
        The checks that could fail earlier and were not made (:func:`belfry_not_made`,
        a registered check's :meth:`~rockscreen.pipeline.risk.checks.registry.CodeCheck.not_made`).
    """
    given = {c.check: c for c in not_made}
    out = []
    for slot in _slots():
        if isinstance(slot, CodeCheck):
            evaluated = slot.evaluate(row)
            result = evaluated if evaluated.made else given.pop(slot.id, None)
        else:
            made = made_result(row, *slot)
            result = made or given.pop(slot.check, None)
        if result is not None:
            out.append(result)
    return out + list(given.values())


def verdict_columns(result: Verdict) -> dict[str, object]:
    """Return the summary columns of a verdict (their texts rendered in English).

    ``governing``, ``governing_kind``, ``governing_check``, ``governing_shown``,
    ``governing_capacity_ag_g`` [g], ``governing_safety_index`` [-], ``governing_bound``,
    ``risk_class`` (the safety class), ``completeness``, ``checks_not_made``,
    ``checks_not_made_codes`` (:func:`~rockscreen.pipeline.verdict.checks.dumps_not_made`),
    ``checks_disagree``; only the three of the checks not made without a governing check.
    """
    out: dict[str, object] = {
        "completeness": result.completeness.value,
        "checks_not_made": not_made_text(result.completeness, result.not_made),
        "checks_not_made_codes": dumps_not_made(result.checks),
    }
    chosen = result.governing_check
    if chosen is None:
        return out
    return {
        "governing": governing_label(result),
        "governing_kind": render(chosen.kind),
        "governing_check": chosen.check,
        "governing_shown": result.governing_shown,
        "governing_capacity_ag_g": chosen.capacity_ag_g,
        "governing_safety_index": chosen.safety_index,
        "governing_bound": chosen.bound.value,
        "risk_class": result.safety_class,
        **out,
        "checks_disagree": render_all(result.disagreement),
    }


def governing_columns(
    row: Mapping[str, object], class_limits: Sequence[float], not_made: Sequence[CheckResult]
) -> dict[str, object]:
    """Return the governing mechanism, its a_C and I_S, the class, and what was not made.

    Parameters
    ----------
    row : dict
        A summary row with the rocking, part and kinematic columns.
    class_limits : sequence of float
        I_S limits of the classes.
    not_made : sequence of CheckResult
        The checks that could fail earlier and were not made, each with why.

    Returns
    -------
    dict
        :func:`verdict_columns` of the row's :func:`tower_check_results`.
    """
    return verdict_columns(verdict(tower_check_results(row, not_made), class_limits))
