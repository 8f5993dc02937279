"""``stop_when_certain``: the free motion ends once the verdict is certain, same verdicts.

The reference is the same solver following the free motion to rest (the default). On
zero-padded records, at many scale factors around overturning, the verdict must be equal
and ``theta_max`` equal to the integration's accuracy (the early stop reads the largest
swing still to come from the energy, the full solve integrates it).
"""

from __future__ import annotations

import numpy as np
import pytest

from rockscreen.solver import RockingBlock, solve_double_block, solve_rocking
from rockscreen.solver.kernel import input_end

DT = 0.01
#: theta_max agreement between the early stop and the full free motion [-] (relative).
THETA_RTOL = 1e-6


def _padded_record(seed, n=900, pad=2500):
    """A decaying random accelerogram [m/s^2] with ``pad`` trailing zeros, and its vertical."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) * DT
    envelope = np.exp(-(((t - 3.0) / 1.5) ** 2))
    horizontal = envelope * (np.sin(2.0 * np.pi * 1.2 * t) + 0.6 * rng.normal(size=n))
    vertical = 0.2 * envelope * rng.normal(size=n)
    zeros = np.zeros(pad)
    return np.concatenate([horizontal, zeros]), np.concatenate([vertical, zeros])


def test_input_end_skips_trailing_zeros_of_both_records():
    acc = np.array([0.0, 1.0, 2.0, 0.0, 0.0, 0.0])
    assert input_end(acc, np.empty(0)) == 4  # the ramp to the first zero is kept
    vertical = np.array([0.0, 0.0, 0.0, 0.0, 0.5, 0.0])
    assert input_end(acc, vertical) == 6
    assert input_end(np.zeros(5), np.empty(0)) == 1
    assert input_end(np.array([1.0, 2.0]), np.empty(0)) == 2


@pytest.mark.parametrize("seed", [1, 2, 3])
@pytest.mark.parametrize("vertical", [False, True])
def test_single_block_verdicts_equal_the_full_free_motion(seed, vertical):
    acc, acc_v = _padded_record(seed)
    kwargs = {"acc_v": acc_v if vertical else None, "history": False}
    block = RockingBlock.from_dimensions(0.6, 3.0)
    stopped = overturned = 0
    for factor in np.geomspace(1.0, 12.0, 30):
        full = solve_rocking(block, acc, DT, scale=factor, **kwargs)
        fast = solve_rocking(block, acc, DT, scale=factor, stop_when_certain=True, **kwargs)
        assert fast.overturned == full.overturned, factor
        assert fast.status == full.status, factor
        overturned += full.overturned
        if not full.overturned:
            assert fast.theta_max == pytest.approx(full.theta_max, rel=THETA_RTOL), factor
            assert fast.t_end <= full.t_end
            stopped += fast.t_end < full.t_end
    # The comparison covered overturning, surviving and early-stopped cases.
    assert 0 < overturned < 30 and stopped > 0


def test_early_stop_ends_at_the_input_not_at_the_padding():
    acc, _ = _padded_record(4)
    block = RockingBlock.from_dimensions(1.2, 6.0)
    factors = np.geomspace(0.5, 3.0, 12)
    ends = []
    for factor in factors:
        fast = solve_rocking(block, acc, DT, scale=factor, stop_when_certain=True, history=False)
        if fast.uplifted and not fast.overturned:
            ends.append(fast.t_end)
    # Rocking cases stop within the record's 9 s, never in its 25 s of zeros.
    assert ends and max(ends) <= 9.0 + DT


def test_double_block_keeps_its_free_motion_but_skips_the_padding_at_rest():
    acc, acc_v = _padded_record(5)
    block = RockingBlock.from_dimensions(1.2, 6.0)
    kwargs = {"tower_mass": 1.0, "building_mass": 20.0, "mu_s": 0.25, "mu_k": 0.2}
    for factor in (0.8, 1.5, 2.5, 4.0):
        full = solve_double_block(block, acc, DT, acc_v=acc_v, scale=factor, **kwargs)
        fast = solve_double_block(
            block, acc, DT, acc_v=acc_v, scale=factor, stop_when_certain=True, **kwargs
        )
        assert (fast.status, fast.overturned) == (full.status, full.overturned)
        assert fast.theta_max == full.theta_max
        assert fast.slip_max == full.slip_max


def test_default_follows_the_free_motion_to_rest():
    acc, _ = _padded_record(1)
    block = RockingBlock.from_dimensions(1.2, 6.0)
    default = solve_rocking(block, acc, DT, scale=1.5, history=False)
    explicit = solve_rocking(block, acc, DT, scale=1.5, history=False, stop_when_certain=False)
    assert default.t_end == explicit.t_end and default.n_impacts == explicit.n_impacts


@pytest.mark.parametrize("linearized", [False, True])
def test_the_swing_still_to_come_is_its_true_peak(linearized):
    """A pulse that ends while the block swings outward: the peak comes after the input, so
    the early stop's theta_max is the energy's peak, which must equal the integrated one
    (a sign error in the nonlinear peak once reported the current angle instead)."""
    block = RockingBlock.from_dimensions(1.0, 6.0)
    t = np.arange(40) * DT
    pulse = np.where(t < 0.25, np.sin(np.pi * t / 0.25), 0.0)
    acc = np.concatenate([pulse, np.zeros(3000)])
    checked = 0
    for factor in np.geomspace(2.0, 12.0, 25):
        full = solve_rocking(block, acc, DT, scale=factor, history=False, linearized=linearized)
        fast = solve_rocking(
            block, acc, DT, scale=factor, history=False, linearized=linearized,
            stop_when_certain=True,
        )  # fmt: skip
        assert fast.overturned == full.overturned, factor
        if not full.overturned and full.theta_max > 0:
            assert fast.theta_max == pytest.approx(full.theta_max, rel=THETA_RTOL), factor
            checked += 1
    assert checked > 3
