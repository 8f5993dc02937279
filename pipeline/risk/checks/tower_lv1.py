"""LV1 model of the Guidelines for towers and bell towers (DPCM 9/2/2011, §5.4.4).

The Guidelines' simplified mechanical model for structures developed mainly in height
(their §5.4.4, "Torri, campanili ed altre strutture a prevalente sviluppo verticale": the
number follows §5.4.2 palaces and §5.4.3 churches of the Guidelines' table of contents, seen
in a public copy; the formulas below are written as the authors know them and are **to be
verified** against the text, ``docs/code_checks.md`` §3):

- the shaft is a cantilever of hollow masonry sections; masses lumped at slices (each
  segment cut into ``slices_per_segment`` slices) and at point masses (belfry, bells, roof);
- seismic forces along the height proportional to ``W_k z_k`` (the linear first mode of
  NTC 2018 §7.3.3.2, eq. 7.3.7): ``F_k = F_h W_k z_k / sum W_j z_j``;
- flexural capacity of the section at height ``z_i`` under its own weight above it,
  ``N_i``, with a stress block ``0.85 f_d`` on the compressed side; for a block within the
  compressed wall this is ``M_u,i = (N_i / 2) (b_i - N_i / (0.85 f_d a_i))`` (``b_i`` the
  outer dimension along the action, ``a_i`` across it), which for a solid rectangle is
  ``(sigma_0 A b / 2)(1 - sigma_0 / (0.85 f_d))`` of NTC 2018 eq. 7.8.2; deeper blocks
  take in the webs (computed exactly);
- base shear of each section's failure ``F_SLV,i = M_u,i sum W_j z_j / sum_{z_k > z_i}
  W_k z_k (z_k - z_i)`` and ``F_SLV = min_i F_SLV,i``;
- spectral acceleration of the limit state ``S_e,SLV = q F_SLV / (e* M)``, ``e* = (sum m_k
  z_k)^2 / (M sum m_k z_k^2)`` the first-mode fraction of mass (0.75 for a uniform
  cantilever with a linear mode);
- period: given (measured), else ``T1 = 0.0187 H`` (:func:`tower_period_guidelines`:
  Faccio, Paolucci & Zanotti's law for masonry towers, as implemented by the open TURRIS
  code of Montabert et al. 2023; the same law as the belfry model's and the floor model's
  ``PERIOD_LAWS["faccio2010"]``, so one tower has one period in every check);
- ``a_SLV``: the ag on rock at which the demand at ``T1`` equals ``S_e,SLV`` on the site's
  hazard, ``T_SLV`` its return period, ``I_S = T_SLV / T_R,SLV``,
  ``f_a = a_SLV / a_g,SLV``. The demand (:func:`lv1_demand`) is the ground's elastic
  spectrum ``Se(T1)`` for a tower on the ground; for a tower standing on a church (or any
  structure beneath its springing, an
  :class:`~rockscreen.pipeline.risk.checks.kinematic_demand.ElevatedSupport`) it is the
  Circolare 2019 floor spectrum ``S_eZ(T1, z)`` of §C7.2.3 ([C7.2.5]-[C7.2.10]) at the
  springing's level, the structure elastic (``T_k`` its period, ``xi_k`` = 5 %), never
  below ``Se(T1)``: the demand the elevated kinematic checks use for an element free to
  vibrate (:func:`~rockscreen.pipeline.risk.checks.kinematic_demand.elastic_spectral_demand`).
"""

from __future__ import annotations

from dataclasses import dataclass

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.hazard import SiteHazard
from rockscreen.pipeline.motion.floor import building_period_from_height
from rockscreen.pipeline.risk.checks.kinematic import PointMass
from rockscreen.pipeline.risk.checks.kinematic_demand import (
    ElevatedSupport,
    elastic_spectral_demand,
    elastic_spectral_demands,
)
from rockscreen.pipeline.risk.checks.site_capacity import (
    SiteCapacity,
    SiteConditions,
    capacity_on_site,
)
from rockscreen.pipeline.risk.checks.validation import check_number
from rockscreen.solver.constants import G

__all__ = [
    "LV1_TOWER_Q",
    "SectionCheck",
    "ShaftSegment",
    "TowerLV1",
    "TowerModel",
    "lv1_demand",
    "lv1_demands",
    "lv1_tower",
    "section_ultimate_moment",
    "shaft_sections",
    "tower_period_guidelines",
]

#: Behaviour factor of the LV1 tower model (rockscreen's default, to be verified against
#: the Guidelines §5.4.4).
LV1_TOWER_Q = 3.0


@dataclass(frozen=True)
class ShaftSegment:
    """A prismatic stretch of the shaft with a hollow rectangular section."""

    #: Length of the stretch [m], > 0.
    height_m: float
    #: Outer plan dimension along the seismic action b [m], > 0.
    width_m: float
    #: Outer plan dimension across it a [m], > 0.
    depth_m: float
    #: Wall thickness t [m], > 0; a wall of half the smaller dimension or more is solid.
    wall_m: float
    #: Masonry density [kg/m3], in [1000, 3000].
    density_kg_m3: float

    def __post_init__(self):
        check_number("segment.height_m", self.height_m, low=0.0, low_open=True, unit="m")
        check_number("segment.width_m", self.width_m, low=0.0, low_open=True, unit="m")
        check_number("segment.depth_m", self.depth_m, low=0.0, low_open=True, unit="m")
        check_number("segment.wall_m", self.wall_m, low=0.0, low_open=True, unit="m")
        check_number(
            "segment.density_kg_m3", self.density_kg_m3, low=1000.0, high=3000.0, unit="kg/m3"
        )

    @property
    def void_m(self) -> tuple[float, float]:
        """Return the inner void's dimensions along and across the action [m] (0 if solid)."""
        bv, av = self.width_m - 2.0 * self.wall_m, self.depth_m - 2.0 * self.wall_m
        return (bv, av) if bv > 0.0 and av > 0.0 else (0.0, 0.0)

    @property
    def area_m2(self) -> float:
        """Return the masonry area of the section [m2]."""
        bv, av = self.void_m
        return self.width_m * self.depth_m - bv * av

    @property
    def mass_kg(self) -> float:
        """Return the stretch's mass [kg]."""
        return self.area_m2 * self.height_m * self.density_kg_m3


def section_ultimate_moment(segment: ShaftSegment, axial_n: float, fd_pa: float) -> float:
    """Return the flexural capacity M_u of a hollow section under an axial force [N m].

    Stress block ``0.85 f_d`` of depth ``x`` from the compressed edge, no tensile strength;
    ``0.85 f_d A_c(x) = N`` and ``M_u = N b/2 - 0.85 f_d S_c(x)``, ``S_c`` the first moment
    of the compressed area about the compressed edge (module docstring). Zero when
    ``N >= 0.85 f_d A`` (the section crushes under its own weight).

    Parameters
    ----------
    segment : ShaftSegment
        The section's geometry.
    axial_n : float
        Compressive axial force N [N], >= 0.
    fd_pa : float
        Design compressive strength f_d [Pa], > 0.

    Returns
    -------
    float
        M_u [N m], >= 0.
    """
    n = check_number("axial_n", axial_n, low=0.0, unit="N")
    fd = check_number("fd_pa", fd_pa, low=0.0, low_open=True, unit="Pa")
    b, a, t = segment.width_m, segment.depth_m, segment.wall_m
    bv, av = segment.void_m
    stress = 0.85 * fd
    needed = n / stress
    if needed >= segment.area_m2:
        return 0.0
    if bv == 0.0 or needed <= a * t:
        x = needed / a
    elif needed <= a * t + (a - av) * bv:
        x = t + (needed - a * t) / (a - av)
    else:
        x = b - t + (needed - a * t - (a - av) * bv) / a
    m = min(max(x, t), b - t) if bv > 0.0 else t
    first_moment = a * x**2 / 2.0 - av * (m**2 - t**2) / 2.0
    return max(n * b / 2.0 - stress * first_moment, 0.0)


def tower_period_guidelines(height_m: float) -> float:
    """Return the tower's first period T1 = 0.0187 H [s] when none is measured.

    Faccio, Paolucci & Zanotti's law for masonry towers
    (:data:`rockscreen.pipeline.motion.floor.PERIOD_LAWS` ``"faccio2010"``; source check:
    the open TURRIS code of Montabert et al. 2023, ``docs/belfry.md``), the law the belfry
    model and the floor model use. The variant ``0.0187 H^1.17`` that some attribute to the
    Guidelines (DPCM 9/2/2011 §5.4.4) was found in no source available to this work; it
    gives longer periods (1.00 s against 0.56 s at H = 30 m), hence a smaller spectral
    demand past the plateau: the law kept here is the safe side of the two
    (``docs/code_checks.md`` §3).

    Parameters
    ----------
    height_m : float
        Tower height H [m], > 0.

    Returns
    -------
    float
        T1 [s].
    """
    height = check_number("height_m", height_m, low=0.0, low_open=True, unit="m")
    return building_period_from_height(height, "faccio2010")


@dataclass(frozen=True)
class TowerModel:
    """A tower for the LV1 model: its shaft from the base up and its point masses."""

    #: Stretches of the shaft, bottom first.
    segments: tuple[ShaftSegment, ...]
    #: Design compressive strength f_d [Pa] (see ``confidence.design_compressive_strength``).
    fd_pa: float
    #: Belfry, bells, roof: heights above the tower's base (``inset_m`` is not used).
    masses: tuple[PointMass, ...] = ()
    #: Slices per segment for the lumped masses and the checked sections, in [1, 1000].
    slices_per_segment: int = 20

    def __post_init__(self):
        object.__setattr__(self, "segments", tuple(self.segments))
        object.__setattr__(self, "masses", tuple(self.masses))
        if not self.segments:
            raise RiskError("a tower model needs one shaft segment at least")
        check_number("fd_pa", self.fd_pa, low=0.0, low_open=True, unit="Pa")
        n = check_number("slices_per_segment", self.slices_per_segment, low=1, high=1000)
        if n != int(n):
            raise RiskError(f"slices_per_segment={self.slices_per_segment!r} must be an integer")

    @property
    def height_m(self) -> float:
        """Return the shaft's height [m]."""
        return sum(s.height_m for s in self.segments)


@dataclass(frozen=True)
class SectionCheck:
    """One checked section of the shaft."""

    #: Height above the base [m].
    height_m: float
    #: Axial force from the weight above [N].
    axial_n: float
    #: Flexural capacity [N m].
    ultimate_moment_nm: float
    #: Base shear that brings the section to M_u [N].
    base_shear_n: float
    #: N / (0.85 f_d A) [-]: the share of the stress block's capacity the weight above
    #: takes (sigma_0 / (0.85 f_d)); at 1 or more the section crushes under its own weight
    #: and has no flexural capacity left (M_u = 0).
    compression_ratio: float = 0.0


@dataclass(frozen=True)
class TowerLV1:
    """The LV1 result of a tower."""

    #: Period T1 used [s] and where it came from (``"given"`` or ``"faccio2010"``, the law).
    period_s: float
    period_source: str
    #: Total mass M [kg] and first-mode fraction e* [-].
    mass_kg: float
    mass_ratio: float
    #: Behaviour factor q [-].
    q: float
    #: F_SLV = min_i F_SLV,i [N] and the critical section.
    base_shear_n: float
    critical: SectionCheck
    #: S_e,SLV = q F_SLV / (e* M) [m/s2].
    se_slv_m_s2: float
    #: a_SLV, T_SLV, I_S, f_a on the site's hazard.
    capacity: SiteCapacity
    #: Every checked section, from the base up.
    sections: tuple[SectionCheck, ...]
    #: The structure beneath the tower whose floor spectrum is the demand (None: the
    #: ground's spectrum), see :func:`lv1_demand`.
    support: ElevatedSupport | None = None

    @property
    def demand_rule(self) -> str:
        """Return ``"ground"`` or ``"floor spectrum"`` (the demand's spectrum)."""
        return "ground" if self.support is None else "floor spectrum"


def lv1_demand(
    period_s: float,
    hazard: SiteHazard,
    site: SiteConditions,
    support: ElevatedSupport | None = None,
) -> float:
    """Return the LV1 spectral demand on the tower at its period T1 [m/s2].

    On the ground: the NTC 2018 elastic spectrum ``Se(T1)`` at the site's damping (eq.
    3.2.2). On a structure beneath the tower's springing (a church): the Circolare 2019
    floor spectrum ``S_eZ(T1, z)`` (§C7.2.3, [C7.2.5]-[C7.2.10]) with the structure
    elastic (``T_k`` = its period, ``xi_k`` = 5 %), the tower's damping the site's, at the
    springing's level ``z = support.level_m``, never below ``Se(T1)``
    (:func:`~rockscreen.pipeline.risk.checks.kinematic_demand.elastic_spectral_demand`; the
    bound is rockscreen's, docs/code_checks.md §1.4).

    Parameters
    ----------
    period_s : float
        The tower's first period T1 [s], > 0.
    hazard : SiteHazard
        ag, F0, T*C of the action.
    site : SiteConditions
        The site (soil, topography, damping of the tower's spectrum).
    support : ElevatedSupport, optional
        The structure beneath the tower; None: the tower stands on the ground.

    Returns
    -------
    float
        The demand [m/s2].
    """
    t1 = check_number("period_s", period_s, low=0.0, low_open=True, unit="s")
    if support is None:
        return site.spectral_acceleration(t1, hazard)
    return elastic_spectral_demand(t1, hazard, site, support, damping=site.damping)


def lv1_demands(
    periods_s,
    hazard: SiteHazard,
    site: SiteConditions,
    support: ElevatedSupport | None = None,
):
    """Return :func:`lv1_demand` at many periods T1 of one action at once [m/s2].

    The same demand (the NTC 2018 elastic spectrum on the ground; the Circolare 2019 floor
    spectrum, §C7.2.3, on a structure, never below ``Se(T1)``) element-wise on an array of
    periods (:func:`~rockscreen.pipeline.risk.checks.kinematic_demand.elastic_spectral_demands`
    at the site's damping): each element equals :func:`lv1_demand` at that period to
    rounding. The code's LV1 check keeps calling :func:`lv1_demand`.

    Parameters
    ----------
    periods_s : array_like
        The tower's periods T1 [s], each > 0.
    hazard : SiteHazard
        ag, F0, T*C of the action.
    site : SiteConditions
        The site (soil, topography, damping of the tower's spectrum).
    support : ElevatedSupport, optional
        The structure beneath the tower; None: on the ground.

    Returns
    -------
    numpy.ndarray
        The demand [m/s2], shape of ``periods_s``.
    """
    return elastic_spectral_demands(periods_s, hazard, site, support, damping=site.damping)


def lv1_tower(
    model: TowerModel,
    site: SiteConditions,
    *,
    q: float = LV1_TOWER_Q,
    period_s: float | None = None,
    support: ElevatedSupport | None = None,
) -> TowerLV1:
    """Return the LV1 capacity of a tower (module docstring).

    Parameters
    ----------
    model : TowerModel
        The tower.
    site : SiteConditions
        The site.
    q : float
        Behaviour factor [-], in [1, 6].
    period_s : float, optional
        First period T1 [s]; default :func:`tower_period_guidelines` of the shaft's height.
    support : ElevatedSupport, optional
        The structure beneath the tower's springing (a church: its height, period and the
        springing's level); None: on the ground. Sets the demand (:func:`lv1_demand`).

    Returns
    -------
    TowerLV1
    """
    q = check_number("q", q, low=1.0, high=6.0)
    if period_s is None:
        t1, source = tower_period_guidelines(model.height_m), "faccio2010"
    else:
        t1 = check_number("period_s", period_s, low=0.0, low_open=True, unit="s")
        source = "given"
    total, e_star, sections = shaft_sections(model)
    critical = min(sections, key=lambda s: s.base_shear_n)
    se_slv = q * critical.base_shear_n / (e_star * total)

    def passes(hazard: SiteHazard) -> bool:
        return lv1_demand(t1, hazard, site, support) <= se_slv

    return TowerLV1(
        period_s=t1,
        period_source=source,
        mass_kg=total,
        mass_ratio=e_star,
        q=q,
        base_shear_n=critical.base_shear_n,
        critical=critical,
        se_slv_m_s2=se_slv,
        capacity=capacity_on_site(passes, site),
        sections=sections,
        support=support,
    )


def shaft_sections(model: TowerModel) -> tuple[float, float, tuple[SectionCheck, ...]]:
    """Return the LV1 mechanics of a tower, without the site: M, e* and every section.

    The part of :func:`lv1_tower` that does not depend on the hazard (module docstring):
    the masses lumped at the slices' mid-heights and the point masses, ``e*``, and for the
    bottom of each slice its axial force, ``M_u``, the base shear ``F_SLV,i`` and
    ``sigma_0 / (0.85 f_d)``. ``S_e,SLV = q min_i F_SLV,i / (e* M)``. Public so that a
    caller sampling the tower's inputs (``risk.uncertainty.shaft``) can invert the
    capacity on the site once for many models.

    Parameters
    ----------
    model : TowerModel
        The tower.

    Returns
    -------
    mass_kg : float
        The total mass M [kg].
    mass_ratio : float
        e* [-].
    sections : tuple of SectionCheck
        Every checked section, from the base up.
    """
    # Lumped masses: (height [m], mass [kg]); section candidates: (height, segment).
    lumps: list[tuple[float, float]] = []
    cuts: list[tuple[float, ShaftSegment]] = []
    base = 0.0
    n = int(model.slices_per_segment)
    for segment in model.segments:
        dz = segment.height_m / n
        for k in range(n):
            cuts.append((base + k * dz, segment))
            lumps.append((base + (k + 0.5) * dz, segment.mass_kg / n))
        base += segment.height_m
    lumps += [(p.height_m, p.mass_kg) for p in model.masses]
    total = sum(m for _, m in lumps)
    mz = sum(m * z for z, m in lumps)
    mzz = sum(m * z * z for z, m in lumps)
    e_star = mz**2 / (total * mzz)
    sections = []
    for z_i, segment in cuts:
        above = [(z, m) for z, m in lumps if z > z_i]
        axial = G * sum(m for _, m in above)
        mu = section_ultimate_moment(segment, axial, model.fd_pa)
        lever = sum(m * z * (z - z_i) for z, m in above) / mz
        ratio = axial / (0.85 * model.fd_pa * segment.area_m2)
        sections.append(SectionCheck(z_i, axial, mu, mu / lever, ratio))
    return total, e_star, tuple(sections)
