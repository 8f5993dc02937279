"""Circolare 2019 Table C8.5.I, the knowledge levels of §C8.5.4.1 and the FC of §C8.5.4.

Every literal below is the table's digit (N/mm2, kN/m3) as transcribed in the verified
extract of ``claudiopagani/structural-codes`` (``corpus/assets/circ2019/C8.5-step1.json``,
PDF p. 261), converted to Pa and N/m3 by the test itself.
"""

from __future__ import annotations

import pytest

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.checks import (
    CONFIDENCE_FACTORS,
    MASONRY_TYPES,
    confidence_factor,
    masonry_elastic_modulus,
    masonry_strength,
)
from rockscreen.solver.constants import G

MPA = 1.0e6
KN = 1.0e3

#: key -> (f min, f max, tau0 min, tau0 max, fv0 (min, max) or None, E min, E max,
#: G min, G max) [N/mm2], w [kN/m3]: Table C8.5.I row by row, in its order.
TABLE = {
    "rubble": ((1.0, 2.0), (0.018, 0.032), None, (690, 1050), (230, 350), 19),
    "roughly_cut_stone": ((2.0, 2.0), (0.035, 0.051), None, (1020, 1440), (340, 480), 20),
    "split_stone": ((2.6, 3.8), (0.056, 0.074), None, (1500, 1980), (500, 660), 21),
    "soft_stone": ((1.4, 2.2), (0.028, 0.042), None, (900, 1260), (300, 420), 16),
    "regular_soft_stone": (
        (2.0, 3.2),
        (0.04, 0.08),
        (0.10, 0.19),
        (1200, 1620),
        (400, 500),
        16,
    ),
    "dressed_stone": ((5.8, 8.2), (0.09, 0.12), (0.18, 0.28), (2400, 3300), (800, 1100), 22),
    "solid_brick": ((2.6, 4.3), (0.05, 0.13), (0.13, 0.27), (1200, 1800), (400, 600), 18),
    "semi_solid_brick": ((5.0, 8.0), (0.08, 0.17), (0.20, 0.36), (3500, 5600), (875, 1400), 15),
}

#: The types the tower inventory has accepted since before the table was verified.
EXISTING_KEYS = (
    "rubble",
    "roughly_cut_stone",
    "split_stone",
    "soft_stone",
    "dressed_stone",
    "solid_brick",
)


def test_the_table_has_its_eight_rows_in_order_and_keeps_the_existing_keys():
    assert tuple(MASONRY_TYPES) == tuple(TABLE)
    assert set(EXISTING_KEYS) <= set(MASONRY_TYPES)


@pytest.mark.parametrize("key", list(TABLE))
def test_every_row_of_table_c8_5_i(key):
    f, tau0, fv0, e, g, w = TABLE[key]
    row = MASONRY_TYPES[key]
    assert (row.fm_min_pa, row.fm_max_pa) == pytest.approx((f[0] * MPA, f[1] * MPA))
    assert (row.tau0_min_pa, row.tau0_max_pa) == pytest.approx((tau0[0] * MPA, tau0[1] * MPA))
    if fv0 is None:
        assert row.fv0_min_pa is None and row.fv0_max_pa is None
    else:
        assert (row.fv0_min_pa, row.fv0_max_pa) == pytest.approx((fv0[0] * MPA, fv0[1] * MPA))
    assert (row.e_min_pa, row.e_max_pa) == pytest.approx((e[0] * MPA, e[1] * MPA))
    assert (row.g_min_pa, row.g_max_pa) == pytest.approx((g[0] * MPA, g[1] * MPA))
    assert row.unit_weight_n_m3 == pytest.approx(w * KN)
    assert row.density_kg_m3 == pytest.approx(w * KN / G)


def test_the_corrected_ranges():
    """The rows that were wrong before the table was verified."""
    assert (MASONRY_TYPES["dressed_stone"].fm_min_pa, MASONRY_TYPES["dressed_stone"].fm_max_pa) == (
        pytest.approx(5.8e6),
        pytest.approx(8.2e6),
    )
    assert (MASONRY_TYPES["soft_stone"].fm_min_pa, MASONRY_TYPES["soft_stone"].fm_max_pa) == (
        pytest.approx(1.4e6),
        pytest.approx(2.2e6),
    )
    # "conci sbozzati": the table's single value 2,0 (min = max); note (*)'s 1.2 not applied.
    row = MASONRY_TYPES["roughly_cut_stone"]
    assert row.fm_min_pa == row.fm_max_pa == pytest.approx(2.0e6)
    assert masonry_strength("roughly_cut_stone", "LC2") == pytest.approx(2.0e6)


def test_soft_stone_takes_the_heavier_end_of_13_to_16():
    assert MASONRY_TYPES["soft_stone"].unit_weight_n_m3 == pytest.approx(16.0e3)
    assert MASONRY_TYPES["regular_soft_stone"].unit_weight_n_m3 == pytest.approx(16.0e3)


def test_the_inventory_unit_weights_are_the_tables():
    from rockscreen.stations.inventory_columns import MASONRY_UNIT_WEIGHTS_KN_M3

    for key, w in MASONRY_UNIT_WEIGHTS_KN_M3.items():
        assert MASONRY_TYPES[key].unit_weight_n_m3 == pytest.approx(w * KN), key


# ------------------------------------------------------------------ knowledge levels, FC


def test_confidence_factors_of_c8_5_4():
    assert CONFIDENCE_FACTORS == {"LC1": 1.35, "LC2": 1.2, "LC3": 1.0}
    assert [confidence_factor(k) for k in ("LC1", " lc2 ", "LC3")] == [1.35, 1.2, 1.0]
    with pytest.raises(RiskError, match=r"knowledge_level='LC0'.*LC1, LC2, LC3"):
        confidence_factor("LC0")


@pytest.mark.parametrize("key", list(TABLE))
def test_lc1_takes_the_minimum_strength_and_lc2_the_mean(key):
    (f_min, f_max), *_ = TABLE[key]
    assert masonry_strength(key, "LC1") == pytest.approx(f_min * MPA)
    assert masonry_strength(key, "lc2") == pytest.approx(0.5 * (f_min + f_max) * MPA)


def test_strengths_by_level_literal():
    assert masonry_strength("dressed_stone", "LC1") == pytest.approx(5.8e6)
    assert masonry_strength("dressed_stone", "LC2") == pytest.approx(7.0e6)
    assert masonry_strength("soft_stone", "LC2") == pytest.approx(1.8e6)
    assert masonry_strength("semi_solid_brick", "LC2") == pytest.approx(6.5e6)


@pytest.mark.parametrize("key", list(TABLE))
@pytest.mark.parametrize("level", ["LC1", "LC2", "LC3"])
def test_every_level_takes_the_mean_elastic_modulus(key, level):
    _, _, _, (e_min, e_max), _, _ = TABLE[key]
    assert masonry_elastic_modulus(key, level) == pytest.approx(0.5 * (e_min + e_max) * MPA)
    assert MASONRY_TYPES[key].e_mean_pa == pytest.approx(0.5 * (e_min + e_max) * MPA)


def test_elastic_modulus_literal():
    assert masonry_elastic_modulus("rubble", "LC1") == pytest.approx(870.0e6)
    assert masonry_elastic_modulus("solid_brick", "LC2") == pytest.approx(1500.0e6)
    assert masonry_elastic_modulus("semi_solid_brick", "LC1") == pytest.approx(4550.0e6)


def test_lc3_takes_the_measured_value():
    assert masonry_strength("solid_brick", "LC3", measured_pa=3.1e6) == 3.1e6
    assert masonry_elastic_modulus("solid_brick", "LC3", measured_pa=1.7e9) == 1.7e9


# -------------------------------------------------------------------------- refusals


def test_lc3_strength_without_a_measured_value_is_refused():
    with pytest.raises(RiskError, match=r"LC3.*measured_pa"):
        masonry_strength("solid_brick", "LC3")


def test_an_unknown_type_is_refused_naming_the_allowed_ones():
    with pytest.raises(RiskError, match=r"masonry='marble'.*semi_solid_brick.*C8\.5\.I"):
        masonry_strength("marble", "LC1")
    with pytest.raises(RiskError, match=r"masonry_type='marble'.*rubble, roughly_cut_stone"):
        masonry_elastic_modulus("marble", "LC1")


def test_an_unknown_level_is_refused():
    with pytest.raises(RiskError, match=r"knowledge_level='LC4'.*LC1, LC2, LC3"):
        masonry_strength("rubble", "LC4")
    with pytest.raises(RiskError, match=r"knowledge_level='LC4'.*LC1, LC2, LC3"):
        masonry_elastic_modulus("rubble", "LC4")


def test_a_measured_value_is_refused_below_lc3_or_out_of_range():
    with pytest.raises(RiskError, match=r"measured_pa=.*only with knowledge_level='LC3'"):
        masonry_strength("rubble", "LC1", measured_pa=1.5e6)
    with pytest.raises(RiskError, match=r"measured_pa=.*only with knowledge_level='LC3'"):
        masonry_elastic_modulus("rubble", "LC2", measured_pa=1.0e9)
    with pytest.raises(RiskError, match=r"measured_pa=-1.*\(0, inf\] Pa"):
        masonry_elastic_modulus("rubble", "LC3", measured_pa=-1.0)
    with pytest.raises(RiskError, match=r"measured_pa='x' is not a number"):
        masonry_strength("rubble", "LC3", measured_pa="x")
