"""The capacity of a code check on the site's hazard: T_R,C, a_C, I_S and f_a.

A code check compares a capacity with a demand read on the NTC 2018 elastic spectrum of the
site; the demand grows with the return period T_R of the action (ag, F0 and T*C of
Allegato A/B, :func:`rockscreen.pipeline.hazard.site_hazard`). The capacity of the check is
the return period ``T_R,C`` at which it holds at equality, found by bisection on ln T_R in
the tabulated 30-2475 years; its ag on rock is ``a_C``. Then, as in the Guidelines (DPCM
9/2/2011 §2.4; :mod:`rockscreen.pipeline.risk.measures.lv1`):

- ``I_S = T_R,C / T_R,SLV`` with ``T_R,SLV`` from V_N and the use class (NTC 2018 §2.4,
  §3.2.1);
- ``f_a = a_C / a_g,SLV`` (ag on rock).

A check that still holds at 2475 years gives lower bounds (``bound = "lower"``); one that
fails at 30 years gives upper bounds: the table defines no hazard beyond, and none is
invented. The bisection assumes the demand grows with T_R (true of ag; F0 and T*C of a
node may dip slightly, which the note of a non-monotone bracket would reveal).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.hazard import (
    RETURN_PERIODS_Y,
    TOWER_DEFAULTS,
    SiteHazard,
    elastic_spectrum,
    limit_state_return_period,
    site_hazard,
    spectrum_parameters,
)
from rockscreen.pipeline.hazard.grid import site_hazards
from rockscreen.pipeline.risk.checks.validation import check_number
from rockscreen.pipeline.verdict.messages import Message, message, render_all
from rockscreen.solver.constants import G

__all__ = ["SiteCapacity", "SiteConditions", "capacity_on_site", "elastic_spectra"]


def elastic_spectra(t, amplitude_g, eta, f0, tb_s, tc_s, td_s) -> np.ndarray:
    """Return Se(T) [m/s2] of NTC 2018 eq. 3.2.2 element-wise, each element its own action.

    :func:`~rockscreen.pipeline.hazard.spectrum.elastic_spectrum`'s four branches written on
    arrays (not there: that module's source is part of the record pools' cache key), for
    the searches that evaluate many (period, action) pairs at once:
    :meth:`SiteConditions.spectral_accelerations` and the kinematic checks of many samples
    (:mod:`rockscreen.pipeline.risk.uncertainty.kinematic_batch`).

    Parameters
    ----------
    t : numpy.ndarray
        Periods T [s], > 0.
    amplitude_g : numpy.ndarray
        ``ag S`` [g] of each action (ag on rock times the soil and topography factor).
    eta : float or numpy.ndarray
        Damping correction factor [-].
    f0 : numpy.ndarray
        F0 [-].
    tb_s, tc_s, td_s : numpy.ndarray
        The spectrum's corner periods [s].

    Returns
    -------
    numpy.ndarray
        Se [m/s2], shape of ``t`` broadcast with the parameters.
    """
    plateau = amplitude_g * eta * f0
    rising = plateau * (t / tb_s + (1.0 - t / tb_s) / (eta * f0))
    safe = np.where(t > 0, t, 1.0)
    shape = np.broadcast_shapes(np.shape(t), np.shape(plateau))
    se_g = np.select(
        [t < tb_s, t < tc_s, t < td_s],
        [rising, np.broadcast_to(plateau, shape), plateau * tc_s / safe],
        plateau * tc_s * td_s / safe**2,
    )
    return se_g * G


@dataclass(frozen=True)
class SiteConditions:
    """The site of a tower and the categories of its spectrum (defaults: tower defaults)."""

    #: Location, WGS84 [deg].
    lon_deg: float
    lat_deg: float
    #: Subsoil (A-E, NTC 2018 Tab. 3.2.II) and topography (T1-T4, Tab. 3.2.III).
    soil_class: str = TOWER_DEFAULTS["soil_class"]
    topography: str = TOWER_DEFAULTS["topography"]
    #: Nominal life V_N [y] and use class (NTC 2018 §2.4).
    nominal_life_y: float = TOWER_DEFAULTS["nominal_life_y"]
    use_class: str = TOWER_DEFAULTS["use_class"]
    #: Viscous damping ratio of the spectrum [-].
    damping: float = 0.05

    def __post_init__(self):
        check_number("lon_deg", self.lon_deg, low=-180.0, high=180.0, unit="deg")
        check_number("lat_deg", self.lat_deg, low=-90.0, high=90.0, unit="deg")
        check_number("nominal_life_y", self.nominal_life_y, low=0.0, low_open=True, unit="y")
        check_number("damping", self.damping, low=0.0, high=1.0, high_open=True)

    @classmethod
    def of(cls, site: Any) -> SiteConditions:
        """Return the conditions of an assessed tower's site; 5 % damping.

        ``site`` has ``lon_deg``, ``lat_deg``, ``soil_class``, ``topography``,
        ``nominal_life_y`` and ``use_class`` (an assessed tower's site).
        """
        return cls(
            lon_deg=site.lon_deg,
            lat_deg=site.lat_deg,
            soil_class=site.soil_class,
            topography=site.topography,
            nominal_life_y=site.nominal_life_y,
            use_class=site.use_class,
        )

    def hazard(self, return_period_y: float) -> SiteHazard:
        """Return ag, F0, T*C at a return period in [30, 2475] y (Allegato A)."""
        return site_hazard(self.lon_deg, self.lat_deg, return_period_y)

    def hazards(self, return_periods_y) -> list[SiteHazard]:
        """Return :meth:`hazard` at many return periods in [30, 2475] y, each bit for bit."""
        return site_hazards(self.lon_deg, self.lat_deg, return_periods_y)

    def soil_factor(self, site: SiteHazard) -> float:
        """Return S = S_S S_T at the site's hazard (NTC 2018 §3.2.3.2.1) [-]."""
        return spectrum_parameters(site, self.soil_class, self.topography, self.damping).S

    def spectral_acceleration(self, period_s: float, site: SiteHazard) -> float:
        """Return Se(T) of NTC 2018 eq. 3.2.2 [m/s2]."""
        se_g = elastic_spectrum(
            np.array([period_s]), site, self.soil_class, self.topography, self.damping
        )
        return float(se_g[0]) * G

    def spectral_accelerations(self, periods_s, sites: Sequence[SiteHazard]) -> np.ndarray:
        """Return :meth:`spectral_acceleration` of each period at its own action [m/s2].

        Element ``i`` is ``spectral_acceleration(periods_s[i], sites[i])`` bit for bit (a
        test checks): NTC 2018 eq. 3.2.2 (§3.2.3.2.1) with each action's parameters by
        :func:`~rockscreen.pipeline.hazard.spectrum.spectrum_parameters`, its four branches
        written as :func:`~rockscreen.pipeline.hazard.spectrum.elastic_spectrum` writes
        them, element-wise on arrays (not there: that module's source is part of the
        record pools' cache key). For a search evaluating many (period, return period)
        pairs at once (the screening risk's shaft capacity).

        Parameters
        ----------
        periods_s : array_like
            Periods T [s], > 0, shape (n,).
        sites : sequence of SiteHazard
            The action of each period, n of them.

        Returns
        -------
        numpy.ndarray
            Se [m/s2], shape (n,).
        """
        t = np.asarray(periods_s, dtype=float)
        if t.ndim != 1 or t.size != len(sites):
            raise RiskError(f"{t.size} periods for {len(sites)} actions: one action per period")
        if not np.all(np.isfinite(t) & (t > 0.0)):
            bad = t[~(np.isfinite(t) & (t > 0.0))].flat[0]
            check_number("period_s", float(bad), low=0.0, low_open=True, unit="s")
        kind = (self.soil_class, self.topography, self.damping)
        params = [spectrum_parameters(site, *kind) for site in sites]
        amplitude = np.array([site.ag_g * p.S for site, p in zip(sites, params, strict=True)])
        factor = np.array([site.F0 for site in sites], dtype=float)
        eta, tb, tc, td = (
            np.array([getattr(p, name) for p in params]) for name in ("eta", "TB_s", "TC_s", "TD_s")
        )
        return elastic_spectra(t, amplitude, eta, factor, tb, tc, td)

    def tr_slv_y(self) -> float:
        """Return T_R,SLV [y] for V_N and the use class (NTC 2018 §2.4.3, §3.2.1)."""
        return limit_state_return_period("SLV", self.nominal_life_y, self.use_class)


@dataclass(frozen=True)
class SiteCapacity:
    """The capacity of one check on the site's hazard."""

    #: T_R,C: return period at which the check holds at equality [y].
    return_period_y: float
    #: a_C: ag on rock at T_R,C [g].
    ag_g: float
    #: T_R,SLV [y] and ag on rock there [g].
    tr_slv_y: float
    ag_slv_g: float
    #: I_S = T_R,C / T_R,SLV and f_a = a_C / a_g,SLV [-].
    safety_index: float
    acceleration_factor: float
    #: Whether the check holds under the SLV action.
    passes_at_slv: bool
    #: ``""``, ``"lower"`` (holds at 2475 y) or ``"upper"`` (fails at 30 y).
    bound: str = ""
    #: Why the values are bounds, a clamped T_R,SLV (codes of
    #: :mod:`rockscreen.pipeline.verdict.catalogue.lv1_model`); empty otherwise.
    messages: tuple[Message, ...] = field(default=())

    @property
    def note(self) -> str:
        """Return :attr:`messages` in English, joined by ``"; "`` (``""`` for none)."""
        return render_all(self.messages)


def capacity_on_site(
    passes: Callable[[SiteHazard], bool],
    site: SiteConditions,
    *,
    rtol: float = 1.0e-6,
) -> SiteCapacity:
    """Return the return period at which a check holds at equality, and the indices.

    Parameters
    ----------
    passes : callable
        ``passes(hazard) -> bool``: whether the check holds under the action of a
        :class:`rockscreen.pipeline.hazard.SiteHazard`; must turn False as T_R grows.
    site : SiteConditions
        The site.
    rtol : float
        Relative tolerance on T_R, in (0, 0.01].

    Returns
    -------
    SiteCapacity
    """
    rtol = check_number("rtol", rtol, low=0.0, high=0.01, low_open=True)
    low, high = float(RETURN_PERIODS_Y[0]), float(RETURN_PERIODS_Y[-1])
    tr_slv = site.tr_slv_y()
    slv = site.hazard(min(max(tr_slv, low), high))
    passes_slv = bool(passes(slv))
    bound, notes = "", []
    if passes(site.hazard(high)):
        tr_c, bound = high, "lower"
        notes.append(message("capacity.holds_longest", tr=high))
    elif not passes(site.hazard(low)):
        tr_c, bound = low, "upper"
        notes.append(message("capacity.fails_shortest", tr=low))
    else:
        lo, hi = math.log(low), math.log(high)
        while hi - lo > rtol:
            mid = 0.5 * (lo + hi)
            if passes(site.hazard(math.exp(mid))):
                lo = mid
            else:
                hi = mid
        tr_c = math.exp(0.5 * (lo + hi))
    ag_c = site.hazard(tr_c).ag_g
    if not low <= tr_slv <= high:
        notes.append(message("capacity.slv_clamped", tr=tr_slv))
    return SiteCapacity(
        return_period_y=tr_c,
        ag_g=ag_c,
        tr_slv_y=tr_slv,
        ag_slv_g=slv.ag_g,
        safety_index=tr_c / tr_slv,
        acceleration_factor=ag_c / slv.ag_g,
        passes_at_slv=passes_slv,
        bound=bound,
        messages=tuple(notes),
    )
