"""The processed records of a campaign archive, read back as stored (for figures).

The archive stores each processed record as recorded (``/records/<record_id>/<channel>``,
m/s2, with the channel azimuths) and each tower's azimuth (``/towers/azimuth_deg``).
:func:`read_stored_record` returns them unchanged; rotating a record to a tower's axes is
a computation, done by the caller
(:func:`rockscreen.pipeline.report.motions.read_component_motion`).
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from typing import Any

import h5py
import numpy as np

from rockscreen.pipeline.archive.safety import open_campaign, read_column, reading

__all__ = ["StoredRecord", "read_stored_record"]


@dataclass(frozen=True)
class StoredRecord:
    """One processed record of a campaign archive, as stored, and one tower's azimuth."""

    #: Sampling step [s].
    dt: float
    #: Channel codes the record lists, in the stored order.
    names: list[str]
    #: Channel code -> processed acceleration [m/s2] (channels stored as 1-D datasets).
    channels: dict[str, np.ndarray]
    #: Azimuth of each channel [deg] (None where unknown), in the same order.
    azimuths: list[float | None]
    #: Azimuth of the tower's axis X [deg], None when the inventory gives none.
    tower_azimuth: float | None


def _tower_azimuth(f: h5py.File, path: Any, tower_id: str) -> float | None:
    ids = read_column(f.get("towers/id"), path, "towers/id")
    azimuths = f.get("towers/azimuth_deg")
    if azimuths is None:
        return None
    hits = np.flatnonzero(np.asarray(ids) == tower_id)
    if not hits.size:
        return None
    value = float(azimuths[int(hits[0])])
    return None if np.isnan(value) else value


def read_stored_record(
    path: str | os.PathLike, tower_id: str, record_id: str
) -> StoredRecord | None:
    """Return one stored record of a campaign archive with the azimuth of a tower.

    Parameters
    ----------
    path : str or path-like
        A campaign archive.
    tower_id : str
        The tower whose azimuth is returned.
    record_id : str
        ``NET.STA.LOC.`` + band/instrument code, e.g. ``"IT.AQV..HN"``.

    Returns
    -------
    StoredRecord or None
        None when the archive holds no such record or no positive sampling step. Listed
        channels that are not 1-D datasets are absent from ``channels``.
    """
    f, _ = open_campaign(path)
    with f, reading(path):
        group = f.get(f"records/{record_id}")
        if not isinstance(group, h5py.Group):
            return None
        dt = float(group.attrs.get("dt", 0.0))
        if not dt > 0.0:
            return None
        names = json.loads(group.attrs.get("channels", "[]"))
        channels = {}
        for name in names:
            ds = group.get(name)
            if isinstance(ds, h5py.Dataset) and ds.ndim == 1:
                channels[name] = np.asarray(ds[()], dtype=float)
        return StoredRecord(
            dt=dt,
            names=list(names),
            channels=channels,
            azimuths=list(json.loads(group.attrs.get("azimuths", "[]"))),
            tower_azimuth=_tower_azimuth(f, path, tower_id),
        )
