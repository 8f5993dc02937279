"""A new code check is one module plus its catalogue entries (issue 29).

A toy check module written into a folder of the checks' package path is registered when
``assess`` loads the package, computed per tower by the one loop of the worker, archived in
``/checks`` and shown by the terminal table, ``inspect --json``, the CSV and the report's
tower sheet, in English and Italian, without another file changing.
"""

from __future__ import annotations

import csv
import json
import math
import sys
import textwrap

import h5py
import pytest
from click.testing import CliRunner

from rockscreen.pipeline.archive.kinds import open_archive
from rockscreen.pipeline.archive.risk_reader import read_summary
from rockscreen.pipeline.archive.risk_schema import assess_tables, bound_columns
from rockscreen.pipeline.archive.safety import read_column
from rockscreen.pipeline.cli import main
from rockscreen.pipeline.risk.checks import code
from rockscreen.pipeline.risk.checks.registry import unregister
from rockscreen.pipeline.risk.checks.tower_code_checks import registered_checks
from rockscreen.pipeline.verdict import catalogue as subjects
from rockscreen.pipeline.verdict.checks import loads_not_made
from rockscreen.pipeline.verdict.messages import catalogue, render

#: The check module: a toy capacity of the shaft from its geometry, and a check that needs
#: the shaft's wall thickness, which the inventory lacks.
TOY_MODULE = '''
"""Toy code checks of the shaft: one made from the geometry, one needing its walls."""

from rockscreen.pipeline.archive.schema import DIMENSIONLESS, G_UNITS, TEXT
from rockscreen.pipeline.risk.checks.registry import CheckOutput, CodeCheck, register
from rockscreen.pipeline.verdict.checks import Family, Method


def compression(context):
    """A fixed toy capacity: ag = 0.01 width / height [g], I_S against ag at 475 y."""
    tower = context.tower
    ag = 0.01 * tower.width_m / tower.height_m
    ag_475 = context.conditions.hazard(475.0).ag_g
    return CheckOutput(
        {
            "toy_capacity_ag_g": ag,
            "toy_safety_index": ag / ag_475,
            "toy_bound": "",
            "toy_compression_ratio": 0.25,
            "toy_slenderness": tower.height_m / tower.width_m,
        }
    )


def walls(context):
    raise AssertionError("not computed: the inventory has no wall_thickness_m")


register(
    CodeCheck(
        "shaft.toy_compression",
        "shaft",
        Family.SHAFT_FLEXURE,
        Method.LV1,
        requires=("width_m", "height_m"),
        governs_before_rocking=True,
        covers="a toy check of the shaft's compression",
        keys=("toy_capacity_ag_g", "toy_safety_index", "toy_bound"),
        details={"compression_ratio": "toy_compression_ratio"},
        columns={
            "toy_capacity_ag_g": G_UNITS,
            "toy_safety_index": DIMENSIONLESS,
            "toy_bound": TEXT,
            "toy_compression_ratio": DIMENSIONLESS,
            "toy_slenderness": DIMENSIONLESS,
        },
        compute=compression,
    )
)
register(
    CodeCheck(
        "shaft.toy_walls",
        "shaft",
        Family.SHAFT_FLEXURE,
        Method.LV1,
        requires=("wall_thickness_m",),
        governs_before_rocking=True,
        covers="a toy check of the shaft's walls",
        keys=("toy_walls_capacity_ag_g", "toy_walls_safety_index", "toy_walls_bound"),
        columns={
            "toy_walls_capacity_ag_g": G_UNITS,
            "toy_walls_safety_index": DIMENSIONLESS,
            "toy_walls_bound": TEXT,
        },
        compute=walls,
    )
)
'''
#: Its catalogue entries: the checks' labels, English and Italian.
TOY_CATALOGUE = '''
"""Labels of the toy code checks."""

from rockscreen.pipeline.verdict.messages import MessageSpec, register

register(
    MessageSpec("check.shaft.toy_compression", "toy compression", "compressione di prova"),
    MessageSpec("check.shaft.toy_walls", "toy walls", "pareti di prova"),
)
'''
TOY_IDS = ("shaft.toy_compression", "shaft.toy_walls")


@pytest.fixture
def toy_check(tmp_path, monkeypatch):
    """Add the toy check module and its catalogue module as plugin folders."""
    checks = tmp_path / "check-plugins"
    checks.mkdir()
    (checks / "toy_checks.py").write_text(textwrap.dedent(TOY_MODULE), encoding="utf-8")
    entries = tmp_path / "catalogue-plugins"
    entries.mkdir()
    (entries / "toy_labels.py").write_text(textwrap.dedent(TOY_CATALOGUE), encoding="utf-8")
    monkeypatch.setattr(code, "__path__", [*code.__path__, str(checks)])
    monkeypatch.setattr(subjects, "__path__", [*subjects.__path__, str(entries)])
    yield
    monkeypatch.undo()
    for check in TOY_IDS:
        unregister(check)
    sys.modules.pop(f"{code.__name__}.toy_checks", None)
    sys.modules.pop(f"{subjects.__name__}.toy_labels", None)


def _assess(tmp_path):
    inventory = tmp_path / "towers.csv"
    inventory.write_text("id;lat;lon;width_m;height_m\nA;41,04;14,42;2;8\n", encoding="utf-8")
    out = tmp_path / "a.h5"
    args = ["assess", "--towers", str(inventory), "--return-periods", "475", "--records", "3"]
    args += ["--models", "ground", "--bootstrap", "0", "--jobs", "1", "--out", str(out)]
    args += ["--allow-noncompliant"]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    return out, result.output


def test_a_new_code_check_is_one_module(toy_check, tmp_path):
    out, printed = _assess(tmp_path)
    assert [c.id for c in registered_checks()][-2:] == list(TOY_IDS)
    assert all(f"check.{c}" in catalogue() for c in TOY_IDS)

    # computed by the worker's loop; the check of lowest capacity governs
    (row,) = read_summary(out, "assess")
    assert row["toy_capacity_ag_g"] == pytest.approx(0.01 * 2 / 8)
    assert row["toy_slenderness"] == 4.0
    assert row["toy_capacity_ag_g"] < row["capacity_pga_g"]
    assert row["governing_check"] == "shaft.toy_compression"
    assert row["governing"] == "toy compression"
    assert row["governing_capacity_ag_g"] == row["toy_capacity_ag_g"]
    # the check whose column the inventory lacks: not made, with the catalogue's message
    assert math.isnan(row["toy_walls_capacity_ag_g"])
    reason = loads_not_made(row["checks_not_made_codes"])["shaft.toy_walls"]
    assert reason.code == "not_made.code_check_columns"
    assert render(reason) == "toy walls not made (no wall_thickness_m in the inventory)"
    italian = "pareti di prova non eseguita (wall_thickness_m assenti nell'inventario)"
    assert render(reason, "it") == italian
    assert "toy walls not made" in row["checks_not_made"]

    # archived as rows of /checks; the column that is not a check's field stays in
    # /summary, with the units the module declared
    with h5py.File(out, "r") as f:
        checks = list(read_column(f["checks/check"], out, "checks/check"))
        status = list(read_column(f["checks/status"], out, "checks/status"))
        ag = f["checks/capacity_ag_g"][checks.index("shaft.toy_compression")]
        assert "toy_capacity_ag_g" not in f["summary"]
        assert f["summary/toy_slenderness"].attrs["units"] == "1"
    assert ag == row["toy_capacity_ag_g"]
    assert status[checks.index("shaft.toy_walls")] == "not_made"
    assert assess_tables()["summary"]["toy_slenderness"] == "1"
    assert bound_columns()["toy_capacity_ag_g"] == "toy_bound"

    # the terminal table of assess, and inspect's
    header = next(x for x in printed.splitlines() if x.split()[:2] == ["tower", "governing"])
    assert "toy compression a_C [g]" in header and "toy walls I_S [-]" in header
    (line,) = [x for x in printed.splitlines() if x.startswith("A ") and "toy compression" in x]
    assert line.rstrip().endswith("not made")
    runner = CliRunner()
    inspected = runner.invoke(main, ["inspect", str(out)])
    assert "toy compression a_C [g]" in inspected.output

    # inspect --json: the toy's columns, and why the other is null
    inspected = runner.invoke(main, ["inspect", "--json", str(out)])
    assert inspected.exit_code == 0, inspected.output
    (tower,) = json.loads(inspected.stdout)["towers"]
    assert tower["toy_capacity_ag_g"] == pytest.approx(row["toy_capacity_ag_g"])
    assert tower["toy_walls_safety_index"] is None
    assert "no wall_thickness_m" in tower["toy_walls_safety_index_note"]

    # the CSV export: one row per tower, the checks' columns beside the others
    exported = runner.invoke(main, ["export", str(out), "--csv", str(tmp_path / "a.csv")])
    assert exported.exit_code == 0, exported.output
    with (tmp_path / "a.csv").open(newline="", encoding="utf-8") as handle:
        (csv_row,) = list(csv.DictReader(handle))
    assert {"toy_capacity_ag_g", "toy_safety_index", "toy_slenderness"} <= set(csv_row)
    assert float(csv_row["toy_capacity_ag_g"]) == pytest.approx(row["toy_capacity_ag_g"])
    geojson = tmp_path / "a.geojson"
    exported = runner.invoke(main, ["export", str(out), "--geojson", str(geojson)])
    assert exported.exit_code == 0, exported.output
    (feature,) = json.loads(geojson.read_text(encoding="utf-8"))["features"]
    assert feature["properties"]["toy_capacity_ag_g"] == pytest.approx(row["toy_capacity_ag_g"])

    # the report's tower sheet, from the checks the archive stores
    from rockscreen.pipeline.report.html.adapters.risk_checks import checks_table

    rows, text = checks_table(row, open_archive(out).checks())
    labels = [r[0] for r in rows if not isinstance(r[0], str)]
    assert [render(label) for label in labels] == ["toy compression", "toy walls"]
    toy, walls = rows[-2:]
    assert toy[1]["num"] == pytest.approx(row["toy_capacity_ag_g"])
    assert render(toy[3]) == "compression_ratio 0.25"
    assert walls[1:3] == ("-", "-") and render(walls[3]) == render(reason)
    assert render(text[0][1]["label"]) == "toy compression"
    for lang, words in (
        ("en", ("toy compression", "toy walls not made")),
        ("it", ("compressione di prova", "pareti di prova non eseguita")),
    ):
        page = tmp_path / f"a_{lang}.html"
        done = runner.invoke(main, ["report", str(out), "--lang", lang, "--out", str(page)])
        assert done.exit_code == 0, done.output
        html = page.read_text(encoding="utf-8")
        assert all(word in html for word in words), lang


def test_a_check_whose_computation_fails_on_a_tower_is_failed_not_fatal(toy_check):
    """The loop says a check's error on the tower's data, and computes the others."""
    from rockscreen.pipeline.risk.checks.registry import CheckContext, code_check
    from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
    from rockscreen.pipeline.risk.checks.tower_code_checks import run_code_checks
    from rockscreen.stations.tower import Tower

    class Site:  # an assessed site off the NTC grid: the toy's hazard(475) fails
        tower = Tower(id="A", width_m=2.0, height_m=8.0)
        lon_deg, lat_deg = 0.0, 0.0
        soil_class, topography, nominal_life_y, use_class = "A", "T1", 50.0, "II"

    registered_checks()
    context = CheckContext(Site(), SiteConditions.of(Site()), "LC1", 1.35)
    columns, notes, not_made = run_code_checks(context)
    by_id = {r.check: r for r in not_made}
    assert by_id["shaft.toy_compression"].status.value == "failed"
    assert "toy compression failed" in render(by_id["shaft.toy_compression"].reason)
    assert by_id["shaft.toy_walls"].status.value == "not_made"
    assert code_check("shaft.toy_compression").empty_columns()["toy_bound"] == ""
    assert "toy_capacity_ag_g" not in columns
    assert "tower_kinematic_alpha0" not in columns  # the kinematic checks: said in a note
    assert any(m.code == "kinematic.not_made" for m in notes)


def test_the_toy_leaves_the_registry_with_its_module(tmp_path):
    assert not {c.id for c in registered_checks()} & set(TOY_IDS)
    assert "toy_slenderness" not in assess_tables()["summary"]


def test_the_method_names_a_stored_check_this_process_has_not_registered():
    """A report written where the check's module is not loaded still names it."""
    from rockscreen.pipeline.archive.long_schema import CheckColumns
    from rockscreen.pipeline.report.html.adapters.risk_method import method_paragraphs
    from rockscreen.pipeline.verdict.messages import message

    keys = ("x_capacity_ag_g", "x_safety_index", "x_bound")
    stored = [
        CheckColumns("shaft.elsewhere", "shaft", "shaft_flexure", "lv1", keys),
        CheckColumns("shaft.nowhere", "shaft", "shaft_flexure", "lv1", ("y_ag_g", "y_si", "")),
        CheckColumns("shaft.lv1", "shaft", "shaft_flexure", "lv1", keys),  # registered
    ]
    summary = [{"id": "A", "x_safety_index": 0.5}, {"id": "B", "x_safety_index": math.nan}]
    (checks,) = [
        p
        for p in method_paragraphs("assess", {}, summary, (), stored)
        if p.heading == "method.h_checks"
    ]
    said = [message(code, **params).render() for code, params in checks.sentences]
    assert "shaft.elsewhere: made (towers: 1 of 2)." in said
    assert "shaft.nowhere: made for no tower (each tower's sheet says why)." in said
    assert sum("LV1" in s for s in said) == 1  # the registered check once


def test_a_check_declares_the_columns_it_computes():
    """A computing check names its a_C, I_S, bound and details among its columns."""
    from dataclasses import replace

    from rockscreen.pipeline.risk.checks.registry import code_check, register

    lv1 = code_check("shaft.lv1")
    with pytest.raises(ValueError, match="not in its columns"):
        register(replace(lv1, id="shaft.lv1_copy", columns={}))
    with pytest.raises(ValueError, match="not a code check's"):
        register(replace(lv1, id="shaft.lv1_copy", columns={**lv1.columns, "safety_index": "1"}))
    assert [c.id for c in registered_checks()][0] == "shaft.lv1"
    assert "shaft.lv1_copy" not in {c.id for c in registered_checks()}


def test_a_process_without_the_check_module_reads_it_from_the_archive(toy_check, tmp_path):
    """inspect, export and report in a fresh interpreter that has only the labels loaded."""
    import subprocess

    out, _ = _assess(tmp_path)
    script = textwrap.dedent(
        f"""
        import json, sys
        from click.testing import CliRunner
        from rockscreen.pipeline.cli import main
        from rockscreen.pipeline.risk.checks.registry import code_checks
        from rockscreen.pipeline.verdict import catalogue

        catalogue.__path__.append({str(tmp_path / "catalogue-plugins")!r})
        runner = CliRunner()
        text = runner.invoke(main, ["inspect", {str(out)!r}]).output
        document = runner.invoke(main, ["inspect", "--json", {str(out)!r}]).stdout
        page = {str(tmp_path / "fresh.html")!r}
        runner.invoke(main, ["report", {str(out)!r}, "--lang", "it", "--out", page])
        print(json.dumps({{
            "registered": [c.id for c in code_checks()],
            "table": "toy compression a_C [g]" in text,
            "tower": json.loads(document)["towers"][0],
        }}))
        """
    )
    done = subprocess.run(
        [sys.executable, "-c", script], capture_output=True, text=True, timeout=300, check=False
    )
    assert done.returncode == 0, done.stderr
    seen = json.loads(done.stdout.strip().splitlines()[-1])
    assert not set(TOY_IDS) & set(seen["registered"])  # the check's module is not loaded
    assert seen["table"]
    assert seen["tower"]["toy_capacity_ag_g"] == pytest.approx(0.01 * 2 / 8)
    assert "no wall_thickness_m" in seen["tower"]["toy_walls_capacity_ag_g_note"]
    html = (tmp_path / "fresh.html").read_text(encoding="utf-8")
    assert "compressione di prova" in html and "pareti di prova non eseguita" in html
