"""The code's own checks of one tower in ``assess`` and the mechanism that governs (issue 22).

Per tower, in the worker, beside the IDA fragility of the whole tower
(:mod:`rockscreen.pipeline.risk.assess.tower_ida`):

- **kinematic checks** (:mod:`rockscreen.pipeline.risk.checks`, Circolare 2019 §C8.7.1
  *(subsection to be verified)*): the whole tower about the toe of its base
  (``tower_mechanisms.tower_kinematic_mechanism``; on a church, an elevated mechanism
  on the church), and,
  when the inventory has the belfry columns, the belfry about the toe at the top of the shaft
  (``tower_mechanisms.belfry_kinematic_mechanism``, an elevated mechanism on the shaft
  with the shaft's period); linear and non-linear, each one's capacity ``a_C`` (ag on
  rock) and ``I_S`` on the site's NTC hazard (:func:`kinematic_columns`);
- the **fragility of each part model** (a model of the registry with its own block: the
  belfry rocking on the shaft, the bell gable rocking on its base) from an IDA on that model
  alone (:func:`part_models`, :func:`part_fragility_columns`);
- when the inventory has the bell-gable columns, the **bell gable** (*vela*) overturning out
  of its plane about its base (``tower_mechanisms.gable_kinematic_mechanism``), an
  elevated mechanism on the structure beneath when its base is above the ground;
- the **LV1 model** of the Guidelines for towers when the inventory has the shaft's wall
  thickness and masonry type (:mod:`rockscreen.pipeline.risk.checks.tower_lv1_checks`);
- the **governing mechanism** (:func:`rockscreen.pipeline.risk.checks.governing.governing_columns`):
  the one of lowest capacity ``a_C``
  [g] among whole-tower rocking (the IDA SLV capacity), each part's rocking, shaft flexure
  (LV1) and the kinematic checks, linear and non-linear. Its ``I_S`` gives the class;
  ``checks_not_made`` lists the checks that could fail earlier and were not made, which
  :func:`rockscreen.pipeline.risk.measures.classes.class_label` shows beside a ``meets``, and
  ``completeness`` says it as a word (:class:`rockscreen.pipeline.verdict.scales.Completeness`).

Units: accelerations in g in names ending ``_g``; masses kg; lengths m.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from rockscreen.pipeline.archive.risk_schema import (
    KINEMATIC_PARTS,
    PART_SUFFIXES,
    part_model_names,
)
from rockscreen.pipeline.archive.schema import TEXT
from rockscreen.pipeline.engine.registry import CAMPAIGN, TowerModel, get, models
from rockscreen.pipeline.risk.assess.tower_ida import collapse_rate, fit_level
from rockscreen.pipeline.risk.checks.kinematic import (
    KinematicCheck,
    kinematic_check,
)
from rockscreen.pipeline.risk.checks.registry import CheckContext, CheckOutput
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.checks.tower_code_checks import empty_check_columns
from rockscreen.pipeline.risk.checks.tower_mechanisms import (
    WHOLE_TOWER,
    belfry_kinematic_mechanism,
    gable_kinematic_mechanism,
    tower_kinematic_mechanism,
    tower_support,
)
from rockscreen.pipeline.risk.measures.hazard_integral import HazardCurve, probability_in
from rockscreen.pipeline.risk.measures.lv1 import lv1_indices
from rockscreen.pipeline.verdict.messages import Message, catalogue, message
from rockscreen.stations.errors import RockscreenError
from rockscreen.stations.tower import Tower

__all__ = [
    "KINEMATIC_PARTS",
    "KINEMATIC_SUFFIXES",
    "PART_SUFFIXES",
    "checks_nan_columns",
    "kinematic_check_output",
    "kinematic_columns",
    "part_block_notes",
    "part_fragility_columns",
    "part_model_names",
    "part_models",
]

#: Columns of one kinematic mechanism, ``<prefix>kinematic_<suffix>`` (prefix ``""`` for
#: the governing mechanism, ``tower_``, ``belfry_``): suffix -> units (schema words).
KINEMATIC_SUFFIXES = {
    "alpha0": "1",  # load multiplier of activation [-]
    "e_star": "1",  # participating mass fraction [-]
    "a0_g": "g",  # spectral acceleration of activation a0* [g] (F_C included)
    "du_star_m": "m",  # d_SLV = 0.4 d0 [m] (Circolare 2019 §C8.7.1.2.1.6)
    "t_slv_s": "s",  # T_SLV = 1.68 pi sqrt(d_SLV / a(d_SLV)) [s] ([C8.7.1.10])
    "t0_s": "s",  # T0 of an element free to vibrate [s] (0: rigidly held)
    "linear_capacity_ag_g": "g",  # ag on rock at which the linear check holds at equality
    "nonlinear_capacity_ag_g": "g",
    "linear_safety_index": "1",
    "nonlinear_safety_index": "1",
    "safety_index": "1",  # the non-linear check's: the code's verdict (§C8.7.1.2.1.7)
    "linear_bound": "text",  # "", "lower" (holds at 2475 y), "upper" (fails at 30 y)
    "nonlinear_bound": "text",
    "bound": "text",  # the non-linear check's
}


def checks_nan_columns() -> dict[str, Any]:
    """Return the checks' columns of a summary row, empty (NaN, ``""``).

    Every registered code check's columns (:func:`rockscreen.pipeline.risk.checks.
    tower_code_checks.empty_check_columns`), each part model's after the kinematic
    checks', then the verdict's.
    """
    checks = empty_check_columns()  # every registered code check's, in compute order
    parts: dict[str, object] = {}
    for model in part_model_names():
        for suffix, units in PART_SUFFIXES.items():
            parts[f"{model}_{suffix}"] = "" if units == TEXT else math.nan
        parts[f"{model}_ida_n_solves"] = 0
    # each part model's columns after the kinematic checks' (as the archive schema places them)
    items = list(checks.items())
    at = list(checks).index("kinematic_mechanism") + 1 if "kinematic_mechanism" in checks else 0
    out: dict[str, Any] = dict(items[:at]) | parts | dict(items[at:])
    out.update(
        governing="",
        governing_kind="",
        governing_check="",
        governing_shown=False,
        governing_capacity_ag_g=math.nan,
        governing_safety_index=math.nan,
        governing_bound="",
        completeness="",
        checks_not_made="",
        checks_not_made_codes="",
        checks_disagree="",
    )
    return out


# ------------------------------------------------------------------------ mechanisms


def _check_columns(prefix: str, check: KinematicCheck) -> dict[str, Any]:
    cap, lin, nl = check.capacity, check.linear, check.nonlinear
    # rockscreen computes the capacity curve, so the non-linear check is the code's verdict:
    # the linear one "può essere utilizzato quando non viene calcolata la curva di capacità"
    # (Circolare 2019 §C8.7.1.2.1.7); it is reported beside.
    pick = nl
    return {
        f"{prefix}kinematic_alpha0": cap.alpha0,
        f"{prefix}kinematic_e_star": cap.mass_ratio,
        f"{prefix}kinematic_a0_g": cap.a0_star_g,
        f"{prefix}kinematic_du_star_m": cap.du_star_m,
        f"{prefix}kinematic_t_slv_s": cap.t_slv_s,
        f"{prefix}kinematic_t0_s": cap.t0_s,
        f"{prefix}kinematic_linear_capacity_ag_g": lin.ag_g,
        f"{prefix}kinematic_nonlinear_capacity_ag_g": nl.ag_g,
        f"{prefix}kinematic_linear_safety_index": lin.safety_index,
        f"{prefix}kinematic_nonlinear_safety_index": nl.safety_index,
        f"{prefix}kinematic_safety_index": pick.safety_index,
        f"{prefix}kinematic_linear_bound": lin.bound,
        f"{prefix}kinematic_nonlinear_bound": nl.bound,
        f"{prefix}kinematic_bound": pick.bound,
    }


def kinematic_columns(site: Any, fc: float) -> tuple[dict[str, Any], list[Message]]:
    """Return the kinematic checks' columns of a tower and the notes they bring.

    Parameters
    ----------
    site : rockscreen.pipeline.risk.assess.sites.TowerSite
        The tower and its site (located).
    fc : float
        Confidence factor F_C [-] (divides a0*).

    Returns
    -------
    columns : dict
        ``tower_kinematic_*``, ``belfry_kinematic_*`` (towers with belfry data),
        ``gable_kinematic_*`` (towers with bell-gable data) and
        ``kinematic_*`` (the governing kinematic mechanism's, named in
        ``kinematic_mechanism``).
    notes : list of Message
    """
    tower = site.tower
    conditions = SiteConditions.of(site)
    mechanism, notes = tower_kinematic_mechanism(tower)
    support, more = tower_support(tower)
    notes += [message("kinematic.of", part=WHOLE_TOWER, note=note) for note in more]
    checks = {"tower_": kinematic_check(mechanism, conditions, fc=fc, support=support)}
    if tower.has_belfry:
        belfry, shaft, more = belfry_kinematic_mechanism(tower)
        notes += more
        checks["belfry_"] = kinematic_check(belfry, conditions, fc=fc, support=shaft)
    if tower.has_gable:
        gable, beneath, more = gable_kinematic_mechanism(tower)
        notes += more
        checks["gable_"] = kinematic_check(gable, conditions, fc=fc, support=beneath)
    out: dict[str, Any] = {}
    for prefix, check in checks.items():
        out.update(_check_columns(prefix, check))
    worst = min(checks, key=lambda p: out[f"{p}kinematic_safety_index"])
    out.update(
        {f"kinematic_{suffix}": out[f"{worst}kinematic_{suffix}"] for suffix in KINEMATIC_SUFFIXES}
    )
    out["kinematic_mechanism"] = checks[worst].capacity.name
    notes.append(message("kinematic.checks"))
    return out, notes


def kinematic_check_output(context: CheckContext) -> CheckOutput:
    """Return the kinematic checks of a tower, the computation of the registered checks.

    The ``<part>.kinematic_nonlinear`` checks of
    :mod:`rockscreen.pipeline.risk.checks.registry` (the whole tower's names this function):
    :func:`kinematic_columns`; an error of the tower's own data (off the NTC grid, a bad
    geometry) is said in the note (``kinematic.not_made``), not fatal.
    """
    try:
        columns, notes = kinematic_columns(context.site, context.fc)
    except RockscreenError as exc:  # off the NTC grid, a bad geometry: said, not fatal
        return CheckOutput(notes=(message("kinematic.not_made", error=str(exc)),))
    return CheckOutput(columns, tuple(notes))


# ------------------------------------------------------------------------ part models


def part_models(tower: Tower, enabled: Sequence[str]) -> list[TowerModel]:
    """Return the enabled campaign models of ``tower`` that rock a part of it (own block)."""
    return [
        m
        for m in models(CAMPAIGN)
        if m.own_block is not None and m.name in enabled and m.available(tower)
    ]


def part_block_notes(tower: Tower, names: Sequence[str]) -> list[Message]:
    """Return what the part models ``names`` assume of ``tower``'s blocks, for the note.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
    names : sequence of str
        The part models' names (:func:`part_model_names`).

    Returns
    -------
    list of Message
        Each model's ``block_note`` (:class:`~rockscreen.pipeline.engine.registry.TowerModel`)
        that has something to say, in the order of ``names``.
    """
    notes = []
    for name in names:
        say = get(name).block_note
        note = say(tower) if say is not None else None
        if note is not None:
            notes.append(note)
    return notes


def part_fragility_columns(
    name: str,
    rows: Sequence[dict[str, Any]],
    curve: HazardCurve,
    tr_slv_y: float,
    ag_slv_g: float,
    fc: float,
) -> tuple[dict[str, Any], list[Message]]:
    """Return one part model's fragility columns from its own IDA rows.

    Parameters
    ----------
    name : str
        The model's name (the columns' prefix).
    rows : sequence of dict
        ``/ida``-like rows of the IDA on that model alone
        (:func:`rockscreen.pipeline.risk.assess.tower_ida.tower_ida`).
    curve : HazardCurve
        The site's hazard curve.
    tr_slv_y : float
        T_R,SLV [y].
    ag_slv_g : float
        ag on rock at T_R,SLV [g].
    fc : float
        F_C [-].

    Returns
    -------
    columns : dict
        ``<name>_fragility_median_g`` [g], ``_fragility_beta`` [-], ``_fragility_bound``,
        ``_p_overturning_50y`` [-], ``_slv_median_g`` [g], ``_capacity_ag_g`` [g],
        ``_safety_index`` [-], ``_ida_n_solves``.
    notes : list of Message
    """
    collapse, slv = fit_level(rows, "collapse"), fit_level(rows, "slv")
    rate = collapse_rate(curve, collapse)
    lv1 = lv1_indices(slv, curve, tr_slv_y, ag_slv_g, fc)
    p50 = probability_in(rate, 50.0) if math.isfinite(rate) else math.nan
    code = f"fit.part_{name}"
    part = message(code) if code in catalogue() else message("fit.part_other", part=name)
    notes = [message("fit.part", part=part, notes=collapse.messages)] if collapse.messages else []
    return {
        f"{name}_fragility_median_g": collapse.median_g,
        f"{name}_fragility_beta": collapse.beta,
        f"{name}_fragility_bound": collapse.bound,
        f"{name}_p_overturning_50y": p50,
        f"{name}_slv_median_g": slv.median_g,
        f"{name}_slv_bound": slv.bound,
        f"{name}_capacity_ag_g": lv1.capacity_pga_g,
        f"{name}_safety_index": lv1.safety_index,
        f"{name}_ida_n_solves": int(sum(int(r["n_solves"]) for r in rows)),
    }, notes


# ------------------------------------------------------------------------ governing
