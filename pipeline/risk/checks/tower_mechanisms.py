"""A tower's local mechanisms from its inventory columns, for the kinematic checks.

The whole tower overturning about its base, the belfry about the top of the shaft and a
bell gable about its base (Circolare 2019 §C8.7.1.2.1; docs/code_checks.md), each as the
:class:`~rockscreen.pipeline.risk.checks.kinematic.Mechanism` of its blocks with the
support it stands on (ground, shaft or building) and the assumptions made for missing
data. :mod:`rockscreen.pipeline.risk.checks.tower_checks` runs the checks on them.

All three stand free above their hinge, the elements "liberi di vibrare" of §C8.7.1.2.1.3,
so each has an elastic period ``T0``: the whole tower its first period (``shaft_period_s``,
else ``0.0187 H``), the belfry and the gable that of a solid masonry cantilever
([C8.7.1.7], :func:`~rockscreen.pipeline.risk.checks.kinematic.cantilever_period`) of
their height and thickness along the action, the mean modulus of the masonry type (Table
C8.5.I) halved for cracking (NTC 2018 §7.2.6).
"""

from __future__ import annotations

from dataclasses import replace

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.motion.floor import building_period_from_height
from rockscreen.pipeline.risk.checks.confidence import (
    MASONRY_TYPES,
    masonry_elastic_modulus,
)
from rockscreen.pipeline.risk.checks.kinematic import (
    CRACKED_STIFFNESS_RATIO,
    Mechanism,
    PointMass,
    cantilever_period,
)
from rockscreen.pipeline.risk.checks.kinematic_demand import ElevatedSupport
from rockscreen.pipeline.risk.checks.mechanisms import (
    belfry_mechanism,
    bell_gable_mechanism,
    whole_tower_mechanism,
)
from rockscreen.pipeline.verdict.messages import Message, message
from rockscreen.stations.tower import Tower

__all__ = [
    "ASSUMED_MASONRY",
    "belfry_kinematic_mechanism",
    "gable_kinematic_mechanism",
    "tower_kinematic_mechanism",
    "tower_period",
    "tower_support",
    "WHOLE_TOWER",
    "BELFRY",
    "GABLE",
]

#: Masonry type whose unit weight (Circolare 2019 Table C8.5.I) gives the tower's mass when
#: the inventory has none (solid prism width x depth x height), and whose modulus gives the
#: belfry's and the gable's T0 when the inventory names no type: an assumption, listed in the
#: note. A uniform block's alpha0 and e* do not depend on its mass; the mass only weighs the
#: bells against the masonry.
ASSUMED_MASONRY = "rubble"


#: The blocks whose assumptions a note names (``{part}`` of ``kinematic.of``).
WHOLE_TOWER = message("kinematic.whole_tower")
BELFRY = message("kinematic.belfry")
GABLE = message("kinematic.gable")


def _of(part: Message, note: Message) -> Message:
    """Return ``note`` said of the block ``part`` (``"belfry kinematic: ..."``)."""
    return message("kinematic.of", part=part, note=note)


def tower_period(tower: Tower) -> tuple[float, list[Message]]:
    """Return the tower's first period [s] (``shaft_period_s``, else ``0.0187 H``) and notes."""
    if tower.shaft_period_s is not None:
        return float(tower.shaft_period_s), []
    period = building_period_from_height(tower.height_m, "faccio2010")
    return period, [message("kinematic.tower_period", period=period)]


def _masonry(tower: Tower, part: Message) -> tuple[str, list[Message]]:
    if tower.masonry_type is not None:
        return tower.masonry_type, []
    return ASSUMED_MASONRY, [
        _of(part, message("kinematic.masonry_assumed", masonry=ASSUMED_MASONRY))
    ]


def _cantilever_t0(tower: Tower, kind: str, length_m: float, thickness_m: float) -> float:
    modulus = masonry_elastic_modulus(kind, tower.knowledge_level or "LC1")
    return cantilever_period(
        length_m,
        thickness_m,
        MASONRY_TYPES[kind].unit_weight_n_m3,
        CRACKED_STIFFNESS_RATIO * modulus,
    )


def tower_kinematic_mechanism(tower: Tower) -> tuple[Mechanism, list[Message]]:
    """Return the whole tower about the toe of its base, in its weaker plan direction.

    One uniform block of the tower's height and smaller plan dimension (``width_m`` or
    the plan depth: alpha0 = b/h is lower along it), of mass ``tower_mass_kg`` or, when the
    inventory has none, a solid prism of :data:`ASSUMED_MASONRY`'s unit weight; the bells
    (``bells_mass_kg``) as a point mass at their height when given; ``T0`` the tower's
    period (:func:`tower_period`).

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower

    Returns
    -------
    mechanism : Mechanism
    assumptions : list of Message
        What was assumed, for the row's note.
    """
    width = min(tower.width_m, tower.plan_depth_m)
    assumptions = []
    if tower.tower_mass_kg is not None:
        mass = float(tower.tower_mass_kg)
    else:
        masonry = MASONRY_TYPES[ASSUMED_MASONRY]
        mass = masonry.density_kg_m3 * tower.width_m * tower.plan_depth_m * tower.height_m
        prism = message(
            "kinematic.solid_prism",
            weight_kn_m3=masonry.unit_weight_n_m3 / 1e3,
            masonry=ASSUMED_MASONRY,
        )
        assumptions.append(_of(WHOLE_TOWER, prism))
    points = []
    if tower.has_belfry and tower.bells_mass_kg:
        z = tower.height_m - tower.belfry_height_m + tower.bells_height_m
        points.append(PointMass(float(tower.bells_mass_kg), z, 0.5 * width, name="bells"))
    period, notes = tower_period(tower)
    assumptions += [_of(WHOLE_TOWER, note) for note in notes]
    mechanism = whole_tower_mechanism(
        height_m=tower.height_m, width_m=width, mass_kg=mass, masses=points
    )
    return replace(mechanism, elastic_period_s=period), assumptions


def belfry_kinematic_mechanism(tower: Tower) -> tuple[Mechanism, ElevatedSupport, list[Message]]:
    """Return the belfry about the toe at the top of the shaft, and the shaft beneath.

    The belfry's smaller pier width, its height, piers' mass and bells
    (:func:`rockscreen.pipeline.risk.checks.mechanisms.belfry_mechanism`), ``T0`` of a
    solid cantilever of the piers' width (module docstring); the support is the shaft
    (height ``height_m - belfry_height_m``, the belfry at its top) with the tower's period
    (:func:`tower_period`, the belfry model's law, ``docs/belfry.md``).

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        A tower with the belfry columns (``tower.has_belfry``).

    Returns
    -------
    mechanism : Mechanism
    support : ElevatedSupport
    assumptions : list of str
    """
    if not tower.has_belfry:
        raise RiskError(f"tower {tower.id}: no belfry columns, no belfry mechanism")
    mechanism = belfry_mechanism(
        width_m=min(tower.belfry_width_m, tower.belfry_plan_depth_m),
        height_m=tower.belfry_height_m,
        piers_mass_kg=tower.belfry_mass_kg,
        bells_mass_kg=tower.bells_mass_kg,
        bells_height_m=tower.bells_height_m,
    )
    period, notes = tower_period(tower)
    assumptions = [_of(BELFRY, note) for note in notes]
    kind, notes = _masonry(tower, BELFRY)
    assumptions += notes
    width = min(tower.belfry_width_m, tower.belfry_plan_depth_m)
    t0 = _cantilever_t0(tower, kind, tower.belfry_height_m, width)
    mechanism = replace(mechanism, elastic_period_s=t0)
    assumptions.append(_of(BELFRY, message("kinematic.belfry_t0", t0=t0)))
    if tower.building_height_m is not None:
        assumptions.append(_of(BELFRY, message("kinematic.belfry_church_ignored")))
    shaft = tower.height_m - tower.belfry_height_m
    return mechanism, ElevatedSupport(height_m=shaft, period_s=period), assumptions


def tower_support(tower: Tower) -> tuple[ElevatedSupport | None, list[Message]]:
    """Return the church beneath a tower standing on it (floor model's columns), or None.

    The support of every check of the whole tower on the church: its elevated kinematic
    mechanism (:func:`tower_kinematic_mechanism`) and its LV1 demand
    (:mod:`rockscreen.pipeline.risk.checks.tower_lv1_checks`). The church is a structure of height
    ``building_height_m`` and period ``building_period_s`` (else ``0.0187 H`` of the church,
    assumed), the tower's springing at ``base_height_m`` above its foundation.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower

    Returns
    -------
    support : ElevatedSupport or None
        None for a tower on the ground (no ``building_height_m``).
    assumptions : list of Message
        What was assumed (the church's period), without a prefix: the caller names its
        check.
    """
    if tower.building_height_m is None:
        return None, []
    notes = []
    period = tower.building_period_s
    if period is None:
        period = building_period_from_height(tower.building_height_m, "faccio2010")
        notes.append(message("kinematic.church_period", period=period))
    level = tower.building_height_m if tower.base_height_m is None else tower.base_height_m
    return ElevatedSupport(tower.building_height_m, float(period), level_m=level), notes


def gable_kinematic_mechanism(
    tower: Tower,
) -> tuple[Mechanism, ElevatedSupport | None, list[Message]]:
    """Return the bell gable (vela) overturning out of its plane, and the structure beneath.

    The gable is one block of its thickness (along the action) and height, of mass
    ``height x width x thickness x (1 - opening ratio)`` at the unit weight of the tower's
    ``masonry_type`` (else :data:`ASSUMED_MASONRY`), the bells at two thirds of its height
    (:func:`rockscreen.pipeline.risk.checks.mechanisms.bell_gable_mechanism`). With its
    base above the ground it is an elevated mechanism (docs/code_checks.md §1.4): on the
    church when ``building_height_m`` reaches the gable's base (``building_period_s`` or
    ``0.0187 H``), else on a structure of the base's height with the period ``0.0187 H``.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        A tower with the bell-gable columns (``tower.has_gable``).

    Returns
    -------
    mechanism : Mechanism
    support : ElevatedSupport or None
        None for a gable on the ground.
    assumptions : list of str
    """
    if not tower.has_gable:
        raise RiskError(f"tower {tower.id}: no bell-gable columns, no gable mechanism")
    kind, assumptions = _masonry(tower, GABLE)
    opening = float(tower.gable_opening_ratio or 0.0)
    volume = tower.gable_height_m * tower.gable_width_m * tower.gable_thickness_m
    mechanism = bell_gable_mechanism(
        thickness_m=tower.gable_thickness_m,
        height_m=tower.gable_height_m,
        mass_kg=MASONRY_TYPES[kind].density_kg_m3 * volume * (1.0 - opening),
        bells_mass_kg=float(tower.gable_bells_mass_kg or 0.0),
    )
    t0 = _cantilever_t0(tower, kind, tower.gable_height_m, tower.gable_thickness_m)
    mechanism = replace(mechanism, elastic_period_s=t0)
    assumptions.append(_of(GABLE, message("kinematic.gable_t0", t0=t0)))
    z = float(tower.gable_base_height_m)
    if z <= 0.0:
        return mechanism, None, assumptions
    if tower.building_height_m is not None and z <= tower.building_height_m:
        height, period = float(tower.building_height_m), tower.building_period_s
        beneath = message("kinematic.church")
    else:
        height, period, beneath = z, None, message("kinematic.structure_beneath")
    if period is None:
        period = building_period_from_height(height, "faccio2010")
        said = message("kinematic.support_period", beneath=beneath, period=period)
        assumptions.append(_of(GABLE, said))
    return mechanism, ElevatedSupport(height, float(period), level_m=z), assumptions
