"""The code checks of issue 22: mechanisms, LV1 tower model, FC (docs/code_checks.md).

The Circolare 2019 kinematic checks themselves: ``test_kinematic_circolare2019.py``.
"""

from __future__ import annotations

import math

import pytest

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.checks import (
    ElevatedSupport,
    Mechanism,
    PointMass,
    RigidBlock,
    ShaftSegment,
    SiteConditions,
    TowerModel,
    belfry_mechanism,
    confidence_factor,
    design_compressive_strength,
    kinematic_capacity,
    kinematic_check,
    lv1_tower,
    masonry_strength,
    section_ultimate_moment,
    tower_period_guidelines,
    whole_tower_mechanism,
)
from rockscreen.solver.constants import G

#: L'Aquila (a high-hazard site inside the NTC grid).
SITE = SiteConditions(13.40, 42.35)


# ----------------------------------------------------------------------- uniform block


@pytest.mark.parametrize(("b", "h"), [(1.0, 4.0), (6.0, 30.0), (0.6, 2.5), (3.0, 3.0)])
def test_uniform_block_identities(b, h):
    block = Mechanism("block", (RigidBlock(1234.0, b, h),))
    cap = kinematic_capacity(block, fc=1.0)
    assert cap.alpha0 == pytest.approx(b / h, rel=1e-14)
    assert cap.mass_ratio == pytest.approx(0.75, rel=1e-14)
    assert cap.participating_mass_kg == pytest.approx(0.75 * 1234.0, rel=1e-14)
    assert cap.a0_star_m_s2 == pytest.approx(b / h * G / 0.75, rel=1e-14)
    # The centroid moves by b/2 to stand over the hinge; d0* = dk0 / e* = 2b/3.
    assert cap.theta0_rad == pytest.approx(math.atan(b / h), rel=1e-14)
    assert cap.dk0_m == pytest.approx(b / 2.0, rel=1e-12)
    assert cap.d0_star_m == pytest.approx(2.0 * b / 3.0, rel=1e-12)
    assert cap.du_star_m == pytest.approx(0.4 * cap.d0_star_m, rel=1e-14)
    assert cap.au_star_m_s2 == pytest.approx(0.6 * cap.a0_star_m_s2, rel=1e-14)


def test_whole_tower_is_the_uniform_block():
    tower = whole_tower_mechanism(height_m=30.0, width_m=6.0, mass_kg=1.0e6)
    cap = kinematic_capacity(tower, fc=1.35)
    assert cap.alpha0 == pytest.approx(0.2)
    assert cap.mass_ratio == pytest.approx(0.75)
    assert cap.a0_star_g == pytest.approx(0.2 / (0.75 * 1.35))


# ------------------------------------------------------------------- monotonicity


def test_a_more_slender_block_has_a_smaller_alpha0():
    alphas = [
        kinematic_capacity(Mechanism("b", (RigidBlock(1000.0, 2.0, h),))).alpha0
        for h in (4.0, 8.0, 16.0, 32.0)
    ]
    assert alphas == sorted(alphas, reverse=True)


def test_a_larger_fc_gives_a_smaller_a0_star():
    tower = whole_tower_mechanism(height_m=20.0, width_m=5.0, mass_kg=5.0e5)
    a0 = [kinematic_capacity(tower, fc).a0_star_m_s2 for fc in (1.0, 1.2, 1.35)]
    assert a0[0] > a0[1] > a0[2]
    assert a0[0] / a0[2] == pytest.approx(1.35)


def test_bells_high_up_lower_alpha0():
    low = belfry_mechanism(
        width_m=3.0, height_m=6.0, piers_mass_kg=5e4, bells_mass_kg=5e3, bells_height_m=1.0
    )
    high = belfry_mechanism(
        width_m=3.0, height_m=6.0, piers_mass_kg=5e4, bells_mass_kg=5e3, bells_height_m=5.0
    )
    assert kinematic_capacity(high).alpha0 < kinematic_capacity(low).alpha0


# --------------------------------------------------------- capacity on the site's hazard


def test_bounds_are_reported_not_invented():
    stocky = kinematic_check(Mechanism("s", (RigidBlock(1e3, 4.0, 2.0),)), SITE).linear
    assert stocky.bound == "lower"
    assert stocky.return_period_y == 2475.0
    assert "lower bounds" in stocky.note
    slender = kinematic_check(Mechanism("s", (RigidBlock(1e3, 0.1, 5.0),)), SITE).linear
    assert slender.bound == "upper"
    assert slender.return_period_y == 30.0
    assert not slender.passes_at_slv


# ------------------------------------------------------------------------ validation


def test_validation_names_the_parameter_and_range():
    with pytest.raises(RiskError, match=r"tower\.width_m=-1.*\(0, inf\] m"):
        whole_tower_mechanism(height_m=10.0, width_m=-1.0, mass_kg=1.0)
    with pytest.raises(RiskError, match=r"fc=0\.9.*\[1, 2\]"):
        kinematic_capacity(whole_tower_mechanism(height_m=10.0, width_m=2.0, mass_kg=1.0), 0.9)
    with pytest.raises(RiskError, match=r"bells_height_m=9.*\[0, 6\] m"):
        belfry_mechanism(
            width_m=3.0, height_m=6.0, piers_mass_kg=1.0, bells_mass_kg=1.0, bells_height_m=9.0
        )
    with pytest.raises(RiskError, match=r"support\.level_m=40.*\[0, 30\] m"):
        ElevatedSupport(height_m=30.0, period_s=0.5, level_m=40.0)
    with pytest.raises(RiskError, match="no block and no mass"):
        Mechanism("empty", ())


def test_point_masses_enter_the_virtual_work():
    m = Mechanism("p", (), (PointMass(10.0, 2.0, 0.5), PointMass(30.0, 4.0, 0.5)))
    cap = kinematic_capacity(m, fc=1.0)
    assert cap.alpha0 == pytest.approx(20.0 / 140.0)
    assert cap.participating_mass_kg == pytest.approx(140.0**2 / (10 * 4 + 30 * 16))


# -------------------------------------------------------------------- FC and materials


def test_confidence_factors():
    assert [confidence_factor(k) for k in ("LC1", "lc2", "LC3")] == [1.35, 1.20, 1.00]
    with pytest.raises(RiskError, match="LC4"):
        confidence_factor("LC4")


def test_masonry_strength_by_knowledge_level():
    assert masonry_strength("solid_brick", "LC1") == pytest.approx(2.6e6)
    assert masonry_strength("solid_brick", "LC2") == pytest.approx(3.45e6)
    with pytest.raises(RiskError, match="LC3"):
        masonry_strength("solid_brick", "LC3")
    with pytest.raises(RiskError, match="Table C8.5.I"):
        masonry_strength("marble", "LC1")
    assert design_compressive_strength(2.6e6, 1.35) == pytest.approx(2.6e6 / 2.7)


# ---------------------------------------------------------------------------- LV1 tower


def test_solid_section_is_the_ntc_pier_formula():
    seg = ShaftSegment(1.0, width_m=2.0, depth_m=1.5, wall_m=1.0, density_kg_m3=1800.0)
    fd, n = 1.0e6, 4.0e5
    sigma0 = n / (2.0 * 1.5)
    expected = sigma0 * 3.0 * 2.0 / 2.0 * (1.0 - sigma0 / (0.85 * fd))
    assert section_ultimate_moment(seg, n, fd) == pytest.approx(expected, rel=1e-12)


def test_hollow_section_block_in_the_wall():
    seg = ShaftSegment(1.0, width_m=6.0, depth_m=6.0, wall_m=1.5, density_kg_m3=1800.0)
    fd, n = 2.0e6, 2.0e6
    x = n / (0.85 * fd * 6.0)
    assert x < 1.5
    expected = n / 2.0 * (6.0 - n / (0.85 * fd * 6.0))
    assert section_ultimate_moment(seg, n, fd) == pytest.approx(expected, rel=1e-12)
    # Deeper blocks take in the webs. dM_u/dN = b/2 - x: the moment grows until the block
    # reaches the centroid (half the area compressed here), then falls to 0 at crushing.
    crush = 0.85 * fd * seg.area_m2
    moments = [section_ultimate_moment(seg, f * crush, fd) for f in (0.2, 0.5, 0.8, 0.99)]
    assert moments[0] < moments[1] > moments[2] > moments[3] > 0.0
    assert moments[1] == pytest.approx(0.85 * fd * (9.0 * 2.25 + 2 * 1.5 * 1.5 * 0.75))
    assert section_ultimate_moment(seg, crush, fd) == 0.0
    near = 0.85 * fd * 6.0 * 1.5
    assert section_ultimate_moment(seg, near * (1 - 1e-9), fd) == pytest.approx(
        section_ultimate_moment(seg, near * (1 + 1e-9), fd), rel=1e-6
    )


def test_lv1_uniform_tower():
    seg = ShaftSegment(30.0, width_m=6.0, depth_m=6.0, wall_m=1.5, density_kg_m3=1800.0)
    fd = design_compressive_strength(masonry_strength("solid_brick", "LC1"), 1.35)
    model = TowerModel((seg,), fd_pa=fd, slices_per_segment=200)
    result = lv1_tower(model, SITE, period_s=0.8)
    assert result.mass_ratio == pytest.approx(0.75, abs=1e-4)
    assert result.mass_kg == pytest.approx(seg.mass_kg)
    # The base is critical for a prismatic shaft under its own weight (the largest lever).
    assert result.critical.height_m == 0.0
    base = result.critical
    assert base.axial_n == pytest.approx(G * seg.mass_kg)
    lever = 2.0 * 30.0 / 3.0  # sum m z^2 / sum m z for a uniform cantilever
    assert base.base_shear_n == pytest.approx(base.ultimate_moment_nm / lever, rel=1e-4)
    assert result.se_slv_m_s2 == pytest.approx(
        3.0 * base.base_shear_n / (result.mass_ratio * result.mass_kg)
    )
    cap = result.capacity
    if not cap.bound:
        se = SITE.spectral_acceleration(0.8, SITE.hazard(cap.return_period_y))
        assert se == pytest.approx(result.se_slv_m_s2, rel=1e-5)


def test_lv1_bells_and_period_default():
    seg = ShaftSegment(30.0, width_m=5.0, depth_m=5.0, wall_m=1.2, density_kg_m3=1900.0)
    bare = TowerModel((seg,), fd_pa=1.0e6)
    heavy = TowerModel((seg,), fd_pa=1.0e6, masses=(PointMass(2.0e5, 33.0, 2.5),))
    a, b = lv1_tower(bare, SITE), lv1_tower(heavy, SITE)
    assert a.period_source == "faccio2010"
    assert a.period_s == pytest.approx(tower_period_guidelines(30.0))
    assert tower_period_guidelines(30.0) == pytest.approx(0.0187 * 30.0)
    assert b.se_slv_m_s2 < a.se_slv_m_s2


def test_lv1_crushing_gives_an_upper_bound():
    seg = ShaftSegment(60.0, width_m=4.0, depth_m=4.0, wall_m=0.5, density_kg_m3=2000.0)
    result = lv1_tower(TowerModel((seg,), fd_pa=2.0e5), SITE, period_s=1.0)
    assert result.base_shear_n == 0.0
    assert result.capacity.bound == "upper"


def test_the_inventory_accepts_exactly_the_masonry_types_of_the_table():
    from rockscreen.pipeline.risk.checks import MASONRY_TYPES
    from rockscreen.stations.inventory_columns import MASONRY_TYPE_NAMES

    assert tuple(MASONRY_TYPES) == MASONRY_TYPE_NAMES


# ------------------------------------------------------------- worked examples by hand


def test_lv1_worked_example_of_the_doc_closed_form():
    """docs/code_checks.md §6.3: a solid shaft, S_e,SLV = q (b/H)(1 - sigma0/(0.85 f_d)) g.

    For a uniform solid prism the base governs and the slices' e* and base shear share the
    factor 1 - 1/(4 n^2), which cancels: the closed form holds for any slicing.
    """
    fd = design_compressive_strength(masonry_strength("solid_brick", "LC2"), 1.20)
    assert fd == pytest.approx(3.45e6 / 2.4)  # f_m mid-range 3.45 MPa / (gamma_M 2 x F_C 1.2)
    sigma0 = 18.0e3 * 20.0  # w H at the base [Pa]
    expected = 3.0 * (4.0 / 20.0) * (1.0 - sigma0 / (0.85 * fd))
    assert expected == pytest.approx(0.4232225, rel=1e-6)
    for slices in (5, 20, 200):
        seg = ShaftSegment(20.0, 4.0, 4.0, 2.0, density_kg_m3=18.0e3 / G)
        result = lv1_tower(TowerModel((seg,), fd, slices_per_segment=slices), SITE)
        assert result.critical.height_m == 0.0
        assert result.mass_ratio == pytest.approx(0.75 / (1.0 - 1.0 / (4 * slices**2)))
        assert result.se_slv_m_s2 / G == pytest.approx(expected, rel=1e-10)
    assert result.period_s == pytest.approx(0.374)  # 0.0187 x 20 m
    cap = result.capacity
    se = SITE.spectral_acceleration(result.period_s, SITE.hazard(cap.return_period_y))
    assert se == pytest.approx(result.se_slv_m_s2, rel=1e-5)
    assert cap.ag_g == pytest.approx(0.2087, abs=5e-4)
