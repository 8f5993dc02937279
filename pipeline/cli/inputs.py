"""Checks of the input paths a command was given, before the heavy stack is imported.

Importing ObsPy, numba and h5py takes seconds on a busy machine; a mistyped path should
not. The commands call these first: a missing file, a folder, a FIFO or a file that is not
HDF5 where an archive is expected is refused in one line
(:class:`~rockscreen.pipeline.errors.ArchiveError` or
:class:`~rockscreen.pipeline.errors.RockscreenError`) before anything heavy is imported. This
module imports nothing but the standard library and the error classes.
"""

from __future__ import annotations

import os
import stat
from collections.abc import Iterable

from rockscreen.pipeline.errors import ArchiveError, RockscreenError
from rockscreen.pipeline.text import printable

__all__ = ["HDF5_SIGNATURE", "check_archive_path", "check_input_files", "check_input_paths"]

#: The 8 bytes an HDF5 superblock starts with (at offset 0, 512, 1024, 2048, ...).
HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"


def _problem(path: str | os.PathLike) -> str | None:
    """Return why a path is not a readable regular file, or None."""
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        return "does not exist"
    except OSError as exc:
        return f"cannot be read ({printable(exc.strerror or type(exc).__name__)})"
    if stat.S_ISDIR(mode):
        return "is a folder, not a file"
    if not stat.S_ISREG(mode):
        return "is not a regular file"
    if not os.access(path, os.R_OK):
        return "cannot be read (permission denied)"
    return None


def _has_hdf5_signature(path: str | os.PathLike) -> bool:
    """Return whether the file carries the HDF5 signature where HDF5 looks for it."""
    with open(path, "rb") as f:
        size = os.fstat(f.fileno()).st_size
        offset = 0
        while offset + len(HDF5_SIGNATURE) <= size:
            f.seek(offset)
            if f.read(len(HDF5_SIGNATURE)) == HDF5_SIGNATURE:
                return True
            offset = 512 if offset == 0 else offset * 2
    return False


def check_archive_path(path: str | os.PathLike) -> None:
    """Refuse, in one line, an archive path that is missing, not a file or not HDF5.

    Parameters
    ----------
    path : str or path-like
        The archive the user named.

    Raises
    ------
    ArchiveError
        If the path does not exist, is a folder, a FIFO or a device, cannot be read, or
        does not start with the HDF5 signature (a CSV given for an archive).
    """
    name = printable(os.fspath(path))
    problem = _problem(path)
    if problem is None:
        try:
            if not _has_hdf5_signature(path):
                problem = "is not an HDF5 file (no HDF5 signature), so not a rockscreen archive"
        except OSError as exc:
            problem = f"cannot be read ({printable(exc.strerror or type(exc).__name__)})"
    if problem:
        raise ArchiveError(f"archive {name!r} {problem}")


def check_input_files(paths: Iterable[str | os.PathLike | None], what: str = "input") -> None:
    """Refuse, in one line, the first input file that is missing or not a regular file.

    Parameters
    ----------
    paths : iterable of str or path-like or None
        Files the command reads (None: an option not given, skipped).
    what : str
        What the files are, for the message (``"record"``, ``"inventory"``, ...).

    Raises
    ------
    RockscreenError
        Naming the file and what is wrong with it.
    """
    for path in paths:
        if path is None:
            continue
        problem = _problem(path)
        if problem == "does not exist":  # as the record readers word it
            problem = ": no such file"
        if problem:
            sep = "" if problem.startswith(":") else " "
            raise RockscreenError(f"{what} {printable(os.fspath(path))}{sep}{problem}")


def check_input_paths(paths: Iterable[str | os.PathLike | None], what: str = "input") -> None:
    """Refuse, in one line, the first input that is neither a readable file nor a folder.

    Parameters
    ----------
    paths : iterable of str or path-like or None
        Files or folders the command reads (None: an option not given, skipped).
    what : str
        What they are, for the message (``"suite"``, ...).

    Raises
    ------
    RockscreenError
        Naming the path and what is wrong with it.
    """
    for path in paths:
        if path is not None and not os.path.isdir(path):
            check_input_files([path], what)
