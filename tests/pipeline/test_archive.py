"""The campaign archive: layout, units, resume after a crash, discarded work files."""

from __future__ import annotations

import math
from types import SimpleNamespace

import h5py
import numpy as np
import pytest

from pipeline.archive.campaign import (
    ArchiveWriter,
    archive_tree,
    part_path,
    read_failures,
    read_histories,
    read_metadata,
    read_results,
    read_stations,
    read_summary,
)
from pipeline.config import CampaignConfig
from pipeline.errors import ArchiveError
from pipeline.screening.campaign import chunk_tasks
from pipeline.screening.cases import CampaignShared, Failure, Motion, Solvers, TowerTask
from pipeline.screening.evaluate import run_chunk
from solver.constants import G
from stations.inventory import Tower, inventory_table


def fake_block(width, height, *, eta=None):
    return SimpleNamespace(alpha=math.atan(width / height))


def fake_rocking(block, acc, dt, *, acc_v=None, history=True, max_free_time=60.0):
    ratio = float(np.max(np.abs(acc))) / (G * math.tan(block.alpha))
    t = np.arange(len(acc)) * dt
    return SimpleNamespace(
        status="overturned" if ratio > 2 else "came_to_rest",
        overturned=ratio > 2,
        uplifted=ratio > 1,
        slipped=False,
        theta_max=max(0.0, ratio - 1) * block.alpha,
        theta_max_over_alpha=max(0.0, ratio - 1),
        n_impacts=0,
        t_overturn=math.nan,
        slip_max=0.0,
        slip_residual=0.0,
        friction_demand_max=0.1,
        alpha=block.alpha,
        p=2.0,
        eta=0.9,
        t=t,
        theta=acc / G * block.alpha,
        u=np.zeros_like(t),
        regime=np.ones(len(t), dtype=np.int8),
    )


FAKE = Solvers(
    block=fake_block, rocking=fake_rocking, double=fake_rocking, floor=lambda a, d, **k: a
)


def motions():
    t = np.arange(3000) * 0.01
    shape = np.sin(2 * np.pi * t) * np.exp(-(((t - 5) / 2) ** 2))
    return {
        "XX.A..HN": Motion(
            "XX.A..HN",
            "XX.A",
            0.01,
            ("HNN", "HNE"),
            (4 * shape, 2 * shape),
            (0.0, 90.0),
            0.1 * shape,
            42.0,
            13.0,
            {"files": ["a.mseed"], "provenance": {"h1": [{"step": "read"}]}},
        )
    }


def towers():
    return [
        Tower(id=f"T{i:02d}", width_m=1.5 + 0.25 * i, height_m=6.0, lat=42.0, lon=13.0)
        for i in range(12)
    ]


def canon(rows):
    """Rows with NaN replaced by a marker, so that equal tables compare equal."""
    return [
        {k: "nan" if isinstance(v, float) and math.isnan(v) else v for k, v in row.items()}
        for row in rows
    ]


def run(path, towers_, *, stop_after=None, fingerprint="abc"):
    """Write an archive chunk by chunk; stop (as a crash would) after ``stop_after`` chunks."""
    m = motions()
    writer = ArchiveWriter(
        path,
        fingerprint=fingerprint,
        metadata={"rockscreen_version": "test", "config_toml": CampaignConfig().to_toml()},
        towers_table=inventory_table(towers_),
        motions=m,
        failures=[Failure("read", "bad.mseed", "empty file")],
    )
    shared = CampaignShared(m, CampaignConfig(), FAKE)
    tasks = [TowerTask(i, t, ("XX.A..HN",)) for i, t in enumerate(towers_)]
    todo = [task for task in tasks if task.tower.id not in writer.done]
    chunks = chunk_tasks(todo, 1, size=3)
    with writer:
        # Reverse order: chunks arrive out of order from parallel workers.
        for n, chunk in enumerate(reversed(chunks), start=1):
            writer.append(run_chunk(shared, chunk))
            if stop_after is not None and n >= stop_after:
                return writer
    writer.finalize()
    return writer


def test_layout_units_and_readers(tmp_path):
    path = tmp_path / "out.h5"
    run(path, towers())
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


def test_resume_after_a_crash_gives_the_same_content(tmp_path):
    reference = tmp_path / "ref.h5"
    run(reference, towers())
    path = tmp_path / "out.h5"
    run(path, towers(), stop_after=2)  # "crash": work file left, no archive
    assert part_path(path).exists() and not path.exists()
    writer = run(path, towers())
    assert writer.resumed
    assert canon(read_summary(path)) == canon(read_summary(reference))
    assert canon(read_results(path)) == canon(read_results(reference))
    for tower_id in ("T00", "T11"):
        a, b = read_histories(path, tower_id), read_histories(reference, tower_id)
        np.testing.assert_array_equal(a[0]["theta"], b[0]["theta"])


def test_uncommitted_rows_are_dropped_on_resume(tmp_path):
    path = tmp_path / "out.h5"
    run(path, towers(), stop_after=1)
    with h5py.File(part_path(path), "r+") as f:  # a kill in the middle of an append
        ds = f["results/tower_id"]
        ds.resize((ds.shape[0] + 5,))
    run(path, towers())
    assert len(read_results(path)) == 24


def test_unreadable_or_foreign_work_file_is_discarded(tmp_path):
    path = tmp_path / "out.h5"
    part_path(path).write_bytes(b"not hdf5 at all")
    writer = run(path, towers())
    assert not writer.resumed and len(read_summary(path)) == 12
    run(path, towers(), stop_after=1, fingerprint="one")
    writer = run(path, towers(), fingerprint="two")
    assert not writer.resumed


def test_reading_a_missing_or_foreign_file_is_an_archive_error(tmp_path):
    with pytest.raises(ArchiveError, match="does not exist"):
        read_summary(tmp_path / "nope.h5")
    foreign = tmp_path / "foreign.h5"
    with h5py.File(foreign, "w") as f:
        f["x"] = 1
    with pytest.raises(ArchiveError, match="not a rockscreen archive"):
        read_summary(foreign)
