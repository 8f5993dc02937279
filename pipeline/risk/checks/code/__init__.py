"""The code checks added as modules, one module each; importing one registers its check.

A module here calls :func:`rockscreen.pipeline.risk.checks.registry.register` with a
:class:`~rockscreen.pipeline.risk.checks.registry.CodeCheck` that declares its id, part,
family, method, the inventory columns it requires, whether it can govern before the whole
tower's rigid overturning, what it covers, its summary columns with their units and its
``compute`` (docs/architecture.md, "A new code check"). :func:`load` imports every module of
the package's ``__path__`` (a test adds a folder to it, as the engine's part models are
found); ``assess`` loads them before it computes (:mod:`rockscreen.pipeline.risk.checks.
tower_code_checks`). The checks of the codes built in (LV1, the kinematic checks) are
declared in :mod:`rockscreen.pipeline.risk.checks.registry` and computed by the same loop.
"""

from __future__ import annotations

import importlib
import pkgutil
import sys

__all__ = ["load"]

#: The ``__path__`` of the last :func:`load` (a folder added or removed loads again).
_LOADED: list[tuple[str, ...]] = []


def load() -> None:
    """Import every module of this package's ``__path__`` not imported yet (each registers)."""
    path = tuple(__path__)
    if _LOADED and _LOADED[-1] == path:
        return
    for info in sorted(pkgutil.iter_modules(list(path)), key=lambda i: i.name):
        name = f"{__name__}.{info.name}"
        if name not in sys.modules:
            importlib.import_module(name)
    _LOADED[:] = [path]
