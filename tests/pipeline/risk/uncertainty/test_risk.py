"""The tower's risk over its epistemic samples (``risk.uncertainty.risk``, issue 31).

Priors collapsed to points give one P in 50 years, the deterministic one, and an interval of
zero width; a wider prior widens the interval; bounds are carried as flags, never as
values; the best estimate is stable across seeds at the default number of samples.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.checks.kinematic import kinematic_check
from rockscreen.pipeline.risk.checks.tower_mechanisms import tower_kinematic_mechanism
from rockscreen.pipeline.risk.measures.hazard_integral import (
    annual_rate_of_overturning,
    probability_in,
)
from rockscreen.pipeline.risk.uncertainty import TowerPriors, best_estimate_lv1, shaft_capacity
from rockscreen.pipeline.risk.uncertainty.distributions import Categorical, LogNormal, Point
from rockscreen.pipeline.risk.uncertainty.kinematic import MechanismCapacity, kinematic_capacities
from rockscreen.pipeline.risk.uncertainty.priors import masonry_prior
from rockscreen.pipeline.risk.uncertainty.risk import (
    DEFAULT_ALEATORY_BETA,
    DEFAULT_SAMPLES,
    quantile_bound,
    site_hazard_curve,
    stratum_weights,
    tower_risk,
)
from rockscreen.stations.inventory import Tower

from rockscreen_testsupport.towers import LAQUILA
from rockscreen_testsupport.towers import LAQUILA_SITE as SITE

CURVE = site_hazard_curve(SITE)
#: Every prior collapses: walls, type, strength and period given.
EXACT = Tower(
    id="EXACT",
    width_m=5.0,
    height_m=40.0,
    lat=LAQUILA[1],
    lon=LAQUILA[0],
    soil_class="B",
    wall_thickness_m=1.2,
    wall_thickness_top_m=0.8,
    masonry_type="rubble",
    masonry_strength_mpa=1.5,
    shaft_period_s=0.75,
)
GEOMETRY_ONLY = Tower(
    id="G", width_m=5.0, height_m=30.0, lat=LAQUILA[1], lon=LAQUILA[0], soil_class="B"
)


def _risk(tower: Tower, priors: TowerPriors, n: int, seed: int = 0):
    samples = priors.sample(np.random.default_rng(seed), n)
    shaft = shaft_capacity(tower, SITE, samples)
    kinematic, _ = kinematic_capacities(tower, SITE, samples)
    mechanisms = [MechanismCapacity("shaft", shaft.ag_g, shaft.bound), *kinematic]
    weights = stratum_weights(samples, priors)
    return tower_risk(mechanisms, CURVE, weights=weights), samples


def test_priors_collapsed_to_points_recover_the_deterministic_p50():
    """Exact inputs: every sample is the deterministic tower, the interval collapses."""
    priors = TowerPriors.from_tower(EXACT)
    assert all(isinstance(p, Point) for p in priors.priors().values())
    risk, samples = _risk(EXACT, priors, 20)
    shaft = best_estimate_lv1(
        EXACT,
        SITE,
        wall_m=1.2,
        wall_top_m=0.8,
        unit_weight_n_m3=float(samples["unit_weight_n_m3"][0]),
        fm_pa=1.5e6,
        period_s=0.75,
    ).capacity
    mechanism, _ = tower_kinematic_mechanism(EXACT)
    whole = kinematic_check(mechanism, SITE, fc=1.0).nonlinear
    theta = min(shaft.ag_g, whole.ag_g)
    assert not shaft.bound or theta == whole.ag_g
    expected = probability_in(annual_rate_of_overturning(CURVE, theta, DEFAULT_ALEATORY_BETA))
    assert risk.p50_best == pytest.approx(expected, rel=1e-6)
    assert risk.p50_lo90 == risk.p50_best == risk.p50_hi90
    assert risk.p50_mean == pytest.approx(risk.p50_best, rel=1e-12)
    assert risk.rate_lo90_per_y == risk.rate_hi90_per_y
    assert risk.governing_share == 1.0
    band = risk.fragility_band([0.1, 0.3])
    np.testing.assert_array_equal(band.lo90, band.hi90)


def test_a_wider_prior_widens_the_p50_interval():
    """The period's log-std 0.15 -> 0.6 (type fixed): the 90 % interval of P widens."""
    base = TowerPriors.from_tower(replace(GEOMETRY_ONLY, masonry_type="solid_brick"))
    widths = []
    for log_std in (0.15, 0.6):
        period = LogNormal(base.period.median_value, log_std, "test")
        risk, _ = _risk(GEOMETRY_ONLY, replace(base, period=period), 150)
        assert risk.p50_lo90 <= risk.p50_best <= risk.p50_hi90
        widths.append(risk.p50_hi90 - risk.p50_lo90)
    assert widths[1] > 1.5 * widths[0] > 0.0


def test_bounds_are_flags_not_values():
    """A capacity bounded at 2475 y makes the quantiles it reaches 'at most'; 30 y 'at least'."""
    n = 100
    ag = np.geomspace(0.1, 0.3, n)
    bound = np.full(n, "", dtype=object)
    bound[-20:] = "lower"  # the strongest 20 %: holds at the longest return period
    risk = tower_risk([MechanismCapacity("shaft", ag, bound)], CURVE)
    assert risk.p50_lo90_bound == "at_most"  # the 5 % quantile of P is a censored sample
    assert risk.p50_best_bound == "" and risk.p50_hi90_bound == ""
    assert risk.p50_mean_bound == "at_most"
    bound[:3] = "upper"
    risk = tower_risk([MechanismCapacity("shaft", ag, bound)], CURVE)
    assert risk.p50_hi90_bound == ""  # 3 % of the samples do not reach the 95 % quantile
    bound[:10] = "upper"
    risk = tower_risk([MechanismCapacity("shaft", ag, bound)], CURVE)
    assert risk.p50_hi90_bound == "at_least"
    assert risk.p50_mean_bound == "both"


def test_the_weakest_mechanism_governs_and_its_bound_follows():
    """min over mechanisms; an exact capacity below a lower bound is exact; 'upper' spreads."""
    shaft = MechanismCapacity("shaft", [0.2, 0.2, 0.2, 0.2], ["lower", "", "", ""])
    whole = MechanismCapacity("whole tower", [0.1, 0.3, 0.3, 0.3], ["", "", "upper", ""])
    risk = tower_risk([shaft, whole], CURVE)
    assert list(risk.governing) == ["whole tower", "shaft", "shaft", "shaft"]
    assert list(risk.capacity_bound) == ["", "", "upper", ""]
    assert risk.governing_mechanism == "shaft"
    assert risk.governing_share == pytest.approx(0.75)


def test_quantile_bound():
    values = np.array([0.1, 0.2, 0.3])
    flags = np.array(["at_most", "", "at_least"], dtype=object)
    assert quantile_bound(values, flags, 0.2) == ""
    assert quantile_bound(values, flags, 0.1) == "at_most"
    assert quantile_bound(values, flags, 0.3) == "at_least"


def test_stratum_weights_restore_the_priors_shares():
    """Type x period band: each stratum weighs its prior probability, whatever its count."""
    priors = TowerPriors.from_tower(GEOMETRY_ONLY)
    prior = Categorical((("rubble", 0.5), ("solid_brick", 0.5)), "test")
    priors = replace(priors, masonry=prior)
    samples = priors.sample(np.random.default_rng(4), 400)
    kinds = samples["masonry_type"].astype(str)
    w = stratum_weights(samples, priors, period_strata=4)
    assert w.sum() == pytest.approx(1.0)
    assert w[kinds == "rubble"].sum() == pytest.approx(0.5)
    median = priors.period.median_value
    assert w[samples["period_s"] < median].sum() == pytest.approx(0.5)
    fixed = replace(priors, masonry=Point("rubble", "x"), period=Point(0.7, "x"))
    one = fixed.sample(np.random.default_rng(4), 10)
    np.testing.assert_allclose(stratum_weights(one, fixed), 0.1)
    with pytest.raises(RiskError, match="not in the prior"):
        stratum_weights({**one, "masonry_type": np.array(["x"] * 10)}, priors)


def test_invalid_inputs_are_refused():
    with pytest.raises(RiskError, match="beta"):
        tower_risk([MechanismCapacity("shaft", [0.2], [""])], CURVE, beta=0.0)
    with pytest.raises(RiskError, match="bound flags"):
        MechanismCapacity("shaft", [0.2], ["maybe"])
    with pytest.raises(RiskError, match="finite"):
        MechanismCapacity("shaft", [0.0], [""])


def test_the_best_estimate_is_stable_across_seeds_at_the_default_n():
    """Geometry only, the default priors, n = DEFAULT_SAMPLES: three seeds within 10 %."""
    priors = TowerPriors.from_tower(GEOMETRY_ONLY)
    assert isinstance(priors.masonry, Categorical) and priors.masonry == masonry_prior()
    best = [_risk(GEOMETRY_ONLY, priors, DEFAULT_SAMPLES, seed)[0].p50_best for seed in range(3)]
    median = float(np.median(best))
    assert max(abs(b / median - 1.0) for b in best) <= 0.10


def test_fragility_band_median_band_and_mixture():
    """Four capacities: the median curve is a sample's curve, the mixture their mean."""
    from scipy.stats import norm

    ag = np.array([0.1, 0.2, 0.3, 0.4])
    risk = tower_risk([MechanismCapacity("shaft", ag, [""] * 4)], CURVE, beta=0.3)
    grid = np.array([0.05, 0.25, 1.0])
    band = risk.fragility_band(grid)
    curves = norm.cdf(np.log(grid[None, :] / ag[:, None]) / 0.3)
    np.testing.assert_allclose(band.mean, curves.mean(axis=0))
    np.testing.assert_allclose(band.median, curves[2])  # inverted_cdf: the 2nd of 4 from above
    np.testing.assert_allclose(band.lo90, curves[3])
    np.testing.assert_allclose(band.hi90, curves[0])
    assert band.bounded_share == 0.0
    assert risk.p50_lo90 <= risk.p50_best <= risk.p50_hi90
    with pytest.raises(RiskError):
        risk.fragility_band([0.0, 0.1])
