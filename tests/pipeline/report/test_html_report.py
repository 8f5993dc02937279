"""The HTML report: builder on every archive kind, escaping, reduction, size."""

from __future__ import annotations

import html
import json
import math
import re

import numpy as np
import pytest
from click.testing import CliRunner

from rockscreen.pipeline.cli import main
from rockscreen.pipeline.errors import ReportError
from rockscreen.pipeline.report.html import archive_kind, build_report, render_html, report_model
from rockscreen.pipeline.report.html.adapters.risk import risk_model, shakemap_contours
from rockscreen.pipeline.report.html.i18n import STRINGS
from rockscreen.pipeline.report.html.model import Column, Note, ReportModel, Sheet
from rockscreen.pipeline.report.html.reduce import expand_series, reduce_series
from rockscreen.pipeline.report.html.render import json_for_script

HOSTILE = '<script>alert("x")</script>\x07<!-- =cmd|'


def page_data(page: str) -> dict:
    match = re.search(
        r'<script id="report-data" type="application/json">(.*?)</script>', page, re.S
    )
    assert match, "no data block"
    return json.loads(match.group(1))


def test_every_string_has_both_languages():
    for key, entry in STRINGS.items():
        assert set(entry) == {"en", "it"}, key
        assert entry["en"].strip() and entry["it"].strip(), key


def test_run_archive_report(example_archive, tmp_path):
    out = build_report(example_archive, tmp_path / "r.html")
    page = out.read_text(encoding="utf-8")
    assert page.startswith("<!DOCTYPE html>")
    assert "http" not in re.sub(r'"url":"https://tile\.openstreetmap\.org[^"]*"', "", page).replace(
        "http://www.w3.org/2000/svg", ""
    ).replace("openstreetmap.org/copyright", "")  # no other address: nothing fetched
    data = page_data(page)
    assert data["kind"] == "run" and len(data["towers"]) == 9
    arc08 = next(t for t in data["towers"] if t["id"] == "ARC-08")
    # ARC-08's bell gable (0.5 m thick, 3.8 m high, on the 9 m facade's floor motion)
    # overturns under the example records: the tower's class is "collapse" (issue 22)
    assert arc08["risk_class"] == "collapse" and arc08["theta_max_over_alpha"] > 1.0
    assert arc08["distance_km"] is not None and arc08["distance_km"] < 50
    sheet = data["sheets"]["ARC-08"]
    assert any("bell gable rocking" in line for line in sheet["verdict"])
    (figure,) = sheet["figures"]
    assert figure["bounds"] and figure["series"] and figure["series"][0]["ref"] in data["motions"]
    assert "Pairing distance" in page and "50 km" in page
    assert "Housner" in page and "rigid-block" in page


def test_run_report_in_italian_through_the_cli(example_archive, tmp_path):
    out = tmp_path / "it.html"
    result = CliRunner().invoke(
        main, ["report", str(example_archive), "--out", str(out), "--lang", "it"]
    )
    assert result.exit_code == 0, result.output
    page = out.read_text(encoding="utf-8")
    assert '<html lang="it">' in page and "Cosa è stato calcolato" in page
    assert page_data(page)["strings"]["col_class"] == "Classe di rischio"
    assert "report written to" in result.stderr


def test_report_of_a_non_archive_is_one_line(tmp_path):
    bogus = tmp_path / "x.h5"
    bogus.write_text("no", encoding="utf-8")
    result = CliRunner().invoke(main, ["report", str(bogus)])
    assert result.exit_code == 1 and result.stderr.startswith("rockscreen: error:")
    assert len(result.stderr.strip().splitlines()) == 1


def test_sweep_archive_report(tmp_path):
    from rockscreen.pipeline.study.sweep import parse_study, run_study, write_sweep_archive

    study = parse_study(
        """
[tower]
name = "tiny"
width_m = 2.0
height_m = 8.0
[[group]]
name = "pulse"
model = "rocking"
excitation = "pulse"
shape = "one-sine"
amplitudes = ["0.1g", "0.6g"]
frequencies_hz = [2.0]
""",
        source="tiny.toml",
    )
    path = tmp_path / "sweep.h5"
    write_sweep_archive(path, study, run_study(study))
    assert archive_kind(path) == "sweep"
    data = page_data(render_html(report_model(path)))
    assert data["kind"] == "sweep" and len(data["towers"]) == 2
    weak, strong = data["towers"]
    assert weak["risk_class"] == "none" and weak["theta_max_over_alpha"] == 0.0
    assert strong["theta_max_over_alpha"] > 0
    assert data["sheets"]["1"]["figures"][0]["series"][0]["data"]


def risk_rows():
    summary = [
        {
            "id": "T1",
            "name": "first",
            "lat_deg": 41.0,
            "lon_deg": 14.4,
            "soil_class": "C",
            "soil_class_source": "default",
            "fragility_median_g": 0.3,
            "fragility_beta": 0.4,
            "annual_rate_overturning_per_y": 2e-3,
            "p_overturning_50y": 0.095,
            "capacity_pga_g": 0.3,
            "capacity_return_period_y": 500.0,
            "safety_index": 0.7,
            "acceleration_factor": 0.8,
            "risk_class": "moderate",
            "note": "",
        },
        {
            "id": "T2",
            "name": "second",
            "lat_deg": math.nan,
            "lon_deg": math.nan,
            "soil_class": "B",
            "soil_class_source": "inventory",
            "fragility_median_g": math.nan,
            "fragility_beta": math.nan,
            "annual_rate_overturning_per_y": math.nan,
            "p_overturning_50y": math.nan,
            "capacity_pga_g": math.nan,
            "capacity_return_period_y": math.inf,
            "safety_index": math.nan,
            "acceleration_factor": math.nan,
            "risk_class": "undefined",
            "note": "never overturned at any stripe",
        },
    ]
    stripes = [
        {"tower_id": "T1", "return_period_y": tr, "ag_g": ag, "n_records": 7, "n_overturned": k}
        for tr, ag, k in ((50.0, 0.1, 0), (475.0, 0.25, 3), (2475.0, 0.45, 6))
    ]
    return summary, stripes


def test_assess_model_from_rows():
    summary, stripes = risk_rows()
    model = risk_model("assess", {"rockscreen_version": "0.1.0"}, summary, stripes)
    data = page_data(render_html(model))
    keys = [c["key"] for c in data["columns"]]
    assert keys[:4] == ["id", "name", "risk_class", "soil_class"]
    assert {"safety_index", "p_overturning_50y", "capacity_pga_g"} <= set(keys)
    t2 = data["towers"][1]
    assert t2["lat"] is None and t2["capacity_return_period_y"] == "inf"
    (figure,) = data["sheets"]["T1"]["figures"]
    curve, points = figure["curves"]
    assert points["style"] == "points" and points["y"] == pytest.approx([0, 3 / 7, 6 / 7], abs=1e-3)
    # the lognormal curve passes 0.5 at its median
    assert np.interp(0.3, curve["x"], curve["y"]) == pytest.approx(0.5, abs=0.02)
    assert any("I_S = 0.7" in line for line in data["sheets"]["T1"]["verdict"])
    assert data["sheets"]["T2"]["notes"] == ["never overturned at any stripe"]
    assert "default: 1" in render_html(model)  # the assumed soil class is stated


def test_assess_sheet_has_the_checks_side_by_side():
    """The checks table of the tower sheet: every check made, signed bounds, why not made."""
    summary, stripes = risk_rows()
    nan = math.nan
    checks = {
        "governing": "bell gable kinematic (linear)",
        "governing_capacity_ag_g": 0.12,
        "governing_safety_index": 0.4,
        "governing_bound": "",
        "checks_not_made": "belfry not checked (no belfry columns in the inventory)",
        "checks_disagree": "rocking (I_S 0.70, moderate) and the kinematic checks (...) disagree",
        "slv_bound": "",
        "collapse_median_g": 0.3,
        "belfry_fragility_median_g": nan,
        "tower_kinematic_alpha0": 0.2,
        "tower_kinematic_e_star": 0.75,
        "tower_kinematic_a0_g": 0.198,
        "tower_kinematic_linear_capacity_ag_g": 0.36,
        "tower_kinematic_linear_safety_index": 3.48,
        "tower_kinematic_linear_bound": "lower",
        "tower_kinematic_nonlinear_capacity_ag_g": 0.36,
        "tower_kinematic_nonlinear_safety_index": 3.48,
        "tower_kinematic_nonlinear_bound": "lower",
        "gable_kinematic_alpha0": 0.13,
        "gable_kinematic_e_star": 0.77,
        "gable_kinematic_a0_g": 0.124,
        "gable_kinematic_linear_capacity_ag_g": 0.12,
        "gable_kinematic_linear_safety_index": 0.4,
        "gable_kinematic_linear_bound": "",
        "gable_kinematic_nonlinear_capacity_ag_g": 0.25,
        "gable_kinematic_nonlinear_safety_index": 2.1,
        "gable_kinematic_nonlinear_bound": "",
        "lv1_capacity_ag_g": 0.23,
        "lv1_safety_index": 1.04,
        "lv1_bound": "",
        "lv1_period_s": 0.26,
    }
    summary[0].update(checks)
    model = risk_model("assess", {}, summary, stripes)
    data = page_data(render_html(model))
    sheet = data["sheets"]["T1"]
    rows = {row[0]: row[1:] for row in sheet["checks"]}
    assert list(rows) == [
        "Whole-tower rocking (IDA)",
        "Belfry rocking on the shaft (IDA)",
        "Kinematic, linear: whole tower",
        "Kinematic, non-linear: whole tower",
        "Kinematic, linear: bell gable",
        "Kinematic, non-linear: bell gable",
        "LV1 tower model",
    ]
    assert rows["Kinematic, linear: whole tower"][:2] == ["> 0.36 g", "> 3.48"]
    assert rows["Kinematic, linear: bell gable"][:2] == ["0.12 g", "0.4"]
    assert rows["Belfry rocking on the shaft (IDA)"] == [
        "-",
        "-",
        "belfry not checked (no belfry columns in the inventory)",
    ]
    assert rows["LV1 tower model"][2] == "shaft flexure, T1 0.26 s"
    assert sheet["checks_text"][0] == (
        "Governing: bell gable kinematic (linear), a_C 0.12 g, I_S 0.4 (the class follows it)."
    )
    assert sheet["checks_text"][1].startswith("Where they disagree: rocking (I_S 0.70")
    assert sheet["checks_text"][2].startswith("Not made: belfry not checked")
    assert data["sheets"]["T2"]["checks"] == []  # a row without the checks (older archive)
    assert "Side by side" in json.dumps(data["strings"])


def test_assess_archive_from_the_risk_writer(tmp_path):
    risk_archive = pytest.importorskip("rockscreen.pipeline.archive.risk_archive")
    summary, stripes = risk_rows()
    path = tmp_path / "assess.h5"
    risk_archive.write_risk_archive(
        path, "assess", {"summary": summary, "stripes": stripes}, {"command_line": "test"}
    )
    assert archive_kind(path) == "assess"
    data = page_data(render_html(report_model(path)))
    assert [t["id"] for t in data["towers"]] == ["T1", "T2"]
    assert data["sheets"]["T1"]["figures"][0]["curves"][1]["y"][2] == pytest.approx(6 / 7, abs=1e-3)


def test_scenario_contours():
    lon = np.linspace(14.0, 15.0, 21)
    lat = np.linspace(41.0, 42.0, 21)
    lon2, lat2 = np.meshgrid(lon, lat)
    pga = 0.6 * np.exp(-((lon2 - 14.5) ** 2 + (lat2 - 41.5) ** 2) / 0.05)
    contours = shakemap_contours(lon, lat, pga)
    assert [c["label"] for c in contours] == ["0.05 g", "0.1 g", "0.2 g", "0.3 g", "0.5 g"]
    ring = np.array(contours[1]["lines"][0])
    radius = np.hypot(ring[:, 0] - 14.5, ring[:, 1] - 41.5)
    assert radius == pytest.approx(math.sqrt(0.05 * math.log(6)), rel=0.05)
    summary, _ = risk_rows()
    data = page_data(render_html(risk_model("scenario", {}, summary, (), contours)))
    assert data["kind"] == "scenario" and len(data["contours"]) == 5


def test_reduction_keeps_peaks_and_envelope():
    t = np.linspace(0, 30, 30001)
    x = np.sin(7 * t) * np.exp(-t / 10)
    x[12345] = 2.5
    series = reduce_series(t, x, label="x", unit="1", bins=200)
    times, lows, highs = expand_series(series)
    assert len(times) == 200 and highs.max() == pytest.approx(2.5, rel=1e-4)
    assert lows.min() == pytest.approx(x.min(), rel=1e-3)
    assert np.all(lows <= highs)
    assert len(series.data) < 1100


def test_json_for_script_cannot_close_the_script():
    text = json_for_script({"id": "</script><!-- & \u2028"})
    assert "<" not in text and ">" not in text and "&" not in text and "\u2028" not in text
    assert json.loads(text) == {"id": "</script><!-- & \u2028"}


def synthetic_model(n: int, hostile: bool = False) -> ReportModel:
    rng = np.random.default_rng(1)
    model = ReportModel(kind="run", title="kind_run", classes=["collapse", "high", "none"])
    model.columns = [
        Column("id", "col_id", "", "text"),
        Column("risk_class", "col_class", "", "class"),
        Column("theta_max_over_alpha", "col_theta", "-"),
        Column("note", "col_note", "", "text"),
    ]
    t = np.linspace(0, 60, 6000)
    for i in range(n):
        tower_id = (HOSTILE if hostile and i == 0 else "") + f"T-{i:04d}"
        model.towers.append(
            {
                "id": tower_id,
                "lat": 41 + rng.random(),
                "lon": 14 + rng.random(),
                "risk_class": ["collapse", "high", "none"][i % 3],
                "theta_max_over_alpha": float(rng.random()),
                "note": HOSTILE if hostile else "",
            }
        )
        from rockscreen.pipeline.report.html.model import Figure

        figure = Figure("history", "s_histories", "s_time", "s_theta", bounds=True)
        for k in range(3):  # three models per tower
            theta = np.sin((2 + k) * t) * np.exp(-t / 20) * rng.random()
            figure.series.append(reduce_series(t, theta, label=f"XX.S{i}..HNE · m{k}", unit="1"))
        model.sheets[tower_id] = Sheet(
            inputs=[("i_width", "2.0 m"), ("i_name", HOSTILE if hostile else "x")],
            figures=[figure],
            verdict=[("v_class", {"cls": {"key": "class_high"}})],
            notes=[Note(HOSTILE)] if hostile else [],
        )
    return model


def test_hostile_ids_are_escaped():
    page = render_html(synthetic_model(3, hostile=True))
    assert "<script>alert" not in page
    static = page.split('<script id="report-data"')[0]
    assert HOSTILE not in static
    data = page_data(page)
    assert data["towers"][0]["id"].startswith(HOSTILE)  # kept, as data, for textContent


def test_header_values_are_escaped():
    from rockscreen.pipeline.report.html.model import HeaderItem

    model = synthetic_model(1)
    model.header = [HeaderItem("h_command", HOSTILE)]
    page = render_html(model)
    assert html.escape(HOSTILE) in page and HOSTILE not in page


def test_unknown_language_is_refused():
    with pytest.raises(ReportError, match="language 'fr'"):
        render_html(synthetic_model(1), "fr")


def test_thousand_towers_under_five_megabytes():
    page = render_html(synthetic_model(1000))
    size = len(page.encode("utf-8"))
    assert size < 5_000_000, f"{size / 1e6:.2f} MB"
    assert len(page_data(page)["sheets"]) == 1000
