"""`rockscreen run` answers that cannot silently mislead (issue 12)."""

from __future__ import annotations

import math
import os
import signal
import sys
from types import SimpleNamespace

import numpy as np
import pytest

from rockscreen.pipeline.archive.campaign import part_path, read_summary
from rockscreen.pipeline.config import config_from_mapping
from rockscreen.pipeline.engine.motion import GroundMotion
from rockscreen.pipeline.engine.search import vertical_limit_factor
from rockscreen.pipeline.engine.solvers import Solvers
from rockscreen.pipeline.screening.cases import CampaignShared, TowerTask
from rockscreen.pipeline.screening.evaluate import evaluate_tower
from rockscreen.solver.constants import G
from rockscreen.stations.inventory import Tower, example_inventory_path


def test_records_without_an_inventory_never_use_the_example_towers(tmp_path, rockscreen, run_args):
    result = rockscreen(*run_args(towers=None, jobs=None))
    assert result.exit_code == 1
    assert "no tower inventory" in result.stderr and "--towers" in result.stderr
    assert "ARC-08" not in result.stdout
    assert not (tmp_path / "rockscreen.h5").exists()


def test_missing_stations_file_is_reported_before_reading_records(rockscreen, run_args):
    result = rockscreen(*run_args(stations="nope.xml", jobs=None))
    assert result.exit_code == 1
    assert "nope.xml" in result.stderr and "no such file" in result.stderr


def test_towers_with_coordinates_and_stations_without_are_warned_and_labelled(
    tmp_path, rockscreen, run_args
):
    # miniSEED carries no coordinates: without StationXML every tower gets every station.
    result = rockscreen(*run_args("--units", "m/s2", stations=None))
    assert result.exit_code == 0, result.output
    assert "no record station has any" in result.stderr
    rows = [r for r in read_summary(tmp_path / "rockscreen.h5") if r["risk_class"] != "unknown"]
    implicit = [r for r in rows if not r["pairing"].startswith("explicit")]
    assert implicit
    assert all(row["pairing"].startswith("every station") for row in implicit)
    assert all("paired with every station" in row["note"] for row in implicit)
    assert "all stations" in result.stdout


def test_pairing_distance_is_in_the_summary(tmp_path, rockscreen):
    result = rockscreen("run", "--example", "--jobs", "1")
    assert result.exit_code == 0, result.output
    rows = read_summary(tmp_path / "rockscreen-example.h5")
    assert any(row["pairing"].startswith("nearest station") for row in rows)
    for row in rows:
        assert row["pairing"].startswith(("nearest station", "explicit station"))
        if math.isfinite(row["lat_deg"]):
            assert 0.0 <= row["pairing_distance_km"] <= 50.0
        else:
            assert math.isnan(row["pairing_distance_km"])
    assert "pairing [km]" in result.stdout.splitlines()[0]
    # The legend explains classes, safety factor and components (stderr, under the table).
    assert "risk classes" in result.stderr and "components: X" in result.stderr


def test_quiet_prints_only_the_table_and_warnings(rockscreen):
    result = rockscreen("run", "--example", "--jobs", "1", "--quiet")
    assert result.exit_code == 0, result.output
    assert result.stderr == ""
    assert result.stdout.startswith("tower")


def _motion(vertical_peak_down: float) -> GroundMotion:
    t = np.arange(2000) * 0.01
    shape = np.sin(2 * np.pi * 1.0 * t) * np.exp(-(((t - 8.0) / 2.0) ** 2))
    vertical = -vertical_peak_down * np.abs(shape)
    return GroundMotion(
        "XX.A..HN",
        "XX.A",
        0.01,
        ("HNN", "HNE"),
        (3.0 * shape, 3.0 * shape),
        (0.0, 90.0),
        vertical=vertical,
    )


def _fake_solvers() -> Solvers:
    # Overturns when the peak horizontal exceeds 3 times the uplift threshold.
    def block(width, height, *, eta=None):
        return SimpleNamespace(alpha=math.atan(width / height))

    def rocking(block, acc, dt, *, acc_v=None, history=True, max_free_time=60.0, **_):
        ratio = float(np.max(np.abs(acc))) / (G * math.tan(block.alpha))
        n = len(acc)
        return SimpleNamespace(
            status="overturned" if ratio > 3 else "came_to_rest",
            overturned=ratio > 3,
            uplifted=ratio > 1,
            alpha=block.alpha,
            theta_max=0.01 * ratio,
            theta_max_over_alpha=min(ratio / 10, 1.0),
            t=np.arange(n) * dt,
            theta=np.zeros(n),
            regime=np.zeros(n, dtype=np.int8),
        )

    return Solvers(block=block, rocking=rocking, double=rocking, floor=lambda a, dt, **k: a)


@pytest.mark.parametrize(
    ("vertical_down", "limit"),
    [(0.5 * G, "vertical_limit"), (0.0, "overturning")],
)
def test_safety_factor_says_which_limit_ended_the_search(vertical_down, limit):
    # Overturning needs a factor of ~1.6 here; with a 0.5 g downward vertical the scaled
    # vertical reaches -g at a factor of 2 ... but the block overturns first (1.6 < 2).
    # With a 0.8 g vertical the limit (1.25) comes first: never reported as failure.
    tower = Tower(id="T", width_m=1.0, height_m=6.0)
    motion = _motion(vertical_down * 1.6 if vertical_down else 0.0)
    config = config_from_mapping({"output": {"histories": "none"}})
    outcome = evaluate_tower(
        TowerTask(0, tower, ("XX.A..HN",)),
        CampaignShared({"XX.A..HN": motion}, config, _fake_solvers()),
    )
    summary = outcome.summary
    assert summary["safety_factor_limit"] == limit
    if limit == "vertical_limit":
        assert math.isinf(summary["safety_factor"])
        expected = vertical_limit_factor(motion.vertical)
        assert summary["safety_factor_lower"] <= expected
        assert summary["risk_class"] not in ("collapse", "high")
        assert "validity limit" in summary["note"]
    else:
        assert math.isfinite(summary["safety_factor"])


def test_vertical_limit_factor():
    assert vertical_limit_factor(None) == math.inf
    assert vertical_limit_factor(np.array([0.1, 0.2])) == math.inf
    assert vertical_limit_factor(np.array([1.0, -0.5 * G])) == pytest.approx(2.0)


def test_a_run_that_screens_no_tower_fails(rockscreen, monkeypatch):
    def broken(*args, **kwargs):
        raise ValueError("solver refused the case")

    monkeypatch.setattr("rockscreen.pipeline.engine.loop.solve_case", broken)
    result = rockscreen("run", "--example", "--jobs", "1")
    assert result.exit_code == 1
    assert "no tower was screened" in result.stderr
    # Failures come before the summary, and the last line counts them.
    assert result.stderr.index("failed ") < result.stderr.index("towers screened")


@pytest.mark.slow
@pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")
@pytest.mark.parametrize("name", ["SIGTERM", "SIGHUP"])
def test_a_stop_signal_exits_128_plus_it_and_keeps_the_partial_archive(
    tmp_path, run_args, run_process, name
):
    # SIGHUP: the terminal of the run closed; it stops like SIGTERM (exit 129).
    result = run_process(run_args(), tmp_path, kill_after=f"1:{name}")
    assert result.returncode == 128 + getattr(signal, name), result.stderr
    last = result.stderr.strip().splitlines()[-1]
    assert f"interrupted ({name})" in last and "rerun the same command to resume" in last
    assert part_path(tmp_path / "rockscreen.h5").exists()
    assert "Traceback" not in result.stderr


@pytest.mark.parametrize("form", ["folder", "glob", "twice"])
def test_records_as_users_give_them(tmp_path, rockscreen, example_records, run_args, form):
    records, _ = example_records
    given = {
        "folder": ["records"],
        "glob": ["records/*.mseed"],  # quoted: the shell did not expand it
        "twice": [*map(str, records), str(records[0])],
    }[form]
    result = rockscreen(*run_args(records=given))
    assert result.exit_code == 0, result.output
    rows = read_summary(tmp_path / "rockscreen.h5")
    stations = {s for row in rows for s in row["stations"].split(",") if s}
    assert stations == {"XX.SYN1", "XX.SYN2", "XX.SYN3"}


def test_a_flagged_record_is_named_in_the_towers_note():
    import dataclasses

    tower = Tower(id="T", width_m=1.0, height_m=6.0)
    motion = dataclasses.replace(
        _motion(0.0), info={"quality_flags": ["vertical_ratio: vertical peak 3.0 x horizontal"]}
    )
    config = config_from_mapping({"output": {"histories": "none"}})
    outcome = evaluate_tower(
        TowerTask(0, tower, ("XX.A..HN",)),
        CampaignShared({"XX.A..HN": motion}, config, _fake_solvers()),
    )
    assert "record XX.A..HN flagged: vertical_ratio" in outcome.summary["note"]


def test_other_inputs_into_a_complete_archive_are_refused_unless_overwrite(
    tmp_path, rockscreen, run_args
):
    base = run_args("--out", "x.h5", towers=None)
    first = rockscreen(*base, "--towers", example_inventory_path())
    assert first.exit_code == 0, first.output
    other = tmp_path / "other.csv"
    other.write_text("id,width_m,height_m,lat,lon\nZ1,3,20,41.04,14.42\n", encoding="utf-8")
    refused = rockscreen(*base, "--towers", other)
    assert refused.exit_code == 1
    assert "x.h5" in refused.stderr and "--overwrite" in refused.stderr
    assert {row["id"] for row in read_summary(tmp_path / "x.h5")} != {"Z1"}
    replaced = rockscreen(*base, "--towers", other, "--overwrite")
    assert replaced.exit_code == 0, replaced.output
    assert [row["id"] for row in read_summary(tmp_path / "x.h5")] == ["Z1"]


def test_a_second_run_on_the_same_out_stops_at_once(tmp_path, rockscreen):
    from rockscreen.pipeline.archive.lock import archive_lock

    with archive_lock(tmp_path / "rockscreen-example.h5", "run"):
        result = rockscreen("run", "--example", "--jobs", "1")
    assert result.exit_code == 1
    assert "another rockscreen run is writing" in result.stderr
    assert not (tmp_path / "rockscreen-example.h5").exists()


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX bytes file names")
def test_a_non_utf8_record_file_name_is_stored_and_printed_safely(
    tmp_path, rockscreen, example_records, run_args
):
    records, _ = example_records
    odd = os.fsdecode(b"r\xe9cord.mseed")
    os.rename(records[0], odd)
    result = rockscreen(*run_args("-q", records=[odd, *records[1:]]))
    assert result.exit_code == 0, result.output
    assert read_summary(tmp_path / "rockscreen.h5")


def _three_component_files(folder, horizontal_peak, vertical_peak):
    """An XX.Q station: HNE/HNN peaking at ``horizontal_peak``, HNZ at ``vertical_peak`` [m/s2]."""
    from obspy import Trace, UTCDateTime

    t = np.arange(4000) / 100.0
    shape = np.sin(2 * np.pi * 1.5 * t) * np.exp(-(((t - 15.0) / 5.0) ** 2))
    paths = []
    peaks = {"HNE": horizontal_peak, "HNN": horizontal_peak, "HNZ": vertical_peak}
    for channel, peak in peaks.items():
        header = {"network": "XX", "station": "Q", "channel": channel, "sampling_rate": 100.0}
        trace = Trace(shape / np.abs(shape).max() * peak, {**header, "starttime": UTCDateTime(0)})
        paths.append(folder / f"XX.Q..{channel}.mseed")
        trace.write(str(paths[-1]), format="MSEED")
    return paths


def test_the_configured_quality_limits_apply_when_records_are_read(tmp_path):
    from rockscreen.pipeline.screening.inputs import prepare_records

    paths = _three_component_files(tmp_path, 6.0 * G, 6.0 * G)  # a 6 g record
    _, failures = prepare_records(paths, units="m/s2")
    assert failures and all("5 g" in f.reason for f in failures)
    quality = {"quality": {"max_peak_m_s2": 100.0}}
    motions, failures = prepare_records(paths, units="m/s2", processing=quality)
    assert not failures and len(motions) == 1


def test_the_configured_vertical_ratio_sets_the_flag(tmp_path):
    from rockscreen.pipeline.screening.inputs import prepare_records

    paths = _three_component_files(tmp_path, 1.0, 3.0)  # V/H = 3
    for quality, flagged in (({}, True), ({"quality": {"max_vertical_ratio": 5.0}}, False)):
        (motion,) = prepare_records(paths, units="m/s2", processing=quality)[0].values()
        flags = motion.info["quality_flags"]
        assert any(flag.startswith("vertical_ratio") for flag in flags) is flagged, quality
