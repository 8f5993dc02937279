"""The screening campaign: towers x paired records x components x models -> archive.

Flow (docs/campaign.md):

1. :func:`prepare_records` reads every record file, processes each trace and groups
   traces into records; unreadable or unprocessable files are failures, not errors.
2. :func:`pair` pairs towers with the stations of the records
   (:mod:`stations.pairing`); unpaired towers are failures.
3. :func:`run_campaign` splits the paired towers into chunks of tower tasks, has an
   executor (:mod:`pipeline.execution.local`) compute them, and writes each chunk's results
   to the archive (:mod:`pipeline.archive.campaign`) from this process only.

Per tower (:func:`evaluate_tower`, run in the workers), for each paired record and
each horizontal component:

- components: rotated to the tower's axes when its azimuth and the channel azimuths
  are known (component ``X`` along the azimuth with the tower's ``width_m``, ``Y``
  90 deg clockwise from it with its plan depth); otherwise each recorded horizontal as
  is, with the tower's smaller plan dimension (the more slender direction: the
  conservative choice when the orientation is unknown);
- models: ``ground`` (single block on the component), ``floor`` (single block on the
  modal floor accelerogram at the tower's springing, for towers with building data),
  ``double`` (tower rocking on the building sliding on its foundation, for towers
  with masses and friction coefficients);
- the vertical component, when recorded, is the ``acc_v`` of every model (the
  building is taken as rigid vertically).

The governing case of a tower is the worst one: overturned first, then the largest
``theta_max/alpha`` (ties: the first in record, component, model order). The safety
factor (:func:`pipeline.screening.risk.safety_factor`) is searched on the governing case only.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import os
import signal
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from pipeline.config import MODELS, CampaignConfig
from pipeline.errors import RockscreenError
from pipeline.screening.risk import (
    risk_class,
    safety_factor,
    sample_uplift_factor,
    uplift_free_factor,
)

#: Environment variable of the crash-safety tests: SIGKILL the run after this many chunks.
ABORT_AFTER_CHUNKS_ENV = "ROCKSCREEN_TEST_ABORT_AFTER_CHUNKS"

#: Columns of the results table: name -> (kind, units). Kinds: "str", "f8", "i8", "bool".
RESULT_COLUMNS: dict[str, tuple[str, str]] = {
    "tower_id": ("str", ""),
    "record_id": ("str", ""),
    "component": ("str", ""),
    "model": ("str", ""),
    "status": ("str", ""),
    "width_m": ("f8", "m"),
    "alpha_rad": ("f8", "rad"),
    "p_rad_s": ("f8", "rad/s"),
    "eta": ("f8", "1"),
    "pga_m_s2": ("f8", "m/s**2"),
    "theta_max_rad": ("f8", "rad"),
    "theta_max_over_alpha": ("f8", "1"),
    "overturned": ("bool", ""),
    "uplifted": ("bool", ""),
    "slipped": ("bool", ""),
    "n_impacts": ("i8", "1"),
    "t_overturn_s": ("f8", "s"),
    "slip_max_m": ("f8", "m"),
    "slip_residual_m": ("f8", "m"),
    "friction_demand_max": ("f8", "1"),
}

#: Columns of the per-tower summary table: name -> (kind, units).
SUMMARY_COLUMNS: dict[str, tuple[str, str]] = {
    "id": ("str", ""),
    "name": ("str", ""),
    "lat": ("f8", "deg"),
    "lon": ("f8", "deg"),
    "stations": ("str", ""),
    "n_records": ("i8", "1"),
    "n_cases": ("i8", "1"),
    "theta_max_over_alpha": ("f8", "1"),
    "theta_max_rad": ("f8", "rad"),
    "alpha_rad": ("f8", "rad"),
    "overturned": ("bool", ""),
    "safety_factor": ("f8", "1"),
    "safety_factor_lower": ("f8", "1"),
    "safety_factor_solves": ("i8", "1"),
    "risk_class": ("str", ""),
    "governing_record": ("str", ""),
    "governing_model": ("str", ""),
    "governing_component": ("str", ""),
}

#: Columns of the failures table.
FAILURE_COLUMNS: dict[str, tuple[str, str]] = {
    "kind": ("str", ""),
    "subject": ("str", ""),
    "reason": ("str", ""),
}


@dataclass(frozen=True)
class Failure:
    """Something that could not be read, processed, paired or solved.

    Attributes
    ----------
    kind : str
        ``"read"``, ``"process"``, ``"pair"`` or ``"solve"``.
    subject : str
        The file, record, tower or case concerned.
    reason : str
        One line a user reads.
    """

    kind: str
    subject: str
    reason: str

    def as_row(self) -> dict[str, str]:
        """Return the failure as a row of the failures table."""
        return {"kind": self.kind, "subject": self.subject, "reason": self.reason}


@dataclass(frozen=True)
class Motion:
    """One processed record, as a worker needs it (plain arrays, cheap to pickle).

    Attributes
    ----------
    record_id : str
        ``"NET.STA.LOC.CHA-prefix"``, e.g. ``"IT.AQV..HN"``.
    station : str
        ``"NET.STA"``.
    dt : float
        Sampling step [s].
    channels : tuple of str
        Horizontal channel codes, e.g. ``("HNN", "HNE")``.
    info : dict
        Archive attributes: files, formats, starttime, provenance, vertical channel.
    horizontals : tuple of numpy.ndarray
        Horizontal accelerations [m/s²], one per channel, equal lengths.
    azimuths : tuple of float or None
        Channel azimuths, clockwise from north [deg]; None when unknown.
    vertical : numpy.ndarray or None
        Vertical acceleration [m/s²], positive up.
    latitude, longitude : float or None
        Station coordinates [deg].
    """

    record_id: str
    station: str
    dt: float
    channels: tuple[str, ...]
    horizontals: tuple[np.ndarray, ...]
    azimuths: tuple[float | None, ...]
    vertical: np.ndarray | None = None
    latitude: float | None = None
    longitude: float | None = None
    info: dict[str, Any] = field(default_factory=dict)

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


@dataclass(frozen=True)
class TowerTask:
    """One tower and the records it is screened against.

    Attributes
    ----------
    index : int
        Position of the tower in the inventory (orders the archive tables).
    tower : stations.inventory.Tower
    record_ids : tuple of str
    """

    index: int
    tower: Any
    record_ids: tuple[str, ...]


@dataclass
class History:
    """A (possibly decimated) time history of one case.

    Attributes
    ----------
    tower_id, record_id, component, model : str
    t : numpy.ndarray
        Times [s].
    theta : numpy.ndarray
        Tower rotation [rad].
    u : numpy.ndarray
        Building slip relative to the ground [m] (zeros for single-block models).
    regime : numpy.ndarray
        0 rest, 1 tower rocking, 2 building sliding, 3 both.
    alpha : float
        Slenderness angle of the block [rad].
    """

    tower_id: str
    record_id: str
    component: str
    model: str
    t: np.ndarray
    theta: np.ndarray
    u: np.ndarray
    regime: np.ndarray
    alpha: float


@dataclass
class TowerOutcome:
    """Everything a worker computed for one tower."""

    index: int
    tower_id: str
    summary: dict[str, Any]
    rows: list[dict[str, Any]]
    histories: list[History]
    failures: list[Failure]


@dataclass(frozen=True)
class Solvers:
    """The functions a campaign calls; None = the real ones from :mod:`solver`.

    Unit tests of the orchestration may pass small pure-Python stand-ins.
    """

    block: Callable[..., Any] | None = None
    rocking: Callable[..., Any] | None = None
    double: Callable[..., Any] | None = None
    floor: Callable[..., Any] | None = None

    def resolved(self) -> Solvers:
        """Return a copy with every None replaced by the real function."""
        if None not in (self.block, self.rocking, self.double, self.floor):
            return self
        import solver
        from pipeline.motion.floor import modal_floor_accelerogram

        return Solvers(
            block=self.block or solver.RockingBlock.from_dimensions,
            rocking=self.rocking or solver.solve_rocking,
            double=self.double or solver.solve_double_block,
            floor=self.floor or modal_floor_accelerogram,
        )


@dataclass(frozen=True)
class CampaignShared:
    """What every worker needs, shipped once per worker."""

    motions: dict[str, Motion]
    config: CampaignConfig
    solvers: Solvers = Solvers()


# --------------------------------------------------------------------------- components


def tower_components(tower: Any, motion: Motion) -> list[tuple[str, np.ndarray, float]]:
    """Return the horizontal components a tower is checked against.

    Parameters
    ----------
    tower : stations.inventory.Tower
    motion : Motion

    Returns
    -------
    list of (str, numpy.ndarray, float)
        ``(component, acceleration [m/s²], block width in that direction [m])``.
        Rotated (``"X"``, ``"Y"``) when the tower's azimuth and the channel azimuths are
        known; otherwise the recorded channels' last letters with the smaller plan
        dimension.
    """
    if tower.azimuth_deg is not None and motion.can_rotate:
        from pipeline.records.grouping import rotate_horizontals

        x, y = rotate_horizontals(*motion.horizontals, *motion.azimuths, tower.azimuth_deg)
        return [("X", x, float(tower.width_m)), ("Y", y, float(tower.plan_depth_m))]
    width = float(min(tower.width_m, tower.plan_depth_m))
    return [(motion.label(i), acc, width) for i, acc in enumerate(motion.horizontals)]


def tower_models(tower: Any, enabled: Sequence[str]) -> list[str]:
    """Return the models that run for a tower: enabled ones its data allow."""
    allowed = {
        "ground": True,
        "floor": bool(tower.has_floor_model),
        "double": bool(tower.has_double_block),
    }
    return [model for model in MODELS if model in enabled and allowed[model]]


# --------------------------------------------------------------------------- one tower


@dataclass
class _Case:
    record_id: str
    component: str
    model: str
    width: float
    acc: np.ndarray
    acc_v: np.ndarray | None
    dt: float
    block: Any
    free_motion_s: float
    response: Any = None


def floor_motion(
    tower: Any, acc: np.ndarray, dt: float, solvers: Solvers | None = None
) -> np.ndarray:
    """Return the floor acceleration at the tower's springing [m/s²].

    First mode of the building, linear mode shape z/H (``docs/floor_motion.md``).

    Parameters
    ----------
    tower : stations.inventory.Tower
        A tower with floor-model data (``has_floor_model``).
    acc : numpy.ndarray
        Ground acceleration [m/s²] at step ``dt``.
    dt : float
        Sampling step [s].
    solvers : Solvers, optional
        Stand-in functions for tests; default the real ones.
    """
    solvers = (solvers or Solvers()).resolved()
    from pipeline.motion.floor import building_period_from_height

    period = tower.building_period_s
    if period is None:
        period = building_period_from_height(tower.building_height_m)
    base = tower.base_height_m if tower.base_height_m is not None else tower.building_height_m
    motion = solvers.floor(
        acc, dt, building_period=period, mode_shape_at_base=base / tower.building_height_m
    )
    return np.asarray(motion, dtype=float)


def _solve(
    solvers: Solvers, tower: Any, case: _Case, factor: float, history: bool, motion: Any = None
) -> Any:
    """Solve ``case`` with its records scaled by ``factor``.

    ``motion`` (a :class:`solver.rocking.BaseMotion` of the case's records, real solvers
    only) makes the solver scale the checked record itself instead of receiving a
    multiplied copy to check again, and skips the friction demand (NaN): the
    safety-factor search uses only the overturning verdict.
    """
    if motion is not None:
        acc, acc_v = motion, None
        extra: dict[str, Any] = {"scale": factor, "friction_demand": False}
    else:
        acc = case.acc if factor == 1.0 else case.acc * factor
        acc_v = None
        if case.acc_v is not None:
            acc_v = case.acc_v if factor == 1.0 else case.acc_v * factor
        extra = {}
    if case.model == "double":
        return solvers.double(
            case.block,
            acc,
            case.dt,
            tower_mass=tower.tower_mass_kg,
            building_mass=tower.building_mass_kg,
            mu_s=tower.mu_s,
            mu_k=tower.mu_k,
            acc_v=acc_v,
            history=history,
            max_free_time=case.free_motion_s,
            **extra,
        )
    return solvers.rocking(
        case.block,
        acc,
        case.dt,
        acc_v=acc_v,
        history=history,
        max_free_time=case.free_motion_s,
        **extra,
    )


def _search_motion(solvers: Solvers, case: _Case) -> Any:
    """Return the case's records checked once for the search, or None for stand-in solvers."""
    import solver
    from solver.rocking import base_motion

    if solvers.rocking is solver.solve_rocking and solvers.double is solver.solve_double_block:
        return base_motion(case.acc, case.dt, case.acc_v)
    return None


def _value(response: Any, name: str, default: float = math.nan) -> Any:
    value = getattr(response, name, default)
    return default if value is None else value


def _row(tower: Any, case: _Case) -> dict[str, Any]:
    r = case.response
    return {
        "tower_id": tower.id,
        "record_id": case.record_id,
        "component": case.component,
        "model": case.model,
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


def severity(row: dict[str, Any]) -> tuple[bool, float]:
    """Return the ordering key of a case: overturned first, then theta_max/alpha."""
    ratio = row["theta_max_over_alpha"]
    return (bool(row["overturned"]), -math.inf if math.isnan(ratio) else float(ratio))


def _decimate(response: Any, points: int | None) -> tuple[np.ndarray, ...]:
    """Return (t, theta, u, regime), peak-preserving decimation to <= ``points`` samples.

    The points go to the motion window (from the sample before the first motion to the
    sample after the last), plus the record's first and last samples: a tower rocks for
    seconds of a record that may last minutes. Inside the window each bin of
    ``ceil(n / (points - 2))`` samples keeps the sample of largest ``|theta|``, so the
    plotted peaks equal the true ones.
    """
    t = np.asarray(response.t, dtype=float)
    theta = np.asarray(response.theta, dtype=float)
    u = getattr(response, "u", None)
    u = np.zeros_like(theta) if u is None else np.asarray(u, dtype=float)
    regime = getattr(response, "regime", None)
    regime = np.zeros(len(theta), dtype=np.int8) if regime is None else np.asarray(regime)
    if points is not None and len(theta) > points:
        keep = _decimated_indices(theta, regime, points)
        t, theta, u, regime = t[keep], theta[keep], u[keep], regime[keep]
    return (
        t.astype(np.float32),
        theta.astype(np.float32),
        u.astype(np.float32),
        regime.astype(np.int8),
    )


def _decimated_indices(theta: np.ndarray, regime: np.ndarray, points: int) -> np.ndarray:
    """Return at most ``points`` sample indices: the ends plus the peak-binned motion window."""
    n = len(theta)
    active = np.flatnonzero((theta != 0.0) | (regime != 0))
    if active.size == 0:
        return np.array([0, n - 1])
    lo, hi = max(active[0] - 1, 0), min(active[-1] + 1, n - 1)
    window = np.abs(theta[lo : hi + 1])
    step = math.ceil(window.size / max(points - 2, 1))
    n_bins = math.ceil(window.size / step)
    padded = np.full(n_bins * step, -1.0)
    padded[: window.size] = window
    peaks = lo + np.arange(n_bins) * step + np.argmax(padded.reshape(n_bins, step), axis=1)
    return np.unique(np.concatenate(([0], peaks, [n - 1])))


def _kept_histories(rows: list[dict[str, Any]], mode: str) -> list[int]:
    """Return the indices of the cases whose history the archive keeps."""
    if mode == "none" or not rows:
        return []
    if mode == "full":
        return list(range(len(rows)))
    worst: dict[tuple[str, str], int] = {}
    for i, row in enumerate(rows):
        key = (row["record_id"], row["model"])
        if key not in worst or severity(row) > severity(rows[worst[key]]):
            worst[key] = i
    return sorted(worst.values())


def evaluate_tower(task: TowerTask, shared: CampaignShared) -> TowerOutcome:
    """Run every case of one tower, find its governing case, safety factor and class.

    Parameters
    ----------
    task : TowerTask
    shared : CampaignShared
        Records, configuration and (resolved) solvers.

    Returns
    -------
    TowerOutcome
    """
    tower, config, solvers = task.tower, shared.config, shared.solvers
    failures: list[Failure] = []
    cases: list[_Case] = []
    blocks: dict[float, Any] = {}
    models = tower_models(tower, config.models.run)
    for record_id in task.record_ids:
        motion = shared.motions[record_id]
        for component, acc, width in tower_components(tower, motion):
            if width not in blocks:
                blocks[width] = solvers.block(width, tower.height_m, eta=tower.eta)
            for model in models:
                subject = f"{tower.id} / {record_id} / {component} / {model}"
                try:
                    excitation = acc
                    if model == "floor":
                        excitation = floor_motion(tower, acc, motion.dt, solvers)
                    case = _Case(
                        record_id,
                        component,
                        model,
                        width,
                        excitation,
                        motion.vertical,
                        motion.dt,
                        blocks[width],
                        config.models.free_motion_s,
                    )
                    case.response = _solve(solvers, tower, case, 1.0, history=False)
                except (RockscreenError, ValueError, ArithmeticError) as exc:
                    failures.append(Failure("solve", subject, f"{type(exc).__name__}: {exc}"))
                    continue
                cases.append(case)
    rows = [_row(tower, case) for case in cases]
    stations = sorted({shared.motions[record_id].station for record_id in task.record_ids})
    summary = _summarise(task, tower, config, solvers, cases, rows, failures, stations)
    histories = []
    points = config.output.history_points if config.output.histories == "decimated" else None
    for i in _kept_histories(rows, config.output.histories):
        case = cases[i]
        try:
            response = _solve(solvers, tower, case, 1.0, history=True)
        except (RockscreenError, ValueError, ArithmeticError) as exc:  # pragma: no cover
            failures.append(Failure("solve", f"{tower.id} history", str(exc)))
            continue
        t, theta, u, regime = _decimate(response, points)
        histories.append(
            History(
                tower.id,
                case.record_id,
                case.component,
                case.model,
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
    tower: Any,
    config: CampaignConfig,
    solvers: Solvers,
    cases: list[_Case],
    rows: list[dict[str, Any]],
    failures: list[Failure],
    stations: list[str],
) -> dict[str, Any]:
    summary: dict[str, Any] = {
        "id": tower.id,
        "name": tower.name or "",
        "lat": math.nan if tower.lat is None else float(tower.lat),
        "lon": math.nan if tower.lon is None else float(tower.lon),
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
    }
    if not rows:
        return summary
    governing = max(range(len(rows)), key=lambda i: severity(rows[i]))
    row, case = rows[governing], cases[governing]
    summary.update(
        theta_max_over_alpha=row["theta_max_over_alpha"],
        theta_max_rad=row["theta_max_rad"],
        alpha_rad=row["alpha_rad"],
        overturned=any(r["overturned"] for r in rows),
        governing_record=_channel_id(case.record_id, case.component),
        governing_model=case.model,
        governing_component=case.component,
    )
    sf_config = config.safety_factor
    if sf_config.enabled:
        try:
            result = _search_safety_factor(solvers, tower, case, row["alpha_rad"], config)
        except (RockscreenError, ValueError, ArithmeticError) as exc:
            failures.append(Failure("solve", f"{tower.id} safety factor", str(exc)))
        else:
            summary.update(
                safety_factor=result.factor,
                safety_factor_lower=result.lower,
                safety_factor_solves=result.n_solves,
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
    return summary


def _search_safety_factor(
    solvers: Solvers, tower: Any, case: _Case, alpha: float, config: CampaignConfig
) -> Any:
    from pipeline.screening.risk import SafetyFactorResult

    sf = config.safety_factor
    # Below the uplift-free factor nothing moves, so the scan may start there.
    start = max(sf.start, uplift_free_factor(case.acc, alpha, case.acc_v))
    if start >= sf.cap:
        return SafetyFactorResult(math.inf, sf.cap, 0)

    from solver.constants import G

    lowest_vertical = float(np.min(case.acc_v)) if case.acc_v is not None else 0.0
    # Below this factor no sample reaches the uplift threshold: safe without a solve
    # (the small margin keeps the kernel's own rounding of the threshold test out).
    still = sample_uplift_factor(case.acc, alpha, case.acc_v) * (1.0 - 1e-9)
    motion = _search_motion(solvers, case)
    solves = 0

    def overturns(factor: float) -> bool:
        nonlocal solves
        # Scaled beyond -g the base would fall away from the tower: the rigid-block
        # model no longer holds, and the screening counts it as failure (conservative).
        if factor * lowest_vertical <= -G:
            return True
        if factor == 1.0 and case.response is not None:
            # 1 is on every scan grid: the case itself was solved at that factor already.
            return bool(case.response.overturned)
        if factor < still:
            return False
        solves += 1
        return bool(_solve(solvers, tower, case, factor, False, motion).overturned)

    result = safety_factor(
        overturns, start=start, ratio=sf.ratio, cap=sf.cap, tolerance=sf.tolerance
    )
    # The archive counts the solver calls the search made, not the verdicts it used.
    return dataclasses.replace(result, n_solves=solves)


def _channel_id(record_id: str, component: str) -> str:
    """``"IT.AQV..HN"`` + ``"E"`` -> ``"IT.AQV..HNE"`` (``X``/``Y``: the tower's axes)."""
    return f"{record_id}{component}"


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


# --------------------------------------------------------------------------- main process


def chunk_tasks(tasks: Sequence[TowerTask], jobs: int, size: int | None = None) -> list[list]:
    """Split tasks into chunks: many towers each, yet >= ~8 chunks per worker.

    Parameters
    ----------
    tasks : sequence of TowerTask
    jobs : int
        Worker processes.
    size : int, optional
        Towers per chunk; default ``clip(ceil(n / (8 jobs)), 1, 64)``: small enough
        for load balance and a live progress bar, large enough that the per-chunk
        cost (pickling, one archive append) stays negligible.

    Returns
    -------
    list of list of TowerTask
    """
    if size is None:
        size = min(64, max(1, math.ceil(len(tasks) / (8 * max(1, jobs)))))
    return [list(tasks[i : i + size]) for i in range(0, len(tasks), size)]


def fingerprint(
    towers_table: np.ndarray, motions: dict[str, Motion], config: CampaignConfig, version: str
) -> str:
    """Return a SHA-256 of everything that determines an archive's results.

    The tower table, the processed records (ids, sampling, samples), the resolved
    configuration and the software version: a ``.part`` file with another print is
    not resumed.
    """
    digest = hashlib.sha256()
    digest.update(version.encode())
    digest.update(config.to_toml().encode())
    digest.update(towers_table.tobytes())
    digest.update(repr(towers_table.dtype).encode())
    for record_id in sorted(motions):
        motion = motions[record_id]
        header = [record_id, motion.station, motion.dt, motion.channels, motion.azimuths]
        digest.update(json.dumps(header, default=str).encode())
        for array in (*motion.horizontals, motion.vertical):
            if array is not None:
                digest.update(np.ascontiguousarray(array, dtype=float).tobytes())
    return digest.hexdigest()


def _abort_hook() -> int | None:
    value = os.environ.get(ABORT_AFTER_CHUNKS_ENV)
    return int(value) if value else None


def run_campaign(
    tasks: Sequence[TowerTask],
    shared: CampaignShared,
    writer: Any,
    executor: Any,
    *,
    jobs: int = 1,
    chunk_size: int | None = None,
    progress: Callable[[int], None] | None = None,
) -> int:
    """Compute the tower tasks the archive does not hold yet and append them.

    Parameters
    ----------
    tasks : sequence of TowerTask
        Every paired tower of the campaign.
    shared : CampaignShared
    writer : pipeline.archive.campaign.ArchiveWriter
        Open on the ``.part`` file; its ``done`` set lists towers already written.
    executor : SerialExecutor or ProcessExecutor
    jobs : int
        Worker count (for chunk sizing).
    chunk_size : int, optional
        Towers per chunk (default: :func:`chunk_tasks`).
    progress : callable, optional
        Called with the number of towers of each written chunk.

    Returns
    -------
    int
        Number of towers computed in this call.
    """
    todo = [task for task in tasks if task.tower.id not in writer.done]
    chunks = chunk_tasks(todo, jobs, chunk_size)
    abort_after = _abort_hook()
    written = 0
    with executor:
        executor.start(run_chunk, shared)
        for chunk in chunks:
            executor.submit(chunk)
        for n_chunks, outcomes in enumerate(executor.completed(), start=1):
            writer.append(outcomes)
            written += len(outcomes)
            if progress is not None:
                progress(len(outcomes))
            if abort_after is not None and n_chunks >= abort_after:
                # Test hook: die like a killed process, right after a flushed chunk.
                os.kill(os.getpid(), signal.SIGKILL)
    return written


def make_tasks(
    towers: Sequence[Any],
    pairing: dict[str, list[str]],
    motions: dict[str, Motion],
    reasons: dict[str, str] | None = None,
) -> tuple[list[TowerTask], list[Failure]]:
    """Build one task per paired tower; unpaired towers become failures.

    Parameters
    ----------
    towers : sequence of Tower
        In inventory order.
    pairing : dict
        Tower id -> station keys (:func:`stations.pairing.pair_towers`).
    motions : dict
        Record id -> Motion.
    reasons : dict, optional
        Tower id -> why it is (not) paired, for the failures table.

    Returns
    -------
    tasks : list of TowerTask
    failures : list of Failure
    """
    by_station: dict[str, list[str]] = {}
    for record_id in sorted(motions):
        by_station.setdefault(motions[record_id].station, []).append(record_id)
    tasks, failures = [], []
    for index, tower in enumerate(towers):
        record_ids = tuple(
            record_id for key in pairing.get(tower.id, []) for record_id in by_station.get(key, [])
        )
        if record_ids:
            tasks.append(TowerTask(index, tower, tuple(sorted(set(record_ids)))))
        else:
            reason = (reasons or {}).get(tower.id) or "no record is paired with this tower"
            failures.append(Failure("pair", tower.id, reason))
    return tasks, failures


def pair(
    towers: Sequence[Any], motions: dict[str, Motion], *, max_distance_km: float
) -> tuple[list[TowerTask], list[Failure]]:
    """Pair towers with the stations of the records and build the tower tasks.

    Parameters
    ----------
    towers : sequence of Tower
    motions : dict
        Record id -> Motion (their stations and coordinates).
    max_distance_km : float
        Largest tower-station distance of nearest-station pairing [km].

    Returns
    -------
    tasks : list of TowerTask
    failures : list of Failure
        Unpaired towers, with the reason.
    """
    from stations.pairing import StationSite, pair_towers_detailed

    sites: dict[str, StationSite] = {}
    for record_id in sorted(motions):
        motion = motions[record_id]
        site = sites.get(motion.station)
        if site is None or (not site.has_coordinates and motion.latitude is not None):
            sites[motion.station] = StationSite(motion.station, motion.latitude, motion.longitude)
    detailed = pair_towers_detailed(towers, list(sites.values()), max_distance_km=max_distance_km)
    keys = {tower_id: list(p.keys) for tower_id, p in detailed.items()}
    reasons = {tower_id: p.reason for tower_id, p in detailed.items()}
    return make_tasks(towers, keys, motions, reasons)


def prepare_records(
    paths: Sequence[str | Path],
    *,
    units: str | None = None,
    stations: Any = None,
    processing: dict[str, Any] | None = None,
) -> tuple[dict[str, Motion], list[Failure]]:
    """Read, process and group record files into the campaign's motions.

    A file that cannot be read, a trace that cannot be processed, and a station whose
    traces cannot be grouped are failures (reported and skipped), never errors.

    Parameters
    ----------
    paths : sequence of path
        Record files.
    units : str, optional
        Units of files that state none (``g``, ``m/s2``, ``cm/s2``).
    stations : path or StationMetadata, optional
        StationXML (coordinates, orientations, responses).
    processing : dict, optional
        The ``[processing]`` table of the configuration.

    Returns
    -------
    motions : dict
        Record id -> Motion, sorted by id.
    failures : list of Failure

    Raises
    ------
    StationMetadataError
        If ``stations`` is given but unreadable (a usage error, not a record failure).
    """
    from obspy import Stream

    from pipeline.config import processing_config
    from pipeline.processing.steps import process_trace
    from pipeline.records.grouping import group_records
    from pipeline.records.io import read_stream
    from stations.stationxml import read_station_metadata

    meta = read_station_metadata(stations) if stations is not None else None
    config = processing_config(processing or {})
    failures: list[Failure] = []
    processed = Stream()
    for path in paths:
        try:
            stream = read_stream(path, units=units, stations=meta)
        except (RockscreenError, OSError) as exc:
            failures.append(Failure("read", str(path), str(exc)))
            continue
        for trace in stream:
            try:
                processed += process_trace(trace, config)
            except RockscreenError as exc:
                failures.append(Failure("process", f"{path} ({trace.id})", str(exc)))
    motions: dict[str, Motion] = {}
    for group in _station_groups(processed):
        try:
            records = group_records(group)
        except RockscreenError as exc:
            ids = ", ".join(sorted({tr.id for tr in group}))
            failures.append(Failure("process", ids, str(exc)))
            continue
        for record in records:
            motion = motion_from_record(record)
            if not motion.horizontals:
                failures.append(Failure("process", record.id, "no horizontal component"))
                continue
            record_id = motion.record_id
            n = 2
            while record_id in motions:  # same station, another event
                record_id = f"{motion.record_id}~{n}"
                n += 1
            motions[record_id] = dataclasses.replace(motion, record_id=record_id)
    return dict(sorted(motions.items())), failures


def _station_groups(stream: Any) -> list[Any]:
    from obspy import Stream

    groups: dict[tuple[str, str, str], Any] = {}
    for trace in stream:
        key = (trace.stats.network, trace.stats.station, trace.stats.location)
        groups.setdefault(key, Stream()).append(trace)
    return [groups[key] for key in sorted(groups)]


def motion_from_record(record: Any) -> Motion:
    """Return the :class:`Motion` of a :class:`pipeline.records.grouping.Record`.

    Parameters
    ----------
    record : pipeline.records.grouping.Record

    Returns
    -------
    Motion
        Horizontals ``h1``, ``h2`` (those present) with their azimuths, the vertical,
        coordinates, and the archive information (files, formats, provenance).
    """
    roles = [role for role in ("h1", "h2") if getattr(record, role) is not None]
    channel_of = {role: str(trace_id).split(".")[-1] for role, trace_id in record.channels.items()}
    coordinates = record.coordinates or {}
    provenance = record.provenance or {}
    files, formats = [], []
    for steps in provenance.values():
        for step in steps:
            if isinstance(step, dict) and step.get("step") == "read":
                files.append(str(step.get("file", "")))
                formats.append(str(step.get("format", "")))
    info = {
        "starttime": str(record.starttime),
        "trace_ids": dict(record.channels),
        "files": sorted(set(files)),
        "formats": sorted(set(formats)),
        "provenance": provenance,
        "vertical_channel": channel_of.get("z", "vertical"),
    }
    return Motion(
        record_id=record.id,
        station=record.station,
        dt=float(record.dt),
        channels=tuple(channel_of.get(role, role) for role in roles),
        horizontals=tuple(np.asarray(getattr(record, role), dtype=float) for role in roles),
        azimuths=tuple(getattr(record, f"{role}_azimuth") for role in roles),
        vertical=None if record.z is None else np.asarray(record.z, dtype=float),
        latitude=coordinates.get("latitude"),
        longitude=coordinates.get("longitude"),
        info=info,
    )
