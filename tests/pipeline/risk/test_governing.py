"""assess wires the code's checks: kinematic columns, the belfry's fragility, the governing
mechanism and the "rocking only" mark (issue 22)."""

from __future__ import annotations

import math
from dataclasses import replace
from functools import partial

import pytest

from rockscreen.pipeline.execution.local import SerialExecutor
from rockscreen.pipeline.risk.assess.run import AssessOptions, run_assess
from rockscreen.pipeline.risk.checks import (
    SiteConditions,
    kinematic_check,
    lv1_tower,
    whole_tower_mechanism,
)
from rockscreen.pipeline.risk.checks.governing import MECHANISMS, governing_columns
from rockscreen.pipeline.risk.checks.registry import code_check
from rockscreen.pipeline.risk.checks.tower_checks import part_model_names
from rockscreen.pipeline.risk.checks.tower_lv1_checks import lv1_tower_model
from rockscreen.pipeline.risk.checks.tower_mechanisms import gable_kinematic_mechanism
from rockscreen.pipeline.risk.measures.classes import (
    INCOMPLETE,
    ROCKING_ONLY,
    base_class,
    class_label,
    row_class_label,
)
from rockscreen.pipeline.verdict.messages import message
from rockscreen.stations.inventory import Tower

from rockscreen_testsupport.records import suite_record
from rockscreen_testsupport.towers import lv1_shaft_tower

MESSINA = (38.1, 15.65)  # lat, lon [deg]


_record = partial(suite_record, source="test suite")


PLAIN = Tower(id="PLAIN", width_m=1.2, height_m=6.0, lat=MESSINA[0], lon=MESSINA[1])
BELFRY = Tower(
    id="BELFRY",
    width_m=3.0,
    height_m=12.0,
    lat=MESSINA[0],
    lon=MESSINA[1],
    belfry_height_m=3.0,
    belfry_width_m=1.2,
    belfry_mass_kg=20000.0,
    bells_mass_kg=1500.0,
    bells_height_m=2.0,
    shaft_period_s=0.3,
)
#: A tower with the shaft's data (LV1), its own knowledge level and a bell gable on top.
SHAFT = lv1_shaft_tower(
    "SHAFT",
    lat=MESSINA[0],
    lon=MESSINA[1],
    knowledge_level="LC2",
    gable_height_m=2.5,
    gable_width_m=2.0,
    gable_thickness_m=0.45,
    gable_base_height_m=20.0,
    gable_bells_mass_kg=400.0,
    gable_opening_ratio=0.3,
)

#: A small tower whose bells hang in a bell gable on its top (no belfry, no shaft data).
GABLE = Tower(
    id="GABLE",
    width_m=2.0,
    height_m=8.0,
    lat=MESSINA[0],
    lon=MESSINA[1],
    gable_height_m=2.0,
    gable_width_m=1.5,
    gable_thickness_m=0.4,
    gable_base_height_m=8.0,
    gable_bells_mass_kg=200.0,
)


@pytest.fixture(scope="module")
def rows():
    suite = [_record(i) for i in range(8)]
    options = AssessOptions(
        return_periods_y=(475.0, 975.0),
        selection={"n_records": 7},
        allow_noncompliant=True,
        bootstrap_resamples=0,
    )
    result = run_assess([PLAIN, BELFRY, SHAFT, GABLE], options, SerialExecutor(), suite=suite)
    return {row["id"]: row for row in result.summary}


def test_a_tower_with_belfry_data_gets_belfry_and_kinematic_columns(rows):
    row = rows["BELFRY"]
    for column in (
        "kinematic_alpha0",
        "kinematic_e_star",
        "kinematic_a0_g",
        "kinematic_linear_capacity_ag_g",
        "kinematic_nonlinear_capacity_ag_g",
        "kinematic_safety_index",
        "belfry_kinematic_alpha0",
        "tower_kinematic_alpha0",
        "belfry_fragility_median_g",
        "belfry_safety_index",
    ):
        assert math.isfinite(row[column]), column
    assert row["belfry_kinematic_alpha0"] == pytest.approx(1.2 / 3.0, rel=0.2)
    assert row["belfry_ida_n_solves"] > 0
    assert row["belfry_slv_bound"] in {"", "lower", "upper"}
    assert row["governing"]
    # the governing mechanism is the one of lowest capacity, and the class follows its I_S
    candidates = [
        row["capacity_pga_g"],
        row["belfry_capacity_ag_g"],
        row["tower_kinematic_nonlinear_capacity_ag_g"],
        row["belfry_kinematic_nonlinear_capacity_ag_g"],
    ]
    assert row["governing_capacity_ag_g"] == min(c for c in candidates if math.isfinite(c))
    # LV1 not made, said why; no "rocking only" (the belfry was checked)
    assert math.isnan(row["lv1_capacity_ag_g"]) and math.isnan(row["lv1_safety_index"])
    assert "wall_thickness_m and masonry_type" in row["checks_not_made"]
    assert not row["checks_not_made"].startswith(ROCKING_ONLY)
    assert "Circolare 2019 §C8.7.1.2.1" in row["note"]  # the kinematic checks cite their rule


def test_a_tower_without_belfry_data_is_marked_rocking_only(rows):
    row = rows["PLAIN"]
    assert row["checks_not_made"].startswith(ROCKING_ONLY)
    assert math.isnan(row["belfry_fragility_median_g"])
    assert math.isnan(row["belfry_kinematic_alpha0"])
    assert row["kinematic_mechanism"] == "whole tower"
    assert row["governing"] in {MECHANISMS["rocking"], MECHANISMS["tower_nonlinear"]}
    label = row_class_label({**row, "risk_class": "meets", "basis_compliant": True})
    # rigid whole-tower overturning alone never makes a tower meet the code
    assert label.startswith(f"{INCOMPLETE} ({ROCKING_ONLY}: ")
    assert base_class(label) == INCOMPLETE != "meets"
    assert "LV1" in label
    # an unmarked lower class: a missing check can only lower it further
    assert row_class_label({**row, "risk_class": "high", "basis_compliant": True}) == "high"


def test_lv1_and_the_gable_are_made_from_the_inventory_columns(rows):
    row = rows["SHAFT"]
    # the row's own knowledge level wins over the run's (none given here: LC1 default)
    assert row["knowledge_level"] == "LC2" and row["confidence_factor"] == 1.20
    assert "knowledge level LC2 (F_C = 1.20 divides the SLV capacity) (inventory)" in row["note"]
    # LV1 reproduced by the library on the model built from the row, both directions
    site = SiteConditions(lon_deg=row["site_lon_deg"], lat_deg=row["site_lat_deg"])
    results = [
        lv1_tower(lv1_tower_model(SHAFT, 1.20, "LC2", across=across), site)
        for across in (False, True)
    ]
    worst = min(r.capacity.ag_g for r in results)
    assert row["lv1_capacity_ag_g"] == pytest.approx(worst, rel=1e-12)
    assert row["lv1_period_s"] == pytest.approx(0.0187 * 20.0, rel=1e-12)
    assert math.isfinite(row["lv1_safety_index"])
    # the gable: an elevated mechanism at 20 m on a structure of that height, T = 0.0187 H
    mechanism, support, _ = gable_kinematic_mechanism(SHAFT)
    assert support.level_m == 20.0 and support.period_s == pytest.approx(0.374)
    check = kinematic_check(mechanism, site, fc=1.20, support=support)
    assert row["gable_kinematic_linear_capacity_ag_g"] == pytest.approx(check.linear.ag_g)
    assert row["gable_kinematic_alpha0"] == pytest.approx(check.capacity.alpha0, rel=1e-12)
    # governing: the lowest of every check made, LV1 and the gable included
    # (the gable's own rocking first: on a tie with the whole tower's IDA it drove it)
    candidates = {
        "gable rocking": row["gable_capacity_ag_g"],
        MECHANISMS["rocking"]: row["capacity_pga_g"],
        MECHANISMS["lv1"]: row["lv1_capacity_ag_g"],
        MECHANISMS["tower_nonlinear"]: row["tower_kinematic_nonlinear_capacity_ag_g"],
        MECHANISMS["gable_nonlinear"]: row["gable_kinematic_nonlinear_capacity_ag_g"],
    }
    finite = {k: v for k, v in candidates.items() if math.isfinite(v)}
    assert row["governing_capacity_ag_g"] == min(finite.values())
    assert row["governing"].split(" (a lower")[0] == min(finite, key=finite.get)
    assert row["gable_ida_n_solves"] > 0 and math.isfinite(row["gable_fragility_median_g"])
    # LV1 made, and the bells hang in a gable whose checks were made: nothing is missing
    assert not row["checks_not_made"].startswith(ROCKING_ONLY)
    assert "belfry not checked" not in row["checks_not_made"]


def test_a_bell_gable_is_the_bells_part_checked(rows):
    # no belfry, no shaft data, but a bell gable: its checks were made, so the verdict is
    # not "rigid overturning only" and a meets stays a meets (with LV1 named as not made)
    row = rows["GABLE"]
    assert math.isfinite(row["gable_kinematic_nonlinear_capacity_ag_g"])
    assert not row["checks_not_made"].startswith(ROCKING_ONLY)
    assert row["checks_not_made"].startswith("LV1 not made")
    label = row_class_label({**row, "risk_class": "meets", "basis_compliant": True})
    assert label.startswith("meets (LV1 not made")


def test_whole_tower_kinematic_reproduces_code_checks(rows):
    row = rows["PLAIN"]
    mass = 19.0e3 / 9.81 * 1.2 * 1.2 * 6.0  # the assumed rubble prism (no point masses)
    # free to vibrate: T0 = the tower's period 0.0187 H (no shaft_period_s)
    mechanism = whole_tower_mechanism(height_m=6.0, width_m=1.2, mass_kg=mass)
    mechanism = replace(mechanism, elastic_period_s=0.0187 * 6.0)
    site = SiteConditions(lon_deg=row["site_lon_deg"], lat_deg=row["site_lat_deg"])
    check = kinematic_check(mechanism, site, fc=row["confidence_factor"])
    assert row["tower_kinematic_alpha0"] == pytest.approx(check.capacity.alpha0, rel=1e-12)
    assert row["tower_kinematic_alpha0"] == pytest.approx(0.2, rel=1e-12)
    assert row["tower_kinematic_e_star"] == pytest.approx(0.75, rel=1e-12)
    assert row["tower_kinematic_a0_g"] == pytest.approx(check.capacity.a0_star_g, rel=1e-12)
    assert row["kinematic_linear_capacity_ag_g"] == pytest.approx(check.linear.ag_g, rel=1e-12)
    assert row["kinematic_nonlinear_capacity_ag_g"] == pytest.approx(
        check.nonlinear.ag_g, rel=1e-12
    )
    assert row["kinematic_linear_safety_index"] == pytest.approx(
        check.linear.safety_index, rel=1e-12
    )


def test_governing_is_the_lowest_capacity():
    row = {
        "capacity_pga_g": 0.5,
        "safety_index": 2.0,
        "slv_bound": "",
        "tower_kinematic_linear_capacity_ag_g": 0.15,
        "tower_kinematic_linear_safety_index": 0.25,
        "tower_kinematic_nonlinear_capacity_ag_g": 0.2,
        "tower_kinematic_nonlinear_safety_index": 0.4,
        "tower_kinematic_bound": "",
        "kinematic_safety_index": 0.4,
    }
    lv1 = message("not_made.lv1_columns", a="wall_thickness_m", b="masonry_type")
    out = governing_columns(row, (1.0, 0.6, 0.3), [code_check("shaft.lv1").not_made(lv1)])
    # the non-linear check is the code's verdict; the linear one only stands beside it
    assert out["governing"] == MECHANISMS["tower_nonlinear"]
    assert out["governing_safety_index"] == 0.4
    assert out["risk_class"] == "high"
    assert "Makris & Konstantinidis 2003" in out["checks_disagree"]
    assert part_model_names()  # the belfry is a part model of the registry


def test_class_label_marks():
    assert class_label("meets") == "meets"
    assert class_label("meets", True, "x") == "meets (x)"
    assert class_label("meets", False, "x") == "meets (basis not code-compliant) (x)"
    assert class_label("moderate", False, "x") == "moderate (basis not code-compliant)"


def test_a_lower_bound_is_not_said_to_govern():
    row = {
        "capacity_pga_g": 0.55,
        "safety_index": 40.0,
        "slv_bound": "",
        "tower_kinematic_nonlinear_capacity_ag_g": 0.26,
        "tower_kinematic_nonlinear_safety_index": 3.48,
        "tower_kinematic_nonlinear_bound": "lower",
    }
    out = governing_columns(row, (1.0, 0.6, 0.3), [])
    label = MECHANISMS["tower_nonlinear"]
    assert out["governing"] == f"{label} (a lower bound: not shown to govern)"
    assert out["governing_safety_index"] == 3.48 and out["governing_bound"] == "lower"
    assert out["risk_class"] == "meets"


def test_lower_bounds_everywhere_name_no_governing_mechanism():
    """Every check still holds at 2475 y: the minimum is a bound, its mechanism unknown."""
    row = {
        "capacity_pga_g": 0.77,
        "safety_index": 9.0,
        "slv_bound": "lower",
        "lv1_capacity_ag_g": 0.27,
        "lv1_safety_index": 3.48,
        "lv1_bound": "lower",
        "tower_kinematic_nonlinear_capacity_ag_g": 0.27,
        "tower_kinematic_nonlinear_safety_index": 3.48,
        "tower_kinematic_nonlinear_bound": "lower",
    }
    out = governing_columns(row, (1.0, 0.6, 0.3), [])
    assert out["governing"].endswith("(a lower bound: not shown to govern)")
    assert out["governing_bound"] == "lower" and out["risk_class"] == "meets"
