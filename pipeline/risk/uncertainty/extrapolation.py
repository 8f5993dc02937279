"""Best-estimate capacities beyond the NTC 2018 table (the screening risk only).

The NTC 2018 hazard is tabulated from T_R = 30 to 2475 y (Allegato B). A check that
holds at 2475 y has, for the code, a capacity of *at least* ag(2475): a lower bound
(:func:`~rockscreen.pipeline.risk.checks.site_capacity.capacity_on_site`). The code's
checks keep that bound. The screening risk needs a value to rank by, so here the demand is
continued beyond the table **with the spectral shape held at the table's end**: F0, T*C,
the soil factor S (S_S x S_T), T_D and, for an elevated mechanism, the floor amplification
as at 2475 y (at 30 y below the table). The elastic spectrum of NTC 2018 §3.2.3.2.1 (eq.
3.2.2) is then ``S_e(T) = ag S eta F0 f(T / T_B, T / T_C, T / T_D)``: linear in ag, and so
are the activation and displacement demands and the floor spectrum of the Circolare 2019
§C7.2.3 (maxima of terms linear in ``ag S``). A check of capacity ``C`` against a demand
``D(ag)`` then holds at equality at

    ag_C = ag_end x C / D(T1; T_R,end)

(``T_R,end`` = 2475 y above the table, 30 y below it). The kinematic check of the
Circolare 2019 §C8.7.1.2.1.8 holds while the activation or the displacement demand is met,
so its ``ag_C`` is the larger of the two ratios' values.

Holding S: ``S_S`` decreases with ``ag F0`` (NTC 2018 Table 3.2.IV, e.g. class B
``1.40 - 0.40 F0 ag / g`` within [1.00, 1.20]), so above 2475 y the true S is at most the
held one: the extrapolated demand is too high and the capacity too low, **conservative**
(P too high). Below 30 y the true S is at least the held one: the demand too low and the
capacity too high, **unconservative**. ``T_D = 4 ag/g + 1.6`` (eq. 3.2.7) grows with ag:
held, the displacement branch beyond it is low above the table (unconservative there).
``docs/uncertainty.md`` "Capacities beyond the
table".
"""

from __future__ import annotations

import numpy as np

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.hazard import RETURN_PERIODS_Y
from rockscreen.pipeline.risk.checks.kinematic import Mechanism, kinematic_capacity
from rockscreen.pipeline.risk.checks.kinematic_demand import (
    ElevatedSupport,
    activation_demand,
    displacement_demand,
)
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.checks.tower_lv1 import lv1_demand, lv1_demands

__all__ = [
    "CONTINUED_BOUNDS",
    "EXTRAPOLATED",
    "end_return_period_y",
    "kinematic_beyond_table",
    "linear_beyond_table",
    "spectral_beyond_table",
]

#: The flag of a capacity continued beyond the table (a value, not a bound).
EXTRAPOLATED = "extrapolated"
#: The bounds continued beyond the table: only ``"lower"`` (a check holding at 2475 y).
#: A check failing at 30 y keeps its bound (``"upper"``: P at least): below the table the
#: held soil factor makes the continued capacity unconservative, and the hazard curve's
#: power-law extrapolation below 30 y has no ceiling on lambda (the mean P of the tall
#: towers whose shaft crushes reached 1 when it was continued there).
CONTINUED_BOUNDS = ("lower",)


def end_return_period_y(bound: str) -> float:
    """Return the table's end a bound sits at [y]: 2475 for ``"lower"``, 30 for ``"upper"``."""
    if bound == "lower":
        return float(RETURN_PERIODS_Y[-1])
    if bound == "upper":
        return float(RETURN_PERIODS_Y[0])
    raise RiskError(f"beyond the table: bound {bound!r}; allowed: 'lower', 'upper'")


def linear_beyond_table(ag_end_g: float, capacity: float, demand_end: float) -> float:
    """Return ``ag_end x capacity / demand_end`` [g]: the crossing of a demand linear in ag.

    NaN for a capacity of 0 (the shaft crushing under its own weight: no ag holds it; the
    caller keeps the code's bound).

    Parameters
    ----------
    ag_end_g : float
        ag on rock at the table's end [g].
    capacity : float
        The check's capacity (any unit, the demand's).
    demand_end : float
        The demand at the table's end, shape held (same unit), > 0.
    """
    if capacity == 0.0:
        return float("nan")
    if not (np.isfinite(demand_end) and demand_end > 0.0 and capacity > 0.0):
        raise RiskError(
            f"beyond the table: capacity {capacity!r} and demand {demand_end!r} must be > 0"
        )
    return float(ag_end_g) * float(capacity) / float(demand_end)


def spectral_beyond_table(
    se_slv_m_s2: np.ndarray,
    period_s: np.ndarray,
    bound: np.ndarray,
    site: SiteConditions,
    support: ElevatedSupport | None = None,
) -> np.ndarray:
    """Return the LV1 capacity ag [g] of bounded samples, continued beyond the table.

    Parameters
    ----------
    se_slv_m_s2, period_s : ndarray
        S_e,SLV [m/s2] and T1 [s] of each sample.
    bound : ndarray of str
        ``"lower"`` or ``"upper"`` per sample (the bound of
        :func:`~rockscreen.pipeline.risk.uncertainty.shaft_hazard.capacity_from_spectral`).
    site : SiteConditions
        The site.
    support : ElevatedSupport, optional
        The structure beneath the tower (:func:`lv1_demand`); None: on the ground.

    Returns
    -------
    ndarray
        ``ag_end S_e,SLV / lv1_demand(T1; T_R,end)`` [g] per sample (NaN where
        ``S_e,SLV = 0``, :func:`linear_beyond_table`, and for a bound not in
        :data:`CONTINUED_BOUNDS`: the code's bound stays).
    """
    se = np.asarray(se_slv_m_s2, dtype=float)
    t1 = np.asarray(period_s, dtype=float)
    flags = np.asarray(bound, dtype=object)
    out = np.full(se.size, np.nan)  # the code's bound stays (CONTINUED_BOUNDS)
    for flag in dict.fromkeys(str(f) for f in flags):
        if flag not in CONTINUED_BOUNDS:
            continue
        at = np.flatnonzero(flags == flag)
        hazard = site.hazard(end_return_period_y(flag))
        if support is None:
            # On the ground the array form is lv1_demand's at each period, bit for bit.
            demand = lv1_demands(t1[at], hazard, site).tolist()
        else:
            demand = [lv1_demand(float(t1[i]), hazard, site, support) for i in at.tolist()]
        out[at] = [
            linear_beyond_table(hazard.ag_g, capacity, end)
            for capacity, end in zip(se[at].tolist(), demand, strict=True)
        ]
    return out


def kinematic_beyond_table(
    mechanism: Mechanism,
    site: SiteConditions,
    bound: str,
    *,
    fc: float,
    support: ElevatedSupport | None = None,
) -> float:
    """Return the non-linear kinematic check's capacity ag [g] beyond the table.

    The check (Circolare 2019 §C8.7.1.2.1.8, as
    :func:`~rockscreen.pipeline.risk.checks.kinematic.kinematic_check`) holds while
    ``a0* >= activation demand`` or ``d_u* >= displacement demand``; both demands linear in
    ag with the shape held, it holds at equality at ``ag_end max(a0* / D_a, d_u* / D_d)``.

    Parameters
    ----------
    mechanism : Mechanism
        The mechanism.
    site : SiteConditions
        The site.
    bound : {"lower", "upper"}
        The code's bound of the check (which end of the table).
    fc : float
        Confidence factor [-] (as the check's).
    support : ElevatedSupport, optional
        The structure beneath an elevated mechanism.

    Returns
    -------
    float
        NaN when neither capacity is > 0 (:func:`linear_beyond_table`), or for a bound
        not in :data:`CONTINUED_BOUNDS` (the code's bound stays).
    """
    if bound not in CONTINUED_BOUNDS:
        return float("nan")
    hazard = site.hazard(end_return_period_y(bound))
    capacity = kinematic_capacity(mechanism, fc)
    t0 = capacity.t0_s
    activation = activation_demand(t0, hazard, site, support)
    displacement = displacement_demand(t0, capacity.t_slv_s, hazard, site, support)
    values = [linear_beyond_table(hazard.ag_g, capacity.a0_star_m_s2, activation)]
    if displacement > 0.0 and capacity.du_star_m > 0.0:
        values.append(linear_beyond_table(hazard.ag_g, capacity.du_star_m, displacement))
    finite = [v for v in values if np.isfinite(v)]
    return max(finite) if finite else float("nan")
