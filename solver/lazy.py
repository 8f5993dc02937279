"""Packages whose public names load on first use (PEP 562).

``import rockscreen.solver`` or ``import rockscreen.pipeline`` then costs nothing:
``rockscreen.solver.constants`` does not compile numba code, and ``rockscreen --help``
imports neither ObsPy, h5py nor numba.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping
from typing import Any

__all__ = ["lazy_exports"]


def lazy_exports(
    package: str, exports: Mapping[str, str], namespace: dict[str, Any]
) -> tuple[Callable[[str], Any], Callable[[], list[str]]]:
    """Return the module-level ``__getattr__`` and ``__dir__`` of a lazy package.

    Parameters
    ----------
    package : str
        The package's name, for the error message.
    exports : mapping of str to str
        Public name -> the module that defines it.
    namespace : dict
        The package's ``globals()``: a name, once loaded, is stored there.

    Returns
    -------
    (callable, callable)
        ``__getattr__(name)`` (AttributeError for a name not exported) and ``__dir__()``.
    """

    def __getattr__(name: str) -> Any:
        module = exports.get(name)
        if module is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        value = getattr(importlib.import_module(module), name)
        namespace[name] = value
        return value

    def __dir__() -> list[str]:
        return sorted(set(namespace) | set(exports))

    return __getattr__, __dir__
