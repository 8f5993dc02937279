"""ObsPy waveform plugin for ESM/ITACA ASCII files ("DYNA 1.2" header).

The format: 64 header lines ``KEY: value`` (network, station, coordinates, first-sample
time, sampling interval, number of samples, units, processing...), then one value per
line. The raw AFAD files distributed in the same layout write dates as ``dd/mm/yyyy``
and times as ``hh:mm:ss.sss``; both spellings are read.

Registered under the ``obspy.plugin.waveform`` entry points (see ``pyproject.toml``),
so ``obspy.read("X.ACC.ASC")`` returns a :class:`obspy.Stream` whose trace carries the
full header in ``stats.esm`` (strings, keys as in the file), the station coordinates in
``stats.coordinates`` and the data in the file's units (``stats.esm["UNITS"]``);
:func:`rockscreen.pipeline.records.io.read_stream` converts them to m/s^2.
"""

from __future__ import annotations

import re

import numpy as np
from obspy import Stream, Trace, UTCDateTime
from obspy.core.util import AttribDict

from rockscreen.pipeline.errors import RecordFormatError
from rockscreen.pipeline.records.readers.text import (
    PLUGIN_DOCS,
    check_sampling,
    probe_lines,
    read_lines,
    read_values,
)
from rockscreen.solver.docstrings import fill_doc

#: Number of header lines of a DYNA 1.2 file.
HEADER_LINES = 64

#: Header keys a time series cannot be read without.
REQUIRED_KEYS = ("NETWORK", "STATION_CODE", "STREAM", "SAMPLING_INTERVAL_S", "NDATA", "UNITS")

#: ``DATA_TYPE`` values that are time series (spectra such as ``*.SA.ASC`` are not).
TIME_SERIES_TYPES = ("ACCELERATION", "VELOCITY", "DISPLACEMENT")

_KEY_LINE = re.compile(r"^([A-Z0-9_/^.\-]+):(.*)$")
_FIRST_SAMPLE_KEY = "DATE_TIME_FIRST_SAMPLE_YYYYMMDD_HHMMSS"


@fill_doc(PLUGIN_DOCS)
def is_esm(filename) -> bool:
    """Tell whether ``filename`` is an ESM/ITACA ASCII file (never raises).

    It is when the first lines are ``KEY: value`` lines starting with ``EVENT_NAME`` and the
    header names the network, station and sampling interval.

    %(probe_sections)s
    """
    return probe_lines(filename, HEADER_LINES, _names_the_station)


def _names_the_station(lines: list[str]) -> bool:
    """Whether ``lines`` open with ``EVENT_NAME`` and name network, station and sampling."""
    if not lines or not lines[0].startswith("EVENT_NAME:"):
        return False
    keys = {m.group(1) for m in map(_KEY_LINE.match, lines) if m}
    return {"NETWORK", "STATION_CODE", "SAMPLING_INTERVAL_S"} <= keys


def _parse_header(lines: list[str], filename) -> dict[str, str]:
    header = {}
    for number, line in enumerate(lines, start=1):
        match = _KEY_LINE.match(line)
        if match is None:
            raise RecordFormatError(
                f"{filename}: ESM header line {number} is not 'KEY: value': {line[:60]!r}"
            )
        header[match.group(1)] = match.group(2).strip()
    data_type = header.get("DATA_TYPE", "ACCELERATION").upper()
    if data_type not in TIME_SERIES_TYPES:
        raise RecordFormatError(
            f"{filename}: ESM DATA_TYPE {header.get('DATA_TYPE')!r} is not a time series "
            f"(allowed: {', '.join(TIME_SERIES_TYPES)}); response-spectrum files are not records"
        )
    missing = [key for key in REQUIRED_KEYS if not header.get(key)]
    if missing:
        raise RecordFormatError(f"{filename}: ESM header lacks {', '.join(missing)}")
    return header


def _parse_first_sample(text: str, filename) -> UTCDateTime:
    """Parse ``yyyymmdd_hhmmss.sss`` (ESM) or ``dd/mm/yyyy hh:mm:ss.sss`` (AFAD)."""
    text = text.strip()
    patterns = (
        r"^(?P<y>\d{4})(?P<mo>\d{2})(?P<d>\d{2})_(?P<h>\d{2})(?P<mi>\d{2})(?P<s>\d{2}(?:\.\d*)?)$",
        r"^(?P<d>\d{1,2})/(?P<mo>\d{1,2})/(?P<y>\d{4})[ T_]+"
        r"(?P<h>\d{1,2}):(?P<mi>\d{2}):(?P<s>\d{2}(?:\.\d*)?)$",
    )
    for pattern in patterns:
        match = re.match(pattern, text)
        if match:
            parts = match.groupdict()
            try:
                base = UTCDateTime(
                    int(parts["y"]),
                    int(parts["mo"]),
                    int(parts["d"]),
                    int(parts["h"]),
                    int(parts["mi"]),
                )
            except ValueError as exc:
                raise RecordFormatError(
                    f"{filename}: invalid first-sample time {text!r}: {exc}"
                ) from exc
            return base + float(parts["s"])
    raise RecordFormatError(
        f"{filename}: first-sample time {text!r} is neither yyyymmdd_hhmmss.sss "
        "nor dd/mm/yyyy hh:mm:ss.sss"
    )


def _number(header: dict[str, str], key: str, filename, *, kind=float):
    try:
        return kind(header[key])
    except (KeyError, ValueError) as exc:
        raise RecordFormatError(
            f"{filename}: ESM header {key}={header.get(key)!r} is not a valid {kind.__name__}"
        ) from exc


def _optional_float(text: str | None) -> float:
    try:
        return float(text) if text else float("nan")
    except ValueError:
        return float("nan")


def _location_code(text: str) -> str:
    # AFAD files put a place name in LOCATION; only a SEED location code (<= 2 chars) is kept.
    return text if re.fullmatch(r"[A-Za-z0-9]{0,2}", text) else ""


@fill_doc(PLUGIN_DOCS)
def read_esm(filename, headonly: bool = False, **kwargs) -> Stream:
    """Read an ESM/ITACA ASCII time series into a one-trace :class:`obspy.Stream`.

    Parameters
    ----------
    filename : str or path-like
        The ``*.ASC`` / ``*.asc`` file.
    %(read_options)s

    Returns
    -------
    obspy.Stream
        One trace in the file's units; ``stats.esm`` holds the header (strings),
        ``stats.coordinates`` latitude [deg], longitude [deg], elevation [m].

    Raises
    ------
    RecordFormatError
        If the header is malformed, the file is a spectrum rather than a time series,
        or the number of values differs from ``NDATA`` (truncated file).
    """
    lines = read_lines(filename)
    if len(lines) < HEADER_LINES:
        raise RecordFormatError(
            f"{filename}: truncated ESM header ({len(lines)} of {HEADER_LINES} lines)"
        )
    header = _parse_header(lines[:HEADER_LINES], filename)
    delta = check_sampling(
        _number(header, "SAMPLING_INTERVAL_S", filename), "SAMPLING_INTERVAL_S", filename
    )
    npts = _number(header, "NDATA", filename, kind=int)
    if npts < 1:
        raise RecordFormatError(
            f"{filename}: ESM header NDATA={npts} is not a number of samples (allowed: >= 1)"
        )
    starttime = _parse_first_sample(header.get(_FIRST_SAMPLE_KEY, ""), filename)

    if headonly:
        data = np.array([], dtype=np.float64)
    else:
        data = read_values(lines[HEADER_LINES:], npts, "NDATA", filename)

    trace = Trace(data=data)
    stats = trace.stats
    stats.network = header["NETWORK"]
    stats.station = header["STATION_CODE"]
    stats.location = _location_code(header.get("LOCATION", ""))
    stats.channel = header["STREAM"]
    stats.delta = delta
    stats.starttime = starttime
    if headonly:
        stats.npts = npts
    stats.esm = AttribDict(header)
    stats.coordinates = AttribDict(
        latitude=_optional_float(header.get("STATION_LATITUDE_DEGREE")),
        longitude=_optional_float(header.get("STATION_LONGITUDE_DEGREE")),
        elevation=_optional_float(header.get("STATION_ELEVATION_M")),
    )
    return Stream([trace])


def esm_units(trace: Trace) -> str:
    """Return the units string of an ESM trace's header (e.g. ``cm/s^2``)."""
    return str(trace.stats.esm["UNITS"])


__all__ = ["HEADER_LINES", "esm_units", "is_esm", "read_esm"]
