"""``belfry``: the belfry (the bell cell on its piers) rocking on the top of the shaft.

The belfry is a rigid block of the piers' effective width and the belfry's height, with
the bells as a point mass on its axis (:func:`composite_section`), rocking about a pier's
outer edge at the top of the shaft. Its base motion is the shaft's response at its top:
the modal floor accelerogram (``docs/floor_motion.md``) of the tower's own first mode,
applied to the motion at the tower's base, the ground's or, for a tower standing on the
church, the floor model's (:func:`shaft_top_motion`). Derivation, assumptions and what
the model leaves out: ``docs/belfry.md``.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import Any, NamedTuple

import numpy as np

from rockscreen.pipeline.engine.models.floor import MODEL as FLOOR_MODEL
from rockscreen.pipeline.engine.models.ground import solve_single_block
from rockscreen.pipeline.engine.registry import TowerModel
from rockscreen.pipeline.engine.solvers import active_solvers
from rockscreen.pipeline.vocabulary import TOWER_AXES
from rockscreen.stations.tower import Tower

__all__ = [
    "CompositeSection",
    "MODEL",
    "belfry_block",
    "tower_belfry_block",
    "belfry_width_for",
    "composite_section",
    "shaft_period",
    "shaft_top_motion",
]


class CompositeSection(NamedTuple):
    """The belfry and its bells as one rigid body, in the rocking plane."""

    #: Total mass M = m_piers + m_bells [kg].
    mass_kg: float
    #: Height of the centre of mass above the belfry's base, z_G [m].
    centroid_height_m: float
    #: Distance R from the rocking edge to the centre of mass [m].
    radius_m: float
    #: Moment of inertia about the rocking edge over the total mass, I_O/M [m^2].
    inertia_per_mass_m2: float


def composite_section(
    width_m: float,
    height_m: float,
    piers_mass_kg: float,
    bells_mass_kg: float,
    bells_height_m: float,
) -> CompositeSection:
    """Return the centroid, R and I_O/M of the belfry with its bells (``docs/belfry.md``).

    The piers and arches are a uniform rectangle ``2b x h`` (``b = width_m / 2``) of mass
    ``m_p``; the bells a point mass ``m_c`` on the axis at height ``z_c``::

        M   = m_p + m_c
        z_G = (m_p h/2 + m_c z_c) / M
        R   = sqrt(b^2 + z_G^2)
        I_O = m_p (4 b^2 + h^2) / 3 + m_c (b^2 + z_c^2)

    Without bells ``R`` is the half-diagonal and ``I_O/M = 4/3 R^2``, the solid block of
    :meth:`rockscreen.solver.RockingBlock.from_dimensions`.

    Parameters
    ----------
    width_m : float
        Effective base width 2b of the piers along the action [m], > 0.
    height_m : float
        Height h of the belfry above the top of the shaft [m], > 0.
    piers_mass_kg : float
        Mass of the piers and arches [kg], > 0.
    bells_mass_kg : float
        Mass of the bells and their frame [kg], >= 0.
    bells_height_m : float
        Height of the bells above the belfry's base [m], in [0, height_m].

    Returns
    -------
    CompositeSection
    """
    b = 0.5 * width_m
    mass = piers_mass_kg + bells_mass_kg
    z_g = (piers_mass_kg * 0.5 * height_m + bells_mass_kg * bells_height_m) / mass
    inertia = piers_mass_kg * (width_m**2 + height_m**2) / 3.0
    inertia += bells_mass_kg * (b**2 + bells_height_m**2)
    return CompositeSection(mass, z_g, math.hypot(b, z_g), inertia / mass)


@lru_cache(maxsize=256)
def _cached_block(
    width_m: float,
    height_m: float,
    piers_mass_kg: float,
    bells_mass_kg: float,
    bells_height_m: float,
) -> Any:
    from rockscreen.solver import RockingBlock

    section = composite_section(width_m, height_m, piers_mass_kg, bells_mass_kg, bells_height_m)
    return RockingBlock.from_section(
        width_m,
        height_m,
        radius=section.radius_m,
        inertia_per_mass=section.inertia_per_mass_m2,
    )


def belfry_block(
    width_m: float,
    height_m: float,
    piers_mass_kg: float,
    bells_mass_kg: float = 0.0,
    bells_height_m: float = 0.0,
) -> Any:
    """Return the belfry with its bells as a :class:`rockscreen.solver.RockingBlock`.

    ``alpha = asin(b/R)``, ``p = sqrt(g R / (I_O/M))`` and Housner's restitution
    ``eta = 1 - 2 (M R^2/I_O) sin^2(alpha)`` of the composite (:func:`composite_section`);
    the tower's ``eta`` belongs to its base joint and is not used.

    Parameters
    ----------
    width_m, height_m, piers_mass_kg, bells_mass_kg, bells_height_m
        As in :func:`composite_section` [m, m, kg, kg, m].

    Returns
    -------
    rockscreen.solver.RockingBlock
    """
    key = (width_m, height_m, piers_mass_kg, bells_mass_kg, bells_height_m)
    return _cached_block(*map(float, key))


def belfry_width_for(tower: Tower, axis: str | None) -> float:
    """Return the belfry's effective width [m] in the direction of a case.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        A tower with the belfry columns.
    axis : {"x", "y"} or None
        The tower axis the case's component is along
        (:data:`rockscreen.stations.inventory_columns.TOWER_AXES`): ``belfry_width_m``
        along x, the belfry's plan depth along y. None (a component along neither axis):
        the smaller of the two, the safe side.

    Returns
    -------
    float
        The piers' effective base width 2b along the action [m].
    """
    along = dict(zip(TOWER_AXES, (tower.belfry_width_m, tower.belfry_plan_depth_m), strict=True))
    if axis is None:
        return min(along.values())
    if axis not in along:
        raise ValueError(f"belfry: axis {axis!r} must be one of {', '.join(along)} or None")
    return along[axis]


def tower_belfry_block(tower: Tower, tower_width_m: float, axis: str | None) -> Any:
    """Return the belfry's block of ``tower`` in the direction of a case.

    The model's ``own_block`` (:data:`rockscreen.pipeline.engine.registry.OwnBlock`): the
    case engine solves, pre-checks uplift and searches on this block.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        A tower with the belfry columns.
    tower_width_m : float
        The tower's base width in the case's direction [m] (the registry's signature; the
        belfry's width follows the axis, :func:`belfry_width_for`).
    axis : {"x", "y"} or None
        The tower axis of the case; None when the component is along neither.

    Returns
    -------
    rockscreen.solver.RockingBlock
    """
    return belfry_block(
        belfry_width_for(tower, axis),
        tower.belfry_height_m,
        tower.belfry_mass_kg,
        tower.bells_mass_kg,
        tower.bells_height_m,
    )


def shaft_period(tower: Tower) -> float:
    """Return the tower's first period [s]: ``shaft_period_s``, else ``0.0187 H``.

    ``H`` is ``height_m``, the tower's height above its springing (shaft and belfry); the
    law is Faccio, Paolucci & Zanotti's (2010) fit on Italian masonry towers
    (:data:`rockscreen.pipeline.motion.floor.PERIOD_LAWS` ``"faccio2010"``; its source and
    the ``0.0187 H^1.17`` variant: ``docs/belfry.md``). An assumption, reported as such.
    """
    from rockscreen.pipeline.motion.floor import building_period_from_height

    if tower.shaft_period_s is not None:
        return float(tower.shaft_period_s)
    return building_period_from_height(tower.height_m, "faccio2010")


def shaft_top_motion(tower: Tower, acc: np.ndarray, dt: float) -> np.ndarray:
    """Return the acceleration at the top of the shaft, the belfry's base [m/s²].

    The motion at the tower's base (the ground's, or the floor model's at the springing
    when the tower stands on the building) filtered through the tower's first mode: the
    modal floor accelerogram with the tower's period (:func:`shaft_period`), its default
    damping (5 %) and participation (3/2) and the linear mode shape at the belfry's
    base, ``(H - h_belfry) / H`` (``docs/belfry.md``); the filters are the active solvers'
    ``floor`` (:func:`~rockscreen.pipeline.engine.solvers.active_solvers`).

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        A tower with the belfry columns.
    acc : numpy.ndarray
        Ground acceleration [m/s²] at step ``dt``.
    dt : float
        Sampling step [s].
    """
    base = np.asarray(acc, dtype=float)
    if FLOOR_MODEL.available(tower):
        base = FLOOR_MODEL.excitation(tower, base, dt)
    shape = (tower.height_m - tower.belfry_height_m) / tower.height_m
    motion = active_solvers().floor(
        base,
        dt,
        building_period=shaft_period(tower),
        mode_shape_at_base=shape,
    )
    return np.asarray(motion, dtype=float)


MODEL = TowerModel(
    name="belfry",
    order=4,
    label="belfry rocking on the top of the shaft",
    label_it="cella campanaria che oscilla sulla sommità del fusto",
    solve=solve_single_block,
    requires=(
        "belfry_height_m",
        "belfry_width_m",
        "belfry_mass_kg",
        "bells_mass_kg",
        "bells_height_m",
    ),
    base_motion=shaft_top_motion,
    own_block=tower_belfry_block,
)
