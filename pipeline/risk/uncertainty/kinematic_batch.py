"""The non-linear kinematic check of many samples of a mechanism at once (issue 31).

What :func:`~rockscreen.pipeline.risk.checks.kinematic.kinematic_check` finds for one
mechanism, its non-linear SLV check's capacity (Circolare 2019 §C8.7.1.2.1.8: the check
holds while ``a0* >= `` the activation demand or ``d_u* >=`` the displacement demand; the
capacity is the return period at which it holds at equality, found by
:func:`~rockscreen.pipeline.risk.checks.site_capacity.capacity_on_site`'s bisection in
ln T_R to 1e-6), for every sample of the screening risk at once: each sample its own
capacity curve (``a0*``, ``d_u*``, ``T_SLV``, ``T0`` of
:func:`~rockscreen.pipeline.risk.checks.kinematic.kinematic_capacity`) and its own structure
beneath (the shaft under a sampled belfry has the sample's period). The bisection runs on
all samples together, each at its own return period: the site's hazard interpolated log-log
between the tabulated return periods (NTC 2018 Allegato A, eq. 4) as arrays, the elastic and
displacement spectra of NTC 2018 §3.2.3.2 (eqs. 3.2.2-3.2.12) and the floor spectrum of the
Circolare 2019 §C7.2.3 ([C7.2.5]-[C7.2.10]) element-wise, the demands of
:mod:`rockscreen.pipeline.risk.checks.kinematic_demand` (activation [C8.7.1.9], displacement
[C8.7.1.12] with the structure at the ultimate states, §C8.7.1.2.1.4; never below the
ground's). A check holding at 2475 y is continued beyond the table as
:func:`~rockscreen.pipeline.risk.uncertainty.extrapolation.kinematic_beyond_table` does.

The scalar path stays the reference: the kinematic capacities with ``batch=False`` call
:func:`kinematic_check` per distinct input, and the test compares the two
(``tests/pipeline/risk/uncertainty/test_kinematic_batch.py``). ``docs/uncertainty.md``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.hazard import RETURN_PERIODS_Y
from rockscreen.pipeline.hazard.spectrum import (
    DISPLACEMENT_CORNERS_S,
    SOIL_CLASSES,
    TOPOGRAPHY_FACTORS,
    damping_factor,
)
from rockscreen.pipeline.risk.checks.floor_spectrum import FLOOR_A, FLOOR_B
from rockscreen.pipeline.risk.checks.kinematic import KinematicCapacity
from rockscreen.pipeline.risk.checks.kinematic_demand import (
    SLD_DAMPING,
    SLV_MECHANISM_DAMPING,
    ULS_STRUCTURE_DAMPING,
    ULS_STRUCTURE_PERIOD_FACTOR,
    ElevatedSupport,
)
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions, elastic_spectra
from rockscreen.pipeline.risk.uncertainty.extrapolation import CONTINUED_BOUNDS, EXTRAPOLATED
from rockscreen.solver.constants import G

__all__ = ["BISECTION_RTOL", "nonlinear_capacities"]

#: Tolerance of the bisection in ln T_R (``capacity_on_site``'s default).
BISECTION_RTOL = 1.0e-6
#: Periods of the displacement demand's maximum over [T0, T_SLV] (``displacement_demand``'s).
_DEMAND_GRID = 241
#: The elastic structure beneath (SLD): its period as given, 5 % (``ElevatedSupport.state``).
_ELASTIC_STRUCTURE_DAMPING = 0.05


@dataclass(frozen=True)
class _Spectrum:
    """NTC 2018 §3.2.3.2.1 spectrum parameters of many actions (columns of shape (n, 1))."""

    ag_g: np.ndarray
    f0: np.ndarray
    s: np.ndarray
    tb_s: np.ndarray
    tc_s: np.ndarray
    td_s: np.ndarray


class _Site:
    """A site's hazard at many return periods at once, and its spectra (arrays)."""

    def __init__(self, site: SiteConditions) -> None:
        self.site = site
        # The tabulated values: site_hazard at a tabulated T_R returns the node's values.
        rows = [site.hazard(float(tr)) for tr in RETURN_PERIODS_Y]
        self.ln_tr = np.log(np.asarray(RETURN_PERIODS_Y, dtype=float))
        self.ln_tables = [
            np.log([getattr(h, k) for h in rows]) for k in ("ag_g", "F0", "Tc_star_s")
        ]
        key = str(site.soil_class).strip().upper()
        if key not in SOIL_CLASSES:
            raise RiskError(f"soil class {site.soil_class!r}; allowed: {', '.join(SOIL_CLASSES)}")
        self.soil = SOIL_CLASSES[key]
        self.s_t = TOPOGRAPHY_FACTORS[str(site.topography).strip().upper()]
        self.corners = DISPLACEMENT_CORNERS_S[key]

    def spectrum(self, ln_tr: np.ndarray) -> _Spectrum:
        """Return the spectrum parameters at each ln T_R (Allegato A eq. 4, Tab. 3.2.IV)."""
        x = np.clip(ln_tr, self.ln_tr[0], self.ln_tr[-1])
        k = np.clip(np.searchsorted(self.ln_tr, x), 1, self.ln_tr.size - 1)
        w = (x - self.ln_tr[k - 1]) / (self.ln_tr[k] - self.ln_tr[k - 1])
        ag, f0, tc_star = (
            np.exp(t[k - 1] + (t[k] - t[k - 1]) * w)[:, None] for t in self.ln_tables
        )
        a, b, lower, upper, c, d = self.soil
        s_s = np.clip(a - b * f0 * ag, lower, upper)
        tc = c * tc_star**d * tc_star
        return _Spectrum(ag, f0, s_s * self.s_t, tc / 3.0, tc, 4.0 * ag + 1.6)

    @staticmethod
    def elastic(t: np.ndarray, p: _Spectrum, damping: float) -> np.ndarray:
        """Return Se(T) [m/s2] of eq. 3.2.2 (``elastic_spectrum`` element-wise)."""
        eta = damping_factor(damping)
        return elastic_spectra(t, p.ag_g * p.s, eta, p.f0, p.tb_s, p.tc_s, p.td_s)

    def displacement(self, t: np.ndarray, p: _Spectrum, damping: float) -> np.ndarray:
        """Return S_De(T) [m] of eqs. 3.2.10-3.2.12 (``displacement_spectrum`` element-wise)."""
        te, tf = self.corners
        se = self.elastic(t, p, damping)
        d_g = 0.025 * p.ag_g * G * p.s * p.tc_s * p.td_s
        f0_eta = p.f0 * damping_factor(damping)
        middle = d_g * (f0_eta + (1.0 - f0_eta) * (t - te) / (tf - te))
        return np.select(
            [t <= te, t <= tf],
            [se * (t / (2.0 * math.pi)) ** 2, middle],
            np.broadcast_to(d_g, t.shape),
        )

    def floor(
        self, t: np.ndarray, p: _Spectrum, tk: np.ndarray, xi_k: float, psi: np.ndarray, xi: float
    ) -> np.ndarray:
        """Return S_eZ(T, xi, z) [m/s2] of [C7.2.5]-[C7.2.8] (``floor_spectral_acceleration``).

        ``tk`` the structure's period and ``psi`` its ``gamma z / H`` per row, ``xi_k`` its
        damping; ``xi`` the element's.
        """
        a_z = (
            self.elastic(tk, p, xi_k) * np.abs(psi) * math.sqrt(1.0 + 0.0004 * (100.0 * xi_k) ** 2)
        )
        amp = 1.1 * xi_k**-0.5 * damping_factor(xi)
        rise = np.clip(1.0 - t / (FLOOR_A * tk), 0.0, None)
        fall = np.clip(t / (FLOOR_B * tk) - 1.0, 0.0, None)
        s_ez = np.select(
            [t < FLOOR_A * tk, t < FLOOR_B * tk],
            [amp * a_z / (1.0 + (amp - 1.0) * rise**1.6), np.broadcast_to(amp * a_z, t.shape)],
            amp * a_z / (1.0 + (amp - 1.0) * fall**1.2),
        )
        return np.where(t > tk, np.maximum(s_ez, self.elastic(t, p, xi)), s_ez)


@dataclass(frozen=True)
class _Samples:
    """The capacity curves and the structures beneath, one row per sample (shape (n, 1))."""

    a0: np.ndarray
    du: np.ndarray
    t0: np.ndarray
    t_slv: np.ndarray
    #: The structure beneath: its period [s] and ``gamma z / H``; None: on the ground.
    tk: np.ndarray | None
    psi: np.ndarray | None


def _rows(capacities: Sequence[KinematicCapacity], supports) -> _Samples:
    col = lambda v: np.asarray(v, dtype=float)[:, None]  # noqa: E731
    a0 = col([c.a0_star_m_s2 for c in capacities])
    du = col([c.du_star_m for c in capacities])
    t0 = col([c.t0_s for c in capacities])
    t_slv = col([c.t_slv_s for c in capacities])
    if supports is None:
        return _Samples(a0, du, t0, t_slv, None, None)
    tk = col([s.period_s for s in supports])
    psi = col([s.participation * float(s.level_m) / s.height_m for s in supports])
    return _Samples(a0, du, t0, t_slv, tk, psi)


def _activation(site: _Site, p: _Spectrum, s: _Samples) -> np.ndarray:
    """Return ``activation_demand`` of every row [m/s2] (T0 > 0, or rigidly held)."""
    free = s.t0 > 0.0
    t0 = np.where(free, s.t0, 1.0)
    ground = np.where(free, site.elastic(t0, p, SLD_DAMPING), p.ag_g * p.s * G)
    if s.tk is None:
        return ground[:, 0]
    floor_free = site.floor(t0, p, s.tk, _ELASTIC_STRUCTURE_DAMPING, s.psi, SLD_DAMPING)
    peak = site.elastic(s.tk, p, _ELASTIC_STRUCTURE_DAMPING) * np.abs(s.psi)
    peak = peak * math.sqrt(1.0 + 0.0004 * (100.0 * _ELASTIC_STRUCTURE_DAMPING) ** 2)
    return np.maximum(np.where(free, floor_free, peak), ground)[:, 0]


def _displacement(site: _Site, p: _Spectrum, s: _Samples) -> np.ndarray:
    """Return ``displacement_demand`` of every row [m]: the largest over [T0, T_SLV]."""
    start = np.minimum(s.t0, s.t_slv)
    step = (s.t_slv - start) / (_DEMAND_GRID - 1)
    periods = start + step * np.arange(_DEMAND_GRID)[None, :]
    periods[:, -1:] = s.t_slv
    ground = site.displacement(periods, p, SLV_MECHANISM_DAMPING).max(axis=1)
    if s.tk is None:
        return ground
    tk = s.tk * ULS_STRUCTURE_PERIOD_FACTOR
    corner = FLOOR_B * tk
    # The corner b T_k past T_SLV is added (a repeat of T_SLV otherwise: the same maximum).
    periods = np.concatenate([periods, np.where(s.t_slv > corner, corner, s.t_slv)], axis=1)
    s_ez = site.floor(periods, p, tk, ULS_STRUCTURE_DAMPING, s.psi, SLV_MECHANISM_DAMPING)
    return np.maximum((s_ez * (periods / (2.0 * math.pi)) ** 2).max(axis=1), ground)


def _passes(site: _Site, ln_tr: np.ndarray, s: _Samples) -> np.ndarray:
    """Return whether each row's non-linear check holds at its own ln T_R."""
    p = site.spectrum(ln_tr)
    holds = s.a0[:, 0] >= _activation(site, p, s)
    if np.all(holds):
        return holds
    return holds | (s.du[:, 0] >= _displacement(site, p, s))


def _take(s: _Samples, rows: np.ndarray) -> _Samples:
    pick = lambda v: None if v is None else v[rows]  # noqa: E731
    return _Samples(*(pick(getattr(s, k)) for k in _Samples.__dataclass_fields__))


def nonlinear_capacities(
    capacities: Sequence[KinematicCapacity],
    site: SiteConditions,
    supports: Sequence[ElevatedSupport] | None = None,
    *,
    extrapolate: bool = True,
) -> tuple[np.ndarray, np.ndarray]:
    """Return the non-linear kinematic check's capacity ag [g] and bound of many samples.

    ``kinematic_check(...).nonlinear`` of each sample (module docstring), with, when
    ``extrapolate``, a check holding at 2475 y continued beyond the table
    (``kinematic_beyond_table``), flagged
    :data:`~rockscreen.pipeline.risk.uncertainty.extrapolation.EXTRAPOLATED`.

    Parameters
    ----------
    capacities : sequence of KinematicCapacity
        Each sample's capacity curve
        (:func:`~rockscreen.pipeline.risk.checks.kinematic.kinematic_capacity`).
    site : SiteConditions
        The site.
    supports : sequence of ElevatedSupport, optional
        Each sample's structure beneath (the same length); None: every sample on the
        ground.
    extrapolate : bool
        Continue a check holding at 2475 y beyond the table.

    Returns
    -------
    ag_g : numpy.ndarray
        The capacity [g] per sample.
    bound : numpy.ndarray of str
        ``""``, ``"lower"``, ``"upper"`` or ``"extrapolated"`` per sample.
    """
    n = len(capacities)
    if supports is not None and len(supports) != n:
        raise RiskError(f"kinematic capacities: {n} capacities for {len(supports)} supports")
    s = _rows(capacities, supports)
    grid = _Site(site)
    low, high = grid.ln_tr[0], grid.ln_tr[-1]
    ln_c = np.empty(n)
    bound = np.full(n, "", dtype=object)
    holds_high = _passes(grid, np.full(n, high), s)
    fails_low = ~_passes(grid, np.full(n, low), s)
    ln_c[holds_high], bound[holds_high] = high, "lower"
    upper = fails_low & ~holds_high
    ln_c[upper], bound[upper] = low, "upper"
    inside = np.flatnonzero(~holds_high & ~upper)
    if inside.size:
        part = _take(s, inside)
        lo, hi = np.full(inside.size, low), np.full(inside.size, high)
        while hi[0] - lo[0] > BISECTION_RTOL:  # every row halves alike
            mid = 0.5 * (lo + hi)
            ok = _passes(grid, mid, part)
            lo, hi = np.where(ok, mid, lo), np.where(ok, hi, mid)
        ln_c[inside] = 0.5 * (lo + hi)
    tr = np.exp(ln_c)
    tr[bound == "lower"], tr[bound == "upper"] = RETURN_PERIODS_Y[-1], RETURN_PERIODS_Y[0]
    ag = np.array(
        [
            site.hazard(float(min(max(x, RETURN_PERIODS_Y[0]), RETURN_PERIODS_Y[-1]))).ag_g
            for x in tr
        ]
    )
    if extrapolate:
        _beyond_table(grid, s, ag, bound)
    return ag, bound


def _beyond_table(grid: _Site, s: _Samples, ag: np.ndarray, bound: np.ndarray) -> None:
    """Continue the bounded rows beyond the table in place (``kinematic_beyond_table``)."""
    for flag in CONTINUED_BOUNDS:
        rows = np.flatnonzero(bound == flag)
        if not rows.size:
            continue
        end = grid.ln_tr[-1] if flag == "lower" else grid.ln_tr[0]
        part = _take(s, rows)
        p = grid.spectrum(np.full(rows.size, end))
        ag_end = p.ag_g[:, 0]
        by_activation = ag_end * part.a0[:, 0] / _activation(grid, p, part)
        demand = _displacement(grid, p, part)
        du = part.du[:, 0]
        usable = (demand > 0.0) & (du > 0.0)
        by_displacement = np.where(usable, ag_end * du / np.where(usable, demand, 1.0), -np.inf)
        beyond = np.maximum(by_activation, by_displacement)
        finite = np.isfinite(beyond) & (beyond > 0.0)
        ag[rows[finite]] = beyond[finite]
        bound[rows[finite]] = EXTRAPOLATED
