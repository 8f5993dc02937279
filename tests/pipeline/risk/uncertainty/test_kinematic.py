"""Best-estimate kinematic capacities per sample (``risk.uncertainty.kinematic``, issue 31).

The mechanisms and checks are the code's (``tower_mechanisms``, ``kinematic_check``) at
F_C = 1 with the sample's period and type: a sample equal to the row's values gives the
code's non-linear capacity at F_C = 1; interpolating on period nodes stays within a few
per cent of checking every sample, and a bounded node's bound is carried.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.checks.kinematic import kinematic_capacity, kinematic_check
from rockscreen.pipeline.risk.checks.kinematic_demand import (
    activation_demand,
    displacement_demand,
)
from rockscreen.pipeline.risk.checks.tower_mechanisms import (
    belfry_kinematic_mechanism,
    tower_kinematic_mechanism,
)
from rockscreen.pipeline.risk.uncertainty import TowerPriors
from rockscreen.pipeline.risk.uncertainty.kinematic import kinematic_capacities
from rockscreen.stations.inventory import Tower

from rockscreen_testsupport.towers import LAQUILA, belfry_tower
from rockscreen_testsupport.towers import LAQUILA_SITE as SITE

BELFRY = belfry_tower("B", bells_mass_kg=0.0)  # no bells: the whole tower's mass does not enter
SLENDER = Tower(id="S", width_m=3.0, height_m=45.0, lat=LAQUILA[1], lon=LAQUILA[0], soil_class="D")


def _samples(tower: Tower, n: int, seed: int = 0) -> dict:
    return TowerPriors.from_tower(tower).sample(np.random.default_rng(seed), n)


def test_a_sample_at_the_rows_values_is_the_codes_capacity_at_fc_1():
    row = replace(BELFRY, shaft_period_s=0.8)
    samples = _samples(row, 3)
    # the code's bound behaviour, kept available (extrapolate=False)
    caps, notes = kinematic_capacities(row, SITE, samples, extrapolate=False)
    assert [c.name for c in caps] == ["whole tower", "belfry"]
    whole, _ = tower_kinematic_mechanism(row)
    belfry, shaft, _ = belfry_kinematic_mechanism(row)
    for cap, check in (
        (caps[0], kinematic_check(whole, SITE, fc=1.0)),
        (caps[1], kinematic_check(belfry, SITE, fc=1.0, support=shaft)),
    ):
        np.testing.assert_array_equal(cap.ag_g, check.nonlinear.ag_g)
        assert set(cap.bound) == {check.nonlinear.bound}
    code = kinematic_check(belfry, SITE, fc=1.35, support=shaft).nonlinear
    assert caps[1].ag_g[0] >= code.ag_g
    assert any(note.render().startswith("belfry kinematic") for note in notes)
    assert not any("solid prism" in note.render() for note in notes)
    # the screening risk's default: a bounded check is continued beyond the table
    beyond, _ = kinematic_capacities(row, SITE, samples)
    for cap, old in zip(beyond, caps, strict=True):
        bounded = old.bound != ""
        np.testing.assert_array_equal(cap.ag_g[~bounded], old.ag_g[~bounded])
        assert np.all(cap.bound == "")
        np.testing.assert_array_equal(cap.extrapolated, bounded)
        lower = old.bound == "lower"
        assert np.all(cap.ag_g[lower] > old.ag_g[lower])
    assert np.any(caps[0].bound == "lower")  # the whole tower holds at 2475 y here


def test_interpolation_on_period_nodes_is_close_to_every_samples_check():
    samples = _samples(BELFRY, 40, seed=2)
    nodes, _ = kinematic_capacities(BELFRY, SITE, samples, period_nodes=17, extrapolate=False)
    exact, _ = kinematic_capacities(BELFRY, SITE, samples, period_nodes=None, extrapolate=False)
    for a, b in zip(nodes, exact, strict=True):
        both = (a.bound == "") & (b.bound == "")
        assert np.all(a.bound[b.bound != ""] != "")  # a bound is never read as a value
        if both.any():
            np.testing.assert_allclose(a.ag_g[both], b.ag_g[both], rtol=0.03)
    assert np.any(exact[1].bound == "")  # the belfry is checked, not bounded, here
    # continued beyond the table, every value interpolates as closely
    nodes, _ = kinematic_capacities(BELFRY, SITE, samples, period_nodes=17)
    exact, _ = kinematic_capacities(BELFRY, SITE, samples, period_nodes=None)
    for a, b in zip(nodes, exact, strict=True):
        np.testing.assert_array_equal(a.extrapolated, b.extrapolated)
        np.testing.assert_allclose(a.ag_g, b.ag_g, rtol=0.03)


def test_tall_towers_never_overturn_at_the_site_a_lower_bound_not_a_value():
    """45 m x 3 m on soil D at L'Aquila: the whole tower holds at 2475 y for every period."""
    samples = _samples(SLENDER, 30, seed=1)
    assert np.unique(samples["period_s"]).size == 30
    (whole,), _ = kinematic_capacities(SLENDER, SITE, samples, period_nodes=None, extrapolate=False)
    assert set(whole.bound) == {"lower"}
    assert whole.ag_g == pytest.approx(SITE.hazard(2475.0).ag_g)


def test_beyond_the_table_the_capacity_is_the_linear_continuation():
    """The same towers, extrapolated: ag(2475) x the larger capacity-to-demand ratio."""
    samples = _samples(SLENDER, 30, seed=1)
    (whole,), _ = kinematic_capacities(SLENDER, SITE, samples, period_nodes=None)
    ag_end = SITE.hazard(2475.0).ag_g
    assert set(whole.bound) == {""} and whole.extrapolated.all()
    assert np.all(whole.ag_g > ag_end)
    hazard = SITE.hazard(2475.0)
    for i in (0, 17):
        row = replace(SLENDER, shaft_period_s=float(samples["period_s"][i]))
        mechanism, _ = tower_kinematic_mechanism(row)
        cap = kinematic_capacity(mechanism, 1.0)
        act = activation_demand(cap.t0_s, hazard, SITE, None)
        disp = displacement_demand(cap.t0_s, cap.t_slv_s, hazard, SITE, None)
        expected = ag_end * max(cap.a0_star_m_s2 / act, cap.du_star_m / disp)
        assert whole.ag_g[i] == pytest.approx(expected, rel=1e-12)
        # the code's check at that ag, shape held: holds at equality (both sides scale)
        assert max(cap.a0_star_m_s2 / act, cap.du_star_m / disp) >= 1.0


def test_missing_or_uneven_samples_are_refused():
    samples = _samples(BELFRY, 4)
    with pytest.raises(RiskError, match="lack period_s"):
        kinematic_capacities(BELFRY, SITE, {k: v for k, v in samples.items() if k != "period_s"})
    samples["wall_m"] = samples["wall_m"][:2]
    with pytest.raises(RiskError, match="differ in length"):
        kinematic_capacities(BELFRY, SITE, samples)
    with pytest.raises(RiskError, match="period_nodes"):
        kinematic_capacities(BELFRY, SITE, _samples(BELFRY, 4), period_nodes=1)
