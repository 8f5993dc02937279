"""The shaft's capacity on a church's floor spectrum, all periods at once, equals the reference.

``capacity_from_spectral(batch=True)`` tabulates the LV1 demand of a tower standing on a
church (the Circolare 2019 floor spectrum, §C7.2.3, never below the ground's ``Se``) at all
the samples' periods of one return period at once (``lv1_demands``); ``batch=False`` calls
the code's scalar ``lv1_demand`` per (return period, period), the reference. Both refine
each sample's crossing with the same scalar false position: the capacities agree to 1e-9
relative (the refinement's own tolerance is 1e-7 in ln T_R), the bounds exactly. Towers on
the church of the example inventory (ARC-01), with and without a belfry and bells, on two
soils; the array demand against the scalar one element-wise, on every branch of the floor
spectrum.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from rockscreen.pipeline.errors import RockscreenError
from rockscreen.pipeline.risk.checks.kinematic_demand import (
    ElevatedSupport,
    elastic_spectral_demand,
    elastic_spectral_demands,
)
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.checks.tower_lv1 import lv1_demand, lv1_demands
from rockscreen.pipeline.risk.checks.tower_mechanisms import tower_support
from rockscreen.pipeline.risk.uncertainty import TowerPriors, shaft_capacity
from rockscreen.pipeline.risk.uncertainty.shaft_hazard import capacity_from_spectral
from rockscreen.stations.inventory import Tower, example_inventory_path, read_inventory

LAQUILA = (13.3995, 42.3498)  # lon, lat [deg]


def _church_tower() -> Tower:
    towers = {t.id: t for t in read_inventory(example_inventory_path())}
    return towers["ARC-01"]


CHURCH = _church_tower()
BELLS = replace(
    CHURCH,
    id="ARC-01-bells",
    height_m=14.0,
    belfry_height_m=3.0,
    belfry_width_m=0.6,
    belfry_mass_kg=12000.0,
    bells_mass_kg=1500.0,
    bells_height_m=2.0,
)


def _site(tower: Tower, soil: str) -> SiteConditions:
    return SiteConditions(lon_deg=tower.lon, lat_deg=tower.lat, soil_class=soil)


@pytest.mark.parametrize("tower", [CHURCH, BELLS], ids=lambda t: t.id)
@pytest.mark.parametrize("soil", ["A", "C"])
def test_floor_capacity_of_all_periods_at_once_equals_the_per_period_reference(tower, soil):
    support, _ = tower_support(tower)
    assert support is not None
    site = _site(tower, soil)
    samples = TowerPriors.from_tower(tower).sample(np.random.default_rng(3), 60)
    fast = shaft_capacity(tower, site, samples, support=support)
    # Spread the capacities so that both bounds and the interior are reached.
    se = fast.se_slv_m_s2 * np.geomspace(0.05, 20.0, fast.se_slv_m_s2.size)
    t1 = fast.period_s
    ag, tr, bound = capacity_from_spectral(se, t1, site, support)
    ag_ref, tr_ref, bound_ref = capacity_from_spectral(se, t1, site, support, batch=False)
    assert list(bound) == list(bound_ref)
    assert {"", "lower", "upper"} <= set(bound)
    np.testing.assert_allclose(tr, tr_ref, rtol=1e-9, atol=0.0)
    np.testing.assert_allclose(ag, ag_ref, rtol=1e-9, atol=0.0)
    # And the floor spectrum matters here: on the ground the capacities differ.
    ag_ground, _, _ = capacity_from_spectral(se, t1, site, None)
    assert np.max(np.abs(ag_ground / ag - 1.0)) > 0.01


@pytest.mark.parametrize("support", [None, ElevatedSupport(12.0, 0.35, level_m=9.0)])
def test_array_demand_equals_the_scalar_demand_at_every_period(support):
    site = SiteConditions(lon_deg=LAQUILA[0], lat_deg=LAQUILA[1], soil_class="B")
    hazard = site.hazard(475.0)
    # Across the floor spectrum's rising branch, plateau, falling branch (a = 0.8,
    # b = 1.1 of T_k = 0.35 s), the ground spectrum's corners and beyond T_D.
    periods = np.concatenate([np.geomspace(0.01, 4.0, 157), [0.28, 0.35, 0.385, 0.6]])
    many = lv1_demands(periods, hazard, site, support)
    one = np.array([lv1_demand(t, hazard, site, support) for t in periods])
    np.testing.assert_allclose(many, one, rtol=1e-13, atol=0.0)
    kin = elastic_spectral_demands(periods, hazard, site, support, damping=0.05)
    ref = np.array([elastic_spectral_demand(t, hazard, site, support) for t in periods])
    np.testing.assert_allclose(kin, ref, rtol=1e-13, atol=0.0)


@pytest.mark.parametrize("bad", [0.0, -0.3, float("nan")])
def test_array_demand_refuses_a_period_that_is_not_positive(bad):
    site = SiteConditions(lon_deg=LAQUILA[0], lat_deg=LAQUILA[1], soil_class="B")
    with pytest.raises(RockscreenError, match="period_s"):
        lv1_demands([0.5, bad], site.hazard(475.0), site, None)
