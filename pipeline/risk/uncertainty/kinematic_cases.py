"""One tower's kinematic mechanisms under a sample's inputs, each distinct case checked once.

:class:`MechanismChecks` builds the mechanism of a part (the whole tower about the toe of
its base, the belfry, the bell gable: :mod:`rockscreen.pipeline.risk.checks.tower_mechanisms`)
from the tower's row with a sample's masonry type, period and mass, and returns the
Circolare 2019 §C8.7.1.2.1 non-linear check's capacity at the best estimate's ``F_C = 1``
(:func:`~rockscreen.pipeline.risk.checks.kinematic.nonlinear_capacity_on_site`), continued
beyond the table when bounded
(:func:`~rockscreen.pipeline.risk.uncertainty.extrapolation.kinematic_beyond_table`). What
:func:`rockscreen.pipeline.risk.uncertainty.kinematic.kinematic_capacities` asks per sample.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.checks.kinematic import (
    kinematic_capacity,
    nonlinear_capacity_on_site,
)
from rockscreen.pipeline.risk.checks.kinematic_demand import ElevatedSupport
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.checks.tower_mechanisms import (
    belfry_kinematic_mechanism,
    gable_kinematic_mechanism,
    tower_kinematic_mechanism,
)
from rockscreen.pipeline.risk.uncertainty.extrapolation import (
    EXTRAPOLATED,
    kinematic_beyond_table,
)
from rockscreen.pipeline.risk.uncertainty.kinematic_batch import nonlinear_capacities
from rockscreen.pipeline.verdict.messages import Message
from rockscreen.stations.tower import Tower

__all__ = [
    "BEST_ESTIMATE_FC",
    "PART_MECHANISMS",
    "MechanismChecks",
    "is_note",
    "whole_tower_mechanism",
]

#: Confidence factor of the best estimate [-]: none (the code's is Table C8.5.I's, §C8.5.4).
BEST_ESTIMATE_FC = 1.0
#: The kinematic mechanism of each part above the shaft (Circolare 2019 §C8.7.1): the part
#: (a kinematic check's, not a model's name) -> its mechanism of a tower.
PART_MECHANISMS = {"belfry": belfry_kinematic_mechanism, "gable": gable_kinematic_mechanism}


class MechanismChecks:
    """The kinematic checks of one tower's mechanisms, each made once, and their notes.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
    site : SiteConditions
    support : ElevatedSupport or None
        The church the whole tower rests on (:func:`tower_support`).
    extrapolate : bool
        A bounded check's capacity continued beyond the table, flagged
        :data:`~rockscreen.pipeline.risk.uncertainty.extrapolation.EXTRAPOLATED`.
    batch : bool
        :meth:`many` checks its inputs at once (``kinematic_batch``), else one by one.
    """

    def __init__(
        self,
        tower: Tower,
        site: SiteConditions,
        support: ElevatedSupport | None,
        extrapolate: bool = True,
        batch: bool = True,
    ) -> None:
        self.tower, self.site, self.support = tower, site, support
        self.extrapolate, self.batch = bool(extrapolate), bool(batch)
        #: What the mechanisms assumed, in the order met (repeats kept).
        self.notes: list[Message] = []
        self.cache: dict[tuple, tuple[float, str]] = {}

    def build(self, part: str, kind: str, period: float, mass: float) -> tuple[Any, Any]:
        """Return the mechanism of ``part`` and the structure beneath it, noting assumptions.

        ``kind`` the masonry type, ``period`` the shaft's period [s], ``mass`` the whole
        tower's mass [kg] (0: the tower's own).
        """
        # A part on the type only (the gable: period 0) keeps the row's period: 0 is no period.
        row = replace(self.tower, masonry_type=kind)
        if period > 0.0:
            row = replace(row, shaft_period_s=period)
        if part == "whole tower":
            mechanism, beneath, more = whole_tower_mechanism(row, mass, self.support)
        else:
            mechanism, beneath, more = PART_MECHANISMS[part](row)
        self.notes.extend(more)
        return mechanism, beneath

    def __call__(self, part: str, kind: str, period: float, mass: float) -> tuple[float, str]:
        """Return the nonlinear check's capacity ag [g] and bound of ``part`` (:meth:`build`)."""
        key = (part, kind, period, mass)
        if key not in self.cache:
            mechanism, beneath = self.build(part, kind, period, mass)
            check = nonlinear_capacity_on_site(
                mechanism, self.site, fc=BEST_ESTIMATE_FC, support=beneath
            )
            ag, bound = check.ag_g, check.bound
            if bound and self.extrapolate:
                beyond = kinematic_beyond_table(
                    mechanism, self.site, bound, fc=BEST_ESTIMATE_FC, support=beneath
                )
                if np.isfinite(beyond):  # else no capacity: the code's bound stays
                    ag, bound = beyond, EXTRAPOLATED
            self.cache[key] = (ag, bound)
        return self.cache[key]

    def many(
        self, part: str, kinds: Any, periods: Any, masses: Any
    ) -> tuple[np.ndarray, np.ndarray]:
        """Return :meth:`__call__` of many inputs: capacities [g] and bounds (arrays).

        The inputs not yet checked are checked at once with ``batch``
        (:func:`~rockscreen.pipeline.risk.uncertainty.kinematic_batch.nonlinear_capacities`),
        else one by one.
        """
        keys = [
            (part, str(k), float(t), float(m))
            for k, t, m in zip(kinds, periods, masses, strict=True)
        ]
        if self.batch:
            todo = [k for k in dict.fromkeys(keys) if k not in self.cache]
            built = [self.build(*k) for k in todo]
            if todo:
                beneath = [b for _, b in built]
                if any(b is None for b in beneath) and not all(b is None for b in beneath):
                    raise RiskError(f"{part}: some samples on the ground, some at height")
                ag, bound = nonlinear_capacities(
                    [kinematic_capacity(m, BEST_ESTIMATE_FC) for m, _ in built],
                    self.site,
                    None if beneath[0] is None else beneath,
                    extrapolate=self.extrapolate,
                )
                for key, a, b in zip(todo, ag, bound, strict=True):
                    self.cache[key] = (float(a), str(b))
        values = [self(*k) for k in keys]
        return (
            np.array([v[0] for v in values], dtype=float),
            np.array([v[1] for v in values], dtype=object),
        )


def is_note(note: Message, code: str) -> bool:
    """Whether a part's note (``kinematic.of``) or a note is of the message ``code``."""
    inner = note.kwargs.get("note") if note.code == "kinematic.of" else note
    return isinstance(inner, Message) and inner.code == code


def _is_solid_prism(note: Message) -> bool:
    """Whether a whole-tower note is the solid prism's mass (``kinematic.solid_prism``)."""
    return is_note(note, "kinematic.solid_prism")


def whole_tower_mechanism(row: Any, mass_kg: float, support: Any) -> tuple[Any, Any, list[Message]]:
    """Return the whole tower's mechanism of the sample's mass, its support and notes.

    :func:`~rockscreen.pipeline.risk.checks.tower_mechanisms.tower_kinematic_mechanism` of the row
    (its block a solid prism when the row has no ``tower_mass_kg``), the block's mass then
    replaced by the sample's (walls and unit weight) when there are bells and the row gives
    no mass (``mass_kg`` > 0; without bells the mass does not enter alpha0 or e*).
    """
    mechanism, notes = tower_kinematic_mechanism(row)
    if row.tower_mass_kg is None:
        # The solid prism is not the mass used: the sample's (or, without bells, none).
        notes = [n for n in notes if not _is_solid_prism(n)]
        if mass_kg > 0.0:
            block = replace(mechanism.blocks[0], mass_kg=mass_kg)
            mechanism = replace(mechanism, blocks=(block, *mechanism.blocks[1:]))
    return mechanism, support, notes
