"""read_stream: every format to m/s^2, units never guessed, bad files named."""

from __future__ import annotations

import csv
import functools
import re

import numpy as np
import pytest
from obspy import Stream, Trace, UTCDateTime, read

from rockscreen.pipeline.errors import RecordFormatError, StationMetadataError, UnitsError
from rockscreen.pipeline.records.io import (
    file_format,
    read_stream,
    read_streams,
    trace_format,
    trace_summary,
)
from rockscreen.pipeline.records.quality import QualityLimits, check_array, plausibility_findings
from rockscreen.solver.constants import G

START = UTCDateTime(2021, 1, 1)


def write_esm(path, data, units="cm/s^2", stream="HNE"):
    """A minimal, valid 64-line DYNA 1.2 file (unlisted keys left empty)."""
    header = {
        "EVENT_NAME": "TEST",
        "NETWORK": "XX",
        "STATION_CODE": "ESM",
        "STATION_LATITUDE_DEGREE": "40.0",
        "STATION_LONGITUDE_DEGREE": "15.0",
        "STATION_ELEVATION_M": "10",
        "DATE_TIME_FIRST_SAMPLE_YYYYMMDD_HHMMSS": "20210101_000000.000",
        "SAMPLING_INTERVAL_S": "0.01",
        "NDATA": str(len(data)),
        "STREAM": stream,
        "UNITS": units,
        "HEADER_FORMAT": "DYNA 1.2",
        "DATA_TYPE": "ACCELERATION",
    }
    lines = [f"{key}: {value}" for key, value in header.items()]
    lines += [f"USER_PAD{i}: " for i in range(64 - len(lines))]
    path.write_text("\n".join(lines + [f"{v:.6f}" for v in data]) + "\n")
    return path


@pytest.fixture
def inventory(make_inventory):
    """``inventory(**options)``: station XX.MS, location 00, 4000 counts per m/s^2."""
    return functools.partial(
        make_inventory,
        "MS",
        location="00",
        latitude=45.0,
        longitude=9.0,
        elevation=120.0,
        sensitivity=4000.0,
        start_date=None,
    )


def counts_trace(channel="HNN"):
    data = (np.sin(np.arange(1000) / 10.0) * 4000).astype(np.int32)
    header = {
        "network": "XX",
        "station": "MS",
        "location": "00",
        "channel": channel,
        "sampling_rate": 100.0,
        "starttime": START,
    }
    return Trace(data=data, header=header)


@pytest.fixture
def wave():
    return np.sin(np.linspace(0.0, 30.0, 600)) * 50.0 + 3.0


def test_esm_cm_s2_to_m_s2(tmp_path, wave):
    (trace,) = read_stream(write_esm(tmp_path / "a.asc", wave))
    np.testing.assert_allclose(trace.data, np.round(wave, 6) / 100.0)
    info = trace.stats.rockscreen
    assert (info.format, info.units_in, info.units, info.units_source) == (
        "ESM",
        "cm/s^2",
        "m/s2",
        "header",
    )
    assert trace.stats.coordinates["latitude"] == 40.0
    assert [step["step"] for step in info.provenance] == ["read", "convert_units"]
    assert trace_format(trace) == "ESM"


def test_at2_g_to_m_s2(tmp_path, wave, write_at2):
    data = wave / 100.0
    (trace,) = read_stream(write_at2(tmp_path / "x.AT2", data))
    np.testing.assert_allclose(trace.data, data * G, rtol=1e-7)
    assert trace.stats.rockscreen.units_in == "g"


def test_header_units_win_over_user_units(tmp_path, wave):
    (trace,) = read_stream(write_esm(tmp_path / "a.asc", wave), units="g")
    assert trace.stats.rockscreen.units_source == "header"
    assert np.abs(trace.data).max() == pytest.approx(np.abs(np.round(wave, 6)).max() / 100.0)


def test_non_acceleration_header_units_refused(tmp_path, wave):
    path = write_esm(tmp_path / "v.asc", wave, units="cm/s")
    with pytest.raises(UnitsError, match="not an acceleration"):
        read_stream(path)


def test_sac_needs_user_units(tmp_path):
    path = tmp_path / "x.sac"
    Trace(np.full(200, 0.01, dtype=np.float32), header={"delta": 0.01}).write(str(path), "SAC")
    with pytest.raises(UnitsError, match=re.escape("--units g|m/s2|cm/s2")) as info:
        read_stream(path)
    assert str(path) in str(info.value)
    (trace,) = read_stream(path, units="g")
    np.testing.assert_allclose(trace.data, 0.01 * G, rtol=1e-6)
    assert trace.stats.rockscreen.units_source == "user"


def test_sac_ignores_stationxml_response(tmp_path, inventory):
    path = tmp_path / "x.sac"
    trace = counts_trace()
    trace.data = trace.data.astype(np.float32)
    trace.write(str(path), "SAC")
    with pytest.raises(UnitsError, match="--units"):
        read_stream(path, stations=inventory())


def test_unknown_user_units_refused_before_reading(tmp_path):
    with pytest.raises(UnitsError, match="unknown acceleration unit"):
        read_stream(tmp_path / "whatever", units="furlong")


def test_mseed_counts_through_stationxml_sensitivity(tmp_path, inventory):
    path = tmp_path / "x.mseed"
    Stream([counts_trace("HNN"), counts_trace("HNE")]).write(str(path), format="MSEED")
    stream = read_stream(path, stations=inventory(sensitivity=4000.0))
    raw = counts_trace().data
    for trace in stream:
        np.testing.assert_allclose(trace.data, raw / 4000.0)
        assert trace.stats.rockscreen.units_source == "stationxml"
        assert trace.stats.coordinates["elevation"] == 120.0
        assert trace.stats.calib == 1.0
    assert stream.select(channel="HNE")[0].stats.orientation["azimuth"] == 90.0


def test_stationxml_file_path_accepted(tmp_path, inventory):
    xml = tmp_path / "st.xml"
    # 2000 counts per m/s^2 (2 gave 2000 m/s^2, now refused as not ground acceleration).
    inventory(sensitivity=2000.0).write(str(xml), format="STATIONXML")
    path = tmp_path / "x.mseed"
    counts_trace().write(str(path), format="MSEED")
    (trace,) = read_stream(path, stations=xml)
    np.testing.assert_allclose(trace.data, counts_trace().data / 2000.0)


def test_velocity_sensor_refused(tmp_path, inventory):
    path = tmp_path / "x.mseed"
    counts_trace().write(str(path), format="MSEED")
    with pytest.raises(UnitsError, match="accelerometer"):
        read_stream(path, stations=inventory(input_units="M/S"))


def test_mseed_without_metadata_or_units_refused(tmp_path, inventory):
    path = tmp_path / "x.mseed"
    counts_trace().write(str(path), format="MSEED")
    with pytest.raises(UnitsError, match="--stations"):
        read_stream(path)
    with pytest.raises(UnitsError, match="--units"):
        read_stream(path, stations=inventory().select(station="NONE"))
    (trace,) = read_stream(path, units="cm/s2")
    np.testing.assert_allclose(trace.data, counts_trace().data / 100.0)


def test_bad_stationxml(tmp_path):
    bad = tmp_path / "bad.xml"
    bad.write_text("nope")
    with pytest.raises(StationMetadataError):
        read_stream(tmp_path / "x.mseed", stations=bad)


@pytest.mark.parametrize(
    ("content", "reason"),
    [
        (None, "no such file"),
        (b"", "empty file"),
        (b"just some text\nthat is no record\n", "unknown format"),
    ],
)
def test_bad_files(tmp_path, content, reason):
    path = tmp_path / "bad.dat"
    if content is not None:
        path.write_bytes(content)
    with pytest.raises(RecordFormatError, match=reason) as info:
        read_stream(path)
    assert str(path) in str(info.value)


def test_truncated_mseed(tmp_path, inventory):
    path = tmp_path / "x.mseed"
    counts_trace().write(str(path), format="MSEED", reclen=512)
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 2 + 100])
    with pytest.raises(RecordFormatError) as info:
        read_stream(path, stations=inventory())
    assert str(path) in str(info.value)


def test_truncated_esm(tmp_path, wave):
    path = write_esm(tmp_path / "t.asc", wave)
    path.write_text(path.read_text()[:-400])
    with pytest.raises(RecordFormatError, match="truncated"):
        read_stream(path)


def test_file_format(tmp_path, wave, write_at2):
    assert file_format(write_esm(tmp_path / "a.asc", wave)) == "ESM"
    assert file_format(write_at2(tmp_path / "b.AT2", wave)) == "AT2"
    path = tmp_path / "c.mseed"
    counts_trace().write(str(path), format="MSEED")
    assert file_format(path) == "MSEED"


def test_read_streams_reports_bad_files(tmp_path, wave):
    good = write_esm(tmp_path / "a.asc", wave)
    bad = tmp_path / "empty.asc"
    bad.write_bytes(b"")
    stream, failures = read_streams([good, bad])
    assert len(stream) == 1
    assert failures == [(str(bad), f"{bad}: empty file")]


def test_trace_summary(tmp_path, write_at2):
    dt = 0.01
    t = np.arange(2000) * dt
    acc = 2.0 * np.sin(2 * np.pi * t) + 5.0  # offset removed by the summary
    (trace,) = read_stream(write_at2(tmp_path / "s.AT2", acc / G, dt=dt))
    summary = trace_summary(trace)
    assert summary["pga_m_s2"] == pytest.approx(2.0, rel=1e-3)
    # v = (1 - cos 2 pi t) / pi from rest, peak 2/pi.
    assert summary["pgv_m_s"] == pytest.approx(2.0 / np.pi, rel=1e-3)
    assert summary["duration_s"] == pytest.approx(20.0)
    assert summary["units"] == "m/s2"
    assert summary["format"] == "AT2"


# --- real data ---------------------------------------------------------------------------


@pytest.mark.data
@pytest.mark.parametrize("pattern", ["esm/*ACC.ASC", "esm/*RawAcc*.asc"])
def test_real_esm_pga_matches_header(shared_data, pattern):
    for path in sorted((shared_data / "formats").glob(pattern)):
        (trace,) = read_stream(path)
        header = abs(float(trace.stats.esm["PGA_CM/S^2"])) / 100.0
        assert trace_summary(trace)["pga_m_s2"] == pytest.approx(header, rel=5e-3)


@pytest.mark.data
def test_real_knet_pga_matches_header(shared_data):
    for path in sorted((shared_data / "formats" / "knet").glob("CHB*")):
        (trace,) = read_stream(path)
        assert trace.stats.rockscreen.units_source == "calibration"
        # K-NET's "Max. Acc. (gal)" is taken after removing the mean.
        header = trace.stats.knet["accmax"] / 100.0
        assert trace_summary(trace)["pga_m_s2"] == pytest.approx(header, rel=5e-3)


@pytest.mark.data
def test_real_at2_in_g(shared_data):
    for path in sorted((shared_data / "formats" / "at2").glob("*.AT2")):
        (trace,) = read_stream(path)
        (raw,) = read(str(path))
        np.testing.assert_allclose(trace.data, raw.data * G)


@pytest.mark.data
def test_real_sac_with_stated_units(shared_data):
    paths = sorted((shared_data / "formats" / "sac").glob("*.sac"))
    with pytest.raises(UnitsError, match="--units"):
        read_stream(paths[0])
    for path in paths:
        (trace,) = read_stream(path, units="g")
        (raw,) = read(str(path))
        np.testing.assert_allclose(trace.data, raw.data.astype(np.float64) * G)


@pytest.mark.data
def test_real_mseed_counts_with_response(shared_data):
    folder = shared_data / "formats" / "mseed_response"
    xml = folder / "CE.79435.xml"
    for path in sorted(folder.glob("*.mseed")):
        with pytest.raises(UnitsError):
            read_stream(path)
        (trace,) = read_stream(path, stations=xml)
        (raw,) = read(str(path))
        sensitivity = {"HNE": 214580.74612, "HNN": 214077.42928, "HNZ": 213909.657}
        np.testing.assert_allclose(trace.data, raw.data / sensitivity[trace.stats.channel])
        assert trace.stats.coordinates["latitude"] == pytest.approx(39.9238)


def _laquila_table(shared_data):
    """PGA NS / WE / UP [m/s^2] per station from the SOURCES.md table."""
    table = {}
    text = (shared_data / "SOURCES.md").read_text()
    rows = [line for line in text.splitlines() if re.match(r"^\| (AQV|AQG|GSA|AVZ) \|", line)]
    for row in csv.reader(rows, delimiter="|"):
        cells = [cell.strip() for cell in row]
        ns, we, up = (float(value) for value in cells[-2].split("/"))
        table[cells[1]] = {"HNN": ns, "HNE": we, "HNZ": up}
    return table


@pytest.mark.data
def test_real_laquila_pga_matches_sources_table(shared_data):
    folder = shared_data / "laquila2009"
    table = _laquila_table(shared_data)
    assert set(table) == {"AQV", "AQG", "GSA", "AVZ"}
    for path in sorted(folder.glob("*.mseed")):
        (trace,) = read_stream(path, stations=folder / "stations.xml")
        assert trace.stats.rockscreen.units_source == "stationxml"
        expected = table[trace.stats.station][trace.stats.channel]
        assert trace_summary(trace)["pga_m_s2"] == pytest.approx(expected, rel=5e-3)


# Issue 12: none of the real records is refused or flagged by the plausibility checks.
@pytest.mark.data
def test_no_real_record_is_implausible(shared_data):
    files = sorted(shared_data.glob("laquila2009*/*.mseed"))
    files += [p for p in sorted(shared_data.glob("formats/*/*")) if p.suffix.lower() != ".xml"]
    files = [p for p in files if ".SA." not in p.name]
    checked = 0
    for path in files:
        kwargs = {}
        if path.suffix == ".mseed":
            xml = sorted(path.parent.glob("*.xml")) or [shared_data / "laquila2009/stations.xml"]
            kwargs["stations"] = xml[0]
        if path.suffix == ".sac":
            kwargs["units"] = "g"
        for trace in read_stream(path, **kwargs):
            assert plausibility_findings(trace.data, trace.stats.delta) == [], trace.id
            assert check_array(trace.data, trace.stats.delta, QualityLimits(min_duration_s=0)) == []
            checked += 1
    assert checked >= 50
    assert np.isclose(G, 9.81)
