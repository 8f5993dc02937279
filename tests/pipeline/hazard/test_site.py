"""Defaults and assumptions of a tower's hazard."""

from __future__ import annotations

import pytest

from rockscreen.pipeline.errors import HazardError
from rockscreen.pipeline.hazard import site_hazard
from rockscreen.pipeline.hazard.site import resolve_hazard, tower_hazard
from rockscreen.stations.inventory import Tower


def test_missing_soil_is_a_stated_assumption_never_silent():
    result = resolve_hazard(13.3995, 42.3498)
    assert (result.limit_state, result.nominal_life_y, result.use_class) == ("SLV", 50.0, "III")
    assert result.soil_class == "A" and result.soil_class_source == "default"
    assert sum("soil class unknown" in text for text in result.assumptions) == 1
    given = resolve_hazard(13.3995, 42.3498, soil_class="d", topography="t4")
    assert (given.soil_class, given.soil_class_source, given.topography) == ("D", "option", "T4")
    assert not any("soil" in text for text in given.assumptions)


def test_short_return_period_of_slo_uses_30_years_and_says_so():
    # Class I, V_N = 50: V_R = 35 y -> TR(SLO) = 21.1 y, below the table.
    result = resolve_hazard(14.42, 41.04, limit_state="SLO", use_class="I", nominal_life_y=50)
    assert result.site.return_period_y == 30.0
    assert result.site.ag_g == site_hazard(14.42, 41.04, 30).ag_g
    assert any("below the tabulated 30 y" in text for text in result.assumptions)
    with pytest.raises(HazardError, match="outside the tabulated"):
        resolve_hazard(14.42, 41.04, return_period_y=21.0)


def test_inventory_values_used_and_overridden():
    tower = Tower("T", 2.0, 6.0, lat=41.04, lon=14.42, use_class="IV", soil_class="C")
    result = tower_hazard(tower)
    assert result.use_class == "IV" and result.soil_class_source == "inventory"
    assert tower_hazard(tower, soil_class="B").soil_class_source == "option"
    with pytest.raises(HazardError, match="no lat/lon"):
        tower_hazard(Tower("U", 2.0, 6.0))
