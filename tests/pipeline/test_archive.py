"""The campaign archive: layout, units, resume after a crash, discarded work files."""

from __future__ import annotations

import math

import h5py
import numpy as np
import pytest

from rockscreen.pipeline.archive.campaign import (
    archive_tree,
    part_path,
    read_failures,
    read_histories,
    read_metadata,
    read_results,
    read_stations,
    read_summary,
)
from rockscreen.pipeline.errors import ArchiveError


def canon(rows):
    """Rows with NaN replaced by a marker, so that equal tables compare equal."""
    return [
        {k: "nan" if isinstance(v, float) and math.isnan(v) else v for k, v in row.items()}
        for row in rows
    ]


@pytest.fixture
def run(write_archive):
    """Write an archive of 12 towers in chunks of 3; stop after ``stop_after`` chunks."""
    return lambda path, **options: write_archive(path, 12, chunk_size=3, **options)


def test_layout_units_and_readers(tmp_path, run):
    path = tmp_path / "out.h5"
    run(path)
    assert path.is_file() and not part_path(path).exists()
    with h5py.File(path, "r") as f:
        assert f.attrs["format"] == "rockscreen-archive"
        for name in ("towers", "records", "results", "summary", "failures", "histories"):
            assert name in f
        units = {}

        def collect(name, obj):
            if isinstance(obj, h5py.Dataset):
                units[name] = obj.attrs["units"]

        f.visititems(collect)
    assert all(isinstance(u, str) for u in units.values())
    assert units["results/theta_max_rad"] == "rad"
    assert units["towers/width_m"] == "m"
    assert units["records/XX.A..HN/HNN"] == "m/s2"
    assert units["histories/t"] == "s"
    summary = read_summary(path)
    assert [row["id"] for row in summary] == [f"T{i:02d}" for i in range(12)]
    assert len(read_results(path)) == 12 * 2
    assert read_failures(path) == [{"kind": "read", "subject": "bad.mseed", "reason": "empty file"}]
    assert read_metadata(path)["rockscreen_version"] == "test"
    histories = read_histories(path, "T03")
    assert [(h["model"], h["component"]) for h in histories] == [("ground", "N")]
    assert histories[0]["theta"].dtype == np.float32
    assert read_stations(path) == [{"key": "XX.A", "latitude": 42.0, "longitude": 13.0}]
    assert any("theta_max_over_alpha" in line for line in archive_tree(path))
    with pytest.raises(ArchiveError, match="T99"):
        read_histories(path, "T99")


def test_resume_after_a_crash_gives_the_same_content(tmp_path, run):
    reference = tmp_path / "ref.h5"
    run(reference)
    path = tmp_path / "out.h5"
    run(path, stop_after=2)  # "crash": work file left, no archive
    assert part_path(path).exists() and not path.exists()
    writer = run(path)
    assert writer.resumed
    assert canon(read_summary(path)) == canon(read_summary(reference))
    assert canon(read_results(path)) == canon(read_results(reference))
    for tower_id in ("T00", "T11"):
        a, b = read_histories(path, tower_id), read_histories(reference, tower_id)
        np.testing.assert_array_equal(a[0]["theta"], b[0]["theta"])


def test_uncommitted_rows_are_dropped_on_resume(tmp_path, run):
    path = tmp_path / "out.h5"
    run(path, stop_after=1)
    with h5py.File(part_path(path), "r+") as f:  # a kill in the middle of an append
        ds = f["results/tower_id"]
        ds.resize((ds.shape[0] + 5,))
    run(path)
    assert len(read_results(path)) == 24


def test_unreadable_or_foreign_work_file_is_discarded(tmp_path, run):
    path = tmp_path / "out.h5"
    part_path(path).write_bytes(b"not hdf5 at all")
    writer = run(path)
    assert not writer.resumed and len(read_summary(path)) == 12
    run(path, stop_after=1, fingerprint="one")
    writer = run(path, fingerprint="two")
    assert not writer.resumed


def test_reading_a_missing_or_foreign_file_is_an_archive_error(tmp_path):
    with pytest.raises(ArchiveError, match="does not exist"):
        read_summary(tmp_path / "nope.h5")
    foreign = tmp_path / "foreign.h5"
    with h5py.File(foreign, "w") as f:
        f["x"] = 1
    with pytest.raises(ArchiveError, match="not a rockscreen archive"):
        read_summary(foreign)
