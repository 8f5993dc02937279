"""No bound is ever printed as a plain value, in any output of an assess archive (issue 23).

One assess archive holding lower bounds (``assess --example`` with three records per
stripe: several towers never overturn up to the IDA cap), then every output that prints
its values: the assess terminal table, ``inspect --json``, ``export`` CSV (both dialects)
and GeoJSON, and the HTML report (the table's data and the sheet sentences). Every value
that :mod:`rockscreen.pipeline.archive.bounds` calls a bound must carry its relation.
"""

from __future__ import annotations

import csv
import io
import json
import math
import re

import pytest
from click.testing import CliRunner

from rockscreen.pipeline.archive.bounds import bounded_columns
from rockscreen.pipeline.cli import main

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def outputs(tmp_path_factory):
    folder = tmp_path_factory.mktemp("bounds")
    runner = CliRunner()
    out = {}
    with pytest.MonkeyPatch.context() as patch:
        patch.chdir(folder)
        commands = {
            "assess": "assess --example --return-periods 101,475,2475 --records 3 --jobs 1 "
            "--allow-noncompliant --out a.h5",
            "json": "inspect a.h5 --json",
            "csv": "export a.h5 --csv a.csv",
            "csv_it": "export a.h5 --csv a-it.csv --excel-it",
            "geojson": "export a.h5 --geojson a.geojson",
            "report": "report a.h5 --out a.html",
        }
        for name, line in commands.items():
            result = runner.invoke(main, line.split())
            assert result.exit_code == 0, (line, result.output)
            out[name] = result.stdout
    out["folder"] = folder
    return out


def _summary(outputs):
    text = outputs["json"]
    data = json.loads(text)
    towers = data["towers"] if isinstance(data, dict) and "towers" in data else data
    return {str(t["id"]): t for t in towers}


def _bounded_rows(outputs):
    """{tower id: {column: sign}} from the archive's own rows (inspect --json carries them)."""
    out = {}
    for tower_id, row in _summary(outputs).items():
        signs = {
            key: sign
            for key, sign in bounded_columns(row).items()
            if isinstance(row.get(key), int | float) and math.isfinite(row[key])
        }
        if signs:
            out[tower_id] = signs
    return out


def test_the_archive_holds_bounds(outputs):
    bounded = _bounded_rows(outputs)
    assert len(bounded) >= 3, bounded  # the example has towers that never overturn
    assert any("safety_index" in signs for signs in bounded.values())


def test_inspect_json_notes_every_bound(outputs):
    summary = _summary(outputs)
    for tower_id, signs in _bounded_rows(outputs).items():
        for key, sign in signs.items():
            note = summary[tower_id].get(f"{key}_note", "")
            assert ("lower bound" if sign == ">" else "upper bound") in note, (tower_id, key)


@pytest.mark.parametrize(("name", "delimiter"), [("a.csv", ","), ("a-it.csv", ";")])
def test_csv_writes_every_bound_with_its_relation(outputs, name, delimiter):
    text = (outputs["folder"] / name).read_text(encoding="utf-8-sig")
    rows = {r["id"]: r for r in csv.DictReader(io.StringIO(text), delimiter=delimiter)}
    for tower_id, signs in _bounded_rows(outputs).items():
        for key, sign in signs.items():
            assert rows[tower_id][key].startswith(sign), (tower_id, key, rows[tower_id][key])


def test_geojson_writes_every_bound_with_its_relation(outputs):
    data = json.loads((outputs["folder"] / "a.geojson").read_text(encoding="utf-8"))
    features = {f["id"]: f["properties"] for f in data["features"]}
    for tower_id, signs in _bounded_rows(outputs).items():
        if tower_id not in features:  # no coordinates: not placed
            continue
        for key, sign in signs.items():
            value = features[tower_id][key]
            assert isinstance(value, str) and value.startswith(sign), (tower_id, key, value)


def test_html_marks_every_bound_in_the_table_and_the_sheet(outputs):
    page = (outputs["folder"] / "a.html").read_text(encoding="utf-8")
    block = re.search(
        r'<script id="report-data" type="application/json">(.*?)</script>', page, re.S
    )
    data = json.loads(block.group(1))
    towers = {t["id"]: t for t in data["towers"]}
    shown = {c["key"] for c in data["columns"]}
    for tower_id, signs in _bounded_rows(outputs).items():
        for key, sign in signs.items():
            if key in shown and towers[tower_id].get(key) is not None:
                assert towers[tower_id].get("bounds", {}).get(key) == sign, (tower_id, key)
        sentences = " ".join(data["sheets"][tower_id]["verdict"])
        if "safety_index" in signs:
            assert "I_S ≥" in sentences or "I_S >" in sentences, sentences


def test_assess_terminal_table_marks_every_shown_bound(outputs):
    summary = _summary(outputs)
    lines = outputs["assess"].splitlines()
    for tower_id, signs in _bounded_rows(outputs).items():
        line = next((ln for ln in lines if ln.split()[:1] == [tower_id]), None)
        assert line is not None, tower_id
        for key, sign in signs.items():
            text = format(summary[tower_id][key], ".3g")
            for match in re.finditer(re.escape(text), line):
                before = line[max(0, match.start() - 1) : match.start()]
                if match.start() and line[match.start() - 1].isdigit():
                    continue  # part of another number
                if line.rfind("[", 0, match.start()) > line.rfind("]", 0, match.start()):
                    continue  # an end of another column's 90 % interval "[low-high]"
                assert before in (sign, "≥" if sign == ">" else "≤"), (tower_id, key, line)
