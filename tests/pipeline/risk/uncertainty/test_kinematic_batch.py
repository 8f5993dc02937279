"""The kinematic capacities of many samples at once against the check per sample (issue 31).

``kinematic_capacities(batch=True)`` (the default) checks the samples together
(``risk.uncertainty.kinematic_batch``); ``batch=False`` with ``period_nodes=None`` calls the
code's ``kinematic_check`` for every sample, the reference. They must agree to rounding,
bounds and extrapolation flags included, on the ground, on a church, with a belfry and bells
in the row, with a sampled belfry, with and without the continuation beyond the table.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.checks.kinematic import kinematic_capacity, kinematic_check
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.checks.tower_mechanisms import (
    belfry_kinematic_mechanism,
    tower_kinematic_mechanism,
)
from rockscreen.pipeline.risk.uncertainty import TowerPriors
from rockscreen.pipeline.risk.uncertainty.belfry import BelfryPriors
from rockscreen.pipeline.risk.uncertainty.kinematic import kinematic_capacities
from rockscreen.pipeline.risk.uncertainty.kinematic_batch import nonlinear_capacities
from rockscreen.stations.inventory import Tower, example_inventory_path, read_inventory

LAQUILA = (13.3995, 42.3498)  # lon, lat [deg]
EXAMPLES = Path(__file__).resolve().parents[4] / "examples" / "tower_population"
T06 = next(t for t in read_inventory(EXAMPLES / "towers_geometry.csv") if t.id == "T06")
BELLS = Tower(
    id="BELLS",
    width_m=6.0,
    height_m=40.0,
    lat=LAQUILA[1],
    lon=LAQUILA[0],
    soil_class="B",
    belfry_height_m=6.0,
    belfry_width_m=2.5,
    belfry_mass_kg=60000.0,
    bells_mass_kg=5000.0,
    bells_height_m=4.0,
)
CHURCH = replace(BELLS, id="CHURCH", building_height_m=12.0, base_height_m=8.0, soil_class="C")
# Slender on soft soil: a whole tower failing inside the table; thinner, failing at 30 y.
SLENDER = Tower(
    id="SLENDER", width_m=1.0, height_m=14.0, lat=LAQUILA[1], lon=LAQUILA[0], soil_class="D"
)
THIN = replace(SLENDER, id="THIN", width_m=0.15)
#: A bell gable on the facade (no shaft period in the row: the gable does not need one).
GABLE = next(t for t in read_inventory(example_inventory_path()) if t.id == "ARC-08")


def _site(tower: Tower) -> SiteConditions:
    return SiteConditions(lon_deg=tower.lon, lat_deg=tower.lat, soil_class=tower.soil_class or "B")


def _compare(tower: Tower, samples: dict, extrapolate: bool) -> list:
    site = _site(tower)
    fast, fast_notes = kinematic_capacities(
        tower, site, samples, period_nodes=None, extrapolate=extrapolate
    )
    slow, slow_notes = kinematic_capacities(
        tower, site, samples, period_nodes=None, extrapolate=extrapolate, batch=False
    )
    assert [m.name for m in fast] == [m.name for m in slow]
    assert fast_notes == slow_notes
    for a, b in zip(fast, slow, strict=True):
        np.testing.assert_allclose(a.ag_g, b.ag_g, rtol=1e-9, err_msg=a.name)
        assert a.bound.tolist() == b.bound.tolist(), a.name
        assert a.extrapolated.tolist() == b.extrapolated.tolist(), a.name
    return fast


@pytest.mark.parametrize("extrapolate", [True, False])
@pytest.mark.parametrize(
    ("tower", "belfry"),
    [
        (T06, BelfryPriors()),
        (BELLS, None),
        (CHURCH, None),
        (SLENDER, None),
        (THIN, None),
        (GABLE, None),
    ],
    ids=["sampled_belfry", "bells", "church", "slender", "thin", "gable"],
)
def test_the_batch_is_the_check_of_every_sample(tower, belfry, extrapolate):
    samples = TowerPriors.from_tower(tower).sample(np.random.default_rng(5), 24, belfry=belfry)
    _compare(tower, samples, extrapolate)


def test_the_cases_cover_values_both_bounds_and_the_continuation():
    """Across the cases the batch meets values, both bounds and the continuation."""
    seen = set()
    for tower, belfry in [(T06, BelfryPriors()), (SLENDER, None), (THIN, None)]:
        samples = TowerPriors.from_tower(tower).sample(np.random.default_rng(5), 24, belfry=belfry)
        for extrapolate in (True, False):
            caps, _ = kinematic_capacities(tower, _site(tower), samples, extrapolate=extrapolate)
            for m in caps:
                seen |= {str(b) or "value" for b in m.bound}
                seen |= {"extrapolated"} if m.extrapolated.any() else set()
    assert seen == {"value", "lower", "upper", "extrapolated"}


def test_a_gable_row_without_a_period_gets_its_capacity():
    """The gable depends on the type only: its checks never set a period of 0 on the row."""
    samples = TowerPriors.from_tower(GABLE).sample(np.random.default_rng(2), 30)
    caps, _ = kinematic_capacities(GABLE, _site(GABLE), samples)
    gable = next(m for m in caps if m.name == "gable")
    assert np.unique(gable.ag_g).size <= len(set(samples["masonry_type"]))


def test_one_mechanism_equals_the_codes_check_at_fc_1():
    site = _site(BELLS)
    row = replace(BELLS, shaft_period_s=0.7, masonry_type="solid_brick")
    mechanism, support, _ = belfry_kinematic_mechanism(row)
    whole, _ = tower_kinematic_mechanism(row)
    code_belfry = kinematic_check(mechanism, site, fc=1.0, support=support).nonlinear
    code_whole = kinematic_check(whole, site, fc=1.0).nonlinear
    ag, bound = nonlinear_capacities(
        [kinematic_capacity(mechanism, 1.0)], site, [support], extrapolate=False
    )
    assert ag[0] == pytest.approx(code_belfry.ag_g, rel=1e-9)
    assert bound[0] == code_belfry.bound
    ag, bound = nonlinear_capacities([kinematic_capacity(whole, 1.0)], site, extrapolate=False)
    assert ag[0] == pytest.approx(code_whole.ag_g, rel=1e-9)
    assert bound[0] == code_whole.bound
    with pytest.raises(RiskError, match="supports"):
        nonlinear_capacities([kinematic_capacity(mechanism, 1.0)] * 2, site, [support])
