"""The screening risk in ``assess`` (issue 31): every located tower ranked, from geometry only.

A geometry-only inventory (``id, lat, lon, width_m, depth_m, height_m``) of six towers at
six Italian sites, and one tower without coordinates, through ``assess``: every located
tower gets a numeric best estimate inside its 90 % interval, a rank, a band and what to
survey first; the judgement priors are named; the tower without coordinates says why it
has none. ``inspect --json``, the CSV and the archive's long tables carry it; the same seed
gives the same numbers whatever a tower's place in the inventory; a resumed assessment
writes the same risk.
"""

from __future__ import annotations

import csv
import json
import math
from functools import partial

import h5py
import pytest
from click.testing import CliRunner

from rockscreen.pipeline.archive.assess_part import AssessJournal
from rockscreen.pipeline.archive.kinds import open_archive
from rockscreen.pipeline.archive.risk_schema import RISK_SUMMARY_UNITS
from rockscreen.pipeline.cli import main
from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.execution.choose import open_executor
from rockscreen.pipeline.report.risk_ranking import ranking_lines
from rockscreen.pipeline.risk.assess.batch import AssessInputs, assess_to_archive
from rockscreen.pipeline.risk.assess.run import AssessOptions, run_assess
from rockscreen.pipeline.risk.assess.screening_risk import (
    FRAGILITY_AG_G,
    MIN_RISK_SAMPLES,
    RiskOptions,
)
from rockscreen.pipeline.risk.assess.stripes import StripeOptions
from rockscreen.pipeline.risk.uncertainty.belfry import BELFRY_KEYS
from rockscreen.pipeline.verdict.messages import loads, render
from rockscreen.stations.inventory import Tower

from rockscreen_testsupport.records import suite_record

#: Six geometry-only towers at six Italian sites (lat, lon), and one not located.
GEOMETRY = [
    Tower(id="AQ", lat=42.35, lon=13.40, width_m=5.0, depth_m=5.0, height_m=30.0),
    Tower(id="FI", lat=43.77, lon=11.25, width_m=6.0, depth_m=5.5, height_m=45.0),
    Tower(id="NA", lat=40.85, lon=14.25, width_m=4.0, depth_m=4.0, height_m=22.0),
    Tower(id="MO", lat=44.65, lon=10.93, width_m=7.0, depth_m=6.5, height_m=55.0),
    Tower(id="PA", lat=38.12, lon=13.36, width_m=4.5, depth_m=5.0, height_m=18.0),
    Tower(id="VE", lat=45.44, lon=12.33, width_m=6.0, depth_m=6.0, height_m=38.0),
]
NOWHERE = Tower(id="NOWHERE", width_m=5.0, depth_m=5.0, height_m=30.0)
#: Enough samples for the 5 % and 95 % ends and the sensitivity's groups; fast.
SAMPLES = 200


_record = partial(
    suite_record,
    seed_base=300,
    n_samples=1000,
    frequency_hz=(1.5, 0.4),
    envelope_duration_s=6.0,
    name="S-{i}",
)


SUITE = [_record(i) for i in range(4)]


def _options(samples: int = SAMPLES, seed: int = 0, **risk) -> AssessOptions:
    """A quick assessment: one stripe, four records, the ground model, no bootstrap."""
    return AssessOptions(
        return_periods_y=(475.0,),
        stripe=StripeOptions(models=("ground",)),
        selection={"n_records": 4},
        allow_noncompliant=True,
        bootstrap_resamples=0,
        seed=seed,
        risk=RiskOptions(samples=samples, **risk),
    )


def _assess(path, towers, options):
    inputs = AssessInputs(inventory=path.with_suffix(".csv"), suite=SUITE, suite_label="test")
    return assess_to_archive(towers, options, path, inputs, jobs=1)


@pytest.fixture(scope="module")
def archive(tmp_path_factory):
    path = tmp_path_factory.mktemp("screening-risk") / "a.h5"
    _assess(path, [*GEOMETRY, NOWHERE], _options())
    return path


def _risk(row):
    return {k: row[k] for k in RISK_SUMMARY_UNITS}


def test_every_located_tower_gets_a_ranked_risk_from_geometry_only(archive):
    rows = {row["id"]: row for row in open_archive(archive).summary()}
    located = [rows[t.id] for t in GEOMETRY]
    assert any(row["risk_extrapolated_share"] > 0.0 for row in located)
    for row in located:
        best, lo, hi = row["risk_p50_best"], row["risk_p50_lo90"], row["risk_p50_hi90"]
        assert all(math.isfinite(v) for v in (best, lo, hi)), row["id"]
        assert 0.0 <= lo <= best <= hi <= 1.0, row["id"]
        assert row["risk_rate_lo90_per_y"] <= row["risk_rate_best_per_y"]
        assert row["risk_rate_best_per_y"] <= row["risk_rate_hi90_per_y"]
        assert row["risk_survey_first"] in (
            "wall_m",
            "taper",
            "masonry_type",
            "fm_pa",
            "unit_weight_n_m3",
            "period_s",
            *BELFRY_KEYS,
        )
        assert 0.0 <= row["risk_survey_first_narrowing"] <= 1.0
        assert row["risk_band"] in ("top_10", "top_25", "top_50", "rest")
        assert row["risk_band_uncertain"] in ("yes", "no")
        assert row["risk_samples"] == SAMPLES
        assert row["risk_governing_mechanism"]
        assert 0.0 < row["risk_governing_share"] <= 1.0
        # a capacity beyond the NTC table is a value, said by the share and a message
        share = row["risk_extrapolated_share"]
        assert 0.0 <= share <= 1.0, row["id"]
        said = "risk.extrapolated_samples" in row["risk_note_codes"]
        assert said == (share > 0.0), row["id"]
        # the masonry type's uniform prior is a judgement, named in the column and a message
        assert "masonry_type" in row["risk_judgement_inputs"].split(";")
        codes = [m.code for m in loads(row["risk_note_codes"])]
        assert "risk.judgement_prior" in codes
        # ... and its source is a catalogue entry: Italian on an Italian page
        judged = {
            m.kwargs["input"]: m
            for m in loads(row["risk_note_codes"])
            if m.code == "risk.judgement_prior"
        }
        assert "uniforme sui sette tipi storici" in render(judged["masonry_type"], "it")
        # no belfry columns: a belfry sampled by default, said, its judgements labelled
        assert "risk.belfry_sampled" in codes
        belfry_judged = {"belfry_present", "belfry_height_share", "belfry_opening_ratio"}
        assert belfry_judged <= set(row["risk_judgement_inputs"].split(";")) & set(judged)
        assert "bells_mass_kg" not in judged  # TURRIS's, not a judgement
        # what is and is not sampled, said with every tower
        (said,) = [m for m in loads(row["risk_note_codes"]) if m.code == "risk.sampled_inputs"]
        assert {"period_s", "masonry_type", "belfry_present"} <= set(
            said.kwargs["inputs"].split(", ")
        )
        assert "restitution" in render(said, "en") and "attrito" in render(said, "it")
        if row["risk_beta_source"] == "judgement_fema_p695":
            assert row["risk_beta"] == pytest.approx(0.40)
            assert "beta" in row["risk_judgement_inputs"].split(";")
            assert "risk.beta_judgement" in codes
        else:
            assert row["risk_beta_source"] == "ida_fit" and "risk.beta_ida" in codes
        assert "risk.rocking_at_row" in codes  # the documented limit, said per tower
    ranks = sorted(row["risk_rank"] for row in located)
    assert ranks[0] == 1 and all(1 <= r <= len(GEOMETRY) for r in ranks)
    by_rank = sorted(located, key=lambda r: r["risk_rank"])
    assert all(
        a["risk_p50_best"] >= b["risk_p50_best"] for a, b in zip(by_rank, by_rank[1:], strict=False)
    )


def test_a_tower_without_coordinates_says_why_it_has_no_risk(archive):
    row = {row["id"]: row for row in open_archive(archive).summary()}["NOWHERE"]
    assert math.isnan(row["risk_p50_best"]) and row["risk_rank"] == 0
    assert row["risk_band"] == ""
    notes = loads(row["risk_note_codes"])
    assert [m.code for m in notes] == ["risk.no_location"]
    assert "lat, lon" in notes[0].render() and "lat, lon" in notes[0].render("it")


def test_the_long_tables_and_root_attributes(archive):
    reader = open_archive(archive)
    fragility = reader.risk_fragility()
    assert len(fragility) == len(GEOMETRY) * len(FRAGILITY_AG_G)
    for row in fragility:
        assert 0.0 <= row["p_lo90"] <= row["p_median"] <= row["p_hi90"] <= 1.0
    sensitivity = reader.risk_sensitivity()
    assert {row["tower_id"] for row in sensitivity} == {t.id for t in GEOMETRY}
    assert {r["judgement"] for r in sensitivity if r["input"] == "masonry_type"} == {"yes"}
    top = reader.risk_top_n()
    assert sorted(row["tower_id"] for row in top) == sorted(t.id for t in GEOMETRY)
    assert {row["side"] for row in top} <= {"in", "out"}
    assert all(0.0 <= row["p_crosses"] <= 1.0 for row in top)
    attrs = reader.attrs
    assert attrs["risk_priors_source"] == "default" and int(attrs["risk_samples"]) == SAMPLES
    assert int(attrs["risk_seed"]) == 0 and int(attrs["risk_top_n"]) == len(GEOMETRY) - 1
    methods = json.loads(attrs["risk_methods"])
    assert "shaft_lv1_mean" in methods
    assert "belfry_sampled" in methods  # the default priors sample a belfry where none is given
    with h5py.File(archive, "r") as f:
        assert f["summary/risk_p50_best"].attrs["units"] == "1"
        assert f["summary/risk_rate_best_per_y"].attrs["units"] == "1/year"


def test_inspect_json_csv_and_the_terminal_carry_the_risk(archive, tmp_path):
    runner = CliRunner()
    result = runner.invoke(main, ["inspect", "--json", str(archive)])
    assert result.exit_code == 0, result.output
    towers = {t["id"]: t for t in json.loads(result.output)["towers"]}
    rows = {row["id"]: row for row in open_archive(archive).summary()}
    for tower in GEOMETRY:
        risk = towers[tower.id]["risk"]
        assert risk["available"] is True
        assert risk["p50_best"] == rows[tower.id]["risk_p50_best"]
        assert risk["rank"] == rows[tower.id]["risk_rank"] and risk["notes"]
    assert towers["NOWHERE"]["risk"]["available"] is False
    assert towers["NOWHERE"]["risk"]["p50_best"] is None
    out = tmp_path / "o.csv"
    result = runner.invoke(main, ["export", str(archive), "--csv", str(out)])
    assert result.exit_code == 0, result.output
    with open(out, newline="", encoding="utf-8") as f:
        header = next(csv.reader(f))
    assert set(RISK_SUMMARY_UNITS) <= set(header)
    geo = tmp_path / "o.geojson"
    result = runner.invoke(main, ["export", str(archive), "--geojson", str(geo)])
    assert result.exit_code == 0, result.output
    assert 'attr="risk_band"' in geo.with_suffix(".qml").read_text(encoding="utf-8")
    assert 'attr="risk_class"' in geo.with_suffix(".class.qml").read_text(encoding="utf-8")
    lines = ranking_lines(list(rows.values()), top=3)
    assert "code verdict" in lines[1] and len(lines) == 2 + 3
    first = sorted(rows.values(), key=lambda r: r["risk_rank"] or 99)[0]
    assert lines[2].split()[1] == first["id"]


def test_same_seed_same_risk_whatever_the_place_in_the_inventory(archive, tmp_path):
    again = tmp_path / "b.h5"
    _assess(again, list(reversed(GEOMETRY[:3])), _options())
    first = {row["id"]: row for row in open_archive(archive).summary()}
    for row in open_archive(again).summary():
        mine, theirs = _risk(row), _risk(first[row["id"]])
        for key in ("risk_p50_best", "risk_p50_lo90", "risk_p50_hi90", "risk_survey_first"):
            assert mine[key] == theirs[key], (row["id"], key)
    other = tmp_path / "c.h5"
    _assess(other, GEOMETRY[:1], _options(seed=7))
    row = open_archive(other).summary()[0]
    assert row["risk_p50_best"] != first[row["id"]]["risk_p50_best"]  # another seed: samples


def test_a_resumed_assessment_ranks_as_an_uninterrupted_one(tmp_path):
    """A work file holding two of three towers: the third computed, the ranks as whole."""
    towers = GEOMETRY[:3]
    whole = run_assess(towers, _options(), open_executor(jobs=1)[0], suite=SUITE)
    with AssessJournal(tmp_path / "a.h5", {"test": 1}) as first:
        run_assess(towers, _options(), open_executor(jobs=1)[0], suite=SUITE, journal=first)
    with AssessJournal(tmp_path / "a.h5", {"test": 1}) as again:
        assert again.resumed and sorted(again.done) == [0, 1, 2]
        del again.done[1]  # as if killed before the second tower was kept
        resumed = run_assess(
            towers, _options(), open_executor(jobs=1)[0], suite=SUITE, journal=again
        )
    assert [_risk(r) for r in resumed.summary] == [_risk(r) for r in whole.summary]
    assert resumed.risk == whole.risk


def test_too_few_samples_are_refused_in_one_line(tmp_path):
    with pytest.raises(RiskError, match=f">= {MIN_RISK_SAMPLES}"):
        RiskOptions(samples=MIN_RISK_SAMPLES - 1)
    (tmp_path / "t.csv").write_text("id,lat,lon,width_m,height_m\nA,42.35,13.40,5,30\n")
    result = CliRunner().invoke(
        main,
        [
            "assess",
            "--towers",
            str(tmp_path / "t.csv"),
            "--risk-samples",
            "50",
            "--out",
            str(tmp_path / "o.h5"),
        ],
    )
    assert result.exit_code == 2
    assert "--risk-samples" in result.output and f">= {MIN_RISK_SAMPLES}" in result.output


def test_a_priors_file_collapses_the_masonry_judgement(tmp_path):
    priors = tmp_path / "region.toml"
    priors.write_text(
        'region = "brick plain"\n[masonry]\nvalue = "solid_brick"\nsource = "survey"\n',
        encoding="utf-8",
    )
    from rockscreen.pipeline.risk.uncertainty.region import read_region_priors

    path = tmp_path / "p.h5"
    options = _options(
        samples=MIN_RISK_SAMPLES, region=read_region_priors(priors), priors_source=priors.name
    )
    _assess(path, GEOMETRY[:1], options)
    reader = open_archive(path)
    row = reader.summary()[0]
    assert "masonry_type" not in row["risk_judgement_inputs"].split(";")
    assert reader.attrs["risk_priors_source"] == "region.toml"
    assert "masonry_type" not in {r["input"] for r in reader.risk_sensitivity()}
    assert math.isfinite(row["risk_p50_best"])


def test_a_priors_file_turns_the_sampled_belfry_off(tmp_path):
    priors = tmp_path / "no-belfry.toml"
    priors.write_text("[belfry]\nsampled = false\n", encoding="utf-8")
    from rockscreen.pipeline.risk.uncertainty.region import read_region_priors

    path = tmp_path / "nb.h5"
    region = read_region_priors(priors)
    _assess(path, GEOMETRY[:1], _options(samples=MIN_RISK_SAMPLES, region=region))
    row = open_archive(path).summary()[0]
    codes = [m.code for m in loads(row["risk_note_codes"])]
    assert "risk.belfry_not_sampled" in codes and "risk.belfry_sampled" not in codes
    assert not set(BELFRY_KEYS) & set(row["risk_judgement_inputs"].split(";"))
    assert math.isfinite(row["risk_p50_best"])


def test_a_located_tower_without_an_ida_gets_a_risk_without_rocking():
    """A tower whose record set failed or was refused: no IDA, the other mechanisms' risk."""
    from rockscreen.pipeline.risk.assess.screening_region import assess_risk
    from rockscreen.pipeline.risk.assess.sites import tower_sites
    from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
    from rockscreen.pipeline.risk.uncertainty.risk import site_hazard_curve

    sites = tower_sites(GEOMETRY[:2], 0.01)
    summary = {site.index: {"id": site.tower.id} for site in sites}

    def hazard(site):
        return {"curve": site_hazard_curve(SiteConditions(site.lon_deg, site.lat_deg))}

    region = assess_risk(sites, summary, {}, hazard, 0, RiskOptions(samples=MIN_RISK_SAMPLES))
    for row in summary.values():
        assert math.isfinite(row["risk_p50_best"]) and row["risk_rank"] in (1, 2)
        assert "rocking" not in row["risk_governing_mechanism"]
        codes = [m.code for m in loads(row["risk_note_codes"])]
        assert "risk.rocking_left_out" in codes and "risk.rocking_at_row" not in codes
    assert region.top_n == 1 and len(region.top_n_rows) == 2
