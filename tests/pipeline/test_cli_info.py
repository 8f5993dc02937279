"""``rockscreen info``: table and JSON output, bad files reported, PGAs against headers."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from rockscreen.pipeline.cli import main
from rockscreen.solver.constants import G

KEYS = [
    "file",
    "id",
    "format",
    "npts",
    "sampling_rate_hz",
    "starttime",
    "units",
    "pga_m_s2",
    "pgv_m_s",
    "duration_s",
]


@pytest.fixture
def at2_file(tmp_path, write_at2):
    t = np.arange(1000) * 0.01
    return write_at2(tmp_path / "RSN1_TEST_090.AT2", 0.2 * np.sin(2 * np.pi * t) + 0.05)


def run(*args):
    return CliRunner().invoke(main, ["info", *map(str, args)])


def test_json_entry(at2_file):
    result = run(at2_file, "--json")
    assert result.exit_code == 0, result.output
    (entry,) = json.loads(result.stdout)
    assert list(entry) == KEYS
    assert entry["id"] == ".RSN1..090"
    assert entry["format"] == "AT2"
    assert entry["npts"] == 1000
    assert entry["sampling_rate_hz"] == 100.0
    assert entry["units"] == "m/s2"
    assert entry["pga_m_s2"] == pytest.approx(0.2 * G, rel=1e-4)  # the 0.05 g offset is removed
    assert entry["pgv_m_s"] == pytest.approx(0.2 * G / np.pi, rel=1e-3)
    assert entry["duration_s"] == pytest.approx(10.0)


def test_table(at2_file):
    result = run(at2_file)
    assert result.exit_code == 0
    header, row = result.stdout.splitlines()
    assert header.split() == KEYS[1:]
    assert row.split()[:3] == [".RSN1..090", "AT2", "1000"]


def test_bad_files_reported_good_ones_kept(tmp_path, at2_file):
    empty = tmp_path / "empty.AT2"
    empty.write_bytes(b"")
    unknown = tmp_path / "notes.txt"
    unknown.write_text("hello\n")
    result = run(empty, at2_file, unknown, tmp_path / "missing.mseed", "--json")
    assert result.exit_code == 1
    assert len(json.loads(result.stdout)) == 1
    errors = result.stderr.strip().splitlines()
    assert errors == [
        f"rockscreen: error: {empty}: empty file",
        f"rockscreen: error: {unknown}: unknown format (not ESM/ITACA ASCII, PEER AT2, K-NET, "
        "miniSEED, SAC or another format ObsPy reads)",
        f"rockscreen: error: {tmp_path / 'missing.mseed'}: no such file",
    ]


def test_sac_without_units_says_how(tmp_path):
    from obspy import Trace

    path = tmp_path / "x.sac"
    Trace(np.zeros(100, dtype=np.float32)).write(str(path), "SAC")
    result = run(path)
    assert result.exit_code == 1
    assert "--units g|m/s2|cm/s2" in result.stderr
    assert str(path) in result.stderr
    assert run(path, "--units", "g").exit_code == 0


def test_bad_units_option(at2_file):
    # A usage error, refused once at parse time (issue 12): exit code 2, not 1.
    result = run(at2_file, "--units", "furlong")
    assert result.exit_code == 2
    assert "unknown acceleration unit 'furlong'" in result.stderr


def test_bad_stations_option(tmp_path, at2_file):
    result = run(at2_file, "--stations", tmp_path / "absent.xml")
    assert result.exit_code != 0


@pytest.mark.data
def test_real_files_pga_match_headers(shared_data):
    formats = shared_data / "formats"
    esm = sorted((formats / "esm").glob("*ACC.ASC"))
    knet = sorted((formats / "knet").glob("CHB*"))
    result = run(*esm, *knet, "--json")
    assert result.exit_code == 0, result.stderr
    entries = json.loads(result.stdout)
    assert len(entries) == len(esm) + len(knet)
    from obspy import read

    for entry in entries:
        (raw,) = read(entry["file"])
        if entry["format"] == "ESM":
            expected = abs(float(raw.stats.esm["PGA_CM/S^2"])) / 100.0
        else:
            expected = raw.stats.knet["accmax"] / 100.0
        assert entry["pga_m_s2"] == pytest.approx(expected, rel=5e-3), entry["id"]


@pytest.mark.data
def test_real_laquila_with_stations(shared_data):
    folder = shared_data / "laquila2009"
    result = run(
        *sorted(folder.glob("IT.AQV*.mseed")),
        "--stations",
        folder / "stations.xml",
        "--json",
    )
    assert result.exit_code == 0, result.stderr
    pga = {e["id"]: e["pga_m_s2"] for e in json.loads(result.stdout)}
    # SOURCES.md: AQV PGA NS / WE / UP = 5.366 / 6.507 / 5.169 m/s^2.
    assert pga["IT.AQV..HNN"] == pytest.approx(5.366, rel=5e-3)
    assert pga["IT.AQV..HNE"] == pytest.approx(6.507, rel=5e-3)
    assert pga["IT.AQV..HNZ"] == pytest.approx(5.169, rel=5e-3)


@pytest.mark.data
def test_real_mixed_batch(shared_data):
    formats = shared_data / "formats"
    result = run(
        formats / "sac" / "20190706031952.CJ.T001230.HNN.sac",
        formats / "at2" / "elCentro.AT2",
        formats / "esm" / "TK.4612..HNE.D.20230206.102449.C.SA.ASC",
        "--units",
        "g",
        "--json",
    )
    assert result.exit_code == 1
    entries = json.loads(result.stdout)
    assert [e["format"] for e in entries] == ["SAC", "AT2"]
    assert entries[1]["pga_m_s2"] == pytest.approx(0.31882 * G, rel=5e-3)
    assert "not a time series" in result.stderr
