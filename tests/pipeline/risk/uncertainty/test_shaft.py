"""The best-estimate shaft capacity over the priors (``risk.uncertainty.shaft``, issue 31).

The mechanics are the code's LV1 (``checks.tower_lv1``): with the code's strength and
factors the functions give ``assess``'s ``lv1_capacity_ag_g`` exactly; with the priors
collapsed to points every sample gives the deterministic best estimate; a wider prior
widens the capacity's 90 % interval; the samples are reproducible with a seed.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.assess.sites import tower_sites
from rockscreen.pipeline.risk.checks.confidence import (
    MASONRY_TYPES,
    confidence_factor,
    masonry_strength,
)
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.checks.tower_lv1 import LV1_TOWER_Q, tower_period_guidelines
from rockscreen.pipeline.risk.checks.tower_lv1_checks import lv1_columns
from rockscreen.pipeline.risk.uncertainty import TowerPriors, best_estimate_lv1, shaft_capacity
from rockscreen.pipeline.risk.uncertainty.distributions import LogNormal, Point
from rockscreen.pipeline.risk.uncertainty.shaft import BEST_ESTIMATE_Q
from rockscreen.pipeline.risk.uncertainty.shaft_hazard import capacity_from_spectral
from rockscreen.stations.inventory import Tower

from rockscreen_testsupport.towers import LAQUILA, belfry_tower
from rockscreen_testsupport.towers import LAQUILA_SITE as SITE

#: A rectangular tapering brick tower with a belfry, measured f_m and period (every prior
#: of TowerPriors collapses on it).
FULL = belfry_tower(
    "FULL",
    wall_thickness_m=1.4,
    wall_thickness_top_m=0.8,
    masonry_strength_mpa=3.0,
    knowledge_level="LC3",
    shaft_period_s=0.7,
    bells_mass_kg=3000.0,
)
GEOMETRY_ONLY = Tower(
    id="G", width_m=6.0, height_m=34.0, lat=LAQUILA[1], lon=LAQUILA[0], soil_class="B"
)


def _conditions(tower: Tower) -> SiteConditions:
    s = tower_sites([tower])[0]
    return SiteConditions(
        lon_deg=s.lon_deg,
        lat_deg=s.lat_deg,
        soil_class=s.soil_class,
        topography=s.topography,
        nominal_life_y=s.nominal_life_y,
        use_class=s.use_class,
    )


@pytest.mark.parametrize("level", ["LC1", "LC2", "LC3"])
def test_with_the_codes_strength_and_factors_it_is_the_codes_lv1(level):
    """The same mechanics: best_estimate_lv1 at the code's f_d and q gives assess's LV1."""
    tower = FULL if level == "LC3" else replace(FULL, masonry_strength_mpa=None)
    tower = replace(tower, knowledge_level=level)
    fc = confidence_factor(level)
    site = tower_sites([tower])[0]
    columns, _, missing = lv1_columns(site, fc, level)
    assert missing == []
    measured = None if level != "LC3" else tower.masonry_strength_mpa * 1e6
    code = best_estimate_lv1(
        tower,
        _conditions(tower),
        wall_m=tower.wall_thickness_m,
        wall_top_m=tower.wall_thickness_top_m,
        unit_weight_n_m3=MASONRY_TYPES["solid_brick"].unit_weight_n_m3,
        fm_pa=masonry_strength("solid_brick", level, measured_pa=measured),
        period_s=tower.shaft_period_s,
        q=LV1_TOWER_Q,
        gamma_m=2.0,
        fc=fc,
    )
    assert code.capacity.ag_g == columns["lv1_capacity_ag_g"]
    assert code.critical.compression_ratio == columns["lv1_compression_ratio"]
    # The sampled path, fed the code's values, gives the code's capacity too.
    point = {
        "wall_m": [tower.wall_thickness_m],
        "wall_top_m": [tower.wall_thickness_top_m],
        "unit_weight_n_m3": [MASONRY_TYPES["solid_brick"].unit_weight_n_m3],
        "fm_pa": [masonry_strength("solid_brick", level, measured_pa=measured)],
        "period_s": [tower.shaft_period_s],
    }
    # the code's bound behaviour (extrapolate=False): a bound stays the code's bound
    cap = shaft_capacity(
        tower, _conditions(tower), point, q=LV1_TOWER_Q, gamma_m=2.0, fc=fc, extrapolate=False
    )
    assert cap.ag_g[0] == pytest.approx(columns["lv1_capacity_ag_g"], rel=1e-6)
    assert cap.compression_ratio[0] == pytest.approx(columns["lv1_compression_ratio"], rel=1e-12)
    assert cap.bound[0] == columns["lv1_bound"]


def test_collapsed_priors_reproduce_the_deterministic_best_estimate():
    priors = TowerPriors.from_tower(FULL)
    assert all(isinstance(p, Point) for p in priors.priors().values())
    samples = priors.sample(np.random.default_rng(1), 7)
    cap = shaft_capacity(FULL, _conditions(FULL), samples)
    reference = best_estimate_lv1(
        FULL,
        _conditions(FULL),
        wall_m=1.4,
        wall_top_m=0.8,
        unit_weight_n_m3=MASONRY_TYPES["solid_brick"].unit_weight_n_m3,
        fm_pa=3.0e6,
        period_s=0.7,
    )
    assert reference.q == BEST_ESTIMATE_Q
    assert reference.capacity.bound == ""
    # The mechanics are the same calls: equal to round-off (the top wall is base x ratio).
    np.testing.assert_allclose(cap.se_slv_m_s2, reference.se_slv_m_s2, rtol=1e-12)
    np.testing.assert_allclose(
        cap.compression_ratio, reference.critical.compression_ratio, rtol=1e-12
    )
    # The inversion on the hazard: both to about 1e-7 in ln T_R.
    np.testing.assert_allclose(cap.ag_g, reference.capacity.ag_g, rtol=1e-6)
    np.testing.assert_allclose(cap.return_period_y, reference.capacity.return_period_y, rtol=1e-6)
    assert cap.interval_g(0.9)[1] - cap.interval_g(0.9)[0] == pytest.approx(0.0, abs=1e-12)


def test_the_best_estimate_is_stronger_than_the_codes_check():
    """Mean strength, no gamma_M nor F_C: a lower compression ratio and a higher capacity."""
    tower = replace(FULL, masonry_strength_mpa=None, knowledge_level="LC1")
    args = dict(
        wall_m=1.4,
        wall_top_m=0.8,
        unit_weight_n_m3=MASONRY_TYPES["solid_brick"].unit_weight_n_m3,
        period_s=0.7,
    )
    code = best_estimate_lv1(
        tower, SITE, fm_pa=2.6e6, gamma_m=2.0, fc=confidence_factor("LC1"), **args
    )
    best = best_estimate_lv1(tower, SITE, fm_pa=3.45e6, **args)
    ratio = best.critical.compression_ratio / code.critical.compression_ratio
    # f_d 2.6 / 2.7 MPa against f_m 3.45 MPa, at the same section when it stays critical.
    assert best.critical.compression_ratio < code.critical.compression_ratio
    assert ratio == pytest.approx((2.6 / 2.7) / 3.45, rel=0.25)
    assert best.capacity.ag_g > code.capacity.ag_g


@pytest.mark.parametrize("name", ["period", "wall"])
def test_a_wider_prior_widens_the_interval(name):
    """Each prior alone (the others points): its log-std from 0.1 to 0.5 widens the band."""
    tower = replace(GEOMETRY_ONLY, masonry_type="rubble", wall_thickness_m=1.2)
    priors = TowerPriors.from_tower(tower)
    period = priors.period if name == "period" else Point(0.6, "fixed")
    wall = LogNormal(1.2, 0.3, "test", upper=3.0) if name == "wall" else priors.wall
    priors = replace(priors, period=period, wall=wall, taper=Point(0.7, "fixed"), fm_given_pa=1.5e6)
    narrow = replace(priors, **{name: replace(getattr(priors, name), log_std=0.1)})
    wide = replace(priors, **{name: replace(getattr(priors, name), log_std=0.5)})
    site = _conditions(GEOMETRY_ONLY)
    widths = []
    for p in (narrow, wide):
        cap = shaft_capacity(GEOMETRY_ONLY, site, p.sample(np.random.default_rng(3), 200))
        lo, hi = cap.interval_g(0.9)
        widths.append(hi - lo)
    assert widths[1] > 2.0 * widths[0] > 0.0


def test_sampling_is_reproducible_and_stable_across_seeds():
    """The same seed gives the same capacities; at n = 200 the 90 % interval's ends move by
    less than 25 % across five seeds (the stated Monte-Carlo tolerance, docs/uncertainty.md)."""
    priors = TowerPriors.from_tower(GEOMETRY_ONLY)
    site = _conditions(GEOMETRY_ONLY)

    def run(seed):
        return shaft_capacity(GEOMETRY_ONLY, site, priors.sample(np.random.default_rng(seed), 200))

    a, b = run(11), run(11)
    np.testing.assert_array_equal(a.ag_g, b.ag_g)
    ends = np.array([run(seed).interval_g(0.9) for seed in range(5)])
    median = np.median(ends, axis=0)
    assert np.all(np.abs(ends / median - 1.0) < 0.25)


def test_capacity_from_spectral_bounds_like_the_code():
    """Above the 2475-y demand: a lower bound at 2475 y; below the 30-y demand: upper."""
    ag, tr, bound = capacity_from_spectral(np.array([1e3, 1e-3]), np.array([0.5, 0.5]), SITE)
    assert list(bound) == ["lower", "upper"]
    assert tr[0] == pytest.approx(2475.0) and tr[1] == pytest.approx(30.0)
    assert ag[0] == pytest.approx(SITE.hazard(2475.0).ag_g)


def test_missing_samples_are_refused():
    with pytest.raises(RiskError, match="fm_pa"):
        shaft_capacity(GEOMETRY_ONLY, SITE, {"wall_m": np.ones(2)})


def test_the_period_prior_is_the_guidelines_law_times_turris():
    priors = TowerPriors.from_tower(GEOMETRY_ONLY)
    assert isinstance(priors.period, LogNormal)
    assert priors.period.median == pytest.approx(0.9501 * tower_period_guidelines(34.0))


@pytest.mark.parametrize("soil", ["A", "B", "D"])
def test_the_ground_refinement_of_all_pairs_at_once_equals_the_per_pair_search(soil):
    """batch=True refines every pair on the ground at once: the per-pair search's roots, exactly.

    Capacities spread across the table's demand (bounded pairs both ends, repeated pairs,
    periods on every branch of the spectrum).
    """
    rng = np.random.default_rng(11)
    site = replace(SITE, soil_class=soil)
    t1 = np.concatenate([rng.uniform(0.05, 3.0, 300), [0.5, 0.5]])
    low = np.array([site.spectral_acceleration(t, site.hazard(30.0)) for t in t1])
    high = np.array([site.spectral_acceleration(t, site.hazard(2475.0)) for t in t1])
    se = np.exp(rng.uniform(np.log(0.7 * low), np.log(1.3 * high)))
    se[-1] = se[-2]
    ag, tr, bound = capacity_from_spectral(se, t1, site)
    ag_ref, tr_ref, bound_ref = capacity_from_spectral(se, t1, site, batch=False)
    assert {"", "lower", "upper"} <= set(bound)
    np.testing.assert_array_equal(tr, tr_ref)
    np.testing.assert_array_equal(ag, ag_ref)
    np.testing.assert_array_equal(bound, bound_ref)


def test_the_spectrum_of_many_actions_at_once_is_the_scalar_spectrum_bit_for_bit():
    """SiteConditions.spectral_accelerations: each (period, action) as spectral_acceleration."""
    rng = np.random.default_rng(5)
    for soil in "ABCDE":
        for topography in ("T1", "T3"):
            site = replace(SITE, soil_class=soil, topography=topography)
            periods = np.concatenate([rng.uniform(0.001, 5.0, 200), rng.lognormal(0.0, 1.0, 50)])
            actions = [site.hazard(x) for x in np.exp(rng.uniform(np.log(30), np.log(2475), 250))]
            many = site.spectral_accelerations(periods, actions)
            one = [
                site.spectral_acceleration(float(t), h)
                for t, h in zip(periods, actions, strict=True)
            ]
            np.testing.assert_array_equal(many, one)
    with pytest.raises(RiskError, match="one action per period"):
        SITE.spectral_accelerations(np.array([0.5, 0.6]), actions[:1])
    with pytest.raises(RiskError, match="period_s"):
        SITE.spectral_accelerations(np.array([0.5, 0.0]), actions[:2])
