"""The bell-gable model (``docs/code_checks.md`` §1.5): its block, its base motion, the oracle.

The block is the belfry's composite section with the gable's thickness, height, masonry
mass (openings deducted) and bells at two thirds of its height; the independent check
solves a gable case with the compiled solver and with the ``solve_ivp`` oracle of
``solver/reference`` on the same floor motion, within the tolerance of the other models'
oracle tests (0.5 % on theta_max, same verdict).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rockscreen.pipeline.engine import registry
from rockscreen.pipeline.engine.cases import BlockCache, Solvers
from rockscreen.pipeline.engine.models.gable import (
    gable_base_motion,
    gable_block,
    gable_mass_kg,
    gable_support,
)
from rockscreen.pipeline.engine.registry import available_models, model_names
from rockscreen.pipeline.motion.floor import modal_floor_accelerogram
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


@pytest.mark.parametrize(
    ("frequency_hz", "cycles", "peak_g", "overturns"),
    [
        (1.0, 1, 0.20, False),  # a one-sine pulse: the gable rocks to ~0.49 alpha
        (1.0, 1, 0.30, True),  # stronger: it overturns
    ],
)
def test_the_gable_case_agrees_with_the_oracle(frequency_hz, cycles, peak_g, overturns):
    dt = 0.005
    t = np.arange(int(8.0 / dt)) * dt
    ground = peak_g * G * np.sin(2 * np.pi * frequency_hz * t) * (t < cycles / frequency_hz)
    tower = gable_tower()
    acc = gable_base_motion(tower, ground, dt)
    model = registry.get("gable")
    block = BlockCache(tower, Solvers())(tower.width_m, model)
    compiled = model.solve(
        Solvers().resolved(), block, acc, dt, model.parameters_of(tower), history=False
    )
    gable = gable_block(tower)
    oracle = reference_rocking(gable.p, gable.alpha, gable.eta, acc, dt)
    assert compiled.alpha == pytest.approx(gable.alpha)
    assert compiled.overturned == oracle.overturned == overturns
    if not overturns:
        assert oracle.theta_max > 0.1 * gable.alpha  # it rocks
        assert compiled.theta_max == pytest.approx(oracle.theta_max, rel=COMPARE_RTOL)
        assert compiled.status == oracle.status
