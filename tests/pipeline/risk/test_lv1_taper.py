"""The LV1 shaft whose walls thin upwards: ``wall_thickness_top_m`` (issue 22).

With one prismatic segment the base stress is ``sigma_0 = w H`` whatever the wall, which
overstates it for a tower whose walls are thick at the base and thinner towards the belfry.
With ``wall_thickness_top_m`` the shaft is 10 prismatic segments of the walls interpolated
linearly at their mid-heights (2 slices each: the prismatic shaft's 20 slices), so the base
stress is ``w integral(A dz) / A_base`` (docs/code_checks.md §3).
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from rockscreen.pipeline.report.html.notes import translate_note
from rockscreen.pipeline.risk.assess.sites import tower_sites
from rockscreen.pipeline.risk.checks import (
    SiteConditions,
    confidence_factor,
    design_compressive_strength,
    lv1_tower,
)
from rockscreen.pipeline.risk.checks.tower_lv1 import TowerModel, section_ultimate_moment
from rockscreen.pipeline.risk.checks.tower_lv1_checks import (
    LV1_TAPER_SEGMENTS,
    LV1_TAPER_SLICES,
    lv1_columns,
    lv1_tower_model,
    shaft_description,
    shaft_walls_m,
)
from rockscreen.solver.constants import G
from rockscreen.stations.inventory import Tower

LAQUILA = (13.40, 42.35)  # lon, lat [deg]
SITE = SiteConditions(lon_deg=LAQUILA[0], lat_deg=LAQUILA[1], soil_class="B")
#: Rubble at LC1: w = 19 kN/m3, f_d = 1.0 MPa / (2 x 1.35) (Table C8.5.I).
RUBBLE_W_N_M3 = 19.0e3
RUBBLE_FD_PA = design_compressive_strength(1.0e6, 1.35)
#: A 4 m square shaft 12 m high, solid at its base (walls 2.4 m, more than half the side)
#: whose walls thin to 0.4 m at the top: t(z) = 2.4 - z/6, hollow from z = 2.4 m up (t = 2),
#: the boundary between the second and third of the ten 1.2 m segments.
SOLID_BASE = Tower(
    id="T-TAPER",
    width_m=4.0,
    height_m=12.0,
    depth_m=4.0,
    lat=LAQUILA[1],
    lon=LAQUILA[0],
    soil_class="B",
    wall_thickness_m=2.4,
    wall_thickness_top_m=0.4,
    masonry_type="rubble",
    knowledge_level="LC1",
)
#: T08 of examples/tower_population: split stone 42 x 8 m, walls 1.33 m, at LC2.
T08 = Tower(
    id="T08",
    width_m=8.0,
    height_m=42.0,
    depth_m=8.0,
    lat=42.3498,
    lon=13.3995,
    soil_class="B",
    wall_thickness_m=1.33,
    masonry_type="split_stone",
    knowledge_level="LC2",
)


def _lv1(tower: Tower, lang: str = "en") -> tuple[dict, list[str]]:
    """Return the LV1 columns and notes, rendered in ``lang``."""
    level = tower.knowledge_level
    columns, notes, missing = lv1_columns(tower_sites([tower])[0], confidence_factor(level), level)
    assert missing == []
    return columns, [n.render(lang) for n in notes]


def test_the_shaft_is_ten_segments_of_the_walls_at_their_mid_heights():
    assert LV1_TAPER_SEGMENTS * LV1_TAPER_SLICES == TowerModel.slices_per_segment  # 20 slices
    model = lv1_tower_model(SOLID_BASE, 1.35, "LC1")
    assert len(model.segments) == 10 and model.slices_per_segment == 2
    assert [s.height_m for s in model.segments] == pytest.approx([1.2] * 10, rel=1e-12)
    walls = [2.4 - (k + 0.5) * 1.2 / 6.0 for k in range(10)]  # t(z) at each mid-height
    assert [s.wall_m for s in model.segments] == pytest.approx(walls, rel=1e-12)
    assert shaft_walls_m(SOLID_BASE) == pytest.approx(walls, rel=1e-12)
    # without the column, or with the base's thickness: today's one prismatic segment
    for tower in (
        replace(SOLID_BASE, wall_thickness_top_m=None),
        replace(SOLID_BASE, wall_thickness_top_m=2.0, wall_thickness_m=2.0),
    ):
        prismatic = lv1_tower_model(tower, 1.35, "LC1")
        (segment,) = prismatic.segments
        assert segment.wall_m == tower.wall_thickness_m and segment.height_m == 12.0
        # 10 x 2 slices of the same wall are the prismatic shaft's 20: only the walls differ
        ten = replace(
            prismatic, segments=(replace(segment, height_m=1.2),) * 10, slices_per_segment=2
        )
        one, many = lv1_tower(prismatic, SITE), lv1_tower(ten, SITE)
        assert many.se_slv_m_s2 == pytest.approx(one.se_slv_m_s2, rel=1e-12)
        assert many.critical.compression_ratio == pytest.approx(
            one.critical.compression_ratio, rel=1e-12
        )
    # the belfry sits on the shaft's top: the segments end there
    belfry = replace(
        T08,
        wall_thickness_top_m=0.8,
        belfry_height_m=6.0,
        belfry_width_m=2.0,
        belfry_mass_kg=5.0e4,
        bells_mass_kg=2000.0,
        bells_height_m=3.0,
    )
    model = lv1_tower_model(belfry, 1.2, "LC2", across=True)
    assert model.height_m == pytest.approx(36.0, rel=1e-12)
    assert [p.height_m for p in model.masses] == [39.0, 39.0]


def test_the_base_stress_of_a_tapered_solid_shaft_by_hand():
    """sigma_0 = w integral_0^H A(z) dz / A_base, below w H.

    ``A(t) = a b`` where the wall reaches half the side (t >= 2 m, z <= 2.4 m) and
    ``2 t (a + b) - 4 t^2`` above, with ``t = t_0 + s z``. Exactly:
    ``I = 16 x 2.4 + 2 (a + b) L (2 + 0.4) / 2 - 4 L (2^2 + 2 x 0.4 + 0.4^2) / 3`` over the
    hollow length ``L = 9.6 m``. The model takes each segment's area at its mid-height (the
    midpoint rule): exact on the two solid segments, and on each hollow one (A quadratic,
    ``A'' = -8 s^2``) above the integral by exactly ``-A'' h^3 / 24 = s^2 h^3 / 3``: the
    segmentation's own discretisation, so the equality holds to rounding.
    """
    model = lv1_tower_model(SOLID_BASE, 1.35, "LC1")
    result = lv1_tower(model, SITE)
    a = b = 4.0
    s, h, length = -1.0 / 6.0, 1.2, 9.6
    exact = a * b * 2.4 + 2 * (a + b) * length * 1.2 - 4 * length * (4.0 + 0.8 + 0.16) / 3
    assert exact == pytest.approx(159.232, rel=1e-12)
    midpoint = exact + 8 * s**2 * h**3 / 3  # eight hollow segments
    base = result.sections[0]
    assert base.height_m == 0.0
    sigma_0 = base.axial_n / (a * b)  # the base segment (wall 2.3 m) is solid
    assert sigma_0 == pytest.approx(RUBBLE_W_N_M3 * midpoint / (a * b), rel=1e-12)
    assert sigma_0 == pytest.approx(RUBBLE_W_N_M3 * exact / (a * b), rel=1e-3)  # 0.08 %
    assert sigma_0 < 0.84 * RUBBLE_W_N_M3 * 12.0  # w H, the prismatic shaft's: 17 % less
    assert base.compression_ratio == pytest.approx(sigma_0 / (0.85 * RUBBLE_FD_PA), rel=1e-12)
    # the base governs, and the capacity is q M_u / sum(m z): the solid rectangle's
    # M_u = N (b/2)(1 - sigma_0/(0.85 f_d)) over a mass whose centre the taper lowers
    assert result.critical is base
    mu = base.axial_n * b / 2 * (1 - base.compression_ratio)
    assert base.ultimate_moment_nm == pytest.approx(mu, rel=1e-12)
    # sum(m z): each segment's two slices about its mid-height
    moment_of_mass = sum(seg.mass_kg * 1.2 * (k + 0.5) for k, seg in enumerate(model.segments))
    assert result.se_slv_m_s2 == pytest.approx(3.0 * mu / moment_of_mass, rel=1e-12)
    # docs/code_checks.md §6.5: z_G = 5.27 m, S_e,SLV = 0.454 g (0.276 g prismatic)
    assert moment_of_mass / result.mass_kg == pytest.approx(5.2684, abs=1e-4)
    assert result.se_slv_m_s2 / G == pytest.approx(0.4543, abs=1e-4)
    # the column and the prismatic shaft of the base's wall (solid: sigma_0 = w H)
    tapered, _ = _lv1(SOLID_BASE)
    prismatic, _ = _lv1(replace(SOLID_BASE, wall_thickness_top_m=None))
    assert tapered["lv1_compression_ratio"] == pytest.approx(base.compression_ratio, rel=1e-12)
    assert prismatic["lv1_compression_ratio"] == pytest.approx(
        RUBBLE_W_N_M3 * 12.0 / (0.85 * RUBBLE_FD_PA), rel=1e-9
    )
    assert tapered["lv1_compression_ratio"] < 0.84 * prismatic["lv1_compression_ratio"]
    assert (tapered["lv1_compression_ratio"], prismatic["lv1_compression_ratio"]) == (
        pytest.approx(0.601, abs=1e-3),
        pytest.approx(0.724, abs=1e-3),
    )
    # §6.5 at L'Aquila, soil B, T1 = 0.224 s: a_SLV 0.165 g against 0.098 g
    assert tapered["lv1_capacity_ag_g"] == pytest.approx(0.165, abs=1e-3)
    assert prismatic["lv1_capacity_ag_g"] == pytest.approx(0.098, abs=1e-3)
    assert tapered["lv1_safety_index"] > 3 * prismatic["lv1_safety_index"]


def test_tapering_lowers_the_compression_and_raises_the_capacity_of_a_shaft_alone():
    """Thinner walls up: less weight over the base and a lower centre of mass.

    The base stays critical, and there ``S_e,SLV = q M_u / sum(m z) = q g (b/2 - x) / z_G``
    (``x`` the depth of the compressed block's centroid): both ``x`` (less weight on nearly
    the same section) and ``z_G`` fall, so the capacity rises. The upper sections' thinner
    walls do not govern on this shaft.
    """
    prismatic, _ = _lv1(T08)
    previous = prismatic
    for top in (1.0, 0.8, 0.6):
        tapered, _ = _lv1(replace(T08, wall_thickness_top_m=top))
        assert tapered["lv1_compression_ratio"] < previous["lv1_compression_ratio"]
        assert tapered["lv1_capacity_ag_g"] > previous["lv1_capacity_ag_g"]
        assert tapered["lv1_safety_index"] > previous["lv1_safety_index"]
        assert tapered["lv1_period_s"] == prismatic["lv1_period_s"]  # 0.0187 H either way
        previous = tapered
    for across in (False, True):
        model = lv1_tower_model(replace(T08, wall_thickness_top_m=0.6), 1.2, "LC2", across=across)
        assert lv1_tower(model, SITE).critical.height_m == 0.0


def test_under_a_heavy_belfry_the_taper_can_lower_the_capacity():
    """Not a law: the weight the taper removes also held the shaft up.

    (i) Strong masonry (a measured f_m = 10 MPa at LC3) under a 100 t belfry: the base stays
    critical and its compression falls, but at so low a compression ``M_u ~ N b / 2`` (the
    rigid block's), and the shaft's weight taken from N is a larger share of N than of
    ``sum(m z)``, which the belfry dominates: the capacity falls (1.4 %).
    (ii) A heavy belfry on walls thinned to 0.1 m: a section under the belfry crushes first,
    the critical section moves up, and its compression exceeds the prismatic base's.
    """
    strong = Tower(
        id="T-STRONG",
        width_m=3.0,
        height_m=19.0,
        lat=LAQUILA[1],
        lon=LAQUILA[0],
        soil_class="B",
        wall_thickness_m=0.45,
        masonry_type="solid_brick",
        masonry_strength_mpa=10.0,
        knowledge_level="LC3",
        belfry_height_m=4.0,
        belfry_width_m=1.0,
        belfry_mass_kg=1.0e5,
        bells_mass_kg=0.0,
        bells_height_m=2.0,
    )
    prismatic, _ = _lv1(strong)
    tapered, notes = _lv1(replace(strong, wall_thickness_top_m=0.2))
    assert "critical section at 0.0 m" in notes[0]
    assert tapered["lv1_compression_ratio"] < prismatic["lv1_compression_ratio"] < 0.15
    assert tapered["lv1_capacity_ag_g"] < prismatic["lv1_capacity_ag_g"]
    assert tapered["lv1_safety_index"] < prismatic["lv1_safety_index"]
    heavy = Tower(
        id="T-HEAVY",
        width_m=4.0,
        height_m=18.0,
        lat=LAQUILA[1],
        lon=LAQUILA[0],
        soil_class="B",
        wall_thickness_m=0.6,
        masonry_type="solid_brick",
        knowledge_level="LC2",
        belfry_height_m=3.0,
        belfry_width_m=1.0,
        belfry_mass_kg=2.0e5,
        bells_mass_kg=0.0,
        bells_height_m=1.5,
    )
    prismatic, notes = _lv1(heavy)
    assert "critical section at 0.0 m" in notes[0]
    tapered, notes = _lv1(replace(heavy, wall_thickness_top_m=0.1))
    assert "critical section at 0.0 m" not in notes[0]
    assert tapered["lv1_compression_ratio"] > prismatic["lv1_compression_ratio"]
    assert tapered["lv1_capacity_ag_g"] < prismatic["lv1_capacity_ag_g"]
    model = lv1_tower_model(replace(heavy, wall_thickness_top_m=0.1), 1.2, "LC2")
    result = lv1_tower(model, SITE, period_s=tapered["lv1_period_s"])
    top = model.segments[-1]
    assert result.critical.height_m > 12.0
    assert result.critical.ultimate_moment_nm == pytest.approx(
        section_ultimate_moment(top, result.critical.axial_n, model.fd_pa), rel=1e-12
    )
    assert result.critical.axial_n > G * 2.0e5  # the belfry and the shaft above


def test_the_note_says_which_shaft_and_reads_in_italian():
    assert shaft_description(replace(T08, wall_thickness_top_m=None)).render() == (
        "prismatic shaft, walls 1.33 m"
    )
    tapered = replace(T08, wall_thickness_top_m=0.8)
    assert shaft_description(tapered).render() == (
        "shaft walls tapering from 1.33 m at the base to 0.80 m at the top (10 segments)"
    )
    for tower, words, italian_words in (
        (T08, "prismatic shaft, walls 1.33 m", "fusto prismatico, pareti di 1,33 m"),
        (
            tapered,
            "shaft walls tapering from 1.33 m at the base to 0.80 m at the top (10 segments)",
            "pareti del fusto rastremate da 1,33 m alla base a 0,80 m in sommità (10 tratti)",
        ),
    ):
        _, notes = _lv1(tower)
        (model_note,) = [n for n in notes if n.startswith("LV1 tower model")]
        assert f"(Table C8.5.I, LC2: the range's mean), {words}, critical section at" in model_note
        assert "; " not in model_note  # one clause of the archive's note
        italian = "; ".join(_lv1(tower, "it")[1])
        assert italian.startswith("modello LV1 per le torri (DPCM 9/2/2011 §5.4.4")
        assert f"(Tabella C8.5.I, LC2: media dell'intervallo), {italian_words}, sezione" in italian
        assert "LV1 tower model" not in italian and "shaft" not in italian
    # an archive written before the shaft's words and the note's codes: its clause still
    # reads in Italian (the adapter of older archives)
    older = (
        "LV1 tower model (DPCM 9/2/2011 §5.4.4, formulas to be verified): T1 = 0.79 s "
        "(0.0187 H of the whole tower, assumed), q = 3, gamma_M = 2, split_stone, f_m = 2.6 "
        "MPa (Table C8.5.I, LC2: the range's mean), critical section at 0.0 m"
    )
    assert translate_note(older, "it").endswith(
        "f_m = 2,6 MPa (Tabella C8.5.I, LC2: media dell'intervallo), sezione critica a 0,0 m"
    )
