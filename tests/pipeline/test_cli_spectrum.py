"""``rockscreen spectrum`` on a miniSEED in m/s^2 written here, and on a real record."""

from __future__ import annotations

import json

import click
import numpy as np
import pytest
from click.testing import CliRunner
from obspy import Stream, Trace, UTCDateTime

from rockscreen.pipeline.cli import main
from rockscreen.pipeline.cli.spectrum import (
    is_vertical,
    parse_periods,
    period_range,
    select_trace,
)
from rockscreen.pipeline.motion.spectra import response_spectrum

DT = 0.01


def _signal(frequency, seed):
    t = np.arange(0.0, 20.0, DT)
    noise = np.random.default_rng(seed).normal(scale=0.05, size=t.size)
    return 0.3 + np.sin(2 * np.pi * frequency * t) * np.exp(-0.2 * t) + noise  # offset 0.3


@pytest.fixture
def record(tmp_path):
    """Three channels in m/s^2, vertical first, so the first horizontal is HNN."""
    traces = []
    for channel, frequency, seed in (("HNZ", 8.0, 1), ("HNN", 2.0, 2), ("HNE", 4.0, 3)):
        header = {
            "network": "XX",
            "station": "TST",
            "channel": channel,
            "delta": DT,
            "starttime": UTCDateTime(2020, 1, 1),
        }
        traces.append(Trace(data=_signal(frequency, seed), header=header))
    path = tmp_path / "record.mseed"
    Stream(traces).write(str(path), format="MSEED", encoding="FLOAT64")
    return path


def _run(*args):
    return CliRunner().invoke(main, ["spectrum", *map(str, args)])


def test_json_holds_the_spectrum_of_the_first_horizontal(record):
    result = _run(record, "--units", "m/s2", "--periods", "0,0.1,0.5,2", "--json")
    assert result.exit_code == 0, result.output
    payload = json.loads(result.stdout)
    assert payload["id"] == "XX.TST..HNN"
    assert payload["damping"] == 0.05
    assert payload["periods_s"] == [0.0, 0.1, 0.5, 2.0]
    acc = _signal(2.0, 2)
    sa, psa = response_spectrum(acc - acc.mean(), DT, payload["periods_s"])
    np.testing.assert_allclose(payload["sa_m_s2"], sa, rtol=1e-12)
    np.testing.assert_allclose(payload["psa_m_s2"], psa, rtol=1e-12)
    assert "XX.TST..HNN (first horizontal of 3 traces" in result.stderr


def test_channel_damping_and_period_range(record):
    result = _run(
        record, "--units", "m/s2", "--channel", "HNZ", "--damping", "0.1",
        "--period-range", "0.05", "2", "5", "--json",
    )  # fmt: skip
    assert result.exit_code == 0, result.output
    payload = json.loads(result.stdout)
    assert payload["id"] == "XX.TST..HNZ"
    np.testing.assert_allclose(payload["periods_s"], np.geomspace(0.05, 2.0, 5))
    acc = _signal(8.0, 1)
    _, psa = response_spectrum(acc - acc.mean(), DT, payload["periods_s"], damping=0.1)
    np.testing.assert_allclose(payload["psa_m_s2"], psa, rtol=1e-12)


def test_default_output_is_a_table_on_the_default_grid(record):
    result = _run(record, "--units", "m/s2")
    assert result.exit_code == 0, result.output
    lines = result.stdout.splitlines()
    assert lines[0].startswith("# XX.TST..HNN")
    assert lines[1].split() == ["period_s", "sa_m_s2", "psa_m_s2"]
    rows = np.array([[float(x) for x in line.split()] for line in lines[2:]])
    assert rows.shape == (100, 3)
    assert rows[0, 0] == pytest.approx(0.01) and rows[-1, 0] == pytest.approx(10.0)


def test_plot_writes_a_png(record, tmp_path):
    out = tmp_path / "spectrum.png"
    result = _run(record, "--units", "m/s2", "--periods", "0,0.05,0.1,0.5,1", "--plot", out)
    assert result.exit_code == 0, result.output
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert f"wrote {out}" in result.stdout


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--channel", "HHZ"], "no trace with channel 'HHZ'"),
        (["--periods", "0.1,abc"], "'abc' is not a number"),
        (["--periods", "0.1,-1"], "must be >= 0"),
        (["--period-range", "1", "0.1", "5"], "0 < A < B"),
        (["--periods", "0.1", "--period-range", "0.1", "1", "5"], "not both"),
        (["--json", "--plot", "x.png"], "not both"),
    ],
)
def test_usage_errors(record, args, message):
    result = _run(record, "--units", "m/s2", *args)
    assert result.exit_code == 2
    assert message in result.stderr


def test_invalid_damping_is_one_line(record):
    result = _run(record, "--units", "m/s2", "--damping", "1.5")
    assert result.exit_code == 1
    assert result.stderr.strip().splitlines()[-1] == (
        "rockscreen: error: damping=1.5 must be in [0, 1) (a ratio, 0.05 = 5 %)"
    )


def test_units_are_never_guessed(record):
    result = _run(record)  # miniSEED without --stations or --units
    assert result.exit_code == 1
    assert "rockscreen: error:" in result.stderr
    assert "Traceback" not in result.output


def test_helpers():
    np.testing.assert_array_equal(parse_periods("0, 0.1,0.2,"), [0.0, 0.1, 0.2])
    np.testing.assert_allclose(period_range(0.1, 10.0, 3), [0.1, 1.0, 10.0])
    with pytest.raises(click.BadParameter, match="N=1"):
        period_range(0.1, 1.0, 1)
    assert [is_vertical(c) for c in ("HNZ", "UD", "HNE", "EW", "NS", "HN1")] == [
        True, True, False, False, False, False,
    ]  # fmt: skip


def test_a_single_vertical_trace_is_used_and_said(record):
    from obspy import read

    stream = read(str(record)).select(channel="HNZ")
    trace, note = select_trace(stream, None)
    assert trace.stats.channel == "HNZ"
    assert note == "XX.TST..HNZ (the only trace)"
    stream += stream[0].copy()
    _, note = select_trace(stream, None)
    assert "no horizontal in the file" in note


@pytest.mark.data
def test_real_esm_record_in_cm_s2(shared_data):
    # The ESM reader converts cm/s^2 to m/s^2: the 5 % SA matches ESM's own spectrum.
    folder = shared_data / "formats" / "esm"
    stem = "TK.4612..HNE.D.20230206.102449.C"
    result = _run(folder / f"{stem}.ACC.ASC", "--periods", "0.1,0.5,1,2", "--json")
    assert result.exit_code == 0, result.output
    reference = np.loadtxt(folder / f"{stem}.SA.ASC", skiprows=64)
    expected = np.interp([0.1, 0.5, 1.0, 2.0], reference[:, 0], reference[:, 1]) / 100.0
    np.testing.assert_allclose(json.loads(result.stdout)["sa_m_s2"], expected, rtol=0.02)
