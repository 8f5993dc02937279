"""First-order Sobol' indices, survey_first and the top-N changes (issue 31)."""

from __future__ import annotations

import numpy as np
import pytest

from rockscreen.pipeline.risk.uncertainty.risk import INTERVAL, QUANTILE_METHOD
from rockscreen.pipeline.risk.uncertainty.sensitivity import (
    NULL_PERMUTATIONS,
    epistemic_inputs,
    expected_narrowing,
    first_order_indices,
    mean_group_width,
    sensitivity,
    top_n_changes,
)


def test_additive_model_recovers_the_analytic_indices():
    """Y = 3 X1 + 2 X2 + X3 + c(K), independent: S_k = a_k^2 Var X_k / Var Y."""
    rng = np.random.default_rng(7)
    n = 4000
    x1, x2, x3 = rng.normal(size=(3, n))
    kinds = rng.choice(np.array(["a", "b"]), n)
    effect = np.where(kinds == "a", -1.5, 1.5)  # variance 2.25
    y = 3 * x1 + 2 * x2 + x3 + effect
    total = 9 + 4 + 1 + 2.25
    got = first_order_indices(y, {"x1": x1, "x2": x2, "x3": x3, "k": kinds})
    expected = {"x1": 9 / total, "x2": 4 / total, "x3": 1 / total, "k": 2.25 / total}
    for name, value in expected.items():
        assert got[name] == pytest.approx(value, abs=0.03), name
    dummy = first_order_indices(y, {"noise": rng.normal(size=n)})
    assert dummy["noise"] < 0.02


def test_survey_first_is_the_dominant_input_and_narrows_the_interval():
    rng = np.random.default_rng(3)
    n = 1000
    samples = {
        "wall_m": rng.uniform(0.8, 1.2, n),
        "wall_top_m": np.full(n, 0.8),
        "masonry_type": np.array(["rubble"] * n, dtype=object),
        "fm_pa": rng.uniform(1e6, 2e6, n),
        "unit_weight_n_m3": np.full(n, 19000.0),
        "period_s": rng.lognormal(np.log(0.6), 0.45, n),
    }
    inputs = epistemic_inputs(samples)
    assert set(inputs) == {"wall_m", "taper", "fm_pa", "period_s"}  # points left out
    p = 1.0 / (1.0 + np.exp(-(3.0 * np.log(samples["period_s"]) + 0.1 * rng.normal(size=n))))
    sens = sensitivity(p, samples)
    assert sens.survey_first == "period_s"
    assert sens.survey_first_index > 0.8
    assert sens.survey_first_narrowing > 0.5
    assert sens.narrowing["fm_pa"] < 0.15
    assert sens.width90_after < 0.5 * sens.width90
    narrowing, after = expected_narrowing(p, rng.normal(size=n))
    assert narrowing < 0.15


def test_no_varying_input_means_nothing_to_survey():
    samples = {"period_s": np.full(50, 0.6), "fm_pa": np.full(50, 1e6)}
    sens = sensitivity(np.full(50, 0.1), samples)
    assert sens.survey_first == "" and sens.first_order == {}


def test_top_n_changes_names_the_tower_at_the_line():
    """Three towers: B sits at the top-1 line and its P hinges on its period."""
    rng = np.random.default_rng(0)
    n = 400
    period = rng.lognormal(0.0, 0.4, n)
    samples = {"period_s": period}
    flat = {"period_s": period}
    p_b = np.where(period > 1.0, 0.5, 0.1)  # median near the line
    p_a = np.full(n, 0.3)
    p_c = np.full(n, 0.01)
    best = [0.3, float(np.median(p_b)), 0.01]
    changes = top_n_changes(
        ["A", "B", "C"], best, [p_a, p_b, p_c], [flat, samples, flat], ["", "period_s", ""], 1
    )
    assert changes[0].tower_id == "B"
    assert 0.3 < changes[0].probability < 0.7
    assert [c.probability for c in changes[1:]] == [0.0, 0.0]


def _group_width_reference(p: np.ndarray, labels: np.ndarray) -> float:
    """The groups' widths one np.quantile per group (the form the array one replaced)."""
    groups, counts = np.unique(labels, return_counts=True)
    q = [0.5 - 0.5 * INTERVAL, 0.5 + 0.5 * INTERVAL]
    widths = []
    for g in groups:
        lo, hi = np.quantile(p[labels == g], q, method=QUANTILE_METHOD)
        widths.append(float(hi - lo))
    return float(sum(c * w for c, w in zip(counts, widths, strict=True)) / p.size)


@pytest.mark.parametrize("seed", range(6))
def test_the_groups_widths_at_once_equal_one_quantile_per_group_bit_for_bit(seed):
    """Sizes 1 to 1500, 1 to 40 groups, ties, tiny groups; a NaN gives the per-group path."""
    rng = np.random.default_rng(seed)
    for _ in range(60):
        n = int(rng.integers(1, 1500))
        p = rng.lognormal(-5.0, 2.0, n)
        if rng.random() < 0.4:
            p = np.round(p, 4)  # ties
        labels = rng.integers(0, int(rng.integers(1, 41)), n)
        assert mean_group_width(p, labels) == _group_width_reference(p, labels)
    p[0] = np.nan
    assert np.isnan(mean_group_width(p, labels)) and np.isnan(_group_width_reference(p, labels))


def test_the_narrowing_of_all_random_groupings_at_once_is_the_per_grouping_one():
    """expected_narrowing: the random groupings' widths at once, the same value exactly.

    A categorical input (its groups are its categories): the reference draws the same
    permutations and takes each grouping's widths one np.quantile per group.
    """
    rng = np.random.default_rng(9)
    for n in (200, 1000, 1337):
        p = rng.lognormal(-6.0, 2.0, n)
        x = rng.choice(np.array(["a", "b", "c", "d", "e"]), n, p=[0.4, 0.3, 0.15, 0.1, 0.05])
        labels = np.unique(x, return_inverse=True)[1]
        draws = np.random.default_rng(0)
        groupings = [draws.permutation(labels) for _ in range(NULL_PERMUTATIONS)]
        null = np.mean([_group_width_reference(p, grouping) for grouping in groupings])
        expected = min(max(1.0 - _group_width_reference(p, labels) / null, 0.0), 1.0)
        assert expected_narrowing(p, x)[0] == expected
