"""Repeated solves of one record: ``scale``, ``friction_demand=False`` and ``BaseMotion``."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rockscreen.solver import ParameterError, RockingBlock, solve_double_block, solve_rocking
from rockscreen.solver.constants import G
from rockscreen.solver.rocking import BaseMotion, base_motion

DT = 0.01
BLOCK = RockingBlock.from_dimensions(1.0, 6.0)


def _record(seed=7, n=1500):
    """A decaying random accelerogram [m/s^2] that makes the 1 x 6 m block rock."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) * DT
    envelope = np.exp(-(((t - 3.0) / 2.0) ** 2))
    horizontal = 2.5 * envelope * np.sin(2.0 * np.pi * 1.3 * t) + envelope * rng.normal(size=n)
    vertical = 0.3 * envelope * rng.normal(size=n)
    return horizontal, vertical


def _same(a, b):
    assert a.status == b.status
    assert a.theta_max == b.theta_max
    assert a.n_impacts == b.n_impacts
    assert np.array_equal(a.impact_times, b.impact_times)
    assert a.slip_max == b.slip_max


@pytest.mark.parametrize("factor", [0.6, 1.0, 1.7, 3.0])
def test_scale_equals_the_multiplied_record(factor):
    acc, acc_v = _record()
    scaled = solve_rocking(BLOCK, acc, DT, acc_v=acc_v, scale=factor, history=False)
    plain = solve_rocking(BLOCK, acc * factor, DT, acc_v=acc_v * factor, history=False)
    _same(scaled, plain)
    assert scaled.friction_demand_max == plain.friction_demand_max
    assert scaled.uplifted


def test_scale_on_the_double_block():
    acc, acc_v = _record(seed=3)
    kwargs = {"tower_mass": 1.0, "building_mass": 20.0, "mu_s": 0.2, "mu_k": 0.15}
    scaled = solve_double_block(BLOCK, acc, DT, acc_v=acc_v, scale=2.0, **kwargs)
    plain = solve_double_block(BLOCK, 2.0 * acc, DT, acc_v=2.0 * acc_v, **kwargs)
    _same(scaled, plain)
    assert scaled.slipped
    assert np.array_equal(scaled.theta, plain.theta)
    assert np.array_equal(scaled.u, plain.u)


def test_without_friction_demand_only_the_demand_changes():
    acc, acc_v = _record()
    on = solve_rocking(BLOCK, acc, DT, acc_v=acc_v)
    off = solve_rocking(BLOCK, acc, DT, acc_v=acc_v, friction_demand=False)
    _same(on, off)
    assert np.array_equal(on.theta, off.theta)
    assert on.friction_demand_max > 0.0
    assert math.isnan(off.friction_demand_max)


def test_friction_demand_at_rest_is_the_peak_ratio():
    acc = np.array([0.0, 0.2, -0.5, 0.1, 0.0])
    res = solve_rocking(BLOCK, acc, DT, scale=2.0)
    assert res.status == "no_motion"
    assert res.friction_demand_max == pytest.approx(1.0 / G)


def test_base_motion_gives_the_same_result_and_is_private():
    acc, acc_v = _record()
    motion = base_motion(acc, DT, acc_v)
    assert isinstance(motion, BaseMotion)
    assert not motion.acc.flags.writeable
    assert motion.acc_v_min == acc_v.min()
    expected = solve_rocking(BLOCK, acc, DT, acc_v=acc_v, scale=1.5)
    acc[:] = 0.0  # changing the caller's array does not change the checked motion
    _same(solve_rocking(BLOCK, motion, DT, scale=1.5), expected)


def test_base_motion_is_checked_once_and_matched():
    acc, acc_v = _record()
    with pytest.raises(ParameterError, match=r"acc\[3\]=nan"):
        base_motion(np.where(np.arange(acc.size) == 3, np.nan, acc), DT)
    with pytest.raises(ParameterError, match="acc_v has 4 samples"):
        base_motion(acc, DT, acc_v[:4])
    motion = base_motion(acc, DT, acc_v)
    with pytest.raises(ParameterError, match="differs from the BaseMotion's dt"):
        solve_rocking(BLOCK, motion, 2 * DT)
    with pytest.raises(ParameterError, match="acc_v must be None"):
        solve_rocking(BLOCK, motion, DT, acc_v=acc_v)


@pytest.mark.parametrize("scale", [0.0, -1.0, math.nan, math.inf])
def test_bad_scale(scale):
    with pytest.raises(ParameterError, match=f"scale={scale!r}"):
        solve_rocking(BLOCK, np.zeros(10), DT, scale=scale)


def test_scaled_vertical_must_stay_above_minus_g():
    acc = np.zeros(10)
    acc_v = np.full(10, -6.0)
    assert solve_rocking(BLOCK, acc, DT, acc_v=acc_v, scale=1.5).status == "no_motion"
    with pytest.raises(ParameterError, match=r"acc_v \(scaled by 2.0\) reaches -12.0"):
        solve_rocking(BLOCK, acc, DT, acc_v=acc_v, scale=2.0)
    # A record beyond -g as given is fine once scaled down.
    assert solve_rocking(BLOCK, acc, DT, acc_v=2 * acc_v, scale=0.5).status == "no_motion"
