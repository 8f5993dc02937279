"""An assess archive keeps each record once and its sets as references, and reruns exactly.

Issue 30 ("Records in the archive once"): ``/records`` holds every record of the sets once
(``/records/index`` and the concatenated samples), ``/set_records`` each set as (record,
exact scale factor); a rerun of the same towers and options on the archive's sets
(:func:`rockscreen.pipeline.risk.assess.archived_sets.archived_record_sets`) gives every verdict
of the archive exactly, with the embedded suite (samples stored as float32, which its pool
records are exactly) and with a user suite (float64).
"""

from __future__ import annotations

import math
from pathlib import Path

import h5py
import numpy as np
import pytest

from rockscreen.pipeline.archive.kinds import open_archive
from rockscreen.pipeline.archive.risk_archive import sample_dtype, write_risk_archive
from rockscreen.pipeline.archive.risk_reader import (
    read_ida,
    read_outcomes,
    read_records,
    read_selection,
    read_set_records,
    read_stripes,
    read_summary,
)
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.execution.local import SerialExecutor
from rockscreen.pipeline.hazard.selection import SuiteRecord
from rockscreen.pipeline.risk.assess import worker as assess_worker
from rockscreen.pipeline.risk.assess.archived_sets import archived_record_sets
from rockscreen.pipeline.risk.assess.batch import AssessInputs, assess_to_archive
from rockscreen.pipeline.risk.assess.run import AssessOptions, run_assess
from rockscreen.pipeline.risk.assess.stripes import StripeOptions
from rockscreen.stations.inventory import Tower

from rockscreen_testsupport.records import suite_record

#: Two sites of different soils (two pools), three towers: one shares its site.
TOWERS = [
    Tower(id="A1", width_m=1.2, height_m=6.0, lat=41.04, lon=14.42, soil_class="A"),
    Tower(id="A2", width_m=0.9, height_m=5.0, lat=41.04, lon=14.42, soil_class="A"),
    Tower(id="C1", width_m=1.5, height_m=9.0, lat=42.35, lon=13.40, soil_class="C"),
]


def _options(n_records: int | None = None) -> AssessOptions:
    selection = {} if n_records is None else {"n_records": n_records}
    return AssessOptions(
        return_periods_y=(475.0,),
        stripe=StripeOptions(models=("ground",)),
        selection=selection,
        bootstrap_resamples=20,
        allow_noncompliant=True,
    )


def _user_suite() -> list[SuiteRecord]:
    """Ten float64 records (not float32 exactly), 15 s at 100 Hz."""
    return [suite_record(i, seed_base=100, name="U-{i:02d}") for i in range(10)]


def _same(a, b) -> bool:
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return a == b


def _assert_same_rows(first, second, what: str) -> None:
    assert len(first) == len(second), what
    for i, (a, b) in enumerate(zip(first, second, strict=True)):
        assert a.keys() == b.keys(), (what, i)
        differ = [k for k in a if not _same(a[k], b[k])]
        assert not differ, (what, i, {k: (a[k], b[k]) for k in differ})


def _assessed(folder: Path, suite, n_records=None) -> Path:
    out = folder / "assess.h5"
    inputs = AssessInputs(inventory=Path("towers.csv"), suite=suite)
    assess_to_archive(TOWERS, _options(n_records), out, inputs, jobs=1)
    return out


@pytest.fixture(scope="module", params=["embedded", "user"])
def archive(request, tmp_path_factory):
    suite = None if request.param == "embedded" else _user_suite()
    n_records = None if suite is None else 7
    return request.param, _assessed(tmp_path_factory.mktemp(request.param), suite, n_records)


def test_each_record_is_stored_once_and_every_set_refers_to_stored_records(archive):
    suite, path = archive
    records = read_records(path)
    references = read_set_records(path)
    selection = read_selection(path)
    assert len(references) == len(selection) > 0
    referenced = {record_id for refs in references for record_id, _ in refs}
    # stored once: one row per distinct record referenced, none left over
    assert len(records) == len(referenced) and set(records) == referenced
    with h5py.File(path) as f:
        ids = f["records/index/id"].asstr()[:]
        assert len(ids) == len(set(ids)) == len(records)
        assert f.attrs["format_version"] == "4"  # 3: records once; 4: the long tables
        # float32 holds the pools' records exactly; a user suite's float64 records are kept
        assert f["records/x"].dtype == (np.float32 if suite == "embedded" else np.float64)
        assert f["records/x"].attrs["units"] == "m/s2"
        assert f["set_records/scale_factor"].dtype == np.float64
        # the sets are the references: no list of ids, names or rounded factors beside them
        assert not {"records", "record_ids", "scale_factors"} & set(f["selection"])
    for row, refs in zip(selection, references, strict=True):
        assert row["n_records"] == len(refs)
        assert all(records[i]["dt_s"] > 0 for i, _ in refs)
    # the one door reads them too
    reader = open_archive(path)
    assert reader.version == "4" and reader.set_records() == references
    assert set(reader.records()) == referenced


def test_a_user_suite_record_is_stored_as_given(tmp_path):
    suite = _user_suite()
    path = _assessed(tmp_path, suite, 7)
    originals = {r.name: r for r in suite}
    for record in read_records(path).values():
        original = originals[record["name"]]
        assert record["dt_s"] == original.dt_s
        for component, acc in zip(
            "xyz", (original.acc_x_m_s2, original.acc_y_m_s2, original.acc_z_m_s2), strict=True
        ):
            assert record[component].dtype == np.float64
            np.testing.assert_array_equal(record[component], acc)


def test_a_rerun_on_the_archive_sets_reproduces_every_verdict_exactly(archive, monkeypatch):
    suite, path = archive
    sets = archived_record_sets(path)

    def no_selection(*args, **kwargs):
        raise AssertionError("the rerun selected a set instead of taking the archive's")

    monkeypatch.setattr(assess_worker, "site_record_set", no_selection)
    n_records = None if suite == "embedded" else 7
    rerun = run_assess(TOWERS, _options(n_records), SerialExecutor(), record_sets=sets)
    out = path.with_name("rerun.h5")
    write_risk_archive(
        out,
        "assess",
        {
            "summary": rerun.summary,
            "stripes": rerun.stripes,
            "outcomes": rerun.outcomes,
            "selection": rerun.selection,
            "ida": rerun.ida,
        },
        {},
    )
    assert [row["id"] for row in read_summary(path)] == ["A1", "A2", "C1"]
    assert all(row["n_solves"] > 0 for row in read_summary(path))  # every tower assessed
    for read in (read_summary, read_stripes, read_outcomes, read_ida, read_selection):
        _assert_same_rows(read(path), read(out), read.__name__)


def test_the_samples_are_stored_in_the_narrowest_exact_type():
    exact = np.array([0.1, -2.5, 3.0], dtype=np.float32).astype(np.float64)
    assert sample_dtype({"a": {"x": exact, "y": None, "z": exact}}) is np.float32
    assert sample_dtype({"a": {"x": exact}, "b": {"x": np.array([0.1])}}) is np.float64


def test_a_set_referring_to_a_record_not_stored_is_refused(tmp_path):
    record = {"x": np.ones(3), "y": None, "z": None, "dt_s": 0.01, "name": "r", "source": ""}
    with pytest.raises(ArchiveError, match="record 'missing'"):
        write_risk_archive(
            tmp_path / "a.h5",
            "assess",
            {"summary": [{"id": "T"}], "selection": [{"n_records": 1}]},
            {},
            records={"r-1": record},
            set_records=[(0, "missing", 1.0)],
        )


def test_a_version_2_archive_reads_its_records_and_refuses_a_rerun(tmp_path):
    record = {"x": np.arange(4.0), "y": None, "z": 0.5 * np.arange(4.0), "dt_s": 0.01}
    path = tmp_path / "v2.h5"
    write_risk_archive(
        path,
        "assess",
        {"summary": [{"id": "T"}]},
        {"command_line": "rockscreen assess --towers t.csv"},
    )
    with h5py.File(path, "a") as f:  # the version-2 layout: one group per record
        f.attrs["format_version"] = "2"
        group = f.create_group("records").create_group("r-0123456789")
        group.attrs.update(dt_s=0.01, name="r", source="s")
        for component in ("x", "z"):
            group.create_dataset(component, data=record[component]).attrs["units"] = "m/s2"
    stored = read_records(path)
    assert list(stored) == ["r-0123456789"] and stored["r-0123456789"]["y"] is None
    np.testing.assert_array_equal(stored["r-0123456789"]["z"], record["z"])
    with pytest.raises(ArchiveError, match=r"format_version '2'.*rockscreen assess --towers t.csv"):
        read_set_records(path)
    assert open_archive(path).version == "2"


def test_real_records_as_the_suite_are_stored_once_and_rerun_exactly(shared_data, tmp_path):
    """``--suite`` with real records (L'Aquila 2009): stored as read (float64), rerun exactly."""
    from rockscreen.pipeline.hazard.suite_io import load_suite

    folder = shared_data / "laquila2009"
    if not (folder / "stations.xml").is_file():
        pytest.skip(f"{folder} is absent")
    suite = load_suite(folder)
    towers = TOWERS[:1]
    options = _options(4)
    out = tmp_path / "real.h5"
    assess_to_archive(towers, options, out, AssessInputs(Path("towers.csv"), suite=suite), jobs=1)
    stored = read_records(out)
    originals = {r.name: r for r in suite}
    for record in stored.values():  # every record as read, to the last bit
        original = originals[record["name"]]
        np.testing.assert_array_equal(record["x"], original.acc_x_m_s2)
        np.testing.assert_array_equal(record["y"], original.acc_y_m_s2)
    with h5py.File(out) as f:
        assert f["records/x"].dtype == np.float64
        assert len(f["records/index/id"]) == len(stored) < len(f["set_records/record"])
    rerun = run_assess(towers, options, SerialExecutor(), record_sets=archived_record_sets(out))
    again = tmp_path / "again.h5"
    write_risk_archive(again, "assess", {"summary": rerun.summary, "ida": rerun.ida}, {})
    for read in (read_summary, read_ida):
        _assert_same_rows(read(out), read(again), read.__name__)
