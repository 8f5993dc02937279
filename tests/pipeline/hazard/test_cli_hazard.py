"""``rockscreen hazard``: the acceptance checks through the command line."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from rockscreen.pipeline.cli import main
from rockscreen.pipeline.hazard import elastic_spectrum, site_hazard


def run(*args):
    return CliRunner().invoke(main, ["hazard", *args])


def test_laquila_475_json():
    result = run("--lon", "13.3995", "--lat", "42.3498", "--return-period", "475", "--json")
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert data["ag_g"] == pytest.approx(0.261, rel=0.01)
    for key in ("F0", "Tc_star_s", "return_period_y", "S", "TB_s", "TC_s", "TD_s", "pga_g"):
        assert key in data
    assert data["return_period_y"] == 475.0
    assert data["soil_class_source"] == "default"
    assert any("soil class unknown: assumed A" in text for text in data["assumptions"])


def test_limit_state_soil_and_periods():
    result = run(
        "--lon", "14.42", "--lat", "41.04", "--limit-state", "slv", "--use-class", "II",
        "--nominal-life", "50", "--soil", "C", "--topography", "T2", "--periods", "0,0.5,1",
        "--json",
    )  # fmt: skip
    assert result.exit_code == 0, result.output
    data = json.loads(result.output)
    assert data["return_period_y"] == pytest.approx(474.56, abs=0.01)
    site = site_hazard(14.42, 41.04, data["return_period_y"])
    assert data["se_g"] == pytest.approx(list(elastic_spectrum([0, 0.5, 1], site, "C", "T2")))
    assert data["soil_class_source"] == "option"
    assert data["assumptions"] == []


def test_site_at_sea_refused_in_one_line():
    result = run("--lon", "12.0", "--lat", "40.0", "--return-period", "475")
    assert result.exit_code == 1
    lines = result.output.strip().splitlines()
    assert len(lines) == 1
    assert lines[0].startswith("rockscreen: error: site lon=12 lat=40")
    assert "outside the NTC 2018 hazard grid" in lines[0]


def test_usage_errors():
    assert run("--lon", "13").exit_code == 2
    both = run("--lon", "13.4", "--lat", "42.3", "--return-period", "475", "--limit-state", "SLV")
    assert both.exit_code == 2


def test_text_table_plot_and_synthetic_suite(tmp_path):
    png = tmp_path / "spectra.png"
    result = run("--lon", "14.42", "--lat", "41.04", "--suite", "synthetic", "--plot", str(png))
    assert result.exit_code == 0, result.output
    assert "ag (rock)" in result.output and " g" in result.output
    # 'synthetic' is the default embedded suite: the stochastic one, 11 records
    assert "records (synthetic): meets the tolerance" in result.output
    assert result.output.count("STO-0-") == 11
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_matched_suite_on_request():
    result = run("--lon", "14.42", "--lat", "41.04", "--suite", "matched")
    assert result.exit_code == 0, result.output
    assert "records (matched): meets the tolerance: 7 records" in result.output
    assert result.output.count("SYN-0-") == 7
    eight = run("--lon", "14.42", "--lat", "41.04", "--suite", "stochastic", "--n-records", "8")
    assert eight.exit_code == 0, eight.output
    assert eight.output.count("STO-0-") == 8


def test_towers_csv_with_inventory_soil(tmp_path):
    inventory = tmp_path / "towers.csv"
    inventory.write_text(
        "id;lat;lon;width_m;height_m;soil_class;use_class\n"
        "A;42,3498;13,3995;2;6;B;II\n"
        "B;;;2;6;;\n"
        "C;40,0;12,0;2;6;;\n",
        encoding="utf-8",
    )
    result = run("--towers", str(inventory), "--limit-state", "SLV", "--json")
    assert result.exit_code == 0, result.output
    first, second, third = json.loads(result.output)
    assert first["soil_class"] == "B" and first["soil_class_source"] == "inventory"
    assert first["use_class"] == "II"
    assert first["return_period_y"] == pytest.approx(474.56, abs=0.01)
    assert "no lat/lon" in second["error"]
    assert "outside the NTC 2018 hazard grid" in third["error"]
