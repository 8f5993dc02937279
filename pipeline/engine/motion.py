"""The one ground-motion record type, and the components a tower is checked against.

A :class:`GroundMotion` is what every product solves towers under: the recorded
earthquake of ``run`` (its channels with their azimuths), a hazard suite's record of
``assess`` (components already along the tower's axes), a study's pulse. It holds plain
arrays, cheap to pickle to the workers.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, NamedTuple

import numpy as np

from rockscreen.pipeline.vocabulary import ROTATED_COMPONENTS, TOWER_AXES
from rockscreen.stations.tower import Tower

__all__ = ["GroundMotion", "TowerComponent", "tower_components"]


@dataclass(frozen=True)
class GroundMotion:
    """One ground motion: horizontal components with their orientation, vertical, ``dt``."""

    #: ``"NET.STA.LOC.CHA-prefix"`` of a recorded motion (e.g. ``"IT.AQV..HN"``), or a
    #: suite record's name.
    record_id: str
    #: ``"NET.STA"`` (empty for a motion that no station recorded).
    station: str
    #: Sampling step [s].
    dt: float
    #: Horizontal channel codes, e.g. ``("HNN", "HNE")``, or ``("X", "Y")``.
    channels: tuple[str, ...]
    #: Horizontal accelerations [m/s²], one per channel, equal lengths.
    horizontals: tuple[np.ndarray, ...]
    #: Channel azimuths, clockwise from north [deg]; None when unknown.
    azimuths: tuple[float | None, ...]
    #: Vertical acceleration [m/s²], positive up.
    vertical: np.ndarray | None = None
    #: Station coordinates [deg].
    latitude: float | None = None
    longitude: float | None = None
    #: Archive attributes: files, formats, starttime, provenance, vertical channel.
    info: dict[str, Any] = field(default_factory=dict)
    #: True when the horizontals are already along the tower's axes (first along its width,
    #: second along its plan depth): a hazard suite's record has no geographic orientation.
    tower_axes: bool = False

    @classmethod
    def along_tower_axes(
        cls,
        name: str,
        x: np.ndarray,
        y: np.ndarray | None,
        z: np.ndarray | None,
        dt: float,
        info: dict[str, Any] | None = None,
    ) -> GroundMotion:
        """Return a motion whose components are the tower's ``X`` (width) and ``Y`` (depth).

        Parameters
        ----------
        name : str
            The record's name.
        x, y : numpy.ndarray
            Accelerations along the tower's width and plan depth [m/s²]; ``y`` may be None.
        z : numpy.ndarray or None
            Vertical acceleration [m/s²], positive up.
        dt : float
            Sampling step [s].
        info : dict, optional
            Provenance.
        """
        horizontals = (x,) if y is None else (x, y)
        channels = ROTATED_COMPONENTS[: len(horizontals)]
        return cls(
            record_id=name,
            station="",
            dt=float(dt),
            channels=channels,
            horizontals=horizontals,
            azimuths=(None,) * len(horizontals),
            vertical=z,
            info=dict(info or {}),
            tower_axes=True,
        )

    @property
    def can_rotate(self) -> bool:
        """Whether two horizontals of known, orthogonal azimuths allow rotation."""
        if len(self.horizontals) != 2 or any(a is None for a in self.azimuths):
            return False
        difference = (self.azimuths[1] - self.azimuths[0]) % 180.0
        return abs(difference - 90.0) < 1.0

    def label(self, i: int) -> str:
        """Component label of horizontal ``i``: its channel code without the prefix (``E``)."""
        channel = self.channels[i] if i < len(self.channels) else ""
        prefix = self.record_id.rsplit(".", 1)[-1]
        if channel.startswith(prefix) and len(channel) > len(prefix):
            return channel[len(prefix) :]
        return channel or f"H{i + 1}"


class TowerComponent(NamedTuple):
    """One horizontal component a tower is checked against (:func:`tower_components`)."""

    #: Its label in every table: ``X``/``Y`` along the tower's axes
    #: (:data:`~rockscreen.pipeline.vocabulary.ROTATED_COMPONENTS`), else the recorded
    #: channel's last letter (``E``).
    component: str
    #: Ground acceleration [m/s²].
    acc: np.ndarray
    #: The tower's base width in the component's direction [m]: the whole tower's block.
    width_m: float
    #: The tower axis the component is along, ``"x"`` or ``"y"``
    #: (:data:`~rockscreen.stations.inventory_columns.TOWER_AXES`); None when it is along
    #: neither (a recorded channel the tower's azimuth could not rotate).
    axis: str | None


def tower_components(tower: Tower, motion: GroundMotion) -> list[TowerComponent]:
    """Return the horizontal components a tower is checked against.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
    motion : GroundMotion

    Returns
    -------
    list of TowerComponent
        ``(component, acceleration [m/s²], block width in that direction [m], axis)``:

        - a motion along the tower's axes: ``"X"`` (axis ``"x"``) with the width
          ``width_m``, ``"Y"`` (axis ``"y"``) with the plan depth;
        - rotated (``"X"``, ``"Y"``) when the tower's azimuth and the channel azimuths are
          known;
        - otherwise the recorded channels' last letters with the smaller plan dimension and
          no axis (None): a model with its own block takes its safe side there.
    """
    widths = (float(tower.width_m), float(tower.plan_depth_m))
    if motion.tower_axes:
        return [
            TowerComponent(ROTATED_COMPONENTS[i], acc, widths[i], TOWER_AXES[i])
            for i, acc in enumerate(motion.horizontals)
        ]
    if tower.azimuth_deg is not None and motion.can_rotate:
        from rockscreen.pipeline.records.grouping import rotate_horizontals  # loads ObsPy

        rotated = rotate_horizontals(*motion.horizontals, *motion.azimuths, tower.azimuth_deg)
        return [
            TowerComponent(ROTATED_COMPONENTS[i], acc, widths[i], TOWER_AXES[i])
            for i, acc in enumerate(rotated)
        ]
    width = min(widths)
    return [
        TowerComponent(motion.label(i), acc, width, None)
        for i, acc in enumerate(motion.horizontals)
    ]
