"""Where numba keeps the compiled solver: a per-user cache folder, never site-packages.

numba's default cache sits in ``__pycache__`` beside the sources. After ``pip install .``
that would be ``site-packages/rockscreen/solver/__pycache__``, which outlives a later
``pip install -e .`` and then shadows the editable package with a namespace package.
:func:`configure` points numba at ``$NUMBA_CACHE_DIR`` when the user set it, else at
``$XDG_CACHE_HOME/rockscreen/numba-rockscreen.solver-<digest of the solver's sources>``
(under ``~/.cache``; ``%LOCALAPPDATA%`` on Windows; one folder per version of the sources,
:func:`cache_dir`). It runs when this module is imported, which :mod:`rockscreen.solver` does first,
before the kernel is compiled.
"""

from __future__ import annotations

import hashlib
import os
import sys
from pathlib import Path

__all__ = ["cache_dir", "configure", "kernel_is_cached", "sources_digest"]


def cache_dir() -> Path:
    """Return the folder numba caches the compiled solver in."""
    configured = os.environ.get("NUMBA_CACHE_DIR")
    if configured:
        return Path(configured)
    if sys.platform == "win32":  # pragma: no cover - not tested on this platform
        base = Path(os.environ.get("LOCALAPPDATA", Path.home() / "AppData" / "Local"))
    else:
        base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    # "rockscreen.solver": numba's cache index pickles the kernel's module path, so the
    # caches of the releases that installed a top-level ``solver`` (``.../numba``) cannot be
    # read by this one (ModuleNotFoundError: No module named 'solver') and stay apart.
    # The digest of the solver's sources: numba checks only the timestamp of a cached
    # function's own file, so a kernel compiled against an older version of a function it
    # calls from another module would be reused (a stale, wrong kernel); a new folder per
    # version of the sources makes every change recompile.
    return base / "rockscreen" / f"numba-rockscreen.solver-{sources_digest()}"


def sources_digest() -> str:
    """Return 12 hex digits of the SHA-256 of the solver's Python sources (names and bytes)."""
    digest = hashlib.sha256()
    for path in sorted(Path(__file__).parent.glob("*.py")):
        digest.update(path.name.encode())
        digest.update(path.read_bytes())
    return digest.hexdigest()[:12]


def configure() -> Path:
    """Point numba's cache at :func:`cache_dir` (before any solver function compiles)."""
    path = cache_dir()
    os.environ.setdefault("NUMBA_CACHE_DIR", str(path))
    if "numba" in sys.modules:  # numba read its configuration already: update it too
        import numba

        numba.config.CACHE_DIR = str(path)
    return path


def kernel_is_cached() -> bool:
    """Whether this installation's compiled kernel is in the cache (False: the next solve compiles).

    numba keeps each source folder's cache in ``<cache dir>/<folder name>_<sha1 of its
    absolute path>`` (its ``_UserProvidedCacheLocator``), so another installation's cache
    does not count.
    """
    folder = os.path.dirname(os.path.abspath(__file__))
    digest = hashlib.sha1(folder.encode()).hexdigest()
    subpath = f"{os.path.basename(folder)}_{digest}"
    return any((cache_dir() / subpath).glob("kernel.*.nbi"))


configure()
