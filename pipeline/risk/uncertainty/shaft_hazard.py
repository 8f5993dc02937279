"""The capacity of a shaft on the site's hazard: ``a_SLV`` of many (S_e,SLV, T1) pairs at once.

What :func:`~rockscreen.pipeline.risk.checks.site_capacity.capacity_on_site` finds by
bisection for one check, for every sample of
:func:`~rockscreen.pipeline.risk.uncertainty.shaft.shaft_capacity` at once: the demand of
:func:`~rockscreen.pipeline.risk.checks.tower_lv1.lv1_demand` on the site's NTC 2018
hazard tabulated on a grid of :data:`GRID_POINTS` return periods, then each sample's
crossing of its ``S_e,SLV`` refined to :data:`RTOL_LN_TR` in ln T_R by false position on the
same functions. ``docs/uncertainty.md``.
"""

from __future__ import annotations

import math

import numpy as np

from rockscreen.pipeline.hazard import RETURN_PERIODS_Y
from rockscreen.pipeline.risk.checks.kinematic_demand import ElevatedSupport
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.checks.tower_lv1 import lv1_demand, lv1_demands

__all__ = ["GRID_POINTS", "RTOL_LN_TR", "capacity_from_spectral"]

#: Return periods of the demand's grid, log-spaced over the table's 30-2475 y.
GRID_POINTS = 161
#: Tolerance of each sample's crossing: the bracket's width in ln T_R, or the demand within
#: this fraction of S_e,SLV (about twice it in ln T_R: the demand grows as T_R^0.3-0.6).
RTOL_LN_TR = 1.0e-7


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
    hazards = site.hazards([_tr(x) for x in ln_tr.tolist()])
    return ln_tr, np.array([lv1_demands(periods, h, site, support) for h in hazards])


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
        tested against (``tests/pipeline/risk/uncertainty/test_shaft_floor.py``). On the
        ground, True also refines all the pairs at once (the same steps and demand, every
        pair's root bit for bit, ``tests/pipeline/risk/uncertainty/test_shaft.py``); on a
        structure, and with False, the refinement calls :func:`lv1_demand` per pair.

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
    lower, upper = ~fails[-1], fails[0] & fails[-1]
    out_tr[lower], bound[lower] = _tr(ln_tr[-1]), "lower"
    out_tr[upper], bound[upper] = _tr(ln_tr[0]), "upper"
    inside = np.flatnonzero(~lower & ~upper)
    if batch and support is None and inside.size:
        j = np.argmax(fails[:, inside], axis=0)
        cap = pairs[inside, 0]
        roots = _false_positions(
            pairs[inside, 1],
            cap,
            site,
            (ln_tr[j - 1], demand[j - 1, inside] - cap, ln_tr[j], demand[j, inside] - cap),
        )
        out_tr[inside] = [_tr(x) for x in roots.tolist()]
        inside = inside[:0]
    for k in inside.tolist():
        cap, t = pairs[k]
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
    ends, at = np.unique(out_tr, return_inverse=True)
    ag = np.array([h.ag_g for h in site.hazards(ends.tolist())])[at.reshape(-1)]
    return ag[inverse], out_tr[inverse], bound[inverse]


def _false_positions(
    period_s: np.ndarray,
    cap: np.ndarray,
    site: SiteConditions,
    bracket: tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray],
) -> np.ndarray:
    """Return :func:`_false_position`'s root of every pair on the ground, all at once.

    The same Illinois steps on every pair in lockstep (a pair leaves when it stops), the
    demand of all the pairs still searching at once
    (:meth:`~rockscreen.pipeline.risk.checks.site_capacity.SiteConditions.spectral_accelerations`,
    each element :func:`lv1_demand`'s bit for bit on the ground): every root is the scalar
    search's, bit for bit.

    Parameters
    ----------
    period_s, cap : ndarray
        T1 [s] and S_e,SLV [m/s2] of each pair.
    site : SiteConditions
        The site.
    bracket : tuple of ndarray
        ``(a, g(a), b, g(b))`` of each pair: ln T_R at both ends and the demand minus
        ``cap`` there, ``g(a) <= 0 < g(b)``.

    Returns
    -------
    ndarray
        ln T_R of each pair's crossing.
    """
    a, ga, b, gb = (np.array(v, dtype=float) for v in bracket)
    tol = cap * RTOL_LN_TR
    side = np.zeros(a.size, dtype=int)
    x = np.empty(a.size)
    searching = np.arange(a.size)
    for _ in range(100):
        k = searching
        with np.errstate(divide="ignore", invalid="ignore"):
            step = b[k] - gb[k] * (b[k] - a[k]) / (gb[k] - ga[k])
        x[k] = np.where(gb[k] != ga[k], step, 0.5 * (a[k] + b[k]))
        hazards = site.hazards([_tr(v) for v in x[k].tolist()])
        gx = site.spectral_accelerations(period_s[k], hazards) - cap[k]
        up = gx > 0.0
        ga[k[up & (side[k] == -1)]] *= 0.5
        gb[k[~up & (side[k] == 1)]] *= 0.5
        b[k[up]], gb[k[up]] = x[k[up]], gx[up]
        a[k[~up]], ga[k[~up]] = x[k[~up]], gx[~up]
        side[k] = np.where(up, -1, 1)
        searching = k[~((b[k] - a[k] < RTOL_LN_TR) | (np.abs(gx) <= tol[k]))]
        if not searching.size:
            break
    return np.where(b - a < RTOL_LN_TR, 0.5 * (a + b), x)


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
