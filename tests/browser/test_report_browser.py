"""The HTML report in a real browser (headless Chromium): renders, sorts, opens sheets."""

from __future__ import annotations

import pytest
from click.testing import CliRunner

from rockscreen.pipeline.cli import main

pytestmark = pytest.mark.browser


def run_commands(folder, *command_lines):
    """Run ``rockscreen`` command lines in ``folder`` (the examples write to the working folder)."""
    runner = CliRunner()
    with pytest.MonkeyPatch.context() as patch:
        patch.chdir(folder)
        for line in command_lines:
            result = runner.invoke(main, line.split())
            assert result.exit_code == 0, (line, result.output)
    return folder


@pytest.fixture(scope="module")
def example_report(tmp_path_factory):
    """``rockscreen run --example`` then ``rockscreen report`` in a temporary folder."""
    folder = run_commands(
        tmp_path_factory.mktemp("report"),
        "run --example --jobs 1",
        "report rockscreen-example.h5 --out report.html",
    )
    return folder / "report.html"


def severe(driver) -> list[str]:
    return [entry["message"] for entry in driver.get_log("browser") if entry["level"] == "SEVERE"]


def test_report_renders_sorts_and_opens_a_sheet(browser, example_report, artifacts):
    from selenium.webdriver.common.by import By

    browser.get(example_report.as_uri())
    assert browser.execute_script("return document.documentElement.dataset.ready") == "1"
    assert severe(browser) == []
    rows = browser.find_elements(By.CSS_SELECTOR, "#towers tbody tr")
    assert len(rows) == 9
    assert len(browser.find_elements(By.CSS_SELECTOR, "#map circle.tower")) == 8  # ARC-07 unplaced

    header = browser.find_element(By.CSS_SELECTOR, "#towers th[data-key='theta_max_over_alpha']")
    header.click()
    header.click()  # descending
    assert header.get_attribute("aria-sort") == "descending"
    ids = [
        r.get_attribute("data-id")
        for r in browser.find_elements(By.CSS_SELECTOR, "#towers tbody tr")
    ]
    assert ids[:3] == ["ARC-08", "ARC-01", "ARC-04"]

    browser.find_element(By.CSS_SELECTOR, "#map circle.tower[data-id='ARC-08']").click()
    assert "ARC-08" in browser.find_element(By.ID, "sheet-title").text
    sheet = browser.find_element(By.ID, "sheet")
    assert sheet.is_displayed()
    assert len(sheet.find_elements(By.CSS_SELECTOR, "svg.chart polyline")) >= 3  # θ/α and motions
    assert "0.68" in sheet.find_element(By.CSS_SELECTOR, ".verdict").text

    browser.find_element(By.CSS_SELECTOR, "#towers tbody tr[data-id='ARC-04']").click()
    assert "ARC-04" in browser.find_element(By.ID, "sheet-title").text
    assert severe(browser) == []
    browser.save_screenshot(str(artifacts / "report-sheet.png"))
    browser.execute_script("window.scrollTo(0, 0)")
    browser.save_screenshot(str(artifacts / "report.png"))
    assert (artifacts / "report.png").stat().st_size > 10_000


def test_filter_and_csv_neutralise_formulas(browser, example_report):
    from selenium.webdriver.common.by import By

    browser.get(example_report.as_uri())
    box = browser.find_element(By.ID, "filter")
    box.send_keys("ARC-0")
    assert len(browser.find_elements(By.CSS_SELECTOR, "#towers tbody tr")) == 8
    csv = browser.execute_script("return RS.csv()")
    lines = csv.strip().split("\r\n")
    assert len(lines) == 9 and lines[0].startswith("Tower,")
    cells = browser.execute_script(
        "return ['=1+1', '+x', '-2', '@a', '\\tb', 'a,b', 'ok'].map(RS.csvCell)"
    )
    assert cells == ["'=1+1", "'+x", "'-2", "'@a", "'\tb", '"a,b"', "ok"]
    assert severe(browser) == []


def test_load_time_of_a_large_report(browser, tmp_path):
    """1,000 synthetic towers: the page opens and the table fills (no timing asserted)."""
    import importlib.util
    from pathlib import Path

    from selenium.webdriver.common.by import By

    from rockscreen.pipeline.report.html import render_html

    spec = importlib.util.spec_from_file_location(
        "report_tests", Path(__file__).parents[1] / "pipeline" / "report" / "test_html_report.py"
    )
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    page = tmp_path / "big.html"
    page.write_text(render_html(module.synthetic_model(1000, hostile=True)), encoding="utf-8")
    browser.get(page.as_uri())
    assert len(browser.find_elements(By.CSS_SELECTOR, "#towers tbody tr")) == 1000
    first = browser.find_element(By.CSS_SELECTOR, "#towers tbody tr td").text
    assert first.startswith('<script>alert("x")</script>')  # shown as text, never run
    assert severe(browser) == []


@pytest.fixture(scope="module")
def risk_reports(tmp_path_factory):
    """``assess --example`` (three stripes) and ``scenario --example``, then their reports."""
    return run_commands(
        tmp_path_factory.mktemp("risk-report"),
        "assess --example --return-periods 101,475,2475 --records 3 --jobs 1 --allow-noncompliant",
        "scenario --example",
        "report rockscreen-assess-example.h5 --out assess.html",
        "report rockscreen-scenario-example.h5 --out scenario.html",
    )


@pytest.mark.parametrize("page", ["assess.html", "scenario.html"])
def test_assess_and_scenario_reports_work_in_the_browser(browser, risk_reports, artifacts, page):
    from selenium.webdriver.common.by import By

    browser.get((risk_reports / page).as_uri())
    assert browser.execute_script("return document.documentElement.dataset.ready") == "1"
    assert severe(browser) == []
    rows = browser.find_elements(By.CSS_SELECTOR, "#towers tbody tr")
    assert len(rows) == 9
    first = rows[0].get_attribute("data-id")
    rows[0].click()  # the table re-renders with the row selected
    sheet = browser.find_element(By.ID, "sheet")
    assert sheet.is_displayed()
    assert first in browser.find_element(By.ID, "sheet-title").text
    assert severe(browser) == []
    browser.save_screenshot(str(artifacts / f"report-{page}.png"))


def test_first_screen_holds_the_answer_and_the_class_counts(browser, example_report, artifacts):
    """At 1400 x 900 the reader sees the answer sentence and the towers per class at once."""
    from selenium.webdriver.common.by import By

    browser.set_window_size(1400, 900)
    browser.get(example_report.as_uri())
    assert browser.execute_script("return document.documentElement.dataset.ready") == "1"
    height = browser.execute_script("return window.innerHeight")
    answer = browser.find_element(By.CSS_SELECTOR, "#answer .answer")
    assert "1 of 9 towers needs an inspection" in answer.text and "ARC-08" in answer.text
    counts = browser.find_element(By.ID, "counts")
    assert "high 1" in counts.text and "none 6" in counts.text
    for node in (answer, counts):
        assert node.rect["y"] + node.rect["height"] <= height, node.rect
    details = browser.find_element(By.CSS_SELECTOR, "#summary details")
    assert details.get_attribute("open") is None  # "What was computed" collapsed, below
    labels = browser.find_elements(By.CSS_SELECTOR, "#map text.tower-label")
    assert {label.text for label in labels} >= {"ARC-08"}
    assert severe(browser) == []
    browser.save_screenshot(str(artifacts / "report-first-screen.png"))


def _spread_report(folder, lat0=40.80, lon0=14.15, spacing_km=5.0):
    """A run report of 16 towers ``spacing_km`` apart near Naples, stations 200 km away."""
    import math

    from rockscreen.pipeline.report.html.model import Column, ReportModel
    from rockscreen.pipeline.report.html.render import render_html

    dlat = spacing_km / 111.2
    dlon = spacing_km / (111.2 * math.cos(math.radians(lat0)))
    classes = ("high", "moderate", "low", "none")
    towers = [
        {
            "id": f"CAMPANIA-{4 * i + j:02d}",
            "lat": lat0 + i * dlat,
            "lon": lon0 + j * dlon,
            "risk_class": classes[(i + j) % 4],
        }
        for i in range(4)
        for j in range(4)
    ]
    model = ReportModel(
        kind="run",
        title="16 towers",
        columns=[Column("id", "Tower", kind="text"), Column("risk_class", "class", kind="class")],
        towers=towers,
        stations=[
            {"key": "IV.FAR1", "lat": 42.35, "lon": 13.40},
            {"key": "IV.FAR2", "lat": 39.20, "lon": 16.20},
        ],
    )
    path = folder / "spread.html"
    path.write_text(render_html(model, generated="2026-01-01T00:00:00Z"), encoding="utf-8")
    return path, towers


def test_map_labels_every_tower_without_overlaps_and_draws_the_coast(browser, tmp_path, artifacts):
    """Towers 5 km apart, stations 200 km away: the first view holds every tower, each
    labelled, no two labels overlapping (their DOM boxes), and the coastline drawn."""
    from selenium.webdriver.common.by import By

    path, towers = _spread_report(tmp_path)
    browser.set_window_size(1400, 900)
    browser.get(path.as_uri())
    assert browser.execute_script("return document.documentElement.dataset.ready") == "1"
    svg = browser.find_element(By.CSS_SELECTOR, "#map svg").rect
    markers = browser.find_elements(By.CSS_SELECTOR, "#map circle.tower")
    assert len(markers) == len(towers)
    for marker in markers:  # the initial view contains every tower
        r = marker.rect
        assert svg["x"] <= r["x"] and r["x"] + r["width"] <= svg["x"] + svg["width"], r
        assert svg["y"] <= r["y"] and r["y"] + r["height"] <= svg["y"] + svg["height"], r
    boxes = browser.execute_script(
        "return Array.from(document.querySelectorAll('#map text.tower-label,"
        " #map text.station-label')).map("
        "function (t) { var b = t.getBoundingClientRect();"
        " return [t.textContent, b.left, b.top, b.right, b.bottom]; });"
    )
    assert {t["id"] for t in towers} <= {b[0] for b in boxes}
    for i, a in enumerate(boxes):
        for b in boxes[i + 1 :]:
            assert not (a[1] < b[3] and b[1] < a[3] and a[2] < b[4] and b[2] < a[4]), (a, b)
    coast = browser.find_elements(By.CSS_SELECTOR, "#map g.basemap polyline")
    assert coast, "no coastline on a map of the Gulf of Naples"
    assert "Natural Earth" in browser.find_element(By.CSS_SELECTOR, "#map .attribution").text
    assert severe(browser) == []
    browser.save_screenshot(str(artifacts / "report-map-16-towers.png"))


@pytest.mark.slow
def test_first_screen_on_sixteen_real_towers_around_laquila(
    browser, shared_data, tmp_path, artifacts
):
    """16 towers around L'Aquila with the shared records: counts and the towers needing
    action on the first screen (1400 x 900); no absolute path outside the provenance."""
    import math

    from selenium.webdriver.common.by import By

    folder = shared_data / "laquila2009"
    centres = {
        "AQV": (42.37722, 13.34389),
        "GSA": (42.42069, 13.51936),
        "AVZ": (42.02746, 13.42593),
        "AQG": (42.37347, 13.33703),
    }
    rows = ["id,lat,lon,width_m,height_m,azimuth_deg"]
    for name, (lat, lon) in centres.items():
        for k, (width, height) in enumerate(((0.4, 3.0), (0.6, 4.0), (1.0, 6.0), (3.0, 12.0))):
            a = 2 * math.pi * k / 4
            where = f"{lat + 0.01 * math.cos(a):.5f},{lon + 0.013 * math.sin(a):.5f}"
            rows.append(f"AQ-{name}{k},{where},{width},{height},{20 * k}")
    (tmp_path / "towers.csv").write_text("\n".join(rows) + "\n", encoding="utf-8")
    records = " ".join(str(p) for p in sorted(folder.glob("*.mseed")))
    run_commands(
        tmp_path,
        f"run {records} --stations {folder / 'stations.xml'} --jobs 2",
        "report rockscreen.h5 --out aq.html",
    )
    browser.set_window_size(1400, 900)
    browser.get((tmp_path / "aq.html").as_uri())
    assert browser.execute_script("return document.documentElement.dataset.ready") == "1"
    height = browser.execute_script("return window.innerHeight")
    answer = browser.find_element(By.CSS_SELECTOR, "#answer .answer")
    counts = browser.find_element(By.ID, "counts")
    for node in (answer, counts):
        assert node.is_displayed() and node.rect["y"] + node.rect["height"] <= height, node.rect
    assert "16 towers" in answer.text
    named = [row["id"] for row in browser.execute_script("return RS.data.towers")
             if row.get("risk_class") in ("collapse", "high")]  # fmt: skip
    assert named and all(name in answer.text for name in named), (named, answer.text)
    assert sum(int(n) for n in counts.text.split() if n.isdigit()) == 16
    # absolute paths only inside the collapsed provenance ("What was computed")
    outside = browser.execute_script(
        "var c = document.body.cloneNode(true);"
        "c.querySelectorAll('#summary details, script').forEach(function (n) { n.remove(); });"
        "return c.textContent;"
    )
    assert str(tmp_path) not in outside and str(folder) not in outside
    labels = browser.execute_script(
        "return Array.from(document.querySelectorAll('#map text.tower-label,"
        " #map text.station-label')).map(function (t) { var b = t.getBoundingClientRect();"
        " return [b.left, b.top, b.right, b.bottom]; });"
    )
    for i, a in enumerate(labels):
        for b in labels[i + 1 :]:
            assert not (a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]), (a, b)
    assert severe(browser) == []
    browser.save_screenshot(str(artifacts / "report-laquila-16-first-screen.png"))


@pytest.fixture(scope="module")
def italian_reports(risk_reports, example_report):
    """The run, assess and scenario reports again, in Italian."""
    folder = run_commands(
        risk_reports,
        "report rockscreen-assess-example.h5 --out assess-it.html --lang it",
        "report rockscreen-scenario-example.h5 --out scenario-it.html --lang it",
    )
    run_commands(example_report.parent, "report rockscreen-example.h5 --out run-it.html --lang it")
    return [
        folder / "assess-it.html",
        folder / "scenario-it.html",
        example_report.parent / "run-it.html",
    ]


def _english_sentences():
    """Every English text of the catalogue that is a phrase (three words or more) and is
    not also the Italian text, split at its {fields}."""
    import re

    from rockscreen.pipeline.report.html.i18n import STRINGS

    out = set()
    for entry in STRINGS.values():
        english, italian = entry["en"], entry.get("it", "")
        if english == italian:
            continue
        for piece in re.split(r"\{[^}]*\}", english):
            piece = piece.strip(" .,:;()")
            if len(piece.split()) >= 3 and piece not in italian:
                out.add(piece)
    return sorted(out)


def test_italian_pages_hold_no_english_sentence_and_use_decimal_commas(
    browser, italian_reports, artifacts
):
    """Every Italian page, with a tower's sheet open: no phrase of the English catalogue in
    the visible text, and numbers with decimal commas in the towers table."""
    import re

    from selenium.webdriver.common.by import By

    english = _english_sentences()
    assert len(english) > 50  # the catalogue is read
    for path in italian_reports:
        browser.set_window_size(1400, 900)
        browser.get(path.as_uri())
        assert browser.execute_script("return document.documentElement.dataset.ready") == "1"
        browser.find_elements(By.CSS_SELECTOR, "#towers tbody tr")[0].click()
        for details in browser.find_elements(By.CSS_SELECTOR, "details"):
            browser.execute_script("arguments[0].open = true", details)
        text = browser.execute_script("return document.body.innerText")
        found = [sentence for sentence in english if sentence in text]
        assert found == [], (path.name, found[:10])
        cells = [c.text for c in browser.find_elements(By.CSS_SELECTOR, "#towers tbody td")]
        decimal_points = [c for c in cells if re.fullmatch(r"[<>≥≤]?\s*-?\d+\.\d+(\s*\S+)?", c)]
        assert decimal_points == [], (path.name, decimal_points[:10])
        assert any(re.search(r"\d,\d", c) for c in cells), path.name
        assert severe(browser) == []
        browser.save_screenshot(str(artifacts / f"report-italian-{path.stem}.png"))


def test_a_bound_towers_sheet_says_at_least(browser, risk_reports, artifacts):
    """The sheet of a tower whose fragility is only a lower bound: every bounded value is
    written with its relation, the bound sentence is there, and the chart's probability
    axis is 0-1 with the bound drawn as a line."""
    from selenium.webdriver.common.by import By

    browser.set_window_size(1400, 900)
    browser.get((risk_reports / "assess.html").as_uri())
    towers = browser.execute_script("return RS.data.towers")
    bound = next(t for t in towers if (t.get("bounds") or {}).get("safety_index") == ">")
    browser.execute_script("RS.openSheet(arguments[0])", bound["id"])
    sheet = browser.find_element(By.ID, "sheet")
    assert sheet.is_displayed()
    text = sheet.text
    assert "lower bound" in text and "at least" in text
    assert "I_S >" in text or "I_S ≥" in text, text
    row = browser.find_element(By.CSS_SELECTOR, f'#towers tbody tr[data-id="{bound["id"]}"]')
    assert ">" in row.text or "≥" in row.text
    assert severe(browser) == []
    browser.execute_script("arguments[0].scrollIntoView()", sheet)
    browser.save_screenshot(str(artifacts / "report-sheet-bound-tower.png"))
