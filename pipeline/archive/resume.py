"""Checking a work file (``OUT.part``) before a run resumes it, in a child process.

A run killed mid-write or stopped by a full disk can leave a ``.part`` whose root
attributes look right (fingerprint, committed row counts) while its data or its HDF5
metadata are damaged; reading it can then raise, or crash libhdf5 itself (a segfault
kills the whole Python process). :func:`verify_part` therefore opens the work file in a
separate Python process that reads every committed row of every column, and reports;
the run resumes only when the child says the file is sound, and discards it otherwise.

Run as ``python -m rockscreen.pipeline.archive.resume PART FINGERPRINT``: prints one JSON object
``{"ok": true, "committed": {...}, "done": [...]}`` or ``{"ok": false, "reason": "..."}``.
``python -m rockscreen.pipeline.archive.resume PART --assess`` checks the work file of
``rockscreen assess`` (:mod:`rockscreen.pipeline.archive.assess_part`) the same way: prints
``{"ok": true, "fingerprint": ..., "inputs": {...}, "committed": N}`` or a reason.

What both work files share lives here too: their name (:func:`part_path`), their life as
an open file (:class:`PartFile`: opened for writing in a ``with`` block, removed, what a
resume found), the HDF5 signature (:func:`is_hdf5`) and what a full disk looks like
(:func:`is_disk_full`). They stay two layouts: ``run``'s is the campaign archive itself
being written (its tables and time histories, copied sorted into ``OUT`` when complete),
``assess``'s a journal of finished towers (each one exact text) from which a separate
writer makes ``OUT`` once every tower is in (its ranks and record sets need them all).
"""

from __future__ import annotations

import errno
import hashlib
import json
import os
import signal
import subprocess
import sys
from pathlib import Path
from typing import Any

import h5py
import numpy as np

__all__ = [
    "ASSESS_PART_FORMAT",
    "NOT_AN_ASSESS_PART",
    "VERIFY_TIMEOUT_S",
    "PartFile",
    "is_disk_full",
    "is_hdf5",
    "part_path",
    "verify_assess_part",
    "verify_part",
]

#: Longest a check may take before the work file is judged unusable, in seconds.
VERIFY_TIMEOUT_S = 600.0
_TABLES = ("results", "summary", "failures", "histories/index")
#: The ``format`` attribute of an assess work file.
ASSESS_PART_FORMAT = "rockscreen-assess-part"
_ASSESS_COLUMNS = ("index", "id", "result", "sha256")
#: The reason :func:`verify_assess_part` gives for an HDF5 file that is no assess work file.
NOT_AN_ASSESS_PART = "it is not the work file of a rockscreen assess"
_ARRAYS = ("t", "theta", "u", "regime")


def part_path(path: str | os.PathLike) -> Path:
    """Return the work file of an archive: ``OUT`` + ``.part``."""
    path = Path(path)
    return path.with_name(path.name + ".part")


class PartFile:
    """A work file ``OUT.part``: its paths, what a resume found, the file open for writing.

    Opened for writing in a ``with`` block; :meth:`remove` deletes it. The work files of
    ``run`` (:class:`~rockscreen.pipeline.archive.campaign.ArchiveWriter`) and ``assess``
    (:class:`~rockscreen.pipeline.archive.assess_part.AssessJournal`) add their layout and
    ``n_done``: together, the work file of :class:`rockscreen.pipeline.execution.job.Job`.

    Parameters
    ----------
    path : str or path-like
        The final archive ``OUT``.

    Attributes
    ----------
    path, part : pathlib.Path
        The final archive and its work file ``OUT.part``.
    resumed : bool
        Whether an earlier work file of the same inputs was resumed.
    discarded : str
        Why an earlier work file was discarded (``""`` when none was).
    write_failed : bool
        Whether a write failed (its error already said what the file keeps).
    """

    def __init__(self, path: str | os.PathLike) -> None:
        self.path = Path(path)
        self.part = part_path(self.path)
        self.resumed = False
        self.discarded = ""
        self.write_failed = False
        self._file: h5py.File | None = None

    def __enter__(self) -> Any:
        self._file = h5py.File(self.part, "r+")
        return self

    def __exit__(self, *exc_info: object) -> None:
        self._close()

    def _close(self) -> None:
        if self._file is not None:
            try:
                self._file.close()
            except (OSError, RuntimeError):
                pass  # a failed write already reported; the file is checked on resume
            self._file = None

    def remove(self) -> None:
        """Delete the work file (the archive is written, or it keeps no tower)."""
        self._close()
        self.part.unlink(missing_ok=True)


def is_hdf5(path: str | os.PathLike) -> bool:
    """Whether ``path`` starts with the HDF5 signature (at offset 0, as rockscreen writes)."""
    try:
        with open(path, "rb") as stream:
            return stream.read(8) == b"\x89HDF\r\n\x1a\n"
    except OSError:
        return False


def is_disk_full(exc: BaseException) -> bool:
    """Whether a failed write failed for want of space (ENOSPC, EDQUOT, or libhdf5's text)."""
    text = str(exc)
    return getattr(exc, "errno", None) in (errno.ENOSPC, errno.EDQUOT) or (
        "No space left" in text or "errno = 28" in text or "Disk quota" in text
    )


def _check(part: str, fingerprint: str) -> dict[str, Any]:
    """Read everything committed in ``part``; return the verdict (runs in the child)."""
    with h5py.File(part, "r") as f:
        if f.attrs.get("fingerprint") != fingerprint:
            return {"ok": False, "reason": "it belongs to other inputs (another fingerprint)"}
        committed = json.loads(f.attrs["committed"])
        if not isinstance(committed, dict) or not all(
            isinstance(committed.get(k), int) and committed[k] >= 0
            for k in (*_TABLES, "histories/data")
        ):
            return {"ok": False, "reason": "its committed row counts are malformed"}
        for name in ("towers", "records"):

            def visit(key: str, obj: Any) -> None:
                if isinstance(obj, h5py.Dataset):
                    obj[()]

            f[name].visititems(visit)
        for table in _TABLES:
            n = committed[table]
            for column in f[table]:
                ds = f[table][column]
                if ds.ndim != 1 or ds.shape[0] < n:
                    return {"ok": False, "reason": f"/{table}/{column} lacks committed rows"}
                data = ds.asstr()[:n] if h5py.check_string_dtype(ds.dtype) else ds[:n]
                del data
        n = committed["histories/data"]
        for name in _ARRAYS:
            ds = f["histories"][name]
            if ds.ndim != 1 or ds.shape[0] < n:
                return {"ok": False, "reason": f"/histories/{name} lacks committed rows"}
            for start in range(0, n, 1 << 22):
                ds[start : min(n, start + (1 << 22))]
        index = f["histories/index"]
        k = committed["histories/index"]
        ends = index["start"][:k] + index["count"][:k]
        if k and (int(np.max(ends)) > n or int(np.min(index["start"][:k])) < 0):
            return {"ok": False, "reason": "its history index points past the committed rows"}
        done = list(f["summary/id"].asstr()[: committed["summary"]])
    return {"ok": True, "committed": committed, "done": done}


def _check_assess(part: str) -> dict[str, Any]:
    """Read every committed tower of an assess work file; return the verdict (in the child)."""
    with h5py.File(part, "r") as f:
        if f.attrs.get("format") != ASSESS_PART_FORMAT:
            return {"ok": False, "reason": NOT_AN_ASSESS_PART}
        committed = int(f.attrs["committed"])
        inputs = json.loads(f.attrs["inputs"])
        fingerprint = str(f.attrs["fingerprint"])
        if committed < 0 or not isinstance(inputs, dict):
            return {"ok": False, "reason": "its committed tower count is malformed"}
        for name in _ASSESS_COLUMNS:
            ds = f["towers"][name]
            if ds.ndim != 1 or ds.shape[0] < committed:
                return {"ok": False, "reason": f"/towers/{name} lacks committed rows"}
        f["towers/index"][:committed]
        f["towers/id"].asstr()[:committed]
        texts = f["towers/result"].asstr()[:committed]
        sums = f["towers/sha256"].asstr()[:committed]
        for i, (text, digest) in enumerate(zip(texts, sums, strict=True)):
            if hashlib.sha256(text.encode("utf-8")).hexdigest() != digest:
                return {"ok": False, "reason": f"tower {i + 1}'s result fails its checksum"}
            json.loads(text)
    return {"ok": True, "fingerprint": fingerprint, "inputs": inputs, "committed": committed}


def _run_child(arguments: list[str], timeout: float) -> tuple[dict[str, Any] | None, str]:
    """Run this module in a child process; return its verdict, or None and why not."""
    command = [sys.executable, "-m", "rockscreen.pipeline.archive.resume", *arguments]
    try:
        proc = subprocess.run(command, capture_output=True, text=True, timeout=timeout, check=False)
    except subprocess.TimeoutExpired:
        return None, f"checking it took over {timeout:.0f} s"
    except OSError as exc:
        return None, f"it could not be checked ({exc})"
    if proc.returncode < 0:
        try:
            name = signal.Signals(-proc.returncode).name
        except ValueError:
            name = f"signal {-proc.returncode}"
        return None, f"reading it crashed the HDF5 library ({name})"
    try:
        verdict = json.loads(proc.stdout.strip().splitlines()[-1])
    except (ValueError, IndexError):
        return None, f"reading it failed (exit code {proc.returncode})"
    if not verdict.get("ok"):
        return None, str(verdict.get("reason", "it is unreadable"))
    return verdict, ""


def verify_assess_part(
    part: str | os.PathLike, *, timeout: float = VERIFY_TIMEOUT_S
) -> tuple[dict[str, Any] | None, str]:
    """Check the work file of ``rockscreen assess`` in a child process.

    Parameters
    ----------
    part : str or path-like
        The work file ``OUT.part``.
    timeout : float
        Seconds before the check is abandoned (the file is then judged unusable).

    Returns
    -------
    (dict or None, str)
        ``({"fingerprint": str, "inputs": dict, "committed": int}, "")`` when every
        committed tower can be read, else ``(None, reason)`` (a crash of the HDF5 library
        included). The caller compares the fingerprint with its own.
    """
    verdict, reason = _run_child([os.fspath(part), "--assess"], timeout)
    if verdict is None:
        return None, reason
    verdict.pop("ok", None)
    return verdict, ""


def verify_part(
    part: str | os.PathLike, fingerprint: str, *, timeout: float = VERIFY_TIMEOUT_S
) -> tuple[dict[str, Any] | None, str]:
    """Check a work file in a child process.

    Parameters
    ----------
    part : str or path-like
        The work file ``OUT.part``.
    fingerprint : str
        The fingerprint of the run that wants to resume it.
    timeout : float
        Seconds before the check is abandoned (the file is then judged unusable).

    Returns
    -------
    (dict or None, str)
        ``({"committed": {...}, "done": [...]}, "")`` when the file can be resumed, else
        ``(None, reason)`` with a short reason (a crash of the HDF5 library included).
    """
    verdict, reason = _run_child([os.fspath(part), fingerprint], timeout)
    if verdict is None:
        return None, reason
    return {"committed": verdict["committed"], "done": verdict["done"]}, ""


def _main(argv: list[str]) -> int:
    part, fingerprint = argv
    try:
        verdict = _check_assess(part) if fingerprint == "--assess" else _check(part, fingerprint)
    except Exception as exc:  # noqa: BLE001 - any failure means: do not resume
        text = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        verdict = {"ok": False, "reason": f"it is unreadable ({text[:200]})"}
    sys.stdout.write(json.dumps(verdict) + "\n")
    return 0


if __name__ == "__main__":  # pragma: no cover - run in a child process by verify_part
    sys.exit(_main(sys.argv[1:]))
