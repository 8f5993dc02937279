"""The message catalogue, one module per subject; each registers its entries when loaded.

A new subject is a module here, named in :data:`SUBJECTS` (a module not named there is
loaded after them: a code check added as a module may bring its entries so). Every entry
has an English and an Italian template (:func:`rockscreen.pipeline.verdict.messages.
register` refuses one without).
"""

from __future__ import annotations

import importlib
import pkgutil
import sys

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


#: The ``__path__`` of the last :func:`load` (a folder added to it loads again).
_LOADED: list[tuple[str, ...]] = []


def load() -> None:
    """Import every subject's module (each registers its entries once; later calls: nothing).

    The modules of :data:`SUBJECTS` in their order, then any other module of the package's
    ``__path__`` (a check added as a module may bring its entries as a module of its own,
    e.g. ``catalogue/<check>.py``; a test adds a folder to ``__path__``).
    """
    path = tuple(__path__)
    if _LOADED and _LOADED[-1] == path:
        return
    for name in SUBJECTS:
        importlib.import_module(f"{__name__}.{name}")
    for info in sorted(pkgutil.iter_modules(list(path)), key=lambda i: i.name):
        if info.name not in SUBJECTS and f"{__name__}.{info.name}" not in sys.modules:
            importlib.import_module(f"{__name__}.{info.name}")
    _LOADED[:] = [path]
