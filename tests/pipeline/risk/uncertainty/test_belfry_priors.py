"""The belfry priors of a geometry-only row (``risk.uncertainty.belfry``, issue 31).

Opt-in: without them the kinematic capacities are unchanged (no belfry on a row without
its columns); with them each sample has a belfry with the prior's probability, one of a
few equal-probability scenarios (a Latin hypercube), checked by the code's belfry
mechanism on the row the scenario builds; judgement priors are labelled.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.checks.kinematic import kinematic_check
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.checks.tower_mechanisms import belfry_kinematic_mechanism
from rockscreen.pipeline.risk.uncertainty import TowerPriors
from rockscreen.pipeline.risk.uncertainty.belfry import (
    BELFRY_KEYS,
    BELLS_MASS_MAX_KG,
    BelfryPriors,
    belfry_for_row,
    belfry_row,
)
from rockscreen.pipeline.risk.uncertainty.distributions import Uniform
from rockscreen.pipeline.risk.uncertainty.kinematic import (
    ABSENT_CAPACITY_G,
    kinematic_capacities,
)
from rockscreen.pipeline.risk.uncertainty.sensitivity import epistemic_inputs
from rockscreen.pipeline.verdict.messages import render
from rockscreen.solver.constants import G
from rockscreen.stations.inventory import example_inventory_path, read_inventory

EXAMPLES = Path(__file__).resolve().parents[4] / "examples" / "tower_population"
T06 = next(t for t in read_inventory(EXAMPLES / "towers_geometry.csv") if t.id == "T06")
SITE = SiteConditions(lon_deg=T06.lon, lat_deg=T06.lat, soil_class="B")


def test_samples_presence_scenarios_and_latin_hypercube():
    priors = BelfryPriors(scenarios=5)
    s = priors.sample(np.random.default_rng(2), 4000)
    assert set(s) == set(BELFRY_KEYS)
    assert s["belfry_present"].mean() == pytest.approx(0.9, abs=0.02)
    shares = np.unique(s["belfry_height_share"])
    assert shares.size == 5
    # One scenario per fifth of each prior (Latin hypercube).
    strata = np.floor((shares - 0.10) / 0.10 * 5).astype(int)
    assert sorted(strata.tolist()) == [0, 1, 2, 3, 4]
    assert np.all(s["bells_mass_kg"] <= BELLS_MASS_MAX_KG)
    assert set(priors.judgements) == {
        "belfry_present",
        "belfry_height_share",
        "belfry_opening_ratio",
        "bells_height_share",
    }  # the bells' mass is TURRIS's, not a judgement
    with pytest.raises(RiskError, match="presence"):
        BelfryPriors(presence=1.5)
    with pytest.raises(RiskError, match="opening"):
        BelfryPriors(opening_ratio=Uniform(0.5, 1.0, "x"))


def test_the_belfry_row_of_a_scenario():
    row = belfry_row(
        T06,
        height_share=0.15,
        opening_ratio=0.5,
        bells_mass_kg=5000.0,
        bells_height_share=0.7,
        wall_top_m=0.8,
        unit_weight_n_m3=18.0e3,
    )
    h = 0.15 * T06.height_m
    assert row.has_belfry and row.belfry_height_m == pytest.approx(h)
    assert row.belfry_width_m == pytest.approx(0.5 * T06.width_m)
    side = T06.width_m
    area = side * side - (side - 1.6) ** 2
    assert row.belfry_mass_kg == pytest.approx(0.5 * area * h * 18.0e3 / G)
    assert row.bells_height_m == pytest.approx(0.7 * h)
    with pytest.raises(RiskError, match="has its belfry"):
        belfry_row(
            row,
            height_share=0.1,
            opening_ratio=0.5,
            bells_mass_kg=1.0,
            bells_height_share=0.5,
            wall_top_m=0.8,
            unit_weight_n_m3=18.0e3,
        )


def test_opt_in_default_unchanged_and_the_sampled_belfry_checked():
    """Type and period points: every present sample is its scenario's row's check."""
    row = replace(T06, masonry_type="solid_brick", shaft_period_s=0.6)
    priors = TowerPriors.from_tower(row)
    plain = priors.sample(np.random.default_rng(5), 40)
    with_belfry = priors.sample(np.random.default_rng(5), 40, belfry=BelfryPriors(scenarios=2))
    for key in plain:  # the belfry draws come last: the other inputs are the same draws
        np.testing.assert_array_equal(plain[key], with_belfry[key])
    names = [m.name for m in kinematic_capacities(row, SITE, plain)[0]]
    assert "belfry" not in names  # the default: no belfry on a row without its columns
    caps, _ = kinematic_capacities(row, SITE, with_belfry)
    belfry = next(m for m in caps if m.name == "belfry")
    present = with_belfry["belfry_present"]
    assert 0 < present.sum() < present.size
    assert np.all(belfry.ag_g[~present] == ABSENT_CAPACITY_G)
    assert set(belfry.bound[~present]) == {"lower"}
    i = int(np.flatnonzero(present)[0])
    expected_row = belfry_row(
        row,
        height_share=with_belfry["belfry_height_share"][i],
        opening_ratio=with_belfry["belfry_opening_ratio"][i],
        bells_mass_kg=with_belfry["bells_mass_kg"][i],
        bells_height_share=with_belfry["bells_height_share"][i],
        wall_top_m=float(
            np.median(
                with_belfry["wall_top_m"][
                    present
                    & (with_belfry["belfry_height_share"] == with_belfry["belfry_height_share"][i])
                ]
            )
        ),
        unit_weight_n_m3=float(with_belfry["unit_weight_n_m3"][i]),
    )
    mechanism, support, _ = belfry_kinematic_mechanism(expected_row)
    check = kinematic_check(mechanism, SITE, fc=1.0, support=support).nonlinear
    assert belfry.ag_g[i] == pytest.approx(check.ag_g, rel=1e-12)
    assert "belfry_height_share" in epistemic_inputs(with_belfry)


def test_the_screening_risks_default_for_a_row_with_and_without_its_belfry():
    """Sampled for a row without the columns, with its judgements labelled; none otherwise."""
    priors, judged, notes = belfry_for_row(T06, BelfryPriors())
    assert priors == BelfryPriors()
    assert set(judged) == set(BelfryPriors().judgements)
    codes = [m.code for m in notes]
    assert codes[0] == "risk.belfry_sampled" and codes.count("risk.judgement_prior") == 4
    labelled = {m.kwargs["input"] for m in notes if m.code == "risk.judgement_prior"}
    assert labelled == set(judged)
    assert "probabilità 0,90" in render(notes[0], "it")
    with_columns = belfry_row(
        T06,
        height_share=0.15,
        opening_ratio=0.5,
        bells_mass_kg=5000.0,
        bells_height_share=0.7,
        wall_top_m=0.8,
        unit_weight_n_m3=18.0e3,
    )
    assert belfry_for_row(with_columns, BelfryPriors()) == (None, (), [])
    none, judged, notes = belfry_for_row(T06, None)
    assert none is None and judged == () and [m.code for m in notes] == ["risk.belfry_not_sampled"]
    # a bell gable holds the bells; a tower too low for the prior's shortest belfry: none, said
    gable = next(t for t in read_inventory(example_inventory_path()) if t.id == "ARC-08")
    assert [m.code for m in belfry_for_row(gable, BelfryPriors())[2]] == ["risk.belfry_in_gable"]
    low = replace(T06, height_m=4.0, width_m=1.0, depth_m=1.0)
    none, _, notes = belfry_for_row(low, BelfryPriors())
    assert none is None and [m.code for m in notes] == ["risk.belfry_too_low"]
    assert "0.40 m" in render(notes[0], "en")


def test_a_sampled_belfry_is_said_once_not_by_each_scenarios_t0():
    samples = TowerPriors.from_tower(T06).sample(
        np.random.default_rng(1), 60, belfry=BelfryPriors()
    )
    _, notes = kinematic_capacities(T06, SITE, samples)
    inner = [getattr(n.kwargs.get("note"), "code", "") for n in notes]
    assert "kinematic.belfry_t0" not in inner
    # ... where a row with the columns says its one T0
    row = belfry_row(
        T06,
        height_share=0.15,
        opening_ratio=0.5,
        bells_mass_kg=5000.0,
        bells_height_share=0.7,
        wall_top_m=0.8,
        unit_weight_n_m3=18.0e3,
    )
    _, notes = kinematic_capacities(
        row, SITE, TowerPriors.from_tower(row).sample(np.random.default_rng(1), 20)
    )
    assert "kinematic.belfry_t0" in [getattr(n.kwargs.get("note"), "code", "") for n in notes]
