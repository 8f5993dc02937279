"""Best-estimate kinematic capacities of a tower's overturning mechanisms, per sample.

The non-linear kinematic check of the Circolare 2019 §C8.7.1.2.1 (§C8.7.1.2.1.6 and
§C8.7.1.2.1.8; ``docs/code_checks.md`` §1), called, not copied: the mechanisms of
:mod:`rockscreen.pipeline.risk.checks.tower_mechanisms` (the whole tower about the toe of its base,
the belfry about the top of the shaft, the bell gable) and
:func:`~rockscreen.pipeline.risk.checks.kinematic.kinematic_check`'s non-linear check
(:func:`~rockscreen.pipeline.risk.checks.kinematic.nonlinear_capacity_on_site`) on the site's NTC
2018 hazard. What differs from the code's check (``tower_checks.kinematic_columns``):

- the confidence factor ``F_C = 1`` (the code divides a0* by Table C8.5.I's FC, 1.35 at
  LC1): a best estimate, with no factor;
- the row's missing values are the sample's: the tower's period ``T1`` (the whole tower's
  ``T0`` and the period of the shaft beneath the belfry), the masonry type (the belfry's
  and the gable's cantilever ``T0``, the gable's mass) and the tower's mass (its shaft's
  walls and unit weight, :func:`~rockscreen.pipeline.risk.uncertainty.shaft.shaft_model`,
  plus the belfry's piers; it weighs only against the bells: a uniform block's alpha0 and
  e* do not depend on its mass); the row's ``tower_mass_kg`` when given.

The capacity is the non-linear check's ``a_SLV,kin`` [g] (the ag on rock at which the
check holds at equality) with its bound (``"lower"``: holds at 2475 y; ``"upper"``: fails
at 30 y). Identical inputs are computed once (a tower whose priors are points: once).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.checks.kinematic import kinematic_capacity
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.checks.tower_mechanisms import WHOLE_TOWER, tower_support
from rockscreen.pipeline.risk.uncertainty.belfry import BELFRY_KEYS, belfry_row
from rockscreen.pipeline.risk.uncertainty.extrapolation import EXTRAPOLATED
from rockscreen.pipeline.risk.uncertainty.kinematic_batch import nonlinear_capacities
from rockscreen.pipeline.risk.uncertainty.kinematic_cases import (
    BEST_ESTIMATE_FC,
    MechanismChecks,
    is_note,
)
from rockscreen.pipeline.risk.uncertainty.shaft import shaft_model
from rockscreen.pipeline.verdict.messages import Message, message
from rockscreen.stations.tower import Tower

__all__ = [
    "ABSENT_CAPACITY_G",
    "BELFRY_PERIOD_NODES",
    "BEST_ESTIMATE_FC",
    "PERIOD_NODES",
    "MechanismCapacity",
    "kinematic_capacities",
]

#: Checks per mechanism (and masonry type) on log-spaced periods, interpolated between
#: (:func:`kinematic_capacities`; the interpolation error is measured in docs/uncertainty.md).
PERIOD_NODES = 17
#: The same for a sampled belfry, per scenario and type (its error: docs/uncertainty.md).
BELFRY_PERIOD_NODES = 5
#: The belfry "capacity" of a sample without a belfry [g], flagged "lower" (none fails).
ABSENT_CAPACITY_G = 10.0


@dataclass(frozen=True)
class MechanismCapacity:
    """One mechanism's capacity for every sample (arrays of the samples' length)."""

    #: The mechanism's name (``"shaft"``, ``"whole tower"``, ``"belfry"``, ``"gable"``,
    #: ``"rocking"`` ...).
    name: str
    #: Capacity: the ag on rock [g] of the mechanism's failure (the fragility's median).
    ag_g: np.ndarray
    #: ``""``, ``"lower"`` (at least this: holds at the table's longest return period) or
    #: ``"upper"`` (at most this: fails at the shortest), per sample.
    bound: np.ndarray
    #: Whether each capacity is continued beyond the table (a value, no bound:
    #: :mod:`~rockscreen.pipeline.risk.uncertainty.extrapolation`); None: none is.
    extrapolated: np.ndarray | None = None

    def __post_init__(self):
        ag = np.atleast_1d(np.asarray(self.ag_g, dtype=float))
        bound = np.asarray(self.bound, dtype=object)
        if bound.ndim == 0:
            bound = np.full(ag.shape, bound.item(), dtype=object)
        if ag.ndim != 1 or bound.shape != ag.shape:
            raise RiskError(
                f"mechanism {self.name!r}: {ag.size} capacities for {bound.size} bound flags"
            )
        beyond = np.zeros(ag.shape, dtype=bool)
        if self.extrapolated is not None:
            beyond = np.broadcast_to(np.asarray(self.extrapolated, dtype=bool), ag.shape).copy()
        if np.any(beyond & (bound != "")):
            raise RiskError(f"mechanism {self.name!r}: an extrapolated capacity has no bound")
        object.__setattr__(self, "extrapolated", beyond)
        if not np.all(np.isfinite(ag) & (ag > 0.0)):
            raise RiskError(f"mechanism {self.name!r}: capacities [g] must be finite and > 0")
        unknown = set(bound.tolist()) - {"", "lower", "upper"}
        if unknown:
            raise RiskError(
                f"mechanism {self.name!r}: bound flags {sorted(unknown)}; allowed: '', "
                "'lower', 'upper'"
            )
        object.__setattr__(self, "ag_g", ag)
        object.__setattr__(self, "bound", bound)


#: The parts whose capacity depends on the masonry type only (the gable, on its base: not
#: on the shaft's period).
_TYPE_ONLY = frozenset({"gable"})


def _tower_mass_kg(tower: Tower, wall_m: float, wall_top_m: float, unit_weight: float) -> float:
    """Return the tower's masonry mass [kg]: the shaft of the sample's walls, the belfry's piers."""
    model = shaft_model(
        tower,
        wall_m=wall_m,
        wall_top_m=wall_top_m,
        unit_weight_n_m3=unit_weight,
        fm_pa=1.0,
    )
    mass = sum(segment.mass_kg for segment in model.segments)
    if tower.has_belfry:
        mass += float(tower.belfry_mass_kg)
    return float(mass)


def kinematic_capacities(
    tower: Tower,
    site: SiteConditions,
    samples: dict[str, np.ndarray],
    *,
    period_nodes: int | None = PERIOD_NODES,
    extrapolate: bool = True,
    batch: bool = True,
) -> tuple[list[MechanismCapacity], list[str]]:
    """Return the best-estimate kinematic capacities of a tower's mechanisms, per sample.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        The row (geometry; the belfry's and the gable's columns when given; a church
        beneath, ``building_height_m``, makes the whole tower an elevated mechanism as in
        ``assess``).
    site : SiteConditions
        The site.
    samples : dict
        ``wall_m``, ``wall_top_m``, ``masonry_type``, ``unit_weight_n_m3``, ``period_s``
        arrays of one length
        (:meth:`~rockscreen.pipeline.risk.uncertainty.priors.TowerPriors.sample`).
    period_nodes : int or None
        Checks per mechanism and masonry type on log-spaced periods over the samples'
        range, ``ln a_SLV`` interpolated linearly in ``ln T1`` between them (a sample
        between a bounded node and another carries the node's bound: a bound is never
        read as a value); None, or fewer distinct periods than nodes: every sample's own
        check. The whole tower with bells is always checked per sample (its mass varies).
    extrapolate : bool
        True (the screening risk): a check holding at 2475 y (failing at 30 y) gets the
        capacity of the demand continued beyond the table, shape held
        (:func:`~rockscreen.pipeline.risk.uncertainty.extrapolation.kinematic_beyond_table`),
        flagged ``extrapolated`` with no bound. False: the code's bound.
    batch : bool
        True (the default): the checks of many samples (a part's period nodes, the whole
        tower with bells, a sampled belfry) made at once
        (:func:`~rockscreen.pipeline.risk.uncertainty.kinematic_batch.nonlinear_capacities`),
        and a sampled belfry checked at every sample's own period (no nodes). False:
        :func:`~rockscreen.pipeline.risk.checks.kinematic.kinematic_check` per distinct
        input, the reference the batch is tested against (and a sampled belfry on
        :data:`BELFRY_PERIOD_NODES` nodes per group).

    Returns
    -------
    capacities : list of MechanismCapacity
        ``"whole tower"``; ``"belfry"`` with the belfry's columns, or when the
        samples carry a sampled belfry (``TowerPriors.sample(..., belfry=BelfryPriors())``)
        and the row has none (each sample at its own period with ``batch``, else each
        (scenario, type) group on :data:`BELFRY_PERIOD_NODES` periods; the whole tower
        and the shaft do not carry the sampled belfry's mass); ``"gable"`` with the
        gable's.
    notes : list of Message
        What the mechanisms assumed (``kinematic.*`` messages), each distinct one once.
    """
    n = _sample_count(samples, period_nodes)
    support, support_notes = tower_support(tower)
    checks = MechanismChecks(tower, site, support, extrapolate, batch)
    checks.notes.extend(
        message("kinematic.of", part=WHOLE_TOWER, note=note) for note in support_notes
    )
    kinds = np.asarray(samples["masonry_type"]).astype(str)
    periods = np.asarray(samples["period_s"], dtype=float)
    bells = bool(tower.has_belfry and tower.bells_mass_kg)
    masses = (
        _sample_masses_kg(tower, samples, n)
        if bells and tower.tower_mass_kg is None
        else np.zeros(n)
    )
    parts = ["whole tower"]
    if tower.has_belfry:
        parts.append("belfry")
    if tower.has_gable:
        parts.append("gable")
    out = [
        _part_capacity(checks, part, kinds, periods, masses, bells, period_nodes) for part in parts
    ]
    if not tower.has_belfry and "belfry_present" in samples:
        out.append(
            _sampled_belfry(
                tower, site, samples, kinds, periods, checks.notes, extrapolate, batch, period_nodes
            )
        )
    return out, list(dict.fromkeys(checks.notes))


def _sampled_belfry(
    tower: Tower,
    site: SiteConditions,
    samples: dict[str, np.ndarray],
    kinds: np.ndarray,
    periods: np.ndarray,
    notes: list[Message],
    extrapolate: bool = True,
    batch: bool = True,
    period_nodes: int | None = PERIOD_NODES,
) -> MechanismCapacity:
    """Return the capacity of the sampled belfry of a row without one.

    Each (scenario, masonry type) group of samples with a belfry is one row
    (:func:`~rockscreen.pipeline.risk.uncertainty.belfry.belfry_row`: the group's median
    top wall and mean unit weight for the piers' mass): its mechanism (which does not
    depend on the period) on the shaft of each sample's period, all samples checked at
    once (``batch``), else each group on :data:`BELFRY_PERIOD_NODES` periods over its
    range (every sample's own check with ``period_nodes`` None: the reference). A sample
    without a belfry has no belfry failure: :data:`ABSENT_CAPACITY_G` flagged
    ``"lower"`` (at least that; never the minimum against an exact capacity of another
    mechanism).
    """
    n = periods.size
    ag = np.full(n, ABSENT_CAPACITY_G)
    bound = np.full(n, "lower", dtype=object)
    present = np.asarray(samples["belfry_present"], dtype=bool)
    keys = np.column_stack([np.asarray(samples[k], dtype=float) for k in BELFRY_KEYS[1:]])
    group = np.array([f"{kinds[i]}|{keys[i].tobytes().hex()}" for i in range(n)], dtype=object)
    rows, capacities, supports = [], [], []
    for name in dict.fromkeys(group[present].tolist()):
        members = np.flatnonzero(present & (group == name))
        first = members[0]
        row = belfry_row(
            replace(tower, masonry_type=str(kinds[first])),
            height_share=keys[first, 0],
            opening_ratio=keys[first, 1],
            bells_mass_kg=keys[first, 2],
            bells_height_share=keys[first, 3],
            wall_top_m=float(np.median(np.asarray(samples["wall_top_m"])[members])),
            unit_weight_n_m3=float(np.mean(np.asarray(samples["unit_weight_n_m3"])[members])),
        )
        checks = MechanismChecks(row, site, None, extrapolate, batch)
        if batch:
            mechanism, shaft = checks.build("belfry", str(kinds[first]), float(periods[first]), 0.0)
            capacity = kinematic_capacity(mechanism, BEST_ESTIMATE_FC)
            rows.extend(members.tolist())
            capacities.extend([capacity] * members.size)
            supports.extend(replace(shaft, period_s=float(periods[i])) for i in members)
        else:
            part = _part_capacity(
                checks,
                "belfry",
                kinds[members],
                periods[members],
                np.zeros(members.size),
                False,
                None if period_nodes is None else BELFRY_PERIOD_NODES,
            )
            ag[members], bound[members] = part.ag_g, part.bound
            bound[members[part.extrapolated]] = EXTRAPOLATED
        # Each scenario's own T0 is no news to the reader: the sampled belfry is said once
        # by the caller (risk.belfry_sampled); other assumptions are kept.
        notes.extend(n for n in checks.notes if not is_note(n, "kinematic.belfry_t0"))
    if rows:
        ag[rows], bound[rows] = nonlinear_capacities(
            capacities, site, supports, extrapolate=extrapolate
        )
    beyond = bound == EXTRAPOLATED
    bound[beyond] = ""
    return MechanismCapacity("belfry", ag, bound, beyond)


def _sample_count(samples: dict[str, np.ndarray], period_nodes: int | None) -> int:
    """Return the number of samples, refusing missing or unequal arrays and too few nodes."""
    names = ("wall_m", "wall_top_m", "masonry_type", "unit_weight_n_m3", "period_s")
    missing = [k for k in names if k not in samples]
    if missing:
        raise RiskError(f"kinematic capacities: samples lack {', '.join(missing)}")
    n = np.asarray(samples["period_s"]).size
    if any(np.asarray(samples[k]).shape != (n,) for k in names):
        raise RiskError("kinematic capacities: the samples' arrays differ in length")
    if period_nodes is not None and int(period_nodes) < 2:
        raise RiskError(f"kinematic capacities: period_nodes={period_nodes!r}; allowed: >= 2")
    return int(n)


def _sample_masses_kg(tower: Tower, samples: dict[str, np.ndarray], n: int) -> np.ndarray:
    """Return the shaft's and belfry's mass of each sample's walls and unit weight [kg]."""
    return np.array(
        [
            _tower_mass_kg(
                tower,
                float(samples["wall_m"][i]),
                float(samples["wall_top_m"][i]),
                float(samples["unit_weight_n_m3"][i]),
            )
            for i in range(n)
        ]
    )


def _part_capacity(
    capacity: MechanismChecks,
    part: str,
    kinds: np.ndarray,
    periods: np.ndarray,
    masses: np.ndarray,
    bells: bool,
    period_nodes: int | None,
) -> MechanismCapacity:
    """Return one part's capacity per sample (:func:`kinematic_capacities`' ``period_nodes``).

    Parameters
    ----------
    capacity : MechanismChecks
    part : {"whole tower", "belfry", "gable"}
    kinds, periods, masses : numpy.ndarray
        Each sample's masonry type, period [s] and whole-tower mass [kg] (0: its own).
    bells : bool
        Whether the whole tower carries bells (its mass varies: checked per sample).
    period_nodes : int or None
    """
    n = periods.size
    ag = np.empty(n)
    bound = np.empty(n, dtype=object)
    # What the part's capacity depends on besides the period: the gable only on the
    # type; the belfry on the type (its T0) and the period (the shaft beneath); the
    # whole tower on the period (and its mass, with bells).
    group_kind = kinds if part != "whole tower" else np.full(n, "", dtype=object)
    for kind in dict.fromkeys(group_kind.tolist()):
        members = np.flatnonzero(group_kind == kind)
        t = periods[members]
        # Whole tower: the type does not enter (its T0 is the tower's period).
        kind_used = kinds[members[0]] if part == "whole tower" else kind
        if part in _TYPE_ONLY:
            a, b = capacity(part, kind, 0.0, 0.0)
            ag[members], bound[members] = a, b
            continue
        if (
            bells
            and part == "whole tower"
            or period_nodes is None
            or (np.unique(t).size <= int(period_nodes))
        ):
            ag[members], bound[members] = capacity.many(
                part, np.full(members.size, kind_used, dtype=object), t, masses[members]
            )
            continue
        nodes = np.geomspace(t.min(), t.max(), int(period_nodes))
        node_ag, node_bound = capacity.many(
            part, np.full(nodes.size, kind_used, dtype=object), nodes, np.zeros(nodes.size)
        )
        ag[members] = np.exp(np.interp(np.log(t), np.log(nodes), np.log(node_ag)))
        j = np.clip(np.searchsorted(nodes, t, side="right"), 1, len(nodes) - 1)
        left, right = node_bound[j - 1], node_bound[j]
        bound[members] = np.where(left != "", left, right)
    beyond = bound == EXTRAPOLATED
    bound[beyond] = ""
    return MechanismCapacity(part, ag, bound, beyond)
