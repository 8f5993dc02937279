"""IDA fragilities wired into ``assess``: limit states, F_C and the bootstrap."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rockscreen.pipeline.hazard import hazard_curve
from rockscreen.pipeline.risk.assess.sites import tower_sites
from rockscreen.pipeline.risk.assess.tower_ida import bootstrap_intervals, record_intensities
from rockscreen.pipeline.risk.assess.tower_summary import summarize_tower
from rockscreen.pipeline.risk.measures.censored_fit import fit_censored_lognormal
from rockscreen.pipeline.risk.measures.hazard_integral import (
    HazardCurve,
    annual_rate_of_overturning,
)
from rockscreen.stations.inventory import Tower

TOWER = Tower(id="T", width_m=2.0, height_m=12.0, lat=41.04, lon=14.42)
COLLAPSE = (0.9, 1.1, 1.3, 1.6, 2.0, 2.4, 2.9)  # [g]
SLV = (0.35, 0.45, 0.5, 0.6, 0.7, 0.9, 1.0)  # [g]


def _ida(collapse=COLLAPSE, slv=SLV, censored=()):
    rows = []
    for i, (c, s) in enumerate(zip(collapse, slv, strict=True)):
        for component, extra in (("X", 1.0), ("Y", 1.25)):  # Y never governs
            rows.append(
                {
                    "record": f"r{i}",
                    "component": component,
                    "models": "ground",
                    "collapse_ag_g": c * extra,
                    "censored": i in censored,
                    "slv_ag_g": s * extra,
                    "slv_censored": False,
                }
            )
    return rows


@pytest.fixture(scope="module")
def hazard():
    (site,) = tower_sites([TOWER], 0.01)
    periods, ag = hazard_curve(site.lon_deg, site.lat_deg)
    curve = HazardCurve.from_return_periods(periods, ag)
    return site, curve, 712.0, curve.ag_at(712.0)


@pytest.mark.parametrize(("level", "fc"), [(None, 1.35), ("LC2", 1.20), ("LC3", 1.00)])
def test_is_from_the_slv_median_and_rate_from_the_collapse_curve(hazard, level, fc):
    site, curve, tr_slv, ag_slv = hazard
    row = summarize_tower(site, [], curve, tr_slv, ag_slv, ida=_ida(), knowledge_level=level)
    slv = fit_censored_lognormal(SLV, [False] * 7)
    collapse = fit_censored_lognormal(COLLAPSE, [False] * 7)
    assert row["slv_median_g"] == pytest.approx(slv.median_g)
    assert row["collapse_median_g"] == pytest.approx(collapse.median_g)
    assert row["slv_median_g"] < 0.5 * row["collapse_median_g"]  # the two differ
    assert row["confidence_factor"] == fc
    a_c = slv.median_g / fc
    assert row["capacity_pga_g"] == pytest.approx(a_c)
    assert row["safety_index"] == pytest.approx(curve.return_period(a_c) / tr_slv)
    assert row["acceleration_factor"] == pytest.approx(a_c / ag_slv)
    # lambda_C from the collapse fragility, without F_C (a best estimate)
    rate = annual_rate_of_overturning(curve, collapse.median_g, collapse.beta)
    assert row["annual_rate_overturning_per_y"] == pytest.approx(rate)
    assert row["p_overturning_50y"] == pytest.approx(1 - math.exp(-50 * rate))
    assumed = "assumed: not in the inventory" in row["note"]
    assert assumed == (level is None) and f"F_C = {fc:.2f}" in row["note"]
    # the bootstrap intervals bracket the values
    assert row["bootstrap_resamples"] == 200
    lo, hi = row["collapse_median_lo90_g"], row["collapse_median_hi90_g"]
    assert lo < row["collapse_median_g"] < hi
    assert row["safety_index_lo90"] < row["safety_index"] < row["safety_index_hi90"]
    lo, hi = row["annual_rate_lo90_per_y"], row["annual_rate_hi90_per_y"]
    assert lo < row["annual_rate_overturning_per_y"] < hi


def test_lower_fc_raises_the_safety_index(hazard):
    site, curve, tr_slv, ag_slv = hazard
    rows = [
        summarize_tower(site, [], curve, tr_slv, ag_slv, ida=_ida(), knowledge_level=level)
        for level in ("LC1", "LC3")
    ]
    assert rows[0]["safety_index"] < rows[1]["safety_index"]
    assert rows[0]["annual_rate_overturning_per_y"] == rows[1]["annual_rate_overturning_per_y"]


def test_all_censored_is_a_bound_in_words_without_interval(hazard):
    site, curve, tr_slv, ag_slv = hazard
    ida = _ida(censored=range(7))
    row = summarize_tower(site, [], curve, tr_slv, ag_slv, ida=ida)
    assert row["collapse_bound"] == "lower" and math.isnan(row["collapse_beta"])
    assert "no record overturned the tower" in row["note"]
    assert math.isnan(row["annual_rate_overturning_per_y"])
    assert "only a bound" in row["note"]
    assert math.isnan(row["collapse_median_lo90_g"]) and row["bootstrap_fitted_collapse"] == 0
    assert row["slv_bound"] == "" and math.isfinite(row["safety_index"])


def test_record_combines_components_and_bootstrap_is_seeded(hazard):
    _, curve, tr_slv, _ = hazard
    data = record_intensities(_ida(), "collapse")
    assert data.records == tuple(f"r{i}" for i in range(7))
    assert np.allclose(data.ag_g, COLLAPSE) and not data.censored.any()
    a = bootstrap_intervals(_ida(), curve, tr_slv, 1.35, 50, seed=3)
    b = bootstrap_intervals(_ida(), curve, tr_slv, 1.35, 50, seed=3)
    assert a == b and a["bootstrap_fitted_collapse"] <= 50


@pytest.mark.parametrize("censored", [(), (5, 6), (1, 3, 6)])
def test_batched_bootstrap_equals_the_reference_fits(hazard, censored):
    """The default bootstrap (batched Newton) gives the reference's intervals (1e-6)."""
    _, curve, tr_slv, _ = hazard
    rows = _ida(censored=censored)
    fast = bootstrap_intervals(rows, curve, tr_slv, 1.35, 120, seed=7)
    reference = bootstrap_intervals(rows, curve, tr_slv, 1.35, 120, seed=7, method="trust-exact")
    assert fast.keys() == reference.keys()
    for key, expected in reference.items():
        if isinstance(expected, float):
            assert fast[key] == pytest.approx(expected, rel=1e-6, nan_ok=True), key
        else:
            assert fast[key] == expected, key
    assert fast["bootstrap_fitted_collapse"] > 0
