"""``double``: the tower rocking on the church building, which slides on its foundation.

The seed paper's double-block model (Di Gennaro, Guadagnuolo and Monaco 2023;
``docs/theory.md`` §5): the masses of tower and building and the foundation's static and
kinetic friction come from the inventory; a study file and ``simulate --model`` call it
``double-block``. While the tower rests the building's acceleration never exceeds the
ground's in magnitude, so the uplift pre-check on the ground motion proves the tower
motionless (status ``no_uplift``: the building's sliding is not computed then).
"""

from __future__ import annotations

from typing import Any

from rockscreen.pipeline.engine.registry import CAMPAIGN, SIMULATE, STUDY, TowerModel
from rockscreen.pipeline.engine.solvers import active_solvers


def solve_double_block(
    block: Any, acc: Any, dt: float, parameters: dict[str, Any], **options: Any
) -> Any:
    """Solve the tower ``block`` on the sliding building under ground motion ``acc`` [m/s²].

    With the active solvers' ``double``
    (:func:`~rockscreen.pipeline.engine.solvers.active_solvers`). ``parameters``:
    ``tower_mass``, ``building_mass`` [kg], ``mu_s``, ``mu_k`` [-]; ``options`` are
    :func:`rockscreen.solver.solve_double_block`'s keywords.
    """
    return active_solvers().double(block, acc, dt, **parameters, **options)


MODEL = TowerModel(
    name="double",
    order=2,
    label="double block (tower on a sliding building)",
    label_it="blocco doppio (torre su un edificio che scorre)",
    solve=solve_double_block,
    requires=("tower_mass_kg", "building_mass_kg", "mu_s", "mu_k"),
    parameters={
        "tower_mass": "tower_mass_kg",
        "building_mass": "building_mass_kg",
        "mu_s": "mu_s",
        "mu_k": "mu_k",
    },
    solver_name="double-block",
    products=frozenset({CAMPAIGN, STUDY, SIMULATE}),
    rest_status="no_uplift",
    paper_formulations=True,
)
