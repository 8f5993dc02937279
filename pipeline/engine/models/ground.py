"""``ground``: the tower as a single rocking block on the ground motion (Housner 1963).

The seed paper's single-block model with the tower on the ground (``docs/theory.md``):
every tower runs it; a study file and ``simulate --model`` call it ``rocking``.
"""

from __future__ import annotations

from typing import Any

from rockscreen.pipeline.engine.registry import CAMPAIGN, SIMULATE, STUDY, TowerModel
from rockscreen.pipeline.engine.solvers import active_solvers


def solve_single_block(
    block: Any, acc: Any, dt: float, parameters: dict[str, Any], **options: Any
) -> Any:
    """Solve the single rocking block ``block`` under ``acc`` [m/s²] at step ``dt`` [s].

    With the active solvers' ``rocking``
    (:func:`~rockscreen.pipeline.engine.solvers.active_solvers`). ``parameters`` is empty
    (the block carries its geometry); ``options`` are
    :func:`rockscreen.solver.solve_rocking`'s keywords.
    """
    return active_solvers().rocking(block, acc, dt, **parameters, **options)


MODEL = TowerModel(
    name="ground",
    order=0,
    label="single block on the ground",
    label_it="blocco singolo sul terreno",
    solve=solve_single_block,
    solver_name="rocking",
    products=frozenset({CAMPAIGN, STUDY, SIMULATE}),
)
