"""The report's first screen: the answer sentences, class counts, bounds, map extent, Italian."""

from __future__ import annotations

from rockscreen.pipeline.report.html import render_html
from rockscreen.pipeline.report.html.adapters.common import header_items, short_paths
from rockscreen.pipeline.report.html.answer import answer_lines, class_counts
from rockscreen.pipeline.report.html.i18n import number, trn
from rockscreen.pipeline.report.html.model import ReportModel


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
