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

Each also declares how it is computed per tower in ``assess``'s worker (``compute``: a
function of a :class:`CheckContext` returning a :class:`CheckOutput`, or its
``"module:function"`` name, imported when it runs) and the summary columns it writes with
their units (``columns``, declared to the archive schema by :func:`register`).
:func:`rockscreen.pipeline.risk.checks.tower_code_checks.run_code_checks` runs every
registered computation; a check whose required inventory columns are missing is NOT_MADE
with a catalogue message, never an exception.

The governing slot table reads these in registration order (:func:`code_checks`). The
built-in checks are declared here, their computations named by ``"module:function"`` so
that this module stays vocabulary (the HTML report names its checks from it without
importing a computation); a new code check is one module of
:mod:`rockscreen.pipeline.risk.checks.code` calling :func:`register` (docs/architecture.md,
"A new code check"). The kinematic parts' names are those of the mechanisms
(:data:`~rockscreen.pipeline.archive.risk_schema.KINEMATIC_PARTS`), not of the engine's
models.
"""

from __future__ import annotations

import importlib
import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Protocol

from rockscreen.pipeline.archive.risk_schema import (
    KINEMATIC_PARTS,
    KINEMATIC_UNITS,
    LV1_UNITS,
    declare_check_columns,
    withdraw_check_columns,
)
from rockscreen.pipeline.archive.schema import TEXT
from rockscreen.pipeline.verdict.checks import CheckResult, Family, Method, check_label
from rockscreen.pipeline.verdict.messages import Message, message
from rockscreen.pipeline.verdict.status import Bound, Status
from rockscreen.stations.inventory_columns import BELFRY_GROUP, GABLE_GROUP, LV1_COLUMNS
from rockscreen.stations.tower import Tower

if TYPE_CHECKING:
    from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions

__all__ = [
    "AssessedSite",
    "CheckContext",
    "CheckOutput",
    "CodeCheck",
    "code_check",
    "code_checks",
    "computations",
    "made_result",
    "register",
    "resolve",
    "unregister",
]


class AssessedSite(Protocol):
    """An assessed tower at its site (``risk.assess.sites.TowerSite``), as a check reads it."""

    tower: Tower
    lon_deg: float
    lat_deg: float
    soil_class: str
    topography: str
    nominal_life_y: float
    use_class: str


@dataclass(frozen=True)
class CheckContext:
    """What a code check's computation is given per tower in ``assess``'s worker."""

    #: The tower at its site (its inventory row is ``site.tower``).
    site: AssessedSite
    #: The site's conditions on the NTC 2018 hazard (location, soil, topography, V_N,
    #: use class; 5 % damping): its ``hazard(T_R)``, ``soil_factor``, spectra.
    conditions: SiteConditions
    #: The tower's knowledge level (``"LC1"``, ``"LC2"``, ``"LC3"``, Circolare 2019 §C8.5.4).
    knowledge_level: str
    #: Its confidence factor F_C [-].
    fc: float

    @property
    def tower(self) -> Tower:
        """The tower's inventory row."""
        return self.site.tower


@dataclass(frozen=True)
class CheckOutput:
    """What a code check's computation returns for one tower."""

    #: Its summary columns (of :attr:`CodeCheck.columns`) with the tower's values.
    columns: Mapping[str, object] = field(default_factory=dict)
    #: The clauses it adds to the tower's note (messages of the catalogue).
    notes: tuple[Message, ...] = ()
    #: The checks it could not make (or that failed), each with its reason.
    not_made: tuple[CheckResult, ...] = ()


#: A check's computation: the tower's context -> its columns, notes and checks not made.
Compute = Callable[[CheckContext], CheckOutput]
#: Why a check cannot be made for a tower (a message), None when it can.
Reason = Callable[[CheckContext], "Message | None"]


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
    #: Every summary column the computation writes -> its units spelling
    #: (:mod:`rockscreen.pipeline.archive.schema`); NaN or ``""`` in a row without it.
    columns: Mapping[str, str] = field(default_factory=dict)
    #: How it is computed per tower (or the ``"module:function"`` naming it); None: its
    #: columns are written by another check's computation (the belfry's and the bell
    #: gable's kinematic checks by the whole tower's).
    compute: Compute | str | None = None
    #: Why it cannot be made for a tower (or its ``"module:function"``); None: the
    #: ``requires`` columns missing from the inventory row
    #: (``not_made.code_check_columns``).
    not_made_reason: Reason | str | None = None
    #: Where its computation runs among the others (lower first: the order of the notes).
    compute_order: int = 100

    def reason(self, context: CheckContext) -> Message | None:
        """Return why the check cannot be made for the tower of ``context``, None if it can."""
        if self.not_made_reason is not None:
            return resolve(self.not_made_reason)(context)
        missing = [c for c in self.requires if getattr(context.tower, c, None) is None]
        if not missing:
            return None
        label = check_label(self.id, self.part)
        return message("not_made.code_check_columns", check=label, columns=", ".join(missing))

    def not_made(self, reason: Message, status: Status = Status.NOT_MADE) -> CheckResult:
        """Return this check not made (or FAILED) for ``reason``."""
        return CheckResult(self.id, self.part, self.family, self.method, status, reason=reason)

    def empty_columns(self) -> dict[str, object]:
        """Return its columns of a row without its result: NaN numbers, ``""`` text."""
        return {c: "" if units == TEXT else math.nan for c, units in self.columns.items()}

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

    Its ``columns`` are declared to the assess archive's schema
    (:func:`~rockscreen.pipeline.archive.risk_schema.declare_check_columns`), its a_C and
    I_S as values its bound column signs.

    Raises
    ------
    ValueError
        For an id registered twice with a different declaration, a check that computes
        without declaring its ``keys`` and ``details`` among its ``columns``, or a column
        the archive's summary has already (not a code check's).
    """
    if check.id in _REGISTRY and _REGISTRY[check.id] != check:
        raise ValueError(f"code check {check.id!r} registered twice")
    undeclared = [c for c in (*check.keys, *check.details.values()) if c not in check.columns]
    if check.compute is not None and undeclared:
        raise ValueError(f"code check {check.id!r}: columns {undeclared} not in its columns")
    bounds = {key: check.keys[2] for key in check.keys[:2] if key in check.columns}
    declare_check_columns(check.columns, bounds if check.keys[2] in check.columns else {})
    _REGISTRY[check.id] = check
    return check


def unregister(check_id: str) -> None:
    """Remove a code check and its declared columns (a plugin's, when a test ends)."""
    check = _REGISTRY.pop(check_id, None)
    if check is not None:
        builtin = {**KINEMATIC_UNITS, **LV1_UNITS}
        withdraw_check_columns(c for c in check.columns if c not in builtin)


def code_checks() -> tuple[CodeCheck, ...]:
    """Return the registered code checks in registration (tie-breaking) order.

    The built-in ones and those of the modules loaded so far; the assess side loads every
    module of :mod:`rockscreen.pipeline.risk.checks.code` first
    (:func:`rockscreen.pipeline.risk.checks.tower_code_checks.registered_checks`).
    """
    return tuple(_REGISTRY.values())


def computations() -> tuple[CodeCheck, ...]:
    """Return the registered checks that compute, in their ``compute_order``."""
    with_compute = [c for c in _REGISTRY.values() if c.compute is not None]
    return tuple(sorted(with_compute, key=lambda c: c.compute_order))


def resolve(function: Callable[..., object] | str) -> Callable[..., object]:
    """Return a function, or the one a ``"module:function"`` name names (imported now)."""
    if callable(function):
        return function
    module, _, name = function.partition(":")
    return getattr(importlib.import_module(module), name)


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
        columns=LV1_UNITS,
        compute="rockscreen.pipeline.risk.checks.tower_lv1_checks:lv1_check",
        not_made_reason="rockscreen.pipeline.risk.checks.tower_lv1_checks:lv1_reason",
        compute_order=20,
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
#: The computation of every part's kinematic checks (one per tower: the mechanism of
#: lowest I_S is the ``kinematic_*`` columns').
_KINEMATIC_COMPUTE = "rockscreen.pipeline.risk.checks.tower_checks:kinematic_check_output"
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
            # the whole tower's computation writes every part's kinematic columns
            columns=KINEMATIC_UNITS if _part == "tower" else {},
            compute=_KINEMATIC_COMPUTE if _part == "tower" else None,
            compute_order=10,
        )
    )
