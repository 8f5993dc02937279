"""The belfry model (``docs/belfry.md``): composite block, shaft-top motion, registry, oracle.

The hand calculation of the composite block is written out below; the independent check
solves a belfry case with the compiled solver and with the ``solve_ivp`` oracle of
``solver/reference`` on the same shaft-top motion, within the tolerance of the other
models' oracle tests (``tests/solver/test_reference.py``: 0.5 % on theta_max, same verdict).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from rockscreen.pipeline.config import CampaignConfig, ModelsConfig
from rockscreen.pipeline.engine import registry
from rockscreen.pipeline.engine.cases import BlockCache, screen_case
from rockscreen.pipeline.engine.models.belfry import (
    belfry_block,
    belfry_width_for,
    composite_section,
    shaft_period,
    shaft_top_motion,
)
from rockscreen.pipeline.engine.models.floor import floor_motion
from rockscreen.pipeline.engine.motion import GroundMotion
from rockscreen.pipeline.engine.registry import available_models, model_names
from rockscreen.pipeline.engine.solvers import Solvers, use_solvers
from rockscreen.pipeline.errors import InventoryError
from rockscreen.pipeline.motion.floor import modal_floor_accelerogram
from rockscreen.pipeline.screening.cases import CampaignShared, TowerTask
from rockscreen.pipeline.screening.evaluate import evaluate_tower
from rockscreen.solver import RockingBlock
from rockscreen.solver.constants import G
from rockscreen.solver.reference import reference_rocking
from rockscreen.stations.inventory import Tower, read_inventory, write_inventory

#: The oracle comparison's tolerance, as tests/solver/test_reference.py's COMPARE_RTOL.
COMPARE_RTOL = 5e-3

#: A 30 m tower, 6 m square, with a 5 m belfry on 3 m of effective pier width (60 t) and
#: 6 t of bells hanging 3.5 m above the belfry's base.
BELFRY = {
    "belfry_height_m": 5.0,
    "belfry_width_m": 3.0,
    "belfry_mass_kg": 60000.0,
    "bells_mass_kg": 6000.0,
    "bells_height_m": 3.5,
}


def belfry_tower(**extra) -> Tower:
    return Tower(id="B", width_m=6.0, height_m=30.0, **{**BELFRY, **extra})


# ------------------------------------------------------------------ the composite block


def test_composite_block_against_the_hand_calculation():
    # By hand: M = 60000 + 6000 = 66000 kg; z_G = (60000*2.5 + 6000*3.5)/66000
    # = 171000/66000 = 2.590909 m; b = 1.5 m; R = sqrt(1.5^2 + z_G^2) = 2.993795 m;
    # I_O = 60000*(3^2 + 5^2)/3 + 6000*(1.5^2 + 3.5^2) = 680000 + 87000 = 767000 kg m^2,
    # I_O/M = 11.621212 m^2; alpha = atan(1.5/z_G) = 0.524796 rad;
    # p = sqrt(9.81 R / (I_O/M)) = 1.589717 rad/s; eta = 1 - 2 M b^2/I_O = 0.612777.
    section = composite_section(3.0, 5.0, 60000.0, 6000.0, 3.5)
    assert section.mass_kg == 66000.0
    assert section.centroid_height_m == pytest.approx(2.590909091, rel=1e-9)
    assert section.radius_m == pytest.approx(2.993795236, rel=1e-9)
    assert section.inertia_per_mass_m2 == pytest.approx(11.621212121, rel=1e-9)
    block = belfry_block(3.0, 5.0, 60000.0, 6000.0, 3.5)
    assert block.alpha == pytest.approx(0.5247957717, rel=1e-9)
    assert block.p == pytest.approx(1.5897170641, rel=1e-9)
    assert block.eta == pytest.approx(0.6127770535, rel=1e-9)
    assert (block.width, block.height) == (3.0, 5.0)


@pytest.mark.parametrize(("width", "height"), [(3.0, 5.0), (1.2, 6.0), (0.8, 2.5)])
def test_a_belfry_without_bells_is_the_solid_block(width, height):
    belfry = belfry_block(width, height, 5.0e4, 0.0, 0.0)
    solid = RockingBlock.from_dimensions(width, height)
    for name in ("alpha", "radius", "inertia_per_mass", "p", "eta"):
        assert getattr(belfry, name) == pytest.approx(getattr(solid, name), rel=1e-12)


def test_bells_high_up_make_the_belfry_more_slender():
    low = belfry_block(3.0, 5.0, 6.0e4, 1.0e4, 0.5)
    high = belfry_block(3.0, 5.0, 6.0e4, 1.0e4, 4.5)
    bare = belfry_block(3.0, 5.0, 6.0e4, 0.0, 0.0)
    assert high.alpha < bare.alpha < low.alpha


# ------------------------------------------------------------------ the inventory columns


def test_the_belfry_columns_are_a_validated_group():
    tower = belfry_tower()
    assert tower.has_belfry and tower.belfry_plan_depth_m == 3.0
    assert not Tower(id="T", width_m=6.0, height_m=30.0).has_belfry
    partial = {k: v for k, v in BELFRY.items() if k != "bells_height_m"}
    with pytest.raises(InventoryError, match="bells_height_m.*belfry model needs all"):
        Tower(id="B", width_m=6.0, height_m=30.0, **partial)
    with pytest.raises(InventoryError, match="belfry_depth_m.*needs the belfry"):
        Tower(id="B", width_m=6.0, height_m=30.0, belfry_depth_m=1.0)
    # the tower's measured period is the whole tower's: LV1 reads it without a belfry too
    assert Tower(id="B", width_m=6.0, height_m=30.0, shaft_period_s=1.0).shaft_period_s == 1.0
    with pytest.raises(InventoryError, match="bells_height_m.*must lie in"):
        belfry_tower(bells_height_m=5.5)
    with pytest.raises(InventoryError, match="belfry_height_m.*less than height_m"):
        belfry_tower(belfry_height_m=30.0)
    with pytest.raises(InventoryError, match="belfry_width_m.*must not exceed width_m"):
        belfry_tower(belfry_width_m=7.0)
    with pytest.raises(InventoryError, match="belfry_width_m.*plan depth"):
        Tower(id="B", width_m=6.0, height_m=30.0, depth_m=2.0, **BELFRY)
    with pytest.raises(InventoryError, match="belfry_mass_kg.*not plausible"):
        belfry_tower(belfry_mass_kg=60.0)  # tonnes written for kilograms
    assert belfry_tower(bells_mass_kg=0.0).has_belfry  # a belfry without bells


def test_the_belfry_columns_round_trip_through_the_csv(tmp_path):
    towers = [belfry_tower(belfry_depth_m=2.5, shaft_period_s=0.9), Tower("T", 2.0, 6.0)]
    path = write_inventory(towers, tmp_path / "towers.csv")
    assert read_inventory(path) == towers


def test_the_example_belfry_inventory_reads():
    from pathlib import Path

    import rockscreen.stations

    path = Path(rockscreen.stations.__file__).parent / "data" / "example_belfries.csv"
    towers = read_inventory(path)
    assert any(t.has_belfry for t in towers) and any(not t.has_belfry for t in towers)


# ------------------------------------------------------------------ the shaft-top motion


def _record(dt: float = 0.01, seconds: float = 8.0) -> np.ndarray:
    t = np.arange(int(seconds / dt)) * dt
    return 0.15 * G * np.sin(2 * np.pi * 1.8 * t) * np.exp(-0.4 * t)


def test_the_period_is_measured_or_0_0187_H():
    assert shaft_period(belfry_tower()) == pytest.approx(0.0187 * 30.0)
    assert shaft_period(belfry_tower(shaft_period_s=0.8)) == 0.8


def test_the_base_motion_is_the_modal_floor_accelerogram_of_the_ground():
    acc, dt = _record(), 0.01
    tower = belfry_tower()
    expected = modal_floor_accelerogram(
        acc, dt, building_period=0.0187 * 30.0, mode_shape_at_base=25.0 / 30.0
    )
    np.testing.assert_allclose(shaft_top_motion(tower, acc, dt), expected, rtol=0, atol=1e-12)
    model = registry.get("belfry")
    excitation = model.excitation(tower, acc, dt)
    np.testing.assert_array_equal(excitation, shaft_top_motion(tower, acc, dt))
    measured = belfry_tower(shaft_period_s=0.8)
    np.testing.assert_allclose(
        shaft_top_motion(measured, acc, dt),
        modal_floor_accelerogram(acc, dt, building_period=0.8, mode_shape_at_base=25.0 / 30.0),
        rtol=0,
        atol=1e-12,
    )


def test_on_the_church_the_floor_motion_is_filtered_first():
    acc, dt = _record(), 0.01
    tower = belfry_tower(building_height_m=12.0, base_height_m=10.0, building_period_s=0.3)
    floor = floor_motion(tower, acc, dt)
    np.testing.assert_allclose(floor, modal_floor_accelerogram(
        acc, dt, building_period=0.3, mode_shape_at_base=10.0 / 12.0), atol=1e-12)  # fmt: skip
    expected = modal_floor_accelerogram(
        floor, dt, building_period=0.0187 * 30.0, mode_shape_at_base=25.0 / 30.0
    )
    np.testing.assert_allclose(shaft_top_motion(tower, acc, dt), expected, rtol=0, atol=1e-12)


def test_the_base_motion_goes_through_the_active_solvers():
    calls = []

    def floor(acc, dt, *, building_period, mode_shape_at_base):
        calls.append((building_period, mode_shape_at_base))
        return 2.0 * acc

    acc = np.ones(10)
    with use_solvers(Solvers(floor=floor)):
        motion = shaft_top_motion(belfry_tower(shaft_period_s=0.7), acc, 0.01)
    np.testing.assert_array_equal(motion, 2.0 * acc)
    assert calls == [(0.7, 25.0 / 30.0)]


# ------------------------------------------------------------------ the registry


def test_the_model_is_available_only_with_the_belfry_columns():
    model = registry.get("belfry")
    assert model_names().index("belfry") > model_names().index("double")
    assert model in available_models(belfry_tower(), model_names())
    assert model not in available_models(Tower(id="T", width_m=6.0, height_m=30.0), model_names())
    assert model.requires == (
        "belfry_height_m",
        "belfry_width_m",
        "belfry_mass_kg",
        "bells_mass_kg",
        "bells_height_m",
    )


def test_the_case_axis_picks_the_belfry_width_along_it():
    tower = Tower(id="R", width_m=6.0, height_m=30.0, depth_m=5.0, **BELFRY, belfry_depth_m=2.0)
    assert belfry_width_for(tower, "x") == 3.0  # along x: belfry_width_m
    assert belfry_width_for(tower, "y") == 2.0  # along y: the belfry's plan depth
    assert belfry_width_for(tower, None) == 2.0  # along neither axis: the smaller width
    with pytest.raises(ValueError, match="axis 'X' must be one of x, y or None"):
        belfry_width_for(tower, "X")
    # The case engine's block cache builds the belfry's block for that axis.
    blocks = BlockCache(tower)
    model = registry.get("belfry")
    wide, narrow = belfry_block(3.0, 5.0, 6e4, 6e3, 3.5), belfry_block(2.0, 5.0, 6e4, 6e3, 3.5)
    assert blocks(6.0, model, "x").alpha == pytest.approx(wide.alpha)
    assert blocks(5.0, model, "y").alpha == pytest.approx(narrow.alpha)
    assert blocks(5.0, model, None).alpha == pytest.approx(narrow.alpha)
    assert blocks(6.0).alpha != blocks(6.0, model, "x").alpha  # the whole tower's block
    assert blocks(6.0, None, "x") is blocks(6.0)  # the whole tower's block has no axis
    with pytest.raises(ValueError, match="block axis 'X': must be one of x, y or None"):
        blocks(6.0, model, "X")


def test_a_square_towers_belfry_is_picked_by_the_axis_not_the_width():
    # A square tower: the width (6 m both ways) cannot tell x from y; the axis does.
    square = belfry_tower(belfry_depth_m=2.0)
    assert square.width_m == square.plan_depth_m == 6.0
    model = registry.get("belfry")
    blocks = BlockCache(square)
    x, y = blocks(6.0, model, "x"), blocks(6.0, model, "y")
    assert x.alpha == pytest.approx(belfry_block(3.0, 5.0, 6e4, 6e3, 3.5).alpha)
    assert y.alpha == pytest.approx(belfry_block(2.0, 5.0, 6e4, 6e3, 3.5).alpha)
    assert blocks(6.0, model, None).alpha == pytest.approx(y.alpha)  # no axis: the safe side
    # A suite record along the tower's axes: X gets the wide belfry, Y the narrow one.
    motion = GroundMotion.along_tower_axes("P", _record(), _record(), None, 0.01)
    config = CampaignConfig(models=ModelsConfig(run=("ground", "belfry")))
    shared = CampaignShared({"P": motion}, config, Solvers().resolved())
    outcome = evaluate_tower(TowerTask(0, square, ("P",)), shared)
    rows = {(r["component"], r["model"]): r for r in outcome.rows}
    assert rows["X", "belfry"]["alpha_rad"] == pytest.approx(x.alpha)
    assert rows["Y", "belfry"]["alpha_rad"] == pytest.approx(y.alpha)


def test_run_lists_belfry_cases():
    tower = belfry_tower(building_height_m=12.0, base_height_m=10.0)
    bare = Tower(id="T", width_m=2.0, height_m=6.0)
    motion = GroundMotion.along_tower_axes("P", _record(), 0.5 * _record(), None, 0.01)
    config = CampaignConfig(models=ModelsConfig(run=model_names()))
    shared = CampaignShared({"P": motion}, config, Solvers().resolved())
    outcome = evaluate_tower(TowerTask(0, tower, ("P",)), shared)
    assert not outcome.failures
    rows = {(r["component"], r["model"]): r for r in outcome.rows}
    assert set(rows) == {(c, m) for c in "XY" for m in ("ground", "floor", "belfry")}
    belfry = belfry_block(3.0, 5.0, 60000.0, 6000.0, 3.5)
    assert rows["X", "belfry"]["alpha_rad"] == pytest.approx(belfry.alpha)
    top = shaft_top_motion(tower, _record(), 0.01)
    assert rows["X", "belfry"]["pga_m_s2"] == pytest.approx(np.max(np.abs(top)))
    bare_outcome = evaluate_tower(TowerTask(1, bare, ("P",)), shared)
    assert {r["model"] for r in bare_outcome.rows} == {"ground"}


# ------------------------------------------------------------------ the independent check


@pytest.mark.parametrize(
    ("frequency_hz", "cycles", "peak_g", "overturns"),
    [
        (1.6, 4, 0.3, False),  # near the shaft's resonance (T1 = 0.56 s): rocks
        (0.5, 1, 0.6, False),  # a long one-sine pulse: rocks to ~0.46 alpha
        (0.5, 1, 0.8, True),  # the same pulse, stronger: overturns
    ],
)
def test_the_belfry_case_agrees_with_the_oracle(frequency_hz, cycles, peak_g, overturns):
    dt = 0.005
    t = np.arange(int(8.0 / dt)) * dt
    ground = peak_g * G * np.sin(2 * np.pi * frequency_hz * t) * (t < cycles / frequency_hz)
    tower = belfry_tower()
    acc = shaft_top_motion(tower, ground, dt)
    model = registry.get("belfry")
    block = BlockCache(tower)(tower.width_m, model)
    compiled = model.solve(block, acc, dt, model.parameters_of(tower), history=False)
    belfry = belfry_block(3.0, 5.0, 60000.0, 6000.0, 3.5)
    oracle = reference_rocking(belfry.p, belfry.alpha, belfry.eta, acc, dt)
    assert compiled.alpha == pytest.approx(belfry.alpha)
    assert compiled.overturned == oracle.overturned == overturns
    if not overturns:
        assert oracle.theta_max > 0.1 * belfry.alpha  # it rocks
        assert compiled.theta_max == pytest.approx(oracle.theta_max, rel=COMPARE_RTOL)
        assert compiled.status == oracle.status


# ------------------------------------------------------------------ a known gap


def test_the_uplift_pre_check_uses_the_belfry():
    # A stocky tower (alpha 0.46) with a slender belfry (alpha 0.12): the shaft-top motion
    # lifts the belfry but stays below the tower's uplift threshold.
    tower = replace(belfry_tower(), width_m=12.0, height_m=24.0, belfry_width_m=0.8)
    model = registry.get("belfry")
    block = BlockCache(tower)(tower.width_m)
    belfry = BlockCache(tower)(tower.width_m, model)
    t = np.arange(800) * 0.01
    acc = 0.25 * G * np.sin(2 * np.pi * 1.5 * t)
    assert math.tan(belfry.alpha) * G < np.max(np.abs(acc)) < math.tan(block.alpha) * G
    verdict = screen_case(model, tower, belfry, acc, None, 0.01, 5.0)
    assert verdict.solved
