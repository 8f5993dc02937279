"""``gable``: a bell gable (*vela campanaria*) rocking on its base.

The gable is a rigid block of its height with its bells as a point mass on its axis at two
thirds of its height (the composite section of the belfry model,
:func:`rockscreen.pipeline.engine.models.belfry.composite_section`). Its mass is
``height x width x thickness x (1 - opening ratio)`` at the unit weight of the row's
``masonry_type`` (Circolare 2019 Table C8.5.I; rubble when none, stated in
``docs/code_checks.md`` §1.5); only the bells' share of it matters to the rocking.

Its base width in the direction of a case (:func:`gable_width_for`): out of its plane, its
thickness; in its plane, the piers' total width ``width x (1 - opening ratio)`` (a gable
with openings is a frame of piers in its plane, and a solid block of its full width would
overstate its stability: the belfry model's effective width). The plane is known from the
inventory's ``gable_axis`` (the tower axis normal to it) and a case's axis; without either
the gable rocks on its thickness in every direction, its weak one and the safe side.

Its base motion (:func:`gable_base_motion`) is the ground's for a gable on the ground, else
the modal floor accelerogram (``docs/floor_motion.md``) at its base: on the church when
``building_height_m`` reaches the gable's base (``building_period_s``, else ``0.0187 H``;
mode shape ``z/H``), else on a structure as high as the base (period ``0.0187 z``, the
gable at its top). The same support as the gable's kinematic check
(:func:`rockscreen.pipeline.risk.checks.tower_mechanisms.gable_kinematic_mechanism`).
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from rockscreen.pipeline.engine.models.belfry import belfry_block
from rockscreen.pipeline.engine.models.ground import solve_single_block
from rockscreen.pipeline.engine.registry import TowerModel
from rockscreen.pipeline.engine.solvers import active_solvers
from rockscreen.pipeline.verdict.messages import Message, message
from rockscreen.solver.constants import G
from rockscreen.stations.inventory_columns import (
    ASSUMED_MASONRY_TYPE,
    GABLE_GROUP,
    MASONRY_UNIT_WEIGHTS_KN_M3,
    TOWER_AXES,
)
from rockscreen.stations.tower import Tower

__all__ = [
    "MODEL",
    "gable_base_motion",
    "gable_block",
    "gable_block_note",
    "gable_mass_kg",
    "gable_support",
    "gable_width_for",
]

#: Height of the bells on the gable, a fraction of its height (as the kinematic check's).
BELLS_HEIGHT_RATIO = 2.0 / 3.0


def gable_mass_kg(tower: Tower) -> float:
    """Return the gable's masonry mass [kg], its openings deducted (module docstring).

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        A tower with the bell-gable columns.

    Returns
    -------
    float
        ``h x w x t x (1 - opening ratio) x w_masonry / g`` [kg].
    """
    kind = tower.masonry_type or ASSUMED_MASONRY_TYPE
    density = MASONRY_UNIT_WEIGHTS_KN_M3[kind] * 1.0e3 / G
    volume = tower.gable_height_m * tower.gable_width_m * tower.gable_thickness_m
    return density * volume * (1.0 - float(tower.gable_opening_ratio or 0.0))


def gable_width_for(tower: Tower, axis: str | None) -> float:
    """Return the gable's base width [m] in the direction of a case (module docstring).

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        A tower with the bell-gable columns.
    axis : {"x", "y"} or None
        The tower axis the case's component is along
        (:data:`rockscreen.stations.inventory_columns.TOWER_AXES`), None when it is along
        neither.

    Returns
    -------
    float
        ``gable_thickness_m`` along ``gable_axis`` (out of its plane), and wherever the
        plane is not known (no ``gable_axis``, or ``axis`` None); across it (in its plane)
        the piers' total width ``gable_width_m x (1 - gable_opening_ratio)``.
    """
    if axis is not None and axis not in TOWER_AXES:
        allowed = ", ".join(TOWER_AXES)
        raise ValueError(f"bell gable: axis {axis!r} must be one of {allowed} or None")
    if axis is None or tower.gable_axis is None or axis == tower.gable_axis:
        return float(tower.gable_thickness_m)
    return float(tower.gable_width_m) * (1.0 - float(tower.gable_opening_ratio or 0.0))


def gable_block(tower: Tower, tower_width_m: float = math.nan, axis: str | None = None) -> Any:
    """Return the gable with its bells as a :class:`rockscreen.solver.RockingBlock`.

    The model's ``own_block`` (:data:`rockscreen.pipeline.engine.registry.OwnBlock`): the
    block of the gable's base width in the case's direction (:func:`gable_width_for`),
    its height, its mass and its bells at two thirds of its height.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        A tower with the bell-gable columns.
    tower_width_m : float
        The tower's width in the case's direction [m] (the registry's signature; not used).
    axis : {"x", "y"} or None
        The tower axis of the case; None (the default): its thickness, the safe side.

    Returns
    -------
    rockscreen.solver.RockingBlock
    """
    height = float(tower.gable_height_m)
    return belfry_block(
        gable_width_for(tower, axis),
        height,
        gable_mass_kg(tower),
        float(tower.gable_bells_mass_kg or 0.0),
        BELLS_HEIGHT_RATIO * height,
    )


def gable_block_note(tower: Tower) -> Message:
    """Return what the gable's block assumes of ``tower``, a clause of ``assess``'s note.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        A tower with the bell-gable columns.

    Returns
    -------
    Message
        ``gable.block_axis``: its thickness along ``gable_axis`` and its piers' width across
        it; or ``gable.block_no_axis``: without ``gable_axis``, its thickness in every
        direction (the safe side).
    """
    thickness = float(tower.gable_thickness_m)
    if tower.gable_axis is None:
        return message("gable.block_no_axis", thickness=thickness)
    across = next(axis for axis in TOWER_AXES if axis != tower.gable_axis)
    return message(
        "gable.block_axis",
        thickness=thickness,
        axis=tower.gable_axis,
        width=gable_width_for(tower, across),
        across=across,
    )


def gable_support(tower: Tower) -> tuple[float, float, float] | None:
    """Return the structure beneath the gable ``(H [m], T1 [s], z [m])``, None on the ground.

    On the church when ``building_height_m`` reaches the gable's base (its
    ``building_period_s``, else ``0.0187 H``), else a structure as high as the base with
    ``0.0187 z`` (module docstring).

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        A tower with the bell-gable columns.

    Returns
    -------
    tuple of float or None
        Height H of the structure [m], its period T1 [s], the gable's base z [m].
    """
    from rockscreen.pipeline.motion.floor import building_period_from_height

    z = float(tower.gable_base_height_m)
    if z <= 0.0:
        return None
    if tower.building_height_m is not None and z <= tower.building_height_m:
        height, period = float(tower.building_height_m), tower.building_period_s
    else:
        height, period = z, None
    if period is None:
        period = building_period_from_height(height, "faccio2010")
    return height, float(period), z


def gable_base_motion(tower: Tower, acc: np.ndarray, dt: float) -> np.ndarray:
    """Return the acceleration at the gable's base [m/s²] (module docstring).

    The filter is the active solvers' ``floor``
    (:func:`~rockscreen.pipeline.engine.solvers.active_solvers`).

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        A tower with the bell-gable columns.
    acc : numpy.ndarray
        Ground acceleration [m/s²] at step ``dt``.
    dt : float
        Sampling step [s].
    """
    support = gable_support(tower)
    base = np.asarray(acc, dtype=float)
    if support is None:
        return base
    height, period, z = support
    motion = active_solvers().floor(base, dt, building_period=period, mode_shape_at_base=z / height)
    return np.asarray(motion, dtype=float)


MODEL = TowerModel(
    name="gable",
    order=5,
    label="bell gable rocking on its base",
    label_it="vela campanaria che oscilla sulla propria base",
    solve=solve_single_block,
    requires=GABLE_GROUP,
    base_motion=gable_base_motion,
    own_block=gable_block,
    block_note=gable_block_note,
)
