"""Safety factor search and risk classes."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rockscreen.pipeline.engine.search import safety_factor, scan_factors
from rockscreen.pipeline.engine.uplift import uplift_free_factor
from rockscreen.pipeline.screening.risk import risk_class
from rockscreen.solver import RockingBlock, solve_rocking
from rockscreen.solver.constants import G


def test_scan_grid_is_geometric_and_contains_one_and_the_cap():
    grid = scan_factors(0.05, 1.2, 10.0)
    assert grid[0] == 0.05 and grid[-1] == 10.0
    assert 1.0 in grid
    assert np.all(np.diff(grid) > 0)
    assert np.max(grid[1:] / grid[:-1]) <= 1.2 + 1e-12


def test_threshold_predicate_found_to_one_percent():
    result = safety_factor(lambda f: f >= 2.345)
    assert 2.345 <= result.factor <= 2.345 * 1.01
    assert result.lower < 2.345


def test_non_monotone_response_gives_the_smallest_overturning_factor():
    # Overturns in [1.5, 1.9] and above 3: a safe window exists above the minimum.
    def overturns(f):
        return 1.5 <= f <= 1.9 or f >= 3.0

    result = safety_factor(overturns, start=0.1, ratio=1.2, cap=10.0, tolerance=0.01)
    assert 1.5 <= result.factor <= 1.5 * 1.01


def test_nothing_overturns_up_to_the_cap_gives_inf():
    result = safety_factor(lambda f: False, start=0.5, ratio=1.5, cap=4.0)
    assert math.isinf(result.factor)
    assert result.lower == 4.0


def test_uplift_free_factor():
    acc = np.array([0.0, 2.0, -4.0, 1.0])
    assert uplift_free_factor(acc, 0.25) == pytest.approx(G * math.tan(0.25) / 4.0)
    assert uplift_free_factor(acc, 0.25, acc_v=np.array([0, 1.0, 0, 0])) == pytest.approx(
        G * math.tan(0.25) / (4.0 + math.tan(0.25))
    )
    assert math.isinf(uplift_free_factor(np.zeros(3), 0.2))


def housner_pulse_overturns(amplitude_over_alpha_g, duration, p=2.0, alpha=0.2):
    """Linearized block under a rectangular pulse A g alpha of a given duration (R5)."""
    block = RockingBlock.from_p_alpha(p, alpha)
    dt = duration / 200
    acc = np.full(201, amplitude_over_alpha_g * G * alpha)
    response = solve_rocking(block, acc, dt, linearized=True, history=False)
    return response.overturned


def test_safety_factor_of_a_housner_rectangular_pulse():
    # REFERENCES R5: p = 2, alpha = 0.2, a pulse of duration ln(2)/p = 0.346574 s
    # overturns the linearized block for A > 2 (cosh(p t1) = 1 + 1/(2A(A-1))).
    # Base pulse A = 1.5: the safety factor is 2 / 1.5 = 1.3333, found to 1 %.
    duration = math.log(2.0) / 2.0
    result = safety_factor(lambda f: housner_pulse_overturns(1.5 * f, duration), start=0.5)
    assert result.factor == pytest.approx(2.0 / 1.5, rel=0.011)
    assert result.lower <= 2.0 / 1.5 * 1.001


@pytest.mark.parametrize(
    ("ratio", "overturned", "sf", "expected"),
    [
        (1.3, True, 0.8, "collapse"),
        (0.6, False, 3.0, "high"),
        (0.05, False, 1.2, "high"),
        (0.3, False, 4.0, "moderate"),
        (0.05, False, 2.0, "moderate"),
        (0.05, False, 6.0, "low"),
        (0.0, False, math.inf, "none"),
        (0.0, False, math.nan, "none"),
    ],
)
def test_risk_classes(ratio, overturned, sf, expected):
    assert risk_class(ratio, overturned, sf) == expected


def test_sample_uplift_factor_is_the_exact_per_sample_bound():
    from rockscreen.pipeline.engine.uplift import sample_uplift_factor

    alpha = 0.25
    tan_alpha = math.tan(alpha)
    acc = np.array([0.0, 2.0, -4.0, 1.0])
    acc_v = np.array([0.0, 1.0, 0.5, -1.0])
    # |a_h| - tan(alpha) a_v per sample: 0, 2 - t, 4 - t/2, 1 + t; the largest is 4 - t/2.
    expected = G * tan_alpha / (4.0 - 0.5 * tan_alpha)
    assert sample_uplift_factor(acc, alpha) == pytest.approx(G * tan_alpha / 4.0)
    assert sample_uplift_factor(acc, alpha, acc_v) == pytest.approx(expected)
    assert sample_uplift_factor(acc, alpha, acc_v) >= uplift_free_factor(acc, alpha, acc_v)
    assert math.isinf(sample_uplift_factor(np.zeros(3), 0.2, np.ones(3)))


def test_sample_uplift_factor_separates_rest_from_uplift_in_the_solver():
    from rockscreen.pipeline.engine.uplift import sample_uplift_factor

    block = RockingBlock.from_dimensions(1.0, 5.0)
    t = np.arange(600) * 0.01
    acc = 3.0 * np.sin(2 * np.pi * t) * np.exp(-t)
    acc_v = 1.5 * np.cos(3 * np.pi * t) * np.exp(-t)
    factor = sample_uplift_factor(acc, block.alpha, acc_v)
    below = solve_rocking(block, acc, 0.01, acc_v=acc_v, scale=factor * 0.999, history=False)
    above = solve_rocking(block, acc, 0.01, acc_v=acc_v, scale=factor * 1.001, history=False)
    assert not below.uplifted
    assert above.uplifted
