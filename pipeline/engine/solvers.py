"""The solvers the engine's models call: a method of the table, or a test's stand-ins.

The models never take their solvers as a parameter: they call :func:`active_solvers`
(``active_solvers().rocking(block, acc, dt, ...)``). What is active is the method's
solvers (:mod:`rockscreen.solver.methods`, default ``compiled``) unless work runs inside
:func:`use_solvers`, entered once where work starts with the :class:`Solvers` given:

- ``run``'s workers enter the campaign's (:attr:`CampaignShared.solvers
  <rockscreen.pipeline.screening.cases.CampaignShared>`, which carries the choice to worker
  processes: a process does not inherit a context);
- a unit test enters pure-Python stand-ins: ``with use_solvers(Solvers(rocking=...)):``.

The engine's objects that outlive a call
(:class:`~rockscreen.pipeline.engine.cases.BlockCache`,
:class:`~rockscreen.pipeline.engine.loop.ComponentCases`) keep the solvers active when they
were made. The active solvers are a :mod:`contextvars` variable: a thread that does not
enter :func:`use_solvers` runs the default method.
"""

from __future__ import annotations

import contextvars
import functools
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from typing import Any

from rockscreen.solver.methods import DEFAULT_METHOD, get_method

__all__ = ["Solvers", "active_solvers", "use_solvers"]


@dataclass(frozen=True)
class Solvers:
    """The functions the models call; None = the one of the method ``method``.

    ``block`` builds the whole tower's block (default
    :meth:`rockscreen.solver.RockingBlock.from_dimensions`), ``rocking``, ``double`` and
    ``sliding`` are the method's solvers (:class:`rockscreen.solver.methods.Method`),
    ``floor`` filters the ground motion through the building (default
    :func:`rockscreen.pipeline.motion.floor.modal_floor_accelerogram`). Unit tests of the
    orchestration pass small pure-Python stand-ins for some of them.
    """

    block: Callable[..., Any] | None = None
    rocking: Callable[..., Any] | None = None
    double: Callable[..., Any] | None = None
    floor: Callable[..., Any] | None = None
    sliding: Callable[..., Any] | None = None
    #: The solver method (:data:`rockscreen.solver.methods.METHOD_NAMES`) of the solvers
    #: left None.
    method: str = DEFAULT_METHOD

    def resolved(self) -> Solvers:
        """Return a copy with every None replaced by the method's (or the real) function."""
        if None not in (self.block, self.rocking, self.double, self.floor, self.sliding):
            return self
        from rockscreen.pipeline.motion.floor import modal_floor_accelerogram
        from rockscreen.solver.block import RockingBlock

        method = get_method(self.method)
        return Solvers(
            block=self.block or RockingBlock.from_dimensions,
            rocking=self.rocking or method.rocking,
            double=self.double or method.double_block,
            floor=self.floor or modal_floor_accelerogram,
            sliding=self.sliding or method.sliding,
            method=self.method,
        )

    @property
    def real(self) -> bool:
        """Whether the tower solvers are the compiled ones of :mod:`rockscreen.solver`.

        Only they take a checked :class:`rockscreen.solver.rocking.BaseMotion` and a
        ``scale`` (:func:`~rockscreen.pipeline.engine.cases.search_motion`).
        """
        compiled = get_method(DEFAULT_METHOD)
        return self.rocking is compiled.rocking and self.double is compiled.double_block


#: The solvers entered by :func:`use_solvers`, resolved; None = the default method's.
_ACTIVE: contextvars.ContextVar[Solvers | None] = contextvars.ContextVar(
    "rockscreen_solvers", default=None
)


@functools.cache
def _default() -> Solvers:
    return Solvers().resolved()


def active_solvers() -> Solvers:
    """Return the solvers the models call now (resolved: no None left).

    Returns
    -------
    Solvers
        Those of the innermost :func:`use_solvers`, else the default method's.
    """
    solvers = _ACTIVE.get()
    return _default() if solvers is None else solvers


@contextmanager
def use_solvers(solvers: Solvers | None = None) -> Iterator[Solvers]:
    """Make ``solvers`` (resolved) the active ones inside the ``with`` block.

    Parameters
    ----------
    solvers : Solvers, optional
        Default the default method's.

    Yields
    ------
    Solvers
        The active solvers, resolved.
    """
    resolved = _default() if solvers is None else solvers.resolved()
    token = _ACTIVE.set(resolved)
    try:
        yield resolved
    finally:
        _ACTIVE.reset(token)
