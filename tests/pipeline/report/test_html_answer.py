"""The report's first screen: the answer sentences, class counts, bounds, map extent, Italian."""

from __future__ import annotations

import pytest

from rockscreen.pipeline.report.html import render_html
from rockscreen.pipeline.report.html.adapters.common import header_items, short_paths
from rockscreen.pipeline.report.html.adapters.risk import RISK_ARCHIVE_CLASSES
from rockscreen.pipeline.report.html.answer import answer_lines, class_counts, class_text
from rockscreen.pipeline.report.html.i18n import number, trn
from rockscreen.pipeline.report.html.model import ReportModel
from rockscreen.pipeline.risk.measures.classes import INCOMPLETE, class_label
from rockscreen.pipeline.verdict.scales import Completeness


def run_model(classes: list[str]) -> ReportModel:
    model = ReportModel(
        kind="run",
        title="kind_run",
        classes=["collapse", "high", "moderate", "low", "none", "unknown"],
    )
    model.towers = [
        {"id": f"T{i}", "risk_class": cls, "lat": None, "lon": None}
        for i, cls in enumerate(classes)
    ]
    return model


def test_run_answer_names_the_towers_to_inspect():
    model = run_model(["none", "high", "collapse", "low", "unknown"])
    lines = answer_lines(model, "en")
    assert (
        lines[0]
        == "2 of 5 towers need an inspection (class collapse or high): T2 (collapse), T1 (high)."
    )
    assert lines[1] == "1 tower could not be screened (no case solved): T4."
    assert answer_lines(run_model(["high", "none"]), "it")[0].startswith(
        "1 torre su 2 richiede un sopralluogo"
    )
    assert answer_lines(run_model(["none", "low"]), "en")[0].startswith("None of the 2 towers")
    assert dict(class_counts(model)) == {
        "collapse": 1,
        "high": 1,
        "moderate": 0,
        "low": 1,
        "none": 1,
        "unknown": 1,
    }


def test_the_answer_and_counts_open_the_page():
    page = render_html(run_model(["high", "none"]))
    body = page.split("<body>", 1)[1]
    assert body.index('id="answer"') < body.index('id="map-section"') < body.index('id="summary"')
    assert "1 of 2 towers needs an inspection" in body
    assert '<li data-class="high">' in body and "<details>" in body


def test_plural_forms():
    assert trn("ans_undefined", 1, "it", ids="A").startswith("1 torre non è stata valutata")
    assert trn("ans_undefined", 2, "it", ids="A, B").startswith("2 torri non sono state valutate")
    assert trn("ans_undefined", 2, "en", ids="A, B").startswith("2 towers could not")


def test_numbers_and_bounds():
    assert number(0.25399, "en", 3, "g", ">") == "> 0.254 g"
    assert number(0.25399, "it", 3, "g") == "0,254 g"
    assert number(float("nan"), "en") == "-" and number("inf", "en") == "∞"


def test_record_paths_are_shortened_with_the_full_path_on_hover():
    text, full = short_paths('["/a/b/XX.S1..HNE.mseed", "/a/b/XX.S1..HNN.mseed"]')
    assert text == "XX.S1..HNE.mseed, XX.S1..HNN.mseed"
    assert full == "/a/b/XX.S1..HNE.mseed\n/a/b/XX.S1..HNN.mseed"
    (item,) = header_items({"inventory_source": "/x/y/towers.csv"}, [("inventory_source", "h")])
    assert item.value == "towers.csv" and item.title == "/x/y/towers.csv"


def bound_rows() -> list[dict]:
    """An assess summary: one fitted tower below the code, one lower-bound tower that meets it."""
    common = {"soil_class": "A", "soil_class_source": "inventory", "note": ""}
    return [
        {
            **common,
            "id": "FIT",
            "lat_deg": 42.35,
            "lon_deg": 13.40,
            "fragility_median_g": 0.2,
            "fragility_beta": 0.4,
            "median_is_bound": "",
            "annual_rate_overturning_per_y": 3e-3,
            "p_overturning_50y": 0.14,
            "capacity_pga_g": 0.2,
            "capacity_return_period_y": 300.0,
            "safety_index": 0.42,
            "acceleration_factor": 0.7,
            "risk_class": "high",
        },
        {
            **common,
            "id": "LOW",
            "lat_deg": 42.36,
            "lon_deg": 13.41,
            "fragility_median_g": 0.254,
            "fragility_beta": float("nan"),
            "median_is_bound": "lower",
            "annual_rate_overturning_per_y": float("nan"),
            "p_overturning_50y": float("nan"),
            "capacity_pga_g": 0.254,
            "capacity_return_period_y": 2475.0,
            "safety_index": 3.48,
            "acceleration_factor": 1.5,
            "risk_class": "meets",
        },
    ]


def test_assess_bounds_are_shown_as_bounds():
    import json
    import re

    from rockscreen.pipeline.report.html.adapters.risk import risk_model

    stripes = [
        {"tower_id": "LOW", "ag_g": ag, "n_records": 3, "n_overturned": 0} for ag in (0.1, 0.254)
    ]
    model = risk_model("assess", {}, bound_rows(), stripes)
    low = model.towers[1]
    assert low["bounds"] == {
        key: ">"
        for key in (
            "fragility_median_g",
            "capacity_pga_g",
            "capacity_return_period_y",
            "safety_index",
            "acceleration_factor",
        )
    }
    assert "bounds" not in model.towers[0]
    lines = answer_lines(model, "en")
    assert (
        lines[0] == "1 of 2 towers does not meet the code (safety index I_S < 1): FIT (I_S 0.42)."
    )
    assert "lower bound" in lines[1] and "LOW" in lines[1]
    page = render_html(model)
    data = json.loads(
        re.search(r'<script id="report-data" type="application/json">(.*?)</script>', page, re.S)[1]
    )
    verdict = " ".join(data["sheets"]["LOW"]["verdict"])
    assert "β -" not in verdict and "probability -" not in verdict
    assert "up to 0.254 g" in verdict and "a_C > 0.254 g" in verdict and "I_S > 3.5" in verdict
    assert "I_S = 0.42" in " ".join(data["sheets"]["FIT"]["verdict"])
    (figure,) = data["sheets"]["LOW"]["figures"]
    assert figure["yrange"] == [0.0, 1.0]
    assert figure["curves"][0]["label"].startswith("median > 0.254 g (lower bound")
    italian = render_html(model, "it")
    assert "a_C \\u003e 0,254 g" in italian and "1 torre su 2 non soddisfa la norma" in italian


def test_run_search_stopped_at_the_vertical_limit_says_so(example_archive):
    from rockscreen.pipeline.archive.campaign import read_summary
    from rockscreen.pipeline.report.html import report_model

    stopped = {
        r["id"]: r
        for r in read_summary(example_archive)
        if r["safety_factor_limit"] != "overturning"
    }
    model = report_model(example_archive)
    page = render_html(model).split('<script id="report-data"')[0]
    for row in model.towers:
        if row["id"] not in stopped:
            assert "bounds" not in row
            continue
        summary = stopped[row["id"]]
        assert row["bounds"] == {"safety_factor": ">"}
        assert row["safety_factor"] == summary["safety_factor_lower"]
        key = "v_sf_vertical" if summary["safety_factor_limit"] == "vertical_limit" else "v_sf_cap"
        assert key in [line[0] for line in model.sheets[row["id"]].verdict]
    assert all("v_sf_inf" not in [line[0] for line in s.verdict] for s in model.sheets.values())
    assert "1 of 9 towers needs an inspection" in page


def test_map_extent_fits_the_towers_not_the_stations():
    from rockscreen.pipeline.report.html.model import tower_extent

    towers = [
        {"id": "A", "lat": 42.30, "lon": 13.30},
        {"id": "B", "lat": 42.40, "lon": 13.50},
        {"id": "C", "lat": None, "lon": None},
    ]
    x0, y0, x1, y1 = tower_extent(towers, [(11.0, 40.0), (16.0, 44.0)])
    assert x0 == pytest.approx(13.27) and x1 == pytest.approx(13.53)
    assert y0 == pytest.approx(42.285) and y1 == pytest.approx(42.415)
    one = tower_extent(towers[:1])
    assert one[2] - one[0] == pytest.approx(0.02 * 1.3)  # one tower: about 2 km around it
    assert tower_extent(towers[2:], [(11.0, 40.0), (16.0, 44.0)])[0] < 11.0  # no tower: stations
    assert tower_extent([]) is None


def test_italian_notes_models_and_numbers(example_archive):
    from rockscreen.pipeline.engine.registry import models
    from rockscreen.pipeline.report.html.i18n import STRINGS
    from rockscreen.pipeline.report.html.notes import translate_note

    for model in models():  # the registry's labels, translated
        assert STRINGS[f"model_{model.name}"]["en"] == model.label
    note = (
        "no record overturned the tower up to ag = 0.2601 g: the median is above it (lower "
        "bound); beta undetermined; assumed soil_class=A (default), nominal_life_y=50.0 "
        "(default); something new"
    )
    assert translate_note(note, "it") == (
        "nessun accelerogramma ha ribaltato la torre fino ad ag = 0,2601 g: la mediana è "
        "superiore (limite inferiore); beta non determinata; ipotizzati soil_class=A "
        "(predefinito), nominal_life_y=50,0 (predefinito); something new"
    )
    assert translate_note(note, "en") == note
    one = (
        "collapse fit: one record overturned the tower; SLV fit (theta_max/alpha >= 0.4): one "
        "record reached the SLV level"
    )
    assert translate_note(one, "it") == (
        "stima al collasso: un solo accelerogramma ha ribaltato la torre; stima allo SLV "
        "(theta_max/alpha >= 0,4): un solo accelerogramma ha raggiunto il livello SLV"
    )
    page = render_html(report_model_of(example_archive), "it")
    assert "blocco singolo" in page and "1 torre su 9 richiede un sopralluogo" in page


def report_model_of(path):
    from rockscreen.pipeline.report.html import report_model

    return report_model(path)


def assess_model(labels: list[str]) -> ReportModel:
    model = ReportModel(kind="assess", title="kind_assess", classes=RISK_ARCHIVE_CLASSES)
    model.towers = [
        {"id": f"T{i}", "risk_class": label, "lat": None, "lon": None}
        for i, label in enumerate(labels)
    ]
    return model


ROCKING_ONLY_MEETS = class_label(
    "meets",
    True,
    "rocking only: belfry not checked (no belfry columns in the inventory)",
    Completeness.ROCKING_ONLY,
)


def test_a_meets_on_rigid_overturning_alone_is_not_counted_or_told_as_meeting_the_code():
    # issue 22: towers whose only checks were the whole tower's rigid overturning
    model = assess_model([ROCKING_ONLY_MEETS, ROCKING_ONLY_MEETS, "meets"])
    lines = answer_lines(model, "en")
    assert not any("All" in line and "meet the code" in line for line in lines)
    assert lines[0] == "1 of 3 towers meets the code (safety index I_S ≥ 1)."
    assert lines[1].startswith("2 of 3 towers are not shown to meet the code")
    assert lines[1].endswith("wall_thickness_m and masonry_type): T0, T1.")
    # the rocking-only mark is no record-basis mark
    assert not any("not code-compliant" in line for line in lines)
    counts = dict(class_counts(model))
    assert counts["meets"] == 1 and counts[INCOMPLETE] == 2
    assert answer_lines(model, "it")[1].startswith("2 torri su 3 non risultano conformi")
    only = answer_lines(assess_model([ROCKING_ONLY_MEETS]), "en")
    assert only[0].startswith("1 of 1 towers is not shown to meet the code") and len(only) == 1


def test_only_a_noncompliant_basis_is_told_as_one():
    marked = class_label("meets", False, "")
    lines = answer_lines(assess_model([marked, "meets"]), "en")
    assert lines[0] == "All 2 assessed towers meet the code (safety index I_S ≥ 1)."
    assert lines[-1].startswith("The record basis of 1 tower is not code-compliant")


def test_the_new_code_check_notes_read_in_italian():
    from dataclasses import replace

    from rockscreen.pipeline.engine.models.gable import gable_block_note
    from rockscreen.pipeline.report.html.notes import translate_note
    from rockscreen.stations.inventory import example_inventory_path, read_inventory

    (gable,) = [t for t in read_inventory(example_inventory_path()) if t.id == "ARC-08"]
    for tower in (gable, replace(gable, gable_axis=None)):
        note = gable_block_note(tower)
        italian = note.render("it")
        assert italian.startswith("ribaltamento della vela campanaria: sul suo spessore 0,50 m")
        assert "rocking" not in italian
        # an archive without note codes: the adapter reads its English the same
        assert translate_note(note.render(), "it") == italian
    crushed = (
        "LV1: the shaft's own weight alone crushes its section at 0.0 m by the code's design "
        "strength (sigma_0 / (0.85 f_d) = 1.09, f_d = f_m / (gamma_M F_C), gamma_M = 2 of "
        "Circolare 2019 §C8.7.1, F_C = 1.35): the section has no flexural capacity left and the "
        "check fails at every return period. A tower that stands carries its weight, so its "
        "masonry is stronger than f_d: a measured f_m (knowledge level LC3, "
        "masonry_strength_mpa) would change this verdict"
    )
    assert translate_note(crushed, "it").startswith(
        "LV1: il solo peso proprio del fusto schiaccia la sua sezione a 0,0 m"
    )


def test_the_answer_reads_the_i_s_the_class_comes_from():
    # the class comes from the governing check's I_S, not whole-tower rocking's
    below = {
        "id": "G",
        "risk_class": "moderate",
        "safety_index": 0.87,
        "governing": "bell gable kinematic (non-linear)",
        "governing_safety_index": 0.64,
        "lat": None,
        "lon": None,
    }
    bound = {
        "id": "B",
        "risk_class": class_label("meets", True, "belfry not checked (no belfry columns)"),
        "safety_index": 36.1,
        "governing": "shaft flexure (LV1) (a lower bound: not shown to govern)",
        "governing_safety_index": 3.48,
        "bounds": {"safety_index": ">", "governing_safety_index": ">"},
        "lat": None,
        "lon": None,
    }
    model = assess_model([])
    model.towers = [below, bound]
    lines = answer_lines(model, "en")
    assert lines[0] == "1 of 2 towers does not meet the code (safety index I_S < 1): G (I_S 0.64)."
    assert lines[1].startswith("For 1 of them (B) I_S is only a lower bound: the check that")
    # a marked meets shows what was not checked, so two 'meets' never read alike
    assert (
        class_text(bound["risk_class"], "en")
        == "meets the code (belfry not checked (no belfry columns))"
    )
    rocking = {
        **bound,
        "governing": "whole-tower rocking",
        "governing_check": "tower.rocking",
        "id": "R",
    }
    model.towers = [rocking]
    assert "no record brought" in answer_lines(model, "en")[1]


def test_the_lv1_model_clause_and_its_bound_read_in_italian():
    from rockscreen.pipeline.report.html.notes import translate_note

    note = (
        "LV1 tower model (DPCM 9/2/2011 §5.4.4, formulas to be verified): T1 = 0.34 s (0.0187 H "
        "of the whole tower, assumed), q = 3, gamma_M = 2, rubble, f_m = 1 MPa (Table C8.5.I, "
        "LC1: the range's lower end), prismatic shaft, walls 0.60 m, critical section at 0.0 m; "
        "LV1: the check fails at 30 y, the shortest tabulated return period: T_R,C, a_C, I_S and "
        "f_a are upper bounds"
    )
    italian = translate_note(note, "it")
    assert "(0,0187 H dell'intera torre, ipotizzato)" in italian
    assert "LV1: la verifica non è soddisfatta già a 30 anni" in italian
    assert "assumed" not in italian and "upper bounds" not in italian
