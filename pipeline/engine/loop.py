"""The case loop: a tower's cases under one ground motion, every component × model.

Every product goes through it (``docs/architecture.md``): ``run`` solves each case of a
recorded motion in full (:meth:`ComponentCases.solve`), the stripes of ``assess`` screen
each case of a scaled suite record (:meth:`ComponentCases.screen` at factor 1), and the IDA
screens one component at the factors its search asks for, stopping at the first model
that overturns (``stop_at_first``). Written here once:

- the cases: the tower's horizontal components of the motion
  (:func:`~rockscreen.pipeline.engine.motion.tower_components`) times the models given,
  each with its block from the tower's
  :class:`~rockscreen.pipeline.engine.cases.BlockCache`;
- each model's excitation, computed once at scale 1: the models' filters (floor, shaft
  top, gable support) are linear, so the excitation at a factor is the factor times it;
- the model's validity limit: a scaled vertical reaching -g leaves every case unsolved
  (status ``vertical_limit``), and a solver refusing a scaled motion is the same limit
  for its case (:func:`~rockscreen.pipeline.engine.cases.screen_case`);
- the uplift pre-check of a screened case (a motionless case is not solved).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from rockscreen.pipeline.engine.cases import (
    BlockCache,
    Case,
    CaseVerdict,
    screen_case,
    solve_case,
)
from rockscreen.pipeline.engine.motion import GroundMotion, TowerComponent, tower_components
from rockscreen.pipeline.engine.registry import TowerModel
from rockscreen.pipeline.engine.solvers import Solvers, active_solvers, use_solvers
from rockscreen.pipeline.errors import RockscreenError
from rockscreen.solver.constants import G
from rockscreen.stations.tower import Tower

__all__ = [
    "CaseFailure",
    "ComponentCases",
    "ComponentVerdict",
    "ModelVerdict",
    "motion_cases",
    "reaches_vertical_limit",
]

#: A case's verdict when the scaled vertical reaches -g: the model's limit, not solved.
_LIMIT = CaseVerdict("vertical_limit", False, math.nan, False)


def reaches_vertical_limit(acc_v: np.ndarray | None) -> bool:
    """Whether a vertical acceleration reaches -g: the rigid-block model's validity limit.

    Parameters
    ----------
    acc_v : numpy.ndarray or None
        Vertical acceleration [m/s²], positive up.
    """
    return acc_v is not None and len(acc_v) > 0 and float(np.min(acc_v)) <= -G


@dataclass(frozen=True)
class ModelVerdict:
    """The verdict of one case of a component: a model at the component's scale factor."""

    #: The case's model.
    model: TowerModel
    verdict: CaseVerdict


@dataclass(frozen=True)
class ComponentVerdict:
    """The verdicts of one component's cases at a scale factor (:meth:`ComponentCases.screen`)."""

    #: The component (``"X"``, ``"Y"``, or a channel's letter).
    component: str
    #: The scale factor of the motion [-].
    factor: float
    #: One per case screened, in model order (with ``stop_at_first`` the cases up to the
    #: first that overturned or met the model's limit).
    cases: tuple[ModelVerdict, ...]
    #: The scaled vertical reaches -g: every case at the model's limit, none solved.
    vertical_limit: bool
    #: Whether any case overturned.
    overturned: bool
    #: Largest theta_max/alpha of the cases [-]; ``inf`` when one overturned (overturning
    #: exceeds every damage level), 0 when none moved; cases at the limit do not count.
    worst: float
    #: Whether a case met the model's validity limit (the vertical or the solver's refusal).
    limited: bool
    #: Solver calls made (motionless cases and cases at the limit are not solves).
    n_solves: int

    @property
    def overturned_models(self) -> frozenset[str]:
        """The names of the models whose case overturned."""
        return frozenset(c.model.name for c in self.cases if c.verdict.overturned)


@dataclass(frozen=True)
class CaseFailure:
    """A case of :meth:`ComponentCases.solve` whose excitation or solve raised."""

    #: The component (``"X"``, ``"Y"``, or a channel's letter).
    component: str
    #: The case's model.
    model: TowerModel
    #: What was raised (a user-facing error, a ``ValueError`` or an ``ArithmeticError``).
    error: Exception


class ComponentCases:
    """The cases of one horizontal component of a motion: the tower's models on it.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
    component : TowerComponent
        The component at scale 1: its name, ground acceleration [m/s²], the tower's base
        width in its direction [m] and its tower axis.
    vertical : numpy.ndarray or None
        Vertical ground acceleration at scale 1 [m/s²], positive up; scaled with the
        component.
    dt : float
        Sampling step [s].
    models : sequence of TowerModel
        The models, in case order.
    blocks : BlockCache, optional
        The tower's blocks, shared between components and motions; default a new one.

    Attributes
    ----------
    solvers : Solvers
        The solvers active when the cases were made
        (:func:`~rockscreen.pipeline.engine.solvers.active_solvers`): the models'
        excitations and solves use them, wherever the cases are screened or solved.
    """

    def __init__(
        self,
        tower: Tower,
        component: TowerComponent,
        vertical: np.ndarray | None,
        dt: float,
        models: Sequence[TowerModel],
        blocks: BlockCache | None = None,
    ) -> None:
        self.tower, self.component, self.vertical, self.dt = tower, component, vertical, dt
        self.models = tuple(models)
        self.solvers: Solvers = active_solvers()
        self.blocks = BlockCache(tower) if blocks is None else blocks
        self._excitations: dict[str, np.ndarray] = {}

    @property
    def name(self) -> str:
        """The component's name (``"X"``, ``"Y"``, or a channel's letter)."""
        return self.component.component

    def block(self, model: TowerModel) -> Any:
        """Return ``model``'s block in the component's direction (from the block cache)."""
        return self.blocks(self.component.width_m, model, self.component.axis)

    def excitation(self, model: TowerModel) -> np.ndarray:
        """Return ``model``'s excitation at the block's base at scale 1 [m/s²], built once."""
        excitation = self._excitations.get(model.name)
        if excitation is None:
            with use_solvers(self.solvers):
                excitation = model.excitation(self.tower, self.component.acc, self.dt)
            self._excitations[model.name] = excitation
        return excitation

    def screen(
        self,
        factor: float = 1.0,
        *,
        free_motion_s: float,
        early_stop: bool = True,
        stop_at_first: bool = False,
    ) -> ComponentVerdict:
        """Return the verdicts of every model on the component scaled by ``factor``.

        Each case goes through :func:`~rockscreen.pipeline.engine.cases.screen_case` (the
        uplift pre-check; the solver's refusal is the model's limit) with the model's
        excitation at scale 1 times ``factor``; a scaled vertical reaching -g leaves every
        case at the limit, unsolved.

        Parameters
        ----------
        factor : float
            Amplitude scale factor of the motion [-].
        free_motion_s : float
            Free motion followed after the record [s].
        early_stop : bool
            Stop each solve's free motion once its verdict is certain
            (:func:`~rockscreen.pipeline.engine.cases.screen_case`).
        stop_at_first : bool
            Stop at the first case that overturns or meets the model's limit: the
            component's verdict is then known (the IDA's search).

        Returns
        -------
        ComponentVerdict
        """
        vertical = self.vertical
        if vertical is not None and factor != 1.0:
            vertical = vertical * factor
        if reaches_vertical_limit(vertical):
            cases = tuple(ModelVerdict(model, _LIMIT) for model in self.models)
            return ComponentVerdict(self.name, factor, cases, True, False, 0.0, True, 0)
        verdicts: list[ModelVerdict] = []
        overturned, worst, limited, n_solves = False, 0.0, False, 0
        for model in self.models:
            excitation = self.excitation(model)
            if factor != 1.0:
                excitation = excitation * factor
            with use_solvers(self.solvers):
                verdict = screen_case(
                    model, self.tower, self.block(model), excitation, vertical, self.dt,
                    free_motion_s, early_stop,
                )  # fmt: skip
            verdicts.append(ModelVerdict(model, verdict))
            n_solves += verdict.solved
            if verdict.status == "vertical_limit":
                limited = True
            elif verdict.overturned:
                overturned, worst = True, math.inf
            else:
                worst = max(worst, verdict.theta_max_over_alpha)
            if stop_at_first and (limited or overturned):
                # Overturning implies every damage level; past the limit nothing is known.
                break
        return ComponentVerdict(
            self.name, factor, tuple(verdicts), False, overturned, worst, limited, n_solves
        )

    def solve(self, record_id: str, free_motion_s: float) -> list[Case | CaseFailure]:
        """Solve every model's case at scale 1 in full (``run``): responses, not verdicts.

        Every case is solved (no pre-check: its row reports the solver's response), with
        the friction demand. A case whose excitation or solve raises a user-facing error,
        a ``ValueError`` (a solver's :class:`~rockscreen.solver.errors.ParameterError`
        included) or an ``ArithmeticError`` is a :class:`CaseFailure`; the others go on.

        Parameters
        ----------
        record_id : str
            The motion's record id (the cases' ``record_id``).
        free_motion_s : float
            Free motion followed after the record [s].

        Returns
        -------
        list of Case or CaseFailure
            One per model, in model order; a :class:`~rockscreen.pipeline.engine.cases.Case`
            carries its ``response``.
        """
        out: list[Case | CaseFailure] = []
        width_m = self.component.width_m
        for model in self.models:
            block = self.block(model)
            try:
                case = Case(
                    record_id, self.name, model, width_m, self.excitation(model),
                    self.vertical, self.dt, block, free_motion_s,
                )  # fmt: skip
                with use_solvers(self.solvers):
                    case.response = solve_case(self.tower, case, 1.0, history=False)
            except (RockscreenError, ValueError, ArithmeticError) as exc:
                out.append(CaseFailure(self.name, model, exc))
                continue
            out.append(case)
        return out


def motion_cases(
    tower: Tower,
    motion: GroundMotion,
    models: Sequence[TowerModel],
    blocks: BlockCache | None = None,
) -> list[ComponentCases]:
    """Return a tower's cases under ``motion``: one :class:`ComponentCases` per component.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
    motion : GroundMotion
        The motion at scale 1 (its vertical, when present, is every case's ``acc_v``).
    models : sequence of TowerModel
        The models, in case order (e.g.
        :func:`~rockscreen.pipeline.engine.registry.available_models`).
    blocks : BlockCache, optional
        The tower's blocks, shared between motions; default a new one.

    Returns
    -------
    list of ComponentCases
        In the order of :func:`~rockscreen.pipeline.engine.motion.tower_components`, each
        with the solvers active now
        (:func:`~rockscreen.pipeline.engine.solvers.active_solvers`).
    """
    blocks = BlockCache(tower) if blocks is None else blocks
    return [
        ComponentCases(tower, component, motion.vertical, motion.dt, models, blocks)
        for component in tower_components(tower, motion)
    ]
