"""Issue 24 (items 1, 3, 4): no command destroys a file, none says "done" when nothing was
done, and the inventory's small traps. The command line runs as a real subprocess."""

from __future__ import annotations

import hashlib
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

from rockscreen.pipeline.archive.lock import archive_lock
from rockscreen.pipeline.archive.risk_archive import write_risk_archive
from rockscreen.pipeline.motion.synthetic import write_example_records
from rockscreen.pipeline.risk.assess.sites import tower_sites
from rockscreen.pipeline.risk.assess.tower_summary import base_summary_row
from rockscreen.pipeline.risk.scenario.example_shakemap import write_example_grid
from rockscreen.stations.errors import InventoryError
from rockscreen.stations.inventory import Tower, read_inventory

from rockscreen_testsupport.cli import run_rockscreen

STUDY = Path(__file__).parents[2] / "examples" / "seed_study" / "single_block.toml"
TOWERS = "id,width_m,height_m,lat,lon\nA,3,20,41.04,14.42\nB,2,10,41.10,14.50\n"


def _one_error_line(done: subprocess.CompletedProcess) -> str:
    """The refusal: exit 1, one error line, last on stderr (progress lines may precede it)."""
    lines = [line for line in done.stderr.splitlines() if line.strip()]
    errors = [line for line in lines if line.startswith("rockscreen: error: ")]
    assert done.returncode == 1, done.stderr
    assert errors == lines[-1:] and "Traceback" not in done.stderr, done.stderr
    return errors[0]


def _digests(folder: Path) -> dict[str, str]:
    return {
        str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
        for p in sorted(folder.rglob("*"))
        if p.is_file()
    }


def _assess_archive(path: Path, towers: list[Tower]) -> Path:
    rows = [base_summary_row(site) for site in tower_sites(towers, 0.01)]
    for row in rows:
        row.update(fragility_median_g=0.3, fragility_beta=0.3, tr_slv_y=712.0)
    write_risk_archive(path, "assess", {"summary": rows}, {})
    return path


@pytest.fixture
def folder(tmp_path):
    """Inputs of every writing command, and an archive of another kind (``other.h5``)."""
    (tmp_path / "towers.csv").write_text(TOWERS)
    write_example_records(tmp_path / "records")
    write_example_grid(tmp_path / "grid.xml")
    shutil.copy(STUDY, tmp_path / "study.toml")
    towers = read_inventory(tmp_path / "towers.csv")
    _assess_archive(tmp_path / "assess.h5", towers)
    write_risk_archive(tmp_path / "other.h5", "scenario", {"summary": [{"id": "Z"}]}, {})
    return tmp_path


def _commands(folder: Path) -> dict[str, list[str]]:
    """Every command that writes a file, with its inputs; ``--out`` is appended."""
    records = sorted(str(p.relative_to(folder)) for p in (folder / "records").iterdir())
    xml = [r for r in records if r.endswith(".xml")]
    records = [r for r in records if not r.endswith(".xml")]
    return {
        "run": ["run", *records, "--stations", *xml, "--towers", "towers.csv"],
        "assess": ["assess", "--towers", "towers.csv", "--return-periods", "475"],
        "scenario": ["scenario", "--shakemap", "grid.xml", "--fragility", "assess.h5"],
        "sweep": ["sweep", "study.toml"],
    }


@pytest.mark.parametrize("command", ["run", "assess", "scenario", "sweep"])
def test_no_command_replaces_another_archive_or_its_own_input(folder, command):
    args = _commands(folder)[command]
    before = _digests(folder)
    refused = _one_error_line(run_rockscreen(*args, "--out", "other.h5", cwd=folder))
    assert "other.h5" in refused and ("--overwrite" in refused or "another campaign" in refused)
    inputs = [a for a in args[1:] if (folder / a).is_file()]
    for own in inputs:
        for extra in ([], ["--overwrite"]):
            done = run_rockscreen(*args, "--out", own, *extra, cwd=folder)
            line = _one_error_line(done)
            assert f"--out {own} is also an input" in line
    assert _digests(folder) == before


def test_exports_reports_and_plots_never_replace_an_archive(folder):
    before = _digests(folder)
    for args in (
        ["export", "assess.h5", "--csv", "assess.h5"],
        ["export", "assess.h5", "--geojson", "other.h5"],
        ["report", "assess.h5", "--out", "other.h5"],
        ["plot", "assess.h5", "--map", "--out", "assess.h5"],
    ):
        line = _one_error_line(run_rockscreen(*args, cwd=folder))
        assert "refused" in line
    assert _digests(folder) == before


def test_assess_checks_its_output_before_any_work(folder):
    start = time.monotonic()
    line = _one_error_line(
        run_rockscreen(*_commands(folder)["assess"], "--out", "no/x.h5", cwd=folder)
    )
    assert "folder" in line and "does not exist" in line
    assert time.monotonic() - start < 60
    with archive_lock(folder / "busy.h5"):
        busy = run_rockscreen(*_commands(folder)["assess"], "--out", "busy.h5", cwd=folder)
    assert "another rockscreen process is writing busy.h5" in _one_error_line(busy)


_HOLDER = (
    "import sys, time\n"
    "from rockscreen.pipeline.archive.lock import archive_lock\n"
    "with archive_lock(sys.argv[1], sys.argv[2]):\n"
    "    print('locked', flush=True)\n"
    "    time.sleep(3600)\n"
)


@pytest.mark.parametrize("command", ["assess", "scenario", "sweep", "run"])
def test_a_busy_output_names_the_command_its_pid_the_lock_file_and_what_to_do(folder, command):
    holder = subprocess.Popen(
        [sys.executable, "-c", _HOLDER, "busy.h5", command],
        cwd=folder,
        stdout=subprocess.PIPE,
        text=True,
    )
    try:
        assert holder.stdout.readline().strip() == "locked"
        busy = run_rockscreen(*_commands(folder)[command], "--out", "busy.h5", cwd=folder)
    finally:
        holder.kill()
        holder.wait(timeout=60)
        holder.stdout.close()
    assert _one_error_line(busy) == (
        f"rockscreen: error: another rockscreen {command} is writing busy.h5 (pid {holder.pid} "
        f"holds the lock file busy.h5.lock); wait for it to end or stop it (kill {holder.pid}), "
        "or choose another --out"
    )
    assert not (folder / "busy.h5").exists()


def test_return_periods_outside_the_table_are_a_usage_error(folder):
    args = ["assess", "--towers", "towers.csv", "--return-periods", "30,50,5000"]
    done = run_rockscreen(*args, cwd=folder)
    assert done.returncode == 2 and "5000 outside the allowed range 30-2475" in done.stderr
    assert not (folder / "rockscreen-assess.h5").exists()


@pytest.mark.parametrize("count", ["0", "-1", "1000000"])
def test_hazard_record_count_is_bounded(folder, count):
    args = ["hazard", "--lon", "13.4", "--lat", "42.35", "--suite", "synthetic"]
    done = run_rockscreen(*args, "--n-records", count, cwd=folder)
    assert done.returncode == 2 and "1<=x<=100" in done.stderr


def test_a_shakemap_covering_no_tower_fails_with_one_line(folder):
    far = [Tower(id=f"F{i}", width_m=2, height_m=10, lat=46.5, lon=12.0 + i) for i in range(2)]
    _assess_archive(folder / "far.h5", far)
    done = run_rockscreen("scenario", "--shakemap", "grid.xml", "--fragility", "far.h5", cwd=folder)
    line = _one_error_line(done)
    assert "covers none of the 2 towers" in line
    assert not (folder / "rockscreen-scenario.h5").exists()


def test_many_unknown_tower_ids_are_named_a_few_and_counted(folder):
    ids = ",".join(f"NOPE-{i:06d}" for i in range(8000))
    args = ["scenario", "--shakemap", "grid.xml", "--fragility", "assess.h5", "--towers", ids]
    line = _one_error_line(run_rockscreen(*args, cwd=folder))
    assert "'NOPE-000000'" in line and "and 7995 more" in line and len(line) < 400


def test_event_text_is_printable(folder):
    text = (folder / "grid.xml").read_text()
    evil = '<event event_id="X&#x9b;31mRED&#x202e;"'  # C1 CSI, a bidi override (XML allows)
    text = text.replace('<event event_id="rockscreen-example"', evil, 1)
    (folder / "evil.xml").write_text(text)
    done = run_rockscreen(
        "scenario", "--shakemap", "evil.xml", "--fragility", "assess.h5", cwd=folder
    )
    assert done.returncode == 0, done.stderr
    assert "\x9b" not in done.stdout and "\u202e" not in done.stdout
    assert "X\\x9b31mRED\\u202e" in done.stdout


def test_a_swapped_tower_is_called_so(folder):
    done = run_rockscreen("hazard", "--lon", "42.35", "--lat", "13.40", cwd=folder)
    assert "lat/lon swapped?" in _one_error_line(done)


@pytest.mark.parametrize(
    ("first", "second"),
    [
        ("Torre", "TORRE"),
        ("Citt\u00e0", "Citta\u0300"),
        ("T1", "\uff34\uff11"),
        ("Stra\u00dfe", "STRASSE"),
    ],
)
def test_ids_equal_up_to_case_or_unicode_form_are_duplicates(tmp_path, first, second):
    path = tmp_path / "t.csv"
    path.write_text(f"id,width_m,height_m\n{first},3,20\n{second},3,20\n", encoding="utf-8")
    with pytest.raises(InventoryError, match=r"row 2 .*duplicate .*equal up to case .* row 1"):
        read_inventory(path)


@pytest.mark.parametrize("value", ["1_0", "\uff13", "\u0663", "0x10"])
def test_only_ascii_numbers_are_numbers(tmp_path, value):
    path = tmp_path / "t.csv"
    path.write_text(f"id,width_m,height_m\nA,3,{value}\n", encoding="utf-8")
    with pytest.raises(InventoryError, match="height_m.*is not a number"):
        read_inventory(path)


def test_a_symbolic_link_loop_among_the_inputs_is_no_traceback(tmp_path):
    """Reliability audit, area 1: a looping link given as a record reached check_output."""
    from rockscreen.pipeline.archive.lock import check_output

    loop = tmp_path / "loopA.mseed"
    loop.symlink_to(tmp_path / "loopB.mseed")
    (tmp_path / "loopB.mseed").symlink_to(loop)
    assert check_output(tmp_path / "out.h5", [loop]) == tmp_path / "out.h5"
    paths, xml = write_example_records(tmp_path / "rec")
    (tmp_path / "towers.csv").write_text(TOWERS)
    done = run_rockscreen(
        "run",
        *paths,
        loop,
        "--stations",
        xml,
        "--towers",
        "towers.csv",
        "--jobs",
        "1",
        cwd=tmp_path,
    )
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr
    assert f"rockscreen: skipped {loop}: symbolic link loop" in done.stderr.splitlines()
