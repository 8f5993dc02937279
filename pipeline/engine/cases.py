"""One case solved: a tower × a ground-motion component × a model, at a scale factor.

One case is written here once: the block of a tower in a direction (cached per width and
tower axis), the uplift pre-check, the model's validity limit, and the call of the model's
solver (the active solvers of :mod:`rockscreen.pipeline.engine.solvers`: a method of the
solver's table, or pure-Python stand-ins a unit test enters). The loop over a motion's
components and a tower's models that every product uses is
:mod:`rockscreen.pipeline.engine.loop`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

from rockscreen.pipeline.engine.registry import TowerModel
from rockscreen.pipeline.engine.solvers import active_solvers
from rockscreen.pipeline.engine.uplift import is_motionless
from rockscreen.pipeline.vocabulary import TOWER_AXES
from rockscreen.solver.errors import ParameterError
from rockscreen.solver.rocking import base_motion
from rockscreen.stations.tower import Tower

__all__ = [
    "BlockCache",
    "Case",
    "CaseVerdict",
    "screen_case",
    "search_motion",
    "solve_case",
]


class BlockCache:
    """The rocking blocks of one tower's cases, by model, width [m] and axis.

    The whole tower's block has the tower's height and ``eta`` and depends on the width
    alone; a model with its own block
    (:attr:`~rockscreen.pipeline.engine.registry.TowerModel.own_block`, e.g. the belfry)
    builds it for the direction of a case: the tower's base width in it and the tower axis
    it is along (:class:`~rockscreen.pipeline.engine.motion.TowerComponent`). The whole
    tower's block is made by the ``block`` of the solvers active when the cache is made
    (:func:`~rockscreen.pipeline.engine.solvers.active_solvers`).
    """

    def __init__(self, tower: Tower) -> None:
        self._tower = tower
        self._make = active_solvers().block
        self._blocks: dict[tuple[str, float, str | None], Any] = {}

    def __call__(
        self, width: float, model: TowerModel | None = None, axis: str | None = None
    ) -> Any:
        """Return the block of ``model`` (default the whole tower) in a case's direction.

        Parameters
        ----------
        width : float
            The tower's base width in the case's direction [m].
        model : TowerModel, optional
            The case's model; None or a model without its own block: the whole tower.
        axis : {"x", "y"} or None
            The tower axis the case's component is along
            (:data:`~rockscreen.stations.inventory_columns.TOWER_AXES`); None when it is
            along neither (a model's own block takes its safe side).

        Returns
        -------
        rockscreen.solver.RockingBlock
        """
        if axis is not None and axis not in TOWER_AXES:
            allowed = ", ".join(TOWER_AXES)
            raise ValueError(f"block axis {axis!r}: must be one of {allowed} or None")
        own = model is not None and model.own_block is not None
        key = (model.name, width, axis) if own else ("", width, None)
        block = self._blocks.get(key)
        if block is None:
            if own:
                block = model.own_block(self._tower, width, axis)
            else:
                block = self._make(width, self._tower.height_m, eta=self._tower.eta)
            self._blocks[key] = block
        return block


@dataclass
class Case:
    """One tower × record × component × model, with its response once solved."""

    record_id: str
    component: str
    #: The model (its ``name`` is the case's model in every table).
    model: TowerModel
    #: Block width in the component's direction [m].
    width: float
    #: Acceleration at the block's base [m/s²] (the model's excitation).
    acc: np.ndarray
    #: Vertical acceleration [m/s²], positive up.
    acc_v: np.ndarray | None
    #: Sampling step [s].
    dt: float
    block: Any
    #: Free motion followed after the record [s].
    free_motion_s: float
    response: Any = None


def solve_case(tower: Tower, case: Case, factor: float, history: bool, motion: Any = None) -> Any:
    """Solve ``case`` with its records scaled by ``factor``, with the active solvers.

    ``motion`` (a :class:`rockscreen.solver.rocking.BaseMotion` of the case's records, real
    solvers only: :func:`search_motion`) makes the solver scale the checked record itself
    instead of receiving a multiplied copy to check again, and skips the friction demand (NaN): the
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
    return case.model.solve(
        case.block,
        acc,
        case.dt,
        case.model.parameters_of(tower),
        acc_v=acc_v,
        history=history,
        max_free_time=case.free_motion_s,
        **extra,
    )


def search_motion(case: Case) -> Any:
    """Return the case's records checked once for a search, or None for stand-in solvers.

    None too when the active solvers are not the compiled ones: only these take a checked
    :class:`rockscreen.solver.rocking.BaseMotion` and a ``scale``.
    """
    if active_solvers().real:
        return base_motion(case.acc, case.dt, case.acc_v)
    return None


class CaseVerdict(NamedTuple):
    """What a verdict-only evaluation of a case gives (:func:`screen_case`)."""

    #: The solver's status, the model's ``rest_status`` for a motionless case, or
    #: ``vertical_limit`` where the model does not hold.
    status: str
    overturned: bool
    #: Normalised peak rotation [-]; 0 at rest, NaN at the vertical limit.
    theta_max_over_alpha: float
    #: Whether the solver was called.
    solved: bool


def screen_case(
    model: TowerModel,
    tower: Tower,
    block: Any,
    acc: np.ndarray,
    acc_v: np.ndarray | None,
    dt: float,
    free_motion_s: float,
    early_stop: bool = True,
) -> CaseVerdict:
    """Return the verdict of one case, solving only when the block can move.

    The model solves with the active solvers
    (:func:`~rockscreen.pipeline.engine.solvers.active_solvers`).

    When no sample of the excitation reaches the uplift threshold
    (:func:`rockscreen.pipeline.engine.uplift.is_motionless`) the block stays at rest: not
    solved, status ``model.rest_status``. A :class:`~rockscreen.solver.errors.ParameterError`
    of the solver (the scaled vertical reaching -g) is the model's validity limit, status
    ``vertical_limit``: never a failure of the tower.

    Parameters
    ----------
    model : TowerModel
    tower : rockscreen.stations.inventory.Tower
    block : rockscreen.solver.RockingBlock
    acc : numpy.ndarray
        Acceleration at the block's base [m/s²]: the model's excitation, which the
        pre-check reads too.
    acc_v : numpy.ndarray or None
        Vertical acceleration [m/s²], positive up.
    dt : float
        Sampling step [s].
    free_motion_s : float
        Free motion followed after the record [s].
    early_stop : bool
        Stop the free motion once the verdict is certain (the solvers'
        ``stop_when_certain``: trailing zeros are free motion, and a single block below the
        overturning energy barrier on a still base cannot overturn; ``docs/theory.md``).
        The verdict and ``theta_max/alpha`` are those of the full solve; False follows the
        free motion to rest (the reference path).
    """
    if is_motionless(acc, block.alpha, acc_v):
        return CaseVerdict(model.rest_status, False, 0.0, False)
    try:
        response = model.solve(
            block,
            acc,
            dt,
            model.parameters_of(tower),
            acc_v=acc_v,
            history=False,
            max_free_time=free_motion_s,
            friction_demand=False,
            stop_when_certain=early_stop,
        )
    except ParameterError:  # the floor motion or a solver check: the model's limit
        return CaseVerdict("vertical_limit", False, math.nan, False)
    ratio = float(response.theta_max_over_alpha)
    return CaseVerdict(str(response.status), bool(response.overturned), ratio, True)
