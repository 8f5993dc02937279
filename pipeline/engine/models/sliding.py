"""``sliding``: the building alone, a rigid block sliding on its foundation (Newmark 1965).

Offered by ``simulate --model sliding`` only: it has no rocking tower, so a campaign
(which screens towers) never runs it.
"""

from __future__ import annotations

from typing import Any

from rockscreen.pipeline.engine.registry import SIMULATE, TowerModel
from rockscreen.pipeline.engine.solvers import active_solvers


def solve_sliding_block(
    block: Any, acc: Any, dt: float, parameters: dict[str, Any], **options: Any
) -> Any:
    """Solve the sliding block under ``acc`` [m/s²]; ``block`` is None.

    With the active solvers' ``sliding``
    (:func:`~rockscreen.pipeline.engine.solvers.active_solvers`). ``parameters``:
    ``mu_s``, ``mu_k`` [-]; ``options`` are :func:`rockscreen.solver.solve_sliding`'s
    keywords.
    """
    return active_solvers().sliding(acc, dt, **parameters, **options)


MODEL = TowerModel(
    name="sliding",
    order=3,
    label="sliding block (the building alone)",
    label_it="blocco che scorre (l'edificio da solo)",
    solve=solve_sliding_block,
    parameters={"mu_s": "mu_s", "mu_k": "mu_k"},
    solver_name="sliding",
    products=frozenset({SIMULATE}),
    has_block=False,
)
