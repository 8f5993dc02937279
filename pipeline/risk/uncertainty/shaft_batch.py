"""The critical sections of many samples of a tower's shaft at once: the LV1 in array form.

:func:`critical_sections` is
:func:`~rockscreen.pipeline.risk.checks.tower_lv1.shaft_sections` on
:func:`~rockscreen.pipeline.risk.uncertainty.shaft.shaft_model` for every sample of
:func:`~rockscreen.pipeline.risk.uncertainty.shaft.shaft_capacity` as rows of one array
(``shaft_capacity(batch=True)``, the default); the scalar functions stay the reference it is
tested against (``tests/pipeline/risk/uncertainty/test_shaft_batch.py``).
``docs/uncertainty.md``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.checks.tower_lv1 import LV1_TOWER_Q, TowerModel
from rockscreen.pipeline.risk.checks.tower_lv1_checks import (
    LV1_TAPER_SEGMENTS,
    LV1_TAPER_SLICES,
)
from rockscreen.solver.constants import G
from rockscreen.stations.tower import Tower

__all__ = ["CriticalSections", "critical_sections"]


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
    q: float = LV1_TOWER_Q,
    across: bool = False,
) -> CriticalSections:
    """Return the critical section of every sample: :func:`shaft_sections` in array form.

    The same mechanics as
    :func:`~rockscreen.pipeline.risk.checks.tower_lv1.shaft_sections` on
    :func:`~rockscreen.pipeline.risk.uncertainty.shaft.shaft_model` (the masses lumped at the
    slices' mid-heights and the belfry's point masses, ``e*``, at the bottom of every slice
    the axial force, ``M_u`` of
    :func:`~rockscreen.pipeline.risk.checks.tower_lv1.section_ultimate_moment`'s
    stress block, the base shear ``M_u / lever``), for all samples at once: the 20 slices
    of a prismatic shaft (one segment of 20) and of a tapering one (ten segments of 2) are
    the same heights, so every sample is a row of one (samples x 20) array. The scalar
    functions stay the reference:
    :func:`~rockscreen.pipeline.risk.uncertainty.shaft.shaft_capacity` with ``batch=False``
    calls them per sample, and the test compares the two on prismatic, tapering, solid,
    crushing and belfried samples (``tests/pipeline/risk/uncertainty/test_shaft_batch.py``).

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        The row (geometry, belfry columns).
    wall_m, wall_top_m, unit_weight_n_m3, fd_pa : ndarray
        Per sample: the walls at the base and the top [m], w [N/m3], f_d [Pa].
    q : float
        Behaviour factor [-] (default: the code's, which the best estimate keeps,
        :data:`~rockscreen.pipeline.risk.uncertainty.shaft.BEST_ESTIMATE_Q`).
    across : bool
        As :func:`~rockscreen.pipeline.risk.uncertainty.shaft.shaft_model`.

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
