"""Run ``rockscreen ARGS...`` and signal it right after its Nth archive chunk is flushed.

Usage: ``python kill_after_chunks.py N[:SIGNAL] ARGS...`` (default SIGKILL), or
``python kill_after_chunks.py N:pause READY ARGS...``: after the Nth chunk, create the file
``READY`` and wait there, so that the test sends a real signal from outside at a known
point, or ``python kill_after_chunks.py N:workers ARGS...``: after the Nth chunk, SIGKILL
the worker processes (a lost worker) and go on. A chunk is one append of ``rockscreen
run``'s archive writer or of ``rockscreen assess``'s work file (both committed and
flushed). The crash-safety tests use it to die, or be interrupted, like a killed process at
a known point; production code carries no test hook.
"""

import os
import signal
import sys
import time
from pathlib import Path

from rockscreen.pipeline.archive.assess_part import AssessJournal
from rockscreen.pipeline.archive.campaign import ArchiveWriter
from rockscreen.pipeline.cli import main


def _install(after: int, act) -> None:
    flushed = 0
    for cls in (ArchiveWriter, AssessJournal):
        original = cls.append

        def append(self, outcomes, _original=original):
            nonlocal flushed
            out = _original(self, outcomes)
            flushed += 1
            if flushed == after:
                act()
            return out

        cls.append = append


def _kill_workers() -> None:
    """SIGKILL this process's pool workers (not multiprocessing's resource tracker)."""
    me = os.getpid()
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            ppid = int((entry / "stat").read_text().rsplit(")", 1)[1].split()[1])
            command = (entry / "cmdline").read_bytes()
        except (OSError, IndexError, ValueError):
            continue
        if ppid == me and b"spawn_main" in command:
            os.kill(int(entry.name), signal.SIGKILL)


def _pause(ready: Path) -> None:
    ready.write_text(str(os.getpid()))
    while True:  # until the test's signal arrives
        time.sleep(0.1)


if __name__ == "__main__":
    count, _, name = sys.argv[1].partition(":")
    args = sys.argv[2:]
    if name == "pause":
        ready = Path(args.pop(0))
        _install(int(count), lambda: _pause(ready))
    elif name == "workers":
        _install(int(count), _kill_workers)
    else:
        signum = getattr(signal, name or "SIGKILL")
        _install(int(count), lambda: os.kill(os.getpid(), signum))
    sys.exit(main(args, prog_name="rockscreen"))
