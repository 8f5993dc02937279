"""rockscreen assess: the multiple-stripe analysis, its archive and the acceptance checks."""

from __future__ import annotations

import math
from functools import partial

import h5py
import numpy as np
import pytest

from rockscreen.pipeline.archive.risk_archive import write_risk_archive
from rockscreen.pipeline.archive.risk_reader import (
    read_metadata,
    read_outcomes,
    read_records,
    read_selection,
    read_set_records,
    read_stripes,
    read_summary,
)
from rockscreen.pipeline.archive.safety import read_column
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.execution.local import SerialExecutor
from rockscreen.pipeline.hazard.selection import SuiteRecord
from rockscreen.pipeline.risk.assess.batch import record_arrays
from rockscreen.pipeline.risk.assess.run import AssessOptions, record_id, run_assess, tower_sites
from rockscreen.stations.inventory import Tower

from rockscreen_testsupport.records import suite_record
from rockscreen_testsupport.towers import block_tower

MESSINA = (38.1, 15.65)  # lat, lon [deg]: high code hazard (ag(2475 y) ~ 0.51 g)
CERVINO = (41.04, 14.42)  # lower hazard (ag(2475 y) ~ 0.25 g)


#: The test suite's records (rockscreen_testsupport.records, SI units): 15 s at 100 Hz,
#: PGA 2 m/s2; record ``i`` has the ground frequency 1.5 + 0.3 i Hz.
_record = partial(suite_record, source="test suite")


@pytest.fixture(scope="module")
def assessed():
    suite = [_record(i) for i in range(10)]
    towers = [
        block_tower("S1", 1.0, 0.10, MESSINA),
        block_tower("S2", 1.0, 0.15, MESSINA),
        block_tower("S3", 1.0, 0.22, MESSINA),
        block_tower("C1", 1.0, 0.10, CERVINO),
        Tower(id="NOWHERE", width_m=1.0, height_m=4.0),
    ]
    # The test suite fails NTC 2018 §3.2.3.6 at TR = 30 y (mean/target 0.88-1.33 at Messina):
    # without allow_noncompliant the assessment is refused before any solve.
    options = AssessOptions(selection={"n_records": 7}, allow_noncompliant=True)
    result = run_assess(towers, options, SerialExecutor(), suite=suite)
    return {row["id"]: row for row in result.summary}, result


def test_rate_grows_with_slenderness_at_equal_size(assessed):
    rows, _ = assessed
    rates = [rows[t]["annual_rate_overturning_per_y"] for t in ("S1", "S2", "S3")]
    assert all(math.isfinite(r) for r in rates)
    assert rates[0] > rates[1] > rates[2]  # alpha 0.10 < 0.15 < 0.22: more slender, more risk
    assert rows["S1"]["safety_index"] < rows["S3"]["safety_index"]


def test_every_located_tower_has_an_ida_fragility_or_says_why(assessed):
    rows, result = assessed
    for tower_id in ("S1", "S2", "S3", "C1"):
        row = rows[tower_id]
        assert row["collapse_n_records"] == 7 and row["ida_n_solves"] > 0
        if row["collapse_bound"]:
            assert row["collapse_n_censored"] >= 6 and "collapse fit:" in row["note"]
            continue
        for key in ("collapse_median_g", "collapse_beta", "collapse_se_ln_median"):
            assert math.isfinite(row[key]) and row[key] > 0, (tower_id, key)
        assert math.isfinite(row["collapse_se_beta"])
        assert row["collapse_beta"] != pytest.approx(0.05)  # no floor
        assert row["slv_median_g"] <= row["collapse_median_g"]
    assert {r["tower_id"] for r in result.ida} == {"S1", "S2", "S3", "C1"}


def test_rate_higher_where_hazard_higher(assessed):
    rows, _ = assessed
    assert rows["S1"]["annual_rate_overturning_per_y"] > rows["C1"]["annual_rate_overturning_per_y"]


def test_tower_without_coordinates_is_listed_not_guessed(assessed):
    rows, result = assessed
    assert rows["NOWHERE"]["risk_class"] == "undefined"
    assert math.isnan(rows["NOWHERE"]["annual_rate_overturning_per_y"])
    assert [f["subject"] for f in result.failures] == ["NOWHERE"]


def test_stripes_counts_and_skipped_motionless_cases(assessed):
    _, result = assessed
    s1 = [s for s in result.stripes if s["tower_id"] == "S1"]
    assert [s["return_period_y"] for s in s1] == sorted(s["return_period_y"] for s in s1)
    assert len(s1) == 9 and all(s["n_records"] == 7 for s in s1)
    assert all(s["n_overturned"] <= s["n_damage_0p5"] <= s["n_damage_0p01"] for s in s1)
    statuses = {o["status"] for o in result.outcomes}
    assert "no_motion" in statuses and "overturned" in statuses
    n_cases = len(result.outcomes)
    ida_solves = sum(row["n_solves"] for row in result.ida)
    assert sum(row["ida_n_solves"] for row in result.summary) == ida_solves > 0
    # the motionless cases of the stripes were not solved (the IDA's solves counted apart)
    assert 0 < result.n_solves - ida_solves < n_cases
    for stripe in s1:
        cases = [
            o
            for o in result.outcomes
            if o["tower_id"] == "S1" and o["return_period_y"] == stripe["return_period_y"]
        ]
        fell = {o["record"] for o in cases if o["overturned"]}
        assert stripe["n_overturned"] == len(fell)


def test_archive_identities_and_units(assessed, tmp_path):
    rows, result = assessed
    path = tmp_path / "assess.h5"
    names = ("summary", "stripes", "outcomes", "selection", "failures", "ida")
    tables = {name: getattr(result, name) for name in names}
    write_risk_archive(path, "assess", tables, {"inventory_source": "test"})
    summary = read_summary(path, "assess")
    assert [r["id"] for r in summary] == ["S1", "S2", "S3", "C1", "NOWHERE"]
    for row in summary:
        if math.isnan(row["safety_index"]):
            continue
        assert row["safety_index"] == pytest.approx(
            row["capacity_return_period_y"] / row["tr_slv_y"], rel=1e-6
        )
        if math.isfinite(row["annual_rate_overturning_per_y"]):
            assert row["p_overturning_50y"] == pytest.approx(
                1 - math.exp(-50 * row["annual_rate_overturning_per_y"]), rel=1e-6
            )
    assert len(read_stripes(path)) == len(result.stripes)
    assert len(read_outcomes(path)) == len(result.outcomes)
    assert {r["return_period_y"] for r in read_selection(path)} == {
        30.0,
        50.0,
        72.0,
        101.0,
        140.0,
        201.0,
        475.0,
        975.0,
        2475.0,
        *{row["tr_slv_y"] for row in summary if math.isfinite(row["tr_slv_y"])},
    }  # the stripes' return periods and the IDA's set at each T_R,SLV
    assert read_metadata(path)["kind"] == "assess"
    with h5py.File(path) as f:

        def check(name, obj):
            if isinstance(obj, h5py.Dataset):
                assert "units" in obj.attrs, name

        f.visititems(check)
        # the collapse, SLV and stripe fits' medians: rows of /fits (format 4)
        assert {"collapse", "slv", "stripe"} <= set(read_column(f["fits/fit"], path, "fit"))
        assert f["fits/median_g"].attrs["units"] == "9.81 m/s2"
        assert f["summary/annual_rate_overturning_per_y"].attrs["units"] == "1/year"
        assert f["ida/collapse_ag_g"].attrs["units"] == "9.81 m/s2"
        assert f["ida/collapse_scale"].attrs["units"] == "1"
    with h5py.File(path, "a") as f:
        f.attrs["format_version"] = "9"
    with pytest.raises(ArchiveError, match="format_version '9'"):
        read_summary(path)


def test_archive_stores_the_records_of_the_selected_sets(assessed, tmp_path):
    _, result = assessed
    path = tmp_path / "assess.h5"
    tables = {"summary": result.summary, "selection": result.selection}
    write_risk_archive(
        path,
        "assess",
        tables,
        {},
        records=record_arrays(result.records),
        set_records=result.set_records,
    )
    stored = read_records(path)
    selection = read_selection(path)
    ids = [[i for i, _ in refs] for refs in read_set_records(path)]
    assert {i for row in ids for i in row} == set(stored)
    # a user suite's record is the same in every set: stored once (10 records in the suite)
    assert 7 <= len(stored) <= 10
    originals = {r.name: r for r in (_record(i) for i in range(10))}
    for row, row_ids in zip(selection, ids, strict=True):
        assert len(row_ids) == row["n_records"]
    # the references read back as written, in order, the factors exact (float64)
    stored_refs = [(row, i, f) for row, refs in enumerate(read_set_records(path)) for i, f in refs]
    assert stored_refs == list(result.set_records)
    for record in stored.values():
        original = originals[record["name"]]
        assert record["dt_s"] == 0.01
        np.testing.assert_array_equal(record["x"], original.acc_x_m_s2)
        np.testing.assert_array_equal(record["y"], original.acc_y_m_s2)
        np.testing.assert_array_equal(record["z"], original.acc_z_m_s2)
    with h5py.File(path) as f:
        assert f["records/index/dt_s"][0] == 0.01 and f["records/x"].attrs["units"] == "m/s2"
        assert f["records/index/dt_s"].attrs["units"] == "s"


def test_record_ids_tell_apart_records_of_one_name():
    a = _record(1)
    b = SuiteRecord(a.name, 2 * a.acc_x_m_s2, a.acc_y_m_s2, a.acc_z_m_s2, 0.01, "other")
    assert record_id(a) == record_id(_record(1)) != record_id(b)
    assert record_id(a).startswith("T-01-")
    assert "/" not in record_id(SuiteRecord("a/b", a.acc_x_m_s2, None, None, 0.01, ""))


def test_sites_share_record_sets_and_record_assumptions():
    towers = [
        Tower(id="A", width_m=1, height_m=4, lat=41.041, lon=14.421),
        Tower(id="B", width_m=1, height_m=4, lat=41.043, lon=14.418),
    ]
    sites = tower_sites(towers, 0.01)
    assert sites[0].key == sites[1].key == (14.42, 41.04, "A", "T1")
    assert sites[0].soil_class_source == "default"
    assert any(a.startswith("soil_class=") for a in sites[0].assumptions)
    assert tower_sites(towers, 0.0)[0].lon_deg == 14.421


def test_a_record_at_the_vertical_limit_is_left_out_of_the_stripe_not_counted_as_failure():
    from types import SimpleNamespace

    import numpy as np

    from rockscreen.pipeline.hazard import SuiteRecord
    from rockscreen.pipeline.risk.assess.stripes import (
        StripeOptions,
        evaluate_stripe,
        stripe_arrays,
    )
    from rockscreen.stations.inventory import Tower

    t = np.arange(1000) * 0.01
    quiet = 0.05 * np.sin(2 * np.pi * t)
    records = (
        SuiteRecord("ok", quiet, quiet, 0.1 * quiet, 0.01, "test"),
        SuiteRecord("falls-away", quiet, quiet, -12.0 * np.abs(np.sin(t)), 0.01, "test"),
    )
    record_set = SimpleNamespace(records=records, scale_factors=np.array([1.0, 1.0]))
    tower = Tower(id="T", width_m=3.0, height_m=20.0)
    stripe, outcomes, _ = evaluate_stripe(
        tower, record_set, 475.0, 0.25, StripeOptions(models=("ground",))
    )
    assert stripe["n_records"] == 1 and stripe["n_vertical_limit"] == 1
    assert stripe["n_overturned"] == 0
    limited = [o for o in outcomes if o["record"] == "falls-away"]
    assert limited and all(o["status"] == "vertical_limit" and not o["overturned"] for o in limited)
    empty = dict(stripe, n_records=0)
    assert len(stripe_arrays([empty])[0]) == 0


def test_cli_matched_suite_on_request(tmp_path):
    """``--suite-kind matched``: the matched suite, 7 records per set, said in the archive."""
    from click.testing import CliRunner

    from rockscreen.pipeline.cli import main

    inventory = tmp_path / "towers.csv"
    inventory.write_text("id;lat;lon;width_m;height_m\nA;41,04;14,42;2;8\n", encoding="utf-8")
    out = tmp_path / "a.h5"
    args = ["assess", "--towers", str(inventory), "--return-periods", "475", "--models", "ground"]
    args += ["--suite-kind", "matched", "--bootstrap", "0", "--jobs", "1", "--out", str(out)]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 0, result.output
    metadata = read_metadata(out)
    assert metadata["suite_kind"] == "matched" and metadata["n_records_per_stripe"] == 7
    assert "embedded matched suite" in metadata["suite_source"]
    (selection, *_) = read_selection(out)
    (refs, *_) = read_set_records(out)
    stored = read_records(out)
    assert selection["n_records"] == len(refs) == 7
    assert all(stored[i]["name"].startswith("SYN-0-") for i, _ in refs)
    assert len(stored) == 2 * 7  # the 475 y set and the T_R,SLV set
