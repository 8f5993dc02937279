"""ShakeMap grids, scenario probabilities and the assess/scenario CLI examples."""

from __future__ import annotations

import json
import math
import os

import h5py
import pytest
from click.testing import CliRunner

from rockscreen.pipeline.archive.risk_reader import (
    read_metadata,
    read_records,
    read_selection,
    read_set_records,
)
from rockscreen.pipeline.cli import main
from rockscreen.pipeline.errors import ShakeMapError
from rockscreen.pipeline.hazard.shakemap import read_shakemap_grid
from rockscreen.pipeline.risk.scenario.example_shakemap import example_pga_g, write_example_grid
from rockscreen.pipeline.risk.scenario.probability import tower_scenario


def test_real_grids_sm3_and_sm4_truncated(shared_data):
    sm3 = read_shakemap_grid(shared_data / "shakemap" / "ghorka-grid.xml")
    assert sm3.event["magnitude"] == "7.8" and sm3.n_rows == 4 and "truncated" in sm3.warning
    pga, sigma = sm3.at(81.7314, 30.8735)  # the first row: 0.44 pctg, STDPGA 0.53
    assert pga == pytest.approx(0.0044) and sigma == pytest.approx(0.53)
    middle = sm3.at(81.7314 + 0.5 * sm3.dlon, 30.8735)
    assert middle[0] == pytest.approx(0.5 * (0.0044 + 0.0047), rel=1e-3)
    assert sm3.at(81.7314, 30.0) is None  # rows there are missing: not guessed
    assert sm3.at(80.0, 30.8735) is None  # outside the extent
    sm4 = read_shakemap_grid(shared_data / "shakemap" / "us7000n05d-grid.xml")
    assert sm4.sigma_ln_pga is None and sm4.n_rows == 8
    assert sm4.at(-71.2167, -19.9833)[0] == pytest.approx(0.009238)
    with pytest.raises(ShakeMapError, match="4 rows but the header describes 361 x 318"):
        read_shakemap_grid(shared_data / "shakemap" / "ghorka-grid.xml", strict=True)


def test_grid_refuses_doctype_and_bad_units(tmp_path):
    path = write_example_grid(tmp_path / "g.xml")
    text = path.read_text()
    bomb = tmp_path / "bomb.xml"
    bomb.write_text(
        text.replace("<shakemap_grid", '<!DOCTYPE x [<!ENTITY a "aaaa">]>\n<shakemap_grid', 1)
    )
    with pytest.raises(ShakeMapError, match="DOCTYPE"):
        read_shakemap_grid(bomb)
    units = tmp_path / "units.xml"
    units.write_text(text.replace('name="PGA" units="%g"', 'name="PGA" units="cm/s2"'))
    with pytest.raises(ShakeMapError, match="PGA units 'cm/s2'"):
        read_shakemap_grid(units)


def test_example_grid_is_complete_and_matches_its_law(tmp_path):
    grid = read_shakemap_grid(write_example_grid(tmp_path / "g.xml"), strict=True)
    assert grid.warning == "" and grid.sigma_ln_pga is not None
    pga, sigma = grid.at(14.551, 41.121)
    assert pga == pytest.approx(float(example_pga_g(14.551, 41.121)), rel=0.02)
    assert sigma == pytest.approx(0.6)


def test_tower_probability_folds_sigma(tmp_path):
    grid = read_shakemap_grid(write_example_grid(tmp_path / "g.xml"))
    row = {
        "id": "T",
        "name": "",
        "lat_deg": 41.12,
        "lon_deg": 14.55,
        "soil_class": "A",
        "topography": "T1",
        "fragility_median_g": 0.40,
        "fragility_beta": 0.3,
        "median_is_bound": "",
        "tr_slv_y": 712.0,
    }
    out = tower_scenario(row, grid)
    assert out["status"] == "ok" and out["soil_factor"] == 1.0
    assert out["beta_total"] == pytest.approx(math.hypot(0.3, 0.6))
    assert out["p_overturning"] == pytest.approx(0.5, abs=0.02)  # PGA ~ median at the epicentre
    far = tower_scenario({**row, "lat_deg": 45.0}, grid)
    assert far["status"] == "outside_grid" and math.isnan(far["p_overturning"])
    soft = tower_scenario({**row, "soil_class": "C"}, grid)
    assert soft["soil_factor"] > 1.0 and soft["ag_equiv_g"] < out["ag_equiv_g"]
    # A lower-bound median above the event: P is at most Phi(ln(ag / m) / hypot(1.0, sigma))
    # (the supremum over every median above m and every beta up to BOUND_BETA_MAX).
    bound = tower_scenario(
        {**row, "median_is_bound": "lower", "fragility_median_g": 1.5, "fragility_beta": math.nan},
        grid,
    )
    assert bound["status"] == "ok" and bound["p_overturning_bound"] == "upper"
    expected = 0.5 * math.erfc(-math.log(out["ag_equiv_g"] / 1.5) / math.hypot(1.0, 0.6) / 2**0.5)
    assert bound["p_overturning"] == pytest.approx(expected, rel=1e-9)
    for median, beta in ((1.5, 0.2), (1.5, 0.99), (2.0, 0.5), (5.0, 1.0)):  # it bounds them all
        fitted = tower_scenario({**row, "fragility_median_g": median, "fragility_beta": beta}, grid)
        assert fitted["p_overturning"] <= bound["p_overturning"]
    assert "at most" in bound["note"] and "1" in bound["note"]
    # A lower bound at or below the event's ag tells nothing: no probability, the reason said.
    beyond = tower_scenario(
        {**row, "median_is_bound": "lower", "fragility_median_g": 0.1, "fragility_beta": math.nan},
        grid,
    )
    assert beyond["status"] == "no_fragility" and math.isnan(beyond["p_overturning"])
    assert "at or above it" in beyond["note"]


@pytest.mark.slow
def test_assess_and_scenario_examples_in_an_empty_folder(tmp_path):
    runner = CliRunner()
    cwd = os.getcwd()
    os.chdir(tmp_path)
    try:
        fast = ["--return-periods", "101,475,2475", "--records", "3", "--site-resolution", "0.5"]
        # Three records per stripe fail NTC 2018 §7.3.5 (seven for a mean): run, marked.
        fast.append("--allow-noncompliant")
        result = runner.invoke(main, ["assess", "--example", "--jobs", "1", *fast])
        assert result.exit_code == 0, result.output
        assert "lambda_C [1/y]" in result.stdout and "legend:" in result.stdout
        # The default embedded suite (stochastic), its records kept in the archive.
        archive = "rockscreen-assess-example.h5"
        metadata = read_metadata(archive)
        assert metadata["suite_kind"] == "stochastic" and metadata["n_records_per_stripe"] == 3
        stored = read_records(archive)
        ids = {i for refs in read_set_records(archive) for i, _ in refs}
        assert len(read_set_records(archive)) == len(read_selection(archive))
        assert ids == set(stored) and all(r["dt_s"] == 0.01 for r in stored.values())
        with h5py.File(archive) as f:  # each record stored once: as many rows as ids referenced
            index = f["records/index/id"].asstr()[:]
            assert len(index) == len(set(index)) == len(ids) < len(f["set_records/record"])
        assert all(r["name"].startswith("STO-0-") and r["z"] is not None for r in stored.values())
        inspected = runner.invoke(main, ["inspect", "--json", "rockscreen-assess-example.h5"])
        assert inspected.exit_code == 0, inspected.output
        towers = json.loads(inspected.stdout)["towers"]
        assert len(towers) == 9
        keys = (
            "collapse_median_g",
            "collapse_beta",
            "slv_median_g",
            "slv_beta",
            "annual_rate_overturning",
            "p_overturning_50y",
            "capacity_pga_g",
            "capacity_return_period_y",
            "safety_index",
            "acceleration_factor",
        )
        for tower in towers:
            for key in keys:
                assert key in tower
                if tower[key] is None:
                    assert f"{key}_note" in tower
            if tower["lat_deg"] is None:
                continue
            # every located tower: a fitted collapse fragility with SEs, or the bound in words
            if tower["collapse_bound"]:
                assert "no record overturned" in tower["note"] or "one record" in tower["note"]
                assert tower["collapse_median_g_note"].endswith("bound")
            else:
                for key in ("collapse_median_g", "collapse_beta", "collapse_se_ln_median"):
                    assert tower[key] is not None and tower[key] > 0
                assert tower["collapse_se_beta"] is not None
                assert tower["collapse_beta"] != pytest.approx(0.05)  # no floor
        scenario = runner.invoke(main, ["scenario", "--example", "--map", "map.png"])
        assert scenario.exit_code == 0, scenario.output
        assert "P(overturn) [-]" in scenario.stdout and (tmp_path / "map.png").stat().st_size
        for args in (
            ["plot", "rockscreen-assess-example.h5", "--map", "--out", "is.png"],
            ["plot", "rockscreen-assess-example.h5", "--tower", "ARC-08", "--out", "f.png"],
            ["export", "rockscreen-assess-example.h5", "--csv", "a.csv"],
            ["export", "rockscreen-scenario-example.h5", "--geojson", "s.geojson"],
        ):
            done = runner.invoke(main, args)
            assert done.exit_code == 0, done.output
        header = (tmp_path / "a.csv").read_text().splitlines()[0].split(",")
        assert header[0] == "id" and "annual_rate_overturning_per_y" in header
        features = json.loads((tmp_path / "s.geojson").read_text())["features"]
        assert len(features) == 8  # ARC-07 has no coordinates
        bad = runner.invoke(
            main,
            [
                "scenario",
                "--shakemap",
                "rockscreen-example-grid.xml",
                "--fragility",
                "rockscreen-scenario-example.h5",
            ],
        )
        assert bad.exit_code == 1 and "not an 'assess' archive" in bad.stderr
    finally:
        os.chdir(cwd)


def test_scenario_classes_on_probability():
    import math

    from rockscreen.pipeline.risk.measures.classes import scenario_class

    assert [scenario_class(p) for p in (0.9, 0.5, 0.3, 0.05, 0.01)] == [
        "very_high",
        "very_high",
        "high",
        "moderate",
        "low",
    ]
    assert scenario_class(math.nan) == "undefined"
