"""Run ``rockscreen ARGS...`` and SIGKILL it right after its Nth archive chunk is flushed.

Usage: ``python kill_after_chunks.py N ARGS...``. The crash-safety tests use it to die
like a killed process at a known point; production code carries no test hook.
"""

import os
import signal
import sys

from pipeline.archive.campaign import ArchiveWriter
from pipeline.cli import main


def _install(after: int) -> None:
    original = ArchiveWriter.append
    flushed = 0

    def append(self, outcomes):
        nonlocal flushed
        original(self, outcomes)
        flushed += 1
        if flushed >= after:
            os.kill(os.getpid(), signal.SIGKILL)

    ArchiveWriter.append = append


if __name__ == "__main__":
    _install(int(sys.argv[1]))
    sys.exit(main(sys.argv[2:], prog_name="rockscreen"))
