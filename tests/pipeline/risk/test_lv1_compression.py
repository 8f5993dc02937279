"""LV1's compression term, stated where the user reads the verdict (issue 22).

The LV1 capacity of a solid shaft is ``q (b/H)(1 - sigma_0/(0.85 f_d)) g``
(docs/code_checks.md §3): a prismatic shaft whose own weight reaches the design strength's
stress block has no flexural capacity left and fails at every return period. That verdict
comes from the strength data (Table C8.5.I at the knowledge level, gamma_M = 2, F_C), not
from the earthquake, so the row carries ``lv1_compression_ratio`` and the note says so.
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from rockscreen.pipeline.risk.assess.sites import tower_sites
from rockscreen.pipeline.risk.checks import confidence_factor, design_compressive_strength
from rockscreen.pipeline.risk.checks.tower_lv1_checks import LV1_COLUMN_UNITS, lv1_columns
from rockscreen.stations.inventory import Tower

#: Rubble at LC1: f_m = 1.0 MPa, f_d = 1.0 / (2 x 1.35) MPa, 19 kN/m3 (Table C8.5.I).
RUBBLE_FD_PA = 1.0e6 / (2.0 * 1.35)
SOLID = Tower(
    id="T-RUBBLE",
    width_m=4.0,
    height_m=12.0,
    depth_m=4.0,
    lat=42.35,
    lon=13.40,
    wall_thickness_m=2.0,  # half the side: a solid section
    masonry_type="rubble",
    knowledge_level="LC1",
)


def _lv1(tower: Tower):
    """Return the LV1 columns, notes (in English) and why it was not made."""
    columns, notes, missing = lv1_columns(tower_sites([tower])[0], confidence_factor("LC1"), "LC1")
    return columns, [n.render() for n in notes], missing


def ratio_by_hand(height_m: float) -> float:
    """sigma_0 / (0.85 f_d) at the base of a solid prismatic rubble shaft."""
    return 19.0e3 * height_m / (0.85 * RUBBLE_FD_PA)


def test_the_ratio_is_the_base_stress_over_the_stress_block():
    assert design_compressive_strength(1.0e6, 1.35) == pytest.approx(RUBBLE_FD_PA)
    assert LV1_COLUMN_UNITS["lv1_compression_ratio"] == "1"
    columns, notes, missing = _lv1(SOLID)
    assert missing == []
    # the base is critical; the lumped slices put the weight above z = 0 exactly
    assert columns["lv1_compression_ratio"] == pytest.approx(ratio_by_hand(12.0), rel=1e-9)
    assert 0.5 <= columns["lv1_compression_ratio"] < 1.0
    (note,) = [n for n in notes if "own weight takes" in n]
    share = round(100 * ratio_by_hand(12.0))
    assert f"takes {share} % of its section's design strength at 0.0 m" in note
    assert "gamma_M = 2 of Circolare 2019 §C8.7.1, F_C = 1.35" in note
    assert "; " not in note  # one clause of the archive's note


def test_a_shaft_crushed_by_its_own_weight_says_why_it_fails():
    tall = replace(SOLID, height_m=18.0)  # sigma_0 = 0.342 MPa > 0.85 f_d = 0.315 MPa
    assert ratio_by_hand(18.0) > 1.0
    columns, notes, _ = _lv1(tall)
    assert columns["lv1_compression_ratio"] == pytest.approx(ratio_by_hand(18.0), rel=1e-9)
    assert columns["lv1_bound"] == "upper"  # fails at 30 y, the shortest return period
    (note,) = [n for n in notes if "crushes" in n]
    assert "no flexural capacity left" in note and "masonry_strength_mpa" in note
    # a short shaft: no compression note
    short_columns, short_notes, _ = _lv1(replace(SOLID, height_m=5.0))
    assert short_columns["lv1_compression_ratio"] < 0.5
    assert not any("own weight" in n for n in short_notes)
