"""Issue 20: the ShakeMap's uncertainty of PGA (grid, uncertainty.xml or a documented
default) and every tower listed, with or without a fragility."""

from __future__ import annotations

import math
from pathlib import Path

import pytest
from click.testing import CliRunner
from scipy.special import ndtr

from rockscreen.pipeline.archive.risk_archive import write_risk_archive
from rockscreen.pipeline.archive.risk_reader import read_summary
from rockscreen.pipeline.cli import main
from rockscreen.pipeline.errors import ShakeMapError
from rockscreen.pipeline.hazard.shakemap import (
    DEFAULT_SIGMA_LN_PGA,
    find_uncertainty,
    read_shakemap_grid,
    read_uncertainty,
)
from rockscreen.pipeline.risk.assess.sites import tower_sites
from rockscreen.pipeline.risk.assess.tower_summary import base_summary_row
from rockscreen.pipeline.risk.scenario.probability import scenario_rows
from rockscreen.pipeline.risk.scenario.run import run_scenario
from rockscreen.pipeline.verdict.messages import message, note_columns
from rockscreen.stations.inventory import Tower

#: A 1-degree grid over Campania and Sardinia: lon 8-15, lat 38-42 (8 x 5 nodes).
SPEC = (
    '<grid_specification lon_min="8" lat_min="38" lon_max="15" lat_max="42" '
    'nominal_lon_spacing="1" nominal_lat_spacing="1" nlon="8" nlat="5"/>'
)
NODES = [(lon, lat) for lat in range(38, 43) for lon in range(8, 16)]


def _xml(fields: list[tuple[str, str]], rows: list[list[float]]) -> str:
    declared = "".join(
        f'<grid_field index="{i + 1}" name="{n}" units="{u}"/>' for i, (n, u) in enumerate(fields)
    )
    data = "\n".join(" ".join(f"{v:g}" for v in row) for row in rows)
    return (
        '<?xml version="1.0" encoding="UTF-8"?><shakemap_grid '
        'xmlns="http://earthquake.usgs.gov/eqcenter/shakemap" code_version="4.1.5">'
        '<event event_id="test" magnitude="6.0" lat="41" lon="14.5"/>'
        f"{SPEC}{declared}<grid_data>\n{data}\n</grid_data></shakemap_grid>"
    )


def _grid(folder: Path, name: str = "grid.xml") -> Path:
    """A ShakeMap 4 grid (no STDPGA): PGA 20 %g everywhere."""
    path = folder / name
    fields = [("LON", "dd"), ("LAT", "dd"), ("PGA", "%g")]
    path.write_text(_xml(fields, [[lon, lat, 20.0] for lon, lat in NODES]))
    return path


def _uncertainty(folder: Path, sigma=lambda k: 0.5, name: str = "uncertainty.xml") -> Path:
    path = folder / name
    fields = [("LON", "dd"), ("LAT", "dd"), ("STDPGA", "ln(g)"), ("STDPGV", "ln(cm/s)")]
    rows = [[lon, lat, sigma(k), 0.6] for k, (lon, lat) in enumerate(NODES)]
    path.write_text(_xml(fields, rows))
    return path


def _assess_rows() -> list[dict]:
    towers = [
        Tower(id="OK", width_m=2, height_m=10, lat=41.04, lon=14.42),
        Tower(id="BOUND", width_m=4, height_m=6, lat=41.04, lon=14.42),
        Tower(id="SARDINIA", width_m=2, height_m=10, lat=39.22, lon=9.11),
        Tower(id="NOT-ASSESSED", width_m=2, height_m=10, lat=40.85, lon=14.25),
    ]
    rows = [base_summary_row(site) for site in tower_sites(towers, 0.01)]
    rows[0].update(collapse_median_g=0.3, collapse_beta=0.3, tr_slv_y=712.0)
    rows[1].update(collapse_median_g=0.5, collapse_bound="lower", tr_slv_y=712.0)
    outside = "site lon=9.11 lat=39.22 deg is outside the NTC 2018 grid"
    rows[2].update(note_columns([message("site.hazard_failed", error=outside)]))
    failed = message("site.records_failed", lon=14.25, lat=40.85, tr=30.0, error="no record")
    rows[3].update(note_columns([failed]))
    assert rows[3]["note"] == "record set at lon=14.25 lat=40.85 TR=30 y: no record"
    return rows


def test_uncertainty_xml_beside_the_grid_is_read(tmp_path):
    grid_path = _grid(tmp_path)
    assert find_uncertainty(grid_path) is None
    _uncertainty(tmp_path)
    assert find_uncertainty(grid_path) == tmp_path / "uncertainty.xml"
    named = _grid(tmp_path, "us1-grid.xml")
    _uncertainty(tmp_path, name="us1-uncertainty.xml")
    (tmp_path / "uncertainty.xml").unlink()
    assert find_uncertainty(named) == tmp_path / "us1-uncertainty.xml"
    grid = read_uncertainty(tmp_path / "us1-uncertainty.xml", read_shakemap_grid(named))
    assert grid.at(14.42, 41.04)[1] == pytest.approx(0.5)
    (ok, *_) = scenario_rows(_assess_rows(), grid)
    assert ok["sigma_ln_pga"] == pytest.approx(0.5) and ok["note"] == ""
    assert ok["beta_total"] == pytest.approx(math.hypot(0.3, 0.5))


@pytest.mark.parametrize(("bad", "row"), [(math.nan, 7), (-0.1, 3), (25.0, 40)])
def test_a_broken_stdpga_is_refused_with_file_and_row(tmp_path, bad, row):
    grid = read_shakemap_grid(_grid(tmp_path))
    path = _uncertainty(tmp_path, sigma=lambda k: bad if k == row - 1 else 0.5)
    with pytest.raises(ShakeMapError, match=rf"uncertainty\.xml: STDPGA .* at grid_data row {row}"):
        read_uncertainty(path, grid)


def test_without_stdpga_the_default_sigma_applies_and_every_row_says_so(tmp_path):
    grid = read_shakemap_grid(_grid(tmp_path))
    assert grid.sigma_ln_pga is None
    assert DEFAULT_SIGMA_LN_PGA == pytest.approx(0.337 * math.log(10))  # ITA10, log10 -> ln
    ok = scenario_rows(_assess_rows(), grid)[0]
    assert ok["sigma_ln_pga"] == pytest.approx(0.776, abs=1e-3)
    assert "Bindi et al. 2011" in ok["note"] and "Bindi et al. 2011" in ok["sigma_source"]
    expected = ndtr(math.log(0.2 / 0.3) / math.hypot(0.3, DEFAULT_SIGMA_LN_PGA))
    assert ok["p_overturning"] == pytest.approx(expected)
    known = scenario_rows(_assess_rows(), grid, gm_uncertainty=False)[0]
    assert known["sigma_ln_pga"] == 0.0 and "--no-gm-uncertainty" in known["note"]
    assert known["p_overturning"] == pytest.approx(ndtr(math.log(0.2 / 0.3) / 0.3))


def test_every_tower_is_listed_and_the_rest_computed(tmp_path):
    fragility = tmp_path / "assess.h5"
    write_risk_archive(fragility, "assess", {"summary": _assess_rows()}, {})
    grid = _grid(tmp_path)
    rows, failures, _ = run_scenario(grid, fragility, tmp_path / "s.h5")
    status = {r["id"]: r["status"] for r in rows}
    assert status == {
        "OK": "ok",
        "BOUND": "ok",  # a lower-bound median above the event: P as an upper bound
        "SARDINIA": "no_fragility",
        "NOT-ASSESSED": "no_fragility",
    }
    by_id = {r["id"]: r for r in rows}
    assert "outside the NTC 2018 grid" in by_id["SARDINIA"]["note"]
    assert "lower bound" in by_id["BOUND"]["note"]
    assert (
        by_id["BOUND"]["p_overturning_bound"] == "upper" and by_id["BOUND"]["p_overturning"] < 0.5
    )
    assert {f["subject"] for f in failures} == {"SARDINIA", "NOT-ASSESSED"}
    assert all(r["sigma_source"] for r in read_summary(tmp_path / "s.h5", "scenario"))
    runner = CliRunner()
    args = ["scenario", "--shakemap", str(grid), "--fragility", str(fragility)]
    done = runner.invoke(main, [*args, "--out", str(tmp_path / "c.h5")])
    assert done.exit_code == 0, done.output
    assert "Bindi et al. 2011" in done.stderr and "no_fragility" in done.stdout
    _uncertainty(tmp_path)
    done = runner.invoke(main, [*args, "--out", str(tmp_path / "d.h5")])
    assert done.exit_code == 0 and "STDPGA of uncertainty.xml" in done.stderr
    done = runner.invoke(main, [*args, "--no-gm-uncertainty", "--out", str(tmp_path / "e.h5")])
    assert done.exit_code == 0 and "sigma_lnPGA = 0" in done.stderr


def test_real_sm4_grid_gets_the_default_sigma(shared_data, tmp_path):
    path = shared_data / "shakemap" / "us7000n05d-grid.xml"
    if not path.is_file():
        pytest.skip(f"{path} is absent")
    grid = read_shakemap_grid(path)
    assert grid.sigma_ln_pga is None and find_uncertainty(path) is None
    sm3 = read_shakemap_grid(shared_data / "shakemap" / "ghorka-grid.xml")
    assert sm3.sigma_source == "STDPGA of ghorka-grid.xml"
