"""Export dialects (issue 23): Italian Excel CSV, --digits, the QGIS style beside a GeoJSON."""

from __future__ import annotations

import json
import math
from xml.etree import ElementTree as ET

from click.testing import CliRunner

from rockscreen.pipeline.cli import main
from rockscreen.pipeline.report.export import summary_csv_text
from rockscreen.pipeline.report.maps import RISK_COLOURS
from rockscreen.pipeline.report.qgis_style import risk_style_qml

ROWS = [
    {"id": "T-1", "name": "Sant'Àngelo", "lat_deg": 41.0412345678, "lon_deg": 14.42,
     "risk_class": "high", "theta_max_over_alpha": 5.3412345e-5, "safety_factor": math.inf},
    {"id": "T-2", "name": "B", "lat_deg": 41.1, "lon_deg": 14.6, "risk_class": "none",
     "theta_max_over_alpha": 0.38412345678, "safety_factor": 1.25},
]  # fmt: skip


def test_default_csv_keeps_full_precision_and_order():
    text = summary_csv_text(ROWS)
    assert text.startswith("id,name,lat_deg")
    assert "5.3412345e-05" in text and "0.38412345678" in text
    assert [line.split(",")[0] for line in text.splitlines()[1:]] == ["T-1", "T-2"]


def test_italian_csv_semicolon_decimal_comma_bom():
    text = summary_csv_text(ROWS, locale="it")
    assert text.startswith("\ufeffid;name;lat_deg;lon_deg")
    body = text.splitlines()[1].split(";")
    assert body[2] == "41,0412345678" and "inf" in body
    assert "0,38412345678" in text and "." not in text.splitlines()[2].split(";")[2]


def test_digits_round_the_numbers_not_the_coordinates():
    text = summary_csv_text(ROWS, digits=3)
    assert "5.34e-05" in text and "0.384," in text
    assert "41.0412345678" in text  # coordinates stay whole
    site = summary_csv_text([{"id": "T", "site_lat_deg": 41.0412345678}], digits=3)
    assert "41.0412345678" in site


def test_italian_csv_is_read_back_by_the_inventory_reader(tmp_path):
    from rockscreen.stations.inventory import read_inventory

    rows = [
        {"id": "T-1", "name": "Sant'Àngelo", "width_m": 5.25, "height_m": 30.5},
    ]  # fmt: skip
    path = tmp_path / "it.csv"
    path.write_text(summary_csv_text(rows, locale="it"), encoding="utf-8")
    raw = path.read_bytes()
    assert raw.startswith(b"\xef\xbb\xbf")
    towers = read_inventory(path)
    assert towers[0].name == "Sant'Àngelo"
    assert towers[0].width_m == 5.25 and towers[0].height_m == 30.5


def test_qgis_style_is_valid_xml_with_the_report_colours():
    qml = risk_style_qml(["none", "high", "meets (basis not code-compliant)"])
    root = ET.fromstring(qml.split("\n", 1)[1])
    assert root.tag == "qgis"
    renderer = root.find("renderer-v2")
    assert renderer.get("type") == "categorizedSymbol" and renderer.get("attr") == "risk_class"
    values = [c.get("value") for c in renderer.iter("category")]
    assert values[0] == "high" and set(values[1:3]) == {"none", "meets (basis not code-compliant)"}
    assert values[3] == ""  # all other values
    colours = {
        s.get("name"): next(p.get("v") for p in s.iter("prop") if p.get("k") == "color")
        for s in renderer.iter("symbol")
    }
    high = RISK_COLOURS["high"]
    assert colours["0"] == ",".join(str(int(high[i : i + 2], 16)) for i in (1, 3, 5)) + ",255"


def test_export_command_italian_csv_and_geojson_style(example_archive, tmp_path):
    out = tmp_path / "it.csv"
    result = CliRunner().invoke(
        main, ["export", str(example_archive), "--csv", str(out), "--excel-it", "--digits", "4"]
    )
    assert result.exit_code == 0, result.output
    text = out.read_text(encoding="utf-8")
    assert text.startswith("\ufeffid;")
    geo = tmp_path / "towers.geojson"
    result = CliRunner().invoke(main, ["export", str(example_archive), "--geojson", str(geo)])
    assert result.exit_code == 0, result.output
    qml = tmp_path / "towers.qml"
    assert qml.is_file() and json.loads(geo.read_text(encoding="utf-8"))["features"]
    ET.fromstring(qml.read_text(encoding="utf-8").split("\n", 1)[1])
    bad = CliRunner().invoke(
        main, ["export", str(example_archive), "--geojson", str(geo), "--digits", "3"]
    )
    assert bad.exit_code == 2
