"""ESM/ITACA ASCII and PEER AT2 readers: synthetic files everywhere, real files with data."""

from __future__ import annotations

import numpy as np
import obspy
import pytest

from rockscreen.pipeline.errors import RecordFormatError
from rockscreen.pipeline.records.readers.at2 import is_at2, read_at2
from rockscreen.pipeline.records.readers.esm import HEADER_LINES, is_esm, read_esm

ESM_KEYS = [
    "EVENT_NAME", "EVENT_ID", "EVENT_DATE_YYYYMMDD", "EVENT_TIME_HHMMSS",
    "EVENT_LATITUDE_DEGREE", "EVENT_LONGITUDE_DEGREE", "EVENT_DEPTH_KM",
    "HYPOCENTER_REFERENCE", "MAGNITUDE_W", "MAGNITUDE_W_REFERENCE", "MAGNITUDE_L",
    "MAGNITUDE_L_REFERENCE", "FOCAL_MECHANISM", "NETWORK", "STATION_CODE", "STATION_NAME",
    "STATION_LATITUDE_DEGREE", "STATION_LONGITUDE_DEGREE", "STATION_ELEVATION_M", "LOCATION",
    "SENSOR_DEPTH_M", "VS30_M/S", "SITE_CLASSIFICATION_EC8", "MORPHOLOGIC_CLASSIFICATION",
    "EPICENTRAL_DISTANCE_KM", "EARTHQUAKE_BACKAZIMUTH_DEGREE",
    "DATE_TIME_FIRST_SAMPLE_YYYYMMDD_HHMMSS", "DATE_TIME_FIRST_SAMPLE_PRECISION",
    "SAMPLING_INTERVAL_S", "NDATA", "DURATION_S", "STREAM", "UNITS", "INSTRUMENT",
    "INSTRUMENT_ANALOG/DIGITAL", "INSTRUMENTAL_FREQUENCY_HZ", "INSTRUMENTAL_DAMPING",
    "FULL_SCALE_G", "N_BIT_DIGITAL_CONVERTER", "PGA_CM/S^2", "TIME_PGA_S",
    "BASELINE_CORRECTION", "FILTER_TYPE", "FILTER_ORDER", "LOW_CUT_FREQUENCY_HZ",
    "HIGH_CUT_FREQUENCY_HZ", "LATE/NORMAL_TRIGGERED", "DATABASE_VERSION", "HEADER_FORMAT",
    "DATA_TYPE", "PROCESSING", "DATA_TIMESTAMP_YYYYMMDD_HHMMSS", "DATA_LICENSE",
    "DATA_CITATION", "DATA_CREATOR", "ORIGINAL_DATA_MEDIATOR_CITATION",
    "ORIGINAL_DATA_MEDIATOR", "ORIGINAL_DATA_CREATOR_CITATION", "ORIGINAL_DATA_CREATOR",
    "USER1", "USER2", "USER3", "USER4", "USER5",
]  # fmt: skip


def esm_text(data, *, stream="HNE", first_sample="20190728_160905.700", **overrides) -> str:
    values = {
        "EVENT_NAME": "TEST",
        "NETWORK": "XX",
        "STATION_CODE": "ABC",
        "STATION_LATITUDE_DEGREE": "42.5",
        "STATION_LONGITUDE_DEGREE": "13.25",
        "STATION_ELEVATION_M": "700",
        "DATE_TIME_FIRST_SAMPLE_YYYYMMDD_HHMMSS": first_sample,
        "SAMPLING_INTERVAL_S": "0.010000",
        "NDATA": str(len(data)),
        "STREAM": stream,
        "UNITS": "cm/s^2",
        "PGA_CM/S^2": f"{np.abs(data).max():.6f}",
        "HEADER_FORMAT": "DYNA 1.2",
        "DATA_TYPE": "ACCELERATION",
    }
    values.update(overrides)
    header = [f"{key}: {values.get(key, '')}" for key in ESM_KEYS]
    assert len(header) == HEADER_LINES
    return "\n".join(header + [f"{v:.6f}" for v in data]) + "\n"


def fixed_width(header, data, per_row, spec) -> str:
    """Header lines, then ``data`` ``per_row`` values a line in the format ``spec``."""
    rows = [data[i : i + per_row] for i in range(0, len(data), per_row)]
    return "\n".join(header + ["".join(f"{v:{spec}}" for v in row) for row in rows])


def at2_text(data, dt=0.01, component="90") -> str:
    header = [
        "PEER NGA STRONG MOTION DATABASE RECORD",
        f"Test Event, 10/18/1989, Test Station, {component}",
        "ACCELERATION TIME SERIES IN UNITS OF G",
        f"NPTS= {len(data):6d}, DT= {dt:7.4f} SEC",
    ]
    return fixed_width(header, data, 5, "15.7E") + "\n"


def legacy_at2_text(data, dt=0.02) -> str:
    header = [
        "Data for Test 1940 North South Component",
        f"{len(data)} points at equal spacing of {dt} sec, format 8F10.5",
        "The units are (g)",
        f"NPTS=  {len(data)}, DT= {dt:.5f} SEC",
    ]
    return fixed_width(header, data, 8, "10.5f")  # the El Centro file has no final newline


@pytest.fixture
def signal():
    return np.round(np.sin(np.linspace(0, 20, 137)) * 12.5, 6)


def test_esm_round_trip(tmp_path, signal):
    path = tmp_path / "XX.ABC..HNE.D.ACC.ASC"
    path.write_text(esm_text(signal))
    assert is_esm(path)
    (trace,) = read_esm(path)
    np.testing.assert_allclose(trace.data, signal)
    assert trace.id == "XX.ABC..HNE"
    assert trace.stats.delta == pytest.approx(0.01)
    assert trace.stats.starttime == obspy.UTCDateTime("2019-07-28T16:09:05.700")
    assert trace.stats.esm["UNITS"] == "cm/s^2"
    assert dict(trace.stats.coordinates) == {
        "latitude": 42.5,
        "longitude": 13.25,
        "elevation": 700.0,
    }


def test_esm_afad_dates_and_place_name_location(tmp_path, signal):
    path = tmp_path / "afad.asc"
    path.write_text(
        esm_text(signal, first_sample="14/11/2010 23:09:19.300", LOCATION="HATAY_HASSA")
    )
    (trace,) = read_esm(path)
    assert trace.stats.starttime == obspy.UTCDateTime("2010-11-14T23:09:19.300")
    assert trace.stats.location == ""


def test_esm_headonly(tmp_path, signal):
    path = tmp_path / "x.asc"
    path.write_text(esm_text(signal))
    (trace,) = read_esm(path, headonly=True)
    assert trace.stats.npts == signal.size
    assert trace.data.size == 0


@pytest.mark.parametrize(
    ("mutate", "reason"),
    [
        (lambda text: "\n".join(text.splitlines()[:-10]), "truncated"),
        (lambda text: "\n".join(text.splitlines()[:30]), "truncated ESM header"),
        (lambda text: text.rstrip("\n").rsplit("\n", 1)[0] + "\nabc\n", "non-numeric"),
        (
            lambda text: text.replace("DATA_TYPE: ACCELERATION", "DATA_TYPE: FOURIER SPECTRUM"),
            "not a time series",
        ),
        (lambda text: text.replace("NETWORK: XX", "NETWORK: "), "lacks NETWORK"),
        (
            lambda text: text.replace("20190728_160905.700", "28-07-2019"),
            "first-sample time",
        ),
    ],
)  # fmt: skip
def test_esm_bad_files_name_file_and_reason(tmp_path, mutate, reason):
    data = np.zeros(50)
    path = tmp_path / "bad.asc"
    path.write_text(mutate(esm_text(data)))
    with pytest.raises(RecordFormatError, match=reason) as info:
        read_esm(path)
    assert str(path) in str(info.value)


def test_at2_round_trip(tmp_path, signal):
    path = tmp_path / "RSN42_TEST_STA090.AT2"
    data = signal / 100.0
    path.write_text(at2_text(data, dt=0.005, component="90"))
    assert is_at2(path)
    (trace,) = read_at2(path)
    np.testing.assert_allclose(trace.data, data, rtol=1e-6)
    assert trace.stats.station == "RSN42"
    assert trace.stats.channel == "090"
    assert trace.stats.delta == pytest.approx(0.005)
    assert trace.stats.at2["units"] == "g"
    assert trace.stats.at2["date"] == "10/18/1989"


def test_legacy_at2(tmp_path, signal):
    path = tmp_path / "oldfile.AT2"
    data = np.round(signal / 40.0, 5)
    path.write_text(legacy_at2_text(data))
    assert is_at2(path)
    (trace,) = read_at2(path)
    np.testing.assert_allclose(trace.data, data)
    assert trace.stats.at2["units"] == "g"
    assert trace.stats.channel == "NS"
    assert trace.stats.station == "oldfile"
    assert trace.stats.delta == pytest.approx(0.02)


def test_at2_truncated(tmp_path, signal):
    path = tmp_path / "cut.AT2"
    path.write_text("\n".join(at2_text(signal).splitlines()[:-3]))
    with pytest.raises(RecordFormatError, match="truncated") as info:
        read_at2(path)
    assert str(path) in str(info.value)


def test_at2_missing_npts_line(tmp_path):
    path = tmp_path / "nonpts.AT2"
    path.write_text("title\nmore\n0.1 0.2 0.3\n")
    assert not is_at2(path)
    with pytest.raises(RecordFormatError, match="NPTS"):
        read_at2(path)


@pytest.mark.parametrize("content", [b"", b"hello world\n", b"\x00\x01\x02\xff" * 40])
def test_detectors_reject_other_files(tmp_path, content):
    path = tmp_path / "other.bin"
    path.write_bytes(content)
    assert not is_esm(path)
    assert not is_at2(path)


def test_detectors_never_raise_on_missing_file(tmp_path):
    assert not is_esm(tmp_path / "missing")
    assert not is_at2(tmp_path / "missing")


def test_obspy_read_uses_the_plugins(tmp_path, signal):
    esm_path = tmp_path / "a.asc"
    esm_path.write_text(esm_text(signal))
    at2_path = tmp_path / "b.AT2"
    at2_path.write_text(at2_text(signal))
    esm = obspy.read(str(esm_path))
    at2 = obspy.read(str(at2_path))
    assert esm[0].stats._format == "ESM"
    assert at2[0].stats._format == "AT2"
    np.testing.assert_allclose(esm[0].data, signal)


@pytest.mark.data
def test_obspy_read_real_esm_and_at2(shared_data):
    formats = shared_data / "formats"
    for path in sorted((formats / "esm").glob("*ACC.ASC")) + [
        formats / "esm" / "20101114230825_3104_ap_RawAcc_E.asc"
    ]:
        (trace,) = obspy.read(str(path))
        assert trace.stats._format == "ESM"
        header_pga = abs(float(trace.stats.esm["PGA_CM/S^2"]))  # signed in ESM headers
        # The raw AFAD file's header PGA is rounded to 4 significant digits.
        assert np.abs(trace.data).max() == pytest.approx(header_pga, rel=5e-4)
        assert trace.stats.npts == int(trace.stats.esm["NDATA"])
    for path in sorted((formats / "at2").glob("*.AT2")):
        (trace,) = obspy.read(str(path))
        assert trace.stats._format == "AT2"
        assert trace.stats.at2["units"] == "g"
        assert trace.stats.npts == trace.stats.at2["npts"]


@pytest.mark.data
def test_real_afad_start_time_and_el_centro(shared_data):
    formats = shared_data / "formats"
    (afad,) = read_esm(formats / "esm" / "20101114230825_3104_ap_RawAcc_E.asc")
    assert afad.stats.starttime == obspy.UTCDateTime("2010-11-14T23:09:19.300")
    (elcentro,) = read_at2(formats / "at2" / "elCentro.AT2")
    assert elcentro.stats.npts == 1559
    assert elcentro.stats.delta == pytest.approx(0.02)
    assert np.abs(elcentro.data).max() == pytest.approx(0.31882)


@pytest.mark.data
def test_esm_spectrum_file_is_refused(shared_data):
    path = next((shared_data / "formats" / "esm").glob("*.SA.ASC"))
    with pytest.raises(RecordFormatError, match="not a time series"):
        read_esm(path)
