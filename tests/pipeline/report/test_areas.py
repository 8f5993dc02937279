"""Towers per class per comune/provincia (issue 23): terminal, export --by, HTML summary."""

from __future__ import annotations

import csv
import io

from click.testing import CliRunner

from rockscreen.pipeline.archive.risk_archive import write_risk_archive
from rockscreen.pipeline.cli import main
from rockscreen.pipeline.report.areas import NO_AREA, area_columns, area_counts, area_lines
from rockscreen.pipeline.risk.assess.sites import tower_sites
from rockscreen.pipeline.risk.assess.tower_summary import base_summary_row
from rockscreen.stations.inventory import Tower, read_inventory

AREAS = [("L'Aquila", "AQ", "high"), ("L'Aquila", "AQ", "meets"), ("Sulmona", "AQ", "meets"),
         ("Teramo", "TE", "very_high"), ("", "", "meets")]  # fmt: skip


def _rows():
    towers = [
        Tower(id=f"T{i}", width_m=2, height_m=10, lat=42.3, lon=13.4, comune=c, provincia=p)
        for i, (c, p, _) in enumerate(AREAS)
    ]
    rows = [base_summary_row(site) for site in tower_sites(towers, 0.01)]
    for row, (_, _, cls) in zip(rows, AREAS, strict=True):
        row["risk_class"] = cls
    return rows


def test_the_inventory_reads_the_area_columns(tmp_path):
    path = tmp_path / "towers.csv"
    path.write_text(
        "id,comune,provincia,width_m,height_m\nA,Barisciano,AQ,2,10\nB,,,1,8\n", encoding="utf-8"
    )
    towers = read_inventory(path)
    assert (towers[0].comune, towers[0].provincia) == ("Barisciano", "AQ")
    assert (towers[1].comune, towers[1].provincia) == ("", "")


def test_counts_per_area_and_class():
    rows = _rows()
    assert area_columns(rows) == ["comune", "provincia"]
    assert area_columns([{**r, "comune": "", "provincia": ""} for r in rows]) == []
    classes, areas = area_counts(rows, "provincia")
    assert set(classes) == {"high", "meets", "very_high"}
    assert areas[0] == ("AQ", {"high": 1, "meets": 2}, 3)  # the largest area first
    assert (NO_AREA, {"meets": 1}, 1) in areas
    lines = area_lines(rows, ["very_high", "high", "moderate", "meets"])
    assert "towers per class by comune:" in lines and "towers per class by provincia:" in lines
    header = next(line for line in lines if line.startswith("comune"))
    assert header.split() == ["comune", "very_high", "high", "meets", "towers"]


def test_export_by_area_and_the_html_summary(tmp_path):
    archive = tmp_path / "a.h5"
    write_risk_archive(archive, "assess", {"summary": _rows()}, {})
    runner = CliRunner()
    out = tmp_path / "by.csv"
    result = runner.invoke(main, ["export", str(archive), "--csv", str(out), "--by", "comune"])
    assert result.exit_code == 0, result.output
    table = list(csv.DictReader(io.StringIO(out.read_text(encoding="utf-8"))))
    by = {row["comune"]: row for row in table}
    assert by["L'Aquila"]["towers"] == "2" and by["L'Aquila"]["high"] == "1"
    assert sum(int(row["towers"]) for row in table) == len(AREAS)
    result = runner.invoke(
        main, ["export", str(archive), "--geojson", "x.geojson", "--by", "comune"]
    )
    assert result.exit_code == 2 and "--by apply to --csv only" in result.stderr
    page = tmp_path / "r.html"
    result = runner.invoke(main, ["report", str(archive), "--out", str(page)])
    assert result.exit_code == 0, result.output
    text = page.read_text(encoding="utf-8")
    assert 'data-column="provincia"' in text and "Towers per class by comune" in text


def test_export_by_an_area_the_archive_lacks_is_a_usage_error(tmp_path):
    archive = tmp_path / "a.h5"
    write_risk_archive(
        archive, "assess", {"summary": [{**r, "comune": "", "provincia": ""} for r in _rows()]}, {}
    )
    out = tmp_path / "by.csv"
    result = CliRunner().invoke(main, ["export", str(archive), "--csv", str(out), "--by", "comune"])
    assert result.exit_code == 2 and "have no comune" in result.stderr
    assert not out.exists()
