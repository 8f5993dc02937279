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
    assert any(t.startswith("Where they disagree: ") for t in texts)
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
