"""Summary export: CSV and GeoJSON round trips, the export command, the risk map."""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from rockscreen.pipeline.cli import main
from rockscreen.pipeline.report.export import (
    summary_csv_text,
    summary_feature_collection,
    summary_geojson_text,
    write_summary_csv,
    write_summary_geojson,
)
from rockscreen.pipeline.report.maps import RISK_COLOURS, plot_risk_map, risk_map_figure
from rockscreen.stations.errors import RockscreenError
from rockscreen.stations.pairing import StationSite


def summary_row(tower_id, lat, lon, risk, theta=0.3, sf=2.0, overturned=False):
    """A summary row with the keys and numpy types that archive.campaign.read_summary gives."""
    return {
        "id": tower_id,
        "name": f"Torre {tower_id}, Sant'Àngelo",
        "lat": np.float64(lat),
        "lon": np.float64(lon),
        "stations": "XX.SYN1",
        "n_records": np.int64(1),
        "theta_max_over_alpha": np.float64(theta),
        "theta_max_rad": np.float64(theta * 0.35),
        "overturned": np.bool_(overturned),
        "safety_factor": np.float64(sf),
        "risk_class": risk,
        "governing_record": "XX.SYN1..HNE",
        "governing_model": "ground",
        "governing_component": "HNE",
    }


@pytest.fixture
def rows():
    return [
        summary_row("CE-SANNA", 41.04, 14.42, "collapse", theta=1.0, sf=0.8, overturned=True),
        summary_row("ARC-01", 41.045, 14.44, "high", theta=0.6, sf=1.2),
        summary_row("ARC-02", 41.02, 14.45, "none", theta=0.0, sf=math.inf),
        summary_row("ARC-07", math.nan, math.nan, "low", theta=0.05, sf=math.nan),
    ]


def read_csv(path):
    with open(path, newline="", encoding="utf-8") as handle:
        return list(csv.DictReader(handle))


def test_csv_round_trip(rows, tmp_path):
    path = tmp_path / "summary.csv"
    assert write_summary_csv(rows, path) == 4
    back = read_csv(path)
    assert list(back[0]) == [
        "id",
        "name",
        "lat_deg",
        "lon_deg",
        "risk_class",
        "theta_max_over_alpha",
        "theta_max_rad",
        "overturned",
        "safety_factor",
        "governing_record",
        "governing_model",
        "governing_component",
        "n_records",
        "stations",
    ]
    assert [r["id"] for r in back] == [r["id"] for r in rows]  # archive order kept
    for original, written in zip(rows, back, strict=True):
        assert written["name"] == original["name"]  # commas, quotes, accents survive
        assert float(written["theta_max_rad"]) == original["theta_max_rad"]  # bit for bit
        assert written["overturned"] == ("true" if original["overturned"] else "false")
        assert written["risk_class"] == original["risk_class"]
        assert int(written["n_records"]) == 1
    assert back[2]["safety_factor"] == "inf"
    assert back[3]["safety_factor"] == "" and back[3]["lat_deg"] == ""  # NaN -> empty


def test_leading_columns_come_first_whatever_the_archive_order(rows):
    shuffled = [dict(sorted(row.items())) for row in rows]  # read_summary sorts its keys
    assert summary_csv_text(shuffled) == summary_csv_text(rows)


def test_csv_of_no_rows_is_an_empty_table():
    assert summary_csv_text([]) == "\n"


def test_csv_columns_are_the_union_of_all_rows(rows):
    rows[1]["extra_m"] = 1.5
    header = summary_csv_text(rows).splitlines()[0].split(",")
    assert header[-1] == "extra_m"
    assert summary_csv_text(rows).splitlines()[1].endswith(",")  # absent -> empty cell


def test_geojson_round_trip(rows, tmp_path):
    path = tmp_path / "summary.geojson"
    written, skipped = write_summary_geojson(rows, path)
    assert (written, skipped) == (3, ["ARC-07"])
    text = path.read_text(encoding="utf-8")
    for literal in ("NaN", "Infinity"):
        assert literal not in text
    collection = json.loads(text, parse_constant=pytest.fail)  # strict JSON
    assert collection["type"] == "FeatureCollection"
    features = collection["features"]
    assert [f["id"] for f in features] == ["CE-SANNA", "ARC-01", "ARC-02"]
    first = features[0]
    assert first["type"] == "Feature"
    assert first["geometry"] == {"type": "Point", "coordinates": [14.42, 41.04]}  # lon, lat
    props = first["properties"]
    assert props["lat_deg"] == 41.04 and props["lon_deg"] == 14.42
    assert props["overturned"] is True and props["safety_factor"] == 0.8
    assert props["risk_class"] == "collapse" and props["name"] == rows[0]["name"]
    assert features[2]["properties"]["safety_factor"] is None  # inf -> null
    assert isinstance(features[1]["properties"]["n_records"], int)


def test_geojson_of_no_located_tower_is_an_empty_collection(rows):
    text, skipped = summary_geojson_text(rows[3:])
    assert json.loads(text) == {"type": "FeatureCollection", "features": []}
    assert skipped == ["ARC-07"]


def test_feature_collection_accepts_bytes_and_missing_coordinates():
    collection, skipped = summary_feature_collection(
        [{"id": b"T1", "lat": 1.0, "lon": 2.0}, {"id": "T2"}]
    )
    assert collection["features"][0]["id"] == "T1" and skipped == ["T2"]


def test_write_is_atomic_on_failure(rows, tmp_path, monkeypatch):
    path = tmp_path / "summary.csv"
    path.write_text("old content", encoding="utf-8")

    def failing_replace(source, target):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr("rockscreen.pipeline.archive.atomic.os.replace", failing_replace)
    with pytest.raises(OSError, match="No space left"):
        write_summary_csv(rows, path)
    assert path.read_text(encoding="utf-8") == "old content"
    assert list(tmp_path.iterdir()) == [path]  # no temporary file left behind


def test_unencodable_value_writes_nothing(rows, tmp_path):
    path = tmp_path / "summary.geojson"
    with pytest.raises(TypeError):
        write_summary_geojson([*rows, {"id": "X", "lat": 1.0, "lon": 2.0, "v": object()}], path)
    assert not path.exists()


@pytest.fixture
def fake_archive(monkeypatch, rows, tmp_path):
    """A minimal campaign archive whose reader's summary returns the rows."""
    import h5py

    from rockscreen.pipeline.archive.kinds import RunReader

    archive = tmp_path / "run.h5"
    with h5py.File(archive, "w") as f:
        f.attrs["format"] = "rockscreen-archive"
        f.attrs["format_version"] = "2"
        f.create_group("summary").create_dataset("id", shape=(0,), dtype=h5py.string_dtype())

    def summary(self):
        assert str(self.path) == str(archive)
        return rows

    monkeypatch.setattr(RunReader, "summary", summary)
    return archive


def test_export_command_csv(fake_archive, rows, tmp_path):
    out = tmp_path / "out.csv"
    result = CliRunner().invoke(
        main, ["export", str(fake_archive), "--csv", str(out), "--order", "inventory"]
    )
    assert result.exit_code == 0, result.output
    assert [r["id"] for r in read_csv(out)] == [r["id"] for r in rows]
    assert "wrote 4 tower(s)" in result.stderr


def test_export_command_geojson_warns_about_skipped_towers(fake_archive, tmp_path):
    out = tmp_path / "out.geojson"
    result = CliRunner().invoke(main, ["export", str(fake_archive), "--geojson", str(out)])
    assert result.exit_code == 0, result.output
    assert len(json.loads(out.read_text(encoding="utf-8"))["features"]) == 3
    assert "warning: 1 tower(s) without coordinates left out" in result.stderr
    assert "ARC-07" in result.stderr
    assert "wrote 3 tower(s)" in result.stderr


@pytest.mark.parametrize("options", [[], ["--csv", "a.csv", "--geojson", "b.geojson"]])
def test_export_command_needs_exactly_one_output(options, tmp_path):
    result = CliRunner().invoke(main, ["export", str(tmp_path / "run.h5"), *options])
    assert result.exit_code == 2
    assert "exactly one of --csv OUT or --geojson OUT" in result.stderr
    assert not list(tmp_path.iterdir())


def test_export_command_refuses_a_non_archive(tmp_path):
    pytest.importorskip("rockscreen.pipeline.archive.campaign")
    bogus = tmp_path / "not_an_archive.h5"
    bogus.write_text("hello", encoding="utf-8")
    out = tmp_path / "out.csv"
    result = CliRunner().invoke(main, ["export", str(bogus), "--csv", str(out)])
    assert result.exit_code == 1
    assert result.stderr.startswith("rockscreen: error:")
    assert len(result.stderr.strip().splitlines()) == 1
    assert not out.exists()


SITES = [
    StationSite("XX.SYN1", 41.03, 14.43),
    StationSite("XX.SYN2", 41.13, 14.60),
    StationSite("XX.NOWHERE"),
]


def test_risk_map_png(rows, tmp_path):
    out = plot_risk_map(rows, SITES, tmp_path / "map.png")
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert out.stat().st_size > 10_000


def test_risk_map_content(rows):
    figure = risk_map_figure(rows, SITES)
    (ax,) = figure.axes
    assert ax.get_xlabel() == "Longitude [° E]" and ax.get_ylabel() == "Latitude [° N]"
    labels = [text.get_text() for text in ax.get_legend().get_texts()]
    # fixed order, worst first, with counts; the tower without coordinates is not drawn
    # the extent is fitted to the towers (issue 23): XX.SYN2, 10 km off, is outside
    assert labels == ["collapse (1)", "high (1)", "none (1)", "station (2; 1 outside the map)"]
    assert "1 without coordinates not shown" in ax.get_title()
    annotations = {text.get_text() for text in ax.texts}
    assert {"XX.SYN1", "CE-SANNA"} <= annotations
    assert "XX.NOWHERE" not in annotations and "XX.SYN2" not in annotations
    mean_lat = np.mean(ax.get_ylim())  # the centre of the map (fitted to the towers)
    assert ax.get_aspect() == pytest.approx(1 / math.cos(math.radians(mean_lat)))
    collapse = next(c for c in ax.collections if c.get_label() == "collapse (1)")
    assert tuple(collapse.get_facecolor()[0][:3]) == pytest.approx(
        tuple(int(RISK_COLOURS["collapse"][i : i + 2], 16) / 255 for i in (1, 3, 5))
    )


def test_risk_map_unknown_class_is_grey_and_listed_last(rows):
    rows[0]["risk_class"] = "special"
    labels = [t.get_text() for t in risk_map_figure(rows, []).axes[0].get_legend().get_texts()]
    assert labels == ["high (1)", "none (1)", "special (1)"]


def test_risk_map_needs_something_to_place(rows):
    with pytest.raises(RockscreenError, match="no tower and no station has coordinates"):
        risk_map_figure(rows[3:], [StationSite("XX.A")])


def test_risk_colours_cover_the_campaign_classes():
    risk = pytest.importorskip("rockscreen.pipeline.screening.risk")
    assert set(risk.RISK_CLASSES) <= set(RISK_COLOURS)
    assert list(RISK_COLOURS)[: len(risk.RISK_CLASSES)] == list(risk.RISK_CLASSES)


@pytest.mark.slow
def test_export_and_map_of_the_example_campaign(tmp_path, monkeypatch):
    """End to end on a real archive: run --example, then export both formats and map."""
    pytest.importorskip("rockscreen.pipeline.cli.run")
    from rockscreen.pipeline.archive.campaign import read_summary
    from rockscreen.pipeline.motion.synthetic import example_station_sites

    monkeypatch.chdir(tmp_path)
    runner = CliRunner()
    assert runner.invoke(main, ["run", "--example"]).exit_code == 0
    (archive,) = tmp_path.glob("*.h5")
    result = runner.invoke(main, ["export", str(archive), "--csv", "towers.csv"])
    assert result.exit_code == 0, result.output
    table = read_csv(tmp_path / "towers.csv")
    assert len(table) == 9 and table[0]["id"] == "ARC-08"  # riskiest first (default order)
    classes = [row["risk_class"] for row in table]
    rank = ["collapse", "high", "moderate", "low", "none", "unknown"]
    assert [rank.index(c) for c in classes] == sorted(rank.index(c) for c in classes)
    assert {"lat_deg", "lon_deg", "theta_max_rad", "safety_factor"} <= set(table[0])
    result = runner.invoke(main, ["export", str(archive), "--geojson", "towers.geojson"])
    assert result.exit_code == 0, result.output
    features = json.loads((tmp_path / "towers.geojson").read_text(encoding="utf-8"))["features"]
    assert len(features) == 8  # ARC-07 has no coordinates
    assert "ARC-07" in result.stderr
    out = plot_risk_map(read_summary(archive), example_station_sites(), tmp_path / "map.png")
    assert out.stat().st_size > 10_000


def test_csv_neutralises_formula_cells_and_keeps_numbers(rows, tmp_path):
    evil = dict(rows[0])
    evil.update(
        id='=HYPERLINK("http://x")',
        name="+1+cmd|' /C calc'!A0",
        stations="@SUM(A1)",
        governing_record="-2+3",
        governing_model="\tTAB",
        risk_class="\rCR",
        theta_max_over_alpha=np.float64(-0.5),
        n_records=np.int64(-3),
    )
    evil["=header"] = "x"
    path = tmp_path / "evil.csv"
    write_summary_csv([evil, rows[1]], path)
    table = read_csv(path)
    first = table[0]
    assert first["id"] == '\'=HYPERLINK("http://x")'
    assert first["name"] == "'+1+cmd|' /C calc'!A0"
    assert first["stations"] == "'@SUM(A1)"
    assert first["governing_record"] == "'-2+3"
    assert first["governing_model"] == "'\tTAB"
    assert first["risk_class"] == "'\rCR"
    assert first["theta_max_over_alpha"] == "-0.5" and first["n_records"] == "-3"
    assert "'=header" in first and first["'=header"] == "x"
    assert table[1]["id"] == "ARC-01" and table[1]["name"] == rows[1]["name"]
    features, _ = summary_feature_collection([evil])
    assert features["features"][0]["id"] == evil["id"]  # JSON needs no such escaping
