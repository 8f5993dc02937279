"""Coulomb sliding block (REFERENCES R6, R7) and the rock-or-slide threshold (R8)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rockscreen.solver import (
    RockingBlock,
    critical_friction_for_rocking,
    solve_rocking,
    solve_sliding,
)
from rockscreen.solver.constants import G


# ---- R6 Newmark sliding block, rectangular pulse (Newmark 1965) --------------------------
@pytest.mark.parametrize(
    ("amp", "mu", "t0", "slip"),
    [(0.5, 0.2, 0.5, 0.919687), (1.0, 0.1, 0.2, 1.765800), (0.3, 0.25, 1.0, 0.294300)],
)
def test_r6_newmark_rectangular_pulse(amp, mu, t0, slip):
    # u = V^2/(2 N g) (1 - N/A), V = A g t0; RK4 is exact on this piecewise-polynomial
    # motion, so the 6-digit table value is met to 1e-6 relative.
    samples = 1000
    res = solve_sliding(np.full(samples + 1, amp * G), t0 / samples, mu_s=mu, mu_k=mu)
    assert abs(res.slip_residual) == pytest.approx(slip, rel=1e-6)
    assert res.slip_residual < 0.0  # the block lags behind a base accelerating to +x
    assert res.status == "came_to_rest" and res.slipped and not res.uplifted
    # It stops when V is used up at deceleration N g: t = t0 A / N.
    assert res.t_end == pytest.approx(t0 * amp / mu, abs=2 * t0 / samples)


# ---- R7 harmonic base motion, steady continuous sliding (derived) ------------------------
@pytest.mark.parametrize(
    ("ratio", "mu", "peak_to_peak"),
    [(2.0, 0.3, 0.184576), (3.0, 0.2, 0.254046), (5.0, 0.1, 0.235909)],
)
def test_r7_harmonic_steady_state(ratio, mu, peak_to_peak):
    # D = (2/w^2) sqrt(A^2 - (pi mu g/2)^2) at 1 Hz. After 25 cycles the transient has
    # decayed; grid extrema at dt = 1 ms are within 1e-5 relative: tolerance 5e-5.
    dt = 1e-3
    t = np.arange(int(round(30.0 / dt)) + 1) * dt
    res = solve_sliding(ratio * mu * G * np.sin(2 * np.pi * t), dt, mu_s=mu, mu_k=mu)
    last = (res.t > 28.0) & (res.t <= 29.0)
    assert np.ptp(res.u[last]) == pytest.approx(peak_to_peak, rel=5e-5)
    # A/(mu g) >= sqrt(1 + pi^2/4) = 1.862: continuous sliding, never sticking.
    steady = (res.t > 20.0) & (res.t <= 30.0)
    assert np.all(res.regime[steady] == 2)


def test_r7_sticks_below_continuous_sliding_threshold():
    # A/(mu g) = 1.5 < 1.862: stick phases remain in the steady state.
    dt = 1e-3
    t = np.arange(int(round(10.0 / dt)) + 1) * dt
    res = solve_sliding(1.5 * 0.2 * G * np.sin(2 * np.pi * t), dt, mu_s=0.2, mu_k=0.2)
    assert np.any(res.regime[res.t > 5.0] == 0)


def test_no_slip_below_static_friction():
    t = np.arange(2001) * 1e-3
    res = solve_sliding(0.29 * G * np.sin(2 * np.pi * t), 1e-3, mu_s=0.3, mu_k=0.1)
    assert res.status == "no_motion" and res.slip_max == 0.0


def test_vertical_acceleration_scales_the_normal_force():
    # A constant upward a_v during the pulse raises the friction to mu (g + a_v); after the
    # record a_v = 0. Relative acceleration (A g - mu g_e) for t0, then deceleration mu g:
    # slip = (A g - mu g_e) t0^2 / 2 + ((A g - mu g_e) t0)^2 / (2 mu g).
    samples, t0, amp, mu, av = 1000, 0.5, 0.5, 0.2, 0.2 * G
    acc = np.full(samples + 1, amp * G)
    res = solve_sliding(acc, t0 / samples, mu_s=mu, mu_k=mu, acc_v=np.full(samples + 1, av))
    rel = amp * G - mu * (G + av)
    expected = 0.5 * rel * t0**2 + (rel * t0) ** 2 / (2 * mu * G)
    assert abs(res.slip_residual) == pytest.approx(expected, rel=1e-6)


def test_static_and_kinetic_friction_differ():
    # mu_k < mu_s: the block slides longer than with mu_k = mu_s.
    acc = np.full(501, 0.5 * G)
    same = solve_sliding(acc, 1e-3, mu_s=0.3, mu_k=0.3)
    lower = solve_sliding(acc, 1e-3, mu_s=0.3, mu_k=0.2)
    assert abs(lower.slip_residual) > abs(same.slip_residual)


# ---- R8 rock or slide at the start of motion (Shenton 1996; Zhang & Makris 2001 eq. 7) ---
def test_r8_critical_friction_closed_form():
    alpha = 0.25
    assert critical_friction_for_rocking(math.tan(alpha), alpha) == pytest.approx(
        math.tan(alpha), rel=1e-12
    )
    assert critical_friction_for_rocking(1.5, alpha) == pytest.approx(0.5096, abs=5e-5)
    limit = (1 + 3 * math.sin(alpha) ** 2) / (3 * math.sin(alpha) * math.cos(alpha))
    assert limit == pytest.approx(1.6459, abs=5e-5)
    assert critical_friction_for_rocking(1e9, alpha) == pytest.approx(limit, rel=1e-6)


@pytest.mark.parametrize("accel_ratio", [0.3, 0.5, 1.0, 1.5])
def test_r8_friction_demand_at_uplift(accel_ratio):
    # A step of A g from t = 0 lasting 0.2 ms: the largest demand |f_x/f_z| is the one at
    # uplift, which must equal mu_cr(A) (tolerance 1e-3 relative for the 0.2 ms evolution).
    alpha = 0.25
    block = RockingBlock.from_p_alpha(2.0, alpha)
    res = solve_rocking(block, np.full(3, accel_ratio * G), 1e-4, history=False)
    assert res.uplifted
    expected = critical_friction_for_rocking(accel_ratio, alpha)
    assert res.friction_demand_max == pytest.approx(expected, rel=1e-3)


def test_friction_demand_without_uplift_is_peak_acceleration_ratio():
    t = np.arange(1001) * 1e-3
    acc = 0.2 * G * np.sin(2 * np.pi * t)
    res = solve_rocking(RockingBlock.from_p_alpha(2.0, 0.25), acc, 1e-3, history=False)
    assert res.status == "no_motion"
    assert res.friction_demand_max == pytest.approx(np.abs(acc).max() / G, rel=1e-12)
