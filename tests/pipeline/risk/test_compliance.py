"""Issue 20: record sets that fail NTC 2018 §3.2.3.6 are refused or marked; lambda_C's
share from the extrapolated hazard curve is measured and flagged."""

from __future__ import annotations

import json
import math
import re
from functools import partial

import numpy as np
import pytest
from click.testing import CliRunner
from scipy.special import ndtr

from rockscreen.pipeline.cli import main
from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.execution.local import SerialExecutor
from rockscreen.pipeline.report.export import summary_csv_text, summary_geojson_text
from rockscreen.pipeline.report.html.adapters.risk import risk_archive_model
from rockscreen.pipeline.report.risk_summary import assess_lines, tower_json
from rockscreen.pipeline.risk.assess.batch import AssessInputs, assess_to_archive
from rockscreen.pipeline.risk.assess.compliance import set_compliance
from rockscreen.pipeline.risk.assess.run import AssessOptions, run_assess
from rockscreen.pipeline.risk.measures.classes import (
    NONCOMPLIANT_MARK,
    base_class,
    class_label,
    row_class_label,
)
from rockscreen.pipeline.risk.measures.hazard_integral import (
    HazardCurve,
    extrapolated_shares,
)
from rockscreen.pipeline.verdict.scales import Completeness
from rockscreen.stations.inventory import Tower

from rockscreen_testsupport.records import suite_record

CERVINO = (41.04, 14.42)  # lat, lon [deg]


_record = partial(
    suite_record,
    seed_base=100,
    n_samples=1000,
    frequency_hz=(2.0, 0.4),
    envelope_duration_s=6.0,
    name="R-{i}",
)


#: Four records where NTC 2018 §7.3.5 wants seven.
SHORT_SUITE = [_record(i) for i in range(4)]
#: A squat tower: never overturns, so its class is ``meets``.
STURDY = Tower(id="STURDY", width_m=4.0, height_m=6.0, lat=CERVINO[0], lon=CERVINO[1])


def test_class_label_is_the_one_place_a_class_becomes_text():
    assert class_label("meets") == "meets"
    marked = class_label("meets", basis_compliant=False)
    assert marked == f"meets ({NONCOMPLIANT_MARK})" and base_class(marked) == "meets"
    assert row_class_label({"risk_class": "high", "basis_compliant": False}).startswith("high (")
    assert row_class_label({"risk_class": "low"}) == "low"  # scenario rows: no basis column


def test_a_suite_failing_the_count_is_refused_with_the_numbers():
    options = AssessOptions(return_periods_y=(475.0,), selection={"n_records": 7})
    with pytest.raises(RiskError) as caught:
        run_assess([STURDY], options, SerialExecutor(), suite=SHORT_SUITE)
    message = str(caught.value)
    assert "TR=475 y" in message and "lon=14.42 lat=41.04" in message
    assert "4 records (7 required, NTC 2018 §7.3.5)" in message
    assert re.search(r"mean/target \d\.\d\d-\d\.\d\d", message)
    assert "§3.2.3.6" in message and "--allow-noncompliant" in message
    assert "--scale-limits" in message and "No tower was solved" in message


def test_set_compliance_measures_count_ratios_and_capped_factors():
    from types import SimpleNamespace

    good = SimpleNamespace(
        records=(None,) * 7,
        scale_factors=np.ones(7),
        periods_s=np.array([0.15, 2.0]),
        ratio_min=0.95,
        ratio_max=1.2,
    )
    assert set_compliance(good).compliant and set_compliance(good).reason == ""
    weak = SimpleNamespace(
        records=(None,) * 7,
        scale_factors=np.full(7, 4.0),
        periods_s=np.array([0.15, 2.0]),
        ratio_min=0.2,
        ratio_max=0.4,
    )
    result = set_compliance(weak)
    assert not result.compliant and result.n_capped == 7
    assert "0.20-0.40" in result.reason and "7 of 7 scale factors at the limits" in result.reason


def test_allow_noncompliant_marks_every_output(tmp_path):
    options = AssessOptions(
        return_periods_y=(101.0, 475.0, 2475.0),
        selection={"n_records": 7},
        allow_noncompliant=True,
    )
    out = tmp_path / "a.h5"
    notes = []
    result = assess_to_archive(
        [STURDY],
        options,
        out,
        AssessInputs(inventory=tmp_path / "towers.csv", suite=SHORT_SUITE, suite_label="test"),
        jobs=1,
        notify=notes.append,
    )
    (row,) = result.summary
    assert row["risk_class"] == "meets" and row["basis_compliant"] is False
    assert NONCOMPLIANT_MARK in row["note"] and "4 records (7 required" in row["note"]
    assert any("warning (--allow-noncompliant)" in n for n in notes)
    # issue 22: the checks not made (LV1, the belfry) follow the non-compliance mark
    rocking_only = Completeness.ROCKING_ONLY
    marked = class_label("meets", False, row["checks_not_made"], rocking_only)
    assert marked.startswith(f"incomplete ({NONCOMPLIANT_MARK}) (rocking only: ")
    table = assess_lines(result.summary)
    assert marked in table[1]
    # the exports: the class is one word of its scale, each mark its own column
    plain = {"risk_class": "meets", "completeness": "rocking_only", "basis_compliant": False}
    assert {k: tower_json(row)[k] for k in plain} == plain
    csv_rows = summary_csv_text(result.summary).splitlines()
    header = csv_rows[0].split(",")
    cells = csv_rows[1].split(",")
    assert [cells[header.index(k)] for k in plain] == ["meets", "rocking_only", "false"]
    assert "basis_compliant" in header
    geojson, _ = summary_geojson_text(result.summary)
    props = json.loads(geojson)["features"][0]["properties"]
    assert {k: props[k] for k in plain} == plain
    model = risk_archive_model(out, "assess")
    assert model.towers[0]["risk_class"] == marked
    verdict = model.sheets["STURDY"].verdict
    assert ("v_noncompliant", {}) in verdict
    assert {"key": f"class_{marked}", "raw": marked} in [v.get("cls") for _, v in verdict]
    runner = CliRunner()
    inspected = runner.invoke(main, ["inspect", "--json", str(out)])
    assert inspected.exit_code == 0, inspected.output
    inspected_tower = json.loads(inspected.stdout)["towers"][0]
    assert {k: inspected_tower[k] for k in plain} == plain
    assert json.loads(inspected.stdout)["metadata"]["allow_noncompliant"] in (True, 1)
    exported = runner.invoke(main, ["export", str(out), "--csv", str(tmp_path / "a.csv")])
    assert exported.exit_code == 0, exported.output
    text = (tmp_path / "a.csv").read_text()
    assert ",meets," in text and ",rocking_only," in text and marked not in text


def test_laquila_suite_is_refused_with_the_ratios(shared_data, tmp_path):
    folder = shared_data / "laquila2009"
    if not (folder / "stations.xml").is_file():
        pytest.skip(f"{folder} is absent")
    args = ["assess", "--example", "--suite", str(folder), "--return-periods", "475"]
    result = CliRunner().invoke(main, [*args, "--jobs", "1", "--out", str(tmp_path / "a.h5")])
    assert result.exit_code == 1
    assert "4 records (7 required" in result.stderr
    assert re.search(r"mean/target \d\.\d\d-\d\.\d\d over 0\.15-2 s", result.stderr)
    assert "--allow-noncompliant" in result.stderr
    assert not (tmp_path / "a.h5").exists()


# ----------------------------------------------------------------- hazard extrapolation


def _share_above(k0: float, k: float, median: float, beta: float, a_u: float) -> float:
    """Closed form of int_{a > a_u} lambda(a) dP(C | a) / lambda_C for lambda = k0 a^-k:
    k0 exp(-k mu + k^2 beta^2 / 2) Phi((mu - k beta^2 - ln a_u) / beta) over Cornell's
    lambda_C = k0 exp(-k mu + k^2 beta^2 / 2)."""
    mu = math.log(median)
    return float(ndtr((mu - k * beta * beta - math.log(a_u)) / beta))


@pytest.mark.parametrize(("median", "beta"), [(0.3, 0.4), (0.6, 0.3), (0.1, 0.5), (0.03, 0.3)])
def test_extrapolated_shares_match_the_closed_form(median, beta):
    k0, k = 1e-4, 2.5
    a = np.array([0.05, 0.4])  # two points: one power law, extrapolated on both sides
    curve = HazardCurve(a, k0 * a**-k)
    above, below = extrapolated_shares(curve, median, beta)
    assert above == pytest.approx(_share_above(k0, k, median, beta, 0.4), abs=1e-5)
    assert below == pytest.approx(1 - _share_above(k0, k, median, beta, 0.05), abs=1e-5)


def test_assessed_tower_carries_the_shares_and_the_flag():
    from rockscreen.pipeline.hazard import hazard_curve
    from rockscreen.pipeline.risk.assess.sites import tower_sites
    from rockscreen.pipeline.risk.assess.tower_summary import summarize_tower

    (site,) = tower_sites([STURDY], 0.01)
    periods, ag = hazard_curve(site.lon_deg, site.lat_deg)
    curve = HazardCurve.from_return_periods(periods, ag)
    # Overturning only at the last stripe: the median lies above ag(2475 y).
    stripes = [
        {"ag_g": float(g), "n_records": 7, "n_overturned": 0, "models": "ground"} for g in ag[:-1]
    ] + [{"ag_g": float(ag[-1]), "n_records": 7, "n_overturned": 1, "models": "ground"}]
    stripes = [{**s, "n_vertical_limit": 0} for s in stripes]
    # Every record's collapse intensity above ag(2475 y): lambda_C comes from beyond it.
    top = float(ag[-1])
    ida = [
        {
            "record": f"r{i}",
            "models": "ground",
            "collapse_ag_g": top * f,
            "censored": False,
            "slv_ag_g": top * f / 2,
            "slv_censored": False,
        }
        for i, f in enumerate((1.3, 1.5, 1.7, 2.0, 2.2, 2.6, 3.0))
    ]
    row = summarize_tower(site, stripes, curve, 712.0, float(ag[6]), ida=ida)
    assert row["rate_share_tr_over_2475"] > 0.5 and row["rate_extrapolated"] is True
    assert "extrapolated beyond TR = 2475 y" in row["note"]
    line = assess_lines([row])[1]
    assert "!" in line
