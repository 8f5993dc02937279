"""The bell-gable model (``docs/code_checks.md`` §1.5): its block, its base motion, the oracle.

The block is the belfry's composite section with the gable's height, masonry mass
(openings deducted) and bells at two thirds of its height, on its thickness out of its
plane and, across the inventory's ``gable_axis``, on its piers' width in its plane; the
independent check solves a gable case (both blocks) with the compiled solver and with the
``solve_ivp`` oracle of ``solver/reference`` on the same floor motion, within the tolerance
of the other models' oracle tests (0.5 % on theta_max, same verdict).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rockscreen.pipeline.config import CampaignConfig, ModelsConfig
from rockscreen.pipeline.engine import registry
from rockscreen.pipeline.engine.cases import BlockCache
from rockscreen.pipeline.engine.models.belfry import belfry_block
from rockscreen.pipeline.engine.models.gable import (
    gable_base_motion,
    gable_block,
    gable_block_note,
    gable_mass_kg,
    gable_support,
    gable_width_for,
)
from rockscreen.pipeline.engine.motion import GroundMotion
from rockscreen.pipeline.engine.registry import available_models, model_names
from rockscreen.pipeline.engine.solvers import Solvers
from rockscreen.pipeline.motion.floor import modal_floor_accelerogram
from rockscreen.pipeline.risk.checks.tower_checks import part_block_notes
from rockscreen.pipeline.screening.cases import CampaignShared, TowerTask
from rockscreen.pipeline.screening.evaluate import evaluate_tower
from rockscreen.solver.constants import G
from rockscreen.solver.reference import reference_rocking
from rockscreen.stations.inventory import Tower

#: The oracle comparison's tolerance, as tests/solver/test_reference.py's COMPARE_RTOL.
COMPARE_RTOL = 5e-3

#: A rubble bell gable 3 m high, 2 m wide, 0.5 m thick, a quarter openings, 300 kg of bells,
#: on top of a 9 m facade (docs/code_checks.md §6.2).
GABLE = {
    "gable_height_m": 3.0,
    "gable_width_m": 2.0,
    "gable_thickness_m": 0.5,
    "gable_base_height_m": 9.0,
    "gable_bells_mass_kg": 300.0,
    "gable_opening_ratio": 0.25,
}


def gable_tower(**extra) -> Tower:
    return Tower(id="G", width_m=6.0, height_m=12.0, **{**GABLE, **extra})


def test_the_block_against_the_hand_calculation():
    tower = gable_tower()
    mass = 19.0e3 / 9.81 * 3.0 * 2.0 * 0.5 * 0.75
    assert gable_mass_kg(tower) == pytest.approx(mass, rel=1e-12)  # 4,357.80 kg
    assert gable_mass_kg(gable_tower(masonry_type="solid_brick")) == pytest.approx(
        mass * 18.0 / 19.0, rel=1e-12
    )
    # the composite: z_G = (m h/2 + m_c 2h/3)/M, R = hypot(t/2, z_G),
    # I_O = m (t^2 + h^2)/3 + m_c ((t/2)^2 + (2h/3)^2)
    m, mc, t, h = mass, 300.0, 0.5, 3.0
    z_g = (m * h / 2 + mc * 2 * h / 3) / (m + mc)
    radius = math.hypot(t / 2, z_g)
    inertia = m * (t**2 + h**2) / 3 + mc * ((t / 2) ** 2 + (2 * h / 3) ** 2)
    block = gable_block(tower)
    assert block.alpha == pytest.approx(math.asin((t / 2) / radius), rel=1e-12)
    assert block.p == pytest.approx(math.sqrt(G * radius / (inertia / (m + mc))), rel=1e-12)
    assert gable_block(tower, 6.0) is gable_block(tower, 2.0)  # one block in every direction


def test_the_base_motion_is_the_floor_motion_at_the_gables_base():
    dt = 0.01
    acc = np.sin(np.arange(600) * dt * 2 * np.pi * 2.0)
    # on a structure as high as its base: T1 = 0.0187 z, the gable at its top
    tower = gable_tower()
    assert gable_support(tower) == pytest.approx((9.0, 0.0187 * 9.0, 9.0))
    expected = modal_floor_accelerogram(
        acc, dt, building_period=0.0187 * 9.0, mode_shape_at_base=1.0
    )
    np.testing.assert_allclose(gable_base_motion(tower, acc, dt), expected, atol=1e-12)
    # on the church: its period and the mode shape at the gable's base
    church = gable_tower(building_height_m=12.0, base_height_m=12.0, building_period_s=0.3)
    assert gable_support(church) == (12.0, 0.3, 9.0)
    np.testing.assert_allclose(
        gable_base_motion(church, acc, dt),
        modal_floor_accelerogram(acc, dt, building_period=0.3, mode_shape_at_base=0.75),
        atol=1e-12,
    )
    # on the ground: the ground's motion
    ground = gable_tower(gable_base_height_m=0.0)
    assert gable_support(ground) is None
    np.testing.assert_array_equal(gable_base_motion(ground, acc, dt), acc)


def test_the_model_runs_only_with_the_gable_columns():
    model = registry.get("gable")
    assert model_names().index("gable") > model_names().index("belfry")
    assert model in available_models(gable_tower(), model_names())
    assert model not in available_models(Tower(id="T", width_m=6.0, height_m=30.0), model_names())
    assert model.own_block is not None  # a part model: its own IDA and fragility in assess


def test_the_gable_axis_gives_the_thickness_along_it_and_the_piers_width_across_it():
    tower = gable_tower(gable_axis="x")  # the gable's plane is along y: it overturns along x
    blocks, model = BlockCache(tower), registry.get("gable")
    thickness, in_plane = gable_block(tower), gable_block(tower, 6.0, "y")
    assert gable_width_for(tower, "x") == 0.5  # out of its plane: its thickness
    assert gable_width_for(tower, "y") == pytest.approx(2.0 * 0.75)  # the piers' width
    assert gable_width_for(tower, None) == 0.5  # along neither axis: the safe side
    # The in-plane block: the belfry's composite of the piers' width, same mass and bells.
    expected = belfry_block(1.5, 3.0, gable_mass_kg(tower), 300.0, 2.0)
    assert (in_plane.alpha, in_plane.p) == pytest.approx((expected.alpha, expected.p), rel=1e-12)
    assert in_plane.alpha > thickness.alpha  # stockier in its plane
    assert blocks(6.0, model, "x").alpha == pytest.approx(thickness.alpha, rel=1e-12)
    assert blocks(6.0, model, "y").alpha == pytest.approx(in_plane.alpha, rel=1e-12)
    assert blocks(6.0, model, None).alpha == pytest.approx(thickness.alpha, rel=1e-12)
    # The other way round: the plane along x, in-plane along x.
    other = BlockCache(gable_tower(gable_axis="y"))
    assert other(6.0, model, "x").alpha == pytest.approx(in_plane.alpha, rel=1e-12)
    assert other(6.0, model, "y").alpha == pytest.approx(thickness.alpha, rel=1e-12)
    with pytest.raises(ValueError, match="axis 'X' must be one of x, y"):
        gable_width_for(tower, "X")


def test_without_a_gable_axis_the_gable_rocks_on_its_thickness_in_both_directions():
    tower = gable_tower()
    blocks, model = BlockCache(tower), registry.get("gable")
    thickness = gable_block(tower)
    for axis in ("x", "y", None):
        assert gable_width_for(tower, axis) == 0.5
        assert blocks(6.0, model, axis).alpha == pytest.approx(thickness.alpha, rel=1e-12)


def test_the_note_states_the_gables_blocks():
    assert gable_block_note(gable_tower()).render() == (
        "bell gable rocking: on its thickness 0.50 m in every direction (no gable_axis in the "
        "inventory: the safe side, which overstates its response in its plane)"
    )
    said = gable_block_note(gable_tower(gable_axis="y"))
    note = said.render()
    assert note.startswith("bell gable rocking: on its thickness 0.50 m along y (gable_axis")
    assert "piers' width 1.50 m along x (in its plane, assumed a frame of piers" in note
    # assess's note has it when the gable model ran (the belfry has nothing to add).
    tower = gable_tower(gable_axis="y")
    assert part_block_notes(tower, ["belfry", "gable"]) == [said]
    assert part_block_notes(tower, []) == []


def _one_sine(frequency_hz: float, cycles: int, peak_g: float, dt: float) -> np.ndarray:
    t = np.arange(int(8.0 / dt)) * dt
    return peak_g * G * np.sin(2 * np.pi * frequency_hz * t) * (t < cycles / frequency_hz)


def test_run_gives_the_in_plane_block_only_along_the_tower_axes():
    tower = gable_tower(gable_axis="x")
    config = CampaignConfig(models=ModelsConfig(run=("ground", "gable")))
    thickness, in_plane = gable_block(tower), gable_block(tower, 6.0, "y")
    record = _one_sine(1.0, 1, 0.05, 0.01)
    # A suite record along the tower's axes: X out of the gable's plane, Y in it.
    along = GroundMotion.along_tower_axes("P", record, record, None, 0.01)
    # A recorded motion the tower (no azimuth) cannot rotate: the thickness both ways.
    recorded = GroundMotion(
        "IT.XX..HN", "IT.XX", 0.01, ("HNN", "HNE"), (record, record), (0.0, 90.0)
    )
    shared = CampaignShared({"P": along, "R": recorded}, config, Solvers().resolved())
    outcome = evaluate_tower(TowerTask(0, tower, ("P", "R")), shared)
    assert not outcome.failures
    rows = {(r["record_id"], r["component"], r["model"]): r for r in outcome.rows}
    assert rows["P", "X", "gable"]["alpha_rad"] == pytest.approx(thickness.alpha)
    assert rows["P", "Y", "gable"]["alpha_rad"] == pytest.approx(in_plane.alpha)
    for component in ("N", "E"):
        assert rows["R", component, "gable"]["alpha_rad"] == pytest.approx(thickness.alpha)


@pytest.mark.parametrize(
    ("frequency_hz", "cycles", "peak_g", "axis", "outcome"),
    [
        (1.0, 1, 0.20, None, "rocks"),  # a one-sine pulse: the gable rocks to ~0.49 alpha
        (1.0, 1, 0.30, None, "overturns"),  # stronger: it overturns
        (1.0, 1, 0.30, "y", "rests"),  # in its plane (gable_axis x) it does not even uplift
        (1.0, 1, 0.65, "y", "rocks"),  # stronger: it rocks in its plane
        (1.0, 1, 0.80, "y", "overturns"),  # stronger still: it overturns in its plane
    ],
)
def test_the_gable_case_agrees_with_the_oracle(frequency_hz, cycles, peak_g, axis, outcome):
    dt = 0.005
    ground = _one_sine(frequency_hz, cycles, peak_g, dt)
    tower = gable_tower(gable_axis="x")
    acc = gable_base_motion(tower, ground, dt)
    model = registry.get("gable")
    block = BlockCache(tower)(tower.width_m, model, axis)
    compiled = model.solve(block, acc, dt, model.parameters_of(tower), history=False)
    gable = gable_block(tower, tower.width_m, axis)
    oracle = reference_rocking(gable.p, gable.alpha, gable.eta, acc, dt)
    assert compiled.alpha == pytest.approx(gable.alpha)
    assert compiled.overturned == oracle.overturned == (outcome == "overturns")
    if outcome == "rocks":
        assert oracle.theta_max > 0.1 * gable.alpha
    if outcome != "overturns":
        assert compiled.theta_max == pytest.approx(oracle.theta_max, rel=COMPARE_RTOL)
        assert compiled.status == oracle.status
