"""The kinematic checks of the Circolare 2019 §C8.7.1.2.1, against hand calculations.

Every number here is computed by hand in docs/code_checks.md §1 and §6 from the formulas of
the Circolare 21/1/2019 n. 7 ([C8.7.1.1]-[C8.7.1.12], §C7.2.3 [C7.2.5]-[C7.2.10]) and of
NTC 2018 §3.2.3.2 (eqs. 3.2.2, 3.2.4, 3.2.10-3.2.12).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.hazard import displacement_spectrum, elastic_spectrum
from rockscreen.pipeline.risk.checks.floor_spectrum import (
    StructureState,
    floor_spectral_acceleration,
    peak_floor_acceleration,
)
from rockscreen.pipeline.risk.checks.kinematic import (
    Mechanism,
    RigidBlock,
    cantilever_period,
    kinematic_capacity,
    kinematic_check,
    nonlinear_capacity_on_site,
)
from rockscreen.pipeline.risk.checks.kinematic_demand import (
    ElevatedSupport,
    activation_demand,
    displacement_demand,
    linear_demand,
)
from rockscreen.pipeline.risk.checks.mechanisms import (
    belfry_mechanism,
    bell_gable_mechanism,
    whole_tower_mechanism,
)
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.solver.constants import G

#: L'Aquila, soil A: the site of the doc's worked examples.
SITE = SiteConditions(13.40, 42.35)


def _belfry() -> Mechanism:
    return belfry_mechanism(
        width_m=3.0,
        height_m=6.0,
        piers_mass_kg=60_000.0,
        bells_mass_kg=3_000.0,
        bells_height_m=3.0,
        roof_mass_kg=10_000.0,
    )


# --------------------------------------------------------------------- the capacity


def test_worked_example_belfry_capacity():
    """docs/code_checks.md §6.1: the belfry, [C8.7.1.1]-[C8.7.1.5], [C8.7.1.10] by hand."""
    cap = kinematic_capacity(_belfry(), fc=1.35)
    tol = 1e-5
    assert cap.alpha0 == pytest.approx(0.439759, rel=tol)
    assert cap.participating_mass_kg == pytest.approx(56_008.13, rel=tol)
    assert cap.mass_ratio == pytest.approx(0.767235, rel=tol)
    assert cap.a0_star_m_s2 == pytest.approx(4.16507, rel=tol)
    assert cap.d0_star_m == pytest.approx(1.955076, rel=tol)
    # d_SLV = 0.4 d0; a(d_SLV) = 0.6 a0 (rigid until activation); T_SLV = 1.68 pi sqrt(d/a).
    assert cap.du_star_m == pytest.approx(0.782030, rel=tol)
    assert cap.au_star_m_s2 == pytest.approx(2.499042, rel=tol)
    assert cap.t_slv_s == pytest.approx(2.952461, rel=tol)
    assert cap.t0_s == 0.0


def test_uniform_block_d_slv_and_t_slv_in_closed_form():
    """A uniform block b x h: d0 = 2b/3, d_SLV = 4b/15, a(d_SLV) = 0.6 a0."""
    b, h, fc = 2.0, 10.0, 1.2
    cap = kinematic_capacity(Mechanism("u", (RigidBlock(5.0e4, b, h),)), fc)
    a0 = (b / h) * G / (0.75 * fc)
    assert cap.a0_star_m_s2 == pytest.approx(a0, rel=1e-14)
    assert cap.d0_star_m == pytest.approx(2.0 * b / 3.0, rel=1e-14)
    assert cap.du_star_m == pytest.approx(4.0 * b / 15.0, rel=1e-14)
    expected = 1.68 * math.pi * math.sqrt((4.0 * b / 15.0) / (0.6 * a0))
    assert cap.t_slv_s == pytest.approx(expected, rel=1e-14)


def test_elastic_branch_of_an_element_free_to_vibrate():
    """[C8.7.1.6]: a = 4 pi^2 d / T0^2 until it meets the rigid-body line."""
    block = Mechanism("u", (RigidBlock(5.0e4, 2.0, 10.0),))
    rigid = kinematic_capacity(block)
    soft = kinematic_capacity(replace(block, elastic_period_s=6.0))
    d = 0.01
    assert soft.spectral_acceleration(d) == pytest.approx((2 * math.pi / 6.0) ** 2 * d)
    # A very flexible element reaches d_SLV on its elastic branch: a(d_SLV) is lower.
    assert soft.au_star_m_s2 < rigid.au_star_m_s2
    assert soft.au_star_m_s2 == pytest.approx((2 * math.pi / 6.0) ** 2 * soft.du_star_m)
    stiff = kinematic_capacity(replace(block, elastic_period_s=0.05))
    assert stiff.au_star_m_s2 == pytest.approx(rigid.au_star_m_s2)


def test_cantilever_period_by_hand():
    """[C8.7.1.7]: T0 = 6.2 (L/t) L sqrt(w / (E g)); 3 m x 0.5 m, 19 kN/m3, E = 435 MPa."""
    t0 = cantilever_period(3.0, 0.5, 19.0e3, 0.5 * 870.0e6)
    assert t0 == pytest.approx(6.2 * 6.0 * 3.0 * math.sqrt(19.0e3 / (435.0e6 * G)), rel=1e-14)
    assert t0 == pytest.approx(0.235484, rel=1e-5)
    with pytest.raises(RiskError, match=r"thickness_m=0.*\(0, inf\] m"):
        cantilever_period(3.0, 0.0, 19.0e3, 1.0e9)


# ------------------------------------------------------------------- the spectra


def test_ntc_displacement_spectrum_branches():
    """NTC 2018 eqs. 3.2.10-3.2.12, Tab. 3.2.VII (soil A: T_E = 4.5 s, T_F = 10 s)."""
    hazard = SITE.hazard(475.0)
    t = np.array([0.5, 2.0, 4.5, 7.25, 10.0, 12.0])
    sde = displacement_spectrum(t, hazard, "A", "T1", 0.05)
    se = elastic_spectrum(t, hazard, "A", "T1", 0.05) * G
    assert sde[:3] == pytest.approx(se[:3] * (t[:3] / (2 * math.pi)) ** 2, rel=1e-14)
    tc, td = 0.0, 4.0 * hazard.ag_g + 1.6
    from rockscreen.pipeline.hazard import spectrum_parameters

    p = spectrum_parameters(hazard, "A", "T1", 0.05)
    tc = p.TC_s
    d_g = 0.025 * hazard.ag_g * G * p.S * tc * td
    mid = d_g * (hazard.F0 + (1 - hazard.F0) * (7.25 - 4.5) / (10.0 - 4.5))
    assert sde[3] == pytest.approx(mid, rel=1e-12)
    assert sde[4] == pytest.approx(d_g, rel=1e-12)
    assert sde[5] == pytest.approx(d_g, rel=1e-12)


def test_floor_spectrum_by_hand():
    """[C7.2.6]-[C7.2.8], [C7.2.10]: first mode, a = 0.8, b = 1.1, gamma = 1.5, z = H."""
    hazard = SITE.hazard(475.0)
    structure = StructureState(height_m=30.0, level_m=30.0, period_s=0.6, damping=0.05)
    se_t1 = SITE.spectral_acceleration(0.6, hazard)
    a_z = se_t1 * 1.5 * math.sqrt(1.0 + 0.0004 * 5.0**2)
    assert peak_floor_acceleration(hazard, SITE, structure) == pytest.approx(a_z, rel=1e-12)
    amp = 1.1 / math.sqrt(0.05) * 1.0  # eta(5 %) = 1
    t = np.array([0.0, 0.24, 0.48, 0.6, 0.66, 1.32])
    s = floor_spectral_acceleration(t, hazard, SITE, structure, 0.05)
    assert s[0] == pytest.approx(a_z, rel=1e-12)  # at T = 0 the floor's own acceleration
    rise = amp * a_z / (1 + (amp - 1) * (1 - 0.24 / 0.48) ** 1.6)
    assert s[1] == pytest.approx(rise, rel=1e-12)
    assert s[2] == pytest.approx(amp * a_z, rel=1e-12)
    assert s[3] == pytest.approx(amp * a_z, rel=1e-12)
    assert s[4] == pytest.approx(amp * a_z, rel=1e-12)
    fall = amp * a_z / (1 + (amp - 1) * (1.32 / 0.66 - 1) ** 1.2)
    ground = SITE.spectral_acceleration(1.32, hazard)
    assert s[5] == pytest.approx(max(fall, ground), rel=1e-12)
    # 8 % on a structure at 10 %: A = 1.1 / sqrt(0.10) sqrt(10 / 13).
    ult = StructureState(height_m=30.0, level_m=30.0, period_s=0.9, damping=0.10)
    a_z10 = (
        replace(SITE, damping=0.10).spectral_acceleration(0.9, hazard)
        * 1.5
        * math.sqrt(1.0 + 0.0004 * 10.0**2)
    )
    plateau = floor_spectral_acceleration([0.9], hazard, SITE, ult, 0.08)[0]
    assert plateau == pytest.approx(1.1 / math.sqrt(0.10) * math.sqrt(10 / 13) * a_z10)


def test_floor_spectrum_never_below_the_ground_past_t1():
    """[C7.2.5]: S_eZ >= Se(T, xi) for T > T1, e.g. low on a flexible structure."""
    hazard = SITE.hazard(475.0)
    structure = StructureState(height_m=30.0, level_m=3.0, period_s=0.5)
    t = np.linspace(0.51, 4.0, 50)
    s = floor_spectral_acceleration(t, hazard, SITE, structure, 0.05)
    assert np.all(s >= elastic_spectrum(t, hazard, "A", "T1", 0.05) * G * (1 - 1e-12))


# ------------------------------------------------------------------------- the checks


def test_linear_check_rigid_on_the_ground_holds_at_equality():
    """§C8.7.1.2.1.7 on the ground: q a0 = ag S at a_SLV,kin."""
    tower = whole_tower_mechanism(height_m=30.0, width_m=6.0, mass_kg=1.0e6)
    check = kinematic_check(tower, SITE, fc=1.35)
    lin = check.linear
    assert lin.bound == ""
    hazard = SITE.hazard(lin.return_period_y)
    assert 2.0 * check.capacity.a0_star_m_s2 == pytest.approx(
        hazard.ag_g * SITE.soil_factor(hazard) * G, rel=1e-5
    )
    assert lin.safety_index == pytest.approx(lin.return_period_y / SITE.tr_slv_y())


def test_linear_check_free_on_the_ground_reads_the_spectrum_at_t0():
    """[C8.7.1.9] on the ground: q a0 = Se(T0, 5 %) at a_SLV,kin; weaker than rigid."""
    tower = whole_tower_mechanism(height_m=30.0, width_m=6.0, mass_kg=1.0e6)
    free = replace(tower, elastic_period_s=0.56)
    check = kinematic_check(free, SITE, fc=1.35)
    hazard = SITE.hazard(check.linear.return_period_y)
    assert 2.0 * check.capacity.a0_star_m_s2 == pytest.approx(
        SITE.spectral_acceleration(0.56, hazard), rel=1e-5
    )
    assert check.linear.ag_g < kinematic_check(tower, SITE, fc=1.35).linear.ag_g


def test_nonlinear_check_holds_at_equality_or_at_activation():
    """§C8.7.1.2.1.8: d_SLV = max S_De(T, 8 %) on [T0, T_SLV], or a_g,SLD when larger."""
    gable = bell_gable_mechanism(thickness_m=0.5, height_m=4.0, mass_kg=8000.0)
    check = kinematic_check(replace(gable, elastic_period_s=0.2), SITE, fc=1.35)
    non, cap = check.nonlinear, check.capacity
    assert non.bound == ""
    hazard = SITE.hazard(non.return_period_y)
    demand = displacement_demand(cap.t0_s, cap.t_slv_s, hazard, SITE)
    activation = activation_demand(cap.t0_s, hazard, SITE)
    holds_by_displacement = demand == pytest.approx(cap.du_star_m, rel=1e-4)
    holds_at_activation = activation == pytest.approx(cap.a0_star_m_s2, rel=1e-4)
    assert holds_by_displacement or holds_at_activation
    t = np.linspace(0.2, cap.t_slv_s, 2001)
    sde = displacement_spectrum(t, hazard, "A", "T1", 0.08)
    assert demand == pytest.approx(sde.max(), rel=1e-3)


def test_nonlinear_capacity_never_below_activation():
    """§C8.7.1.2.1.8: "nel caso in cui questa risulti minore di a_g,SLD ... quest'ultima"."""
    for mech in (
        whole_tower_mechanism(height_m=30.0, width_m=6.0, mass_kg=1.0e6),
        replace(
            bell_gable_mechanism(thickness_m=0.4, height_m=3.0, mass_kg=5e3), elastic_period_s=0.3
        ),
    ):
        check = kinematic_check(mech, SITE)
        # a_g,SLD is the linear capacity with q = 1.
        sld = kinematic_check(mech, SITE, q=1.0).linear
        assert check.nonlinear.ag_g >= sld.ag_g * (1 - 1e-5)


def test_elevated_mechanism_on_the_floor_spectrum():
    """At height: a_Z(z) (rigid) or S_eZ(T0, z) (free), never below the ground's."""
    hazard = SITE.hazard(475.0)
    top = ElevatedSupport(height_m=30.0, period_s=0.8)
    elastic = top.state(ultimate=False)
    assert activation_demand(0.0, hazard, SITE, top) == pytest.approx(
        max(peak_floor_acceleration(hazard, SITE, elastic), hazard.ag_g * G)
    )
    free = activation_demand(0.3, hazard, SITE, top)
    assert free == pytest.approx(floor_spectral_acceleration([0.3], hazard, SITE, elastic, 0.05)[0])
    assert linear_demand(0.3, hazard, SITE, top) == pytest.approx(free / 2.0)
    base = ElevatedSupport(height_m=30.0, period_s=0.8, level_m=0.0)
    assert activation_demand(0.0, hazard, SITE, base) == pytest.approx(hazard.ag_g * G)
    ult = top.state(ultimate=True)
    assert (ult.period_s, ult.damping) == (pytest.approx(1.2), 0.10)
    assert displacement_demand(0.0, 1.0, hazard, SITE, top) >= displacement_demand(
        0.0, 1.0, hazard, SITE
    )


def test_elevated_belfry_is_weaker_than_on_the_ground():
    belfry = replace(_belfry(), elastic_period_s=0.1)
    ground = kinematic_check(belfry, SITE)
    top = kinematic_check(belfry, SITE, support=ElevatedSupport(30.0, 0.8))
    assert top.linear.return_period_y <= ground.linear.return_period_y
    assert top.demand_rule == "floor spectrum"


def test_validation_names_the_parameter():
    with pytest.raises(RiskError, match=r"elastic_period_s=-1"):
        Mechanism("m", (RigidBlock(1.0, 1.0, 1.0),), elastic_period_s=-1.0)
    with pytest.raises(RiskError, match=r"t_slv_s=0"):
        displacement_demand(0.0, 0.0, SITE.hazard(475.0), SITE)
    with pytest.raises(RiskError, match=r"q=5"):
        kinematic_check(Mechanism("m", (RigidBlock(1.0, 1.0, 1.0),)), SITE, q=5.0)


def test_soil_class_lowers_the_capacity_ag():
    tower = whole_tower_mechanism(height_m=30.0, width_m=6.0, mass_kg=1.0e6)
    site_c = SiteConditions(13.40, 42.35, soil_class="C", topography="T2")
    rock = kinematic_check(tower, SITE).linear
    soft = kinematic_check(tower, site_c).linear
    assert soft.ag_g < rock.ag_g
    hazard = SITE.hazard(soft.return_period_y)
    assert linear_demand(0.0, hazard, site_c) == pytest.approx(
        kinematic_capacity(tower).a0_star_m_s2, rel=1e-5
    )


def test_worked_example_bell_gable_on_a_facade():
    """docs/code_checks.md §6.2: a bell gable, free to vibrate, on top of a 9 m facade."""
    rho = 19.0e3 / 9.81  # rubble, Table C8.5.I
    mass = rho * 3.0 * 2.0 * 0.5 * (1.0 - 0.25)  # h x w x t, a quarter of it openings
    assert mass == pytest.approx(4357.798, rel=1e-6)
    gable = bell_gable_mechanism(thickness_m=0.5, height_m=3.0, mass_kg=mass, bells_mass_kg=300.0)
    assert gable.sums() == pytest.approx((4657.798, 1164.4495, 7136.6972, 14273.3945), rel=1e-6)
    t0 = cantilever_period(3.0, 0.5, 19.0e3, 0.5 * 870.0e6)  # rubble: E mean 870 MPa, halved
    cap = kinematic_capacity(replace(gable, elastic_period_s=t0), fc=1.35)
    tol = 1e-5
    assert cap.alpha0 == pytest.approx(0.163164, rel=tol)
    assert cap.participating_mass_kg == pytest.approx(3568.349, rel=tol)
    assert cap.mass_ratio == pytest.approx(0.766102, rel=tol)
    assert cap.a0_star_g == pytest.approx(0.157762, rel=tol)
    assert cap.d0_star_m == pytest.approx(0.326327, rel=tol)
    assert cap.du_star_m == pytest.approx(0.130531, rel=tol)
    assert cap.au_star_m_s2 == pytest.approx(0.928588, rel=tol)
    assert cap.t_slv_s == pytest.approx(1.978811, rel=tol)
    # On the facade's top (T1 = 0.25 s, z = H): T0 = 0.2355 s lies on the floor spectrum's
    # plateau [0.8 T1, 1.1 T1]: S_eZ(T0) = 1.1/sqrt(0.05) x 1.5 x sqrt(1.01) x Se(T1).
    support = ElevatedSupport(height_m=9.0, period_s=0.25, level_m=9.0)
    amplification = 1.1 / math.sqrt(0.05) * 1.5 * math.sqrt(1.01)
    assert amplification == pytest.approx(7.415828, rel=1e-6)
    hazard = SITE.hazard(475.0)
    assert activation_demand(t0, hazard, SITE, support) == pytest.approx(
        amplification * SITE.spectral_acceleration(0.25, hazard), rel=1e-12
    )
    # 2 a0 = 3.095 m/s2 is below 7.416 Se(T1) already at 30 y: the gable fails the linear
    # check at every tabulated return period (an upper bound, never a value).
    check = kinematic_check(replace(gable, elastic_period_s=t0), SITE, fc=1.35, support=support)
    low = SITE.hazard(30.0)
    assert 2.0 * cap.a0_star_m_s2 < amplification * SITE.spectral_acceleration(0.25, low)
    assert check.linear.bound == "upper" and not check.linear.passes_at_slv


def test_the_nonlinear_capacity_alone_is_the_checks_nonlinear_capacity():
    """nonlinear_capacity_on_site: kinematic_check(...).nonlinear, without the linear search."""
    soft = SiteConditions(13.40, 42.35, soil_class="D")
    mechanisms = (
        _belfry(),
        replace(_belfry(), elastic_period_s=0.1),
        whole_tower_mechanism(height_m=30.0, width_m=6.0, mass_kg=1.0e6),
        replace(
            bell_gable_mechanism(thickness_m=0.4, height_m=3.0, mass_kg=5e3), elastic_period_s=0.3
        ),
    )
    for mech in mechanisms:
        for site in (SITE, soft):
            for support in (None, ElevatedSupport(30.0, 0.8)):
                for fc in (1.0, 1.35):
                    check = kinematic_check(mech, site, fc=fc, support=support)
                    alone = nonlinear_capacity_on_site(mech, site, fc=fc, support=support)
                    assert alone == check.nonlinear
