"""Collapse intensity per record: incremental dynamic analysis of one tower.

For one tower, one ground motion and each of its horizontal components (against the
tower's enabled models), the **collapse scale** is the smallest amplitude scale factor at
which the tower first overturns (any model: the tower is lost whatever the model that
predicts it), and the **SLV scale** the smallest factor at which it reaches the
life-safety damage level :data:`SLV_THETA_RATIO` (or overturns). The records of a set
give a sample of collapse intensities, fitted by
:func:`rockscreen.pipeline.risk.measures.censored_fit.fit_censored_lognormal` (Baker 2015,
Earthquake Spectra 31(1), 579-599, "incremental dynamic analysis"; Vamvatsikos & Cornell 2002).

Intensity measure
-----------------
The intensity of a scaled motion is its PGA: ``collapse_pga_g = collapse_scale *
pga_g``, where ``pga_g`` [g] is the motion's own PGA at scale 1 (the larger peak of its
horizontal channels, as given). The IM is a property of the motion alone, so the
components of one record share it and the record's collapse intensity is the smaller of
its components' (:func:`record_collapse`). A caller that scaled a record to a target
(e.g. a stripe's ag on rock with the record's factor ``k``) passes the scaled motion and
reads intensities in that motion's PGA; converting to the stripe's IM
(``collapse_scale * ag``) is the caller's business, not this module's.

The search
----------
Rocking is not monotone in amplitude (a block that overturns at ``f`` may survive at
``1.1 f``: the safe regions of Zhang & Makris 2001), so the search is the engine's one
scan-then-bisect (:func:`rockscreen.pipeline.engine.search.first_exceedance_factors`, also
the campaign's safety factor), not a plain bisection:

1. an upward geometric scan ``f_k = f_0 ratio**k`` (default ratio 1.2, steps of 20 %)
   from ``f_0`` = the uplift-free factor
   (:func:`rockscreen.pipeline.engine.uplift.uplift_free_factor`: up to it no sample can
   lift the block, so nothing moves, and the first factor solved is ``f_0 ratio``) up to
   the cap (always on the grid), until the tower overturns; the first grid factor
   reaching the SLV level is noted on the way;
2. for each level, bisection between the last grid factor below it and the first one
   reaching it, until the bracket is narrower than ``tolerance`` (default 1 %) of its
   upper end; the upper end, a factor that reaches the level, is reported.

A window of overturning narrower than one grid step below the first overturning grid
factor can be missed: the grid step is the stated resolution of the search. Each scale
factor is solved once (both levels read the same verdicts). Overturning implies the SLV
level, so the SLV scale is never above the collapse scale.

The components of a record are searched together (``IdaOptions.adaptive``, default;
:func:`rockscreen.pipeline.engine.search.joint_first_exceedances`): the record's intensity
is the smaller of its components', so a component's level is left **settled** (censored
where its search stopped, reason ``"other_component"``) once the other component reaches it
lower. The record's intensities, censoring and reasons are those of the full search of
every component (:func:`record_collapse`), with fewer solves.

Censoring
---------
A component is **right-censored** (never dropped, never counted as overturning) when

- ``cap``: no overturning up to the cap, the factor at which the motion's PGA reaches
  ``cap_pga_g`` (default :data:`DEFAULT_CAP_PGA_G` = 3 g): the level of the largest PGAs
  ever recorded (about 3-4 g, e.g. Iwate-Miyagi 2008) and about three times the largest
  surface PGA of the Italian code hazard (the shipped NTC grid's largest ag on rock is
  0.62 g at T_R = 2475 y; times the soil and topography factors, about 1 g), where the
  annual rate of exceedance, and so the contribution to ``lambda_C``, is nil; for a
  slender tower (``tan(alpha) <= 0.3``) it is at least ten times the uplift threshold
  ``g tan(alpha)`` (20 times for the 0.6 m x 4 m block of the tests);
- ``other_component``: the record's other component reaches the level lower (the adaptive
  search above): a lower bound of this component's capacity, never the record's;
- ``vertical_limit``: the scaled vertical reaches -g first (the base would fall away
  from the tower; the rigid-block model no longer holds; the search stops just below
  that factor, ``-g / min(a_v)``, as the campaign's safety factor does), or the solver
  refuses the scaled motion as out of the model's validity
  (:func:`rockscreen.pipeline.engine.cases.screen_case` status ``vertical_limit``).

A censored component's scale and intensity are the censoring values: the largest factor
(and PGA) up to which the search saw no overturning, a lower bound of the capacity.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rockscreen.pipeline.engine.cases import BlockCache
from rockscreen.pipeline.engine.loop import ComponentCases
from rockscreen.pipeline.engine.motion import GroundMotion, TowerComponent, tower_components
from rockscreen.pipeline.engine.registry import available_models, model_names
from rockscreen.pipeline.engine.search import (
    Exceedance,
    first_exceedance_factors,
    geometric_grid,
    joint_first_exceedances,
)
from rockscreen.pipeline.engine.uplift import uplift_free_factor
from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.measures.censored_fit import CensoredFit, fit_censored_lognormal
from rockscreen.solver.constants import G
from rockscreen.stations.tower import Tower

__all__ = [
    "CENSOR_REASONS",
    "DEFAULT_CAP_PGA_G",
    "SLV_THETA_RATIO",
    "CollapseIntensity",
    "IdaOptions",
    "component_collapse_intensity",
    "ida_fragility",
    "motion_pga_g",
    "record_collapse",
    "record_collapse_intensities",
]

#: SLV (life-safety) level of a local mechanism as theta_max/alpha [-]: the Circolare 2019
#: (Circ. 21/01/2019 n. 7, §C8.7.1.2.1.6, PDF p. 276) places the SLV displacement of a local
#: mechanism at "il 40% dello spostamento d_0" at which its capacity vanishes (the kinematic
#: analysis' ``d_SLV = 0.4 d_0``); for the rigid block the overturning rotation is alpha, so
#: the level is ``theta_max / alpha >= 0.4``.
SLV_THETA_RATIO = 0.4

#: Default cap of the search as the PGA of the scaled motion [g] (module docstring: why).
DEFAULT_CAP_PGA_G = 3.0

#: ``censor_reason`` values: no overturning up to the cap; the model's vertical limit first;
#: the record's other component reaches the level lower, so this one's search stopped.
CENSOR_REASONS = ("cap", "vertical_limit", "other_component")


@dataclass(frozen=True)
class IdaOptions:
    """How the collapse intensity is searched."""

    #: Models enabled (names of the campaign models of the registry; default all).
    models: tuple[str, ...] = field(default_factory=model_names)
    #: Geometric step of the upward scan, > 1 [-] (the resolution of the search).
    ratio: float = 1.2
    #: Relative width of the final bisection bracket, > 0 [-].
    tolerance: float = 0.01
    #: The search stops where the scaled motion's PGA reaches this [g].
    cap_pga_g: float = DEFAULT_CAP_PGA_G
    #: Free motion followed after the record [s] (the solvers' ``max_free_time``).
    free_motion_s: float = 60.0
    #: Damage level searched besides overturning, theta_max/alpha [-].
    slv_theta_ratio: float = SLV_THETA_RATIO
    #: Stop each solve's free motion once its verdict is certain (``docs/theory.md``,
    #: :func:`rockscreen.pipeline.engine.cases.screen_case`); False: the reference path.
    early_stop: bool = True
    #: Search a record's components together and stop a component's level once the other
    #: component reaches it lower (the record's intensities are those of the full search,
    #: with fewer solves: :func:`rockscreen.pipeline.engine.search.joint_first_exceedances`);
    #: False: every component searched in full (the reference).
    adaptive: bool = True

    def __post_init__(self) -> None:
        if not (self.ratio > 1.0 and math.isfinite(self.ratio)):
            raise RiskError(f"IDA: ratio={self.ratio!r} must be a finite number > 1")
        if not (0.0 < self.tolerance < 1.0):
            raise RiskError(f"IDA: tolerance={self.tolerance!r} must be in (0, 1)")
        if not (self.cap_pga_g > 0.0 and math.isfinite(self.cap_pga_g)):
            raise RiskError(f"IDA: cap_pga_g={self.cap_pga_g!r} g must be a finite number > 0")
        if not (0.0 < self.slv_theta_ratio <= 1.0):
            raise RiskError(f"IDA: slv_theta_ratio={self.slv_theta_ratio!r} must be in (0, 1]")


@dataclass(frozen=True)
class CollapseIntensity:
    """The collapse and SLV intensities of one record component against a tower's models.

    When ``censored`` (``slv_censored``) the scale and intensity are the censoring values:
    the largest factor, and its PGA, up to which the search saw no overturning (no SLV
    level), a lower bound of the capacity.
    """

    #: The motion's name (``GroundMotion.record_id``).
    record: str
    #: The component (``"X"``, ``"Y"``, or a channel's letter).
    component: str
    #: The models searched together (comma-separated names): any of them counts.
    models: str
    #: PGA of the motion at scale 1 [g]: the larger peak of its horizontal channels.
    pga_g: float
    #: Smallest scale factor found to overturn the tower [-] (censoring factor if censored).
    collapse_scale: float
    #: ``collapse_scale * pga_g`` [g] (``cap_pga_g`` for a component without motion, whose
    #: scale is ``inf``).
    collapse_pga_g: float
    #: Smallest scale factor found to reach theta_max/alpha >= the SLV level or overturn [-].
    slv_scale: float
    #: ``slv_scale * pga_g`` [g].
    slv_pga_g: float
    #: No overturning found up to the censoring factor.
    censored: bool
    #: No SLV level found up to the censoring factor.
    slv_censored: bool
    #: Why the search stopped short of a level: ``"cap"`` or ``"vertical_limit"``; ``""``
    #: when neither level is censored.
    censor_reason: str
    #: Largest factor known safe below ``collapse_scale`` [-] (the bisection's lower end;
    #: the uplift-free factor when the scan's first factor overturned).
    collapse_lower_scale: float
    #: Solver calls made (motionless cases and shared verdicts are not solves).
    n_solves: int


def motion_pga_g(motion: GroundMotion) -> float:
    """Return the PGA of ``motion`` [g]: the larger peak of its horizontal channels.

    Parameters
    ----------
    motion : GroundMotion
        Horizontal accelerations in [m/s²].
    """
    peaks = [float(np.max(np.abs(h))) for h in motion.horizontals if len(h)]
    return max(peaks, default=0.0) / G


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
class _ComponentSearch:
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


def _prepare(
    tower: Tower,
    record: str,
    component: TowerComponent,
    vertical: np.ndarray | None,
    dt: float,
    pga_g: float,
    options: IdaOptions,
    blocks: BlockCache,
) -> _ComponentSearch:
    """Return a component's search, ready to run (:func:`component_collapse_intensity`)."""
    models = available_models(tower, options.models)
    names = ",".join(m.name for m in models)
    if not models:
        raise RiskError(f"IDA: tower {tower.id!r} runs none of the models {options.models}")
    acc = component.acc
    peak_g = float(np.max(np.abs(acc))) / G if len(acc) else 0.0
    name = component.component
    if not (pga_g > 0.0 and math.isfinite(pga_g)) or peak_g == 0.0:
        # A component without motion never moves at any scale: censored at the cap.
        return _ComponentSearch(record, name, names, pga_g, None, math.inf, math.inf, "cap", None)
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
    return _ComponentSearch(record, name, names, pga_g, verdicts, start, top, reason, grid)


def _search_record(
    searches: Sequence[_ComponentSearch], options: IdaOptions
) -> tuple[CollapseIntensity, ...]:
    """Run the searches of a record's components and return their intensities.

    With ``options.adaptive`` the components that move are searched together
    (:func:`rockscreen.pipeline.engine.search.joint_first_exceedances`): a level of a
    component is settled once another component reaches it lower (the record's intensity
    is the smaller of its components'); else each is searched in full on its own.
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
    search: _ComponentSearch, found: Sequence[Exceedance] | None, cap_pga_g: float
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


def component_collapse_intensity(
    tower: Tower,
    record: str,
    component: str,
    acc: np.ndarray,
    width_m: float,
    axis: str | None,
    vertical: np.ndarray | None,
    dt: float,
    pga_g: float,
    options: IdaOptions | None = None,
    blocks: Any = None,
) -> CollapseIntensity:
    """Search the collapse and SLV scale factors of one component (module docstring).

    The component alone, searched in full (:func:`record_collapse_intensities` searches
    a record's components together).

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
    record : str
        The motion's name.
    component : str
        The component's name.
    acc : numpy.ndarray
        The component's ground acceleration at scale 1 [m/s²].
    width_m : float
        Block width in the component's direction [m].
    axis : {"x", "y"} or None
        The tower axis the component is along, None when it is along neither
        (:class:`rockscreen.pipeline.engine.motion.TowerComponent`): a part model's block
        follows it.
    vertical : numpy.ndarray or None
        Vertical ground acceleration at scale 1 [m/s²], positive up; scaled with ``acc``.
    dt : float
        Sampling step [s].
    pga_g : float
        The motion's PGA at scale 1 [g] (:func:`motion_pga_g`): the intensity is
        ``scale * pga_g``.
    options : IdaOptions, optional
    blocks : rockscreen.pipeline.engine.cases.BlockCache, optional
        The tower's blocks by width and axis.

    Returns
    -------
    CollapseIntensity
    """
    options = options or IdaOptions()
    blocks = BlockCache(tower) if blocks is None else blocks
    part = TowerComponent(component, acc, width_m, axis)
    search = _prepare(tower, record, part, vertical, dt, pga_g, options, blocks)
    (result,) = _search_record([search], options)
    return result


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


def record_collapse_intensities(
    tower: Tower,
    motion: GroundMotion,
    options: IdaOptions | None = None,
    blocks: Any = None,
) -> tuple[CollapseIntensity, ...]:
    """Return the collapse and SLV intensities of every component of ``motion``.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
    motion : GroundMotion
        The ground motion at scale 1 (e.g. ``suite_motion(record, 1.0)``); its vertical,
        when present, is scaled with the horizontals.
    options : IdaOptions, optional
    blocks : rockscreen.pipeline.engine.cases.BlockCache, optional
        The tower's blocks by width and axis, shared between records.

    Returns
    -------
    tuple of CollapseIntensity
        One per component of :func:`rockscreen.pipeline.engine.motion.tower_components`.
    """
    options = options or IdaOptions()
    blocks = BlockCache(tower) if blocks is None else blocks
    pga_g = motion_pga_g(motion)
    searches = [
        _prepare(
            tower,
            motion.record_id,
            TowerComponent(component, acc, width, axis),
            motion.vertical,
            motion.dt,
            pga_g,
            options,
            blocks,
        )
        for component, acc, width, axis in tower_components(tower, motion)
    ]
    return _search_record(searches, options)


def record_collapse(results: Sequence[CollapseIntensity], level: str = "collapse") -> dict:
    """Combine the components of each record: the tower is lost when either component fails.

    The record's scale is the smallest of its components'; it is censored when that
    smallest one is (the record then survived every component up to it). Components of a
    record share its PGA, so the intensity combines the same way.

    Parameters
    ----------
    results : sequence of CollapseIntensity
    level : {'collapse', 'slv'}

    Returns
    -------
    dict
        record -> ``(intensity [g], censored, censor_reason)``, in first-seen order.
    """
    if level not in ("collapse", "slv"):
        raise RiskError(f"IDA: level {level!r} is not 'collapse' or 'slv'")
    out: dict[str, tuple[float, bool, str]] = {}
    for r in results:
        if level == "collapse":
            value, censored = r.collapse_pga_g, r.censored
        else:
            value, censored = r.slv_pga_g, r.slv_censored
        reason = r.censor_reason if censored else ""
        best = out.get(r.record)
        # Ties: an observed level beats a censoring at the same intensity.
        if best is None or (value, censored) < (best[0], best[1]):
            out[r.record] = (value, censored, reason)
    return out


def ida_fragility(results: Sequence[CollapseIntensity], level: str = "collapse") -> CensoredFit:
    """Fit the censored lognormal fragility in PGA to the records' intensities.

    Parameters
    ----------
    results : sequence of CollapseIntensity
        Components of the records (combined per record by :func:`record_collapse`).
    level : {'collapse', 'slv'}

    Returns
    -------
    CensoredFit
    """
    combined = record_collapse(results, level)
    intensities = [value for value, _, _ in combined.values()]
    censored = [flag for _, flag, _ in combined.values()]
    return fit_censored_lognormal(intensities, censored)
