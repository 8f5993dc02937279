"""The solvers the models call (``engine/solvers.py``): the method's, or entered stand-ins."""

from __future__ import annotations

import threading
from types import SimpleNamespace

import numpy as np
import pytest

from rockscreen import solver
from rockscreen.pipeline.engine import registry
from rockscreen.pipeline.engine.cases import BlockCache
from rockscreen.pipeline.engine.loop import motion_cases
from rockscreen.pipeline.engine.motion import GroundMotion
from rockscreen.pipeline.engine.solvers import Solvers, active_solvers, use_solvers
from rockscreen.pipeline.motion.floor import modal_floor_accelerogram
from rockscreen.solver.constants import G
from rockscreen.stations.inventory import Tower

TOWER = Tower(id="T", width_m=2.0, height_m=6.0, building_height_m=10.0, base_height_m=10.0)


def test_by_default_the_models_call_the_compiled_method():
    active = active_solvers()
    assert active.real and active.method == "compiled"
    assert active.rocking is solver.solve_rocking
    assert active.double is solver.solve_double_block
    assert active.sliding is solver.solve_sliding
    assert active.floor is modal_floor_accelerogram
    assert active.block == solver.RockingBlock.from_dimensions


def test_stand_ins_are_active_inside_use_solvers_only():
    calls = []

    def rocking(block, acc, dt, **options):
        calls.append(options)
        return SimpleNamespace(overturned=False)

    model = registry.get("ground")
    with use_solvers(Solvers(rocking=rocking)) as entered:
        assert active_solvers() is entered and not entered.real
        # The ones not given are the method's.
        assert entered.double is solver.solve_double_block
        model.solve("block", np.zeros(3), 0.01, {}, history=False)
    assert calls == [{"history": False}]
    assert active_solvers().rocking is solver.solve_rocking


def test_use_solvers_nests_and_restores_on_error():
    def floor(acc, dt, **kwargs):
        return 3.0 * acc

    def other(acc, dt, **kwargs):
        return -acc

    acc = np.ones(4)
    model = registry.get("floor")
    with pytest.raises(RuntimeError), use_solvers(Solvers(floor=floor)):
        np.testing.assert_array_equal(model.excitation(TOWER, acc, 0.01), 3.0 * acc)
        with use_solvers(Solvers(floor=other)):
            np.testing.assert_array_equal(model.excitation(TOWER, acc, 0.01), -acc)
        np.testing.assert_array_equal(model.excitation(TOWER, acc, 0.01), 3.0 * acc)
        raise RuntimeError("leaves the block")
    assert active_solvers().floor is modal_floor_accelerogram


def test_a_block_cache_keeps_the_block_maker_active_when_it_was_made():
    def block(width, height, *, eta=None):
        return SimpleNamespace(width=width, height=height)

    with use_solvers(Solvers(block=block)):
        blocks = BlockCache(TOWER)
    assert blocks(2.0) == SimpleNamespace(width=2.0, height=6.0)


def test_an_unknown_method_is_refused_naming_the_allowed_ones():
    with pytest.raises(ValueError, match="'nope'.*compiled"), use_solvers(Solvers(method="nope")):
        pass


def test_another_thread_runs_the_default_method():
    seen = []
    with use_solvers(Solvers(rocking=lambda *a, **k: None)):
        thread = threading.Thread(target=lambda: seen.append(active_solvers().real))
        thread.start()
        thread.join()
    assert seen == [True]


def test_the_reference_method_runs_a_case_through_the_engine():
    # REFERENCES R9's tower on a building three times heavier, a 3 Hz harmonic along X:
    # the single block and the double block, solved by the oracle and by the compiled kernel.
    tower = Tower(id="R9", width_m=2.06, height_m=5.80, eta=0.9, tower_mass_kg=1.0e5,
                  building_mass_kg=3.0e5, mu_s=0.5, mu_k=0.4)  # fmt: skip
    dt = 0.0025
    t = np.arange(801) * dt
    motion = GroundMotion.along_tower_axes("H", 0.6 * G * np.cos(6 * np.pi * t), None, None, dt)
    models = [registry.get("ground"), registry.get("double")]
    (compiled,) = motion_cases(tower, motion, models)
    with use_solvers(Solvers(method="reference")):
        (reference,) = motion_cases(tower, motion, models)
    assert not reference.solvers.real and compiled.solvers.real
    for ref, res in zip(reference.solve("H", 5.0), compiled.solve("H", 5.0), strict=True):
        assert ref.model is res.model
        assert ref.response.overturned == res.response.overturned
        if not res.response.overturned:
            assert ref.response.theta_max == pytest.approx(res.response.theta_max, rel=5e-3)
        assert np.isnan(ref.response.friction_demand_max)
