"""The seismic demand on a kinematic mechanism at its level (Circolare 2019 §C8.7.1.2.1).

The demand side of the kinematic checks of :mod:`rockscreen.pipeline.risk.checks.kinematic`
(docs/code_checks.md §1.3-1.4): the structure beneath an elevated mechanism
(:class:`ElevatedSupport`: a shaft under a belfry, a church under a tower or a gable) and
what the site's hazard asks of the mechanism there:

- SLD, activation ([C8.7.1.8], [C8.7.1.9]): the peak acceleration at the mechanism's level
  for one held rigidly (``ag S`` on the ground, ``a_Z(z)`` [C7.2.8] at height), the
  spectrum at its own period ``T0`` for one free to vibrate (``Se(T0)``, ``S_eZ(T0, z)``
  [C7.2.5]), damping 5 % (:func:`activation_demand`, :func:`elastic_spectral_demand`);
- linear SLV check (§C8.7.1.2.1.7): the activation demand over ``q = 2``
  (:func:`linear_demand`);
- non-linear SLV check (§C8.7.1.2.1.8): the largest displacement spectrum over
  ``[T0, T_SLV]`` at 8 %, on the ground NTC 2018 eqs. 3.2.10-3.2.12, at height the floor
  spectrum times ``T^2 / 4 pi^2`` ([C8.7.1.12]) with the structure lengthened and damped
  (§C8.7.1.2.1.4; :func:`displacement_demand`).

At height the demand is never taken below the same mechanism's on the ground (the
first-mode floor spectrum vanishes at the foundation; rockscreen's bound,
docs/code_checks.md §1.4).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from rockscreen.pipeline.hazard import SiteHazard, displacement_spectrum, elastic_spectrum
from rockscreen.pipeline.motion.floor import linear_mode_participation
from rockscreen.pipeline.risk.checks.floor_spectrum import (
    FLOOR_B,
    StructureState,
    floor_spectral_acceleration,
    peak_floor_acceleration,
)
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.checks.validation import check_number
from rockscreen.solver.constants import G

__all__ = [
    "LOCAL_MECHANISM_Q",
    "SLD_DAMPING",
    "SLV_MECHANISM_DAMPING",
    "ULS_STRUCTURE_DAMPING",
    "ULS_STRUCTURE_PERIOD_FACTOR",
    "ElevatedSupport",
    "activation_demand",
    "displacement_demand",
    "elastic_spectral_demand",
    "elastic_spectral_demands",
    "linear_demand",
]

#: Behaviour factor of the linear check (Circolare 2019 §C8.7.1.2.1.7: "si può assumere q=2").
LOCAL_MECHANISM_Q = 2.0
#: Damping of the mechanism at the SLV (§C8.7.1.2.1.8: "pari all'8% per lo SLV").
SLV_MECHANISM_DAMPING = 0.08
#: Damping of the activation (SLD) demand on an element free to vibrate ([C8.7.1.9]: 5 %).
SLD_DAMPING = 0.05
#: The structure beneath at the ultimate limit states (§C8.7.1.2.1.4: masonry buildings
#: lengthen their period by 50-100 % and reach 10-20 % damping): the lower ends.
ULS_STRUCTURE_PERIOD_FACTOR = 1.5
ULS_STRUCTURE_DAMPING = 0.10
#: Periods at which the displacement demand's maximum over [T0, T_SLV] is sought.
_DEMAND_GRID = 241


@dataclass(frozen=True)
class ElevatedSupport:
    """The structure beneath an elevated mechanism (the shaft under a belfry, a church)."""

    #: Height H of the structure from its foundation [m], > 0.
    height_m: float
    #: Its fundamental (elastic) period T1 [s], > 0.
    period_s: float
    #: Height z of the mechanism's hinge above the foundation [m]; None: the top (z = H).
    level_m: float | None = None
    #: Number of storeys N for gamma = 3N/(2N+1) ([C7.2.10]); None: a cantilever (1.5).
    n_storeys: int | None = None

    def __post_init__(self):
        h = check_number("support.height_m", self.height_m, low=0.0, low_open=True, unit="m")
        check_number("support.period_s", self.period_s, low=0.0, low_open=True, unit="s")
        if self.level_m is None:
            object.__setattr__(self, "level_m", h)
        check_number("support.level_m", self.level_m, low=0.0, high=h, unit="m")

    @property
    def participation(self) -> float:
        """Return gamma = 3N/(2N+1) (1.5 for a cantilever) [-]."""
        return linear_mode_participation(self.n_storeys)

    def state(self, ultimate: bool) -> StructureState:
        """Return the structure for the floor spectrum: elastic, or at the ultimate states.

        Elastic (SLD): ``T1`` and 5 %. Ultimate (SLV): ``T1`` times
        :data:`ULS_STRUCTURE_PERIOD_FACTOR` and :data:`ULS_STRUCTURE_DAMPING`
        (§C8.7.1.2.1.4).
        """
        return StructureState(
            height_m=self.height_m,
            level_m=float(self.level_m),
            period_s=self.period_s * (ULS_STRUCTURE_PERIOD_FACTOR if ultimate else 1.0),
            damping=ULS_STRUCTURE_DAMPING if ultimate else 0.05,
            n_storeys=self.n_storeys,
        )


def activation_demand(
    t0_s: float,
    hazard: SiteHazard,
    site: SiteConditions,
    support: ElevatedSupport | None = None,
) -> float:
    """Return the acceleration that activates the mechanism at the SLD [m/s2].

    Rigidly held (``t0_s = 0``): the peak acceleration at its level, ``ag S`` on the ground,
    ``a_Z(z)`` at height ([C8.7.1.8] with [C7.2.8]). Free to vibrate: the spectrum at
    ``T0`` and 5 %, ``Se(T0)`` on the ground, ``S_eZ(T0, z)`` at height ([C8.7.1.9] with
    [C7.2.5]). The structure beneath is elastic (``T1``, 5 %). At height the demand is
    never taken below the same mechanism's on the ground: the first-mode floor spectrum
    vanishes at the foundation (``psi(0) = 0``), where the floor moves with the ground
    (rockscreen's bound, docs/code_checks.md §1.4).

    Parameters
    ----------
    t0_s : float
        T0 of the element [s], >= 0 (0: rigidly held).
    hazard : SiteHazard
        ag, F0, T*C of the action.
    site : SiteConditions
        Soil and topography.
    support : ElevatedSupport, optional
        The structure beneath an elevated mechanism; None at ground level.

    Returns
    -------
    float
        The demand [m/s2].
    """
    t0 = check_number("t0_s", t0_s, low=0.0, unit="s")
    if t0 > 0.0:
        return elastic_spectral_demand(t0, hazard, site, support)
    ground = hazard.ag_g * site.soil_factor(hazard) * G
    if support is None:
        return ground
    floor = peak_floor_acceleration(hazard, site, support.state(ultimate=False))
    return max(floor, ground)


def elastic_spectral_demand(
    period_s: float,
    hazard: SiteHazard,
    site: SiteConditions,
    support: ElevatedSupport | None = None,
    *,
    damping: float = SLD_DAMPING,
) -> float:
    """Return the elastic spectral acceleration of an element of period T at its level [m/s2].

    On the ground: the NTC 2018 elastic spectrum ``Se(T, xi)`` (eq. 3.2.2). At height: the
    Circolare 2019 floor spectrum ``S_eZ(T, xi, z)`` ([C7.2.5]-[C7.2.10], §C7.2.3) of the
    structure beneath in its elastic state (``T_k = T1``, ``xi_k`` = 5 %:
    :meth:`ElevatedSupport.state` with ``ultimate=False``) at the support's level, never
    below ``Se(T, xi)`` (the first-mode floor spectrum vanishes at the foundation;
    rockscreen's bound, docs/code_checks.md §1.4). The activation demand of an element free
    to vibrate ([C8.7.1.9], :func:`activation_demand`) and the LV1 demand of a tower standing
    on a church (:func:`rockscreen.pipeline.risk.checks.tower_lv1.lv1_demand`).

    Parameters
    ----------
    period_s : float
        Period T of the element [s], > 0.
    hazard : SiteHazard
        ag, F0, T*C of the action.
    site : SiteConditions
        Soil and topography (its damping is not used: ``damping`` is the element's).
    support : ElevatedSupport, optional
        The structure beneath; None at ground level.
    damping : float
        Damping ratio of the element xi [-], in (0, 1); 5 % by default ([C8.7.1.9]).

    Returns
    -------
    float
        The demand [m/s2].
    """
    period = check_number("period_s", period_s, low=0.0, low_open=True, unit="s")
    damping = check_number("damping", damping, low=0.0, high=1.0, low_open=True, high_open=True)
    ground = _at(site, damping).spectral_acceleration(period, hazard)
    if support is None:
        return ground
    structure = support.state(ultimate=False)
    floor = float(floor_spectral_acceleration([period], hazard, site, structure, damping)[0])
    return max(floor, ground)


def elastic_spectral_demands(
    periods_s,
    hazard: SiteHazard,
    site: SiteConditions,
    support: ElevatedSupport | None = None,
    *,
    damping: float = SLD_DAMPING,
) -> np.ndarray:
    """Return :func:`elastic_spectral_demand` at many periods of one action at once [m/s2].

    The same formulas (NTC 2018 eq. 3.2.2 on the ground; the Circolare 2019 floor spectrum
    [C7.2.5]-[C7.2.10], §C7.2.3, of the structure in its elastic state, never below
    ``Se(T, xi)``) evaluated element-wise on an array of periods: each element equals the
    scalar function's value at that period to rounding (tested,
    ``tests/pipeline/risk/uncertainty/test_shaft_floor.py``). Used where one action is
    evaluated at many periods (the screening risk's demand grid,
    :func:`rockscreen.pipeline.risk.uncertainty.shaft_hazard.capacity_from_spectral`).

    Parameters
    ----------
    periods_s : array_like
        Periods T of the element [s], each > 0.
    hazard : SiteHazard
        ag, F0, T*C of the action.
    site : SiteConditions
        Soil and topography (its damping is not used: ``damping`` is the element's).
    support : ElevatedSupport, optional
        The structure beneath; None at ground level.
    damping : float
        Damping ratio of the element xi [-], in (0, 1); 5 % by default ([C8.7.1.9]).

    Returns
    -------
    numpy.ndarray
        The demand [m/s2], shape of ``periods_s``.
    """
    t = np.asarray(periods_s, dtype=float)
    if not np.all(np.isfinite(t) & (t > 0.0)):
        bad = t[~(np.isfinite(t) & (t > 0.0))].flat[0]
        check_number("period_s", float(bad), low=0.0, low_open=True, unit="s")
    damping = check_number("damping", damping, low=0.0, high=1.0, low_open=True, high_open=True)
    ground = elastic_spectrum(t, hazard, site.soil_class, site.topography, damping) * G
    if support is None:
        return ground
    structure = support.state(ultimate=False)
    floor = floor_spectral_acceleration(t, hazard, site, structure, damping)
    return np.maximum(floor, ground)


def _at(site: SiteConditions, damping: float) -> SiteConditions:
    return replace(site, damping=float(damping))


def linear_demand(
    t0_s: float,
    hazard: SiteHazard,
    site: SiteConditions,
    support: ElevatedSupport | None = None,
    *,
    q: float = LOCAL_MECHANISM_Q,
) -> float:
    """Return the acceleration a0 must reach for the linear SLV check [m/s2].

    ``a_g,SLV = q a_g,SLD`` (§C8.7.1.2.1.7): the check holds while ``a0`` reaches the
    :func:`activation_demand` divided by ``q``.

    Parameters
    ----------
    t0_s : float
        T0 of the element [s], >= 0 (0: rigidly held).
    hazard : SiteHazard
        ag, F0, T*C of the action.
    site : SiteConditions
        Soil and topography.
    support : ElevatedSupport, optional
        The structure beneath an elevated mechanism.
    q : float
        Behaviour factor, in [1, 4] (2 for local mechanisms).

    Returns
    -------
    float
        The demand [m/s2].
    """
    q = check_number("q", q, low=1.0, high=4.0)
    return activation_demand(t0_s, hazard, site, support) / q


def displacement_demand(
    t0_s: float,
    t_slv_s: float,
    hazard: SiteHazard,
    site: SiteConditions,
    support: ElevatedSupport | None = None,
) -> float:
    """Return the SLV displacement demand: the spectrum's largest over [T0, T_SLV] [m].

    §C8.7.1.2.1.8, damping 8 %. On the ground: NTC 2018 ``S_De(T)`` (eqs. 3.2.10-3.2.12).
    At height: ``S_eZ(T, z) T^2 / 4 pi^2`` on the structure at the ultimate states
    (:meth:`ElevatedSupport.state`), not less than its value at ``b T_k`` past it
    ([C8.7.1.12]), and never below the ground's (as :func:`activation_demand`).

    Parameters
    ----------
    t0_s : float
        T0 of the element [s], >= 0.
    t_slv_s : float
        T_SLV [s], > 0.
    hazard : SiteHazard
        ag, F0, T*C of the action.
    site : SiteConditions
        Soil and topography.
    support : ElevatedSupport, optional
        The structure beneath an elevated mechanism.

    Returns
    -------
    float
        The demand [m].
    """
    t0 = check_number("t0_s", t0_s, low=0.0, unit="s")
    t_slv = check_number("t_slv_s", t_slv_s, low=0.0, low_open=True, unit="s")
    periods = np.linspace(min(t0, t_slv), t_slv, _DEMAND_GRID)
    sde = displacement_spectrum(
        periods, hazard, site.soil_class, site.topography, SLV_MECHANISM_DAMPING
    )
    ground = float(np.max(sde))
    if support is None:
        return ground
    structure = support.state(ultimate=True)
    corner = FLOOR_B * structure.period_s
    if t_slv > corner:
        periods = np.append(periods, corner)
    s_ez = floor_spectral_acceleration(periods, hazard, site, structure, SLV_MECHANISM_DAMPING)
    return max(float(np.max(s_ez * (periods / (2.0 * math.pi)) ** 2)), ground)
