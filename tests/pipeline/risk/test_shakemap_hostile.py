"""Issue 24 (item 2): ShakeMap grids as they come: hardened parser, bounded header, rows."""

from __future__ import annotations

import math
import os
import threading

import pytest

from rockscreen.pipeline.errors import ShakeMapError
from rockscreen.pipeline.hazard import shakemap_xml
from rockscreen.pipeline.hazard.shakemap import read_shakemap_grid
from rockscreen.pipeline.risk.scenario.probability import tower_scenario

NODES = [(lon, lat) for lat in range(38, 43) for lon in range(8, 16)]  # 8 x 5, 1 degree
SPEC = dict(lon_min="8", lat_min="38", lon_max="15", lat_max="42", nlon="8", nlat="5")
FIELDS = [("1", "LON", "dd"), ("2", "LAT", "dd"), ("3", "PGA", "%g")]


def _xml(spec=None, fields=None, rows=None, event='event_id="t" magnitude="6"') -> str:
    spec = {**SPEC, **(spec or {})}
    attrs = " ".join(f'{k}="{v}"' for k, v in spec.items())
    declared = "".join(
        f'<grid_field index="{i}" name="{n}" units="{u}"/>' for i, n, u in fields or FIELDS
    )
    rows = [[lon, lat, 20.0] for lon, lat in NODES] if rows is None else rows
    data = "\n".join(" ".join(str(v) for v in row) for row in rows)
    return (
        '<?xml version="1.0" encoding="UTF-8"?><shakemap_grid code_version="4">'
        f"<event {event}/><grid_specification {attrs}/>{declared}"
        f"<grid_data>\n{data}\n</grid_data></shakemap_grid>"
    )


def _refused(tmp_path, text, match, **kwargs):
    path = tmp_path / "grid.xml"
    path.write_text(text, encoding="utf-8")
    with pytest.raises(ShakeMapError, match=match):
        read_shakemap_grid(path, **kwargs)


def test_a_good_grid_is_read(tmp_path):
    path = tmp_path / "grid.xml"
    path.write_text(_xml())
    grid = read_shakemap_grid(path, strict=True)
    assert grid.n_rows == 40 and grid.at(14.5, 41.5)[0] == pytest.approx(0.2)


def test_a_utf16_doctype_is_refused(tmp_path):
    bomb = _xml().replace("<shakemap_grid", '<!DOCTYPE x [<!ENTITY a "aaaa">]><shakemap_grid')
    bomb = bomb.replace('encoding="UTF-8"', 'encoding="UTF-16"').replace('"t"', '"&a;"')
    path = tmp_path / "grid.xml"
    path.write_bytes(bomb.encode("utf-16"))
    with pytest.raises(ShakeMapError, match="DOCTYPE"):
        read_shakemap_grid(path)


def test_a_fifo_is_refused_without_waiting(tmp_path):
    fifo = tmp_path / "grid.xml"
    os.mkfifo(fifo)
    outcome = []

    def read() -> None:
        try:
            read_shakemap_grid(fifo)
        except ShakeMapError as exc:
            outcome.append(str(exc))

    worker = threading.Thread(target=read, daemon=True)
    worker.start()
    worker.join(10)
    assert outcome and "not a regular file" in outcome[0]


def test_a_file_above_the_size_limit_is_refused_before_reading(tmp_path, monkeypatch):
    path = tmp_path / "grid.xml"
    path.write_text(_xml())
    monkeypatch.setattr(shakemap_xml, "MAX_FILE_BYTES", 100)
    with pytest.raises(ShakeMapError, match="refused before reading"):
        read_shakemap_grid(path)


@pytest.mark.parametrize(
    ("spec", "match"),
    [
        ({"nlon": "1e9"}, "nlon='1e9' must be an integer from 2"),
        ({"nlat": "nan"}, "'nlat' is missing or not a finite number"),
        ({"nlon": "2.5"}, "nlon='2.5' must be an integer"),
        ({"nlon": "-8"}, "must be an integer"),
        ({"nlon": "4000", "nlat": "4001"}, "does not describe a grid"),  # 16e6 nodes
        ({"lon_min": "inf"}, "'lon_min' is missing or not a finite number"),
        ({"lon_min": "15", "lon_max": "8"}, "does not describe a grid"),
        ({"nlon": "9"}, "not on a node of the 9 x 5"),
    ],
)
def test_a_header_that_does_not_describe_the_rows_is_refused(tmp_path, spec, match):
    _refused(tmp_path, _xml(spec=spec), match)


@pytest.mark.parametrize(
    ("fields", "match"),
    [
        ([("1", "LON", "dd"), ("2", "LAT", "dd"), ("x", "PGA", "%g")], "index 'x'"),
        ([("1", "LON", "dd"), ("2", "LAT", "dd"), ("0", "PGA", "%g")], "index '0'"),
        ([("1", "LON", "dd"), ("2", "LAT", "dd"), ("9", "PGA", "%g")], "has index 9"),
        ([("1", "LON", "dd"), ("2", "LAT", "dd"), ("2", "PGA", "%g")], "same index 2"),
        (
            [("1", "LON", "dd"), ("2", "LAT", "dd"), ("3", "PGA", "%g"), ("3", "pga", "g")],
            "'PGA' is declared twice",
        ),
    ],
)
def test_grid_fields_need_a_valid_unique_index_and_name(tmp_path, fields, match):
    rows = [[lon, lat, 20.0, 0.2] for lon, lat in NODES]
    _refused(tmp_path, _xml(fields=fields, rows=rows), match)


def test_duplicated_rows_are_called_what_they_are(tmp_path):
    rows = [[lon, lat, 20.0] for lon, lat in NODES[:-1]] + [[8, 38, 21.0]]
    _refused(tmp_path, _xml(rows=rows), "rows 1 and 40 are the same node .* duplicated rows")
    more = [[lon, lat, 20.0] for lon, lat in NODES] + [[8, 38, 21.0]]
    _refused(tmp_path, _xml(rows=more), "41 rows .* 40 nodes: more rows than nodes")


@pytest.mark.parametrize(
    ("value", "units", "match"),
    [
        ("inf", "%g", "PGA inf at grid_data row 3 .* not a finite number"),
        ("nan", "%g", "PGA nan at grid_data row 3"),
        ("-5", "%g", "row 3 .* negative"),
        ("20", "g", "PGA 20.0 at grid_data row 3 .* above 5 g.*units 'g' declared"),
    ],
)
def test_a_pga_that_is_not_a_pga_is_refused_with_its_row(tmp_path, value, units, match):
    rows = [[lon, lat, 0.2 if units == "g" else 20.0] for lon, lat in NODES]
    rows[2][2] = value
    fields = [("1", "LON", "dd"), ("2", "LAT", "dd"), ("3", "PGA", units)]
    _refused(tmp_path, _xml(fields=fields, rows=rows), match)


def test_pga_zero_at_a_tower_is_probability_zero(tmp_path):
    path = tmp_path / "grid.xml"
    path.write_text(_xml(rows=[[lon, lat, 0.0] for lon, lat in NODES]))
    grid = read_shakemap_grid(path)
    row = {
        "id": "T",
        "lat_deg": 41.04,
        "lon_deg": 14.42,
        "soil_class": "B",
        "topography": "T1",
        "fragility_median_g": 0.3,
        "fragility_beta": 0.4,
        "median_is_bound": "",
        "tr_slv_y": 712.0,
    }
    out = tower_scenario(row, grid)
    assert out["p_overturning"] == 0.0 and "PGA 0" in out["note"]
    assert not math.isnan(out["beta_total"])
