"""Screening: the cases towers × records × components × models, their evaluation,
the safety factor and the risk classes of a record-based run.

The names below are the stable entry points other stages (risk, report) use.
"""

from pipeline.screening.campaign import (
    MODELS,
    Motion,
    Solvers,
    floor_motion,
    tower_components,
    tower_models,
)
from pipeline.screening.risk import sample_uplift_factor, uplift_free_factor

__all__ = [
    "MODELS",
    "Motion",
    "Solvers",
    "floor_motion",
    "sample_uplift_factor",
    "tower_components",
    "tower_models",
    "uplift_free_factor",
]
