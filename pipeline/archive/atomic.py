"""Atomic file writing: a file appears at its final path complete, or not at all.

Every writer of rockscreen (campaign, sweep, assess and scenario archives, CSV and
GeoJSON exports, HTML reports) goes through :func:`atomic_path`: it writes a work file
beside the target in the same folder (so the final :func:`os.replace` is a rename on one
file system, atomic on POSIX and Windows) and renames it only when the block ends
without an exception.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator
from pathlib import Path

__all__ = ["atomic_path", "write_text_atomic"]


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike, *, suffix: str | None = None) -> Iterator[Path]:
    """Yield a work path to write; move it to ``path`` when the block succeeds.

    Parameters
    ----------
    path : str or path-like
        The final file.
    suffix : str, optional
        Work-file name ``path + suffix``; default a hidden per-process name
        ``.NAME.PID.tmp`` beside ``path``.

    Yields
    ------
    pathlib.Path
        The work file. On any exception (Ctrl-C included) it is removed and ``path`` is
        left untouched.
    """
    path = Path(path)
    if suffix is None:
        work = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    else:
        work = path.with_name(path.name + suffix)
    try:
        yield work
        os.replace(work, path)
    except BaseException:
        work.unlink(missing_ok=True)
        raise


def write_text_atomic(path: str | os.PathLike, text: str) -> Path:
    """Write UTF-8 ``text`` to ``path`` atomically and return the path."""
    with atomic_path(path) as work:
        with work.open("w", encoding="utf-8", newline="") as stream:
            stream.write(text)
    return Path(path)
