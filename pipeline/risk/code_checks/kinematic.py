"""Kinematic analysis of a rigid overturning mechanism (Circolare 2019 §C8.7.1, formerly C8A.4).

A mechanism is a rigid body (blocks and point masses) rotating about a horizontal hinge at
the toe of its base. With ``a_i`` the horizontal distance of weight ``P_i`` from the hinge
(inward) and ``y_i`` its height above it, a virtual rotation ``theta`` moves it by
``delta_x,i = y_i theta`` horizontally and ``delta_y,i = a_i theta`` upward. Then (formulas
and sections in ``docs/code_checks.md``):

- load multiplier of activation, by virtual work: ``alpha0 = sum P a / sum P y``;
- participating mass ``M* = (sum P delta_x)^2 / (g sum P delta_x^2)`` and its fraction
  ``e* = g M* / sum P``; a uniform block has ``sum m y^2 = m (y_c^2 + h^2/12)``;
- spectral acceleration of activation ``a0* = alpha0 g / (e* FC)``;
- linear check: ``a0* >= ag S / q`` (ground), and for a mechanism at height ``z`` on a
  structure the floor demand (rules below), with ``q = 2``;
- non-linear: ``alpha(d_k) = alpha0 (1 - d_k / d_k0)``, ``d_k0`` the displacement of the
  control point (the centroid of the weights) when ``alpha = 0`` (the resultant over the
  hinge, ``tan theta0 = sum P a / sum P y``), ``d* = d_k sum P delta_x^2 / (delta_x,k sum P
  delta_x)``; ``du* = 0.4 d0*``, ``ds* = 0.4 du*``, ``as* = a0* (1 - ds*/d0*)``,
  ``Ts = 2 pi sqrt(ds*/as*)``; check ``du* >= Delta_d``, the displacement demand at ``Ts``.

Elevated mechanisms (``support`` given): ``elevated_rule="floor_spectrum"`` reads the floor
spectrum of Circolare 2019 §C7.2.3 eq. C7.2.11
(:func:`rockscreen.pipeline.motion.floor.ntc_floor_acceleration`) at the mechanism's base
``z`` on the structure of height ``H`` and period ``T1``: at ``T_a = 0`` (rigid mechanism)
for the linear check, at ``T_a = Ts`` (times ``(Ts/2 pi)^2``) for the non-linear one.
``elevated_rule="psi_gamma"`` uses the first-mode form of Circolare 2009 §C8A.4.2.3:
``Se(T1) psi(z) gamma`` (linear) and ``SDe(T1) psi gamma (Ts/T1)^2 / sqrt((1 - Ts/T1)^2 +
0.02 Ts/T1)`` for ``Ts < 1.5 T1``, ``SDe(Ts) psi gamma`` beyond (non-linear), with ``psi =
z/H`` and ``gamma = 3N/(2N+1)``. Either way the demand is never taken below the ground
demand (rockscreen's choice, stated in the doc).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.hazard import SiteHazard
from rockscreen.pipeline.motion.floor import linear_mode_participation, ntc_floor_acceleration
from rockscreen.pipeline.risk.code_checks.site_capacity import (
    SiteCapacity,
    SiteConditions,
    capacity_on_site,
)
from rockscreen.pipeline.risk.code_checks.validation import check_number
from rockscreen.solver.constants import G

__all__ = [
    "DISPLACEMENT_LIMIT_RATIO",
    "ELEVATED_RULES",
    "LOCAL_MECHANISM_Q",
    "SERVICE_DISPLACEMENT_RATIO",
    "ElevatedSupport",
    "KinematicCapacity",
    "KinematicCheck",
    "Mechanism",
    "PointMass",
    "RigidBlock",
    "displacement_demand",
    "kinematic_capacity",
    "kinematic_check",
    "linear_demand",
]

#: Behaviour factor of the linear check of local mechanisms (Circolare 2019 §C8.7.1;
#: Circolare 2009 §C8A.4.2.3: q = 2.0).
LOCAL_MECHANISM_Q = 2.0
#: du* = 0.4 d0* (Circolare 2009 §C8A.4.2.2; Circolare 2019 §C8.7.1).
DISPLACEMENT_LIMIT_RATIO = 0.4
#: ds* = 0.4 du*: the point of the capacity curve that defines the secant period Ts.
SERVICE_DISPLACEMENT_RATIO = 0.4
#: Ways of computing the demand on an elevated mechanism (module docstring).
ELEVATED_RULES = ("floor_spectrum", "psi_gamma")


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
    """A rigid overturning mechanism: blocks and point masses rotating about one hinge."""

    name: str
    blocks: tuple[RigidBlock, ...]
    points: tuple[PointMass, ...] = ()

    def __post_init__(self):
        object.__setattr__(self, "blocks", tuple(self.blocks))
        object.__setattr__(self, "points", tuple(self.points))
        if not self.blocks and not self.points:
            raise RiskError(f"mechanism {self.name!r} has no block and no mass")
        if self.sums()[2] <= 0.0:
            raise RiskError(f"mechanism {self.name!r}: every weight sits at the hinge's level")

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
class ElevatedSupport:
    """The structure beneath an elevated mechanism (the shaft under a belfry, a church)."""

    #: Height H of the structure from its foundation [m], > 0.
    height_m: float
    #: Its fundamental period T1 [s], > 0.
    period_s: float
    #: Height z of the mechanism's hinge above the foundation [m]; None: the top (z = H).
    level_m: float | None = None
    #: Number of storeys N for gamma = 3N/(2N+1) (``psi_gamma``); None: a cantilever (1.5).
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


@dataclass(frozen=True)
class KinematicCapacity:
    """The site-independent capacity of a mechanism."""

    name: str
    #: Load multiplier of activation alpha0 [-].
    alpha0: float
    #: Participating mass M* [kg] and total mass [kg].
    participating_mass_kg: float
    total_mass_kg: float
    #: Fraction of participating mass e* = g M* / sum P [-].
    mass_ratio: float
    #: Confidence factor used [-].
    fc: float
    #: Spectral acceleration of activation a0* [m/s2].
    a0_star_m_s2: float
    #: Rotation at which alpha = 0 [rad]; control point displacement there [m].
    theta0_rad: float
    dk0_m: float
    #: Spectral displacements d0*, du* = 0.4 d0*, ds* = 0.4 du* [m].
    d0_star_m: float
    du_star_m: float
    ds_star_m: float
    #: Spectral acceleration at ds*: as* = a0* (1 - ds*/d0*) [m/s2].
    as_star_m_s2: float
    #: Secant period Ts = 2 pi sqrt(ds*/as*) [s].
    ts_s: float

    @property
    def a0_star_g(self) -> float:
        """Return a0* [g]."""
        return self.a0_star_m_s2 / G

    def spectral_acceleration(self, d_star_m: float) -> float:
        """Return the capacity curve a*(d*) = a0* (1 - d*/d0*) [m/s2], >= 0."""
        return max(self.a0_star_m_s2 * (1.0 - float(d_star_m) / self.d0_star_m), 0.0)


def kinematic_capacity(mechanism: Mechanism, fc: float = 1.35) -> KinematicCapacity:
    """Return alpha0, M*, e*, a0*, d0*, du*, ds*, Ts of a mechanism (module docstring).

    Parameters
    ----------
    mechanism : Mechanism
        The mechanism.
    fc : float
        Confidence factor FC [-], in [1, 2] (1.35 for LC1, the Circolare's default when
        the knowledge is limited).

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
    # d* = d_k sum m dx^2 / (dx_k sum m dx), dx = y theta: d* = d_k myy / (y_G my).
    d0 = dk0 * myy / (y_g * my)
    du = DISPLACEMENT_LIMIT_RATIO * d0
    ds = SERVICE_DISPLACEMENT_RATIO * du
    as_ = a0 * (1.0 - ds / d0)
    return KinematicCapacity(
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
        ds_star_m=ds,
        as_star_m_s2=as_,
        ts_s=2.0 * math.pi * math.sqrt(ds / as_),
    )


def _check_rule(elevated_rule: str) -> str:
    if elevated_rule not in ELEVATED_RULES:
        raise RiskError(
            f"elevated_rule={elevated_rule!r} is not one of {', '.join(ELEVATED_RULES)}"
        )
    return elevated_rule


def linear_demand(
    hazard: SiteHazard,
    site: SiteConditions,
    support: ElevatedSupport | None = None,
    *,
    q: float = LOCAL_MECHANISM_Q,
    elevated_rule: str = "floor_spectrum",
) -> float:
    """Return the acceleration a0* must reach for the linear check [m/s2].

    Ground: ``ag S / q``. Elevated: the larger of that and the floor demand over ``q``
    (module docstring).

    Parameters
    ----------
    hazard : SiteHazard
        ag, F0, T*C of the action.
    site : SiteConditions
        Soil, topography and damping.
    support : ElevatedSupport, optional
        The structure beneath an elevated mechanism; None for a mechanism at ground level.
    q : float
        Behaviour factor, in [1, 4] (2 for local mechanisms).
    elevated_rule : {"floor_spectrum", "psi_gamma"}
        The elevated demand's rule.

    Returns
    -------
    float
        The demand [m/s2].
    """
    q = check_number("q", q, low=1.0, high=4.0)
    s = site.soil_factor(hazard)
    ground = hazard.ag_g * s * G / q
    if support is None:
        return ground
    if _check_rule(elevated_rule) == "floor_spectrum":
        floor_g = ntc_floor_acceleration(
            hazard.ag_g, s, support.level_m, support.height_m, 0.0, support.period_s
        )
        elevated = floor_g * G / q
    else:
        psi = support.level_m / support.height_m
        se = site.spectral_acceleration(support.period_s, hazard)
        elevated = se * psi * support.participation / q
    return max(ground, elevated)


def displacement_demand(
    ts_s: float,
    hazard: SiteHazard,
    site: SiteConditions,
    support: ElevatedSupport | None = None,
    *,
    elevated_rule: str = "floor_spectrum",
) -> float:
    """Return the displacement demand Delta_d at the secant period Ts [m].

    Ground: ``S_De(Ts)`` (NTC 2018 eq. 3.2.12). Elevated: the larger of that and the
    floor demand (module docstring).

    Parameters
    ----------
    ts_s : float
        Secant period Ts [s], > 0.
    hazard : SiteHazard
        ag, F0, T*C of the action.
    site : SiteConditions
        Soil, topography and damping.
    support : ElevatedSupport, optional
        The structure beneath an elevated mechanism.
    elevated_rule : {"floor_spectrum", "psi_gamma"}
        The elevated demand's rule.

    Returns
    -------
    float
        Delta_d [m].
    """
    ts = check_number("ts_s", ts_s, low=0.0, low_open=True, unit="s")
    ground = site.spectral_displacement(ts, hazard)
    if support is None:
        return ground
    t1 = support.period_s
    if _check_rule(elevated_rule) == "floor_spectrum":
        s = site.soil_factor(hazard)
        floor_g = ntc_floor_acceleration(hazard.ag_g, s, support.level_m, support.height_m, ts, t1)
        elevated = floor_g * G * (ts / (2.0 * math.pi)) ** 2
    else:
        psi_gamma = support.level_m / support.height_m * support.participation
        ratio = ts / t1
        if ratio < 1.5:
            sde_t1 = site.spectral_displacement(t1, hazard)
            elevated = sde_t1 * psi_gamma * ratio**2 / math.sqrt((1.0 - ratio) ** 2 + 0.02 * ratio)
        else:
            elevated = ground * psi_gamma
    return max(ground, elevated)


@dataclass(frozen=True)
class KinematicCheck:
    """A mechanism's capacity and the capacity of its two checks on the site's hazard."""

    capacity: KinematicCapacity
    #: Linear check (a0* against the acceleration demand).
    linear: SiteCapacity
    #: Non-linear check (du* against the displacement demand at Ts).
    nonlinear: SiteCapacity
    #: ``"ground"`` or the elevated rule used.
    demand_rule: str
    q: float
    #: What was assumed, one sentence each.
    assumptions: tuple[str, ...] = field(default=())


def kinematic_check(
    mechanism: Mechanism,
    site: SiteConditions,
    *,
    fc: float = 1.35,
    support: ElevatedSupport | None = None,
    q: float = LOCAL_MECHANISM_Q,
    elevated_rule: str = "floor_spectrum",
) -> KinematicCheck:
    """Return the linear and non-linear kinematic checks of a mechanism at a site.

    Each check's capacity is the return period at which it holds at equality
    (:func:`rockscreen.pipeline.risk.code_checks.site_capacity.capacity_on_site`), with its ag
    on rock (``a_SLV,kin``), I_S and f_a.

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
    q : float
        Behaviour factor of the linear check [-].
    elevated_rule : {"floor_spectrum", "psi_gamma"}
        The elevated demand's rule (ignored at ground level).

    Returns
    -------
    KinematicCheck
    """
    capacity = kinematic_capacity(mechanism, fc)
    rule = "ground" if support is None else _check_rule(elevated_rule)

    def linear_passes(hazard: SiteHazard) -> bool:
        demand = linear_demand(hazard, site, support, q=q, elevated_rule=elevated_rule)
        return capacity.a0_star_m_s2 >= demand

    def nonlinear_passes(hazard: SiteHazard) -> bool:
        demand = displacement_demand(
            capacity.ts_s, hazard, site, support, elevated_rule=elevated_rule
        )
        return capacity.du_star_m >= demand

    assumptions = [
        "rigid blocks, no sliding, no tensile strength, infinite compressive strength at the hinge",
        "capacity curve linear from alpha0 to zero at the control displacement d_k0",
    ]
    if support is not None:
        assumptions.append(
            f"elevated demand by the {rule} rule, never below the ground demand ag S"
        )
    return KinematicCheck(
        capacity=capacity,
        linear=capacity_on_site(linear_passes, site),
        nonlinear=capacity_on_site(nonlinear_passes, site),
        demand_rule=rule,
        q=float(q),
        assumptions=tuple(assumptions),
    )
