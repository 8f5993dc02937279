"""Ctrl-C or SIGTERM while ``run`` starts its workers: one line, no worker traceback (issue 24).

A real ``rockscreen run --example --jobs 2`` in its own process group; the signal goes to
the whole group (as Ctrl-C from a terminal does) as soon as a worker process exists, while
the workers are still importing.
"""

from __future__ import annotations

import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="uses /proc")


def _children(pid: int) -> list[str]:
    """Return the command lines of the child processes of ``pid``."""
    out = []
    for task in Path(f"/proc/{pid}/task").glob("*"):
        try:
            kids = (task / "children").read_text().split()
        except OSError:
            continue
        for kid in kids:
            try:
                out.append(Path(f"/proc/{kid}/cmdline").read_bytes().replace(b"\0", b" ").decode())
            except OSError:
                pass
    return out


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_a_stop_while_workers_start_prints_one_line(tmp_path, signum):
    exe = shutil.which("rockscreen", path=os.path.dirname(sys.executable))
    command = [exe] if exe else [sys.executable, "-m", "rockscreen.pipeline"]
    proc = subprocess.Popen(
        [*command, "run", "--example", "--jobs", "2", "-q"],
        cwd=tmp_path,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        start_new_session=True,
    )
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and proc.poll() is None:
        if any("spawn_main" in line for line in _children(proc.pid)):
            break
        time.sleep(0.02)
    else:
        proc.kill()
        pytest.fail("no worker process started")
    time.sleep(0.3)  # the workers are importing the stack
    os.killpg(proc.pid, signum)
    _, err = proc.communicate(timeout=120)
    lines = err.decode("utf-8", "replace").strip().splitlines()
    assert proc.returncode == 128 + signum, lines
    assert len(lines) == 1, lines
    assert lines[0].startswith(f"rockscreen: interrupted ({signal.Signals(signum).name})")
