"""Ctrl-C or SIGTERM while ``run`` starts its workers: one line, no worker traceback (issue 24).

A real ``rockscreen run --jobs 2`` in its own process group; the signal goes to the whole
group (as Ctrl-C from a terminal does) as soon as a worker process exists, while the workers
are still importing. The run screens the example's records against the example towers
repeated :data:`COPIES` times, so that it cannot end before the signal reaches it however
slowly the machine runs this test (``run --example`` alone lasts about 3 s).

The run starts with SIGINT at its default action, as a command typed in a terminal has it:
a shell without job control starts a background job (``pytest &``) with SIGINT ignored,
its children inherit that, and Python then keeps Ctrl-C ignored (POSIX; a run started so
finished with exit 0 and no line, which is right for it, not for this test).
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

from rockscreen.stations.inventory import example_inventory_path

#: Copies of the example towers in the interrupted run (minutes of work on two workers).
COPIES = 40

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


def _default_interrupts() -> None:
    """Give the child SIGINT's default action whatever this test process inherited."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def _many_towers(path: Path) -> Path:
    """Write the example inventory with its towers repeated :data:`COPIES` times."""
    header, *rows = example_inventory_path().read_text(encoding="utf-8").splitlines()
    out = [header]
    for k in range(COPIES):
        out += [row.replace(",", f"-{k},", 1) for row in rows if row.strip()]
    path.write_text("\n".join(out) + "\n", encoding="utf-8")
    return path


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM])
def test_a_stop_while_workers_start_prints_one_line(tmp_path, signum):
    exe = shutil.which("rockscreen", path=os.path.dirname(sys.executable))
    command = [exe] if exe else [sys.executable, "-m", "rockscreen.pipeline"]
    # The example's records, written by a first (uninterrupted) example run.
    subprocess.run(
        [*command, "run", "--example", "--jobs", "1", "-q", "--out", "first.h5"],
        cwd=tmp_path,
        check=True,
        capture_output=True,
    )
    records = sorted(str(p) for p in (tmp_path / "rockscreen-example").glob("*.mseed"))
    stations = tmp_path / "rockscreen-example" / "XX.stations.xml"
    towers = _many_towers(tmp_path / "towers.csv")
    proc = subprocess.Popen(
        [*command, "run", *records, "--stations", str(stations), "--towers", str(towers)]
        + ["--jobs", "2", "-q", "--out", "stopped.h5"],
        cwd=tmp_path,
        preexec_fn=_default_interrupts,
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
    assert proc.poll() is None, "the run ended before the signal: the test's workload is too small"
    os.killpg(proc.pid, signum)
    _, err = proc.communicate(timeout=120)
    lines = err.decode("utf-8", "replace").strip().splitlines()
    assert proc.returncode == 128 + signum, lines
    assert len(lines) == 1, lines
    assert lines[0].startswith(f"rockscreen: interrupted ({signal.Signals(signum).name})")
