"""ObsPy waveform plugin for PEER NGA ``*.AT2`` acceleration files.

Two layouts are read:

* PEER NGA (West1/West2): four header lines -- title, ``event, date, station, component``,
  ``ACCELERATION TIME SERIES IN UNITS OF G``, ``NPTS=  7999, DT=   .0050 SEC`` -- then the
  values, several per line (usually 5E15.7);
* the legacy "AT2-like" text of many teaching files (e.g. the El Centro 1940 record):
  free-text title lines, a line stating ``The units are (g)``, the same ``NPTS=, DT=`` line,
  then 8F10.5 values. The old PEER ``  4000   .0050   NPTS, DT`` line is also recognised.

AT2 files carry no absolute time: ``starttime`` is left at ObsPy's default
1970-01-01T00:00:00 (read it as "unknown"); the event date of the title, when present, is in
``stats.at2["date"]``. The station code is ``RSN<n>`` for NGA file names ``RSN<n>_...`` (the
record sequence number identifies station and event, so the components of one record
group together), otherwise the file stem with every character other than a letter, digit,
``_`` or ``-`` replaced by ``_`` (at most 64 characters); the channel is the component
azimuth (``067``, ``337``...) or vertical token (``UP``, ``DWN``, ``V``) of the title, or
``NS``/``EW``/``UD`` when a legacy free-text title names the component ("North South
Component"); else empty.
Header units go to ``stats.at2["units"]`` (``g``, ``cm/s2``, ``m/s2``, or the raw text).
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
from obspy import Stream, Trace
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

#: How many leading lines may hold the header (the ``NPTS``/``DT`` line ends it).
MAX_HEADER_LINES = 10

_NPTS_DT = (
    re.compile(r"NPTS\s*=\s*(?P<npts>\d+)\s*,?\s*DT\s*=\s*(?P<dt>[0-9.Ee+-]+)", re.IGNORECASE),
    re.compile(r"^\s*(?P<npts>\d+)\s+(?P<dt>[0-9.Ee+-]+)\s+NPTS\s*,\s*DT", re.IGNORECASE),
)
_UNITS = (
    re.compile(r"UNITS\s+OF\s+\(?\s*([A-Za-z/*^0-9]+)", re.IGNORECASE),
    re.compile(r"UNITS\s+ARE\s*\(?\s*([A-Za-z/*^0-9]+)", re.IGNORECASE),
)
_UNIT_NAMES = {
    "G": "g",
    "CM/S/S": "cm/s2",
    "CM/SEC/SEC": "cm/s2",
    "CM/S^2": "cm/s2",
    "CM/S2": "cm/s2",
    "CM/S**2": "cm/s2",
    "GAL": "cm/s2",
    "M/S/S": "m/s2",
    "M/S^2": "m/s2",
    "M/S2": "m/s2",
    "M/S**2": "m/s2",
}
_VERTICAL_TOKENS = ("UP", "DWN", "DN", "V", "VER", "VERT", "Z", "UD")


def _find_npts_dt(lines: list[str]):
    """Return ``(index, npts, dt)`` of the header's ``NPTS``/``DT`` line, or None."""
    for index, line in enumerate(lines[:MAX_HEADER_LINES]):
        for pattern in _NPTS_DT:
            match = pattern.search(line)
            if match:
                try:
                    return index, int(match.group("npts")), float(match.group("dt"))
                except ValueError:
                    return None
    return None


@fill_doc(PLUGIN_DOCS)
def is_at2(filename) -> bool:
    """Tell whether ``filename`` is a PEER AT2 (or legacy AT2-like) file (never raises).

    It is when one of the first lines is an ``NPTS=..., DT=...`` line and the line after it
    holds numbers only.

    %(probe_sections)s
    """
    # One line past the header, to see whether the values start there.
    return probe_lines(filename, MAX_HEADER_LINES + 1, _values_follow_header)


def _values_follow_header(lines: list[str]) -> bool:
    """Whether ``lines`` hold an ``NPTS``/``DT`` line followed by a line of numbers."""
    found = _find_npts_dt(lines)
    if found is None or found[0] + 1 >= len(lines):
        return False
    return bool([float(value) for value in lines[found[0] + 1].split()])


def _units(header_lines: list[str]) -> str | None:
    for line in header_lines:
        for pattern in _UNITS:
            match = pattern.search(line)
            if match:
                raw = match.group(1).strip().upper()
                return _UNIT_NAMES.get(raw, raw.lower())
    return None


def _title_fields(header_lines: list[str]) -> dict[str, str]:
    """Event, date, station name and component from an NGA ``event, date, station, comp`` line."""
    if len(header_lines) < 2:
        return {}
    fields = [field.strip() for field in header_lines[1].split(",")]
    if len(fields) < 4 or not re.fullmatch(r"\d{1,2}/\d{1,2}/\d{2,4}", fields[1]):
        return {}
    return {
        "event": fields[0],
        "date": fields[1],
        "station_name": ", ".join(fields[2:-1]),
        "component": fields[-1],
    }


def _channel(component: str) -> str:
    token = component.strip().upper()
    if re.fullmatch(r"\d{1,3}", token):
        return f"{int(token):03d}"
    return token if token in _VERTICAL_TOKENS else ""


def _legacy_component(header_lines: list[str]) -> str:
    """``NS``, ``EW`` or ``UD`` when a free-text title names the component, else ``""``."""
    text = " ".join(header_lines).lower()
    for pattern, code in (
        (r"north[\s-]*south", "NS"),
        (r"east[\s-]*west", "EW"),
        (r"\bvertical\b|up[\s-]*down", "UD"),
    ):
        if re.search(pattern, text):
            return code
    return ""


def _station(filename) -> str:
    stem = Path(str(filename)).stem
    match = re.match(r"^(RSN\d+)_", stem, re.IGNORECASE)
    if match:
        return match.group(1).upper()
    # A file name may hold anything; a station code holds letters, digits, '_' and '-'
    # (a '.' would split the trace id NET.STA.LOC.CHA, a control character would reach the
    # terminal). The cut keeps the code within the limit of every station code.
    return re.sub(r"[^A-Za-z0-9_-]", "_", stem)[:64] or "AT2"


@fill_doc(PLUGIN_DOCS)
def read_at2(filename, headonly: bool = False, **kwargs) -> Stream:
    """Read a PEER AT2 file into a one-trace :class:`obspy.Stream`.

    Parameters
    ----------
    filename : str or path-like
        The ``*.AT2`` file.
    %(read_options)s

    Returns
    -------
    obspy.Stream
        One trace in the file's units; ``stats.at2`` holds ``header`` (the header lines),
        ``units`` (or None when the header does not state them), ``npts``, ``dt`` [s] and,
        for NGA files, ``event``, ``date``, ``station_name``, ``component``.

    Raises
    ------
    RecordFormatError
        If the ``NPTS``/``DT`` line is missing or invalid, a value is not a number, or the
        number of values differs from ``NPTS`` (truncated file).
    """
    lines = read_lines(filename)
    found = _find_npts_dt(lines)
    if found is None:
        raise RecordFormatError(
            f"{filename}: no 'NPTS=..., DT=...' line in the first {MAX_HEADER_LINES} lines"
        )
    index, npts, dt = found
    if npts < 1:
        raise RecordFormatError(
            f"{filename}: AT2 header NPTS={npts} is not a number of samples (allowed: >= 1)"
        )
    check_sampling(dt, "DT", filename)
    header_lines = lines[: index + 1]

    if headonly:
        data = np.array([], dtype=np.float64)
    else:
        data = read_values(lines[index + 1 :], npts, "NPTS", filename)

    title = _title_fields(header_lines)
    trace = Trace(data=data)
    stats = trace.stats
    stats.station = _station(filename)
    stats.channel = _channel(title["component"]) if title else _legacy_component(header_lines)
    stats.delta = dt
    if headonly:
        stats.npts = npts
    stats.at2 = AttribDict(
        header=header_lines, units=_units(header_lines), npts=npts, dt=dt, **title
    )
    return Stream([trace])


__all__ = ["is_at2", "read_at2"]
