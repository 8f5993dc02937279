"""Evaluation of one tower: every case, the governing case, the safety factor, the class.

Runs in the workers (:func:`run_chunk` is the executors' work function). The governing
case of a tower is the worst one: overturned first, then the largest ``theta_max/alpha``
(ties: the first in record, component, model order). The safety factor
(:func:`rockscreen.pipeline.screening.risk.safety_factor`) is searched on the governing case only.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from rockscreen.pipeline.config import CampaignConfig
from rockscreen.pipeline.engine.cases import BlockCache, Case, search_motion, solve_case
from rockscreen.pipeline.engine.loop import CaseFailure, motion_cases
from rockscreen.pipeline.engine.registry import available_models
from rockscreen.pipeline.engine.results import Failure, History, TowerOutcome
from rockscreen.pipeline.engine.search import (
    SafetyFactorResult,
    safety_factor,
    vertical_limit_factor,
)
from rockscreen.pipeline.engine.solvers import use_solvers
from rockscreen.pipeline.engine.uplift import sample_uplift_factor, uplift_free_factor
from rockscreen.pipeline.errors import RockscreenError
from rockscreen.pipeline.screening.cases import CampaignShared, TowerTask
from rockscreen.pipeline.screening.histories import decimate, kept_histories, severity
from rockscreen.pipeline.screening.risk import risk_class
from rockscreen.pipeline.verdict.messages import Message, message, note_columns
from rockscreen.pipeline.vocabulary import channel_id
from rockscreen.stations.tower import Tower


def _value(response: Any, name: str, default: float = math.nan) -> Any:
    value = getattr(response, name, default)
    return default if value is None else value


def _row(tower: Tower, case: Case) -> dict[str, Any]:
    r = case.response
    return {
        "tower_id": tower.id,
        "record_id": case.record_id,
        "component": case.component,
        "model": case.model.name,
        "status": str(r.status),
        "width_m": case.width,
        "alpha_rad": float(_value(r, "alpha")),
        "p_rad_s": float(_value(r, "p")),
        "eta": float(_value(r, "eta")),
        "pga_m_s2": float(np.max(np.abs(case.acc))) if len(case.acc) else 0.0,
        "theta_max_rad": float(_value(r, "theta_max")),
        "theta_max_over_alpha": float(_value(r, "theta_max_over_alpha")),
        "overturned": bool(r.overturned),
        "uplifted": bool(_value(r, "uplifted", False)),
        "slipped": bool(_value(r, "slipped", False)),
        "n_impacts": int(_value(r, "n_impacts", 0)),
        "t_overturn_s": float(_value(r, "t_overturn")),
        "slip_max_m": float(_value(r, "slip_max")),
        "slip_residual_m": float(_value(r, "slip_residual")),
        "friction_demand_max": float(_value(r, "friction_demand_max")),
    }


def evaluate_tower(task: TowerTask, shared: CampaignShared) -> TowerOutcome:
    """Run every case of one tower, find its governing case, safety factor and class.

    Parameters
    ----------
    task : TowerTask
    shared : CampaignShared
        Records, configuration and the solvers, active while the tower is evaluated
        (:func:`~rockscreen.pipeline.engine.solvers.use_solvers`).

    Returns
    -------
    TowerOutcome
    """
    with use_solvers(shared.solvers):
        return _evaluate(task, shared)


def _evaluate(task: TowerTask, shared: CampaignShared) -> TowerOutcome:
    """Evaluate one tower with the active solvers (:func:`evaluate_tower`)."""
    tower, config = task.tower, shared.config
    failures: list[Failure] = []
    cases: list[Case] = []
    blocks = BlockCache(tower)
    models = available_models(tower, config.models.run)
    for record_id in task.record_ids:
        for component in motion_cases(tower, shared.motions[record_id], models, blocks):
            for case in component.solve(record_id, config.models.free_motion_s):
                if isinstance(case, CaseFailure):
                    subject = f"{tower.id} / {record_id} / {case.component} / {case.model.name}"
                    error = f"{type(case.error).__name__}: {case.error}"
                    failures.append(Failure("solve", subject, error))
                else:
                    cases.append(case)
    rows = [_row(tower, case) for case in cases]
    stations = sorted({shared.motions[record_id].station for record_id in task.record_ids})
    flags = [
        message("run.record_flagged", record=record_id, flag=str(flag))
        for record_id in task.record_ids
        for flag in shared.motions[record_id].info.get("quality_flags", [])
    ]
    summary = _summarise(task, tower, config, cases, rows, failures, stations, flags)
    histories = []
    points = config.output.history_points if config.output.histories == "decimated" else None
    for i in kept_histories(rows, config.output.histories):
        case = cases[i]
        try:
            response = solve_case(tower, case, 1.0, history=True)
        except (RockscreenError, ValueError, ArithmeticError) as exc:  # pragma: no cover
            failures.append(Failure("solve", f"{tower.id} history", str(exc)))
            continue
        t, theta, u, regime = decimate(response, points)
        histories.append(
            History(
                tower.id,
                case.record_id,
                case.component,
                case.model.name,
                t,
                theta,
                u,
                regime,
                rows[i]["alpha_rad"],
            )
        )
    return TowerOutcome(task.index, tower.id, summary, rows, histories, failures)


def _summarise(
    task: TowerTask,
    tower: Tower,
    config: CampaignConfig,
    cases: list[Case],
    rows: list[dict[str, Any]],
    failures: list[Failure],
    stations: list[str],
    flags: list[Message],
) -> dict[str, Any]:
    summary: dict[str, Any] = {
        "id": tower.id,
        "name": tower.name or "",
        "lat_deg": math.nan if tower.lat is None else float(tower.lat),
        "lon_deg": math.nan if tower.lon is None else float(tower.lon),
        "stations": ",".join(stations),
        "n_records": len(task.record_ids),
        "n_cases": len(rows),
        "theta_max_over_alpha": math.nan,
        "theta_max_rad": math.nan,
        "alpha_rad": math.nan,
        "overturned": False,
        "safety_factor": math.nan,
        "safety_factor_lower": math.nan,
        "safety_factor_solves": 0,
        "risk_class": "unknown",
        "governing_record": "",
        "governing_model": "",
        "governing_component": "",
        "safety_factor_limit": "",
        "pairing": task.pairing,
        "pairing_distance_km": task.pairing_distance_km,
        **note_columns(()),
    }
    if not rows:
        summary.update(note_columns([message("run.no_case_solved"), *flags]))
        return summary
    governing = max(range(len(rows)), key=lambda i: severity(rows[i]))
    row, case = rows[governing], cases[governing]
    summary.update(
        theta_max_over_alpha=row["theta_max_over_alpha"],
        theta_max_rad=row["theta_max_rad"],
        alpha_rad=row["alpha_rad"],
        overturned=any(r["overturned"] for r in rows),
        governing_record=channel_id(case.record_id, case.component),
        governing_model=case.model.name,
        governing_component=case.component,
    )
    sf_config = config.safety_factor
    if sf_config.enabled:
        try:
            result, limit = _search_safety_factor(tower, case, row["alpha_rad"], config)
        except (RockscreenError, ValueError, ArithmeticError) as exc:
            failures.append(Failure("solve", f"{tower.id} safety factor", str(exc)))
        else:
            summary.update(
                safety_factor=result.factor,
                safety_factor_lower=result.lower,
                safety_factor_solves=result.n_solves,
                safety_factor_limit=limit,
            )
    risk = config.risk
    summary["risk_class"] = risk_class(
        summary["theta_max_over_alpha"],
        summary["overturned"],
        summary["safety_factor"],
        rocking_from=risk.rocking_from,
        moderate_from=risk.moderate_from,
        high_from=risk.high_from,
        sf_high_below=risk.sf_high_below,
        sf_moderate_below=risk.sf_moderate_below,
    )
    summary.update(note_columns(summary_note(summary, flags)))
    return summary


def summary_note(summary: dict[str, Any], flags: Sequence[Message] = ()) -> list[Message]:
    """Return the messages that explain a summary row's verdict to its reader.

    Parameters
    ----------
    summary : dict
        The summary row (safety factor, its limit, pairing, ...).
    flags : sequence of Message
        Quality flags of the tower's records (kept records that a check found doubtful).

    Returns
    -------
    list of Message
        Codes of :mod:`rockscreen.pipeline.verdict.catalogue.screening`.
    """
    sf, limit = summary["safety_factor"], summary["safety_factor_limit"]
    notes = list(flags)
    if limit == "vertical_limit":
        notes.append(message("run.sf_vertical_limit", sf=summary["safety_factor_lower"]))
    elif limit == "cap":
        notes.append(message("run.sf_cap", sf=summary["safety_factor_lower"]))
    elif limit == "overturning" and sf < 1.0 and not summary["overturned"]:
        notes.append(message("run.sf_not_monotone", sf=sf))
    if summary["pairing"].startswith("every station"):
        # paired with every station (stations.pairing): the tower, or every station, unlocated
        unlocated = math.isnan(summary["lat_deg"]) or math.isnan(summary["lon_deg"])
        notes.append(
            message(
                "run.every_station_tower_unlocated"
                if unlocated
                else "run.every_station_stations_unlocated"
            )
        )
    return notes


def _search_safety_factor(
    tower: Tower, case: Case, alpha: float, config: CampaignConfig
) -> tuple[Any, str]:
    """Search the governing case's safety factor; return it and the limit that ended it."""
    sf = config.safety_factor
    vertical = vertical_limit_factor(case.acc_v)
    # Stop just below the vertical limit, where the model still holds.
    cap = min(sf.cap, vertical * (1.0 - 1e-9))
    limit_if_safe = "vertical_limit" if vertical <= sf.cap else "cap"
    # Below the uplift-free factor nothing moves, so the scan may start there.
    start = max(sf.start, uplift_free_factor(case.acc, alpha, case.acc_v))
    if start >= cap:
        return SafetyFactorResult(math.inf, cap, 0), limit_if_safe

    # Below this factor no sample reaches the uplift threshold: safe without a solve
    # (the small margin keeps the kernel's own rounding of the threshold test out).
    still = sample_uplift_factor(case.acc, alpha, case.acc_v) * (1.0 - 1e-9)
    motion = search_motion(case)
    solves = 0

    def overturns(factor: float) -> bool:
        nonlocal solves
        if factor == 1.0 and case.response is not None:
            # 1 is on every scan grid: the case itself was solved at that factor already.
            return bool(case.response.overturned)
        if factor < still:
            return False
        solves += 1
        return bool(solve_case(tower, case, factor, False, motion).overturned)

    result = safety_factor(overturns, start=start, ratio=sf.ratio, cap=cap, tolerance=sf.tolerance)
    limit = "overturning" if math.isfinite(result.factor) else limit_if_safe
    # The archive counts the solver calls the search made, not the verdicts it used.
    return dataclasses.replace(result, n_solves=solves), limit


def run_chunk(shared: CampaignShared, chunk: Sequence[TowerTask]) -> list[TowerOutcome]:
    """Evaluate the towers of one chunk (the executors' work function).

    Parameters
    ----------
    shared : CampaignShared
    chunk : sequence of TowerTask

    Returns
    -------
    list of TowerOutcome
    """
    resolved = CampaignShared(shared.motions, shared.config, shared.solvers.resolved())
    return [evaluate_tower(task, resolved) for task in chunk]
