"""The input motion of one case, from a campaign archive's stored records (for figures).

A component rotated to a tower's axes (``X``, ``Y``) is rotated again here exactly as the
screening did (:func:`rockscreen.pipeline.records.grouping.rotate_horizontals`), so the
figure shows the ground motion the tower was solved on; the archive stores the records
as recorded (:func:`rockscreen.pipeline.archive.motions.read_stored_record`).
"""

from __future__ import annotations

import os

import numpy as np

from rockscreen.pipeline.archive.motions import read_stored_record
from rockscreen.pipeline.records.grouping import rotate_horizontals
from rockscreen.pipeline.vocabulary import ROTATED_COMPONENTS

__all__ = ["read_component_motion"]


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
    record = read_stored_record(path, tower_id, record_id)
    if record is None:
        return None
    names = record.names
    if component in ROTATED_COMPONENTS:
        azimuths, azimuth = record.azimuths, record.tower_azimuth
        if len(names) != 2 or len(azimuths) != 2 or azimuth is None or None in azimuths:
            return None
        if not all(name in record.channels for name in names):
            return None
        h1, h2 = (record.channels[name] for name in names)
        along, across = rotate_horizontals(h1, h2, azimuths[0], azimuths[1], azimuth)
        acc = along if component == ROTATED_COMPONENTS[0] else across
    else:
        name = next((c for c in names if c.endswith(component)), None)
        if name not in record.channels:
            return None
        acc = record.channels[name]
    return np.arange(acc.size) * record.dt, acc
