"""The message catalogue, one module per subject; each registers its entries when loaded.

A new subject is a module here, named in :data:`SUBJECTS`. Every entry has an English and an
Italian template (:func:`rockscreen.pipeline.verdict.messages.register` refuses one without).
"""

from __future__ import annotations

import importlib
from functools import cache

__all__ = ["SUBJECTS", "load"]

#: The subjects' modules, loaded by :func:`load`.
SUBJECTS: tuple[str, ...] = (
    "general",
    "screening",
    "fits",
    "sites",
    "kinematic",
    "lv1_model",
    "records",
    "scenario",
    "disagreement",
    "checks",
    "method",
    "screening_risk",
)


@cache
def load() -> None:
    """Import every subject's module (each registers its entries once; later calls: nothing)."""
    for name in SUBJECTS:
        importlib.import_module(f"{__name__}.{name}")
