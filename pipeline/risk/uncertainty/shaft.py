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
(:func:`~rockscreen.pipeline.risk.uncertainty.shaft_hazard.capacity_from_spectral`: the
demand tabulated on a grid of return periods, then each sample's crossing refined by false
position on the same functions). The sections of all samples are computed at once
(:func:`~rockscreen.pipeline.risk.uncertainty.shaft_batch.critical_sections`). Both plan
directions share T1 and so the demand: the governing one is the lower ``S_e,SLV`` (a square
plan is computed once).
"""

from __future__ import annotations

from dataclasses import dataclass
from types import SimpleNamespace

import numpy as np

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.checks.confidence import design_compressive_strength
from rockscreen.pipeline.risk.checks.kinematic import PointMass
from rockscreen.pipeline.risk.checks.kinematic_demand import ElevatedSupport
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.checks.tower_lv1 import (
    LV1_TOWER_Q,
    ShaftSegment,
    TowerLV1,
    TowerModel,
    lv1_tower,
    shaft_sections,
)
from rockscreen.pipeline.risk.checks.tower_lv1_checks import LV1_TAPER_SLICES, shaft_walls_m
from rockscreen.pipeline.risk.uncertainty.extrapolation import spectral_beyond_table
from rockscreen.pipeline.risk.uncertainty.shaft_batch import critical_sections
from rockscreen.pipeline.risk.uncertainty.shaft_hazard import capacity_from_spectral
from rockscreen.solver.constants import G
from rockscreen.stations.tower import Tower

__all__ = [
    "BEST_ESTIMATE_Q",
    "ShaftCapacity",
    "best_estimate_lv1",
    "shaft_capacity",
    "shaft_model",
]

#: Behaviour factor of the best estimate [-] (module docstring).
BEST_ESTIMATE_Q = LV1_TOWER_Q


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
        The structure beneath the tower
        (:func:`~rockscreen.pipeline.risk.checks.tower_lv1.lv1_demand`); None: on the ground.

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
        True: the sections of all samples at once
        (:func:`~rockscreen.pipeline.risk.uncertainty.shaft_batch.critical_sections`, about
        50 times faster); False: :func:`shaft_model` and ``shaft_sections`` per sample (the
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
