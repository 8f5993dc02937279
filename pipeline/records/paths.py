"""Which files the user means: folders, unexpanded globs, duplicates, and non-regular files.

:func:`expand_record_paths` turns command-line arguments into record files (a folder gives
its record files, a quoted glob such as ``'records/*.mseed'`` -- left unexpanded by Windows
shells or by quoting -- is expanded here, a file named twice is read once);
:func:`check_record_file` refuses, with one sentence, what is not a readable regular file
(a symbolic link loop, a FIFO, a device such as ``/dev/zero``, an empty file).
"""

from __future__ import annotations

import errno
import glob
import os
import stat

from rockscreen.pipeline.errors import RecordFormatError
from rockscreen.pipeline.text import printable

#: File name extensions of the record formats rockscreen reads (lower case): miniSEED,
#: SAC, ESM/ITACA and AFAD ASCII, PEER AT2, K-NET / KiK-net components.
RECORD_EXTENSIONS = (
    ".mseed",
    ".miniseed",
    ".ms",
    ".msd",
    ".sac",
    ".asc",
    ".at2",
    ".ew",
    ".ns",
    ".ud",
    ".ew1",
    ".ns1",
    ".ud1",
    ".ew2",
    ".ns2",
    ".ud2",
)

_KINDS = (
    (stat.S_ISFIFO, "a FIFO (named pipe)"),
    (stat.S_ISCHR, "a character device"),
    (stat.S_ISBLK, "a block device"),
    (stat.S_ISSOCK, "a socket"),
)


def _name(path) -> str:
    return printable(os.fsdecode(path))


def check_record_file(path) -> int:
    """Refuse anything but a non-empty regular file; return its size [bytes].

    Parameters
    ----------
    path : str, bytes or path-like
        The record file (symbolic links are followed).

    Returns
    -------
    int
        The file size [bytes].

    Raises
    ------
    RecordFormatError
        Naming the file: no such file, a symbolic link loop or a broken link, permission
        denied, a folder, a FIFO/device/socket, or an empty file.
    """
    name = _name(path)
    try:
        info = os.stat(path)
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            raise RecordFormatError(f"{name}: symbolic link loop") from exc
        if exc.errno in (errno.ENOENT, errno.ENOTDIR):
            if os.path.islink(path):
                target = _name(os.readlink(path))
                raise RecordFormatError(f"{name}: broken symbolic link (to {target})") from exc
            if glob.has_magic(os.fsdecode(path)):
                raise RecordFormatError(f"{name}: no file matches this pattern") from exc
            raise RecordFormatError(f"{name}: no such file") from exc
        raise RecordFormatError(f"{name}: cannot read: {exc.strerror or exc}") from exc
    if stat.S_ISDIR(info.st_mode):
        raise RecordFormatError(
            f"{name}: is a folder, not a record file (give the folder itself on the command "
            "line to read the record files inside it)"
        )
    if not stat.S_ISREG(info.st_mode):
        kind = next((text for test, text in _KINDS if test(info.st_mode)), "not a regular file")
        raise RecordFormatError(f"{name}: {kind}, not a regular record file")
    if info.st_size == 0:
        raise RecordFormatError(f"{name}: empty file")
    return int(info.st_size)


def _folder_files(folder: str, notes: list[str]) -> list[str]:
    """Record files of a folder (not recursive): known extensions, else all regular files."""
    try:
        with os.scandir(folder) as entries:
            names = sorted(
                entry.name
                for entry in entries
                if not entry.name.startswith(".") and entry.is_file(follow_symlinks=True)
            )
    except OSError as exc:
        raise RecordFormatError(
            f"{_name(folder)}: cannot list the folder: {exc.strerror or exc}"
        ) from exc
    if not names:
        raise RecordFormatError(f"{_name(folder)}: the folder holds no files")
    known = [n for n in names if os.path.splitext(n)[1].lower() in RECORD_EXTENSIONS]
    chosen = known or names
    other = len(names) - len(chosen)
    notes.append(
        f"{_name(folder)}: {len(chosen)} record file(s)"
        + (f", {other} file(s) of other extensions ignored" if other else "")
        + ("" if known else " (no known record extension: every file is tried)")
    )
    return [os.path.join(folder, n) for n in chosen]


def expand_record_paths(args, *, strict: bool = False) -> tuple[list[str], list[str]]:
    """Turn command-line record arguments into record files, each once.

    Parameters
    ----------
    args : iterable of str, bytes or path-like
        Files, folders or glob patterns (``*``, ``?``, ``[...]``) as the user typed them.
    strict : bool
        Raise for an argument that does not exist or a pattern that matches nothing.
        When False (default) such an argument is kept as it is, so that reading it
        reports the error for that file alone (:func:`check_record_file`: "no such file";
        "no file matches this pattern") while the other files are read.

    Returns
    -------
    paths : list of str
        In argument order: a file as given; a folder's files sorted by name (those with a
        record extension, :data:`RECORD_EXTENSIONS`, or every regular non-hidden file when
        none has one; not recursive); a pattern's matching files sorted by name. A file
        reached twice (same resolved path) is kept at its first place only. Non-regular
        files named explicitly are kept: :func:`check_record_file` refuses them when read.
    notes : list of str
        One sentence per folder or pattern expanded and per duplicate dropped (for stderr).

    Raises
    ------
    RecordFormatError
        Naming the argument when a folder holds no files or cannot be listed, and (with
        ``strict``) when it does not exist or is a pattern that matches no file.
    """
    paths: list[str] = []
    notes: list[str] = []
    seen: dict[str, str] = {}
    for arg in args:
        arg = os.fsdecode(os.fspath(arg))
        if os.path.lexists(arg):
            found = _folder_files(arg, notes) if os.path.isdir(arg) else [arg]
        elif glob.has_magic(arg):
            matches = sorted(glob.glob(arg))
            found = [m for m in matches if not os.path.isdir(m)]
            if not found:
                if strict:
                    raise RecordFormatError(f"{_name(arg)}: no file matches this pattern")
                paths.append(arg)
                continue
            skipped = len(matches) - len(found)
            notes.append(
                f"{_name(arg)}: {len(found)} file(s) match"
                + (f" ({skipped} folder(s) skipped)" if skipped else "")
            )
        elif strict:
            raise RecordFormatError(f"{_name(arg)}: no such file or folder")
        else:
            paths.append(arg)
            continue
        for path in found:
            key = os.path.realpath(path)
            if key in seen:
                notes.append(f"{_name(path)}: the same file as {_name(seen[key])}; read once")
                continue
            seen[key] = path
            paths.append(path)
    return paths, notes


__all__ = ["RECORD_EXTENSIONS", "check_record_file", "expand_record_paths"]
