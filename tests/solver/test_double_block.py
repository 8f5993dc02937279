"""Double block: the limits and invariants of REFERENCES R9 (any correct formulation)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rockscreen.solver import RockingBlock, solve_double_block, solve_rocking, solve_sliding
from rockscreen.solver.constants import G
from rockscreen.solver.errors import ParameterError

# The seed paper's tower (S. Anna in Cervino): 2b = 2.06 m, 2h = 5.80 m, eta = 0.9.
CERVINO = RockingBlock.from_dimensions(2.06, 5.80, eta=0.9)
DT = 0.0025


def _harmonic(amplitude_g, freq, duration, dt=DT):
    t = np.arange(int(round(duration / dt)) + 1) * dt
    return amplitude_g * G * np.cos(2 * np.pi * freq * t)


def test_cervino_slenderness():
    # REFERENCES R9 quotes atan(b/h) = 0.35 rad; atan(1.03/2.90) = 0.3413 rad while
    # tan(alpha) = 0.3552, so the quoted 0.35 is rounded (or is tan(alpha)).
    assert CERVINO.alpha == pytest.approx(math.atan(1.03 / 2.90), rel=1e-12)
    assert CERVINO.alpha == pytest.approx(0.35, abs=1e-2)
    assert math.tan(CERVINO.alpha) == pytest.approx(0.35, abs=1e-2)


def test_heavy_building_that_sticks_equals_single_block():
    # M -> infinity: the tower no longer loads the building, which sticks whenever
    # |ag| <= mu_s g; then the tower is Housner's block on the ground motion.
    # Same integrator and events: identical to 1e-9 rad.
    acc = _harmonic(0.5, 3.0, 3.0)
    single = solve_rocking(CERVINO, acc, DT)
    double = solve_double_block(
        CERVINO, acc, DT, tower_mass=1.0, building_mass=1e12, mu_s=0.55, mu_k=0.5
    )
    assert single.uplifted and not double.slipped
    np.testing.assert_allclose(double.theta, single.theta, atol=1e-9)
    assert double.n_impacts == single.n_impacts
    assert double.status == single.status


def test_large_friction_equals_single_block():
    # mu -> infinity (mu = 50 here, with m/(M+m) small enough for a unique solution).
    acc = _harmonic(0.5, 3.0, 3.0)
    single = solve_rocking(CERVINO, acc, DT)
    double = solve_double_block(
        CERVINO, acc, DT, tower_mass=1.0, building_mass=30.0, mu_s=50.0, mu_k=50.0
    )
    assert not double.slipped
    np.testing.assert_allclose(double.theta, single.theta, atol=1e-9)


def test_light_tower_equals_sliding_block():
    # m -> 0: the building is Newmark's sliding block (R6, R7); 1e-9 m agreement.
    acc = _harmonic(0.5, 3.0, 3.0)
    slide = solve_sliding(acc, DT, mu_s=0.3, mu_k=0.2)
    double = solve_double_block(
        CERVINO, acc, DT, tower_mass=1e-9, building_mass=1.0, mu_s=0.3, mu_k=0.2
    )
    assert slide.slipped
    np.testing.assert_allclose(double.u, slide.u, atol=1e-9)
    assert double.slip_residual == pytest.approx(slide.slip_residual, abs=1e-9)


def _energy_momentum(res, block, m, big_m):
    s = np.sign(res.theta)
    phi = block.alpha * s - res.theta
    radius = block.radius
    xg_dot = radius * np.cos(phi) * res.theta_dot
    zg_dot = radius * np.sin(phi) * res.theta_dot
    momentum = (big_m + m) * res.u_dot + m * xg_dot
    i_g = m * (block.inertia_per_mass - radius**2)
    energy = (
        0.5 * big_m * res.u_dot**2
        + 0.5 * m * ((res.u_dot + xg_dot) ** 2 + zg_dot**2)
        + 0.5 * i_g * res.theta_dot**2
        + m * G * radius * np.cos(phi)
    )
    return momentum, energy


def test_frictionless_momentum_and_energy():
    # mu = 0, no ground motion, tower released from a rotation: the horizontal momentum of
    # the system stays zero (also across impacts: momentum-consistent impact law) and the
    # energy is constant between impacts (RK4 at 1 ms: 1e-9 relative), lost at impacts.
    m, big_m = 1.0, 3.0
    res = solve_double_block(
        CERVINO, np.zeros(1), 1e-3, tower_mass=m, building_mass=big_m,
        mu_s=0.0, mu_k=0.0, theta0=0.2, max_free_time=4.0,
    )  # fmt: skip
    momentum, energy = _energy_momentum(res, CERVINO, m, big_m)
    scale = m * CERVINO.radius * np.abs(res.theta_dot).max()
    assert np.abs(momentum).max() < 1e-10 * scale
    assert res.n_impacts >= 2
    edges = np.concatenate(([0.0], res.impact_times, [res.t_end + 1.0]))
    for start, stop in zip(edges[:-1], edges[1:], strict=True):
        inside = (res.t > start) & (res.t < stop)
        if inside.sum() > 1:
            seg = energy[inside]
            assert np.ptp(seg) < 1e-9 * abs(seg.mean())
    first, second = (energy[res.t < res.impact_times[0]], energy[res.t > res.impact_times[0]])
    assert second[0] < first[-1]  # the impact dissipates


def test_no_uplift_while_sliding_when_mu_k_below_tan_alpha():
    # Ramp to 0.5 g > tan(alpha) g: slip starts at mu_s g = 0.2 g first; while sliding the
    # building's acceleration is mu_k g < tan(alpha) g, so the tower never uplifts.
    ramp = np.linspace(0.0, 0.5 * G, 1001)
    res = solve_double_block(
        CERVINO, ramp, 1e-3, tower_mass=1.0, building_mass=10.0, mu_s=0.2, mu_k=0.2
    )
    assert res.slipped and not res.uplifted
    assert set(np.unique(res.regime)) <= {0, 2}


def test_lower_threshold_acts_first_uplift():
    # tan(alpha) = 0.355 < mu_s = 0.45: uplift at |ag| = g tan(alpha), sample 710.3 of the
    # ramp (exact location inside the step), before any slip.
    ramp = np.linspace(0.0, 0.5 * G, 1001)
    res = solve_double_block(
        CERVINO, ramp, 1e-3, tower_mass=1.0, building_mass=10.0, mu_s=0.45, mu_k=0.4
    )
    first = int(np.argmax(res.regime > 0))
    assert res.regime[first] == 1
    assert first == math.ceil(math.tan(CERVINO.alpha) / 0.5 * 1000)


def test_uplift_during_sliding_when_mu_k_above_tan_alpha():
    # mu_k = 0.4 > tan(alpha): a sliding building carries the tower past its uplift limit.
    ramp = np.linspace(0.0, 0.5 * G, 1001)
    res = solve_double_block(
        CERVINO, ramp, 1e-3, tower_mass=1.0, building_mass=10.0, mu_s=0.4, mu_k=0.4
    )
    assert res.slipped and res.uplifted


def test_seed_paper_case_runs_and_tower_is_the_light_body():
    # Tower 339 kN on a complex of 96,840.67 kN (REFERENCES R9), 0.5 g at 5 Hz, mu 1/0.7.
    res = solve_double_block(
        CERVINO, _harmonic(0.5, 5.0, 3.0), DT, tower_mass=339e3 / G,
        building_mass=96840.67e3 / G, mu_s=1.0, mu_k=0.7, history=False,
    )  # fmt: skip
    assert res.uplifted and not res.slipped and not res.overturned
    assert res.t is None


def test_painleve_inconsistent_parameters_are_refused():
    with pytest.raises(ParameterError, match="Painleve"):
        solve_double_block(
            CERVINO, np.zeros(10), DT, tower_mass=1.0, building_mass=1.0, mu_s=50, mu_k=50
        )
