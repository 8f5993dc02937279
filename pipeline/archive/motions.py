"""The input motion of one case, read back from a campaign archive (for figures).

The archive stores each processed record as recorded (``/records/<record_id>/<channel>``,
m/s2, with the channel azimuths); a component rotated to a tower's axes (``X``, ``Y``) is
rotated again here exactly as the screening did (:func:`rockscreen.pipeline.records.grouping.
rotate_horizontals`), so the figure shows the ground motion the tower was solved on.
"""

from __future__ import annotations

import json
import os
from typing import Any

import h5py
import numpy as np

from rockscreen.pipeline.archive.safety import open_archive, read_column, reading
from rockscreen.pipeline.records.grouping import rotate_horizontals
from rockscreen.pipeline.vocabulary import ROTATED_COMPONENTS


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


def read_component_motion(
    path: str | os.PathLike, tower_id: str, record_id: str, component: str
) -> tuple[np.ndarray, np.ndarray] | None:
    """Return ``(t [s], acceleration [m/s2])`` of one component of a stored record.

    Parameters
    ----------
    path : str or path-like
        A campaign archive.
    tower_id : str
        The tower (its azimuth rotates ``X``/``Y`` components).
    record_id : str
        ``NET.STA.LOC.`` + band/instrument code, e.g. ``"IT.AQV..HN"``.
    component : str
        A channel's last letter (``"E"``) or ``"X"``/``"Y"``.

    Returns
    -------
    tuple of numpy.ndarray, or None
        None when the archive does not hold what is needed (no such record or channel).
    """
    f, _ = open_archive(path)
    with f, reading(path):
        group = f.get(f"records/{record_id}")
        if not isinstance(group, h5py.Group):
            return None
        dt = float(group.attrs.get("dt", 0.0))
        if not dt > 0.0:
            return None
        channels = json.loads(group.attrs.get("channels", "[]"))
        if component in ROTATED_COMPONENTS:
            azimuths = json.loads(group.attrs.get("azimuths", "[]"))
            azimuth = _tower_azimuth(f, path, tower_id)
            if len(channels) != 2 or azimuth is None or None in azimuths:
                return None
            if not all(isinstance(group.get(c), h5py.Dataset) for c in channels):
                return None
            h1, h2 = (np.asarray(group[c][()], dtype=float) for c in channels)
            along, across = rotate_horizontals(h1, h2, azimuths[0], azimuths[1], azimuth)
            acc = along if component == ROTATED_COMPONENTS[0] else across
        else:
            name = next((c for c in channels if c.endswith(component)), None)
            ds = group.get(name) if name else None
            if not isinstance(ds, h5py.Dataset) or ds.ndim != 1:
                return None
            acc = np.asarray(ds[()], dtype=float)
    return np.arange(acc.size) * dt, acc
