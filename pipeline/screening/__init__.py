"""Screening: cases (towers × records × components × models), evaluation, safety factor.

The names below are the stable entry points other stages (risk, report) use.
"""

from rockscreen.pipeline.config import MODELS
from rockscreen.pipeline.screening.cases import (
    Motion,
    Solvers,
    floor_motion,
    solve_model,
    tower_components,
    tower_models,
)
from rockscreen.pipeline.screening.risk import sample_uplift_factor, uplift_free_factor

__all__ = [
    "MODELS",
    "Motion",
    "Solvers",
    "floor_motion",
    "sample_uplift_factor",
    "solve_model",
    "tower_components",
    "tower_models",
    "uplift_free_factor",
]
