"""Read any supported record file to an ObsPy ``Stream`` in m/s^2, units never guessed.

How each format's units are determined (``stats.rockscreen["units_source"]``):

========================  ==================================================================
format (``_format``)      units
========================  ==================================================================
ESM (ESM/ITACA ASCII)     header ``UNITS`` (``cm/s^2``)                        -> ``header``
AT2 (PEER NGA, legacy)    header ``UNITS OF G`` / ``units are (g)``            -> ``header``
KNET (K-NET/KiK-net)      counts x ``stats.calib`` (ObsPy: header scale factor, m/s^2 per count)
                          -> ``calibration``
MSEED and other formats   counts / StationXML instrument sensitivity, accelerometers only
                          (input units an acceleration, e.g. ``M/S**2``)       -> ``stationxml``;
                          or the units the user states                         -> ``user``
SAC                       only the units the user states (SAC has no unit field) -> ``user``
========================  ==================================================================

A format whose file states its units uses them; ``units`` given by the user applies only to
files that carry none. Anything else is a :class:`~pipeline.errors.UnitsError` that says how
to state the units. Unreadable files raise :class:`~rockscreen.pipeline.errors.RecordFormatError`
naming the file and the reason.

Nothing in a file makes rockscreen read anything beyond it: the format is told from the
first 64 KiB (:mod:`rockscreen.pipeline.records.probe`), ObsPy gets the path escaped (no glob
expansion, no URL download, no decompression), and only non-empty regular files are read
(:func:`rockscreen.pipeline.records.paths.check_record_file`). Every trace is then checked: codes of
letters, digits, ``_`` and ``-``; a sampling rate in :data:`SAMPLING_RATE_RANGE_HZ`; numeric
samples, as many as the header announces; and, in m/s^2, samples that can be ground
acceleration (finite, peak at most 5 g, no isolated spike:
:func:`rockscreen.pipeline.records.quality.plausibility_findings`).
"""

from __future__ import annotations

import glob
import math
import os
import sys
import warnings
from pathlib import Path

import numpy as np
from obspy import Stream, Trace, read
from obspy.core.util import AttribDict
from scipy.integrate import cumulative_trapezoid

from rockscreen.pipeline.errors import (
    RecordFormatError,
    RockscreenError,
    StationMetadataError,
    UnitsError,
)
from rockscreen.pipeline.records.paths import check_record_file, expand_record_paths
from rockscreen.pipeline.records.probe import detect_format
from rockscreen.pipeline.records.quality import QualityLimits, plausibility_findings
from rockscreen.pipeline.records.readers.esm import esm_units
from rockscreen.pipeline.records.validate import (
    CODE_PATTERN,
    SAMPLING_RATE_RANGE_HZ,
    check_coordinates,
    validate_trace,
)
from rockscreen.pipeline.text import printable
from rockscreen.pipeline.units import unit_factor
from rockscreen.stations.stationxml import StationMetadata, read_station_metadata

#: Units of every trace :func:`read_stream` returns.
OUTPUT_UNITS = "m/s2"

#: Formats whose traces must carry user-stated units (no unit field, no calibration).
USER_UNITS_ONLY = ("SAC",)

_HOW_TO_STATE = "state them with --units g|m/s2|cm/s2 (or 'units' in the configuration)"
_SAC_UNSET = -12345.0
_COORDINATE_KEYS = ("latitude", "longitude", "elevation")
_IGNORED_WARNINGS = (DeprecationWarning, PendingDeprecationWarning, FutureWarning)


def _one_line(text: str) -> str:
    return printable(" ".join(str(text).split()))


def _check_file(path: Path) -> None:
    check_record_file(path)


def _obspy_read(path: Path, headonly: bool = False) -> Stream:
    """Read with the format detected on a bounded prefix; ObsPy's warnings refuse the file.

    The path goes to ObsPy escaped and absolute: ``obspy.read`` expands glob patterns and
    downloads URLs, and a file named ``[a].mseed`` must not read ``a.mseed``.
    """
    name = printable(str(path))
    fmt = detect_format(path)
    target = glob.escape(os.path.abspath(path))
    unraisable = []  # libmseed's log callback can fail on a corrupt record's garbage bytes
    previous_hook = sys.unraisablehook
    sys.unraisablehook = unraisable.append
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            stream = read(target, format=fmt, headonly=headonly, check_compression=False)
    except RecordFormatError:
        raise
    except TypeError as exc:
        if "Unknown format" in str(exc):
            raise RecordFormatError(
                f"{name}: unknown format (not ESM/ITACA ASCII, PEER AT2, K-NET, miniSEED, SAC "
                "or another format ObsPy reads)"
            ) from exc
        raise RecordFormatError(f"{name}: unreadable: {_one_line(exc)}") from exc
    except Exception as exc:  # ObsPy's format readers raise many types on corrupt files
        reason = _one_line(exc) or type(exc).__name__
        raise RecordFormatError(f"{name}: unreadable (corrupt or truncated?): {reason}") from exc
    finally:
        sys.unraisablehook = previous_hook
    if unraisable:
        raise RecordFormatError(
            f"{name}: corrupt {fmt or 'record'} file: the reader failed on it "
            f"({_one_line(unraisable[0].exc_value) or unraisable[0].exc_type.__name__})"
        )
    problems = [w for w in caught if not issubclass(w.category, _IGNORED_WARNINGS)]
    if problems:
        raise RecordFormatError(
            f"{name}: corrupt or truncated {fmt or 'record'} file: the reader reports "
            f"{_one_line(problems[0].message)}"
        )
    if len(stream) == 0:
        raise RecordFormatError(f"{name}: no traces in the file")
    return stream


def file_format(path) -> str:
    """Return the format ObsPy (with rockscreen's plugins) detects for a file.

    Parameters
    ----------
    path : str or path-like
        The record file.

    Returns
    -------
    str
        ObsPy's format name: ``ESM``, ``AT2``, ``KNET``, ``MSEED``, ``SAC``...

    Raises
    ------
    RecordFormatError
        If the file is missing, not a regular file, empty or of an unknown format.
    """
    path = Path(os.fsdecode(path))
    _check_file(path)
    return str(_obspy_read(path, headonly=True)[0].stats._format)


def trace_format(trace: Trace) -> str:
    """Return the format a trace returned by :func:`read_stream` was read as."""
    return str(trace.stats.rockscreen["format"])


def _header_units(trace: Trace, fmt: str, path: Path) -> tuple[str, float, str] | None:
    """``(units_in, factor to m/s^2, source)`` for formats whose files state units."""
    stats = trace.stats
    if fmt == "ESM":
        data_type = str(stats.esm.get("DATA_TYPE", "ACCELERATION")).strip().upper()
        if data_type != "ACCELERATION":
            raise UnitsError(
                f"{printable(str(path))}: {trace.id}: ESM DATA_TYPE {printable(data_type)!r} is "
                "not an acceleration (rockscreen reads accelerograms: DATA_TYPE ACCELERATION)"
            )
        units_in = esm_units(trace)
        return units_in, _factor(units_in, path, trace, "ESM header UNITS"), "header"
    if fmt == "AT2":
        units_in = stats.at2.get("units")
        if units_in is None:
            return None
        return units_in, _factor(units_in, path, trace, "AT2 header"), "header"
    if fmt == "KNET":
        # ObsPy's K-NET reader turns the header scale factor (gal per count) into calib
        # in m/s^2 per count (0.01 x numerator / denominator): counts * calib = m/s^2.
        return "counts", float(stats.calib), "calibration"
    return None


def _factor(units_in: str, path: Path, trace: Trace, where: str) -> float:
    try:
        return unit_factor(units_in)
    except UnitsError as exc:
        raise UnitsError(
            f"{printable(str(path))}: {trace.id}: {where} states {printable(units_in)!r}, "
            "not an acceleration "
            "(rockscreen reads accelerograms: g, m/s2, cm/s2)"
        ) from exc


def _stationxml_units(trace: Trace, meta: StationMetadata, path: Path):
    if trace.stats._format in USER_UNITS_ONLY:
        return None
    if not meta.has_channel(trace.id, trace.stats.starttime):
        return None
    sens = meta.sensitivity(trace.id, trace.stats.starttime)
    try:
        per_unit = unit_factor(sens.input_units)
    except UnitsError as exc:
        raise UnitsError(
            f"{printable(str(path))}: {trace.id}: StationXML input units "
            f"{printable(sens.input_units)!r} are not an "
            "acceleration; rockscreen reads accelerometer channels only"
        ) from exc
    # Strong-motion practice (gmprocess): an accelerometer's response is flat over the
    # band of engineering interest, so dividing by the overall sensitivity suffices.
    return "counts", per_unit / sens.value, "stationxml"


def _units_for(trace: Trace, path: Path, units: str | None, meta: StationMetadata | None):
    fmt = str(trace.stats._format)
    found = _header_units(trace, fmt, path)
    if found is None and meta is not None:
        found = _stationxml_units(trace, meta, path)
    if found is None and units is not None:
        found = units, unit_factor(units), "user"
    if found is None:
        hint = "" if fmt in USER_UNITS_ONLY else ", or give the instrument response with --stations"
        raise UnitsError(
            f"{printable(str(path))}: {fmt} trace {trace.id} carries no units rockscreen can "
            "trust; "
            f"{_HOW_TO_STATE}{hint}"
        )
    return found


def _header_coordinates(trace: Trace) -> dict[str, float] | None:
    stats = trace.stats
    if "coordinates" in stats:
        return {key: float(stats.coordinates[key]) for key in _COORDINATE_KEYS}
    # K-NET and SAC headers both name them stla, stlo, stel (SAC marks unset with -12345).
    for key in ("knet", "sac"):
        if key in stats and "stla" in stats[key] and "stlo" in stats[key]:
            values = [float(stats[key].get(name, _SAC_UNSET)) for name in ("stla", "stlo", "stel")]
            if values[0] == _SAC_UNSET or values[1] == _SAC_UNSET:
                return None
            elevation = values[2] if values[2] != _SAC_UNSET else math.nan
            return {"latitude": values[0], "longitude": values[1], "elevation": elevation}
    return None


def _attach_coordinates(trace: Trace, meta: StationMetadata | None, name: str) -> str | None:
    code = f"{trace.stats.network}.{trace.stats.station}"
    coordinates, source = None, None
    if meta is not None:
        try:
            coordinates, source = meta.coordinates(code), "stationxml"
        except StationMetadataError:
            coordinates = None
        if meta.has_channel(trace.id, trace.stats.starttime):
            trace.stats.orientation = AttribDict(meta.orientation(trace.id, trace.stats.starttime))
    if coordinates is None:
        coordinates, source = _header_coordinates(trace), "header"
    if coordinates is None:
        return None
    check_coordinates(trace, coordinates, source, name)
    trace.stats.coordinates = AttribDict(coordinates)
    return source


def _plausibility_hint(trace: Trace, units_in: str, source: str) -> str:
    if source == "user":
        return f"raw counts? cm/s^2 given as {units_in}? give --units or --stations"
    if source == "stationxml":
        return "is the StationXML sensitivity this channel's? or the samples are corrupt"
    return f"the {trace.stats._format} header states {units_in}: header or samples corrupt"


def _check_plausible(trace: Trace, name: str, units_in: str, source: str, limits) -> None:
    findings = plausibility_findings(trace.data, float(trace.stats.delta), limits)
    if not findings:
        return
    reasons = "; ".join(str(finding) for finding in findings)
    message = f"{name}: {trace.id}: {reasons}"
    if any(finding.check == "implausible_peak" for finding in findings):
        raise UnitsError(f"{message}: {_plausibility_hint(trace, units_in, source)}")
    raise RecordFormatError(message)


def read_stream(
    path,
    *,
    units: str | None = None,
    stations=None,
    check: bool = True,
    limits: QualityLimits | None = None,
) -> Stream:
    """Read a record file to a :class:`obspy.Stream` whose traces are all in m/s^2.

    Parameters
    ----------
    path : str, bytes or path-like
        The record file (any format in the module table).
    units : str, optional
        Units of files that carry none (SAC; miniSEED without StationXML): ``g``,
        ``m/s2`` or ``cm/s2``. Files stating their own units ignore it.
    stations : str, path-like, obspy.Inventory or StationMetadata, optional
        StationXML: instrument sensitivities for counts, station coordinates and
        channel orientations.
    check : bool
        Refuse samples that cannot be ground acceleration (default True): NaN or inf, a
        peak above ``limits.max_peak_m_s2`` (5 g), an isolated spike
        (:func:`rockscreen.pipeline.records.quality.plausibility_findings`).
    limits : QualityLimits, optional
        Thresholds of those checks.

    Returns
    -------
    obspy.Stream
        Float64 traces in m/s^2 with ``stats.calib = 1``; ``stats.rockscreen`` holds
        ``format``, ``file``, ``units_in``, ``units`` (``"m/s2"``), ``units_source``,
        ``factor``, ``quality_flags`` (list of str, empty when none) and ``provenance``
        (list of dicts); ``stats.coordinates`` (latitude [deg], longitude [deg],
        elevation [m]) when StationXML or the file header gives them, and
        ``stats.orientation`` (azimuth, dip [deg]) from StationXML.

    Raises
    ------
    RecordFormatError
        If the file is missing, not a regular file (folder, FIFO, device, link loop),
        empty, truncated, of an unknown format, has codes with characters other than
        letters, digits, ``_`` and ``-``, a sampling rate outside
        :data:`SAMPLING_RATE_RANGE_HZ`, NaN/inf samples or an isolated spike.
    UnitsError
        If a trace's units are unknown and not stated, or not an acceleration, or its
        peak is not a plausible ground acceleration (the message names the likely cause).
    StationMetadataError
        If ``rockscreen.stations`` is not readable StationXML.
    """
    path = Path(os.fsdecode(path))
    name = printable(str(path))
    if units is not None:
        unit_factor(units)  # refuse an unknown unit before reading anything
    meta = read_station_metadata(stations) if stations is not None else None
    _check_file(path)
    stream = _obspy_read(path)
    for trace in stream:
        validate_trace(trace, name)
        units_in, factor, source = _units_for(trace, path, units, meta)
        fmt = str(trace.stats._format)
        with np.errstate(over="ignore", invalid="ignore"):  # inf/NaN are refused below
            trace.data = np.asarray(trace.data, dtype=np.float64) * factor
        trace.stats.calib = 1.0
        if check:
            _check_plausible(trace, name, units_in, source, limits)
        coordinates_source = _attach_coordinates(trace, meta, name)
        # The summary is the union of the two provenance steps: each value is written once.
        read = {"file": str(path), "format": fmt}
        conversion = {"units_in": units_in, "units": OUTPUT_UNITS, "factor": factor}
        trace.stats.rockscreen = AttribDict(
            **read,
            **conversion,
            units_source=source,
            coordinates_source=coordinates_source,
            quality_flags=[],
            provenance=[
                {"step": "read", **read},
                {"step": "convert_units", **conversion, "source": source},
            ],
        )
    return stream


def read_streams(paths, *, units: str | None = None, stations=None):
    """Read several files; bad files are reported, not fatal.

    Parameters
    ----------
    paths : iterable of str or path-like
        Record files.
    units, stations
        As for :func:`read_stream` (StationXML is parsed once).

    Returns
    -------
    stream : obspy.Stream
        All traces of the readable files, in m/s^2.
    failures : list of tuple(str, str)
        ``(path, reason)`` for each file that could not be read.
    """
    meta = read_station_metadata(stations) if stations is not None else None
    stream, failures = Stream(), []
    for path in paths:
        try:
            stream += read_stream(path, units=units, stations=meta)
        except RockscreenError as exc:
            failures.append((str(path), str(exc)))
    return stream, failures


def trace_summary(trace: Trace) -> dict:
    """Summarise a trace read by :func:`read_stream` (what ``rockscreen info`` prints).

    Parameters
    ----------
    trace : obspy.Trace
        Acceleration [m/s^2] with ``stats.rockscreen``.

    Returns
    -------
    dict
        ``id``, ``format``, ``npts``, ``sampling_rate_hz`` [Hz], ``starttime`` (ISO 8601),
        ``units`` (``m/s2``), ``pga_m_s2`` = max |a - mean(a)| [m/s^2] (no other processing),
        ``pgv_m_s`` = max |v| [m/s] with v the trapezoidal integral of a - mean(a) from rest
        (unfiltered: on raw records a baseline drift can inflate it), ``duration_s`` =
        ``npts * dt`` [s] (as the ESM header's DURATION_S), and, only when the trace has
        any, ``quality_flags`` (list of str: warnings that do not refuse the trace, e.g.
        ``vertical_ratio: ...``).
    """
    acc = np.asarray(trace.data, dtype=np.float64)
    dt = float(trace.stats.delta)
    centred = acc - acc.mean() if acc.size else acc
    velocity = cumulative_trapezoid(centred, dx=dt, initial=0.0) if acc.size else acc
    return {
        "id": trace.id,
        "format": trace_format(trace),
        "npts": int(trace.stats.npts),
        "sampling_rate_hz": float(trace.stats.sampling_rate),
        "starttime": str(trace.stats.starttime),
        "units": str(trace.stats.rockscreen["units"]),
        "pga_m_s2": float(np.abs(centred).max()) if acc.size else math.nan,
        "pgv_m_s": float(np.abs(velocity).max()) if acc.size else math.nan,
        "duration_s": int(trace.stats.npts) * dt,
    } | _flags_entry(trace)


def _flags_entry(trace: Trace) -> dict:
    flags = list(trace.stats.rockscreen.get("quality_flags", []) or [])
    return {"quality_flags": flags} if flags else {}


__all__ = [
    "CODE_PATTERN",
    "OUTPUT_UNITS",
    "SAMPLING_RATE_RANGE_HZ",
    "check_record_file",
    "expand_record_paths",
    "file_format",
    "read_stream",
    "read_streams",
    "trace_format",
    "trace_summary",
]
