"""Capacities beyond the NTC 2018 table for the screening risk (issue 31).

A tower whose checks hold at 2475 y: the code's bound stays the code's (and the library's
with ``extrapolate=False``); the screening risk's capacity is the demand continued beyond
the table with the shape held at 2475 y, a value, and its P a value below the bound's.
"""

from __future__ import annotations

import numpy as np
import pytest

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.assess.sites import tower_sites
from rockscreen.pipeline.risk.checks.confidence import confidence_factor
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.checks.tower_lv1 import lv1_demand
from rockscreen.pipeline.risk.checks.tower_lv1_checks import lv1_columns
from rockscreen.pipeline.risk.uncertainty import TowerPriors, shaft_capacity
from rockscreen.pipeline.risk.uncertainty.extrapolation import (
    CONTINUED_BOUNDS,
    end_return_period_y,
    linear_beyond_table,
    spectral_beyond_table,
)
from rockscreen.pipeline.risk.uncertainty.kinematic import MechanismCapacity
from rockscreen.pipeline.risk.uncertainty.risk import site_hazard_curve, tower_risk
from rockscreen.stations.inventory import Tower

LECCE = (18.17, 40.35)  # lon, lat [deg]: a low hazard, ag(2475) about 0.08 g on rock
SITE = SiteConditions(lon_deg=LECCE[0], lat_deg=LECCE[1], soil_class="B")
#: A squat, thick-walled brick tower: its shaft holds at 2475 y.
STOUT = Tower(
    id="STOUT",
    width_m=8.0,
    height_m=14.0,
    lat=LECCE[1],
    lon=LECCE[0],
    soil_class="B",
    wall_thickness_m=2.0,
    wall_thickness_top_m=2.0,
    masonry_type="solid_brick",
    masonry_strength_mpa=5.0,
    shaft_period_s=0.25,
)


def _samples(n: int = 5) -> dict:
    return TowerPriors.from_tower(STOUT).sample(np.random.default_rng(0), n)


def test_a_shaft_holding_at_2475_y_gets_the_linear_continuation():
    samples = _samples()
    bounded = shaft_capacity(STOUT, SITE, samples, extrapolate=False)
    assert set(bounded.bound) == {"lower"}  # the old behaviour, kept
    ag_end = SITE.hazard(2475.0).ag_g
    np.testing.assert_allclose(bounded.ag_g, ag_end)
    cap = shaft_capacity(STOUT, SITE, samples)
    assert set(cap.bound) == {""} and cap.extrapolated.all()
    assert np.all(np.isfinite(cap.ag_g)) and np.all(cap.ag_g > ag_end)
    demand = lv1_demand(0.25, SITE.hazard(2475.0), SITE, None)
    np.testing.assert_allclose(cap.ag_g, ag_end * cap.se_slv_m_s2 / demand, rtol=1e-12)
    # the mechanics are the same: only the capacity's reading changes
    np.testing.assert_array_equal(cap.se_slv_m_s2, bounded.se_slv_m_s2)


def test_only_above_the_table_a_capacity_is_continued():
    """A check failing at 30 y keeps its bound (CONTINUED_BOUNDS): NaN, the caller keeps it."""
    se = np.array([1.0e-3, 1.0e3])
    ag = spectral_beyond_table(se, np.array([0.5, 0.5]), np.array(["upper", "lower"]), SITE)
    high = SITE.hazard(2475.0)
    assert CONTINUED_BOUNDS == ("lower",)
    assert np.isnan(ag[0]) and ag[1] > high.ag_g
    assert end_return_period_y("upper") == 30.0 and end_return_period_y("lower") == 2475.0
    with pytest.raises(RiskError, match="allowed"):
        end_return_period_y("")
    assert np.isnan(linear_beyond_table(0.1, 0.0, 1.0))  # no capacity: the bound stays
    with pytest.raises(RiskError, match="must be > 0"):
        linear_beyond_table(0.1, 1.0, 0.0)


def test_its_p_is_a_value_below_the_bounds_and_the_codes_verdict_is_unchanged():
    samples = _samples(100)
    curve = site_hazard_curve(SITE)
    old = shaft_capacity(STOUT, SITE, samples, extrapolate=False)
    new = shaft_capacity(STOUT, SITE, samples)
    as_bound = tower_risk([MechanismCapacity("shaft", old.ag_g, old.bound)], curve)
    as_value = tower_risk(
        [MechanismCapacity("shaft", new.ag_g, new.bound, new.extrapolated)], curve
    )
    assert as_bound.p50_best_bound == "at_most"
    assert as_value.p50_best_bound == "" and as_value.p50_mean_bound == ""
    assert as_value.p50_best < as_bound.p50_best
    assert as_value.extrapolated_share == pytest.approx(1.0)
    assert 0.0 < as_value.rate_extrapolated_share <= 1.0
    assert as_bound.extrapolated_share == 0.0
    # the code's LV1 of the tower still holds at 2475 y: a lower bound
    columns, _, missing = lv1_columns(tower_sites([STOUT])[0], confidence_factor("LC3"), "LC3")
    assert missing == [] and columns["lv1_bound"] == "lower"
    assert columns["lv1_capacity_ag_g"] == pytest.approx(SITE.hazard(2475.0).ag_g)


def test_an_extrapolated_capacity_carries_no_bound():
    with pytest.raises(RiskError, match="no bound"):
        MechanismCapacity("shaft", np.array([0.2]), np.array(["lower"]), np.array([True]))


def test_on_the_ground_all_samples_at_once_equal_the_per_sample_continuation():
    """The array demand at the table's end is lv1_demand's per sample: the same values, exactly."""
    rng = np.random.default_rng(2)
    t1 = rng.uniform(0.05, 3.0, 200)
    se = rng.uniform(0.0, 30.0, 200)
    se[:3] = 0.0  # no capacity: NaN, the bound stays
    flags = np.where(rng.random(200) < 0.7, "lower", "upper").astype(object)
    got = spectral_beyond_table(se, t1, flags, SITE)
    high = SITE.hazard(2475.0)
    expected = [
        linear_beyond_table(high.ag_g, se[i], lv1_demand(float(t1[i]), high, SITE, None))
        if flags[i] == "lower"
        else np.nan
        for i in range(200)
    ]
    np.testing.assert_array_equal(got, expected)
