"""A campaign's inputs: record files to motions, and towers paired with them into tasks.

Unreadable files and unpaired towers are failures, not errors.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from obspy import Stream

from rockscreen.pipeline.config import processing_config
from rockscreen.pipeline.engine.motion import GroundMotion
from rockscreen.pipeline.engine.results import Failure
from rockscreen.pipeline.errors import RockscreenError
from rockscreen.pipeline.processing.steps import process_trace
from rockscreen.pipeline.records.grouping import group_records
from rockscreen.pipeline.records.io import read_stream
from rockscreen.pipeline.screening.cases import TowerTask
from rockscreen.stations.pairing import StationSite, pair_towers_detailed
from rockscreen.stations.stationxml import read_station_metadata


def make_tasks(
    towers: Sequence[Any],
    pairing: dict[str, list[str]],
    motions: dict[str, GroundMotion],
    reasons: dict[str, str] | None = None,
    distances_km: dict[str, float | None] | None = None,
) -> tuple[list[TowerTask], list[Failure]]:
    """Build one task per paired tower; unpaired towers become failures.

    Parameters
    ----------
    towers : sequence of Tower
        In inventory order.
    pairing : dict
        Tower id -> station keys (:func:`rockscreen.stations.pairing.pair_towers`).
    motions : dict
        Record id -> GroundMotion.
    reasons : dict, optional
        Tower id -> how it is paired, or why it is not (summary ``pairing`` column and
        failures table).
    distances_km : dict, optional
        Tower id -> distance to its nearest paired station [km] (None when unknown).

    Returns
    -------
    tasks : list of TowerTask
    failures : list of Failure
    """
    by_station: dict[str, list[str]] = {}
    for record_id in sorted(motions):
        by_station.setdefault(motions[record_id].station, []).append(record_id)
    tasks, failures = [], []
    for index, tower in enumerate(towers):
        record_ids = tuple(
            record_id for key in pairing.get(tower.id, []) for record_id in by_station.get(key, [])
        )
        if record_ids:
            distance = (distances_km or {}).get(tower.id)
            tasks.append(
                TowerTask(
                    index,
                    tower,
                    tuple(sorted(set(record_ids))),
                    pairing=(reasons or {}).get(tower.id, ""),
                    pairing_distance_km=math.nan if distance is None else float(distance),
                )
            )
        else:
            reason = (reasons or {}).get(tower.id) or "no record is paired with this tower"
            failures.append(Failure("pair", tower.id, reason))
    return tasks, failures


def pair(
    towers: Sequence[Any], motions: dict[str, GroundMotion], *, max_distance_km: float
) -> tuple[list[TowerTask], list[Failure]]:
    """Pair towers with the stations of the records and build the tower tasks.

    Parameters
    ----------
    towers : sequence of Tower
    motions : dict
        Record id -> GroundMotion (their stations and coordinates).
    max_distance_km : float
        Largest tower-station distance of nearest-station pairing [km].

    Returns
    -------
    tasks : list of TowerTask
    failures : list of Failure
        Unpaired towers, with the reason.
    """
    sites: dict[str, StationSite] = {}
    for record_id in sorted(motions):
        motion = motions[record_id]
        site = sites.get(motion.station)
        if site is None or (not site.has_coordinates and motion.latitude is not None):
            sites[motion.station] = StationSite(motion.station, motion.latitude, motion.longitude)
    detailed = pair_towers_detailed(towers, list(sites.values()), max_distance_km=max_distance_km)
    keys = {tower_id: list(p.keys) for tower_id, p in detailed.items()}
    reasons = {tower_id: p.reason for tower_id, p in detailed.items()}
    distances = {tower_id: p.distance_km for tower_id, p in detailed.items()}
    return make_tasks(towers, keys, motions, reasons, distances)


def prepare_records(
    paths: Sequence[str | Path],
    *,
    units: str | None = None,
    stations: Any = None,
    processing: dict[str, Any] | None = None,
) -> tuple[dict[str, GroundMotion], list[Failure]]:
    """Read, process and group record files into the campaign's motions.

    A file that cannot be read, a trace that cannot be processed, and a station whose
    traces cannot be grouped are failures (reported and skipped), never errors.

    Parameters
    ----------
    paths : sequence of path
        Record files.
    units : str, optional
        Units of files that state none (``g``, ``m/s2``, ``cm/s2``).
    stations : path or StationMetadata, optional
        StationXML (coordinates, orientations, responses).
    processing : dict, optional
        The ``[processing]`` table of the configuration.

    Returns
    -------
    motions : dict
        Record id -> GroundMotion, sorted by id.
    failures : list of Failure

    Raises
    ------
    StationMetadataError
        If ``rockscreen.stations`` is given but unreadable (a usage error, not a record failure).
    """
    meta = read_station_metadata(stations) if stations is not None else None
    config = processing_config(processing or {})
    failures: list[Failure] = []
    processed = Stream()
    for path in paths:
        try:
            stream = read_stream(path, units=units, stations=meta, limits=config.quality)
        except (RockscreenError, OSError) as exc:
            failures.append(Failure("read", str(path), str(exc)))
            continue
        for trace in stream:
            try:
                processed += process_trace(trace, config)
            except RockscreenError as exc:
                failures.append(Failure("process", f"{path} ({trace.id})", str(exc)))
    motions: dict[str, GroundMotion] = {}
    for group in _station_groups(processed):
        try:
            records = group_records(group, config.quality)
        except RockscreenError as exc:
            ids = ", ".join(sorted({tr.id for tr in group}))
            failures.append(Failure("process", ids, str(exc)))
            continue
        for record in records:
            motion = motion_from_record(record)
            if not motion.horizontals:
                failures.append(Failure("process", record.id, "no horizontal component"))
                continue
            record_id = motion.record_id
            n = 2
            while record_id in motions:  # same station, another event
                record_id = f"{motion.record_id}~{n}"
                n += 1
            motions[record_id] = dataclasses.replace(motion, record_id=record_id)
    return dict(sorted(motions.items())), failures


def _station_groups(stream: Any) -> list[Any]:
    groups: dict[tuple[str, str, str], Any] = {}
    for trace in stream:
        key = (trace.stats.network, trace.stats.station, trace.stats.location)
        groups.setdefault(key, Stream()).append(trace)
    return [groups[key] for key in sorted(groups)]


def motion_from_record(record: Any) -> GroundMotion:
    """Return the :class:`GroundMotion` of a :class:`rockscreen.pipeline.records.grouping.Record`.

    Parameters
    ----------
    record : rockscreen.pipeline.records.grouping.Record

    Returns
    -------
    GroundMotion
        Horizontals ``h1``, ``h2`` (those present) with their azimuths, the vertical,
        coordinates, and the archive information (files, formats, provenance).
    """
    roles = [role for role in ("h1", "h2") if getattr(record, role) is not None]
    channel_of = {role: str(trace_id).split(".")[-1] for role, trace_id in record.channels.items()}
    coordinates = record.coordinates or {}
    provenance = record.provenance or {}
    files, formats = [], []
    for steps in provenance.values():
        for step in steps:
            if isinstance(step, dict) and step.get("step") == "read":
                files.append(str(step.get("file", "")))
                formats.append(str(step.get("format", "")))
    info = {
        "starttime": str(record.starttime),
        "trace_ids": dict(record.channels),
        "files": sorted(set(files)),
        "formats": sorted(set(formats)),
        "provenance": provenance,
        "vertical_channel": channel_of.get("z", "vertical"),
        "quality_flags": [str(flag) for flag in getattr(record, "quality_flags", []) or []],
    }
    return GroundMotion(
        record_id=record.id,
        station=record.station,
        dt=float(record.dt),
        channels=tuple(channel_of.get(role, role) for role in roles),
        horizontals=tuple(np.asarray(getattr(record, role), dtype=float) for role in roles),
        azimuths=tuple(getattr(record, f"{role}_azimuth") for role in roles),
        vertical=None if record.z is None else np.asarray(record.z, dtype=float),
        latitude=coordinates.get("latitude"),
        longitude=coordinates.get("longitude"),
        info=info,
    )
