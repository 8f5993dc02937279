"""Bad parameters raise ParameterError naming the parameter, the value and the range."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rockscreen.solver import (
    ParameterError,
    RockingBlock,
    critical_friction_for_rocking,
    solve_double_block,
    solve_rocking,
    solve_sliding,
)

BLOCK = RockingBlock.from_dimensions(2.0, 6.0)
ACC = np.zeros(10)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"width": 0.0, "height": 6.0}, "width=0.0 m must be"),
        ({"width": -1.0, "height": 6.0}, "width=-1.0"),
        ({"width": 2.0, "height": 0.0}, "height=0.0"),
        ({"width": 2.0, "height": math.nan}, "height=nan"),
        ({"width": 2.0, "height": 6.0, "eta": 0.0}, r"eta=0.0 must be in \(0, 1\]"),
        ({"width": 2.0, "height": 6.0, "eta": 1.2}, "eta=1.2"),
    ],
)
def test_bad_dimensions(kwargs, match):
    with pytest.raises(ParameterError, match=match):
        RockingBlock.from_dimensions(**kwargs)


@pytest.mark.parametrize(
    ("p", "alpha", "match"),
    [(0.0, 0.2, "p=0.0"), (2.0, 0.0, "alpha=0.0"), (2.0, 1.6, "alpha=1.6"), (-1, 0.2, "p=-1")],
)
def test_bad_p_alpha(p, alpha, match):
    with pytest.raises(ParameterError, match=match):
        RockingBlock.from_p_alpha(p, alpha)


def test_bad_section():
    with pytest.raises(ParameterError, match="inertia_per_mass"):
        RockingBlock.from_section(2.0, 6.0, inertia_per_mass=1.0)
    with pytest.raises(ParameterError, match="radius"):
        RockingBlock.from_section(2.0, 6.0, radius=0.5)


def test_friction_order():
    with pytest.raises(ParameterError, match="mu_k=0.5 must not exceed mu_s=0.3"):
        solve_sliding(ACC, 0.01, mu_s=0.3, mu_k=0.5)
    with pytest.raises(ParameterError, match="mu_s=-0.1"):
        solve_double_block(BLOCK, ACC, 0.01, tower_mass=1, building_mass=10, mu_s=-0.1, mu_k=-0.2)


@pytest.mark.parametrize("dt", [0.0, -0.01, math.nan, math.inf])
def test_bad_dt(dt):
    with pytest.raises(ParameterError, match="dt="):
        solve_rocking(BLOCK, ACC, dt)


def test_nan_in_record():
    acc = ACC.copy()
    acc[3] = np.nan
    with pytest.raises(ParameterError, match=r"acc\[3\]=nan"):
        solve_rocking(BLOCK, acc, 0.01)
    with pytest.raises(ParameterError, match=r"acc\[3\]"):
        solve_sliding(acc, 0.01, mu_s=0.3, mu_k=0.2)


def test_bad_arrays():
    with pytest.raises(ParameterError, match="non-empty 1-D"):
        solve_rocking(BLOCK, np.zeros((3, 3)), 0.01)
    with pytest.raises(ParameterError, match="non-empty 1-D"):
        solve_rocking(BLOCK, [], 0.01)
    with pytest.raises(ParameterError, match="acc_v has 5 samples"):
        solve_rocking(BLOCK, ACC, 0.01, acc_v=np.zeros(5))
    with pytest.raises(ParameterError, match="above -g"):
        solve_rocking(BLOCK, ACC, 0.01, acc_v=np.full(10, -10.0))


def test_bad_masses_and_block():
    with pytest.raises(ParameterError, match="tower_mass=0"):
        solve_double_block(BLOCK, ACC, 0.01, tower_mass=0, building_mass=1, mu_s=1, mu_k=1)
    with pytest.raises(ParameterError, match="block must be a RockingBlock"):
        solve_rocking("tower", ACC, 0.01)
    with pytest.raises(ParameterError, match="theta0"):
        solve_rocking(BLOCK, ACC, 0.01, theta0=2.0)


def test_unknown_keyword_is_named():
    with pytest.raises(TypeError, match="solve_rocking.*'max_free_tim'.*max_free_time"):
        solve_rocking(BLOCK, ACC, 0.01, max_free_tim=5.0)
    with pytest.raises(TypeError, match="solve_double_block.*'linearized'"):
        solve_double_block(
            BLOCK, ACC, 0.01, tower_mass=1, building_mass=10, mu_s=1, mu_k=1, linearized=True
        )


def test_critical_friction_domain():
    with pytest.raises(ParameterError, match="accel_ratio"):
        critical_friction_for_rocking(0.1, 0.25)
