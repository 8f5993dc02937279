"""The LV1 tower model of the Guidelines in ``assess``, from the inventory's shaft columns.

Per tower, in the worker (issue 22): when the inventory gives the shaft's wall thickness
(``wall_thickness_m``) and masonry type (``masonry_type``, Circolare 2019 Table C8.5.I), the
LV1 model of the Guidelines for towers (DPCM 9/2/2011 §5.4.4,
:func:`rockscreen.pipeline.risk.checks.tower_lv1.lv1_tower`) gives ``lv1_capacity_ag_g``
and ``lv1_safety_index``; otherwise they stay NaN and :func:`lv1_columns` returns the reason,
naming the missing columns, for ``checks_not_made``.

The model built from a row (:func:`lv1_tower_model`):

- the shaft: hollow segments of outer ``width_m`` x plan depth, of the type's unit weight
  (Table C8.5.I), from the tower's base to the top of the shaft (``height_m -
  belfry_height_m`` with the belfry columns, else the whole ``height_m``: a belfry without
  its columns is counted as shaft). Without ``wall_thickness_top_m``: one prismatic segment
  of wall ``wall_thickness_m`` (cut into 20 slices). With it (and thinner than the base):
  :data:`LV1_TAPER_SEGMENTS` = 10 prismatic segments of equal height, each of the wall
  interpolated linearly at its mid-height between ``wall_thickness_m`` at the base and
  ``wall_thickness_top_m`` at the top, cut into 2 slices each: the same 20 slices as the
  prismatic shaft, so the two differ only by the walls. Each checked section (a slice's
  bottom) gets a wall no thicker than the true one at its height, and the shaft's weight
  (the midpoint rule on the hollow area ``A(z) = 2 t (a + b) - 4 t^2``, concave in ``z``)
  is overstated by ``w s^2 H h^2 / 3`` (``s`` the taper dt/dz, ``h = H / 10``; 6e-5 of it
  for a 55 m shaft tapering from 1.67 to 0.80 m): both on the safe side;
- the belfry's piers at mid-height of the belfry and the bells at their height, as point
  masses (with the belfry columns);
- ``f_m`` of the type at the knowledge level (LC1 the table's lower end, LC2 its mid value;
  LC3 the measured ``masonry_strength_mpa`` of the row, Circolare 2019 §C8.5.4.1:
  :func:`lv1_masonry_strength`), ``f_d = f_m / (gamma_M F_C)`` with ``gamma_M = 2``
  (``design_compressive_strength``); at LC3 without ``masonry_strength_mpa`` the model is
  not made (said, naming the column); a measured value at LC1 or LC2 is refused;
- the period: ``shaft_period_s`` when measured, else ``0.0187 H`` with H the whole tower's
  height ``height_m``, belfry included
  (:func:`~rockscreen.pipeline.risk.checks.tower_lv1.tower_period_guidelines`), the
  same T1 as the belfry model's;
- both plan directions; the lower ``a_SLV`` governs.

The demand: the ground's elastic spectrum ``Se(T1)`` for a tower on the ground. A tower
standing on a church (``building_height_m``) is checked on the church's floor spectrum, the
Circolare 2019's ``S_eZ(T1, z)`` (§C7.2.3, [C7.2.5]-[C7.2.10]) at the tower's springing
``z = base_height_m``, the church elastic (``T_k`` = ``building_period_s``, else
``0.0187 H`` of the church; ``xi_k`` = 5 %), never below ``Se(T1)``: the support of the
whole tower's elevated kinematic check
(:func:`rockscreen.pipeline.risk.checks.tower_mechanisms.tower_support`) and the demand of
:func:`rockscreen.pipeline.risk.checks.tower_lv1.lv1_demand`; said in the note.
"""

from __future__ import annotations

from typing import Any

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.checks.confidence import (
    MASONRY_TYPES,
    design_compressive_strength,
    masonry_strength,
)
from rockscreen.pipeline.risk.checks.kinematic import PointMass
from rockscreen.pipeline.risk.checks.kinematic_demand import ElevatedSupport
from rockscreen.pipeline.risk.checks.registry import CheckContext, CheckOutput, code_check
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.checks.tower_lv1 import (
    ShaftSegment,
    TowerLV1,
    TowerModel,
    lv1_tower,
    tower_period_guidelines,
)
from rockscreen.pipeline.risk.checks.tower_mechanisms import tower_support
from rockscreen.pipeline.verdict.messages import Message, message, render
from rockscreen.pipeline.verdict.status import Status
from rockscreen.stations.errors import RockscreenError
from rockscreen.stations.inventory_columns import (
    MEASURED_STRENGTH_COLUMN,
    TESTED_KNOWLEDGE_LEVEL,
)
from rockscreen.stations.tower import Tower

__all__ = [
    "LV1_COLUMN_UNITS",
    "LV1_NOT_MADE",
    "LV1_TAPER_SEGMENTS",
    "LV1_TAPER_SLICES",
    "lv1_check",
    "lv1_columns",
    "lv1_masonry_strength",
    "lv1_not_made_reason",
    "lv1_reason",
    "lv1_tower_model",
    "shaft_description",
    "shaft_walls_m",
]

#: Prismatic segments of a shaft whose walls taper (``wall_thickness_top_m``), and the
#: slices each is cut into: 10 x 2, the 20 slices of a prismatic shaft (``TowerModel``'s
#: default ``slices_per_segment``).
LV1_TAPER_SEGMENTS = 10
LV1_TAPER_SLICES = 2
#: How every reason for a missing LV1 starts as printed (``checks_not_made``; the reasons
#: are messages, :func:`lv1_not_made_reason`).
LV1_NOT_MADE = "LV1 not made"
#: Pa per MPa (the inventory's ``masonry_strength_mpa`` -> SI).
_PA_PER_MPA = 1.0e6
#: The LV1 columns of a summary row -> units (schema words).
LV1_COLUMN_UNITS = {
    # a_SLV: ag on rock at which the demand at T1 (Se(T1), on a church its floor spectrum
    # S_eZ(T1, z)) equals S_e,SLV
    "lv1_capacity_ag_g": "g",
    "lv1_safety_index": "1",  # I_S = T_SLV / T_R,SLV
    "lv1_acceleration_factor": "1",  # f_a = a_SLV / a_g,SLV
    "lv1_period_s": "s",  # T1 used
    # sigma_0 / (0.85 f_d) at the critical section: >= 1 the weight alone crushes it
    "lv1_compression_ratio": "1",
    "lv1_bound": "text",  # "", "lower" (holds at 2475 y), "upper" (fails at 30 y)
}


def lv1_masonry_strength(tower: Tower, knowledge_level: str) -> tuple[float, Message]:
    """Return the mean compressive strength f_m [Pa] of a tower's masonry, and its source.

    Circolare 2019 §C8.5.4.1 on Table C8.5.I
    (:func:`~rockscreen.pipeline.risk.checks.confidence.masonry_strength`): LC1 the
    lower end of the type's range, LC2 its mean, LC3 the value from tests, the row's
    ``masonry_strength_mpa``.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        A tower with ``masonry_type`` (and ``masonry_strength_mpa`` at LC3).
    knowledge_level : {"LC1", "LC2", "LC3"}
        The tower's knowledge level.

    Returns
    -------
    fm_pa : float
        f_m [Pa], not yet divided by F_C.
    source : Message
        For the note (``lv1model.fm_*``), e.g. ``"f_m = 3.45 MPa (Table C8.5.I, LC2: the
        range's mean)"`` in English.

    Raises
    ------
    RiskError
        For LC3 without ``masonry_strength_mpa``, or ``masonry_strength_mpa`` at LC1 or LC2
        (each naming the column).
    """
    level = str(knowledge_level).strip().upper()
    measured = tower.masonry_strength_mpa
    if measured is not None and level != TESTED_KNOWLEDGE_LEVEL:
        raise RiskError(
            f"tower {tower.id}: {MEASURED_STRENGTH_COLUMN}={measured:g} MPa is a measured f_m, "
            f"used only at knowledge level {TESTED_KNOWLEDGE_LEVEL} (Circolare 2019 §C8.5.4.1); "
            f"at {level} the LV1 model takes Table C8.5.I's value"
        )
    if measured is None and level == TESTED_KNOWLEDGE_LEVEL:
        raise RiskError(
            f"tower {tower.id}: knowledge level {TESTED_KNOWLEDGE_LEVEL} rests on a measured "
            f"f_m (Circolare 2019 §C8.5.4.1): no {MEASURED_STRENGTH_COLUMN} in the inventory"
        )
    measured_pa = None if measured is None else float(measured) * _PA_PER_MPA
    fm = masonry_strength(tower.masonry_type, level, measured_pa=measured_pa)
    mpa = fm / _PA_PER_MPA
    if measured is not None:
        return fm, message("lv1model.fm_measured", fm_mpa=mpa, level=level)
    which = "lv1model.fm_table_min" if level == "LC1" else "lv1model.fm_table_mean"
    return fm, message(which, fm_mpa=mpa, level=level)


def lv1_tower_model(tower: Tower, fc: float, knowledge_level: str, *, across: bool = False):
    """Return the LV1 model of a tower from its inventory row (module docstring).

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        A tower with ``wall_thickness_m`` and ``masonry_type`` (and, for walls tapering
        upwards, ``wall_thickness_top_m``).
    fc : float
        Confidence factor F_C [-].
    knowledge_level : {"LC1", "LC2", "LC3"}
        Knowledge level (which value of Table C8.5.I's range, or at LC3 the measured
        ``masonry_strength_mpa``: :func:`lv1_masonry_strength`).
    across : bool
        False: the action along ``width_m``; True: along the plan depth.

    Returns
    -------
    TowerModel
        One prismatic segment of ``wall_thickness_m`` (20 slices) when the row has no
        ``wall_thickness_top_m`` or the same thickness there; else
        :data:`LV1_TAPER_SEGMENTS` segments of :data:`LV1_TAPER_SLICES` slices, bottom
        first, segment ``k``'s wall ``t_0 + (t_top - t_0)(k + 1/2) / 10`` [m].

    Raises
    ------
    RiskError
        For a missing column, LC3 without ``masonry_strength_mpa`` or that column at LC1
        or LC2.
    """
    if tower.lv1_missing:
        raise RiskError(f"tower {tower.id}: no {', '.join(tower.lv1_missing)}")
    masonry = MASONRY_TYPES[tower.masonry_type]
    fm, _ = lv1_masonry_strength(tower, knowledge_level)
    fd = design_compressive_strength(fm, fc)
    b, a = tower.width_m, tower.plan_depth_m
    if across:
        b, a = a, b
    shaft = tower.height_m - tower.belfry_height_m if tower.has_belfry else tower.height_m
    walls = shaft_walls_m(tower)
    segments = tuple(
        ShaftSegment(shaft / len(walls), b, a, wall, masonry.density_kg_m3) for wall in walls
    )
    masses = []
    if tower.has_belfry:
        masses.append(PointMass(tower.belfry_mass_kg, shaft + 0.5 * tower.belfry_height_m, 0.0))
        if tower.bells_mass_kg:
            masses.append(PointMass(tower.bells_mass_kg, shaft + tower.bells_height_m, 0.0))
    if len(segments) == 1:
        return TowerModel(segments, fd, tuple(masses))  # 20 slices, the default
    return TowerModel(segments, fd, tuple(masses), slices_per_segment=LV1_TAPER_SLICES)


def shaft_walls_m(tower: Tower) -> tuple[float, ...]:
    """Return the wall thickness of each of the LV1 model's shaft segments, bottom first [m].

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        A tower with ``wall_thickness_m`` (the base's when ``wall_thickness_top_m`` is
        given).

    Returns
    -------
    tuple of float
        ``(wall_thickness_m,)`` for a prismatic shaft (no ``wall_thickness_top_m``, or the
        same thickness); else :data:`LV1_TAPER_SEGMENTS` values, the linear interpolation
        between the base's and the top's thickness at each segment's mid-height.
    """
    base = float(tower.wall_thickness_m)
    top = tower.wall_thickness_top_m
    if top is None or float(top) == base:
        return (base,)
    n = LV1_TAPER_SEGMENTS
    return tuple(base + (float(top) - base) * (k + 0.5) / n for k in range(n))


def shaft_description(tower: Tower) -> Message:
    """Return the LV1 note's words on the shaft's walls (a part of the model's clause).

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        A tower with ``wall_thickness_m``.

    Returns
    -------
    Message
        ``lv1model.shaft_prismatic`` (``"prismatic shaft, walls 1.20 m"``) or
        ``lv1model.shaft_tapered`` (``"shaft walls tapering from 1.67 m at the base to
        0.80 m at the top (10 segments)"``).
    """
    walls = shaft_walls_m(tower)
    if len(walls) == 1:
        return message("lv1model.shaft_prismatic", wall_m=walls[0])
    return message(
        "lv1model.shaft_tapered",
        base_m=float(tower.wall_thickness_m),
        top_m=float(tower.wall_thickness_top_m),
        n=len(walls),
    )


def lv1_not_made_reason(tower: Tower, knowledge_level: str) -> Message | None:
    """Return why the LV1 model cannot be made for ``tower`` (a message), None when it can.

    Without ``wall_thickness_m`` or ``masonry_type`` (naming those missing); at LC3 without
    the measured ``masonry_strength_mpa`` LC3 rests on.

    Parameters
    ----------
    tower : Tower
        The tower.
    knowledge_level : str
        Its knowledge level (``"LC1"``...).
    """
    missing = list(tower.lv1_missing)
    if len(missing) == 2:
        return message("not_made.lv1_columns", a=missing[0], b=missing[1])
    if missing:
        return message("not_made.lv1_column", column=" and ".join(missing))
    if (
        str(knowledge_level).strip().upper() == TESTED_KNOWLEDGE_LEVEL
        and tower.masonry_strength_mpa is None
    ):
        return message(
            "not_made.lv1_measured_strength",
            level=TESTED_KNOWLEDGE_LEVEL,
            column=MEASURED_STRENGTH_COLUMN,
        )
    return None


def lv1_columns(
    site: Any, fc: float, knowledge_level: str
) -> tuple[dict[str, Any], list[Message], list[str]]:
    """Return the LV1 columns of a tower, the notes, and why it was not made (if not).

    Parameters
    ----------
    site : rockscreen.pipeline.risk.assess.sites.TowerSite
        The tower and its site.
    fc : float
        Confidence factor F_C [-].
    knowledge_level : str
        The tower's knowledge level (LC1, LC2, LC3).

    Returns
    -------
    columns : dict
        :data:`LV1_COLUMN_UNITS` (empty when not made).
    notes : list of Message
    missing : list of str
        ``["LV1 not made (...)"]`` naming the missing columns or the reason (at LC3 without
        ``masonry_strength_mpa``, that column); empty when made.

    Raises
    ------
    RiskError
        For ``masonry_strength_mpa`` at LC1 or LC2 (:func:`lv1_masonry_strength`; ``assess``
        refuses it before any work, ``knowledge.check_measured_strengths``).
    """
    tower = site.tower
    reason = lv1_not_made_reason(tower, knowledge_level)
    if reason is not None:
        return {}, [], [render(reason)]
    knowledge_level = str(knowledge_level).strip().upper()
    _, strength = lv1_masonry_strength(tower, knowledge_level)
    conditions = SiteConditions.of(site)
    # The whole tower's period (belfry included), measured or from its full height: the
    # same T1 as the belfry model's (docs/belfry.md), not the shaft's alone.
    period = tower.shaft_period_s or tower_period_guidelines(tower.height_m)
    source = message("lv1model.t1_measured" if tower.shaft_period_s else "lv1model.t1_assumed")
    support, _ = tower_support(tower)  # its assumption is in _church_demand_note
    results: list[TowerLV1] = []
    for across in (False, True):
        model = lv1_tower_model(tower, fc, knowledge_level, across=across)
        results.append(lv1_tower(model, conditions, period_s=period, support=support))
    worst = min(results, key=lambda r: (r.capacity.ag_g, r.capacity.safety_index))
    cap = worst.capacity
    notes = [
        message(
            "lv1model.model",
            t1=worst.period_s,
            source=source,
            q=worst.q,
            masonry=tower.masonry_type,
            strength=strength,
            shaft=shaft_description(tower),
            z=worst.critical.height_m,
        )
    ]
    if support is not None:
        notes.append(_church_demand_note(tower, support, worst.period_s))
    compression = _compression_note(worst, fc)
    if compression is not None:
        notes.append(compression)
    if cap.messages:
        notes.append(message("lv1model.capacity", notes=cap.messages))
    columns = {
        "lv1_capacity_ag_g": cap.ag_g,
        "lv1_safety_index": cap.safety_index,
        "lv1_acceleration_factor": cap.acceleration_factor,
        "lv1_period_s": worst.period_s,
        "lv1_compression_ratio": worst.critical.compression_ratio,
        "lv1_bound": cap.bound,
    }
    return columns, notes, []


def lv1_reason(context: CheckContext) -> Message | None:
    """Return why the registered ``shaft.lv1`` cannot be made (:func:`lv1_not_made_reason`)."""
    return lv1_not_made_reason(context.tower, context.knowledge_level)


def lv1_check(context: CheckContext) -> CheckOutput:
    """Return the LV1 check of a tower, the computation of the registered ``shaft.lv1``.

    :func:`lv1_columns`; an error of the tower's own data (off the NTC grid, a bad
    geometry) makes the check FAILED with its message (``not_made.lv1_error``), not fatal.
    """
    try:
        columns, notes, _ = lv1_columns(context.site, context.fc, context.knowledge_level)
    except RockscreenError as exc:  # off the NTC grid, a bad geometry: said, not fatal
        error = message("not_made.lv1_error", error=str(exc))
        failed = code_check("shaft.lv1").not_made(error, Status.FAILED)
        return CheckOutput(not_made=(failed,))
    return CheckOutput(columns, tuple(notes))


#: sigma_0 / (0.85 f_d) from which the LV1 note says that compression drives the result.
COMPRESSION_NOTE_FROM = 0.5


def _compression_note(result: TowerLV1, fc: float) -> Message | None:
    """Return the note on the weight's share of the critical section's strength, or None.

    The capacity of a solid shaft is ``q (b/H)(1 - sigma_0/(0.85 f_d)) g``
    (docs/code_checks.md §3): where the weight takes half the stress block or more, the
    masonry's design strength (the table's value at the knowledge level over gamma_M F_C),
    not the seismic demand, decides the verdict, and the user must read it so.
    """
    ratio = result.critical.compression_ratio
    if ratio < COMPRESSION_NOTE_FROM:
        return None
    z_m = result.critical.height_m
    if ratio >= 1.0:
        return message("lv1model.crushed", z_m=z_m, ratio=ratio, fc=fc)
    share = round(100.0 * ratio)
    return message(
        "lv1model.compression", share=share, z_m=z_m, ratio=ratio, fc=fc, rest=100 - share
    )


def _church_demand_note(tower: Tower, support: ElevatedSupport, period_s: float) -> Message:
    """Return the note saying which floor spectrum is the LV1 demand of a tower on a church."""
    given = tower.building_period_s is not None
    return message(
        "lv1model.church_demand",
        h_m=support.height_m,
        tk=support.period_s,
        period_source=message("lv1model.tk_given" if given else "lv1model.tk_assumed"),
        z_m=support.level_m,
        t1=period_s,
    )
