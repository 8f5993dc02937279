"""The HTML report in a real browser (headless Chromium): renders, sorts, opens sheets."""

from __future__ import annotations

import re

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
    # ARC-03's belfry (0.9 m piers on the shaft's amplified motion) rocks: theta/alpha 0.108
    assert ids[:3] == ["ARC-08", "ARC-01", "ARC-03"]

    browser.find_element(By.CSS_SELECTOR, "#map circle.tower[data-id='ARC-08']").click()
    assert "ARC-08" in browser.find_element(By.ID, "sheet-title").text
    sheet = browser.find_element(By.ID, "sheet")
    assert sheet.is_displayed()
    assert len(sheet.find_elements(By.CSS_SELECTOR, "svg.chart polyline")) >= 3  # θ/α and motions
    # the gable model governs ARC-08 and overturns it (issue 22's example gable)
    assert "bell gable rocking" in sheet.find_element(By.CSS_SELECTOR, ".verdict").text

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


def test_assess_sheet_shows_the_checks_side_by_side(browser, risk_reports, artifacts):
    """The tower sheet of assess: rocking, belfry, kinematic and LV1 checks in one table."""
    from selenium.webdriver.common.by import By

    browser.get((risk_reports / "assess.html").as_uri())
    assert browser.execute_script("return document.documentElement.dataset.ready") == "1"
    seen = {}
    for tower in ("ARC-03", "ARC-08"):
        browser.find_element(By.CSS_SELECTOR, f'#towers tbody tr[data-id="{tower}"]').click()
        sheet = browser.find_element(By.ID, "sheet")
        assert "Side by side: rocking and the code's checks" in sheet.text
        table = sheet.find_element(By.CSS_SELECTOR, "table.checks")
        heads = [th.text for th in table.find_elements(By.CSS_SELECTOR, "thead th")]
        assert heads == ["Check", "a_C (ag on rock)", "I_S", "Details"]
        rows = {
            tr.find_element(By.TAG_NAME, "th").text: [
                td.text for td in tr.find_elements(By.TAG_NAME, "td")
            ]
            for tr in table.find_elements(By.CSS_SELECTOR, "tbody tr")
        }
        texts = [p.text for p in sheet.find_elements(By.CSS_SELECTOR, "p.checks-text")]
        assert texts[0].startswith("Governing: ")
        seen[tower] = (rows, texts)
    rows, _ = seen["ARC-03"]  # the tower with a belfry and the shaft's data
    assert rows["Whole-tower rocking (IDA)"][0].endswith("g")
    assert "fragility median" in rows["Belfry rocking on the shaft (IDA)"][2]
    assert {"Kinematic, linear: belfry", "Kinematic, non-linear: belfry"} <= set(rows)
    assert rows["LV1 tower model"][2].startswith("shaft flexure, T1")
    rows, texts = seen["ARC-08"]  # the bell gable on the facade
    assert {"Kinematic, linear: bell gable", "Kinematic, non-linear: bell gable"} <= set(rows)
    assert "fragility median" in rows["Bell gable rocking on its base (IDA)"][2]
    assert "LV1 not made (no wall_thickness_m and masonry_type" in rows["LV1 tower model"][2]
    assert any(t.startswith("Not made: ") for t in texts)  # the belfry and LV1 (no data)
    assert severe(browser) == []
    browser.save_screenshot(str(artifacts / "report-assess-checks.png"))


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
    # ARC-08's bell gable overturns ("collapse"); ARC-03 is "low" from its belfry's rocking
    assert "collapse 1" in counts.text and "high 0" in counts.text
    assert "low 3" in counts.text and "none 5" in counts.text
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


@pytest.fixture(scope="module")
def twelve_towers(tmp_path_factory):
    """The twelve-tower example (``examples/tower_population``, geometry only) assessed with
    its screening risk, then its report in English and in Italian."""
    from pathlib import Path

    towers = Path(__file__).parents[2] / "examples" / "tower_population" / "towers_geometry.csv"
    return run_commands(
        tmp_path_factory.mktemp("twelve"),
        f"assess --towers {towers} --out twelve.h5 --jobs 1",
        "report twelve.h5 --out twelve.html",
        "report twelve.h5 --out twelve-it.html --lang it",
    )


@pytest.mark.parametrize(
    ("page", "risk", "code", "masonry"),
    [
        ("twelve.html", "Screening risk (best estimate)", "The code's verdict", "masonry"),
        ("twelve-it.html", "Rischio di screening (stima migliore)", "Esito di norma", "muratura"),
    ],
)
def test_twelve_towers_show_the_ranked_list_first_with_the_code_beside(
    browser, twelve_towers, artifacts, page, risk, code, masonry
):
    """The first screen at 1400 x 900 is the ranked list: twelve towers by rank, each with
    its P50 and 90 % interval, the code's class and governing check beside under their own
    heading; below it what to survey first, naming the tower a masonry survey moves most;
    a row opens the tower's sheet with the risk, the sensitivity bars and the band."""
    from selenium.webdriver.common.by import By

    browser.set_window_size(1400, 900)
    browser.get((twelve_towers / page).as_uri())
    assert browser.execute_script("return document.documentElement.dataset.ready") == "1"
    sections = browser.execute_script(
        "return Array.from(document.querySelectorAll('body > section')).map(s => s.id)"
    )
    assert sections[0] == "risk"  # the ranked list first, the code's answer after it
    table = browser.find_element(By.ID, "risk-list")
    assert table.location["y"] < 900  # on the first screen
    groups = [th.text for th in table.find_elements(By.CSS_SELECTOR, "thead th.group")]
    assert groups == [risk, code]
    rows = table.find_elements(By.CSS_SELECTOR, "tbody tr")
    assert len(rows) == 12
    ranks = [int(r.find_element(By.CSS_SELECTOR, "td").text) for r in rows]
    assert ranks == sorted(ranks) and ranks[0] == 1
    first = rows[0].find_elements(By.TAG_NAME, "td")
    assert first[-2].text and first[-1].text  # the code's class and its governing check
    assert rows[0].find_elements(By.CSS_SELECTOR, "svg.whisker")  # the interval drawn
    survey = browser.find_element(By.ID, "survey-first")
    assert masonry in survey.find_element(By.CSS_SELECTOR, "p.masonry").text
    if page == "twelve-it.html":
        text = browser.find_element(By.ID, "risk").text
        assert not re.search(r"\d\.\d", text), text  # decimal commas
        for english in ("uncertain", "Survey first", "Governing mechanism", "judgement"):
            assert english not in text
    name = page.removesuffix(".html")
    browser.save_screenshot(str(artifacts / f"report-ranked-{name}.png"))  # the first screen
    rows[0].click()
    sheet = browser.find_element(By.ID, "sheet")
    assert sheet.is_displayed()
    assert sheet.find_elements(By.CSS_SELECTOR, ".verdict.risk p")
    assert sheet.find_elements(By.CSS_SELECTOR, "table.sens tbody tr")
    assert sheet.find_elements(By.CSS_SELECTOR, "table.checks")  # the code's checks beside
    assert severe(browser) == []
    browser.execute_script("document.querySelector('#sheet table.sens').scrollIntoView()")
    browser.save_screenshot(str(artifacts / f"report-ranked-{name}-sheet.png"))


def test_assess_example_shows_the_ranked_list_first(browser, risk_reports, artifacts):
    """``assess --example``: the ranked list opens the page, the located towers ranked, the
    unlocated one named without a risk, the code's verdict beside each row."""
    from selenium.webdriver.common.by import By

    browser.set_window_size(1400, 900)
    browser.get((risk_reports / "assess.html").as_uri())
    assert browser.execute_script("return document.documentElement.dataset.ready") == "1"
    sections = browser.execute_script(
        "return Array.from(document.querySelectorAll('body > section')).map(s => s.id)"
    )
    assert sections[:2] == ["risk", "answer"]
    rows = browser.find_elements(By.CSS_SELECTOR, "#risk-list tbody tr")
    towers = browser.execute_script("return RS.data.towers.length")
    assert 0 < len(rows) <= towers
    assert all(r.find_elements(By.CSS_SELECTOR, "td.code .cls") for r in rows)
    assert browser.find_element(By.ID, "survey-first").is_displayed()
    assert severe(browser) == []
    browser.save_screenshot(str(artifacts / "report-assess-example-ranked.png"))
