"""One run per output archive, and no silent overwrite of another campaign's archive.

:func:`archive_lock` holds an exclusive, non-blocking ``flock`` on ``OUT.lock`` for the
whole run: a second run on the same ``--out`` stops at once with one line naming the
command and the pid of the first, the lock file, and what to do. The kernel releases the
lock when its process dies, however it dies, so a lock file left by a killed run never
blocks the next one.

:func:`check_overwrite` refuses to replace a complete archive of *another* campaign
(another fingerprint: other records, inventory or configuration) unless asked to.

:func:`check_output` is the first check of every command that writes a file: the output
is never one of the command's inputs, an existing file is replaced only with
``--overwrite``, and its folder exists and is writable, all before any work.

:func:`claimed_output` is both, in the order every command that writes an archive takes
them (``run``, ``assess``, ``scenario``, ``sweep``): the output checked, then locked for the
command's duration. The rest of a long command's shell (executor, work file, stop signals)
is :class:`rockscreen.pipeline.execution.job.Job`.
"""

from __future__ import annotations

import contextlib
import errno
import os
from collections.abc import Iterator, Sequence
from pathlib import Path

from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.text import printable

try:  # POSIX only; elsewhere runs are not locked
    import fcntl
except ImportError:  # pragma: no cover - Windows
    fcntl = None  # type: ignore[assignment]
from rockscreen.pipeline.archive.reader import read_metadata
from rockscreen.pipeline.archive.resume import is_hdf5

__all__ = [
    "archive_lock",
    "busy_message",
    "check_output",
    "check_overwrite",
    "claimed_output",
    "lock_path",
]


def lock_path(path: str | os.PathLike) -> Path:
    """Return the lock file of an archive: ``OUT`` + ``.lock``."""
    path = Path(path)
    return path.with_name(path.name + ".lock")


def _holder(lock: Path) -> tuple[str, str]:
    """Return the pid (digits, or ``""``) and the command written in a lock file."""
    try:
        lines = lock.read_text(encoding="ascii", errors="replace").splitlines()
    except OSError:
        return "", ""
    pid = lines[0].strip() if lines and lines[0].strip().isdigit() else ""
    command = lines[1].strip() if len(lines) > 1 else ""
    command = command if command.isascii() and command.replace("-", "").isalpha() else ""
    return pid, command


def busy_message(path: str | os.PathLike, lock: Path, pid: str, command: str) -> str:
    """Return the one line said when another process holds the lock of ``path``.

    Parameters
    ----------
    path : str or path-like
        The output the command wanted to write.
    lock : pathlib.Path
        Its lock file.
    pid, command : str
        The holder's process id and rockscreen command, as its lock file says (``""``:
        unknown).

    Returns
    -------
    str
        E.g. ``another rockscreen assess is writing out.h5 (pid 1234 holds the lock file
        out.h5.lock); wait for it to end or stop it (kill 1234), or choose another --out``.
    """
    who = f"rockscreen {command}" if command else "rockscreen process"
    holds = f"pid {pid} holds" if pid else "a process whose pid is unknown holds"
    stop = f"stop it (kill {pid})" if pid else "stop it"
    return (
        f"another {who} is writing {printable(os.fspath(path))} ({holds} the lock file "
        f"{printable(os.fspath(lock))}); wait for it to end or {stop}, or choose another --out"
    )


@contextlib.contextmanager
def archive_lock(path: str | os.PathLike, command: str = "") -> Iterator[Path]:
    """Hold the exclusive lock of an output archive for the duration of the block.

    Parameters
    ----------
    path : str or path-like
        The final archive ``OUT``; the lock is ``OUT.lock`` (it holds this process id and
        ``command`` on a second line).
    command : str
        The rockscreen command that writes ``OUT`` (``run``, ``assess``, ...), named to a
        second command that finds it busy.

    Yields
    ------
    pathlib.Path
        The lock file.

    Raises
    ------
    ArchiveError
        At once (no waiting) when another process holds the lock: one line naming its
        command, its pid, the lock file and what to do (:func:`busy_message`).

    Notes
    -----
    On file systems without ``flock`` (some network mounts) and off POSIX the run goes
    on unlocked.
    """
    lock = lock_path(path)
    if fcntl is None:
        yield lock
        return
    while True:
        fd = os.open(lock, os.O_RDWR | os.O_CREAT, 0o644)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as exc:
            os.close(fd)
            if exc.errno in (errno.EWOULDBLOCK, errno.EAGAIN, errno.EACCES):
                raise ArchiveError(busy_message(path, lock, *_holder(lock))) from None
            yield lock  # no flock on this file system: unlocked
            return
        try:
            same = os.fstat(fd).st_ino == os.stat(lock).st_ino
        except FileNotFoundError:
            same = False
        if same:
            break
        os.close(fd)  # the holder removed the file meanwhile: lock the new one
    try:
        os.ftruncate(fd, 0)
        os.write(fd, f"{os.getpid()}\n{command}\n".encode("ascii", errors="replace"))
        yield lock
    finally:
        with contextlib.suppress(OSError):
            lock.unlink()
        os.close(fd)


def _describe(meta: dict) -> str:
    created = meta.get("created_utc") or "unknown date"
    inventory = meta.get("inventory_source") or "unknown inventory"
    fingerprint = str(meta.get("fingerprint") or "none")[:12]
    return (
        f"created {printable(created)}, inventory {printable(inventory)}, "
        f"fingerprint {printable(fingerprint)}"
    )


def check_overwrite(
    path: str | os.PathLike,
    fingerprint: str,
    *,
    overwrite: bool = False,
    inventory_source: str | None = None,
) -> None:
    """Refuse to replace an existing archive of another campaign.

    Parameters
    ----------
    path : str or path-like
        The output archive ``OUT``.
    fingerprint : str
        The fingerprint of the run about to write it.
    overwrite : bool
        Replace whatever is there (``--overwrite``).
    inventory_source : str, optional
        The run's inventory, named in the message.

    Raises
    ------
    ArchiveError
        When ``OUT`` exists and is not an archive of this same campaign (same
        fingerprint): one line naming both campaigns (created date, inventory,
        fingerprint), or saying ``OUT`` is not a readable rockscreen archive.
    """
    path = Path(path)
    if overwrite or not path.exists():
        return

    shown = printable(os.fspath(path))
    this = f"inventory {printable(inventory_source or 'unknown')}, fingerprint {fingerprint[:12]}"
    hint = "choose another --out, or pass --overwrite to replace it"
    try:
        meta = read_metadata(path)
    except ArchiveError:
        raise ArchiveError(
            f"{shown} exists and is not a readable rockscreen archive; {hint}"
        ) from None
    if meta.get("fingerprint") == fingerprint:
        return
    raise ArchiveError(
        f"{shown} holds another campaign ({_describe(meta)}) than this run ({this}); {hint}"
    )


def check_output(
    path: str | os.PathLike,
    inputs: Sequence[str | os.PathLike | None] = (),
    *,
    overwrite: bool | None = False,
    option: str = "--out",
    keep_archives: bool = False,
) -> Path:
    """Refuse an output file that would destroy something, before any work is done.

    Parameters
    ----------
    path : str or path-like
        The file the command is about to write.
    inputs : sequence of str or path-like
        The files the command reads (None entries are skipped): ``path`` must be none of
        them, whatever ``overwrite`` says (same file by :func:`os.path.samefile`, so a
        symbolic or hard link to an input is caught too).
    overwrite : bool or None
        True: replace an existing ``path`` (``--overwrite``); False: refuse it; None: leave
        the decision to the caller (``run`` resumes or checks the campaign itself).
    option : str
        The option that names ``path``, quoted in the messages.
    keep_archives : bool
        Refuse an existing HDF5 file even with ``overwrite`` (a CSV, PNG or HTML writer
        replaces its own kind of file, never an archive).

    Returns
    -------
    pathlib.Path
        ``path``.

    Raises
    ------
    ArchiveError
        One line naming the file and the option: ``path`` is an input, exists (without
        ``overwrite``), or its folder is missing or not writable.
    """
    path = Path(path)
    shown = printable(os.fspath(path))
    for source in inputs:
        if source is None:
            continue
        # realpath, not Path.resolve: a symbolic link loop among the inputs (a record the
        # run reports and skips) must not raise here.
        same = os.path.realpath(os.path.abspath(path)) == os.path.realpath(os.path.abspath(source))
        with contextlib.suppress(OSError):
            same = same or os.path.samefile(path, source)
        if same:
            raise ArchiveError(
                f"{option} {shown} is also an input of this command ({printable(source)}); "
                f"refused: writing it would destroy the input, choose another {option}"
            )
    if path.exists() or path.is_symlink():
        if path.is_dir():
            raise ArchiveError(f"{option} {shown} is a folder; give a file name")
        if keep_archives and is_hdf5(path):
            raise ArchiveError(
                f"{option} {shown} is an HDF5 archive; refused: it is not replaced by this "
                f"file, choose another {option}"
            )
        if overwrite is False:
            raise ArchiveError(
                f"{option} {shown} exists; choose another {option}, or pass --overwrite "
                "to replace it"
            )
    folder = path.absolute().parent
    if not folder.is_dir():
        raise ArchiveError(f"{option} {shown}: folder {printable(folder)} does not exist")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise ArchiveError(f"{option} {shown}: folder {printable(folder)} is not writable")
    return path


@contextlib.contextmanager
def claimed_output(
    path: str | os.PathLike,
    inputs: Sequence[str | os.PathLike | None],
    command: str,
    *,
    overwrite: bool | None,
) -> Iterator[Path]:
    """Check a command's output archive and hold its lock for the duration of the block.

    :func:`check_output` (never one of ``inputs``, an existing file only with
    ``overwrite``, a writable folder), then :func:`archive_lock` (one ``command`` per
    output), both before any work.

    Parameters
    ----------
    path : str or path-like
        The archive the command writes (``--out``).
    inputs : sequence of str or path-like
        The files the command reads (None entries skipped).
    command : str
        The rockscreen command (``run``, ``assess``, ``scenario``, ``sweep``).
    overwrite : bool or None
        As :func:`check_output` (None: the command checks an existing archive itself).

    Yields
    ------
    pathlib.Path
        ``path``.

    Raises
    ------
    ArchiveError
        As :func:`check_output` and :func:`archive_lock`.
    """
    path = check_output(path, inputs, overwrite=overwrite)
    with archive_lock(path, command):
        yield path
