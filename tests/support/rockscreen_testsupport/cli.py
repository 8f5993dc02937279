"""The command line as a user runs it: ``python -m rockscreen.pipeline`` in a subprocess."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path


def run_rockscreen(*args, cwd: Path, timeout_s: float = 300.0) -> subprocess.CompletedProcess:
    """Run ``python -m rockscreen.pipeline ARGS`` in ``cwd`` and return the finished process.

    Parameters
    ----------
    *args
        The command's arguments (paths are passed as text).
    cwd : pathlib.Path
        The working folder.
    timeout_s : float
        Past this the process is killed and :class:`subprocess.TimeoutExpired` raised [s]:
        a guard against a hang, not a measure of speed.

    Returns
    -------
    subprocess.CompletedProcess
        Its return code, and its stdout and stderr as text.
    """
    command = [sys.executable, "-m", "rockscreen.pipeline", *map(str, args)]
    return subprocess.run(command, cwd=cwd, capture_output=True, text=True, timeout=timeout_s)
