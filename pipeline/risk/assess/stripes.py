"""The multiple-stripe evaluation of one tower: records x components x models per stripe.

A stripe is one return period ``TR`` of the site: the spectrum-compatible record set of the
site at that ``TR`` (:func:`rockscreen.pipeline.hazard.site_record_set`), each record scaled by its
factor, at the intensity ``ag(TR)`` [g] of the site on rock (Jalayer & Cornell 2009,
multiple-stripe analysis).

Per record, the cases are its two horizontal components times the tower's models:

- components: ``X`` = the record's ``x`` along the tower's x axis (block width
  ``width_m``), ``Y`` = its ``y`` along the tower's y axis (plan depth). A suite record
  carries no orientation and a hypothetical future record has no relation to the site's
  geography, so the tower's azimuth is not used: the records' ``x``/``y`` are taken as
  the tower's axes (for the embedded suites as for a user suite);
- models (the registry's campaign models the tower's data allow,
  :func:`rockscreen.pipeline.engine.registry.available_models`): ``ground`` (single block
  on the component), ``floor`` (single block on the modal floor motion,
  :func:`rockscreen.pipeline.engine.models.floor.floor_motion`) when the tower has
  building data, ``double`` (tower on the sliding building,
  :func:`rockscreen.solver.solve_double_block`) when it has masses and friction;
- the vertical component, when the record has one, is the ``acc_v`` of every case.

Rules:

- **a record overturns the tower** when any of its cases overturns (either component,
  any model): the tower is lost if it falls in either direction, whatever the model that
  predicts it. The per-model counts (``n_overturned_<model>``) use the cases of that model.
  A scaled record whose vertical reaches -g (the base would fall away; the rigid-block
  model no longer holds, status ``vertical_limit``) is **left out of the stripe**: a limit
  of the model is never counted as a failure of the tower (nor as a survival); the stripe
  counts it in ``n_vertical_limit`` and its ``n_records`` holds the records that count;
- **damage level** ``d`` (normalised peak rotation ``theta_max/alpha``, D'Angela et al.
  2026): a record exceeds it when any case has ``theta_max/alpha >= d`` or overturns;
- **motionless cases are not solved**: when the per-sample uplift factor of the scaled
  excitation (:func:`rockscreen.pipeline.engine.uplift.sample_uplift_factor`) exceeds 1 no sample
  reaches the uplift threshold, so the block stays at rest (status ``no_motion``,
  ``theta_max/alpha = 0``). For the double block the ground motion is checked: while the
  tower rests, the building's acceleration never exceeds the ground's in magnitude
  (sticking it equals it, sliding it is the friction force over the mass), so the tower
  cannot uplift; the building's sliding is not computed (status ``no_uplift``).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rockscreen.pipeline.engine.cases import BlockCache
from rockscreen.pipeline.engine.loop import motion_cases
from rockscreen.pipeline.engine.motion import GroundMotion
from rockscreen.pipeline.engine.registry import available_models, model_names
from rockscreen.stations.tower import Tower

__all__ = ["DEFAULT_DAMAGE_LEVELS", "StripeOptions", "damage_column", "evaluate_stripe"]

#: Default damage levels of theta_max/alpha [-]: onset of rocking and the screening cut points.
DEFAULT_DAMAGE_LEVELS = (0.01, 0.2, 0.5)


@dataclass(frozen=True)
class StripeOptions:
    """What a stripe evaluation needs besides the tower and the records."""

    #: Models enabled (names of the campaign models of the registry; default all).
    models: tuple[str, ...] = field(default_factory=model_names)
    #: theta_max/alpha levels counted per stripe [-].
    damage_levels: tuple[float, ...] = DEFAULT_DAMAGE_LEVELS
    #: Free motion followed after the record [s] (the solvers' ``max_free_time``).
    free_motion_s: float = 60.0
    #: Stop each solve's free motion once its verdict is certain (energy argument,
    #: ``docs/theory.md``; :func:`rockscreen.pipeline.engine.cases.screen_case`); False is
    #: the reference path that follows it to rest (the same verdicts, slower).
    early_stop: bool = True


def damage_column(level: float) -> str:
    """Return the stripe column of a damage level: ``0.2`` -> ``"n_damage_0p2"``."""
    return "n_damage_" + f"{level:g}".replace(".", "p").replace("-", "m")


def evaluate_stripe(
    tower: Tower,
    record_set: Any,
    return_period_y: float,
    ag_g: float,
    options: StripeOptions,
    blocks: dict[float, Any] | None = None,
) -> tuple[dict[str, Any], list[dict[str, Any]], int]:
    """Evaluate a tower under every record of one stripe.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
    record_set : rockscreen.pipeline.hazard.RecordSet
        The site's record set at ``return_period_y`` (records and scale factors).
    return_period_y : float
        The stripe's return period [y].
    ag_g : float
        The stripe's intensity: the site's ag on rock at ``return_period_y`` [g].
    options : StripeOptions
    blocks : rockscreen.pipeline.engine.cases.BlockCache, optional
        The tower's blocks by width and axis, shared between its stripes.

    Returns
    -------
    stripe : dict
        ``tower_id``, ``return_period_y`` [y], ``ag_g`` [g], ``n_records``,
        ``n_overturned``, ``n_overturned_<model>`` for every model, ``n_damage_<level>``,
        ``models`` (the models that ran, comma-separated).
    outcomes : list of dict
        One row per record x component x model: ``tower_id``, ``return_period_y``,
        ``record``, ``scale_factor``, ``component``, ``model``, ``status``,
        ``overturned``, ``theta_max_over_alpha`` (NaN for ``vertical_limit``).
    n_solves : int
        Solver calls made (the motionless cases are not solved).
    """
    blocks = BlockCache(tower) if blocks is None else blocks
    models = available_models(tower, options.models)
    stripe: dict[str, Any] = {
        "tower_id": tower.id,
        "return_period_y": float(return_period_y),
        "ag_g": float(ag_g),
        "n_records": len(record_set.records),
        "n_overturned": 0,
        "n_vertical_limit": 0,
        **{f"n_overturned_{m}": 0 for m in model_names()},
        **{damage_column(level): 0 for level in options.damage_levels},
        "models": ",".join(m.name for m in models),
    }
    outcomes: list[dict[str, Any]] = []
    n_solves = 0
    for record, factor in zip(record_set.records, record_set.scale_factors, strict=True):
        factor = float(factor)
        motion = suite_motion(record, factor)
        verdicts = [
            component.screen(free_motion_s=options.free_motion_s, early_stop=options.early_stop)
            for component in motion_cases(tower, motion, models, blocks)
        ]
        outcomes.extend(
            {
                "tower_id": tower.id,
                "return_period_y": float(return_period_y),
                "record": record.name,
                "scale_factor": factor,
                "component": v.component,
                "model": case.model.name,
                "status": case.verdict.status,
                "overturned": case.verdict.overturned,
                "theta_max_over_alpha": case.verdict.theta_max_over_alpha,
            }
            for v in verdicts
            for case in v.cases
        )
        n_solves += sum(v.n_solves for v in verdicts)
        if any(v.vertical_limit for v in verdicts):
            # The model's validity limit, for every case of this record: left out.
            stripe["n_vertical_limit"] += 1
            stripe["n_records"] -= 1
            continue
        fell = frozenset().union(*(v.overturned_models for v in verdicts))
        worst = max((v.worst for v in verdicts), default=0.0)
        stripe["n_overturned"] += bool(fell)
        for name in fell:
            stripe[f"n_overturned_{name}"] += 1
        for level in options.damage_levels:
            stripe[damage_column(level)] += worst >= level
    return stripe, outcomes, n_solves


def suite_motion(record: Any, factor: float) -> GroundMotion:
    """Return a suite record scaled by ``factor`` as a motion along the tower's axes.

    A suite record carries no orientation and a hypothetical future record has no relation
    to the site's geography: its ``x``/``y`` are taken as the tower's axes.

    Parameters
    ----------
    record : rockscreen.pipeline.hazard.SuiteRecord
        ``acc_x_m_s2``, ``acc_y_m_s2`` (or None), ``acc_z_m_s2`` (or None) [m/s²], ``dt_s`` [s].
    factor : float
        Amplitude scale factor [-].
    """
    y, z = record.acc_y_m_s2, record.acc_z_m_s2
    return GroundMotion.along_tower_axes(
        record.name,
        record.acc_x_m_s2 * factor,
        None if y is None else y * factor,
        None if z is None else z * factor,
        record.dt_s,
    )


def stripe_arrays(stripes: Sequence[dict[str, Any]]) -> tuple[np.ndarray, ...]:
    """Return (ag_g [g], n_records, n_overturned) of a tower's stripes, sorted by ag.

    Stripes left without a counting record (every record at the vertical limit) are dropped.
    """
    stripes = [s for s in stripes if s["n_records"] > 0]
    order = np.argsort([s["ag_g"] for s in stripes])
    ag = np.array([stripes[i]["ag_g"] for i in order], dtype=float)
    n = np.array([stripes[i]["n_records"] for i in order], dtype=float)
    k = np.array([stripes[i]["n_overturned"] for i in order], dtype=float)
    return ag, n, k
