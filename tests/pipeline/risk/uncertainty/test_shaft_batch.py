"""The fast paths of the uncertainty library equal the reference computations.

The shaft's sections of all samples at once equal the code's per-sample mechanics.

``shaft_capacity(batch=True)`` (``critical_sections``: the LV1 mechanics in array form)
against ``batch=False`` (``shaft_model`` and ``checks.tower_lv1.shaft_sections`` per
sample, the reference): the same S_e,SLV, compression ratio and critical height on square
and rectangular plans, prismatic and tapering shafts, solid sections, shafts crushing under
their own weight, with and without a belfry and bells, at the best estimate's and the code's
factors. The risk rates of many capacities (a spline on nodes) follow the risk integral.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.measures.hazard_integral import annual_rate_of_overturning
from rockscreen.pipeline.risk.uncertainty import TowerPriors, shaft_capacity
from rockscreen.pipeline.risk.uncertainty.risk import (
    RATE_NODES,
    rates_of_capacities,
    site_hazard_curve,
)
from rockscreen.stations.inventory import Tower

from rockscreen_testsupport.towers import LAQUILA
from rockscreen_testsupport.towers import LAQUILA_SITE as SITE

SQUARE = Tower(id="S", width_m=5.0, height_m=34.0, lat=LAQUILA[1], lon=LAQUILA[0])
RECTANGLE = replace(SQUARE, id="R", width_m=7.0, depth_m=4.5, height_m=55.0)
BELFRY = replace(
    RECTANGLE,
    id="B",
    height_m=40.0,
    belfry_height_m=6.0,
    belfry_width_m=1.0,
    belfry_mass_kg=90000.0,
    bells_mass_kg=4000.0,
    bells_height_m=2.5,
)


def _samples(tower: Tower, n: int, seed: int) -> dict[str, np.ndarray]:
    samples = TowerPriors.from_tower(tower).sample(np.random.default_rng(seed), n)
    # A few solid sections (wall of half the side), prismatic shafts and weak masonry.
    side = min(tower.width_m, tower.plan_depth_m)
    samples["wall_m"][:5] = 0.5 * side
    samples["wall_top_m"][3:8] = samples["wall_m"][3:8]
    samples["fm_pa"][8:12] = 0.3e6  # crushes under its own weight (tall towers)
    return samples


@pytest.mark.parametrize("tower", [SQUARE, RECTANGLE, BELFRY], ids=lambda t: t.id)
@pytest.mark.parametrize(("gamma_m", "fc"), [(1.0, 1.0), (2.0, 1.35)])
def test_batch_sections_equal_the_per_sample_mechanics(tower, gamma_m, fc):
    samples = _samples(tower, 120, seed=7)
    fast = shaft_capacity(tower, SITE, samples, gamma_m=gamma_m, fc=fc)
    slow = shaft_capacity(tower, SITE, samples, gamma_m=gamma_m, fc=fc, batch=False)
    np.testing.assert_allclose(fast.se_slv_m_s2, slow.se_slv_m_s2, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(fast.compression_ratio, slow.compression_ratio, rtol=1e-9)
    np.testing.assert_allclose(fast.critical_height_m, slow.critical_height_m, atol=1e-9)
    np.testing.assert_allclose(fast.ag_g, slow.ag_g, rtol=1e-9)
    assert list(fast.bound) == list(slow.bound)
    # The crushing samples were reached: no flexural capacity left, S_e,SLV = 0.
    assert np.all(slow.compression_ratio[8:12] >= 1.0)
    assert np.all(fast.se_slv_m_s2[8:12] == 0.0)


def test_rates_of_many_capacities_follow_the_risk_integral():
    """The spline over 65 nodes: within 5e-4 of integrating each capacity, 0.02-2 g."""
    curve = site_hazard_curve(SITE)
    theta = np.geomspace(0.02, 2.0, 400)
    spline = rates_of_capacities(curve, theta, 0.4)
    exact = np.array([annual_rate_of_overturning(curve, t, 0.4) for t in theta])
    np.testing.assert_allclose(spline, exact, rtol=5e-4)
    few = theta[:RATE_NODES]  # no more capacities than nodes: each integrated, exactly
    np.testing.assert_array_equal(rates_of_capacities(curve, few, 0.4), exact[:RATE_NODES])
    with pytest.raises(RiskError, match="nodes"):
        rates_of_capacities(curve, theta, 0.4, nodes=2)
