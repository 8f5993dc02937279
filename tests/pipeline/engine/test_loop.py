"""The case loop (``engine/loop.py``): components × models of a motion, screened or solved.

Stand-in solvers record every call, so what the loop solves, skips and scales is checked
directly; ``run``, the stripes and the IDA tests check the products on top of it.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from rockscreen.pipeline.engine.cases import Case
from rockscreen.pipeline.engine.loop import CaseFailure, motion_cases, reaches_vertical_limit
from rockscreen.pipeline.engine.motion import GroundMotion
from rockscreen.pipeline.engine.registry import available_models, model_names
from rockscreen.pipeline.engine.solvers import Solvers, use_solvers
from rockscreen.solver.constants import G
from rockscreen.solver.errors import ParameterError
from rockscreen.stations.inventory import Tower

CHURCH = Tower(id="C", width_m=2.0, height_m=6.0, building_height_m=10.0, base_height_m=10.0)
DT = 0.01


def pulse(peak_m_s2: float, vertical_m_s2: float | None = None) -> GroundMotion:
    t = np.arange(200) * DT
    shape = np.sin(2 * np.pi * 2.0 * t) * np.exp(-(((t - 1.0) / 0.3) ** 2))
    shape /= np.max(np.abs(shape))
    vertical = None if vertical_m_s2 is None else vertical_m_s2 * np.abs(shape)
    return GroundMotion.along_tower_axes("P", peak_m_s2 * shape, 0.5 * peak_m_s2 * shape,
                                         vertical, DT)  # fmt: skip


class Recorder:
    """Stand-in solvers: the rocking block overturns beyond twice its uplift threshold."""

    def __init__(self, refuse_above_m_s2: float = math.inf) -> None:
        self.solves: list[float] = []
        self.filters = 0
        self.refuse_above_m_s2 = refuse_above_m_s2

    def block(self, width, height, *, eta=None):
        return SimpleNamespace(alpha=math.atan(width / height))

    def rocking(self, block, acc, dt, **options):
        peak = float(np.max(np.abs(acc)))
        if peak > self.refuse_above_m_s2:
            raise ParameterError("the stand-in refuses this motion")
        self.solves.append(peak)
        ratio = peak / (G * math.tan(block.alpha))
        return SimpleNamespace(
            status="overturned" if ratio > 2 else "came_to_rest",
            overturned=ratio > 2,
            theta_max_over_alpha=max(0.0, ratio - 1.0),
        )

    def floor(self, acc, dt, *, building_period, mode_shape_at_base=1.0):
        self.filters += 1
        return 2.0 * acc  # the floor doubles the ground motion

    def solvers(self) -> Solvers:
        return Solvers(block=self.block, rocking=self.rocking, double=self.rocking,
                       floor=self.floor)  # fmt: skip


def church_cases(motion: GroundMotion, recorder: Recorder):
    models = available_models(CHURCH, model_names())
    assert [m.name for m in models] == ["ground", "floor"]
    # The cases keep the solvers active when they are made.
    with use_solvers(recorder.solvers()):
        return motion_cases(CHURCH, motion, models)


def test_the_cases_are_the_components_times_the_models():
    recorder = Recorder()
    components = church_cases(pulse(4.0), recorder)
    assert [c.name for c in components] == ["X", "Y"]
    verdict = components[0].screen(free_motion_s=5.0)
    assert [c.model.name for c in verdict.cases] == ["ground", "floor"]
    assert verdict.n_solves == len(recorder.solves) == 2


def test_excitations_are_built_once_at_scale_1_and_scaled():
    recorder = Recorder()
    x, _ = church_cases(pulse(4.0), recorder)
    for factor in (1.0, 1.5, 2.0):
        x.screen(factor, free_motion_s=5.0)
    # One floor filter for the component, whatever the number of factors screened.
    assert recorder.filters == 1
    ground, floor = recorder.solves[0::2], recorder.solves[1::2]
    assert ground == pytest.approx([4.0, 6.0, 8.0])
    assert floor == pytest.approx([8.0, 12.0, 16.0])


def test_a_motionless_case_is_screened_without_a_solve_but_solved_in_full():
    recorder = Recorder()
    x, _ = church_cases(pulse(0.01), recorder)
    verdict = x.screen(free_motion_s=5.0)
    assert [c.verdict.status for c in verdict.cases] == ["no_motion", "no_motion"]
    assert verdict.n_solves == 0 and recorder.solves == []
    assert verdict.worst == 0.0 and not verdict.overturned
    cases = x.solve("P", 5.0)
    assert all(isinstance(c, Case) for c in cases) and len(recorder.solves) == 2


def test_stop_at_first_stops_at_the_first_overturning_model():
    # g tan(alpha) = 3.27 m/s2: the ground case overturns beyond 6.5 m/s2.
    recorder = Recorder()
    x, _ = church_cases(pulse(8.0), recorder)
    first = x.screen(free_motion_s=5.0, stop_at_first=True)
    assert [c.model.name for c in first.cases] == ["ground"]
    assert first.overturned and first.worst == math.inf and first.n_solves == 1
    every = x.screen(free_motion_s=5.0)
    assert every.overturned_models == {"ground", "floor"} and every.n_solves == 2


def test_a_vertical_reaching_g_leaves_every_case_unsolved():
    recorder = Recorder()
    x, y = church_cases(pulse(4.0, vertical_m_s2=-0.6 * G), recorder)
    assert not x.screen(free_motion_s=5.0).vertical_limit
    recorder.solves.clear()
    for component in (x, y):
        verdict = component.screen(2.0, free_motion_s=5.0)
        assert verdict.vertical_limit and verdict.limited and verdict.n_solves == 0
        assert [c.verdict.status for c in verdict.cases] == ["vertical_limit"] * 2
        assert all(math.isnan(c.verdict.theta_max_over_alpha) for c in verdict.cases)
    assert recorder.solves == []
    assert reaches_vertical_limit(np.array([0.0, -G])) and not reaches_vertical_limit(None)


def test_a_solver_refusal_is_the_models_limit_when_screened_and_a_failure_when_solved():
    recorder = Recorder(refuse_above_m_s2=5.0)  # the floor's 2 x 4 m/s2 is refused
    x, _ = church_cases(pulse(4.0), recorder)
    verdict = x.screen(free_motion_s=5.0, stop_at_first=True)
    assert [c.verdict.status for c in verdict.cases] == ["came_to_rest", "vertical_limit"]
    assert verdict.limited and not verdict.vertical_limit and not verdict.overturned
    ground, floor = x.solve("P", 5.0)
    assert isinstance(ground, Case) and ground.response.status == "came_to_rest"
    assert isinstance(floor, CaseFailure) and floor.model.name == "floor"
    assert isinstance(floor.error, ParameterError) and floor.component == "X"
