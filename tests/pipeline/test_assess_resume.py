"""``rockscreen assess`` keeps finished towers in ``OUT.part`` and resumes (issue 24).

A real child process is stopped from outside (SIGKILL, SIGTERM) at a known point: the
helper ``kill_after_chunks.py N:pause READY`` creates ``READY`` once the work file holds N
committed towers and waits, so the test never races the run. The same command then resumes
and its archive equals an uninterrupted run's, dataset by dataset, attribute by attribute,
but for :data:`~rockscreen.pipeline.risk.assess.batch.RUN_ATTRIBUTES` (when it was written and how
long it took). Other inputs are refused with the difference named and the ``.part`` kept.
"""

from __future__ import annotations

import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import h5py
import numpy as np
import pytest

from rockscreen.pipeline.archive.assess_part import part_path
from rockscreen.pipeline.archive.kept_rows import decode_result, encode_result
from rockscreen.pipeline.archive.risk_reader import read_inventory
from rockscreen.pipeline.risk.assess.batch import RUN_ATTRIBUTES

KILL_AFTER_CHUNKS = Path(__file__).with_name("kill_after_chunks.py")
#: Three towers on one site: one chunk per tower with one job, a few seconds in all.
INVENTORY = (
    "id,name,lat,lon,width_m,height_m\n"
    "T1,one,41.04,14.42,2.06,5.80\n"
    "T2,two,41.04,14.42,2.4,9.0\n"
    "T3,three,41.04,14.42,2.6,14.0\n"
)
ARGS = [
    "assess",
    "--towers",
    "towers.csv",
    "--return-periods",
    "475",
    "--bootstrap",
    "0",
    "--models",
    "ground",
    "--jobs",
    "1",
]


def _folder(base: Path, name: str) -> Path:
    folder = base / name
    folder.mkdir()
    (folder / "towers.csv").write_text(INVENTORY)
    return folder


def _rockscreen(folder: Path, *extra: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "rockscreen.pipeline", *ARGS, *extra],
        cwd=folder,
        capture_output=True,
        text=True,
        timeout=600,
    )


def _stopped(folder: Path, signum: int, after: int = 1) -> subprocess.CompletedProcess:
    """Start the assess, wait until its work file holds ``after`` towers, send ``signum``."""
    ready = folder / "ready"
    proc = subprocess.Popen(
        [sys.executable, str(KILL_AFTER_CHUNKS), f"{after}:pause", str(ready), *ARGS],
        cwd=folder,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    deadline = time.monotonic() + 300
    while not ready.exists() and proc.poll() is None and time.monotonic() < deadline:
        time.sleep(0.05)
    assert ready.exists(), proc.communicate(timeout=60)
    proc.send_signal(signum)
    stdout, stderr = proc.communicate(timeout=120)
    ready.unlink()
    return subprocess.CompletedProcess(proc.args, proc.returncode, stdout, stderr)


def _contents(path: Path) -> dict:
    """Every dataset's values and attributes and every group's attributes, by HDF5 path."""
    out = {}
    with h5py.File(path, "r") as f:
        out["/"] = {k: v for k, v in f.attrs.items() if k not in RUN_ATTRIBUTES}

        def visit(name, obj):
            attrs = dict(obj.attrs)
            if isinstance(obj, h5py.Dataset):
                out[name] = (obj.dtype.str, obj[()], attrs)
            else:
                out[name] = attrs

        f.visititems(visit)
    return out


def _assert_same_archive(reference: Path, other: Path) -> None:
    a, b = _contents(reference), _contents(other)
    assert sorted(a) == sorted(b)
    for name in a:
        if isinstance(a[name], tuple):
            (dtype_a, data_a, attrs_a), (dtype_b, data_b, attrs_b) = a[name], b[name]
            assert dtype_a == dtype_b, name
            assert np.shape(data_a) == np.shape(data_b), name
            equal_nan = np.asarray(data_a).dtype.kind == "f"
            assert np.array_equal(data_a, data_b, equal_nan=equal_nan), name
            assert attrs_a == attrs_b, name
        else:
            assert {k: str(v) for k, v in a[name].items()} == {
                k: str(v) for k, v in b[name].items()
            }, name


@pytest.fixture(scope="module")
def reference(tmp_path_factory):
    """An uninterrupted assess: its folder and its process."""
    folder = _folder(tmp_path_factory.mktemp("assess-resume"), "reference")
    done = _rockscreen(folder)
    assert done.returncode == 0, done.stderr
    assert not part_path(folder / "rockscreen-assess.h5").exists()
    # the towers as read are kept (/inventory): the resumed archives must equal it too
    stored = read_inventory(folder / "rockscreen-assess.h5")
    assert [(t["id"], t["width_m"]) for t in stored] == [("T1", 2.06), ("T2", 2.4), ("T3", 2.6)]
    return folder, done


@pytest.mark.slow
@pytest.mark.parametrize("signum", [signal.SIGKILL, signal.SIGTERM])
def test_a_stopped_assess_resumes_to_the_same_archive(tmp_path, reference, signum):
    ref_folder, ref = reference
    folder = _folder(tmp_path, "stopped")
    archive, part = folder / "rockscreen-assess.h5", part_path(folder / "rockscreen-assess.h5")
    stopped = _stopped(folder, signum)
    if signum == signal.SIGKILL:
        assert stopped.returncode == -signal.SIGKILL
    else:  # one line saying what is kept, exit 128 + 15
        assert stopped.returncode == 128 + signal.SIGTERM, stopped.stderr
        last = stopped.stderr.strip().splitlines()[-1]
        assert last == (
            f"rockscreen: interrupted (SIGTERM): the 1 tower(s) assessed so far are kept in "
            f"{part.name}; rerun the same command to resume"
        )
        assert "Traceback" not in stopped.stderr
    assert part.is_file() and not archive.exists()
    with h5py.File(part, "r") as f:
        assert int(f.attrs["committed"]) == 1
    resumed = _rockscreen(folder)
    assert resumed.returncode == 0, resumed.stderr
    assert f"resuming {part.name}: 1 of 3 tower(s) already assessed" in resumed.stderr
    assert "towers: 1/3 assessed (kept in the work file)" in resumed.stderr
    assert not part.exists()
    assert resumed.stdout == ref.stdout
    _assert_same_archive(ref_folder / "rockscreen-assess.h5", archive)


@pytest.mark.slow
@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="finds the workers in /proc")
def test_a_lost_worker_keeps_the_finished_towers_and_the_rerun_resumes(tmp_path, reference):
    ref_folder, ref = reference
    folder = _folder(tmp_path, "lost")
    part = part_path(folder / "rockscreen-assess.h5")
    args = [a if a != "1" or i != ARGS.index("--jobs") + 1 else "2" for i, a in enumerate(ARGS)]
    lost = subprocess.run(
        [sys.executable, str(KILL_AFTER_CHUNKS), "1:workers", *args],
        cwd=folder,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert lost.returncode == 1, lost.stderr
    last = lost.stderr.strip().splitlines()[-1]
    assert re.fullmatch(
        rf"rockscreen: error: a worker process died \(.+\); the [12] tower\(s\) assessed so "
        rf"far are kept in {re.escape(part.name)}; rerun the same command to resume",
        last,
    ), lost.stderr
    assert "Traceback" not in lost.stderr and part.is_file()
    resumed = _rockscreen(folder)
    assert resumed.returncode == 0, resumed.stderr
    assert re.search(r"resuming .*: [12] of 3 tower\(s\) already assessed", resumed.stderr)
    assert resumed.stdout == ref.stdout
    _assert_same_archive(ref_folder / "rockscreen-assess.h5", folder / "rockscreen-assess.h5")


@pytest.mark.slow
def test_other_inputs_are_refused_with_the_difference_named_and_the_part_kept(tmp_path):
    folder = _folder(tmp_path, "other")
    assert _stopped(folder, signal.SIGKILL).returncode == -signal.SIGKILL
    part = part_path(folder / "rockscreen-assess.h5")
    before = part.read_bytes()

    options = _rockscreen(folder, "--records", "8")
    assert options.returncode == 1
    lines = options.stderr.strip().splitlines()
    assert lines[-1].startswith(f"rockscreen: error: {part.name} holds 1 tower(s) of an assess")
    assert "options selection.n_records: 11 in the .part, 8 now" in lines[-1]
    assert "the file is kept" in lines[-1] and "--overwrite" in lines[-1]
    assert part.read_bytes() == before

    (folder / "towers.csv").write_text(INVENTORY.replace("2.06", "2.1"))
    inventory = _rockscreen(folder)
    assert inventory.returncode == 1
    assert "inventory content (towers.csv)" in inventory.stderr
    assert part.read_bytes() == before

    # --overwrite discards it (said) and starts afresh.
    fresh = _rockscreen(folder, "--overwrite")
    assert fresh.returncode == 0, fresh.stderr
    assert f"discarded {part.name}: it holds towers of other inputs" in fresh.stderr
    assert not part.exists()


def test_a_part_that_is_not_an_assess_work_file_is_refused_and_kept(tmp_path):
    folder = _folder(tmp_path, "foreign")
    part = part_path(folder / "rockscreen-assess.h5")
    part.write_text("my notes\n")
    done = _rockscreen(folder)
    assert done.returncode == 1
    assert "is not a work file of rockscreen assess; refused" in done.stderr
    assert part.read_text() == "my notes\n"


def test_the_work_file_codec_keeps_every_value_exactly():
    value = {
        "index": np.int64(3),
        "row": {"id": "T1", "p": np.float64(0.1) + 0.2, "nan": float("nan"), "ok": np.bool_(True)},
        "rows": [(1, "a", None), {"inf": -np.inf}],
        "array": np.arange(3, dtype=np.float32),
        "keyed": {(1.5, "B"): 2, 475.0: "x"},
    }
    back = decode_result(encode_result(value))
    assert back["index"] == 3 and type(back["index"]) is int
    assert back["row"]["p"] == 0.1 + 0.2 and np.isnan(back["row"]["nan"])
    assert back["row"]["ok"] is True
    assert back["rows"] == [(1, "a", None), {"inf": -np.inf}]
    assert back["array"].dtype == np.float32 and back["array"].tolist() == [0.0, 1.0, 2.0]
    assert back["keyed"] == {(1.5, "B"): 2, 475.0: "x"}
    assert encode_result(back) == encode_result(value)


def test_the_work_file_changes_no_value_of_the_archive(tmp_path):
    """Towers read back from the work file write the archive that the computed ones write."""
    from rockscreen.pipeline.archive.assess_part import AssessJournal
    from rockscreen.pipeline.archive.risk_archive import write_risk_archive
    from rockscreen.pipeline.execution.choose import open_executor
    from rockscreen.pipeline.risk.assess.run import AssessOptions, run_assess
    from rockscreen.pipeline.risk.assess.stripes import StripeOptions
    from rockscreen.stations.inventory import read_inventory

    (tmp_path / "towers.csv").write_text(INVENTORY.split("T2")[0].rstrip("\n") + "\n")
    towers = read_inventory(tmp_path / "towers.csv")
    options = AssessOptions(
        return_periods_y=(475.0,),
        stripe=StripeOptions(models=("ground",)),
        selection={"n_records": 7},
        bootstrap_resamples=20,
    )

    def tables(result):
        names = ("summary", "stripes", "outcomes", "selection", "failures", "ida")
        return {name: getattr(result, name) for name in names}

    direct = run_assess(towers, options, open_executor(jobs=1)[0])
    with AssessJournal(tmp_path / "x.h5", {"test": 1}) as journal:
        kept = run_assess(towers, options, open_executor(jobs=1)[0], journal=journal)
    assert direct.ida and direct.summary[0]["id"] == "T1"
    for name, result in (("direct.h5", direct), ("kept.h5", kept)):
        write_risk_archive(tmp_path / name, "assess", tables(result), {})
    _assert_same_archive(tmp_path / "direct.h5", tmp_path / "kept.h5")


def _result(index: int) -> dict:
    return {"index": index, "row": {"id": f"T{index}", "x": 0.1 * index}, "n_solves": 3}


def test_a_full_disk_while_keeping_towers_is_one_line_and_the_rest_is_kept(tmp_path, monkeypatch):
    from rockscreen.pipeline.archive.assess_part import AssessJournal
    from rockscreen.pipeline.errors import ArchiveError

    out = tmp_path / "a.h5"
    with AssessJournal(out, {"v": 1}) as journal:
        journal.append([_result(0)])

        def full(self, *args):
            raise OSError(28, "No space left on device")

        monkeypatch.setattr(h5py.Dataset, "resize", full)
        with pytest.raises(ArchiveError) as info:
            journal.append([_result(1)])
    monkeypatch.undo()
    assert str(info.value) == (
        f"{part_path(out)}: the disk is full; the 1 tower(s) committed before are kept: free "
        "space and rerun to resume"
    )
    again = AssessJournal(out, {"v": 1})
    without_row = {k: v for k, v in _result(0).items() if k != "row"}
    assert again.resumed and list(again.done) == [0] and again.done[0] == without_row
    assert again.rows([0]) == [_result(0)["row"]]  # the summary row stays in the file


def test_a_damaged_work_file_of_assess_is_discarded_and_said(tmp_path):
    from rockscreen.pipeline.archive.assess_part import AssessJournal

    out = tmp_path / "a.h5"
    with AssessJournal(out, {"v": 1}) as journal:
        journal.append([_result(0), _result(1)])
    data = part_path(out).read_bytes()
    part_path(out).write_bytes(data[: len(data) // 3])  # killed while the file was written
    again = AssessJournal(out, {"v": 1})
    assert not again.resumed and again.done == {} and again.discarded
    assert part_path(out).is_file()  # a fresh one


def test_a_work_file_of_another_layout_is_discarded_and_said(tmp_path):
    """A work file written by a rockscreen whose tower results had another layout (part
    version 1: every risk sample kept) is not resumed: its towers are computed again."""
    from rockscreen.pipeline.archive.assess_part import PART_VERSION, AssessJournal

    out = tmp_path / "a.h5"
    with AssessJournal(out, {"v": 1}) as journal:
        journal.append([_result(0), _result(1)])
    assert AssessJournal(out, {"v": 1}).resumed  # the same layout: resumed
    with h5py.File(part_path(out), "r+") as f:
        f.attrs["part_version"] = "1"
    again = AssessJournal(out, {"v": 1})
    assert not again.resumed and again.done == {}
    assert again.discarded == (
        "it was written in another layout of the work file (part_version 1; this rockscreen "
        f"writes {PART_VERSION})"
    )
    with h5py.File(part_path(out), "r") as f:  # a fresh one, of this layout
        assert f.attrs["committed"] == 0 and f.attrs["part_version"] == PART_VERSION


def test_a_tower_whose_result_fails_its_checksum_is_never_resumed(tmp_path):
    from rockscreen.pipeline.archive.assess_part import AssessJournal

    out = tmp_path / "a.h5"
    with AssessJournal(out, {"v": 1}) as journal:
        journal.append([_result(0), _result(1)])
    with h5py.File(part_path(out), "r+") as f:  # a torn write: valid JSON, other content
        texts = f["towers/result"].asstr()[:]
        f["towers/result"][1] = texts[1].replace("0.1", "0.2")
    again = AssessJournal(out, {"v": 1})
    assert not again.resumed and again.discarded == "tower 2's result fails its checksum"


#: Issue 30: six towers at six sites on a 0.02 deg lattice around L'Aquila (soil B).
REGION = "id,lat,lon,width_m,height_m,soil_class\n" + "".join(
    f"AQ{i},{42.34 + 0.02 * (i % 2):.2f},{13.38 + 0.02 * (i // 2):.2f},{2.0 + 0.2 * i:.1f},"
    f"{8.0 + i:.1f},B\n"
    for i in range(6)
)


@pytest.mark.slow
def test_a_killed_multi_site_assess_resumes_to_the_archive_of_an_uninterrupted_run(tmp_path):
    folders = {}
    for name in ("reference", "killed"):
        folders[name] = tmp_path / name
        folders[name].mkdir()
        (folders[name] / "towers.csv").write_text(REGION)
    extra = ("--records", "7")
    reference = _rockscreen(folders["reference"], *extra)
    assert reference.returncode == 0, reference.stderr
    assert "6 tower(s), 6 site(s)" in reference.stderr
    folder = folders["killed"]
    part = part_path(folder / "rockscreen-assess.h5")
    killed = subprocess.run(
        [sys.executable, str(KILL_AFTER_CHUNKS), "2", *ARGS, *extra],
        cwd=folder,
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert killed.returncode == -signal.SIGKILL, killed.stderr
    with h5py.File(part, "r") as f:
        assert int(f.attrs["committed"]) == 2
    resumed = _rockscreen(folder, *extra)
    assert resumed.returncode == 0, resumed.stderr
    assert f"resuming {part.name}: 2 of 6 tower(s) already assessed" in resumed.stderr
    assert not part.exists()
    assert resumed.stdout == reference.stdout
    _assert_same_archive(
        folders["reference"] / "rockscreen-assess.h5", folder / "rockscreen-assess.h5"
    )
