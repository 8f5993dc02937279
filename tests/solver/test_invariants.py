"""Invariants and Hypothesis properties of the rocking solver (DESIGN.md, 'Tests')."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from rockscreen.solver import RockingBlock, solve_rocking
from rockscreen.solver.constants import G
from rockscreen.solver.dynamics import free_motion_overturns
from rockscreen.solver.kernel import make_par
from rockscreen.solver.rocking import RunOptions


def _sine_pulse(amplitude, freq, dt=2e-3):
    t = np.arange(int(round(1.0 / freq / dt)) + 1) * dt
    return amplitude * np.sin(2 * np.pi * freq * t)


blocks = st.builds(
    RockingBlock.from_p_alpha,
    p=st.floats(0.8, 4.0),
    alpha=st.floats(0.05, 0.5),
)


@given(
    block=blocks,
    ratio=st.floats(1.05, 4.0),
    freq=st.floats(0.5, 4.0),
)
def test_mirror_symmetry(block, ratio, freq):
    # Mirrored input gives the mirrored rotation (exact up to round-off).
    acc = _sine_pulse(ratio * math.tan(block.alpha) * G, freq)
    plus = solve_rocking(block, acc, 2e-3)
    minus = solve_rocking(block, -acc, 2e-3)
    assert plus.status == minus.status
    np.testing.assert_allclose(minus.theta, -plus.theta, atol=1e-12)
    np.testing.assert_allclose(minus.impact_times, plus.impact_times, atol=1e-12)


@given(block=blocks, ratio=st.floats(0.0, 0.999), freq=st.floats(0.2, 10.0))
def test_below_threshold_no_motion(block, ratio, freq):
    # Peak |ag| below g tan(alpha): the block never uplifts.
    acc = _sine_pulse(ratio * math.tan(block.alpha) * G, freq)
    res = solve_rocking(block, acc, 2e-3, history=False)
    assert res.status == "no_motion" and res.theta_max == 0.0 and res.n_impacts == 0


@given(
    alpha=st.floats(0.05, 0.5),
    eta=st.floats(0.5, 1.0),
    start=st.floats(0.2, 0.9),
)
def test_energy_ratio_across_impact_is_eta_squared(alpha, eta, start):
    # Free rocking: potential energy at the peaks before and after the first impact,
    # measured from rest, differs by eta^2 (kinetic-energy ratio of the impact).
    # Peaks from the 0.5 ms grid: 1e-5 relative.
    block = RockingBlock.from_p_alpha(2.0, alpha, eta=eta)
    res = solve_rocking(block, np.zeros(1), 5e-4, theta0=start * alpha, max_free_time=3.0)
    t1 = res.impact_times[0]
    t2 = res.impact_times[1] if res.n_impacts > 1 else res.t_end
    after = (res.t > t1) & (res.t < t2)
    peak = np.abs(res.theta[after]).max()
    before = math.cos(alpha - start * alpha) - math.cos(alpha)
    later = math.cos(alpha - peak) - math.cos(alpha)
    assert later / before == pytest.approx(eta**2, rel=1e-5)


@given(
    block=blocks,
    theta=st.floats(0.0, 0.6),
    omega=st.floats(0.01, 3.0),
)
def test_free_motion_verdict_agrees_with_energy_barrier(block, theta, omega):
    # Released in free motion with (theta, omega) moving outward about the right corner:
    # the verdict is final (below the barrier it falls back and every later impact only
    # dissipates), so the integrated outcome must match the energy-barrier test.
    theta = min(theta, 0.95 * block.alpha)
    par = make_par(block, RunOptions())
    predicted = free_motion_overturns(theta, omega, 1.0, par)
    barrier = 2 * block.p**2 * (1 - math.cos(block.alpha - theta))
    if abs(omega**2 - barrier) < 1e-3 * barrier:
        return  # too close to the separatrix to integrate to a clear verdict
    res = solve_rocking(
        block, np.zeros(1), 1e-3, theta0=theta, theta_dot0=omega, max_free_time=20.0
    )
    assert res.overturned == predicted
    if not predicted:
        assert res.theta_max < block.alpha


def test_overturning_agrees_with_integration_past_the_barrier():
    # Energy just above the barrier: overturned; just below: rocks back.
    block = RockingBlock.from_p_alpha(2.0, 0.2, eta=1.0)
    barrier = math.sqrt(2 * block.p**2 * (1 - math.cos(block.alpha)))
    over = solve_rocking(block, np.zeros(1), 1e-3, theta_dot0=1.001 * barrier, history=False)
    back = solve_rocking(
        block, np.zeros(1), 1e-3, theta_dot0=0.999 * barrier, history=False, max_free_time=5.0
    )
    assert over.overturned
    assert not back.overturned and back.theta_max < block.alpha


def test_uplift_located_inside_the_step():
    # Ramp reaching g tan(alpha) at t* = 0.61234 s, between samples: no rotation before t*.
    block = RockingBlock.from_p_alpha(2.0, 0.2)
    dt = 0.01
    t_star = 0.61234
    t = np.arange(101) * dt
    acc = math.tan(0.2) * G * t / t_star
    res = solve_rocking(block, acc, dt)
    assert np.all(res.theta[res.t <= 0.61] == 0.0)
    assert res.theta[res.t >= 0.62][0] < 0.0  # a_b > 0 tips the block to theta < 0
    assert res.theta[res.t >= 0.62][0] > -1e-6  # rotation ~ (t - t*)^3 from rest


def test_constant_vertical_acceleration_rescales_gravity():
    # With a constant a_v the block behaves as under gravity g + a_v: free rocking period
    # scales as sqrt(g / (g + a_v)) (1e-5 relative).
    block = RockingBlock.from_p_alpha(2.0, 0.25, eta=1.0)
    base = solve_rocking(block, np.zeros(2001), 1e-3, theta0=0.1, history=False)
    av = 0.3 * G
    heavy = solve_rocking(
        block, np.zeros(2001), 1e-3, theta0=0.1, acc_v=np.full(2001, av), history=False
    )
    ratio = heavy.impact_times[0] / base.impact_times[0]
    assert ratio == pytest.approx(math.sqrt(G / (G + av)), rel=1e-5)


def test_history_false_allocates_no_arrays_and_matches():
    block = RockingBlock.from_p_alpha(2.0, 0.2)
    acc = _sine_pulse(2.0 * math.tan(0.2) * G, 1.0)
    full = solve_rocking(block, acc, 2e-3)
    lean = solve_rocking(block, acc, 2e-3, history=False)
    assert lean.t is None and lean.theta is None and lean.regime is None
    assert lean.theta_max == full.theta_max and lean.status == full.status
    assert full.regime.dtype == np.int8
    assert full.t[-1] == pytest.approx(full.t_end)
    np.testing.assert_allclose(np.diff(full.t[:-1]), 2e-3, rtol=1e-9)


def test_zeno_rest_after_free_rocking():
    block = RockingBlock.from_p_alpha(2.0, 0.2, eta=0.8)
    res = solve_rocking(block, np.zeros(1), 1e-3, theta0=0.1)
    assert res.status == "came_to_rest"
    assert res.theta[-1] == 0.0 and res.theta_dot[-1] == 0.0 and res.regime[-1] == 0
    # Impact intervals shrink geometrically by eta (linearized Zeno sequence, approx.).
    gaps = np.diff(res.impact_times)
    assert np.all(gaps[1:] < gaps[:-1])


def test_hollow_section_defaults():
    # A hollow shaft: I_O/m = I_G/m + R^2 with a larger centroidal inertia than a solid one.
    solid = RockingBlock.from_dimensions(6.0, 30.0)
    hollow = RockingBlock.from_section(6.0, 30.0, inertia_per_mass=1.5 * solid.radius**2)
    assert hollow.alpha == pytest.approx(solid.alpha)
    assert hollow.p < solid.p
    assert hollow.eta == pytest.approx(1 - 2 / 1.5 * math.sin(hollow.alpha) ** 2)
    assert solid.eta == pytest.approx(1 - 1.5 * math.sin(solid.alpha) ** 2)
    assert solid.p == pytest.approx(math.sqrt(3 * G / (4 * solid.radius)))
    assert RockingBlock.from_p_alpha(solid.p, solid.alpha).radius == pytest.approx(solid.radius)


@pytest.mark.parametrize("bound", [0.3, 0.9, 1.7, 3.0])
def test_free_motion_bound_below_barrier_is_certain_rest(bound):
    # eta close to 1 rocks for long; cut at the bound, the status is still came_to_rest
    # (no overturning is possible below the barrier) and theta_max includes the swing still
    # to come, from the energy: it matches a run integrated to rest (1e-7 rad).
    block = RockingBlock.from_p_alpha(2.0, 0.15, eta=0.97)
    acc = np.full(201, 1.3 * math.tan(0.15) * G)
    short = solve_rocking(block, acc, 1e-3, max_free_time=bound, history=False)
    full = solve_rocking(block, acc, 1e-3, max_free_time=200.0, history=False)
    assert full.status == "came_to_rest" and short.status == "came_to_rest"
    assert "barrier" in short.message
    assert short.theta_max == pytest.approx(full.theta_max, abs=1e-7)


def test_undamped_rocking_stays_moving_at_end():
    block = RockingBlock.from_p_alpha(2.0, 0.15, eta=1.0)
    res = solve_rocking(block, np.zeros(1), 1e-3, theta0=0.05, max_free_time=2.0)
    assert res.status == "moving_at_end"
