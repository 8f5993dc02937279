"""Records: the components of one station's recording of one event, on a common time grid.

:func:`group_records` groups the traces of a :class:`obspy.Stream` (in m/s^2, from
:func:`pipeline.records.io.read_stream`) by station (``NET.STA.LOC`` and the channel's band and
instrument prefix, e.g. ``HN``) and overlapping time windows, pairs the two horizontals
and keeps the vertical. Components are trimmed to their common window and, if their
sampling differs, linearly interpolated onto the finest grid (the solver treats records
as piecewise linear between samples anyway); both are recorded in the provenance.

Orientation of the components:

* StationXML azimuth and dip (``stats.orientation``, attached by ``read_stream``) when known;
* otherwise the channel code: ``..N``/``NS`` north (0 deg), ``..E``/``EW`` east (90 deg),
  ``..Z``/``UD``/``UP``/``DWN``/``V`` vertical; PEER components named by their azimuth
  (``067``, ``337``); ``..1``/``..2``/``H1``/``H2`` are horizontals of unknown azimuth.

**Azimuth convention** of :meth:`Record.rotate`: degrees clockwise from north of the
tower's "width" axis (the axis of its width ``2b`` in the rocking model). ``along`` is the
ground acceleration along that axis, ``across`` along the axis 90 deg clockwise from it.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

import numpy as np
from obspy import Stream, Trace, UTCDateTime
from obspy.core.util import AttribDict

from rockscreen.pipeline.errors import ProcessingError
from rockscreen.pipeline.records.quality import QualityLimits, vertical_ratio_flag

_VERTICAL_CODES = ("Z", "UD", "UP", "DWN", "DN", "V", "VER", "VERT", "3")
_NORTH_CODES = ("N", "NS")
_EAST_CODES = ("E", "EW", "WE")
_UNKNOWN_AZIMUTH_CODES = ("1", "2", "H1", "H2")

#: Largest departure from 90 deg between the two horizontals that rotation accepts [deg].
ORTHOGONALITY_TOLERANCE_DEG = 1.0


@dataclass(frozen=True)
class Component:
    """How one trace enters a record."""

    #: Band and instrument codes shared by the record's channels (``HN``; ``""`` when the channel
    #: code is only an orientation, as in K-NET and PEER files).
    prefix: str
    #: True for the vertical component.
    vertical: bool
    #: Horizontal direction [deg clockwise from north]; None when unknown.
    azimuth: float | None
    #: Pairing order: 0 for north/``1`` channels (they become ``h1``), 1 for east/``2``, 2 for
    #: azimuth-named channels (ordered by their code).
    rank: int = 2


def classify(trace: Trace) -> Component:
    """Tell which component a trace is, from StationXML orientation or its channel code.

    Raises
    ------
    ProcessingError
        If the channel code does not tell horizontal from vertical.
    """
    channel = trace.stats.channel.strip().upper()
    if len(channel) == 3 and not channel.isdigit() and channel not in _VERTICAL_CODES:
        prefix, code = channel[:2], channel[2]
    else:
        prefix, code = "", channel
    if code in _VERTICAL_CODES:
        component = Component(prefix, True, None)
    elif code in _NORTH_CODES:
        component = Component(prefix, False, 0.0, 0)
    elif code in _EAST_CODES:
        component = Component(prefix, False, 90.0, 1)
    elif code in _UNKNOWN_AZIMUTH_CODES:
        component = Component(prefix, False, None, 0 if code in ("1", "H1") else 1)
    elif re.fullmatch(r"\d{1,3}", code):
        component = Component(prefix, False, float(int(code) % 360))
    else:
        raise ProcessingError(
            f"{trace.id}: channel {trace.stats.channel!r} does not say whether it is "
            "horizontal or vertical (expected ..N/..E/..Z, ..1/..2, NS/EW/UD or an azimuth)"
        )
    orientation = trace.stats.get("orientation")
    if orientation is not None:
        dip = float(orientation.get("dip", math.nan))
        azimuth = float(orientation.get("azimuth", math.nan))
        if math.isfinite(dip) and abs(dip) >= 45.0:
            return Component(prefix, True, None)
        if math.isfinite(dip) and math.isfinite(azimuth):
            return Component(prefix, False, azimuth % 360.0, component.rank)
    return component


@dataclass
class Record:
    """One station's three-component (or fewer) accelerogram on a common grid."""

    #: ``NET.STA.LOC.PREFIX`` (e.g. ``IT.AQV..HN``).
    id: str
    #: ``NET.STA``.
    station: str
    #: ``latitude`` [deg], ``longitude`` [deg], ``elevation`` [m].
    coordinates: dict | None
    #: Time of the first sample.
    starttime: UTCDateTime
    #: Sampling interval [s].
    dt: float
    #: First and second horizontal and vertical acceleration [m/s^2], shape (npts,).
    h1: np.ndarray | None = None
    h2: np.ndarray | None = None
    z: np.ndarray | None = None
    #: Azimuths of ``h1`` and ``h2`` [deg clockwise from north], None when unknown.
    h1_azimuth: float | None = None
    h2_azimuth: float | None = None
    #: Role (``h1``, ``h2``, ``z``) -> trace id.
    channels: dict = field(default_factory=dict)
    #: Role -> the provenance list of that trace, plus ``record`` -> grouping steps.
    provenance: dict = field(default_factory=dict)
    #: Warnings that do not refuse the record but must reach the user (each ``"check: sentence"``):
    #: the components' own ``stats.rockscreen["quality_flags"]`` and ``vertical_ratio``
    #: (:func:`rockscreen.pipeline.records.quality.vertical_ratio_flag`).
    quality_flags: list = field(default_factory=list)

    @property
    def npts(self) -> int:
        """Number of samples of every component."""
        for data in (self.h1, self.h2, self.z):
            if data is not None:
                return int(data.size)
        return 0

    @property
    def times(self) -> np.ndarray:
        """Sample times from the first sample [s], shape (npts,)."""
        return np.arange(self.npts) * self.dt

    def rotate(self, azimuth_deg: float) -> tuple[np.ndarray, np.ndarray]:
        """Rotate the horizontals to a tower's principal axes.

        Parameters
        ----------
        azimuth_deg : float
            Azimuth of the tower's width axis [deg clockwise from north].

        Returns
        -------
        along : numpy.ndarray, shape (npts,)
            Acceleration along the width axis [m/s^2].
        across : numpy.ndarray, shape (npts,)
            Acceleration along the axis 90 deg clockwise from it [m/s^2].

        Raises
        ------
        ProcessingError
            If a horizontal or its azimuth is missing, or the two are not orthogonal.
        """
        if not math.isfinite(azimuth_deg):
            raise ProcessingError(f"azimuth_deg={azimuth_deg!r} must be a finite number [deg]")
        if self.h1 is None or self.h2 is None:
            raise ProcessingError(f"record {self.id}: rotation needs two horizontal components")
        if self.h1_azimuth is None or self.h2_azimuth is None:
            raise ProcessingError(
                f"record {self.id}: the azimuths of {self.channels.get('h1')} and "
                f"{self.channels.get('h2')} are unknown; give StationXML (--stations) with "
                "channel azimuths"
            )
        separation = (self.h2_azimuth - self.h1_azimuth) % 180.0
        if abs(separation - 90.0) > ORTHOGONALITY_TOLERANCE_DEG:
            raise ProcessingError(
                f"record {self.id}: horizontals at {self.h1_azimuth:g} and "
                f"{self.h2_azimuth:g} deg are not orthogonal (tolerance "
                f"{ORTHOGONALITY_TOLERANCE_DEG:g} deg)"
            )
        return rotate_horizontals(self.h1, self.h2, self.h1_azimuth, self.h2_azimuth, azimuth_deg)


def rotate_horizontals(h1, h2, h1_azimuth: float, h2_azimuth: float, azimuth_deg: float):
    """Project two orthogonal horizontals onto the axes at ``azimuth_deg`` and ``+90`` deg.

    Parameters
    ----------
    h1, h2 : array_like, shape (n,)
        Horizontal accelerations [m/s^2], positive towards their azimuths.
    h1_azimuth, h2_azimuth : float
        Their azimuths [deg clockwise from north]; orthogonal (either handedness).
    azimuth_deg : float
        Azimuth of the target "along" axis [deg clockwise from north].

    Returns
    -------
    along, across : numpy.ndarray, shape (n,)
        ``along = h1 cos(a - a1) + h2 cos(a - a2)`` and the same at ``a + 90``.
    """
    h1 = np.asarray(h1, dtype=np.float64)
    h2 = np.asarray(h2, dtype=np.float64)

    def project(direction: float) -> np.ndarray:
        return h1 * math.cos(math.radians(direction - h1_azimuth)) + h2 * math.cos(
            math.radians(direction - h2_azimuth)
        )

    return project(azimuth_deg), project(azimuth_deg + 90.0)


def common_grid(traces: list[Trace], record_id: str):
    """Trim (and if needed interpolate) traces onto one grid; return data and the step.

    The grid starts at the latest start, ends at the earliest end and has the finest
    sampling step of the traces; a trace already on it is trimmed, any other is
    interpolated linearly (the convention of every record in rockscreen).

    Parameters
    ----------
    traces : list of obspy.Trace
        The components of one record.
    record_id : str
        The record's id, for the message.

    Returns
    -------
    arrays : list of numpy.ndarray
        The samples of each trace on the grid, in the order of ``traces``.
    start : obspy.UTCDateTime
        The grid's first time.
    dt : float
        The grid's step [s].
    step : dict
        The provenance entry (``"common_grid"``: which traces were trimmed or interpolated).

    Raises
    ------
    ProcessingError
        When the components share no time window.
    """
    dt = min(float(tr.stats.delta) for tr in traces)
    start = max(tr.stats.starttime for tr in traces)
    end = min(tr.stats.endtime for tr in traces)
    if end <= start:
        raise ProcessingError(f"record {record_id}: its components share no time window")
    npts = int(math.floor((end - start) / dt + 1e-6)) + 1
    arrays, trimmed, interpolated = [], [], []
    for tr in traces:
        delta = float(tr.stats.delta)
        offset = (start - tr.stats.starttime) / delta
        index = int(round(offset))
        data = np.asarray(tr.data, dtype=np.float64)
        if abs(delta - dt) <= 1e-9 * dt and abs(offset - index) < 1e-3:
            arrays.append(data[index : index + npts])
            if index > 0 or data.size > npts:
                trimmed.append(tr.id)
        else:
            source_t = (tr.stats.starttime - start) + np.arange(data.size) * delta
            arrays.append(np.interp(np.arange(npts) * dt, source_t, data))
            interpolated.append(tr.id)
    step = {
        "step": "common_grid",
        "starttime": str(start),
        "dt": dt,
        "npts": npts,
        "trimmed": trimmed,
        "interpolated_linear": interpolated,
    }
    return arrays, start, dt, step


def _build(
    key, traces: list[Trace], components: list[Component], limits: QualityLimits | None = None
) -> Record:
    network, station, location, prefix = key
    record_id = f"{network}.{station}.{location}.{prefix}"
    horizontals = [(tr, c) for tr, c in zip(traces, components, strict=True) if not c.vertical]
    verticals = [tr for tr, c in zip(traces, components, strict=True) if c.vertical]
    if len(horizontals) > 2 or len(verticals) > 1:
        ids = ", ".join(tr.id for tr in traces)
        raise ProcessingError(
            f"record {record_id}: more than two horizontals or one vertical in one time "
            f"window ({ids}); merge gappy traces or remove duplicates first"
        )
    horizontals.sort(key=lambda pair: (pair[1].rank, pair[0].stats.channel))
    roles = {f"h{i + 1}": tr for i, (tr, _) in enumerate(horizontals)}
    if verticals:
        roles["z"] = verticals[0]
    arrays, start, dt, step = common_grid(list(roles.values()), record_id)
    data = dict(zip(roles, arrays, strict=True))
    coordinates = next(
        (dict(tr.stats.coordinates) for tr in roles.values() if "coordinates" in tr.stats), None
    )
    provenance = {
        role: list(tr.stats.rockscreen.get("provenance", [])) if "rockscreen" in tr.stats else []
        for role, tr in roles.items()
    }
    provenance["record"] = [step]
    flags = _record_flags(roles, data, limits)
    azimuths = [c.azimuth for _, c in horizontals]
    return Record(
        id=record_id,
        station=f"{network}.{station}",
        coordinates=coordinates,
        starttime=start,
        dt=dt,
        h1=data.get("h1"),
        h2=data.get("h2"),
        z=data.get("z"),
        h1_azimuth=azimuths[0] if azimuths else None,
        h2_azimuth=azimuths[1] if len(azimuths) > 1 else None,
        channels={role: tr.id for role, tr in roles.items()},
        provenance=provenance,
        quality_flags=flags,
    )


def _peak(data: np.ndarray) -> float:
    return float(np.abs(data - np.median(data)).max()) if data.size else 0.0


def _record_flags(
    roles: dict[str, Trace], data: dict[str, np.ndarray], limits: QualityLimits | None = None
) -> list[str]:
    """Return the components' quality flags, then the vertical/horizontal ratio flag."""
    flags: list[str] = []
    for tr in roles.values():
        for flag in tr.stats.get("rockscreen", {}).get("quality_flags", []) or []:
            if flag not in flags:
                flags.append(flag)
    if "z" in data and any(role in data for role in ("h1", "h2")):
        horizontal = [_peak(data[role]) for role in ("h1", "h2") if role in data]
        flag = vertical_ratio_flag(horizontal, _peak(data["z"]), limits)
        if flag is not None and flag not in flags:
            flags.append(flag)
    return flags


def flag_vertical_ratio(stream: Stream) -> list[tuple[str, str]]:
    """Flag stations whose vertical peak is implausibly larger than their horizontals.

    For traces not (yet) grouped into records, e.g. the files given to ``rockscreen info``:
    traces of one ``NET.STA.LOC`` and channel prefix are compared (peaks of
    ``a - median(a)`` [m/s^2]); traces whose channel does not tell horizontal from
    vertical are left out. The flag is appended to ``stats.rockscreen["quality_flags"]``
    of every trace of the station.

    Parameters
    ----------
    stream : obspy.Stream
        Traces in m/s^2 (from :func:`rockscreen.pipeline.records.io.read_stream`).

    Returns
    -------
    list of tuple(str, str)
        ``(station key NET.STA.LOC.PREFIX, flag)`` of each flagged station.
    """
    groups: dict[tuple, list[tuple[Trace, Component]]] = {}
    for trace in stream:
        try:
            component = classify(trace)
        except ProcessingError:
            continue
        stats = trace.stats
        key = (stats.network, stats.station, stats.location, component.prefix)
        groups.setdefault(key, []).append((trace, component))
    flagged = []
    for key in sorted(groups):
        members = groups[key]
        horizontal = [_peak(np.asarray(tr.data)) for tr, c in members if not c.vertical]
        vertical = [_peak(np.asarray(tr.data)) for tr, c in members if c.vertical]
        if not horizontal or not vertical:
            continue
        flag = vertical_ratio_flag(horizontal, max(vertical))
        if flag is None:
            continue
        flagged.append((".".join(key), flag))
        for trace, _ in members:
            if "rockscreen" not in trace.stats:
                trace.stats.rockscreen = AttribDict()
            trace.stats.rockscreen.setdefault("quality_flags", [])
            if flag not in trace.stats.rockscreen["quality_flags"]:
                trace.stats.rockscreen["quality_flags"].append(flag)
    return flagged


def group_records(stream: Stream, limits: QualityLimits | None = None) -> list[Record]:
    """Group traces into records by station and overlapping time window.

    Parameters
    ----------
    stream : obspy.Stream
        Traces in m/s^2 (from :func:`rockscreen.pipeline.records.io.read_stream`, processed or not).
    limits : QualityLimits, optional
        Thresholds of the vertical/horizontal ratio flag (``max_vertical_ratio``);
        the defaults of :class:`~rockscreen.pipeline.records.quality.QualityLimits` when omitted.

    Returns
    -------
    list of Record
        Sorted by id, then start time.

    Raises
    ------
    ProcessingError
        If a channel's orientation cannot be told, a window holds duplicate components,
        or the components of a group share no time window.
    """
    groups: dict[tuple, list[tuple[Trace, Component]]] = {}
    for trace in stream:
        component = classify(trace)
        stats = trace.stats
        key = (stats.network, stats.station, stats.location, component.prefix)
        groups.setdefault(key, []).append((trace, component))
    records = []
    for key in sorted(groups):
        members = sorted(groups[key], key=lambda pair: pair[0].stats.starttime)
        window: list[tuple[Trace, Component]] = []
        window_end = None
        for trace, component in members:
            if window and trace.stats.starttime > window_end:
                records.append(_build(key, *map(list, zip(*window, strict=True)), limits))
                window = []
            window.append((trace, component))
            end = trace.stats.endtime
            window_end = end if window_end is None or len(window) == 1 else max(window_end, end)
        records.append(_build(key, *map(list, zip(*window, strict=True)), limits))
    return records


__all__ = [
    "ORTHOGONALITY_TOLERANCE_DEG",
    "Component",
    "Record",
    "classify",
    "common_grid",
    "flag_vertical_ratio",
    "group_records",
    "rotate_horizontals",
]
