"""The LV1 tower model of a tower standing on a church: the church's floor spectrum.

docs/code_checks.md §3: the demand is the Circolare 2019 floor spectrum ``S_eZ(T1, z)``
(§C7.2.3, [C7.2.5]-[C7.2.10]) of the church at the tower's springing, the church elastic
(``T_k`` its period, ``xi_k`` = 5 %), never below the ground's ``Se(T1)``.
"""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

from rockscreen.pipeline.risk.assess.sites import tower_sites
from rockscreen.pipeline.risk.checks import (
    ElevatedSupport,
    ShaftSegment,
    SiteConditions,
    TowerModel,
    design_compressive_strength,
    lv1_demand,
    lv1_tower,
    masonry_strength,
)
from rockscreen.pipeline.risk.checks.floor_spectrum import (
    StructureState,
    floor_spectral_acceleration,
)
from rockscreen.pipeline.risk.checks.tower_lv1_checks import lv1_columns, lv1_tower_model
from rockscreen.pipeline.risk.checks.tower_mechanisms import tower_support
from rockscreen.solver.constants import G
from rockscreen.stations.inventory import Tower

from rockscreen_testsupport.towers import lv1_shaft_tower

#: L'Aquila (lon, lat), a high-hazard site inside the NTC grid.
LAQUILA = (13.40, 42.35)
SITE = SiteConditions(*LAQUILA)
#: A hollow brick shaft of 20 m on the ground: T1 = 0.0187 x 20 = 0.374 s.
GROUND = lv1_shaft_tower("LV1", lat=LAQUILA[1], lon=LAQUILA[0])
T1 = 0.0187 * 20.0


def _on_church(height_m: float, level_m: float, period_s: float | None) -> Tower:
    return replace(
        GROUND, building_height_m=height_m, base_height_m=level_m, building_period_s=period_s
    )


def _lv1(tower: Tower, lang: str | None = "en") -> tuple[dict, list]:
    """Return the LV1 columns and notes, rendered in ``lang`` (None: the messages)."""
    columns, notes, missing = lv1_columns(tower_sites([tower])[0], 1.20, "LC2")
    assert missing == []
    return columns, notes if lang is None else [n.render(lang) for n in notes]


@pytest.mark.parametrize(
    ("height_m", "level_m", "period_s"),
    [
        (12.0, 4.0, 0.39),  # the church's period near the tower's: on the plateau
        (12.0, 8.0, None),  # 0.0187 H = 0.22 s
        (12.0, 3.0, 0.10),  # a stiff church, low springing
        (12.0, 6.0, 2.00),  # a flexible church: T1 on the floor spectrum's rising branch
        (12.0, 0.0, 0.39),  # springing at the church's foundation: psi = 0
    ],
)
def test_lv1_on_a_church_is_never_above_the_same_tower_on_the_ground(height_m, level_m, period_s):
    ground, _ = _lv1(GROUND)
    church, _ = _lv1(_on_church(height_m, level_m, period_s))
    assert church["lv1_period_s"] == ground["lv1_period_s"] == pytest.approx(T1)
    assert church["lv1_capacity_ag_g"] <= ground["lv1_capacity_ag_g"]
    assert church["lv1_safety_index"] <= ground["lv1_safety_index"]


def test_lv1_on_a_church_of_a_period_near_the_towers_is_strictly_lower():
    ground, _ = _lv1(GROUND)
    near, _ = _lv1(_on_church(12.0, 4.0, 0.39))  # T1 / T_k = 0.96, on [0.8, 1.1]
    assert near["lv1_bound"] == ""
    assert near["lv1_capacity_ag_g"] < 0.75 * ground["lv1_capacity_ag_g"]
    assert near["lv1_safety_index"] < ground["lv1_safety_index"]
    # the stiff church and the springing at its foundation leave the ground's demand
    for tower in (_on_church(12.0, 3.0, 0.10), _on_church(12.0, 0.0, 0.39)):
        same, _ = _lv1(tower)
        assert same["lv1_capacity_ag_g"] == ground["lv1_capacity_ag_g"]


def test_lv1_demand_on_a_church_by_hand_against_the_floor_spectrum():
    support = ElevatedSupport(12.0, 0.39, level_m=4.0)
    hazard = SITE.hazard(475.0)
    se_t1 = SITE.spectral_acceleration(T1, hazard)
    se_tk = SITE.spectral_acceleration(0.39, hazard)
    structure = StructureState(height_m=12.0, level_m=4.0, period_s=0.39, damping=0.05)
    floor = float(floor_spectral_acceleration([T1], hazard, SITE, structure, 0.05)[0])
    assert lv1_demand(T1, hazard, SITE, support) == pytest.approx(max(floor, se_t1), rel=1e-12)
    # [C7.2.6] on the plateau (0.8 T_k <= T1 < 1.1 T_k): S_eZ = A a_Z, A = 1.1 xi_k^-0.5
    # (eta = 1 at 5 %), a_Z = Se(T_k) gamma psi sqrt(1 + 0.0004 xi_k^2) ([C7.2.7]-[C7.2.10],
    # gamma = 1.5 for a cantilever, psi = z / H, xi_k = 5 in percent under the root).
    assert 0.8 * 0.39 <= T1 < 1.1 * 0.39
    by_hand = 1.1 / math.sqrt(0.05) * se_tk * 1.5 * (4.0 / 12.0) * math.sqrt(1.0 + 0.0004 * 25)
    assert floor == pytest.approx(by_hand, rel=1e-12)
    assert by_hand > se_t1  # the floor spectrum governs here, not the ground's bound
    assert lv1_demand(T1, hazard, SITE, support) == pytest.approx(by_hand, rel=1e-12)
    # on the ground: Se(T1)
    assert lv1_demand(T1, hazard, SITE) == se_t1


def test_lv1_capacity_on_a_church_holds_the_floor_spectrum_at_equality():
    tower = _on_church(12.0, 4.0, 0.39)
    support, _ = tower_support(tower)
    assert (support.height_m, support.period_s, support.level_m) == (12.0, 0.39, 4.0)
    result = lv1_tower(lv1_tower_model(tower, 1.20, "LC2"), SITE, period_s=T1, support=support)
    assert result.demand_rule == "floor spectrum" and result.support is support
    cap = result.capacity
    assert cap.bound == ""
    hazard = SITE.hazard(cap.return_period_y)
    structure = support.state(ultimate=False)
    assert (structure.period_s, structure.damping) == (0.39, 0.05)
    floor = float(floor_spectral_acceleration([T1], hazard, SITE, structure, 0.05)[0])
    assert max(floor, SITE.spectral_acceleration(T1, hazard)) == pytest.approx(
        result.se_slv_m_s2, rel=1e-5
    )
    # assess reports the same capacity (the worse of the two plan directions)
    columns, _ = _lv1(tower)
    worst = min(
        lv1_tower(
            lv1_tower_model(tower, 1.20, "LC2", across=a), SITE, period_s=T1, support=support
        ).capacity.ag_g
        for a in (False, True)
    )
    assert columns["lv1_capacity_ag_g"] == pytest.approx(worst, rel=1e-12)


def test_lv1_note_says_the_church_floor_spectrum_was_used():
    _, notes = _lv1(_on_church(12.0, 4.0, 0.39))
    text = "; ".join(notes)
    assert "ground's spectrum" not in text and "not counted" not in text
    assert "LV1 demand: the Circolare 2019 floor spectrum S_eZ(T1, z) of the church" in text
    assert "§C7.2.3, [C7.2.5]-[C7.2.10]" in text
    assert "church H = 12 m, T_k = 0.39 s (building_period_s)" in text
    assert "springing z = 4 m (base_height_m)" in text and "T1 = 0.37 s" in text
    assert "never below the ground's Se(T1)" in text
    _, notes = _lv1(_on_church(12.0, 8.0, None))
    assert "T_k = 0.22 s (0.0187 H of the church, assumed: no building_period_s)" in "; ".join(
        notes
    )
    _, notes = _lv1(GROUND)
    assert not any("floor spectrum" in note for note in notes)


def test_lv1_church_note_reads_in_italian_on_the_report():
    _, notes = _lv1(_on_church(12.0, 4.0, 0.39), "it")
    italian = "; ".join(notes)
    assert "domanda LV1: lo spettro di piano della Circolare 2019 S_eZ(T1, z)" in italian
    assert "chiesa H = 12 m, T_k = 0,39 s (building_period_s)" in italian
    assert "all'imposta della torre z = 4 m (base_height_m)" in italian
    assert "LV1 demand" not in italian and "LV1 tower model" not in italian


def test_lv1_worked_example_on_a_church():
    """docs/code_checks.md §6.4: the solid shaft of §6.3 springing at 4 m on a 12 m church."""
    fd = design_compressive_strength(masonry_strength("solid_brick", "LC2"), 1.20)
    model = TowerModel((ShaftSegment(20.0, 4.0, 4.0, 2.0, density_kg_m3=18.0e3 / G),), fd)
    support = ElevatedSupport(12.0, 0.39, level_m=4.0)
    ground, church = lv1_tower(model, SITE), lv1_tower(model, SITE, support=support)
    assert church.se_slv_m_s2 == ground.se_slv_m_s2  # the capacity ignores the support
    assert church.se_slv_m_s2 / G == pytest.approx(0.4232225, rel=1e-6)
    cap = church.capacity
    hazard = SITE.hazard(cap.return_period_y)
    ratio = 1.1 / math.sqrt(0.05) * 1.5 * (4.0 / 12.0) * math.sqrt(1.0 + 0.0004 * 5.0**2)
    assert ratio == pytest.approx(2.47194, rel=1e-5)
    se_tk = SITE.spectral_acceleration(0.39, hazard)
    assert lv1_demand(T1, hazard, SITE, support) == pytest.approx(ratio * se_tk, rel=1e-12)
    assert ratio * se_tk > SITE.spectral_acceleration(T1, hazard)  # the bound does not bind
    assert se_tk / G == pytest.approx(0.171, abs=5e-4)
    assert cap.return_period_y == pytest.approx(48.0, abs=0.5)
    assert cap.ag_g == pytest.approx(0.102, abs=5e-4)
    assert cap.safety_index == pytest.approx(0.068, abs=5e-4)
    assert ground.capacity.ag_g == pytest.approx(0.209, abs=5e-4)  # §6.3
