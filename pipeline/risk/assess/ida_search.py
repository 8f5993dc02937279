"""The scan-then-bisect search of a record's components for their collapse and SLV scales.

A component's search made ready (:func:`prepare_search`: its models' verdicts, computed once
per scale factor and shared by both levels, the uplift-free start, the grid up to the cap or
the vertical limit), the components of a record searched together or each in full
(:func:`search_record`, on :mod:`rockscreen.pipeline.engine.search`), and each one's scale
factors censored. The method is described in :mod:`rockscreen.pipeline.risk.assess.ida`,
which runs it.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from rockscreen.pipeline.engine.cases import BlockCache
from rockscreen.pipeline.engine.loop import ComponentCases
from rockscreen.pipeline.engine.motion import TowerComponent
from rockscreen.pipeline.engine.registry import available_models
from rockscreen.pipeline.engine.search import (
    Exceedance,
    first_exceedance_factors,
    geometric_grid,
    joint_first_exceedances,
)
from rockscreen.pipeline.engine.uplift import uplift_free_factor
from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.assess.ida_intensity import CollapseIntensity, IdaOptions
from rockscreen.solver.constants import G
from rockscreen.stations.tower import Tower

__all__ = ["ComponentSearch", "prepare_search", "search_record"]


class _Verdicts:
    """Verdicts of one component at a scale factor, computed once and shared by the searches.

    The engine's case loop (:class:`~rockscreen.pipeline.engine.loop.ComponentCases`)
    screens the models at a factor, each model's excitation built once at scale 1, and
    stops at the first model that overturns or meets the model's limit.
    """

    def __init__(self, cases: ComponentCases, options: IdaOptions) -> None:
        self.cases, self.options = cases, options
        self.cache: dict[float, tuple[bool, float, bool]] = {}
        self.n_solves = 0
        #: Smallest factor the model's validity limit was met at (inf: never).
        self.limit = math.inf

    def __call__(self, factor: float) -> tuple[bool, float, bool]:
        """Return (overturned by any model, worst theta_max/alpha, at the model's limit)."""
        if factor in self.cache:
            return self.cache[factor]
        verdict = self.cases.screen(
            factor,
            free_motion_s=self.options.free_motion_s,
            early_stop=self.options.early_stop,
            stop_at_first=True,
        )
        self.n_solves += verdict.n_solves
        if verdict.limited:
            self.limit = min(self.limit, factor)
        self.cache[factor] = (verdict.overturned, verdict.worst, verdict.limited)
        return self.cache[factor]

    def largest_safe_below(self, factor: float, floor: float) -> float:
        """Return the largest factor below ``factor`` seen without overturning (or ``floor``)."""
        safe = [f for f, (fell, _, limit) in self.cache.items() if not (fell or limit)]
        return max([floor, *(f for f in safe if f < factor)])


@dataclass
class ComponentSearch:
    """One component's search: its verdicts, grid and censoring, before the search runs."""

    record: str
    component: str
    models: str
    pga_g: float
    verdicts: _Verdicts | None  # None: a component without motion
    start: float
    top: float
    reason: str
    grid: np.ndarray | None  # None: nothing moves below the top (or no motion)

    def levels(self, options: IdaOptions) -> tuple:
        """Return the two level predicates: overturned, and the SLV level reached."""
        verdicts = self.verdicts
        return (
            lambda f: verdicts(f)[0],  # overturned
            lambda f: verdicts(f)[1] >= options.slv_theta_ratio,  # SLV (inf when overturned)
        )


def prepare_search(
    tower: Tower,
    record: str,
    component: TowerComponent,
    vertical: np.ndarray | None,
    dt: float,
    pga_g: float,
    options: IdaOptions,
    blocks: BlockCache,
) -> ComponentSearch:
    """Return a component's search, ready to run by :func:`search_record`.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
    record : str
        The motion's name.
    component : TowerComponent
        The component at scale 1.
    vertical : numpy.ndarray or None
        Vertical ground acceleration at scale 1 [m/s²], positive up.
    dt : float
        Sampling step [s].
    pga_g : float
        The motion's PGA at scale 1 [g].
    options : IdaOptions
    blocks : rockscreen.pipeline.engine.cases.BlockCache
        The tower's blocks by width and axis.

    Returns
    -------
    ComponentSearch
    """
    models = available_models(tower, options.models)
    names = ",".join(m.name for m in models)
    if not models:
        raise RiskError(f"IDA: tower {tower.id!r} runs none of the models {options.models}")
    acc = component.acc
    peak_g = float(np.max(np.abs(acc))) / G if len(acc) else 0.0
    name = component.component
    if not (pga_g > 0.0 and math.isfinite(pga_g)) or peak_g == 0.0:
        # A component without motion never moves at any scale: censored at the cap.
        return ComponentSearch(record, name, names, pga_g, None, math.inf, math.inf, "cap", None)
    top, reason = _search_top(options.cap_pga_g / pga_g, vertical)
    # Below the smallest uplift-free factor of the models' own excitations (a floor or
    # shaft-top motion is amplified; the filters are linear, so scaling commutes) and
    # blocks, no model moves.
    cases = ComponentCases(tower, component, vertical, dt, models, blocks)
    verdicts = _Verdicts(cases, options)
    start = min(
        uplift_free_factor(cases.excitation(m), cases.block(m).alpha, vertical) for m in models
    )
    grid = None
    if start < top:
        # ``start`` itself is motionless (known safe): the grid's first factor is one step up.
        grid = geometric_grid(min(start * options.ratio, top), options.ratio, top)
    return ComponentSearch(record, name, names, pga_g, verdicts, start, top, reason, grid)


def search_record(
    searches: Sequence[ComponentSearch], options: IdaOptions
) -> tuple[CollapseIntensity, ...]:
    """Run the searches of a record's components and return their intensities.

    With ``options.adaptive`` the components that move are searched together
    (:func:`rockscreen.pipeline.engine.search.joint_first_exceedances`): a level of a
    component is settled once another component reaches it lower (the record's intensity
    is the smaller of its components'); else each is searched in full on its own.

    Parameters
    ----------
    searches : sequence of ComponentSearch
        The record's components (:func:`prepare_search`).
    options : IdaOptions

    Returns
    -------
    tuple of CollapseIntensity
        One per search, in order.
    """
    moving = [s for s in searches if s.grid is not None]
    members = [s.levels(options) for s in moving]
    grids = [s.grid for s in moving]
    floors = [s.start for s in moving]
    if options.adaptive:
        found = joint_first_exceedances(members, grids, options.tolerance, floors)
    else:
        found = [
            [Exceedance(f, lo) for f, lo in first_exceedance_factors(m, g, options.tolerance, fl)]
            for m, g, fl in zip(members, grids, floors, strict=True)
        ]
    by_search = {id(s): levels for s, levels in zip(moving, found, strict=True)}
    return tuple(_intensity(s, by_search.get(id(s)), options.cap_pga_g) for s in searches)


def _intensity(
    search: ComponentSearch, found: Sequence[Exceedance] | None, cap_pga_g: float
) -> CollapseIntensity:
    """Return the intensity of one component from its search's result (None: no search)."""
    s = search
    if s.verdicts is None:  # without motion: never moves, censored at the cap
        return CollapseIntensity(
            s.record, s.component, s.models, s.pga_g, math.inf, cap_pga_g, math.inf,
            cap_pga_g, True, True, "cap", math.inf, 0,
        )  # fmt: skip
    if found is None:  # nothing moves below the top
        found = [Exceedance(math.inf, s.top)] * 2
    collapse, lower, slv, censored, slv_censored, reason = _censor(
        found, s.top, s.verdicts, s.start, s.reason
    )
    return CollapseIntensity(
        record=s.record,
        component=s.component,
        models=s.models,
        pga_g=s.pga_g,
        collapse_scale=collapse,
        collapse_pga_g=collapse * s.pga_g,
        slv_scale=slv,
        slv_pga_g=slv * s.pga_g,
        censored=censored,
        slv_censored=slv_censored,
        censor_reason=reason,
        collapse_lower_scale=lower,
        n_solves=s.verdicts.n_solves,
    )


def _search_top(cap_factor: float, vertical: np.ndarray | None) -> tuple[float, str]:
    """Return the largest scale factor searched and the reason a search ending there is censored.

    The search stops at the cap, or just below the factor at which the scaled vertical
    reaches -g (where the rigid-block model still holds), whichever is lower.

    Parameters
    ----------
    cap_factor : float
        The factor at which the motion's PGA reaches the cap.
    vertical : numpy.ndarray or None
        Vertical ground acceleration at scale 1 [m/s²], positive up.

    Returns
    -------
    top : float
        The largest factor searched.
    reason : {"cap", "vertical_limit"}
        The censoring reason of a search that finds nothing up to ``top``.
    """
    lowest = float(np.min(vertical)) if vertical is not None and len(vertical) else 0.0
    limit_factor = -G / lowest if lowest < 0.0 else math.inf
    reason = "vertical_limit" if limit_factor <= cap_factor else "cap"
    return min(cap_factor, limit_factor * (1.0 - 1e-9)), reason


def _censor(
    found: Sequence[Exceedance],
    top: float,
    verdicts: _Verdicts,
    start: float,
    reason: str,
) -> tuple[float, float, float, bool, bool, str]:
    """Return the found scale factors with their censoring.

    ``(collapse, lower, slv, censored, slv_censored, reason)``. A level not reached below
    ``top`` is censored there; a level settled by the record's other component
    (:func:`rockscreen.pipeline.engine.search.joint_first_exceedances`) is censored where
    its search stopped (reason ``"other_component"``); where the solver refused a scaled
    motion (the model's limit, ``verdicts.limit``) below what was found, the levels above
    it are unknown and censored where the model last held. Overturning implies the SLV
    level, and ``reason`` is ``""`` when neither level is censored.
    """
    fell, damaged = found
    collapse, lower, slv = fell.factor, fell.lower, damaged.factor
    censored, slv_censored = math.isinf(collapse), math.isinf(slv)
    if censored:
        collapse = lower = fell.lower if fell.settled else top
    if slv_censored:
        slv = damaged.lower if damaged.settled else top
    if censored or slv_censored:
        settled = fell.settled if censored else damaged.settled
        reason = "other_component" if settled else reason
    if math.isfinite(verdicts.limit):
        # The solver refused a scaled motion (the model's limit) below what was found: the
        # levels above the limit are unknown, censored where the model last held.
        reason = "vertical_limit"
        held = verdicts.largest_safe_below(verdicts.limit, start)
        if censored or collapse >= verdicts.limit:
            collapse, lower, censored = held, held, True
        if slv_censored or slv >= verdicts.limit:
            slv, slv_censored = held, True
    if not censored:
        slv = min(slv, collapse)  # overturning implies the SLV level (a guard)
    if not (censored or slv_censored):
        reason = ""
    return collapse, lower, slv, censored, slv_censored, reason
