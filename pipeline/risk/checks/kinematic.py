"""Kinematic analysis of a rigid overturning mechanism (Circolare 2019 §C8.7.1.2.1).

The Circolare 21/1/2019 n. 7, §C8.7.1.2.1 (PDF pp. 273-277; docs/code_checks.md §1 gives
every formula with its number). A mechanism is a rigid body (blocks and point masses)
rotating about a horizontal hinge at the toe of its base. With ``a_i`` the horizontal
distance of weight ``P_i`` from the hinge (inward) and ``y_i`` its height above it, a virtual
rotation ``theta`` moves it by ``delta_x,i = y_i theta`` and ``delta_y,i = a_i theta``:

- load multiplier of activation ([C8.7.1.1]): ``alpha0 = sum P a / sum P y``;
- participating mass fraction ([C8.7.1.5]) ``e* = (sum P delta_x)^2 / (sum P sum P
  delta_x^2)`` (a uniform block: 0.75), and the capacity curve of the equivalent oscillator
  ``a = alpha g / (e* FC)``, ``d = d_k sum P delta_x^2 / (delta_x,k sum P delta_x)``
  ([C8.7.1.3], [C8.7.1.4]): ``a0 = alpha0 g / (e* FC)`` at activation, zero at ``d0``,
  linear between (the control point is the centroid of the weights);
- an element free to vibrate (a tower standing free, a belfry, a bell gable: "porzioni
  svettanti") has an elastic branch ``a = 4 pi^2 d / T0^2`` ([C8.7.1.6]) before activation,
  ``T0`` its own period ([C8.7.1.7] for a solid cantilever: ``T0 = 6.2 lambda L sqrt(w / (E
  g))``);
- SLD, activation ([C8.7.1.8], [C8.7.1.9]): ``a0`` against the peak acceleration at the
  mechanism's level (rigidly held mechanisms: ``ag S`` on the ground, ``a_Z(z)`` [C7.2.8] at
  height) or, free to vibrate, the spectrum there at ``T0`` (``Se(T0)``, ``S_eZ(T0, z)``
  [C7.2.5]), damping 5 %;
- linear SLV check (§C8.7.1.2.1.7): ``a_g,SLV = q a_g,SLD`` with ``q = 2``: the check holds
  while ``q a0`` reaches the activation demand;
- non-linear SLV check (§C8.7.1.2.1.6, §C8.7.1.2.1.8): ``d_SLV = 0.4 d0``, ``T_SLV = 1.68 pi
  sqrt(d_SLV / a(d_SLV))`` ([C8.7.1.10]); the demand is the largest displacement spectrum
  over ``[T0, T_SLV]`` at 8 % damping (NTC 2018 eq. 3.2.10-3.2.12 on the ground; the floor
  spectrum times ``T^2 / 4 pi^2`` at height, [C8.7.1.12], with the structure lengthened and
  damped, §C8.7.1.2.1.4); where that gives less than the SLD's ``a_g``, the SLD's is taken.

The demands (the structure beneath, the spectra at the mechanism's level) are in
:mod:`rockscreen.pipeline.risk.checks.kinematic_demand`; at height rockscreen never
takes a demand below the same mechanism's on the ground (the first-mode floor spectrum
vanishes at the foundation; docs/code_checks.md §1.4).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.hazard import SiteHazard
from rockscreen.pipeline.risk.checks.kinematic_demand import (
    LOCAL_MECHANISM_Q,
    ULS_STRUCTURE_DAMPING,
    ULS_STRUCTURE_PERIOD_FACTOR,
    ElevatedSupport,
    activation_demand,
    displacement_demand,
)
from rockscreen.pipeline.risk.checks.site_capacity import (
    SiteCapacity,
    SiteConditions,
    capacity_on_site,
)
from rockscreen.pipeline.risk.checks.validation import check_number
from rockscreen.solver.constants import G

__all__ = [
    "CANTILEVER_KAPPA",
    "CRACKED_STIFFNESS_RATIO",
    "SLV_DISPLACEMENT_RATIO",
    "SLV_PERIOD_FACTOR",
    "KinematicCapacity",
    "KinematicCheck",
    "Mechanism",
    "PointMass",
    "RigidBlock",
    "cantilever_period",
    "kinematic_capacity",
    "kinematic_check",
    "nonlinear_capacity_on_site",
]

#: d_SLV = 0.4 d0 (§C8.7.1.2.1.6; no ties or connections whose failure could come first).
SLV_DISPLACEMENT_RATIO = 0.4
#: T_SLV = 1.68 pi sqrt(d_SLV / a(d_SLV)) ([C8.7.1.10]).
SLV_PERIOD_FACTOR = 1.68
#: kappa of [C8.7.1.7] for a cantilever ("6,2 per elementi svettanti (mensola)").
CANTILEVER_KAPPA = 6.2
#: Cracked over uncracked stiffness of masonry (NTC 2018 §7.2.6: "può essere ridotta sino al
#: 50%"), for the modulus in [C8.7.1.7] ("un valore ridotto per ... condizioni fessurate").
CRACKED_STIFFNESS_RATIO = 0.5


def cantilever_period(
    length_m: float, thickness_m: float, unit_weight_n_m3: float, modulus_pa: float
) -> float:
    """Return ``T0 = kappa lambda L sqrt(w / (E g))`` of a solid cantilever ([C8.7.1.7]) [s].

    Parameters
    ----------
    length_m : float
        Free length L of the element [m], > 0.
    thickness_m : float
        Thickness t along the action [m], > 0 (slenderness ``lambda = L / t``).
    unit_weight_n_m3 : float
        Unit weight of the masonry w [N/m3], > 0.
    modulus_pa : float
        Young's modulus E [Pa], > 0 (pass the cracked value).

    Returns
    -------
    float
        T0 [s].
    """
    length = check_number("length_m", length_m, low=0.0, low_open=True, unit="m")
    t = check_number("thickness_m", thickness_m, low=0.0, low_open=True, unit="m")
    w = check_number("unit_weight_n_m3", unit_weight_n_m3, low=0.0, low_open=True, unit="N/m3")
    e = check_number("modulus_pa", modulus_pa, low=0.0, low_open=True, unit="Pa")
    return CANTILEVER_KAPPA * (length / t) * length * math.sqrt(w / (e * G))


@dataclass(frozen=True)
class RigidBlock:
    """A uniform rectangular block of a mechanism (in the plane of the seismic action)."""

    #: Mass [kg], > 0.
    mass_kg: float
    #: Width along the seismic action [m], > 0.
    width_m: float
    #: Height [m], > 0.
    height_m: float
    #: Height of the block's base above the hinge [m], >= 0.
    bottom_m: float = 0.0
    #: Horizontal distance of the centroid from the hinge, inward [m]; None: width/2.
    inset_m: float | None = None
    name: str = "block"

    def __post_init__(self):
        check_number(f"{self.name}.mass_kg", self.mass_kg, low=0.0, low_open=True, unit="kg")
        check_number(f"{self.name}.width_m", self.width_m, low=0.0, low_open=True, unit="m")
        check_number(f"{self.name}.height_m", self.height_m, low=0.0, low_open=True, unit="m")
        check_number(f"{self.name}.bottom_m", self.bottom_m, low=0.0, unit="m")
        if self.inset_m is None:
            object.__setattr__(self, "inset_m", 0.5 * float(self.width_m))
        check_number(f"{self.name}.inset_m", self.inset_m, low=0.0, unit="m")

    @property
    def centroid_height_m(self) -> float:
        """Return the height of the centroid above the hinge [m]."""
        return self.bottom_m + 0.5 * self.height_m

    @property
    def second_moment_kg_m2(self) -> float:
        """Return ``sum m y^2 = m (y_c^2 + h^2/12)`` about the hinge's level [kg m2]."""
        return self.mass_kg * (self.centroid_height_m**2 + self.height_m**2 / 12.0)


@dataclass(frozen=True)
class PointMass:
    """A concentrated mass of a mechanism (bells, roof, spire)."""

    #: Mass [kg], > 0.
    mass_kg: float
    #: Height above the hinge [m], >= 0.
    height_m: float
    #: Horizontal distance from the hinge, inward [m], >= 0.
    inset_m: float
    name: str = "mass"

    def __post_init__(self):
        check_number(f"{self.name}.mass_kg", self.mass_kg, low=0.0, low_open=True, unit="kg")
        check_number(f"{self.name}.height_m", self.height_m, low=0.0, unit="m")
        check_number(f"{self.name}.inset_m", self.inset_m, low=0.0, unit="m")


@dataclass(frozen=True)
class Mechanism:
    """A rigid overturning mechanism: blocks and point masses rotating about one hinge.

    ``elastic_period_s`` is the period ``T0`` of an element free to vibrate before the
    mechanism activates (Circolare 2019 §C8.7.1.2.1.3: parapets, "porzioni svettanti",
    pinnacles; a free-standing tower, its belfry, a bell gable): its capacity curve starts
    with the elastic branch of [C8.7.1.6] and its demands are read at ``T0``. None: a
    mechanism held rigidly until it activates.
    """

    name: str
    blocks: tuple[RigidBlock, ...]
    points: tuple[PointMass, ...] = ()
    elastic_period_s: float | None = None

    def __post_init__(self):
        object.__setattr__(self, "blocks", tuple(self.blocks))
        object.__setattr__(self, "points", tuple(self.points))
        if not self.blocks and not self.points:
            raise RiskError(f"mechanism {self.name!r} has no block and no mass")
        if self.sums()[2] <= 0.0:
            raise RiskError(f"mechanism {self.name!r}: every weight sits at the hinge's level")
        if self.elastic_period_s is not None:
            check_number(
                f"{self.name}.elastic_period_s",
                self.elastic_period_s,
                low=0.0,
                low_open=True,
                unit="s",
            )

    def sums(self) -> tuple[float, float, float, float]:
        """Return ``(sum m, sum m a, sum m y, sum m y^2)`` [kg, kg m, kg m, kg m2]."""
        m = sum(b.mass_kg for b in self.blocks) + sum(p.mass_kg for p in self.points)
        ma = sum(b.mass_kg * b.inset_m for b in self.blocks)
        ma += sum(p.mass_kg * p.inset_m for p in self.points)
        my = sum(b.mass_kg * b.centroid_height_m for b in self.blocks)
        my += sum(p.mass_kg * p.height_m for p in self.points)
        myy = sum(b.second_moment_kg_m2 for b in self.blocks)
        myy += sum(p.mass_kg * p.height_m**2 for p in self.points)
        return float(m), float(ma), float(my), float(myy)


@dataclass(frozen=True)
class KinematicCapacity:
    """The site-independent capacity of a mechanism (Circolare 2019 §C8.7.1.2.1.3-6)."""

    name: str
    #: Load multiplier of activation alpha0 [-].
    alpha0: float
    #: Participating mass M* [kg] and total mass [kg].
    participating_mass_kg: float
    total_mass_kg: float
    #: Fraction of participating mass e* [-].
    mass_ratio: float
    #: Confidence factor used [-].
    fc: float
    #: Spectral acceleration of activation a0 = alpha0 g / (e* FC) [m/s2].
    a0_star_m_s2: float
    #: Rotation at which alpha = 0 [rad]; control point displacement there [m].
    theta0_rad: float
    dk0_m: float
    #: Spectral displacement at which a = 0, d0 [m].
    d0_star_m: float
    #: d_SLV = 0.4 d0 [m] and a(d_SLV) [m/s2].
    du_star_m: float
    au_star_m_s2: float
    #: T_SLV = 1.68 pi sqrt(d_SLV / a(d_SLV)) [s].
    t_slv_s: float
    #: T0 of an element free to vibrate [s]; 0 for a rigidly held mechanism.
    t0_s: float = 0.0

    @property
    def a0_star_g(self) -> float:
        """Return a0 [g]."""
        return self.a0_star_m_s2 / G

    def spectral_acceleration(self, d_star_m: float) -> float:
        """Return the capacity curve a(d) [m/s2], >= 0 (the elastic branch first, if any)."""
        d = float(d_star_m)
        a = max(self.a0_star_m_s2 * (1.0 - d / self.d0_star_m), 0.0)
        if self.t0_s > 0.0:
            a = min(a, (2.0 * math.pi / self.t0_s) ** 2 * d)
        return a


def kinematic_capacity(mechanism: Mechanism, fc: float = 1.35) -> KinematicCapacity:
    """Return alpha0, e*, a0, d0, d_SLV, a(d_SLV), T_SLV of a mechanism (module docstring).

    Parameters
    ----------
    mechanism : Mechanism
        The mechanism.
    fc : float
        Confidence factor FC [-], in [1, 2] (1.35 for LC1, Circolare 2019 §C8.5.4).

    Returns
    -------
    KinematicCapacity
    """
    fc = check_number("fc", fc, low=1.0, high=2.0)
    m, ma, my, myy = mechanism.sums()
    alpha0 = ma / my
    m_star = my**2 / myy
    e_star = m_star / m
    a0 = alpha0 * G / (e_star * fc)
    theta0 = math.atan2(ma, my)
    # Control point: the centroid of the weights, (a_G, y_G) = (sum m a, sum m y) / sum m.
    a_g, y_g = ma / m, my / m
    dk0 = a_g * (1.0 - math.cos(theta0)) + y_g * math.sin(theta0)
    # d = d_k sum m dx^2 / (dx_k sum m dx), dx = y theta: d = d_k myy / (y_G my).
    d0 = dk0 * myy / (y_g * my)
    t0 = float(mechanism.elastic_period_s or 0.0)
    du = SLV_DISPLACEMENT_RATIO * d0
    capacity = KinematicCapacity(
        name=mechanism.name,
        alpha0=alpha0,
        participating_mass_kg=m_star,
        total_mass_kg=m,
        mass_ratio=e_star,
        fc=fc,
        a0_star_m_s2=a0,
        theta0_rad=theta0,
        dk0_m=dk0,
        d0_star_m=d0,
        du_star_m=du,
        au_star_m_s2=math.nan,
        t_slv_s=math.nan,
        t0_s=t0,
    )
    au = capacity.spectral_acceleration(du)
    return KinematicCapacity(
        **{
            **capacity.__dict__,
            "au_star_m_s2": au,
            "t_slv_s": SLV_PERIOD_FACTOR * math.pi * math.sqrt(du / au),
        }
    )


@dataclass(frozen=True)
class KinematicCheck:
    """A mechanism's capacity and the capacity of its two SLV checks on the site's hazard."""

    capacity: KinematicCapacity
    #: Linear check (a_g,SLV = q a_g,SLD, §C8.7.1.2.1.7).
    linear: SiteCapacity
    #: Non-linear check (d_SLV against the displacement demand, §C8.7.1.2.1.8).
    nonlinear: SiteCapacity
    #: ``"ground"`` or ``"floor spectrum"``.
    demand_rule: str
    q: float
    #: What was assumed, one sentence each.
    assumptions: tuple[str, ...] = field(default=())


def _nonlinear_passes(
    capacity: KinematicCapacity, site: SiteConditions, support: ElevatedSupport | None
) -> Callable[[SiteHazard], bool]:
    """Return whether the non-linear check holds under an action (§C8.7.1.2.1.8).

    It holds where the mechanism does not activate, else where ``d_u*`` covers the
    displacement demand.
    """
    t0 = capacity.t0_s

    def nonlinear_passes(hazard: SiteHazard) -> bool:
        if capacity.a0_star_m_s2 >= activation_demand(t0, hazard, site, support):
            return True
        demand = displacement_demand(t0, capacity.t_slv_s, hazard, site, support)
        return capacity.du_star_m >= demand

    return nonlinear_passes


def nonlinear_capacity_on_site(
    mechanism: Mechanism,
    site: SiteConditions,
    *,
    fc: float = 1.35,
    support: ElevatedSupport | None = None,
) -> SiteCapacity:
    """Return the non-linear kinematic check's capacity alone (Circolare 2019 §C8.7.1.2.1.8).

    ``kinematic_check(mechanism, site, fc=fc, support=support).nonlinear`` without the
    linear check's search: for a caller that reads only the non-linear check (the
    screening risk's best estimate,
    :func:`rockscreen.pipeline.risk.uncertainty.kinematic.kinematic_capacities`).

    Parameters
    ----------
    mechanism : Mechanism
        The mechanism.
    site : SiteConditions
        The site.
    fc : float
        Confidence factor [-].
    support : ElevatedSupport, optional
        The structure beneath an elevated mechanism; None at ground level.

    Returns
    -------
    SiteCapacity
    """
    capacity = kinematic_capacity(mechanism, fc)
    return capacity_on_site(_nonlinear_passes(capacity, site, support), site)


def kinematic_check(
    mechanism: Mechanism,
    site: SiteConditions,
    *,
    fc: float = 1.35,
    support: ElevatedSupport | None = None,
    q: float = LOCAL_MECHANISM_Q,
) -> KinematicCheck:
    """Return the linear and non-linear kinematic SLV checks of a mechanism at a site.

    Each check's capacity is the return period at which it holds at equality
    (:func:`rockscreen.pipeline.risk.checks.site_capacity.capacity_on_site`), with its ag
    on rock (``a_SLV,kin``), I_S and f_a. The non-linear check holds wherever the
    mechanism does not activate (§C8.7.1.2.1.8: ``a_g,SLV`` is never below ``a_g,SLD``).

    Parameters
    ----------
    mechanism : Mechanism
        The mechanism (with ``elastic_period_s`` when free to vibrate).
    site : SiteConditions
        The site.
    fc : float
        Confidence factor [-].
    support : ElevatedSupport, optional
        The structure beneath an elevated mechanism; None at ground level.
    q : float
        Behaviour factor of the linear check [-].

    Returns
    -------
    KinematicCheck
    """
    capacity = kinematic_capacity(mechanism, fc)
    q = check_number("q", q, low=1.0, high=4.0)
    t0 = capacity.t0_s

    def linear_passes(hazard: SiteHazard) -> bool:
        return q * capacity.a0_star_m_s2 >= activation_demand(t0, hazard, site, support)

    assumptions = [
        "rigid blocks, no sliding, no tensile strength, infinite compressive strength at the hinge",
        "capacity curve linear from alpha0 to zero at the control displacement d0",
    ]
    if t0 > 0.0:
        assumptions.append(f"free to vibrate: elastic branch and demand at T0 = {t0:.3g} s")
    if support is not None:
        assumptions.append(
            "floor spectrum of the Circolare 2019 §C7.2.3 (first mode); at the SLV the "
            f"structure's period x{ULS_STRUCTURE_PERIOD_FACTOR:g} and damping "
            f"{100 * ULS_STRUCTURE_DAMPING:g} % (§C8.7.1.2.1.4)"
        )
    return KinematicCheck(
        capacity=capacity,
        linear=capacity_on_site(linear_passes, site),
        nonlinear=capacity_on_site(_nonlinear_passes(capacity, site, support), site),
        demand_rule="ground" if support is None else "floor spectrum",
        q=float(q),
        assumptions=tuple(assumptions),
    )
