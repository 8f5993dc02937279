"""The code's checks as registered objects (issue 29): one :class:`CodeCheck` each.

A code check is a check of the codes that sits beside the rocking IDA in ``assess``'s
verdict (:mod:`rockscreen.pipeline.risk.checks.governing`): the LV1 tower model of the Guidelines
(DPCM 9/2/2011 §5.4.4) and the non-linear kinematic checks of Circolare 2019 §C8.7.1 of
the whole tower, the belfry and the bell gable (the linear ones stand beside, in the same
columns' family). Each declares its id, the part it checks, its family and method, the
inventory columns it requires, whether it can govern before the whole tower's rigid
overturning, what it covers, and the summary columns it reads; :meth:`CodeCheck.evaluate`
returns its :class:`~rockscreen.pipeline.verdict.checks.CheckResult` from a summary row, a
check NOT_MADE with a message (never an exception) when the row has no capacity for it.

The governing slot table reads these in registration order (:func:`code_checks`); a new
code check is one :func:`register` call with its columns declared in
:mod:`rockscreen.pipeline.archive.risk_schema`. The kinematic parts' names are those of
the mechanisms (:data:`~rockscreen.pipeline.archive.risk_schema.KINEMATIC_PARTS`), not of
the engine's models.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

from rockscreen.pipeline.archive.risk_schema import KINEMATIC_PARTS
from rockscreen.pipeline.verdict.checks import CheckResult, Family, Method, check_label
from rockscreen.pipeline.verdict.messages import Message, message
from rockscreen.pipeline.verdict.status import Bound, Status
from rockscreen.stations.inventory_columns import BELFRY_GROUP, GABLE_GROUP, LV1_COLUMNS

__all__ = ["CodeCheck", "code_check", "code_checks", "made_result", "register"]


@dataclass(frozen=True)
class CodeCheck:
    """One check of the codes, what it needs and where its result is in a summary row."""

    #: The check's id, ``<part>.<what>`` (``"shaft.lv1"``, ``"belfry.kinematic_nonlinear"``).
    id: str
    #: The part checked (``"shaft"``, ``"tower"``, ``"belfry"``, ``"gable"``).
    part: str
    family: Family
    method: Method
    #: Inventory columns the check requires (without them it is not made).
    requires: tuple[str, ...]
    #: Whether the check can govern before the whole tower's rigid overturning (a part
    #: above the shaft, the shaft's flexure) rather than re-checking the same mechanism.
    governs_before_rocking: bool
    #: What the check covers, in words, with its code section.
    covers: str
    #: The summary columns of its capacity a_C [g], its I_S [-] and their bound.
    keys: tuple[str, str, str]
    #: Detail name (:data:`~rockscreen.pipeline.verdict.checks.DETAIL_UNITS`) -> column.
    details: Mapping[str, str] = field(default_factory=dict)

    def evaluate(self, row: Mapping[str, object], reason: Message | None = None) -> CheckResult:
        """Return the check's result on a summary row.

        Parameters
        ----------
        row : mapping
            A summary row (``assess``'s ``/summary``).
        reason : Message, optional
            Why the check was not made, when the caller knows (an LV1 without the measured
            strength at LC3...); by default the row lacking its capacity is said with the
            columns the check requires.

        Returns
        -------
        CheckResult
            MADE with a_C, I_S, the bound and the details when the row has a finite
            capacity; else NOT_MADE with ``reason`` (never an exception).
        """
        made = made_result(
            row, self.id, self.part, self.family, self.method, self.keys, self.details
        )
        if made is not None:
            return made
        return CheckResult(
            self.id,
            self.part,
            self.family,
            self.method,
            Status.NOT_MADE,
            reason=reason or self._missing(),
        )

    def _missing(self) -> Message:
        label = check_label(self.id, self.part)
        if self.requires:
            return message(
                "not_made.code_check_columns", check=label, columns=", ".join(self.requires)
            )
        return message("not_made.code_check_result", check=label)


def made_result(
    row: Mapping[str, object],
    check: str,
    part: str,
    family: Family,
    method: Method,
    keys: tuple[str, str, str],
    details: Mapping[str, str],
) -> CheckResult | None:
    """Return a check made on a summary row (a finite capacity in its columns), else None.

    The one reading of a check's columns, for the registered code checks and the rocking
    checks of :mod:`rockscreen.pipeline.risk.checks.governing` alike.

    Parameters
    ----------
    row : mapping
        A summary row.
    check, part : str
        The check's id and the part it checks.
    family : Family
    method : Method
    keys : (str, str, str)
        The columns of a_C [g], I_S [-] and their bound.
    details : mapping
        Detail name (:data:`~rockscreen.pipeline.verdict.checks.DETAIL_UNITS`) -> column;
        a detail whose column is not a finite number is left out.

    Returns
    -------
    CheckResult or None
    """
    ag, index, bound = (row.get(key) for key in keys)
    if not (isinstance(ag, float) and math.isfinite(ag)):
        return None
    values = {
        name: float(row[column])
        for name, column in details.items()
        if isinstance(row.get(column), (int, float)) and math.isfinite(row[column])
    }
    return CheckResult(
        check,
        part,
        family,
        method,
        Status.MADE,
        ag,
        math.nan if index is None else index,
        Bound.parse(bound or ""),
        details=values,
    )


_REGISTRY: dict[str, CodeCheck] = {}


def register(check: CodeCheck) -> CodeCheck:
    """Add a code check to the registry (its id once); return it.

    Raises
    ------
    ValueError
        For an id registered twice with a different declaration.
    """
    if check.id in _REGISTRY and _REGISTRY[check.id] != check:
        raise ValueError(f"code check {check.id!r} registered twice")
    _REGISTRY[check.id] = check
    return check


def code_checks() -> tuple[CodeCheck, ...]:
    """Return the registered code checks in registration (tie-breaking) order."""
    return tuple(_REGISTRY.values())


def code_check(check_id: str) -> CodeCheck:
    """Return the code check ``check_id``; KeyError naming the registered ones."""
    try:
        return _REGISTRY[check_id]
    except KeyError:
        raise KeyError(f"no code check {check_id!r}; registered: {', '.join(_REGISTRY)}") from None


register(
    CodeCheck(
        "shaft.lv1",
        "shaft",
        Family.SHAFT_FLEXURE,
        Method.LV1,
        requires=LV1_COLUMNS,
        governs_before_rocking=True,
        covers="shaft flexure, the LV1 tower model of the Guidelines (DPCM 9/2/2011 §5.4.4)",
        keys=("lv1_capacity_ag_g", "lv1_safety_index", "lv1_bound"),
        details={"period_s": "lv1_period_s", "compression_ratio": "lv1_compression_ratio"},
    )
)

#: What each kinematic part's mechanism requires, whether it can govern before the whole
#: tower's overturning, its family and what it covers (Circolare 2019 §C8.7.1); every check
#: of the bell gable is of the GABLE family.
_KINEMATIC = {
    "tower": ((), False, Family.KINEMATIC, "the whole tower overturning about its base"),
    "belfry": (BELFRY_GROUP, True, Family.KINEMATIC, "the belfry overturning on the shaft"),
    "gable": (GABLE_GROUP, True, Family.GABLE, "the bell gable overturning out of its plane"),
}
#: The kinematic mechanism's details (the ``<part>_kinematic_<name>`` columns).
_KINEMATIC_DETAILS = ("alpha0", "e_star", "a0_g", "du_star_m", "t_slv_s", "t0_s")

for _part in KINEMATIC_PARTS:
    _requires, _first, _family, _covers = _KINEMATIC[_part]
    _key = f"{_part}_kinematic_nonlinear"
    register(
        CodeCheck(
            f"{_part}.kinematic_nonlinear",
            _part,
            _family,
            Method.KINEMATIC,
            requires=_requires,
            governs_before_rocking=_first,
            covers=f"{_covers}, non-linear kinematic check (Circolare 2019 §C8.7.1.2.1.7)",
            keys=(f"{_key}_capacity_ag_g", f"{_key}_safety_index", f"{_key}_bound"),
            details={name: f"{_part}_kinematic_{name}" for name in _KINEMATIC_DETAILS},
        )
    )
