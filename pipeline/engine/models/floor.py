"""``floor``: the tower as a single rocking block on the floor motion at its springing.

The church's first mode filters the ground motion (``docs/floor_motion.md``): the
building's period (inventory ``building_period_s``, else the NTC 2018 §7.3.3.2 estimate
from ``building_height_m``) and a linear mode shape ``z/H`` at the tower's springing
(``base_height_m``, default the building's height).
"""

from __future__ import annotations

import numpy as np

from rockscreen.pipeline.engine.models.ground import solve_single_block
from rockscreen.pipeline.engine.registry import TowerModel
from rockscreen.pipeline.engine.solvers import active_solvers
from rockscreen.stations.tower import Tower


def floor_motion(tower: Tower, acc: np.ndarray, dt: float) -> np.ndarray:
    """Return the floor acceleration at the tower's springing [m/s²].

    First mode of the building, linear mode shape z/H (``docs/floor_motion.md``), with the
    active solvers' ``floor`` (:func:`~rockscreen.pipeline.engine.solvers.active_solvers`).

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        A tower with floor-model data (``building_height_m``).
    acc : numpy.ndarray
        Ground acceleration [m/s²] at step ``dt``.
    dt : float
        Sampling step [s].
    """
    from rockscreen.pipeline.motion.floor import building_period_from_height

    period = tower.building_period_s
    if period is None:
        period = building_period_from_height(tower.building_height_m)
    base = tower.base_height_m if tower.base_height_m is not None else tower.building_height_m
    motion = active_solvers().floor(
        acc, dt, building_period=period, mode_shape_at_base=base / tower.building_height_m
    )
    return np.asarray(motion, dtype=float)


MODEL = TowerModel(
    name="floor",
    order=1,
    label="single block on the floor motion",
    label_it="blocco singolo sul moto del solaio",
    solve=solve_single_block,
    requires=("building_height_m",),
    base_motion=floor_motion,
)
