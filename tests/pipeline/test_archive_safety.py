"""Trusting an archive: format versions, crafted files, damaged work files, full disks, locks."""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys

import h5py
import numpy as np
import pytest
from click.testing import CliRunner

from rockscreen.pipeline.archive import campaign, resume
from rockscreen.pipeline.archive import reader as readers
from rockscreen.pipeline.archive.campaign import (
    part_path,
    read_failures,
    read_histories,
    read_summary,
    read_summary_table,
)
from rockscreen.pipeline.archive.lock import archive_lock, check_overwrite, lock_path
from rockscreen.pipeline.archive.schema import (
    FORMAT_VERSION,
    SUMMARY_COLUMNS,
    SUPPORTED_VERSIONS,
    TOWER_COLUMNS,
    UNITS,
)
from rockscreen.pipeline.cli import main
from rockscreen.pipeline.errors import ArchiveError

# Every public reader of the archive (pipeline.archive.reader), as a function of the path.
READERS = [getattr(readers, name) for name in readers.__all__ if name != "read_histories"]
READERS.append(lambda path: read_histories(path, "T00"))


# ----------------------------------------------------------------- a small archive


TOWER_IDS = [f"T{i:02d}" for i in range(6)]


@pytest.fixture(scope="session")
def write(write_archive):
    """Write an archive of 6 towers in chunks of 2; stop after ``stop_after`` chunks."""
    return lambda path, **options: write_archive(path, len(TOWER_IDS), chunk_size=2, **options)


@pytest.fixture(scope="module")
def base(tmp_path_factory, write):
    path = tmp_path_factory.mktemp("base") / "base.h5"
    write(path)
    return path


@pytest.fixture
def copy(base, tmp_path):
    def make(name="a.h5"):
        path = tmp_path / name
        shutil.copy(base, path)
        return path

    return make


def one_line(exc_info) -> str:
    message = str(exc_info.value)
    assert "\n" not in message and "Traceback" not in message
    return message


# ----------------------------------------------------------------- schema and versions


def test_schema_units_are_one_spelling(base):
    assert FORMAT_VERSION == "2" and SUPPORTED_VERSIONS == ("1", "2")
    units = {}

    def collect(name, obj):
        if isinstance(obj, h5py.Dataset):
            units[name] = obj.attrs["units"]

    with h5py.File(base, "r") as f:
        assert f.attrs["format_version"] == "2"
        f.visititems(collect)
    assert set(units.values()) <= UNITS and "-" not in units.values()
    assert units["towers/mu_s"] == "1" and units["towers/eta"] == "1"
    assert units["records/XX.A..HN/HNN"] == "m/s2"
    assert units["summary/lat_deg"] == "deg" and "summary/lat" not in units
    for name, (_, expected) in TOWER_COLUMNS.items():
        assert units[f"towers/{name}"] == expected, name
    for name, (_, expected) in SUMMARY_COLUMNS.items():
        assert units[f"summary/{name}"] == expected, name


def test_history_index_names_the_channel_like_the_summary(base):
    with h5py.File(base, "r") as f:
        stored = set(f["histories/index/record_id"].asstr()[:])
    assert stored <= {"XX.A..HNN", "XX.A..HNE"}
    history = read_histories(base, "T02")[0]
    assert history["record_id"] == "XX.A..HN"
    assert history["channel_id"] == "XX.A..HN" + history["component"]
    governing = {row["governing_record"] for row in read_summary(base)} - {""}
    assert governing <= stored


@pytest.mark.parametrize("reader", READERS)
def test_an_unknown_format_version_is_one_line(copy, reader):
    path = copy()
    with h5py.File(path, "r+") as f:
        f.attrs["format_version"] = "9"
    with pytest.raises(ArchiveError) as info:
        reader(path)
    assert one_line(info) == (
        f"{path}: archive format_version '9' is not supported (this rockscreen reads 1, 2)"
    )


def test_version_1_archives_are_read_with_the_new_names(copy):
    path = copy()
    with h5py.File(path, "r+") as f:
        f.attrs["format_version"] = "1"
        f.move("summary/lat_deg", "summary/lat")
        f.move("summary/lon_deg", "summary/lon")
        ids = f["histories/index/record_id"].asstr()[:]
        components = f["histories/index/component"].asstr()[:]
        del f["histories/index/record_id"]
        old = [i[: -len(c)] for i, c in zip(ids, components, strict=True)]
        f["histories/index"].create_dataset("record_id", data=old, dtype=h5py.string_dtype("utf-8"))
    rows = read_summary(path)
    assert rows[0]["lat_deg"] == 42.0 and "lat" not in rows[0]
    history = read_histories(path, "T02")[0]
    assert history["record_id"] == "XX.A..HN"
    assert history["channel_id"] == "XX.A..HN" + history["component"]


def test_inspect_of_an_unknown_version_exits_1_with_one_line(copy):
    path = copy()
    with h5py.File(path, "r+") as f:
        f.attrs["format_version"] = "9"
    for options in ([], ["--json"]):
        result = CliRunner().invoke(main, ["inspect", str(path), *options])
        assert result.exit_code == 1
        lines = result.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("rockscreen: error: ")
        assert "format_version '9' is not supported (this rockscreen reads 1, 2)" in lines[0]


def test_the_summary_table_has_text_as_str(base):
    table = read_summary_table(base)
    assert list(table["id"]) == TOWER_IDS
    assert all(type(cell) is str for cell in table["risk_class"])
    assert table["lat_deg"].dtype == np.float64
    pandas = pytest.importorskip("pandas")
    frame = pandas.DataFrame(read_summary_table(base))
    assert list(frame["id"]) == TOWER_IDS and len(frame.columns) == len(table)


# ----------------------------------------------------------------- crafted archives


def craft_external_link(f, tmp):
    (tmp / "secret.txt").write_text("SECRET-MARKER")
    with h5py.File(tmp / "secret.h5", "w") as g:
        g["id"] = np.array([b"SECRET-MARKER"])
    del f["summary/id"]
    f["summary/id"] = h5py.ExternalLink(str(tmp / "secret.h5"), "/id")


def craft_soft_link(f, tmp):
    del f["summary/name"]
    f["summary/name"] = h5py.SoftLink("/summary/id")


def craft_external_storage(f, tmp):
    (tmp / "secret.txt").write_text("SECRET-MARKER" * 10)
    del f["summary/theta_max_rad"]
    f["summary"].create_dataset(
        "theta_max_rad", shape=(6,), dtype="f8", external=[(str(tmp / "secret.txt"), 0, 48)]
    )


def craft_virtual(f, tmp):
    with h5py.File(tmp / "src.h5", "w") as g:
        g["x"] = np.arange(6.0)
    layout = h5py.VirtualLayout(shape=(6,), dtype="f8")
    layout[:] = h5py.VirtualSource(str(tmp / "src.h5"), "x", shape=(6,))
    del f["summary/alpha_rad"]
    f["summary"].create_virtual_dataset("alpha_rad", layout)


def craft_references(f, tmp):
    del f["summary/stations"]
    refs = np.array([f["towers"].ref] * 6, dtype=h5py.ref_dtype)
    f["summary"].create_dataset("stations", data=refs)


def craft_huge(f, tmp):
    del f["results/width_m"]
    f["results"].create_dataset(
        "width_m", shape=(2**40,), dtype="f8", chunks=(2**16,), compression="gzip"
    )


def craft_short_column(f, tmp):
    del f["summary/alpha_rad"]
    f["summary/alpha_rad"] = np.zeros(3)


def craft_2d_column(f, tmp):
    del f["summary/alpha_rad"]
    f["summary/alpha_rad"] = np.zeros((6, 2))


def craft_compound(f, tmp):
    del f["failures/reason"]
    f["failures/reason"] = np.zeros(1, dtype=[("a", "i4"), ("b", "f8")])


def craft_missing_table(f, tmp):
    del f["summary"]


CRAFTS = {
    "external link": (craft_external_link, "external link"),
    "soft link": (craft_soft_link, "soft link"),
    "external storage": (craft_external_storage, "external files"),
    "virtual dataset": (craft_virtual, "virtual dataset"),
    "references": (craft_references, "references"),
    "huge dataset": (craft_huge, "GiB"),
    "short column": (craft_short_column, "rows where its table has"),
    "2-D column": (craft_2d_column, "1-D"),
    "compound dtype": (craft_compound, "dtype rockscreen never writes"),
}


@pytest.mark.parametrize("name", list(CRAFTS))
def test_crafted_archives_are_refused_in_one_line(copy, tmp_path, name):
    craft, needle = CRAFTS[name]
    path = copy()
    with h5py.File(path, "r+") as f:
        craft(f, tmp_path)
    for reader in (read_summary, read_summary_table) if "column" in name else READERS:
        with pytest.raises(ArchiveError) as info:
            reader(path)
        message = one_line(info)
        assert "SECRET" not in message
    with pytest.raises(ArchiveError, match=needle):
        read_summary(path) if name != "compound dtype" else read_failures(path)


def test_a_missing_table_is_one_line(copy, tmp_path):
    path = copy()
    with h5py.File(path, "r+") as f:
        craft_missing_table(f, tmp_path)
    with pytest.raises(ArchiveError, match="table /summary is missing"):
        read_summary(path)


def test_a_history_index_pointing_outside_the_arrays_is_refused(copy):
    path = copy()
    with h5py.File(path, "r+") as f:
        f["histories/index/count"][0] = 10**9
    with pytest.raises(ArchiveError, match="points to rows"):
        read_histories(path, read_summary(path)[0]["id"])


def test_inspect_escapes_control_characters(copy):
    path = copy()
    with h5py.File(path, "r+") as f:
        ids = f["summary/id"].asstr()[:]
        ids[0] = "X\x1b]0;pwned\x07"
        del f["summary/id"]
        f["summary"].create_dataset("id", data=ids, dtype=h5py.string_dtype("utf-8"))
        f.attrs["command_line"] = "run \x1b[2J"
    result = CliRunner().invoke(main, ["inspect", str(path)])
    assert result.exit_code == 0, result.output
    assert "\x1b" not in result.stdout and "\x07" not in result.stdout
    assert "X\\x1b]0;pwned\\x07" in result.stdout and "run \\x1b[2J" in result.stdout


# ----------------------------------------------------------------- damaged work files


def test_a_truncated_work_file_is_discarded_not_resumed(tmp_path, write):
    path = tmp_path / "out.h5"
    write(path, stop_after=2)
    part = part_path(path)
    data = part.read_bytes()
    part.write_bytes(data[: len(data) // 2])
    writer = write(path)
    assert not writer.resumed and writer.discarded
    assert [row["id"] for row in read_summary(path)] == TOWER_IDS


def test_a_sound_work_file_is_resumed(tmp_path, write):
    path = tmp_path / "out.h5"
    write(path, stop_after=1)
    verdict, reason = resume.verify_part(part_path(path), "abc")
    assert verdict is not None and reason == "" and len(verdict["done"]) == 2
    assert resume.verify_part(part_path(path), "other")[0] is None
    writer = write(path)
    assert writer.resumed and not writer.discarded
    assert len(read_summary(path)) == len(TOWER_IDS)


def test_a_check_that_crashes_libhdf5_discards_the_work_file(tmp_path, monkeypatch, write):
    path = tmp_path / "out.h5"
    write(path, stop_after=1)

    def segfault(command, **kwargs):
        return subprocess.CompletedProcess(command, -signal.SIGSEGV, "", "")

    monkeypatch.setattr(resume.subprocess, "run", segfault)
    verdict, reason = resume.verify_part(part_path(path), "abc")
    assert verdict is None and reason == "reading it crashed the HDF5 library (SIGSEGV)"
    writer = write(path)
    assert not writer.resumed and "SIGSEGV" in writer.discarded
    assert len(read_summary(path)) == len(TOWER_IDS)


def test_the_check_runs_in_a_child_process(tmp_path, write):
    path = tmp_path / "out.h5"
    write(path, stop_after=1)
    command = [
        sys.executable,
        "-m",
        "rockscreen.pipeline.archive.resume",
        str(part_path(path)),
        "abc",
    ]
    out = subprocess.run(command, capture_output=True, text=True, timeout=120, check=True)
    assert '"ok": true' in out.stdout


# ----------------------------------------------------------------- full disk


def test_too_little_space_for_a_chunk_is_one_line_and_keeps_the_part(tmp_path, monkeypatch, write):
    path = tmp_path / "out.h5"
    real = shutil.disk_usage

    def nearly_full(folder):
        return real(folder)._replace(free=1000)

    writer = write(path, stop_after=1)
    monkeypatch.setattr(campaign.shutil, "disk_usage", nearly_full)
    with pytest.raises(ArchiveError) as info:
        write(path)
    message = one_line(info)
    assert message.startswith(f"{path}: not enough disk space for the next chunk")
    assert "MB more" in message and "is kept: rerun to resume" in message
    assert part_path(path).exists() and not path.exists() and writer.done
    monkeypatch.undo()
    assert write(path).resumed and len(read_summary(path)) == len(TOWER_IDS)


def test_a_write_failing_with_enospc_is_one_line(tmp_path, monkeypatch, write):
    path = tmp_path / "out.h5"
    write(path, stop_after=1)

    def no_space(*args, **kwargs):
        raise OSError(28, "Can't write data (file write failed: errno = 28, No space left)")

    monkeypatch.setattr(campaign, "_append_table", no_space)
    with pytest.raises(ArchiveError) as info:
        write(path)
    message = one_line(info)
    assert message.startswith(f"{path}: not enough disk space for the archive")
    # Nothing was written by the failed append: the committed rows are sound, kept.
    assert "is kept: rerun to resume" in message and part_path(path).exists()


# ----------------------------------------------------------------- overwrite and lock


def test_an_archive_of_another_campaign_is_not_overwritten(base, tmp_path):
    path = tmp_path / "a.h5"
    shutil.copy(base, path)
    check_overwrite(path, "abc")  # the same campaign: a rerun may replace it
    check_overwrite(tmp_path / "absent.h5", "xyz")
    with pytest.raises(ArchiveError) as info:
        check_overwrite(path, "fedcba987654321", inventory_source="other.csv")
    message = one_line(info)
    assert "holds another campaign (created " in message
    assert "inventory towers.csv, fingerprint abc" in message
    assert "than this run (inventory other.csv, fingerprint fedcba987654)" in message
    check_overwrite(path, "xyz", overwrite=True)
    (tmp_path / "notes.h5").write_text("my notes")
    with pytest.raises(ArchiveError, match="is not a readable rockscreen archive"):
        check_overwrite(tmp_path / "notes.h5", "abc")


def test_a_second_run_on_the_same_out_stops_at_once(tmp_path):
    path = tmp_path / "out.h5"
    with archive_lock(path, "run") as lock:
        pid, command = lock.read_text().splitlines()
        assert lock == lock_path(path) and pid == str(os.getpid()) and command == "run"
        with pytest.raises(ArchiveError) as info:
            with archive_lock(path):
                pass
        assert one_line(info) == (
            f"another rockscreen run is writing {path} (pid {pid} holds the lock file "
            f"{lock}); wait for it to end or stop it (kill {pid}), or choose another --out"
        )
    assert not lock_path(path).exists()
    with archive_lock(path):
        pass


def test_the_lock_of_a_killed_run_does_not_block(tmp_path):
    path = tmp_path / "out.h5"
    code = (
        "import sys, time\n"
        "from rockscreen.pipeline.archive.lock import archive_lock\n"
        "with archive_lock(sys.argv[1]):\n"
        "    print('locked', flush=True)\n"
        "    time.sleep(3600)\n"
    )
    holder = subprocess.Popen(
        [sys.executable, "-c", code, str(path)], stdout=subprocess.PIPE, text=True
    )
    try:
        assert holder.stdout.readline().strip() == "locked"
        with pytest.raises(ArchiveError, match=f"pid {holder.pid}"):
            with archive_lock(path):
                pass
        holder.kill()
        holder.wait(timeout=120)
        assert lock_path(path).exists()  # left behind by the killed run
        with archive_lock(path):
            pass
    finally:
        if holder.poll() is None:
            holder.kill()
            holder.wait()
        holder.stdout.close()


@pytest.mark.parametrize("column", ["id", "risk_class"])
def test_a_summary_without_a_required_column_is_one_line(copy, column):
    path = copy()
    with h5py.File(path, "r+") as f:
        del f[f"summary/{column}"]
    with pytest.raises(ArchiveError, match=f"table /summary lacks column\\(s\\) {column}"):
        read_summary(path)
    result = CliRunner().invoke(main, ["inspect", str(path)])
    assert result.exit_code == 1 and len(result.stderr.strip().splitlines()) == 1


def test_a_fifo_is_refused_without_blocking(tmp_path):
    fifo = tmp_path / "x.h5"
    os.mkfifo(fifo)
    for command in (["inspect", str(fifo)], ["export", str(fifo), "--csv", "o.csv"]):
        result = CliRunner().invoke(main, command)
        assert result.exit_code == 1 and "is not a regular file" in result.stderr
