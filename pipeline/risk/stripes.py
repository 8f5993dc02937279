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
  the tower's axes (for the embedded synthetic suite as for a user suite);
- models (:func:`rockscreen.pipeline.screening.tower_models`): ``ground`` (single block on the
  component), ``floor`` (single block on the modal floor motion,
  :func:`rockscreen.pipeline.screening.floor_motion`) when the tower has building data, ``double``
  (tower on the sliding building, :func:`rockscreen.solver.solve_double_block`) when it has masses
  and friction;
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
  excitation (:func:`rockscreen.pipeline.screening.sample_uplift_factor`) exceeds 1 no sample
  reaches the uplift threshold, so the block stays at rest (status ``no_motion``,
  ``theta_max/alpha = 0``). For the double block the ground motion is checked: while the
  tower rests, the building's acceleration never exceeds the ground's in magnitude
  (sticking it equals it, sliding it is the friction force over the mass), so the tower
  cannot uplift; the building's sliding is not computed (status ``no_uplift``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from rockscreen import solver
from rockscreen.pipeline.screening import (
    MODELS,
    Solvers,
    floor_motion,
    sample_uplift_factor,
    solve_model,
    tower_models,
)
from rockscreen.solver.constants import G
from rockscreen.solver.errors import ParameterError

__all__ = ["DEFAULT_DAMAGE_LEVELS", "StripeOptions", "damage_column", "evaluate_stripe"]

#: Default damage levels of theta_max/alpha [-]: onset of rocking and the screening cut points.
DEFAULT_DAMAGE_LEVELS = (0.01, 0.2, 0.5)


@dataclass(frozen=True)
class StripeOptions:
    """What a stripe evaluation needs besides the tower and the records."""

    #: Models enabled (a subset of :data:`rockscreen.pipeline.screening.MODELS`).
    models: tuple[str, ...] = tuple(MODELS)
    #: theta_max/alpha levels counted per stripe [-].
    damage_levels: tuple[float, ...] = DEFAULT_DAMAGE_LEVELS
    #: Free motion followed after the record [s] (the solvers' ``max_free_time``).
    free_motion_s: float = 60.0


def damage_column(level: float) -> str:
    """Return the stripe column of a damage level: ``0.2`` -> ``"n_damage_0p2"``."""
    return "n_damage_" + f"{level:g}".replace(".", "p").replace("-", "m")


def _case(model, tower, block, acc, acc_v, dt, free) -> tuple[str, bool, float, bool]:
    """Return (status, overturned, theta_max/alpha, solved) of one case."""
    if sample_uplift_factor(acc, block.alpha, acc_v) * (1.0 - 1e-9) > 1.0:
        return ("no_uplift" if model == "double" else "no_motion"), False, 0.0, False
    try:
        response = solve_model(
            Solvers().resolved(),
            model,
            tower,
            block,
            acc,
            dt,
            acc_v=acc_v,
            history=False,
            max_free_time=free,
            friction_demand=False,
        )
    except ParameterError:  # the floor motion or a solver check: the model's limit
        return "vertical_limit", False, math.nan, False
    ratio = float(response.theta_max_over_alpha)
    return str(response.status), bool(response.overturned), ratio, True


def evaluate_stripe(
    tower: Any,
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
    blocks : dict, optional
        Cache width [m] -> :class:`rockscreen.solver.RockingBlock` shared between stripes.

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
    blocks = {} if blocks is None else blocks
    models = tower_models(tower, options.models)
    stripe: dict[str, Any] = {
        "tower_id": tower.id,
        "return_period_y": float(return_period_y),
        "ag_g": float(ag_g),
        "n_records": len(record_set.records),
        "n_overturned": 0,
        "n_vertical_limit": 0,
        **{f"n_overturned_{m}": 0 for m in MODELS},
        **{damage_column(level): 0 for level in options.damage_levels},
        "models": ",".join(models),
    }
    outcomes: list[dict[str, Any]] = []
    n_solves = 0
    for record, factor in zip(record_set.records, record_set.scale_factors, strict=True):
        factor = float(factor)
        acc_v = None if record.acc_z_m_s2 is None else record.acc_z_m_s2 * factor
        if acc_v is not None and len(acc_v) and float(np.min(acc_v)) <= -G:
            # The model's validity limit, for every case of this record: left out.
            stripe["n_vertical_limit"] += 1
            stripe["n_records"] -= 1
            outcomes.extend(
                _limit_rows(tower, return_period_y, record.name, factor, models, record)
            )
            continue
        components = [("X", record.acc_x_m_s2, float(tower.width_m))]
        if record.acc_y_m_s2 is not None:
            components.append(("Y", record.acc_y_m_s2, float(tower.plan_depth_m)))
        fell: set[str] = set()
        worst = 0.0
        for component, acc, width in components:
            acc = acc * factor
            if width not in blocks:
                blocks[width] = solver.RockingBlock.from_dimensions(
                    width, tower.height_m, eta=tower.eta
                )
            block = blocks[width]
            for model in models:
                excitation = floor_motion(tower, acc, record.dt_s) if model == "floor" else acc
                status, overturned, ratio, solved = _case(
                    model, tower, block, excitation, acc_v, record.dt_s, options.free_motion_s
                )
                n_solves += solved
                if overturned:
                    fell.add(model)
                worst = max(worst, ratio if not overturned else math.inf)
                outcomes.append(
                    {
                        "tower_id": tower.id,
                        "return_period_y": float(return_period_y),
                        "record": record.name,
                        "scale_factor": factor,
                        "component": component,
                        "model": model,
                        "status": status,
                        "overturned": overturned,
                        "theta_max_over_alpha": ratio,
                    }
                )
        stripe["n_overturned"] += bool(fell)
        for model in fell:
            stripe[f"n_overturned_{model}"] += 1
        for level in options.damage_levels:
            stripe[damage_column(level)] += worst >= level
    return stripe, outcomes, n_solves


def _limit_rows(tower, return_period_y, name, factor, models, record) -> list[dict[str, Any]]:
    """Outcome rows of a record left out at the vertical limit (every component and model)."""
    components = ["X"] + (["Y"] if record.acc_y_m_s2 is not None else [])
    return [
        {
            "tower_id": tower.id,
            "return_period_y": float(return_period_y),
            "record": name,
            "scale_factor": factor,
            "component": component,
            "model": model,
            "status": "vertical_limit",
            "overturned": False,
            "theta_max_over_alpha": math.nan,
        }
        for component in components
        for model in models
    ]


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
