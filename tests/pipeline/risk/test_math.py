"""Fragility fit, hazard integral, LV1 indices and classes: the pure math of pipeline.risk."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.report.risk_summary import rank_towers
from rockscreen.pipeline.risk.measures.classes import parse_limits, risk_class
from rockscreen.pipeline.risk.measures.fragility import (
    fit_fragility,
    fragility_probability,
    log_likelihood,
)
from rockscreen.pipeline.risk.measures.hazard_integral import (
    HazardCurve,
    annual_rate_of_overturning,
    cornell_closed_form,
    probability_in,
)
from rockscreen.pipeline.risk.measures.lv1 import lv1_indices

TR = np.array([30.0, 50.0, 72.0, 101.0, 140.0, 201.0, 475.0, 975.0, 2475.0])


def _power_law_curve(k0: float, k: float) -> HazardCurve:
    """Tabulated points of lambda(a) = k0 a^-k at the nine return periods."""
    ag = (k0 * TR) ** (1.0 / k)
    return HazardCurve.from_return_periods(TR, ag)


@pytest.mark.parametrize(
    ("k0", "k", "median", "beta"),
    [(1e-4, 2.5, 0.3, 0.4), (5e-5, 3.0, 0.15, 0.6), (2e-4, 1.8, 0.6, 0.3), (1e-4, 2.2, 0.05, 0.8)],
)
def test_rate_matches_cornell_closed_form(k0, k, median, beta):
    curve = _power_law_curve(k0, k)
    exact = cornell_closed_form(k0, k, median, beta)
    rate = annual_rate_of_overturning(curve, median, beta)
    assert rate == pytest.approx(exact, rel=0.02)
    assert rate == pytest.approx(exact, rel=1e-4)  # the grid is much finer than needed


def test_curve_interpolates_log_log_and_extrapolates_end_segments():
    ag = np.array([0.05, 0.06, 0.07, 0.08, 0.09, 0.1, 0.15, 0.2, 0.3])
    curve = HazardCurve.from_return_periods(TR, ag)
    assert curve.rate(ag) == pytest.approx(1 / TR)
    assert curve.return_period(0.125) == pytest.approx(
        math.exp(math.log(201) + math.log(475 / 201) * math.log(0.125 / 0.1) / math.log(1.5))
    )
    k_last = math.log(2475 / 975) / math.log(0.3 / 0.2)
    assert curve.return_period(0.6) == pytest.approx(2475 * 2.0**k_last)
    assert curve.ag_at(300.0) == pytest.approx(
        0.1 * (0.15 / 0.1) ** (math.log(300 / 201) / math.log(475 / 201))
    )
    assert curve.ag_at(curve.return_period(0.04)) == pytest.approx(0.04)
    assert not curve.covers(0.6) and curve.covers(0.1)


def test_curve_drops_ties_and_refuses_flat():
    curve = HazardCurve.from_return_periods([30, 50, 72], [0.05, 0.05, 0.06])
    assert curve.ag_g.tolist() == [0.05, 0.06]
    with pytest.raises(RiskError, match="grow with the return period"):
        HazardCurve.from_return_periods([30, 50], [0.05, 0.05])
    with pytest.raises(RiskError, match="> 0"):
        HazardCurve.from_return_periods([30, 50], [0.05, -1])


def test_rate_grows_with_hazard_and_falls_with_capacity():
    curve = _power_law_curve(1e-4, 2.5)
    stronger = _power_law_curve(3e-4, 2.5)
    assert annual_rate_of_overturning(stronger, 0.3, 0.4) > annual_rate_of_overturning(
        curve, 0.3, 0.4
    )
    assert annual_rate_of_overturning(curve, 0.2, 0.4) > annual_rate_of_overturning(curve, 0.3, 0.4)
    with pytest.raises(RiskError, match="beta"):
        annual_rate_of_overturning(curve, 0.3, math.nan)


def test_probability_in_50_years():
    assert probability_in(1e-3) == pytest.approx(1 - math.exp(-0.05))


def _stripe_counts(rng, ag, n, median, beta):
    return rng.binomial(n, fragility_probability(ag, median, beta))


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_fit_recovers_known_fragility_within_its_standard_errors(seed):
    rng = np.random.default_rng(seed)
    ag = np.geomspace(0.05, 0.8, 9)
    n = np.full(9, 40)
    median, beta = 0.25, 0.45
    k = _stripe_counts(rng, ag, n, median, beta)
    fit = fit_fragility(ag, n, k)
    assert fit.is_fitted and fit.note == ""
    assert abs(math.log(fit.median_g) - math.log(median)) < 3 * fit.se_ln_median
    assert abs(fit.beta - beta) < 3 * fit.se_beta
    assert fit.se_ln_median < 0.2 and fit.se_beta < 0.2
    assert fit.loglik == pytest.approx(log_likelihood(ag, n, k, fit.median_g, fit.beta))
    # the optimum: moving either parameter lowers the likelihood
    for dm, db in ((1.02, 0), (0.98, 0), (1, 0.02), (1, -0.02)):
        assert log_likelihood(ag, n, k, fit.median_g * dm, fit.beta + db) < fit.loglik
    assert fit.dof == 7 and fit.deviance >= 0 and fit.max_residual < 4


def test_fit_coverage_over_many_seeds():
    """About 95 % of 2-standard-error intervals cover the true median (binomial check)."""
    ag = np.geomspace(0.05, 0.8, 9)
    n = np.full(9, 7)
    covered = 0
    trials = 60
    for seed in range(trials):
        k = _stripe_counts(np.random.default_rng(100 + seed), ag, n, 0.25, 0.45)
        fit = fit_fragility(ag, n, k)
        if fit.is_fitted and math.isfinite(fit.se_ln_median):
            covered += abs(math.log(fit.median_g / 0.25)) < 2 * fit.se_ln_median
    assert covered >= 0.8 * trials


def test_fit_bounds_are_reported_not_invented():
    ag = np.array([0.05, 0.1, 0.2])
    never = fit_fragility(ag, [7, 7, 7], [0, 0, 0])
    assert never.bound == "lower" and never.median_g == 0.2 and math.isnan(never.beta)
    assert "lower bound" in never.note and math.isnan(never.probability(0.1))
    always = fit_fragility(ag, [7, 7, 7], [7, 7, 7])
    assert always.bound == "upper" and always.median_g == 0.05 and math.isnan(always.beta)
    step = fit_fragility(ag, [7, 7, 7], [0, 7, 7])
    assert step.is_fitted and step.beta == pytest.approx(0.05) and "lower limit" in step.note
    assert 0.05 < step.median_g < 0.1


@pytest.mark.parametrize(
    ("ag", "n", "k", "match"),
    [
        ([0.1, 0.2], [7], [1], "one length"),
        ([0.1, -0.2], [7, 7], [1, 2], "ag_g"),
        ([0.1, 0.2], [7, 7], [1, 8], "n_failures"),
        ([0.1, 0.2], [0, 7], [0, 2], "n_records"),
    ],
)
def test_fit_refuses_bad_stripes(ag, n, k, match):
    with pytest.raises(RiskError, match=match):
        fit_fragility(ag, n, k)


def test_lv1_indices_and_bounds():
    ag = np.array([0.05, 0.06, 0.07, 0.08, 0.09, 0.1, 0.15, 0.2, 0.3])
    curve = HazardCurve.from_return_periods(TR, ag)
    fit = fit_fragility([0.05, 0.1, 0.15, 0.2], [7, 7, 7, 7], [0, 2, 4, 6])
    lv1 = lv1_indices(fit, curve, tr_slv_y=712.0, ag_slv_g=curve.ag_at(712.0))
    assert lv1.capacity_pga_g == fit.median_g
    assert lv1.capacity_return_period_y == pytest.approx(curve.return_period(fit.median_g))
    assert lv1.safety_index == pytest.approx(lv1.capacity_return_period_y / 712.0)
    assert lv1.acceleration_factor == pytest.approx(fit.median_g / curve.ag_at(712.0))
    never = fit_fragility([0.05, 0.3], [7, 7], [0, 0])
    bound = lv1_indices(never, curve, 712.0, 0.17)
    assert bound.bound == "lower" and "lower bounds" in bound.note
    assert bound.capacity_return_period_y == pytest.approx(2475.0)
    far = fit_fragility([0.5, 0.9], [7, 7], [0, 7])
    assert "extrapolated" in lv1_indices(far, curve, 712.0, 0.17).note


def test_classes_and_ranking():
    assert [risk_class(x) for x in (2.0, 1.0, 0.7, 0.4, 0.1, math.nan, math.inf)] == [
        "meets",
        "meets",
        "moderate",
        "high",
        "very_high",
        "undefined",
        "meets",
    ]
    assert risk_class(0.4, parse_limits("0.8,0.5,0.2")) == "high"
    for bad in ("1,2,3", "1,0.5", "a,b,c", "1,0.5,-1"):
        with pytest.raises(RiskError, match="class limits"):
            parse_limits(bad)
    rows = [
        {
            "id": "a",
            "median_is_bound": "lower",
            "annual_rate_overturning_per_y": math.nan,
            "safety_index": 5.0,
        },
        {
            "id": "b",
            "median_is_bound": "",
            "annual_rate_overturning_per_y": 1e-4,
            "safety_index": 1.2,
        },
        {
            "id": "c",
            "median_is_bound": "",
            "annual_rate_overturning_per_y": 1e-3,
            "safety_index": 0.4,
        },
        {
            "id": "d",
            "median_is_bound": "upper",
            "annual_rate_overturning_per_y": math.nan,
            "safety_index": 0.01,
        },
    ]
    assert [r["id"] for r in rank_towers(rows)] == ["d", "c", "b", "a"]


def test_the_curves_logarithms_kept_give_the_values_computed_afresh():
    """HazardCurve keeps ln a, ln lambda and the slopes: the same values, read-only."""
    ag = np.array([0.05, 0.08, 0.11, 0.2, 0.31])
    rate = 1.0 / np.array([30.0, 72.0, 140.0, 475.0, 2475.0])
    curve = HazardCurve(ag, rate)
    slopes = -np.diff(np.log(rate)) / np.diff(np.log(ag))
    np.testing.assert_array_equal(curve.slopes, slopes)
    with pytest.raises(ValueError, match="read-only"):
        curve.slopes[0] = 1.0
    a = np.geomspace(0.01, 1.0, 500)
    seg = np.searchsorted(np.log(ag)[1:-1], np.log(a), side="right")
    direct = np.exp(np.log(rate)[seg] - slopes[seg] * (np.log(a) - np.log(ag)[seg]))
    np.testing.assert_array_equal(curve.rate(a), direct)
    first = annual_rate_of_overturning(curve, 0.2, 0.4)
    assert annual_rate_of_overturning(HazardCurve(ag, rate), 0.2, 0.4) == first
    assert annual_rate_of_overturning(curve, 0.2, 0.4) == first
