"""Best-estimate capacity of a tower's shaft in compression and flexure, over its priors.

The mechanics are the LV1 tower model of the Guidelines (DPCM 9/2/2011 §5.4.4;
:mod:`rockscreen.pipeline.risk.checks.tower_lv1`, ``docs/code_checks.md`` §3),
called, not copied: the shaft of ``ShaftSegment`` s built as ``assess`` builds it
(:func:`shaft_model`; the walls of
:func:`~rockscreen.pipeline.risk.checks.tower_lv1_checks.shaft_walls_m`), its sections by
:func:`~rockscreen.pipeline.risk.checks.tower_lv1.shaft_sections`, the demand of
:func:`~rockscreen.pipeline.risk.checks.tower_lv1.lv1_demand` on the site's NTC 2018
hazard. What differs from the code's check is the strength and the factors:

- the **mean** compressive strength ``f_m`` (a sample of its prior, or the measured value),
  with no partial factor and no confidence factor: ``f_d = f_m`` (``gamma_M = 1``,
  ``F_C = 1``; the code takes Table C8.5.I's value at the knowledge level over
  ``gamma_M F_C = 2 x 1.35`` at LC1);
- the unit weight, the walls and the period of each sample;
- the behaviour factor ``q`` = :data:`BEST_ESTIMATE_Q` = 3.0, the value rockscreen reads in
  the Guidelines (:data:`~rockscreen.pipeline.risk.checks.tower_lv1.LV1_TOWER_Q`, to
  be verified): no other value for masonry towers is sourced here, so the best estimate
  keeps the code's.

The capacity is ``a_SLV``, the ag on rock [g] at which the demand at T1 equals
``S_e,SLV = q F_SLV / (e* M)``: the LV1's, found for every sample at once
(:func:`capacity_from_spectral`: the demand tabulated on a grid of return periods, then
each sample's crossing refined to :data:`RTOL_LN_TR` in ln T_R by false position on the
same functions). Both plan directions share T1 and so the demand: the governing one is the
lower ``S_e,SLV`` (a square plan is computed once).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.hazard import RETURN_PERIODS_Y
from rockscreen.pipeline.risk.checks.confidence import design_compressive_strength
from rockscreen.pipeline.risk.checks.kinematic import PointMass
from rockscreen.pipeline.risk.checks.kinematic_demand import ElevatedSupport
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.checks.tower_lv1 import (
    LV1_TOWER_Q,
    ShaftSegment,
    TowerLV1,
    TowerModel,
    lv1_demand,
    lv1_demands,
    lv1_tower,
    shaft_sections,
)
from rockscreen.pipeline.risk.checks.tower_lv1_checks import (
    LV1_TAPER_SEGMENTS,
    LV1_TAPER_SLICES,
    shaft_walls_m,
)
from rockscreen.pipeline.risk.uncertainty.extrapolation import spectral_beyond_table
from rockscreen.solver.constants import G
from rockscreen.stations.tower import Tower

__all__ = [
    "BEST_ESTIMATE_Q",
    "GRID_POINTS",
    "RTOL_LN_TR",
    "ShaftCapacity",
    "best_estimate_lv1",
    "capacity_from_spectral",
    "critical_sections",
    "shaft_capacity",
    "shaft_model",
]

#: Behaviour factor of the best estimate [-] (module docstring).
BEST_ESTIMATE_Q = LV1_TOWER_Q
#: Return periods of the demand's grid, log-spaced over the table's 30-2475 y.
GRID_POINTS = 161
#: Tolerance of each sample's crossing: the bracket's width in ln T_R, or the demand within
#: this fraction of S_e,SLV (about twice it in ln T_R: the demand grows as T_R^0.3-0.6).
RTOL_LN_TR = 1.0e-7


def shaft_model(
    tower: Tower,
    *,
    wall_m: float,
    wall_top_m: float,
    unit_weight_n_m3: float,
    fm_pa: float,
    gamma_m: float = 1.0,
    fc: float = 1.0,
    across: bool = False,
) -> TowerModel:
    """Return the LV1 model of a tower's shaft for given walls, weight and strength.

    As ``assess`` builds it
    (:func:`~rockscreen.pipeline.risk.checks.tower_lv1_checks.lv1_tower_model`,
    ``docs/code_checks.md`` §3), the values given instead of the row's: the shaft from the base to
    ``height_m - belfry_height_m`` with the belfry columns (else ``height_m``), plan ``width_m`` x
    the plan depth; one prismatic segment (20 slices) when ``wall_top_m == wall_m``, else the ten
    tapering segments of ``shaft_walls_m`` (2 slices each); the belfry's piers and bells as point
    masses; ``f_d = f_m / (gamma_M F_C)``.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        The row (geometry, belfry columns).
    wall_m, wall_top_m : float
        Wall thickness at the base and at the top of the shaft [m], > 0.
    unit_weight_n_m3 : float
        Masonry unit weight w [N/m3].
    fm_pa : float
        Mean compressive strength f_m [Pa], > 0.
    gamma_m, fc : float
        Partial and confidence factors (1, 1: the best estimate; 2 and Table C8.5.I's FC:
        the code's).
    across : bool
        False: the action along ``width_m``; True: along the plan depth.

    Returns
    -------
    TowerModel
    """
    fd = design_compressive_strength(fm_pa, fc, gamma_m)
    b, a = float(tower.width_m), float(tower.plan_depth_m)
    if across:
        b, a = a, b
    belfry = tower.has_belfry
    shaft = tower.height_m - tower.belfry_height_m if belfry else tower.height_m
    walls = shaft_walls_m(
        SimpleNamespace(wall_thickness_m=float(wall_m), wall_thickness_top_m=float(wall_top_m))
    )
    density = float(unit_weight_n_m3) / G
    segments = tuple(ShaftSegment(shaft / len(walls), b, a, t, density) for t in walls)
    masses = []
    if belfry:
        masses.append(PointMass(tower.belfry_mass_kg, shaft + 0.5 * tower.belfry_height_m, 0.0))
        if tower.bells_mass_kg:
            masses.append(PointMass(tower.bells_mass_kg, shaft + tower.bells_height_m, 0.0))
    if len(segments) == 1:
        return TowerModel(segments, fd, tuple(masses))
    return TowerModel(segments, fd, tuple(masses), slices_per_segment=LV1_TAPER_SLICES)


def best_estimate_lv1(
    tower: Tower,
    site: SiteConditions,
    *,
    wall_m: float,
    wall_top_m: float,
    unit_weight_n_m3: float,
    fm_pa: float,
    period_s: float,
    q: float = BEST_ESTIMATE_Q,
    gamma_m: float = 1.0,
    fc: float = 1.0,
    support: ElevatedSupport | None = None,
) -> TowerLV1:
    """Return the LV1 result of one set of inputs, the governing plan direction's.

    :func:`~rockscreen.pipeline.risk.checks.tower_lv1.lv1_tower` on :func:`shaft_model`
    along both plan directions, the lower ``a_SLV`` kept (as ``assess``): the reference
    that :func:`shaft_capacity` reproduces for priors collapsed to points, and, with the
    code's strength and factors (``fm_pa`` of the knowledge level, ``gamma_m = 2``, ``fc``,
    ``q = 3``), the code's LV1.

    Parameters
    ----------
    tower, wall_m, wall_top_m, unit_weight_n_m3, fm_pa, gamma_m, fc
        As :func:`shaft_model`.
    site : SiteConditions
        The site.
    period_s : float
        T1 [s].
    q : float
        Behaviour factor [-].
    support : ElevatedSupport, optional
        The structure beneath the tower (:func:`lv1_demand`); None: on the ground.

    Returns
    -------
    TowerLV1
    """
    results = []
    for across in _directions(tower):
        model = shaft_model(
            tower,
            wall_m=wall_m,
            wall_top_m=wall_top_m,
            unit_weight_n_m3=unit_weight_n_m3,
            fm_pa=fm_pa,
            gamma_m=gamma_m,
            fc=fc,
            across=across,
        )
        results.append(lv1_tower(model, site, q=q, period_s=period_s, support=support))
    return min(results, key=lambda r: (r.capacity.ag_g, r.capacity.safety_index))


def _directions(tower: Tower) -> tuple[bool, ...]:
    """Return the plan directions to compute (one for a square plan: the same model)."""
    return (False,) if float(tower.width_m) == float(tower.plan_depth_m) else (False, True)


@dataclass(frozen=True)
class ShaftCapacity:
    """The best-estimate shaft capacity of every sample (arrays of the samples' length)."""

    #: a_SLV: ag on rock [g] at which the shaft fails (the governing direction's).
    ag_g: np.ndarray
    #: T_R of a_SLV [y] and I_S = T_R / T_R,SLV [-].
    return_period_y: np.ndarray
    safety_index: np.ndarray
    #: ``""``, ``"lower"`` (holds at 2475 y: a lower bound) or ``"upper"`` (fails at 30 y).
    bound: np.ndarray
    #: sigma_0 / (0.85 f_m) at the critical section [-] (f_d = f_m / (gamma_M F_C)).
    compression_ratio: np.ndarray
    #: Height of the critical section above the base [m].
    critical_height_m: np.ndarray
    #: S_e,SLV [m/s2] and the period T1 [s] of each sample.
    se_slv_m_s2: np.ndarray
    period_s: np.ndarray
    #: The factors used.
    q: float
    gamma_m: float
    fc: float
    #: Whether each sample's capacity is continued beyond the table (a value, not a bound:
    #: :mod:`~rockscreen.pipeline.risk.uncertainty.extrapolation`); None: none is.
    extrapolated: np.ndarray | None = None

    @property
    def median_g(self) -> float:
        """Return the median of ``ag_g`` [g]."""
        return float(np.median(self.ag_g))

    def interval_g(self, p: float = 0.9) -> tuple[float, float]:
        """Return the central interval of probability ``p`` of ``ag_g`` [g]."""
        if not 0.0 < p < 1.0:
            raise RiskError(f"interval level p={p!r} must be in (0, 1)")
        lo, hi = np.quantile(self.ag_g, [0.5 - 0.5 * p, 0.5 + 0.5 * p])
        return (float(lo), float(hi))


def _tr(ln_tr: float) -> float:
    """Return T_R [y] of ln T_R, kept inside the table's 30-2475 y (round-off at the ends)."""
    low, high = float(RETURN_PERIODS_Y[0]), float(RETURN_PERIODS_Y[-1])
    return min(max(math.exp(ln_tr), low), high)


def _demand_grid(
    periods: np.ndarray,
    site: SiteConditions,
    support: ElevatedSupport | None,
    vectorised: bool = True,
) -> tuple[np.ndarray, np.ndarray]:
    """Return ln T_R of the grid and the demand [m/s2] at each (T_R, period).

    ``vectorised``: all periods of one return period at once (:func:`lv1_demands`), else
    :func:`lv1_demand` per (T_R, period), the reference the array form is tested against.
    """
    ln_tr = np.linspace(
        math.log(float(RETURN_PERIODS_Y[0])), math.log(float(RETURN_PERIODS_Y[-1])), GRID_POINTS
    )
    if not vectorised:
        rows = [[lv1_demand(t, site.hazard(_tr(x)), site, support) for t in periods] for x in ln_tr]
        return ln_tr, np.array(rows, dtype=float).reshape(len(ln_tr), len(periods))
    return ln_tr, np.array(
        [lv1_demands(periods, site.hazard(_tr(x)), site, support) for x in ln_tr]
    )


def capacity_from_spectral(
    se_slv_m_s2: np.ndarray,
    period_s: np.ndarray,
    site: SiteConditions,
    support: ElevatedSupport | None = None,
    *,
    batch: bool = True,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return a_SLV [g], its T_R [y] and the bound for many (S_e,SLV, T1) pairs.

    What :func:`~rockscreen.pipeline.risk.checks.site_capacity.capacity_on_site` finds
    by bisection for one check (the same demand, :func:`lv1_demand`; the same bounds: a
    check holding at 2475 y is a lower bound, one failing at 30 y an upper bound), for all
    pairs at once: the demand on a grid of :data:`GRID_POINTS` return periods brackets each
    crossing, refined by false position (Illinois) to :data:`RTOL_LN_TR` in ln T_R.

    Parameters
    ----------
    se_slv_m_s2 : array_like
        S_e,SLV [m/s2] of each sample.
    period_s : array_like
        T1 [s] of each sample, > 0.
    site : SiteConditions
        The site.
    support : ElevatedSupport, optional
        The structure beneath the tower; None: on the ground.
    batch : bool
        True: the grid's demand at all periods of a return period at once
        (:func:`lv1_demands`; on a church's floor spectrum about 100 times faster); False:
        :func:`lv1_demand` per (return period, period), the reference the array form is
        tested against (``tests/pipeline/risk/uncertainty/test_shaft_floor.py``). The
        refinement calls :func:`lv1_demand` per sample in both.

    Returns
    -------
    ag_g, return_period_y : ndarray
    bound : ndarray of str
    """
    se = np.asarray(se_slv_m_s2, dtype=float)
    t1 = np.asarray(period_s, dtype=float)
    pairs, inverse = np.unique(np.column_stack([se, t1]), axis=0, return_inverse=True)
    ln_tr, demand = _demand_grid(pairs[:, 1], site, support, vectorised=batch)
    fails = demand > pairs[:, 0][None, :]
    out_tr = np.empty(len(pairs))
    bound = np.full(len(pairs), "", dtype=object)
    for k, (cap, t) in enumerate(pairs):
        if not fails[-1, k]:
            out_tr[k], bound[k] = _tr(ln_tr[-1]), "lower"
            continue
        if fails[0, k]:
            out_tr[k], bound[k] = _tr(ln_tr[0]), "upper"
            continue
        j = int(np.argmax(fails[:, k]))
        out_tr[k] = _tr(
            _false_position(
                lambda x, t=t, cap=cap: lv1_demand(t, site.hazard(_tr(x)), site, support) - cap,
                cap * RTOL_LN_TR,
                ln_tr[j - 1],
                demand[j - 1, k] - cap,
                ln_tr[j],
                demand[j, k] - cap,
            )
        )
    ag = np.array([site.hazard(tr).ag_g for tr in out_tr])
    return ag[inverse], out_tr[inverse], bound[inverse]


def _false_position(g, tol: float, a: float, ga: float, b: float, gb: float) -> float:
    """Return the root of ``g`` in [a, b] (``ga <= 0 < gb``), Illinois false position.

    Stops when ``|g| <= tol`` or the bracket is narrower than :data:`RTOL_LN_TR`.
    """
    side = 0
    for _ in range(100):
        x = b - gb * (b - a) / (gb - ga) if gb != ga else 0.5 * (a + b)
        gx = g(x)
        if gx > 0.0:
            b, gb = x, gx
            if side == -1:
                ga *= 0.5
            side = -1
        else:
            a, ga = x, gx
            if side == 1:
                gb *= 0.5
            side = 1
        if b - a < RTOL_LN_TR or abs(gx) <= tol:
            break
    return 0.5 * (a + b) if b - a < RTOL_LN_TR else x


@dataclass(frozen=True)
class CriticalSections:
    """The LV1 mechanics of many samples of one tower along one direction (arrays)."""

    #: S_e,SLV = q F_SLV / (e* M) [m/s2] of each sample.
    se_slv_m_s2: np.ndarray
    #: sigma_0 / (0.85 f_d) and the height above the base [m] of the critical section.
    compression_ratio: np.ndarray
    critical_height_m: np.ndarray


def critical_sections(
    tower: Tower,
    *,
    wall_m: np.ndarray,
    wall_top_m: np.ndarray,
    unit_weight_n_m3: np.ndarray,
    fd_pa: np.ndarray,
    q: float = BEST_ESTIMATE_Q,
    across: bool = False,
) -> CriticalSections:
    """Return the critical section of every sample: :func:`shaft_sections` in array form.

    The same mechanics as
    :func:`~rockscreen.pipeline.risk.checks.tower_lv1.shaft_sections` on
    :func:`shaft_model` (the masses lumped at the slices' mid-heights and the belfry's point
    masses, ``e*``, at the bottom of every slice the axial force, ``M_u`` of
    :func:`~rockscreen.pipeline.risk.checks.tower_lv1.section_ultimate_moment`'s
    stress block, the base shear ``M_u / lever``), for all samples at once: the 20 slices
    of a prismatic shaft (one segment of 20) and of a tapering one (ten segments of 2) are
    the same heights, so every sample is a row of one (samples x 20) array. The scalar
    functions stay the reference: :func:`shaft_capacity` with ``batch=False`` calls them
    per sample, and the test compares the two on prismatic, tapering, solid, crushing and
    belfried samples (``tests/pipeline/risk/uncertainty/test_shaft_batch.py``).

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        The row (geometry, belfry columns).
    wall_m, wall_top_m, unit_weight_n_m3, fd_pa : ndarray
        Per sample: the walls at the base and the top [m], w [N/m3], f_d [Pa].
    q : float
        Behaviour factor [-].
    across : bool
        As :func:`shaft_model`.

    Returns
    -------
    CriticalSections
    """
    t0 = np.asarray(wall_m, dtype=float)[:, None]
    t1 = np.asarray(wall_top_m, dtype=float)[:, None]
    fd = np.asarray(fd_pa, dtype=float)[:, None]
    density = np.asarray(unit_weight_n_m3, dtype=float)[:, None] / G
    b, a = float(tower.width_m), float(tower.plan_depth_m)
    if across:
        b, a = a, b
    belfry = tower.has_belfry
    shaft = tower.height_m - tower.belfry_height_m if belfry else tower.height_m
    slices = LV1_TAPER_SEGMENTS * LV1_TAPER_SLICES
    if TowerModel.__dataclass_fields__["slices_per_segment"].default != slices:
        raise RiskError(
            "critical_sections: a prismatic shaft's slices differ from a tapering one's; "
            "use shaft_capacity(batch=False)"
        )
    j = np.arange(slices)
    # The wall of each slice: the sample's base wall (prismatic) or its segment's
    # mid-height value (shaft_walls_m: base + (top - base) (k + 0.5) / 10).
    k = (j // LV1_TAPER_SLICES)[None, :]
    tapered = t0 + (t1 - t0) * (k + 0.5) / LV1_TAPER_SEGMENTS
    t = np.where(t1 == t0, np.broadcast_to(t0, tapered.shape), tapered)
    dz = shaft / slices
    bv, av = b - 2.0 * t, a - 2.0 * t
    hollow = (bv > 0.0) & (av > 0.0)
    bv, av = np.where(hollow, bv, 0.0), np.where(hollow, av, 0.0)
    area = b * a - bv * av
    z_cut = j * dz
    z = np.concatenate([(j + 0.5) * dz, [0.0, 0.0]])
    m = np.concatenate([area * dz * density, np.zeros((t.shape[0], 2))], axis=1)
    if belfry:
        z[slices] = shaft + 0.5 * tower.belfry_height_m
        m[:, slices] = tower.belfry_mass_kg
        if tower.bells_mass_kg:
            z[slices + 1] = shaft + tower.bells_height_m
            m[:, slices + 1] = tower.bells_mass_kg
    total = m.sum(axis=1)
    mz = m @ z
    e_star = mz**2 / (total * (m @ (z * z)))
    above = (z[None, :] > z_cut[:, None]).astype(float)  # cuts x lumps
    axial = G * (m @ above.T)
    # lever_j = sum_above m z (z - z_j) / sum m z
    lever = ((m * z * z) @ above.T - ((m * z) @ above.T) * z_cut[None, :]) / mz[:, None]
    mu = _ultimate_moment(b, a, t, bv, av, area, axial, fd)
    shear = mu / lever
    crit = np.argmin(shear, axis=1)
    rows = np.arange(t.shape[0])
    ratio = axial / (0.85 * fd * area)
    return CriticalSections(
        se_slv_m_s2=q * shear[rows, crit] / (e_star * total),
        compression_ratio=ratio[rows, crit],
        critical_height_m=z_cut[crit],
    )


def _ultimate_moment(b, a, t, bv, av, area, axial, fd) -> np.ndarray:
    """Return M_u [N m] of every (sample, section): section_ultimate_moment in array form."""
    stress = 0.85 * fd
    needed = axial / stress
    solid = bv == 0.0
    web = a * t
    flange = web + (a - av) * bv
    with np.errstate(divide="ignore", invalid="ignore"):
        x = np.where(
            solid | (needed <= web),
            needed / a,
            np.where(
                needed <= flange,
                t + (needed - web) / (a - av),
                b - t + (needed - flange) / a,
            ),
        )
    mid = np.where(solid, t, np.clip(np.maximum(x, t), None, b - t))
    first = a * x**2 / 2.0 - av * (mid**2 - t**2) / 2.0
    mu = np.maximum(axial * b / 2.0 - stress * first, 0.0)
    return np.where(needed >= area, 0.0, mu)


def shaft_capacity(
    tower: Tower,
    site: SiteConditions,
    samples: dict[str, np.ndarray],
    *,
    q: float = BEST_ESTIMATE_Q,
    gamma_m: float = 1.0,
    fc: float = 1.0,
    support: ElevatedSupport | None = None,
    batch: bool = True,
    extrapolate: bool = True,
) -> ShaftCapacity:
    """Return the best-estimate shaft capacity of every sample of a tower's inputs.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        The row (geometry, belfry columns).
    site : SiteConditions
        The site.
    samples : dict
        ``wall_m``, ``wall_top_m``, ``unit_weight_n_m3``, ``fm_pa``, ``period_s`` arrays of
        one length (:meth:`~rockscreen.pipeline.risk.uncertainty.priors.TowerPriors.sample`).
    q, gamma_m, fc : float
        Behaviour, partial and confidence factors (defaults: the best estimate).
    support : ElevatedSupport, optional
        The structure beneath the tower; None: on the ground.
    batch : bool
        True: the sections of all samples at once (:func:`critical_sections`, about 50
        times faster); False: :func:`shaft_model` and ``shaft_sections`` per sample (the
        reference the batch is tested against).
    extrapolate : bool
        True (the screening risk): a sample holding at 2475 y (failing at 30 y) gets the
        capacity of the demand continued beyond the table, shape held
        (:func:`~rockscreen.pipeline.risk.uncertainty.extrapolation.spectral_beyond_table`),
        flagged ``extrapolated`` with no bound; its ``return_period_y`` stays the table's
        end. False: the bound, as the code's check.

    Returns
    -------
    ShaftCapacity
    """
    names = ("wall_m", "wall_top_m", "unit_weight_n_m3", "fm_pa", "period_s")
    missing = [k for k in names if k not in samples]
    if missing:
        raise RiskError(f"shaft capacity: samples lack {', '.join(missing)}")
    x = {k: np.asarray(samples[k], dtype=float) for k in names}
    n = x["period_s"].size
    if any(v.shape != (n,) for v in x.values()):
        raise RiskError("shaft capacity: the samples' arrays differ in length")
    if batch:
        se, ratio, height = _batch_sections(tower, x, q, gamma_m, fc)
    else:
        se, ratio, height = _sample_sections(tower, x, q, gamma_m, fc)
    ag, tr, bound = capacity_from_spectral(se, x["period_s"], site, support)
    beyond = np.zeros(n, dtype=bool)
    if extrapolate and np.any(bound != ""):
        ag, bound = ag.copy(), bound.copy()
        out = np.full(n, np.nan)
        out[bound != ""] = spectral_beyond_table(
            se[bound != ""], x["period_s"][bound != ""], bound[bound != ""], site, support
        )
        beyond = np.isfinite(out)  # not where S_e,SLV = 0: the code's bound stays
        ag[beyond], bound[beyond] = out[beyond], ""
    return ShaftCapacity(
        ag_g=ag,
        return_period_y=tr,
        safety_index=tr / site.tr_slv_y(),
        bound=bound,
        compression_ratio=ratio,
        critical_height_m=height,
        se_slv_m_s2=se,
        period_s=x["period_s"],
        q=float(q),
        gamma_m=float(gamma_m),
        fc=float(fc),
        extrapolated=beyond,
    )


def _batch_sections(
    tower: Tower, x: dict[str, np.ndarray], q: float, gamma_m: float, fc: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return S_e,SLV, the ratio and the height of the governing direction, all at once."""
    fd = np.array([design_compressive_strength(v, fc, gamma_m) for v in np.unique(x["fm_pa"])])
    fd = fd[np.searchsorted(np.unique(x["fm_pa"]), x["fm_pa"])]
    best = None
    for across in _directions(tower):
        out = critical_sections(
            tower,
            wall_m=x["wall_m"],
            wall_top_m=x["wall_top_m"],
            unit_weight_n_m3=x["unit_weight_n_m3"],
            fd_pa=fd,
            q=q,
            across=across,
        )
        arrays = (out.se_slv_m_s2, out.compression_ratio, out.critical_height_m)
        if best is None:
            best = arrays
        else:
            lower = arrays[0] < best[0]  # the first direction kept on a tie (as per sample)
            best = tuple(np.where(lower, new, old) for new, old in zip(arrays, best, strict=True))
    return best


def _sample_sections(
    tower: Tower, x: dict[str, np.ndarray], q: float, gamma_m: float, fc: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return S_e,SLV, the ratio and the height of the governing direction, per sample."""
    n = x["period_s"].size
    se = np.empty(n)
    ratio = np.empty(n)
    height = np.empty(n)
    for i in range(n):
        best = None
        for across in _directions(tower):
            model = shaft_model(
                tower,
                wall_m=x["wall_m"][i],
                wall_top_m=x["wall_top_m"][i],
                unit_weight_n_m3=x["unit_weight_n_m3"][i],
                fm_pa=x["fm_pa"][i],
                gamma_m=gamma_m,
                fc=fc,
                across=across,
            )
            mass, e_star, sections = shaft_sections(model)
            critical = min(sections, key=lambda s: s.base_shear_n)
            value = q * critical.base_shear_n / (e_star * mass)
            if best is None or value < best[0]:
                best = (value, critical)
        se[i], ratio[i], height[i] = best[0], best[1].compression_ratio, best[1].height_m
    return se, ratio, height
