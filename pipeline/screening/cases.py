"""The cases of a screening: records, towers' components and models, one solve.

A case is one tower × one record × one horizontal component × one model
(``docs/campaign.md``): components are rotated to the tower's axes when the tower's
azimuth and the channel azimuths are known, otherwise each recorded horizontal is used
with the tower's smaller plan dimension; models are ``ground``, ``floor`` and ``double``.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rockscreen import solver
from rockscreen.pipeline.config import CampaignConfig
from rockscreen.pipeline.motion.floor import building_period_from_height, modal_floor_accelerogram
from rockscreen.pipeline.records.grouping import rotate_horizontals
from rockscreen.pipeline.vocabulary import SCREENING_MODELS
from rockscreen.solver.rocking import base_motion

#: The double-block solver's keyword arguments, and the tower attributes (inventory
#: columns) that give them: the masses [kg] and the foundation's friction [-].
_DOUBLE_BLOCK_ARGUMENTS: dict[str, str] = {
    "tower_mass": "tower_mass_kg",
    "building_mass": "building_mass_kg",
    "mu_s": "mu_s",
    "mu_k": "mu_k",
}


@dataclass(frozen=True)
class Failure:
    """Something that could not be read, processed, paired or solved."""

    #: ``"read"``, ``"process"``, ``"pair"`` or ``"solve"``.
    kind: str
    #: The file, record, tower or case concerned.
    subject: str
    #: One line a user reads.
    reason: str

    def as_row(self) -> dict[str, str]:
        """Return the failure as a row of the failures table."""
        return {"kind": self.kind, "subject": self.subject, "reason": self.reason}


@dataclass(frozen=True)
class Motion:
    """One processed record, as a worker needs it (plain arrays, cheap to pickle)."""

    #: ``"NET.STA.LOC.CHA-prefix"``, e.g. ``"IT.AQV..HN"``.
    record_id: str
    #: ``"NET.STA"``.
    station: str
    #: Sampling step [s].
    dt: float
    #: Horizontal channel codes, e.g. ``("HNN", "HNE")``.
    channels: tuple[str, ...]
    #: Horizontal accelerations [m/s²], one per channel, equal lengths.
    horizontals: tuple[np.ndarray, ...]
    #: Channel azimuths, clockwise from north [deg]; None when unknown.
    azimuths: tuple[float | None, ...]
    #: Vertical acceleration [m/s²], positive up.
    vertical: np.ndarray | None = None
    #: Station coordinates [deg].
    latitude: float | None = None
    longitude: float | None = None
    #: Archive attributes: files, formats, starttime, provenance, vertical channel.
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
    """One tower and the records it is screened against."""

    #: Position of the tower in the inventory (orders the archive tables).
    index: int
    tower: Any
    record_ids: tuple[str, ...]
    #: How the tower was paired, in words (``"nearest station IT.AQV at 3.2 km"``).
    pairing: str = ""
    #: Distance to the nearest paired station [km]; NaN when unknown.
    pairing_distance_km: float = math.nan


@dataclass
class History:
    """A (possibly decimated) time history of one case."""

    tower_id: str
    record_id: str
    component: str
    model: str
    #: Times [s].
    t: np.ndarray
    #: Tower rotation [rad].
    theta: np.ndarray
    #: Building slip relative to the ground [m] (zeros for single-block models).
    u: np.ndarray
    #: 0 rest, 1 tower rocking, 2 building sliding, 3 both.
    regime: np.ndarray
    #: Slenderness angle of the block [rad].
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
    """The functions a campaign calls; None = the real ones from :mod:`rockscreen.solver`.

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


def tower_components(tower: Any, motion: Motion) -> list[tuple[str, np.ndarray, float]]:
    """Return the horizontal components a tower is checked against.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
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
    return [model for model in SCREENING_MODELS if model in enabled and allowed[model]]


@dataclass
class Case:
    """One tower × record × component × model, with its response once solved."""

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
    tower : rockscreen.stations.inventory.Tower
        A tower with floor-model data (``has_floor_model``).
    acc : numpy.ndarray
        Ground acceleration [m/s²] at step ``dt``.
    dt : float
        Sampling step [s].
    solvers : Solvers, optional
        Stand-in functions for tests; default the real ones.
    """
    solvers = (solvers or Solvers()).resolved()

    period = tower.building_period_s
    if period is None:
        period = building_period_from_height(tower.building_height_m)
    base = tower.base_height_m if tower.base_height_m is not None else tower.building_height_m
    motion = solvers.floor(
        acc, dt, building_period=period, mode_shape_at_base=base / tower.building_height_m
    )
    return np.asarray(motion, dtype=float)


def solve_case(
    solvers: Solvers, tower: Any, case: Case, factor: float, history: bool, motion: Any = None
) -> Any:
    """Solve ``case`` with its records scaled by ``factor``.

    ``motion`` (a :class:`rockscreen.solver.rocking.BaseMotion` of the case's records, real solvers
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
    return solve_model(
        solvers,
        case.model,
        tower,
        case.block,
        acc,
        case.dt,
        acc_v=acc_v,
        history=history,
        max_free_time=case.free_motion_s,
        **extra,
    )


def solve_model(
    solvers: Solvers,
    model: str,
    tower: Any,
    block: Any,
    acc: Any,
    dt: float,
    **options: Any,
) -> Any:
    """Solve ``block`` under ``acc`` with the solver of ``model``.

    ``double`` is the tower on the sliding building (the tower's masses and friction
    from ``tower``); every other model is the single block. ``options`` are the
    solver's keyword arguments (``acc_v``, ``history``, ``max_free_time``, ...).
    """
    if model == "double":
        building = {arg: getattr(tower, column) for arg, column in _DOUBLE_BLOCK_ARGUMENTS.items()}
        return solvers.double(block, acc, dt, **building, **options)
    return solvers.rocking(block, acc, dt, **options)


def search_motion(solvers: Solvers, case: Case) -> Any:
    """Return the case's records checked once for the search, or None for stand-in solvers."""
    if solvers.rocking is solver.solve_rocking and solvers.double is solver.solve_double_block:
        return base_motion(case.acc, case.dt, case.acc_v)
    return None
