"""The solver methods: one table from a method's name to the solvers that integrate it.

As SciPy's ``solve_ivp`` keeps its integrators in one table, a method of rockscreen is one
row here: the functions that solve the single rocking block, the double block and the
sliding block (:class:`Method`), with the signatures and the
:class:`~rockscreen.solver.response.Response` of :func:`rockscreen.solver.solve_rocking`,
:func:`rockscreen.solver.solve_double_block` and :func:`rockscreen.solver.solve_sliding`.
The engine (``rockscreen.pipeline.engine.solvers``) takes its solvers from this table.

A method's modules load when the method is first asked for (:func:`get_method`):
importing this module loads no numba, so ``rockscreen --help`` stays light.
"""

from __future__ import annotations

import functools
import importlib
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

__all__ = ["DEFAULT_METHOD", "METHOD_NAMES", "Method", "get_method"]

#: Each method's solvers: role -> (module, function). ``compiled``: the event-driven kernel
#: compiled by numba (:mod:`rockscreen.solver.kernel`), cached on disk; ``reference``: the
#: independent ``solve_ivp`` oracle (:mod:`rockscreen.solver.reference`) behind the compiled
#: solvers' API (:mod:`rockscreen.solver.reference_method`: slow, for checks; no friction
#: demand).
_TABLE: dict[str, dict[str, tuple[str, str]]] = {
    "compiled": {
        "rocking": ("rockscreen.solver.rocking", "solve_rocking"),
        "double_block": ("rockscreen.solver.double_block", "solve_double_block"),
        "sliding": ("rockscreen.solver.sliding", "solve_sliding"),
    },
    "reference": {
        "rocking": ("rockscreen.solver.reference_method", "rocking"),
        "double_block": ("rockscreen.solver.reference_method", "double_block"),
        "sliding": ("rockscreen.solver.reference_method", "sliding"),
    },
}

#: The methods' names, in table order.
METHOD_NAMES: tuple[str, ...] = tuple(_TABLE)
#: The method every product uses unless told otherwise.
DEFAULT_METHOD = "compiled"


@dataclass(frozen=True)
class Method:
    """One way of integrating the rigid-block equations: its three solvers."""

    #: The method's name in :data:`METHOD_NAMES`.
    name: str
    #: ``rocking(block, acc, dt, **options) -> Response``: the single rocking block.
    rocking: Callable[..., Any]
    #: ``double_block(block, acc, dt, *, tower_mass, building_mass, mu_s, mu_k, **options)
    #: -> Response``: the tower rocking on a sliding building.
    double_block: Callable[..., Any]
    #: ``sliding(acc, dt, *, mu_s, mu_k, **options) -> Response``: the sliding block.
    sliding: Callable[..., Any]


@functools.cache
def get_method(name: str = DEFAULT_METHOD) -> Method:
    """Return the method called ``name``, loading its solvers' modules on first use.

    Parameters
    ----------
    name : str
        One of :data:`METHOD_NAMES`.

    Returns
    -------
    Method

    Raises
    ------
    ValueError
        For a name not in the table, naming the allowed ones.
    """
    roles = _TABLE.get(name)
    if roles is None:
        raise ValueError(f"solver method {name!r}: must be one of {', '.join(METHOD_NAMES)}")
    solvers = {
        role: getattr(importlib.import_module(module), function)
        for role, (module, function) in roles.items()
    }
    return Method(name=name, **solvers)
