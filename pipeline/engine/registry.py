"""The model registry: every tower model is one registered object.

A model says what it needs and does, as OpenQuake's hazardlib GMPEs declare the
parameters they require (``REQUIRES_*``) and SciPy's ``solve_ivp`` keeps its methods in
one table:

- ``name``: its one spelling in every table, archive, configuration key and CLI option of
  a campaign (``ground``, ``floor``, ``double``); ``solver_name``: its spelling where one
  excitation is solved (``simulate --model``, a study file's ``model``);
- ``requires``: the inventory columns it needs (a tower without them does not run it);
- ``parameters``: the solver keywords it takes from the tower (masses, friction);
- ``base_motion``: how its excitation is built from the ground motion (``None``: the ground
  motion itself); ``own_block``: the block that rocks when it is not the whole tower, and
  ``block_note``: what that block assumes of a tower, as a message (a code);
- ``solve``: how it solves, with the active solvers
  (:func:`~rockscreen.pipeline.engine.solvers.active_solvers`: a method of
  :mod:`rockscreen.solver.methods`, or the pure-Python stand-ins a test enters with
  :func:`~rockscreen.pipeline.engine.solvers.use_solvers`); its ``base_motion`` takes its
  filters (the floor accelerogram) from them too, so neither takes the solvers as a
  parameter;
- ``label`` for figures and the report.

The models are the modules of :mod:`rockscreen.pipeline.engine.models`, found on first use
(each defines ``MODEL``); nothing else in rockscreen compares model names.
"""

from __future__ import annotations

import importlib
import pkgutil
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

from rockscreen.pipeline.verdict.messages import Message
from rockscreen.stations.tower import Tower

__all__ = [
    "CAMPAIGN",
    "SIMULATE",
    "STUDY",
    "TowerModel",
    "available_models",
    "clear",
    "get",
    "ground_input_model",
    "model_names",
    "models",
    "solver_model",
    "tower_models",
]

#: Products that run models, as ``TowerModel.products`` names them: a campaign (``run``
#: and ``assess``: towers of an inventory against records), a study file (``sweep``), and
#: one excitation (``simulate``).
CAMPAIGN, STUDY, SIMULATE = "campaign", "study", "simulate"

#: ``base_motion(tower, acc, dt) -> acc`` [m/s²] at the block's base; a filter through a
#: structure calls ``active_solvers().floor``.
BaseMotion = Callable[[Any, Any, float], Any]
#: ``solve(block, acc, dt, parameters, **options) -> Response``: calls the active solvers
#: (``active_solvers().rocking``, ``.double`` or ``.sliding``) with ``parameters`` and
#: ``options`` as keywords.
Solve = Callable[..., Any]
#: ``own_block(tower, width_m, axis) -> RockingBlock``: the model's block in the direction of
#: a case, in which the tower's base is ``width_m`` [m] wide and which is along the tower
#: axis ``axis`` (``"x"``, ``"y"``: :data:`rockscreen.stations.inventory_columns.TOWER_AXES`),
#: or None when the component is along neither (the model's safe side).
OwnBlock = Callable[[Any, float, str | None], Any]
#: ``block_note(tower) -> Message | None``: what a model's own block assumes of ``tower``, as
#: a message (:mod:`rockscreen.pipeline.verdict.messages`, a clause of ``assess``'s note);
#: None when there is nothing to say.
BlockNote = Callable[[Any], Message | None]


@dataclass(frozen=True)
class TowerModel:
    """One model of a tower (or of the building under it) and what it needs."""

    #: The model's name in tables, archives, ``[models] run`` and ``assess --models``.
    name: str
    #: Position in case order (cases of a record list the models by increasing order).
    order: int
    #: What the model is, in words (figure titles, the report).
    label: str
    #: ``solve(block, acc, dt, parameters, **options)``: the active solver's response
    #: (:data:`Solve`).
    solve: Solve
    #: Inventory columns the model needs; a tower lacking any does not run it.
    requires: tuple[str, ...] = ()
    #: Solver keyword -> the inventory column that gives it (masses [kg], friction [-]).
    parameters: Mapping[str, str] = field(default_factory=dict)
    #: How the excitation at the block's base is built; None = the ground motion itself.
    base_motion: BaseMotion | None = None
    #: The model's own rocking block (a part of the tower, e.g. the belfry) in a case's
    #: direction (:data:`OwnBlock`); None = the whole tower (its width in the component's
    #: direction × its height).
    own_block: OwnBlock | None = None
    #: What the own block assumes of a tower (:data:`BlockNote`); None: nothing to say.
    block_note: BlockNote | None = None
    #: Its name where one excitation is solved (``simulate --model``, a study file); ``""``
    #: when not offered there.
    solver_name: str = ""
    #: The products that offer the model (:data:`CAMPAIGN`, :data:`STUDY`, :data:`SIMULATE`).
    products: frozenset[str] = frozenset({CAMPAIGN})
    #: Whether a rocking block is part of the model (False: the sliding building alone).
    has_block: bool = True
    #: Status of a case that the uplift pre-check proves motionless, left unsolved.
    rest_status: str = "no_motion"
    #: The label in Italian (the report's ``--lang it``); ``""`` shows the English one.
    label_it: str = ""
    #: Whether the seed paper's formulations (``docs/theory.md`` §5: ``di-gennaro-2023``,
    #: its switches) exist for the model besides rockscreen's consistent one.
    paper_formulations: bool = False

    def takes(self, keyword: str) -> bool:
        """Whether the model's solver takes the parameter ``keyword`` (``mu_s``, ...)."""
        return keyword in self.parameters

    def available(self, tower: Tower) -> bool:
        """Whether ``tower`` has every inventory column the model requires."""
        return all(getattr(tower, column, None) is not None for column in self.requires)

    def parameters_of(self, tower: Tower) -> dict[str, Any]:
        """Return the solver keywords the model takes from ``tower`` (the inventory)."""
        return {keyword: getattr(tower, column) for keyword, column in self.parameters.items()}

    def excitation(self, tower: Tower, acc: Any, dt: float) -> Any:
        """Return the acceleration at the block's base [m/s²] under ground motion ``acc``.

        Built with the active solvers' filters
        (:func:`~rockscreen.pipeline.engine.solvers.active_solvers`).

        Parameters
        ----------
        tower : rockscreen.stations.inventory.Tower
        acc : numpy.ndarray
            Ground acceleration [m/s²] at step ``dt``.
        dt : float
            Sampling step [s].
        """
        if self.base_motion is None:
            return acc
        return self.base_motion(tower, acc, dt)


_REGISTRY: dict[str, TowerModel] = {}


def _load() -> Mapping[str, TowerModel]:
    """Import every module of the models package once and register its ``MODEL``."""
    if not _REGISTRY:
        package = importlib.import_module("rockscreen.pipeline.engine.models")
        found = []
        for info in pkgutil.iter_modules(package.__path__):
            module = importlib.import_module(f"{package.__name__}.{info.name}")
            model = getattr(module, "MODEL", None)
            if not isinstance(model, TowerModel):
                raise TypeError(f"{module.__name__} defines no MODEL (a TowerModel)")
            found.append(model)
        names = [m.name for m in found]
        if len(set(names)) != len(names):
            raise TypeError(f"two tower models share a name: {sorted(names)}")
        for model in sorted(found, key=lambda m: (m.order, m.name)):
            _REGISTRY[model.name] = model
    return MappingProxyType(_REGISTRY)


def clear() -> None:
    """Forget the registered models: the next use imports the models package again.

    For a model module added while rockscreen runs (a plugin folder appended to the
    package's ``__path__``, or a test).
    """
    _REGISTRY.clear()


def models(product: str | None = None) -> tuple[TowerModel, ...]:
    """Return the registered models in case order, optionally only those of ``product``."""
    return tuple(m for m in _load().values() if product is None or product in m.products)


def model_names(product: str = CAMPAIGN) -> tuple[str, ...]:
    """Return the names a product spells its models with, in case order.

    A campaign uses :attr:`TowerModel.name`; a study file and ``simulate`` use
    :attr:`TowerModel.solver_name`.
    """
    if product == CAMPAIGN:
        return tuple(m.name for m in models(product))
    return tuple(m.solver_name for m in models(product))


def get(name: str) -> TowerModel:
    """Return the model called ``name`` (a campaign name); KeyError naming the allowed ones."""
    try:
        return _load()[name]
    except KeyError:
        raise KeyError(f"no tower model {name!r}; registered: {', '.join(_load())}") from None


def solver_model(solver_name: str) -> TowerModel:
    """Return the model a study file or ``simulate --model`` calls ``solver_name``."""
    for model in _load().values():
        if model.solver_name and model.solver_name == solver_name:
            return model
    allowed = ", ".join(m.solver_name for m in _load().values() if m.solver_name)
    raise KeyError(f"no model {solver_name!r} of one excitation; registered: {allowed}")


def available_models(tower: Tower, enabled: Sequence[str]) -> list[TowerModel]:
    """Return the campaign models that run for ``tower``: enabled ones its data allow."""
    return [m for m in models(CAMPAIGN) if m.name in enabled and m.available(tower)]


def ground_input_model() -> TowerModel:
    """Return the campaign model that every tower runs on the ground motion itself.

    Its cases' input is the record component as recorded (their ``pga_m_s2`` is the
    ground's PGA): the first campaign model that requires no inventory data and builds no
    base motion of its own (``ground``).
    """
    return next(m for m in models(CAMPAIGN) if not m.requires and m.base_motion is None)


def tower_models(tower: Tower, enabled: Sequence[str]) -> list[str]:
    """Return the names of :func:`available_models` (a stripe's ``models`` column)."""
    return [m.name for m in available_models(tower, enabled)]
