"""One vocabulary: the names of statuses, classes and components used everywhere.

Every table, archive, command and document of rockscreen uses these spellings; a new
status is added here first. The models' names live with the models, in their registry
(:mod:`rockscreen.pipeline.engine.registry`).
"""

from __future__ import annotations

from rockscreen.stations.inventory_columns import TOWER_AXES

#: Single-pulse excitation shapes (:func:`rockscreen.pipeline.motion.excitations.pulse`; ``simulate
#: --pulse``, a study group's ``shape``).
PULSE_SHAPES = ("one-sine", "one-cosine", "half-sine", "rectangular")

#: Record-based risk classes of ``run``, most severe first.
RECORD_RISK_CLASSES = ("collapse", "high", "moderate", "low", "none")

#: Components of a record rotated to a tower's axes: along its width axis (the tower's
#: azimuth) and 90 degrees clockwise from it; the labels of the tower's axes
#: :data:`~rockscreen.stations.inventory_columns.TOWER_AXES` (``x``, ``y``, as the inventory
#: and a case's ``axis`` spell them) in upper case, in the same order.
ROTATED_COMPONENTS = tuple(axis.upper() for axis in TOWER_AXES)


def channel_id(record_id: str, component: str) -> str:
    """Return the channel id of a record component.

    Parameters
    ----------
    record_id : str
        Record id ``NET.STA.LOC.`` + band/instrument code, e.g. ``"IT.AQV..HN"``.
    component : str
        Component label: a channel's last letter (``"E"``) or a rotated component
        (``"X"``, ``"Y"``).

    Returns
    -------
    str
        ``"IT.AQV..HNE"``, or ``"IT.AQV..HNX"`` for the component along the tower's width axis.
    """
    return f"{record_id}{component}"
