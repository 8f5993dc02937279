"""Run ``rockscreen ARGS...`` and signal it right after its Nth archive chunk is flushed.

Usage: ``python kill_after_chunks.py N[:SIGNAL] ARGS...`` (default SIGKILL). The
crash-safety tests use it to die, or be interrupted, like a killed process at a known
point; production code carries no test hook.
"""

import os
import signal
import sys

from rockscreen.pipeline.archive.campaign import ArchiveWriter
from rockscreen.pipeline.cli import main


def _install(after: int, signum: int) -> None:
    original = ArchiveWriter.append
    flushed = 0

    def append(self, outcomes):
        nonlocal flushed
        original(self, outcomes)
        flushed += 1
        if flushed >= after:
            os.kill(os.getpid(), signum)

    ArchiveWriter.append = append


if __name__ == "__main__":
    count, _, name = sys.argv[1].partition(":")
    _install(int(count), getattr(signal, name or "SIGKILL"))
    sys.exit(main(sys.argv[2:], prog_name="rockscreen"))
