"""Issue 12, record input: a hostile or corrupt record file never yields a silent wrong answer.

Every test builds its small hostile file in ``tmp_path``; only the last ones (marked
``data``) use the real records of ``../shared/data``.
"""

from __future__ import annotations

import glob
import json
import os
import re
import struct
import sys

import numpy as np
import pytest
from click.testing import CliRunner
from obspy import Stream, Trace, UTCDateTime

from rockscreen.pipeline.cli import main
from rockscreen.pipeline.errors import RecordFormatError, StationMetadataError, UnitsError
from rockscreen.pipeline.records.grouping import group_records
from rockscreen.pipeline.records.io import expand_record_paths, read_stream
from rockscreen.pipeline.records.quality import QualityLimits, check_array, plausibility_findings
from rockscreen.pipeline.records.readers.text import PROBE_BYTES, head_lines
from rockscreen.pipeline.text import printable
from rockscreen.stations.stationxml import read_station_metadata

START = UTCDateTime(2021, 1, 1)


def esm_text(data, *, station="ESM", stream="HNE", dt="0.01", ndata=None, units="cm/s^2"):
    """A minimal 64-line DYNA 1.2 file, values written as given (strings allowed)."""
    header = {
        "EVENT_NAME": "TEST",
        "NETWORK": "XX",
        "STATION_CODE": station,
        "DATE_TIME_FIRST_SAMPLE_YYYYMMDD_HHMMSS": "20210101_000000.000",
        "SAMPLING_INTERVAL_S": dt,
        "NDATA": str(len(data) if ndata is None else ndata),
        "STREAM": stream,
        "UNITS": units,
        "DATA_TYPE": "ACCELERATION",
    }
    lines = [f"{key}: {value}" for key, value in header.items()]
    lines += [f"USER_PAD{i}: " for i in range(64 - len(lines))]
    values = [v if isinstance(v, str) else f"{v:.6f}" for v in data]
    return "\n".join(lines + values) + "\n"


def write_esm(path, data, **kwargs):
    path.write_text(esm_text(data, **kwargs), encoding="latin-1")
    return path


def wave(n=2000, amplitude=50.0):
    """A band-limited test accelerogram [cm/s^2]: 2 Hz sine at 100 Hz, amplitude 0.5 m/s^2."""
    return amplitude * np.sin(2 * np.pi * 2.0 * np.arange(n) * 0.01)


def knet_text(values, duration_s=20):
    header = [
        "Origin Time       2014/12/31 23:49:00",
        "Lat.              35.785",
        "Long.             139.887",
        "Depth. (km)       84",
        "Mag.              4.2",
        "Station Code      TST001",
        "Station Lat.      35.7868",
        "Station Long.     139.9031",
        "Station Height(m) 14",
        "Record Time       2014/12/31 23:50:00",
        "Sampling Freq(Hz) 100Hz",
        f"Duration Time(s)  {duration_s}",
        "Dir.              E-W",
        "Scale Factor      7845(gal)/8223790",
        "Max. Acc. (gal)   6.847",
        "Last Correction   2014/12/31 23:49:59",
        "Memo.             ",
    ]
    rows = [
        "".join(f"{int(v):>9d}" for v in values[i : i + 8]) + " " for i in range(0, len(values), 8)
    ]
    return "\n".join(header + rows) + "\n"


def counts_trace(channel="HNN", amplitude=4000):
    data = (np.sin(np.arange(2000) / 10.0) * amplitude).astype(np.int32)
    header = {"network": "XX", "station": "MS", "location": "00", "channel": channel}
    return Trace(data=data, header={**header, "sampling_rate": 100.0, "starttime": START})


def info(*args):
    return CliRunner().invoke(main, ["info", *map(str, args)])


# --- printable -----------------------------------------------------------------------------


def test_printable_escapes_terminal_controls_and_undecodable_bytes():
    assert printable("X\x1b]0;pwned\x07") == "X\\x1b]0;pwned\\x07"
    assert printable("a\nb\tc\x7f\x9b") == "a\\x0ab\\x09c\\x7f\\x9b"
    assert printable(os.fsdecode(b"bad\xff\xfename")) == "bad\\xff\\xfename"
    assert printable(b"raw\xffbytes") == "raw\\xffbytes"
    assert printable("Perugia, Città di Castello") == "Perugia, Città di Castello"


# --- one bad sample must not decide the verdict -------------------------------------------


@pytest.mark.parametrize("bad", ["1e30", "1e10", "-1e308"])
def test_one_huge_sample_refused(tmp_path, bad):
    data = list(wave())
    data[1000] = bad
    with pytest.raises((UnitsError, RecordFormatError), match="not a plausible|spike"):
        read_stream(write_esm(tmp_path / "a.asc", data))


@pytest.mark.parametrize("bad", ["nan", "NaN", "inf", "-inf"])
def test_non_finite_text_value_refused(tmp_path, bad):
    data = list(wave())
    data[7] = bad
    with pytest.raises(RecordFormatError, match="NaN or infinite") as caught:
        read_stream(write_esm(tmp_path / "a.asc", data))
    assert "value 8 of 2000" in str(caught.value)


def test_isolated_spike_below_5g_refused(tmp_path):
    data = wave()  # peak 0.5 m/s^2
    data[1234] = 2000.0  # 20 m/s^2: plausible as a peak, not as one sample among 0.5 m/s^2
    with pytest.raises(RecordFormatError, match=r"spike.*sample 1234 \(t = 12.34 s\)"):
        read_stream(write_esm(tmp_path / "a.asc", data))
    assert read_stream(write_esm(tmp_path / "b.asc", data), check=False)


def test_real_peak_is_not_a_spike():
    # A sharp but band-limited pulse (a 10 Hz cycle at 100 Hz) is ground motion.
    acc = np.zeros(2000)
    t = np.arange(10) * 0.01
    acc[1000:1010] = 30.0 * np.sin(2 * np.pi * 10.0 * t)
    assert plausibility_findings(acc, 0.01) == []
    acc[1500] = 40.0  # the same size, but one sample among zeros
    assert [f.check for f in plausibility_findings(acc, 0.01)] == ["spike"]


def test_processing_quality_checks_include_plausibility():
    acc = np.sin(np.arange(2000) / 5.0)
    acc[100] = 1e30
    checks = {finding.check for finding in check_array(acc, 0.01)}
    assert {"implausible_peak", "spike"} <= checks
    assert check_array(np.sin(np.arange(2000) / 5.0), 0.01) == []


def test_peak_limit_is_configurable():
    acc = 60.0 * np.sin(np.arange(2000) / 5.0)  # 6.1 g
    assert [f.check for f in plausibility_findings(acc, 0.01)] == ["implausible_peak"]
    assert plausibility_findings(acc, 0.01, QualityLimits(max_peak_m_s2=100.0)) == []


def test_raw_counts_as_m_s2_refused_with_likely_cause(tmp_path):
    path = tmp_path / "counts.mseed"
    counts_trace(amplitude=2000).write(str(path), format="MSEED")
    with pytest.raises(UnitsError) as caught:
        read_stream(path, units="m/s2")
    message = str(caught.value)
    assert "is not a plausible ground acceleration" in message
    assert "raw counts? cm/s^2 given as m/s2? give --units or --stations" in message
    assert re.search(r"peak 20\d\d(\.\d+)? m/s\^2 \(20\d g\)", message)
    result = info(path, "--units", "m/s2")
    assert result.exit_code == 1
    assert result.stderr.count("\n") == 1 and result.stderr.startswith("rockscreen: error: ")
    (trace,) = read_stream(path, units="cm/s2")  # the same counts as cm/s^2 are plausible
    assert np.abs(trace.data).max() < 49.05


# --- sampling rate and truncation in every reader -----------------------------------------


@pytest.mark.parametrize("dt", ["0", "-0.01", "nan", "inf", "1e-300", "abc"])
def test_esm_bad_sampling_interval_refused(tmp_path, dt):
    with pytest.raises(RecordFormatError, match="SAMPLING_INTERVAL_S|sampling rate"):
        read_stream(write_esm(tmp_path / "a.asc", wave(), dt=dt))


@pytest.mark.parametrize("ndata", [1999, 2001, 0])
def test_esm_ndata_must_match_values(tmp_path, ndata):
    with pytest.raises(RecordFormatError, match="NDATA"):
        read_stream(write_esm(tmp_path / "a.asc", wave(), ndata=ndata))


@pytest.mark.parametrize("dt", ["0", "1e-300", "5"])
def test_at2_bad_sampling_interval_refused(tmp_path, dt):
    path = tmp_path / "RSN1_X_090.AT2"
    values = wave() / 981.0
    lines = ["PEER", "Test, 1/2/2003, Somewhere, 90", "UNITS OF G", f"NPTS= 2000, DT= {dt} SEC"]
    lines += [" ".join(f"{v:.7E}" for v in values[i : i + 5]) for i in range(0, 2000, 5)]
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(RecordFormatError, match="DT|sampling rate"):
        read_stream(path)


def _sac(tmp_path, delta):
    path = tmp_path / "x.sac"
    Trace(wave().astype(np.float32) / 981.0, header={"delta": 0.01}).write(str(path), "SAC")
    raw = bytearray(path.read_bytes())
    struct.pack_into("<f", raw, 0, delta)
    path.write_bytes(bytes(raw))
    return path


@pytest.mark.parametrize("delta", [0.0, -0.01, float("nan"), float("inf"), 1e-30, 1e30])
def test_sac_bad_delta_refused(tmp_path, delta):
    with pytest.raises(RecordFormatError):
        read_stream(_sac(tmp_path, delta), units="g")


def test_sac_sample_nan_refused(tmp_path):
    path = _sac(tmp_path, 0.01)
    raw = bytearray(path.read_bytes())
    struct.pack_into("<f", raw, 632 + 4 * 100, float("nan"))
    path.write_bytes(bytes(raw))
    with pytest.raises(RecordFormatError, match="NaN or inf"):
        read_stream(path, units="g")


@pytest.mark.parametrize("rate", [0.0, 1e9])
def test_mseed_bad_sampling_rate_refused(tmp_path, rate):
    path = tmp_path / "x.mseed"
    counts_trace().write(str(path), format="MSEED")
    raw = bytearray(path.read_bytes())
    factor, multiplier = (0, 1) if rate == 0.0 else (32767, 32767)
    for offset in range(0, len(raw), 4096):
        struct.pack_into(">hh", raw, offset + 32, factor, multiplier)
    path.write_bytes(bytes(raw))
    with pytest.raises(RecordFormatError, match="sampling rate"):
        read_stream(path, units="cm/s2")


def test_knet_truncated_file_refused(tmp_path):
    values = (np.sin(np.arange(2000) / 5.0) * 1000).astype(int)
    good = tmp_path / "TST0011412312349.EW"
    good.write_text(knet_text(values))
    (trace,) = read_stream(good)
    assert trace.stats.npts == 2000
    cut = tmp_path / "TST0011412312349.NS"
    cut.write_text(knet_text(values)[:-3000])
    with pytest.raises(RecordFormatError, match="truncated K-NET file"):
        read_stream(cut)


@pytest.mark.parametrize("rate", ["1e2Hz", "1e308Hz"])
def test_knet_sampling_frequency_not_plain_is_refused(tmp_path, rate):
    # ObsPy reads the leading digits only: "1e2Hz" would be 1 Hz, the record 100x too long.
    values = (np.sin(np.arange(2000) / 5.0) * 1000).astype(int)
    path = tmp_path / "TST0011412312349.EW"
    path.write_text(knet_text(values).replace("100Hz", rate))
    with pytest.raises(RecordFormatError, match="sampling frequency or duration is corrupt"):
        read_stream(path)


def test_ascii_encoded_mseed_refused(tmp_path):
    path = tmp_path / "text.mseed"
    text = np.frombuffer(b"this is a log message, not samples " * 20, dtype="|S1")
    Trace(text.copy(), header={"sampling_rate": 100.0, "station": "LOG"}).write(
        str(path), format="MSEED", encoding="ASCII"
    )
    with pytest.raises(RecordFormatError, match="not samples"):
        read_stream(path, units="g")
    result = info(path, "--units", "g")
    assert result.exit_code == 1 and "Traceback" not in result.output


def test_esm_velocity_is_not_read_as_acceleration(tmp_path):
    text = esm_text(wave()).replace("DATA_TYPE: ACCELERATION", "DATA_TYPE: VELOCITY")
    (tmp_path / "v.asc").write_text(text)
    with pytest.raises(UnitsError, match="DATA_TYPE 'VELOCITY' is not an acceleration"):
        read_stream(tmp_path / "v.asc")


@pytest.mark.parametrize(
    "field, value", [("STATION_LATITUDE_DEGREE", "999"), ("STATION_LONGITUDE_DEGREE", "-500")]
)
def test_impossible_station_coordinates_refused(tmp_path, field, value):
    text = esm_text(wave()).replace("USER_PAD0: ", f"{field}: {value}")
    (tmp_path / "c.asc").write_text(text)
    with pytest.raises(RecordFormatError, match="is impossible"):
        read_stream(tmp_path / "c.asc")


# --- probes read a bounded prefix; only regular files ---------------------------------------


def test_probe_reads_a_bounded_prefix(tmp_path):
    path = tmp_path / "oneline.asc"
    path.write_bytes(b"1" * (4 * PROBE_BYTES))
    lines = head_lines(path, 5)
    assert len(lines) == 1 and len(lines[0]) <= PROBE_BYTES
    with pytest.raises(RecordFormatError, match="without a line break"):
        read_stream(path)


def test_sparse_gigabyte_refused_as_binary(tmp_path):
    path = tmp_path / "sparse.mseed"
    with open(path, "wb") as handle:
        handle.truncate(1 << 30)  # sparse: no disk used
    with pytest.raises(RecordFormatError, match="binary, and neither miniSEED nor SAC"):
        read_stream(path, units="g")


def test_glob_characters_in_a_name_read_that_file(tmp_path):
    write_esm(tmp_path / "a.asc", wave(), station="AAA")
    bracketed = write_esm(tmp_path / "[a].asc", wave(), station="BRK")
    (trace,) = read_stream(bracketed)
    assert trace.stats.station == "BRK"


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX file types")
def test_non_regular_files_refused(tmp_path):
    fifo = tmp_path / "pipe.mseed"
    os.mkfifo(fifo)
    with pytest.raises(RecordFormatError, match="FIFO"):
        read_stream(fifo, units="g")
    zero = tmp_path / "zero.mseed"
    zero.symlink_to("/dev/zero")
    with pytest.raises(RecordFormatError, match="character device"):
        read_stream(zero, units="g")
    loop_a, loop_b = tmp_path / "a.mseed", tmp_path / "b.mseed"
    loop_a.symlink_to(loop_b)
    loop_b.symlink_to(loop_a)
    with pytest.raises(RecordFormatError, match="symbolic link loop"):
        read_stream(loop_a, units="g")
    with pytest.raises(RecordFormatError, match="is a folder"):
        read_stream(tmp_path, units="g")


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX byte file names")
def test_non_utf8_file_name_read_and_printed_escaped(tmp_path):
    raw = os.fsencode(tmp_path) + b"/bad\xff\xfename.asc"
    with open(raw, "wb") as handle:
        handle.write(esm_text(wave()).encode())
    (trace,) = read_stream(raw)
    assert trace.stats.station == "ESM"
    bad = os.fsencode(tmp_path) + b"/bad\xfe.asc"
    with open(bad, "wb") as handle:
        handle.write(b"hello\n")
    with pytest.raises(RecordFormatError) as caught:
        read_stream(bad)
    assert "bad\\xfe.asc" in str(caught.value)
    str(caught.value).encode("utf-8")  # printable: no lone surrogate left


# --- hostile header strings ------------------------------------------------------------------


@pytest.mark.parametrize(
    "station",
    ["AB/CD", "../..", ".", "X\x1b[2J\x1b]0;pwned\x07", "S" * 5000, "A\x00B", "??", "Città"],
)
def test_hostile_station_codes_refused_with_one_escaped_line(tmp_path, station):
    path = write_esm(tmp_path / "a.asc", wave(), station=station)
    with pytest.raises(RecordFormatError, match="station code") as caught:
        read_stream(path)
    message = str(caught.value)
    assert printable(message) == message and len(message) < 400
    result = info(path)
    assert result.exit_code == 1
    assert "\x1b" not in result.output and result.stderr.count("\n") == 1


def test_at2_station_from_an_odd_file_name_is_a_code(tmp_path):
    path = tmp_path / "my record.v2.AT2"
    values = wave() / 981.0
    lines = ["TITLE", "The units are (g)", "NPTS= 2000, DT= .01 SEC"]
    lines += [" ".join(f"{v:.7E}" for v in values[i : i + 5]) for i in range(0, 2000, 5)]
    path.write_text("\n".join(lines) + "\n")
    (trace,) = read_stream(path)
    assert trace.stats.station == "my_record_v2"


# --- command-line arguments: folders, globs, duplicates, units --------------------------------


def test_expand_record_paths(tmp_path):
    folder = tmp_path / "records"
    folder.mkdir()
    a = write_esm(folder / "a.asc", wave())
    b = write_esm(folder / "b.ASC", wave(), station="BBB")
    (folder / "notes.txt").write_text("not a record\n")
    (folder / ".hidden.asc").write_text("x")
    paths, notes = expand_record_paths([folder])
    assert paths == [str(a), str(b)]
    assert notes == [f"{folder}: 2 record file(s), 1 file(s) of other extensions ignored"]
    pattern = str(folder / "*.asc")
    paths, notes = expand_record_paths([pattern, a, folder / "." / "a.asc"])
    assert paths == [str(a)]
    assert notes[0] == f"{pattern}: 1 file(s) match"
    assert notes[1:] == [f"{a}: the same file as {a}; read once"] * 2
    missing = tmp_path / "absent.asc"
    assert expand_record_paths([missing]) == ([str(missing)], [])
    with pytest.raises(RecordFormatError, match="no such file or folder"):
        expand_record_paths([missing], strict=True)
    with pytest.raises(RecordFormatError, match="no file matches this pattern"):
        expand_record_paths([tmp_path / "*.none"], strict=True)
    empty = tmp_path / "empty"
    empty.mkdir()
    with pytest.raises(RecordFormatError, match="holds no files"):
        expand_record_paths([empty])


def test_info_reads_a_folder_a_quoted_glob_and_a_duplicate_once(tmp_path):
    folder = tmp_path / "records"
    folder.mkdir()
    write_esm(folder / "a.asc", wave(), station="AAA")
    write_esm(folder / "b.asc", wave(), station="BBB")
    result = info(folder, "--json")
    assert result.exit_code == 0, result.output
    assert [e["id"] for e in json.loads(result.stdout)] == ["XX.AAA..HNE", "XX.BBB..HNE"]
    result = info(str(folder / "*.asc"), folder / "a.asc", "--json")
    assert result.exit_code == 0, result.output
    assert len(json.loads(result.stdout)) == 2
    assert "read once" in result.stderr
    result = info(str(folder / "*.none"))
    assert result.exit_code == 1
    assert (
        result.stderr.strip()
        == f"rockscreen: error: {folder / '*.none'}: no file matches this pattern"
    )


def test_spectrum_takes_a_quoted_glob_of_one_file(tmp_path):
    write_esm(tmp_path / "a.asc", wave())
    result = CliRunner().invoke(main, ["spectrum", str(tmp_path / "*.asc"), "--periods", "0,0.5"])
    assert result.exit_code == 0, result.output
    write_esm(tmp_path / "b.asc", wave(), station="BBB")
    result = CliRunner().invoke(main, ["spectrum", str(tmp_path / "*.asc")])
    assert result.exit_code == 2 and "gives 2 files" in result.output


@pytest.mark.parametrize("command", ["info", "spectrum"])
def test_unknown_units_is_a_usage_error(tmp_path, command):
    path = write_esm(tmp_path / "a.asc", wave())
    result = CliRunner().invoke(main, [command, str(path), "--units", "mg"])
    assert result.exit_code == 2
    assert result.output.count("unknown acceleration unit 'mg'") == 1


# --- vertical / horizontal ratio: a flag the user sees ----------------------------------------


def _three_components(z_gain):
    traces = []
    for channel, gain in (("HNN", 1.0), ("HNE", 1.0), ("HNZ", z_gain)):
        data = gain * np.sin(np.arange(2000) / 7.0 + len(traces))
        header = {"network": "IT", "station": "AQA", "channel": channel, "delta": 0.01}
        traces.append(Trace(data, header={**header, "starttime": START}))
    return Stream(traces)


def test_vertical_three_times_horizontals_is_flagged_on_the_record():
    (record,) = group_records(_three_components(3.0))
    (flag,) = record.quality_flags
    assert re.match(r"vertical_ratio: vertical peak 3\.\d+ m/s\^2 is 2\.9\d times the larger", flag)
    (record,) = group_records(_three_components(0.7))
    assert record.quality_flags == []


def test_info_shows_the_vertical_ratio_flag(tmp_path):
    for channel, gain in (("HNN", 1.0), ("HNE", 1.0), ("HNZ", 3.0)):
        write_esm(tmp_path / f"{channel}.asc", gain * wave(), stream=channel)
    result = info(*sorted(glob.glob(str(tmp_path / "*.asc"))), "--json")
    assert result.exit_code == 0, result.output
    assert "rockscreen: warning: XX.ESM..HN: vertical_ratio:" in result.stderr
    entries = json.loads(result.stdout)
    assert all(e["quality_flags"][0].startswith("vertical_ratio") for e in entries)


# --- StationXML: no DTD, no entities ----------------------------------------------------------

XXE = """<?xml version="1.0" encoding="UTF-8"?>
<!DOCTYPE FDSNStationXML [<!ENTITY secret SYSTEM "file:///etc/passwd">]>
<FDSNStationXML xmlns="http://www.fdsn.org/xml/station/1" schemaVersion="1.1">
  <Source>&secret;</Source><Created>2021-01-01T00:00:00</Created>
</FDSNStationXML>
"""


@pytest.mark.parametrize("encoding", ["utf-8", "utf-16"])
def test_stationxml_with_entities_refused(tmp_path, encoding):
    path = tmp_path / "evil.xml"
    path.write_text(XXE.replace("UTF-8", encoding.upper()), encoding=encoding)
    with pytest.raises(StationMetadataError, match="DOCTYPE declaration"):
        read_station_metadata(path)
    result = info(write_esm(tmp_path / "a.asc", wave()), "--stations", path)
    assert result.exit_code == 1
    assert result.stderr.count("\n") == 1 and "root:" not in result.output
