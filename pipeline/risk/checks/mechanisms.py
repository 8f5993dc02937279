"""The three overturning mechanisms of a bell tower, built from its dimensions.

- :func:`whole_tower_mechanism`: the whole tower rotating about the toe of its base;
- :func:`belfry_mechanism`: the belfry rotating about the toe at the top of the shaft (an
  elevated mechanism: check it with an
  :class:`rockscreen.pipeline.risk.checks.kinematic_demand.ElevatedSupport` for the shaft);
- :func:`bell_gable_mechanism`: a bell gable (*vela campanaria*) overturning out of its
  plane about its base.

Masses in kg, lengths in m. Each mass is placed in the mechanism's own frame: heights above
its hinge, horizontal distances from the hinge inward. The bells hang at mid-width (the
swinging bells' own dynamic forces are not modelled).
"""

from __future__ import annotations

from collections.abc import Sequence

from rockscreen.pipeline.risk.checks.kinematic import Mechanism, PointMass, RigidBlock
from rockscreen.pipeline.risk.checks.validation import check_number

__all__ = ["belfry_mechanism", "bell_gable_mechanism", "whole_tower_mechanism"]


def whole_tower_mechanism(
    *,
    height_m: float,
    width_m: float,
    mass_kg: float,
    masses: Sequence[PointMass] = (),
) -> Mechanism:
    """Return the whole tower as one uniform block rotating about the toe of its base.

    Parameters
    ----------
    height_m : float
        Height of the masonry [m], > 0.
    width_m : float
        Plan dimension along the seismic action [m], > 0 (hollow or not: a symmetric
        section has its centroid at mid-width).
    mass_kg : float
        Mass of the masonry [kg], > 0.
    masses : sequence of PointMass
        Bells, roof, spire... (heights above the tower's base).

    Returns
    -------
    Mechanism
    """
    shaft = RigidBlock(mass_kg, width_m, height_m, name="tower")
    return Mechanism("whole tower", (shaft,), tuple(masses))


def belfry_mechanism(
    *,
    width_m: float,
    height_m: float,
    piers_mass_kg: float,
    bells_mass_kg: float = 0.0,
    bells_height_m: float | None = None,
    roof_mass_kg: float = 0.0,
) -> Mechanism:
    """Return the belfry rotating about the toe at the top of the shaft.

    Parameters
    ----------
    width_m : float
        Effective width of the belfry's piers along the action [m], > 0 (the outer plan
        dimension when the belfry rocks as a whole).
    height_m : float
        Height of the belfry above the top of the shaft [m], > 0.
    piers_mass_kg : float
        Mass of the piers and arches [kg], > 0.
    bells_mass_kg : float
        Mass of the bells and their frame [kg], >= 0.
    bells_height_m : float, optional
        Height of the bells' hanging point above the top of the shaft [m], in
        [0, height_m]; default: half the belfry's height.
    roof_mass_kg : float
        Mass of the roof or spire, applied at the belfry's top [kg], >= 0.

    Returns
    -------
    Mechanism
    """
    piers = RigidBlock(piers_mass_kg, width_m, height_m, name="belfry piers")
    points = []
    if check_number("bells_mass_kg", bells_mass_kg, low=0.0, unit="kg") > 0.0:
        z = 0.5 * height_m if bells_height_m is None else bells_height_m
        check_number("bells_height_m", z, low=0.0, high=height_m, unit="m")
        points.append(PointMass(bells_mass_kg, z, 0.5 * width_m, name="bells"))
    if check_number("roof_mass_kg", roof_mass_kg, low=0.0, unit="kg") > 0.0:
        points.append(PointMass(roof_mass_kg, height_m, 0.5 * width_m, name="roof"))
    return Mechanism("belfry", (piers,), tuple(points))


def bell_gable_mechanism(
    *,
    thickness_m: float,
    height_m: float,
    mass_kg: float,
    bells_mass_kg: float = 0.0,
    bells_height_m: float | None = None,
) -> Mechanism:
    """Return a bell gable (vela) overturning out of its plane about its base.

    Parameters
    ----------
    thickness_m : float
        Thickness of the gable (its dimension along the action) [m], > 0.
    height_m : float
        Height of the gable above its base [m], > 0.
    mass_kg : float
        Mass of the gable's masonry, openings deducted [kg], > 0.
    bells_mass_kg : float
        Mass of the bells [kg], >= 0.
    bells_height_m : float, optional
        Height of the bells' hanging point above the base [m], in [0, height_m]; default
        two thirds of the height.

    Returns
    -------
    Mechanism
    """
    gable = RigidBlock(mass_kg, thickness_m, height_m, name="bell gable")
    points = ()
    if check_number("bells_mass_kg", bells_mass_kg, low=0.0, unit="kg") > 0.0:
        z = 2.0 * height_m / 3.0 if bells_height_m is None else bells_height_m
        check_number("bells_height_m", z, low=0.0, high=height_m, unit="m")
        points = (PointMass(bells_mass_kg, z, 0.5 * thickness_m, name="bells"),)
    return Mechanism("bell gable", (gable,), points)
