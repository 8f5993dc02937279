"""Local executors: worker processes end with their parent; --jobs is capped."""

from __future__ import annotations

import ast
import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from rockscreen.pipeline.execution import local
from rockscreen.pipeline.execution.local import (
    ProcessExecutor,
    SerialExecutor,
    cap_jobs,
    make_executor,
)

# Generous bound for processes to start and to disappear: it only stops a broken test
# from hanging; a passing run takes a few seconds.
WAIT_S = 120.0

PARENT = textwrap.dedent(
    """
    import json, multiprocessing, os, sys, time
    from rockscreen.pipeline.execution.local import ProcessExecutor


    def work(shared, seconds):
        time.sleep(seconds)
        return os.getpid()


    if __name__ == "__main__":
        with ProcessExecutor(2) as executor:
            executor.start(work, None)
            for _ in range(2):
                executor.submit(0.5)
            pids = sorted(set(executor.completed()))
            for _ in range(4):
                executor.submit(3600)  # the workers are busy when the parent dies
            children = [p.pid for p in multiprocessing.active_children()]
            print(json.dumps(sorted(set(pids + children))), flush=True)
            time.sleep(3600)
    """
)


def alive(pid: int) -> bool:
    """Whether ``pid`` runs (a zombie, dead but not yet reaped, counts as ended)."""
    try:
        state = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0]
    except (FileNotFoundError, ProcessLookupError, IndexError):
        return False
    return state not in {"Z", "X"}


@pytest.mark.skipif(not Path("/proc/self/stat").exists(), reason="needs /proc (Linux)")
@pytest.mark.parametrize("sig", [signal.SIGKILL, signal.SIGTERM])
def test_workers_end_when_their_parent_is_killed(tmp_path, sig):
    script = tmp_path / "parent.py"
    script.write_text(PARENT, encoding="utf-8")
    parent = subprocess.Popen(
        [sys.executable, str(script)], stdout=subprocess.PIPE, text=True, cwd=tmp_path
    )
    try:
        line = parent.stdout.readline()
        workers = json.loads(line)
        assert workers and parent.pid not in workers
        assert all(alive(pid) for pid in workers)
        os.kill(parent.pid, sig)
        parent.wait(timeout=WAIT_S)
        deadline = time.monotonic() + WAIT_S
        while any(alive(pid) for pid in workers) and time.monotonic() < deadline:
            time.sleep(0.2)
        assert not [pid for pid in workers if alive(pid)]
    finally:
        if parent.poll() is None:
            parent.kill()
            parent.wait()
        parent.stdout.close()


def test_watch_parent_exits_an_orphan(tmp_path):
    # The portable fallback alone (no Linux death signal): a grandchild whose parent
    # exits at once must notice and end.
    code = textwrap.dedent(
        """
        import os, subprocess, sys, time
        child = subprocess.Popen([sys.executable, "-c", '''
        import os, sys, time
        from rockscreen.pipeline.execution.local import watch_parent
        watch_parent(int(sys.argv[1]), interval=0.1, death_signal=False)
        print(os.getpid(), flush=True)
        time.sleep(3600)
        ''', str(os.getpid())], stdout=subprocess.PIPE, text=True)
        print(child.stdout.readline().strip(), flush=True)
        os._exit(0)
        """
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=WAIT_S
    )
    pid = int(out.stdout.strip())
    deadline = time.monotonic() + WAIT_S
    while alive(pid) and time.monotonic() < deadline:
        time.sleep(0.2)
    assert not alive(pid)


def test_jobs_are_capped_per_cpu_and_by_the_chunks(monkeypatch):
    monkeypatch.setattr(local, "default_jobs", lambda: 2)
    assert cap_jobs(3) == (3, "")
    assert cap_jobs(10000) == (8, "--jobs 10000 capped at 8 (4 per CPU, 2 CPUs)")
    assert cap_jobs(6, n_tasks=2) == (2, "--jobs 6 capped at 2 (2 chunks to compute)")
    assert cap_jobs(1, n_tasks=0) == (1, "")
    executor = make_executor(10000)
    assert isinstance(executor, ProcessExecutor) and executor.jobs == 8
    assert executor.note == "--jobs 10000 capped at 8 (4 per CPU, 2 CPUs)"
    executor = make_executor(5, n_tasks=1)
    assert isinstance(executor, SerialExecutor) and "capped at 1" in executor.note
    assert make_executor(2).note == ""


@pytest.mark.parametrize("jobs", [0, -3, 2.5, True, "4"])
def test_bad_jobs_are_refused(jobs):
    with pytest.raises(ValueError, match="must be an integer >= 1"):
        make_executor(jobs)


BLAS_WORKER = textwrap.dedent(
    """
    import ctypes, json, os, sys
    from rockscreen.pipeline.execution.choose import open_executor

    VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")


    def openblas_threads():
        # The thread count of the OpenBLAS numpy loaded (None: no OpenBLAS found).
        with open("/proc/self/maps") as maps:
            paths = {line.split()[-1] for line in maps if "openblas" in line.lower()}
        for path in sorted(p for p in paths if p.startswith("/")):
            lib = ctypes.CDLL(path)
            for name in ("scipy_openblas_get_num_threads64_", "openblas_get_num_threads64_",
                         "openblas_get_num_threads"):
                if hasattr(lib, name):
                    return getattr(lib, name)()
        return None


    def work(shared, chunk):
        import numpy as np

        np.ones((300, 300)) @ np.ones((300, 300))  # BLAS in use
        try:
            from threadpoolctl import threadpool_info
            pools = [pool["num_threads"] for pool in threadpool_info()]
        except ImportError:
            pools = None
        return {"env": {v: os.environ.get(v) for v in VARIABLES}, "openblas": openblas_threads(),
                "threadpoolctl": pools, "pid": os.getpid()}


    if __name__ == "__main__":
        before = {v: os.environ.get(v) for v in VARIABLES}
        executor, workers = open_executor(jobs=2, n_tasks=4)
        with executor:
            executor.start(work, None)
            for chunk in range(4):
                executor.submit(chunk)
            reports = list(executor.completed())
        after = {v: os.environ.get(v) for v in VARIABLES}
        print(json.dumps({"workers": workers, "reports": reports, "parent": [before, after],
                          "here": os.getpid()}))
    """
)


def _blas_reports(tmp_path_factory, source):
    """What two local workers report about their BLAS threads (``source`` as the main)."""
    script = tmp_path_factory.mktemp("blas") / "blas_worker.py"
    script.write_text(source, encoding="utf-8")
    env = {k: v for k, v in os.environ.items() if not k.endswith("_NUM_THREADS")}
    done = subprocess.run(
        [sys.executable, str(script)], capture_output=True, text=True, timeout=WAIT_S, env=env
    )
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


@pytest.fixture(scope="module")
def blas_reports(tmp_path_factory):
    """What two local workers report about their BLAS threads (a script as the user's main)."""
    return _blas_reports(tmp_path_factory, BLAS_WORKER)


def test_workers_of_a_script_that_imports_numpy_first_run_a_single_threaded_blas(
    tmp_path_factory,
):
    """A spawned worker imports the main module again before its initializer: numpy, imported
    at the script's top, has loaded its OpenBLAS before the variables were set; the
    initializer limits the loaded library itself."""
    reports = _blas_reports(tmp_path_factory, "import numpy\n" + BLAS_WORKER)["reports"]
    assert len(reports) == 4
    assert all(report["openblas"] in (None, 1) for report in reports)


def test_local_workers_run_a_single_threaded_blas(blas_reports):
    assert blas_reports["workers"] == 2
    reports = blas_reports["reports"]
    assert len(reports) == 4 and blas_reports["here"] not in {r["pid"] for r in reports}
    for report in reports:
        assert report["env"] == dict.fromkeys(local.BLAS_THREAD_VARIABLES, "1")
        assert report["openblas"] in (None, 1)  # None: numpy is not built on OpenBLAS
    # The parent's own environment is left alone.
    before, after = blas_reports["parent"]
    assert before == after == dict.fromkeys(local.BLAS_THREAD_VARIABLES)


def test_local_workers_blas_pools_report_one_thread(blas_reports):
    pytest.importorskip("threadpoolctl", reason="threadpoolctl is not installed")
    for report in blas_reports["reports"]:
        assert report["threadpoolctl"] and set(report["threadpoolctl"]) == {1}


# The executor classes and factories are used only through execution.choose.open_executor.
EXECUTOR_NAMES = {"ProcessPoolExecutor", "ProcessExecutor", "DaskExecutor", "make_executor"}


def test_the_executor_is_chosen_in_one_place():
    root = Path(__file__).resolve().parents[2]
    sources = [
        path
        for folder in ("pipeline", "solver", "stations", "benchmarks")
        for path in (root / folder).rglob("*.py")
        if "execution" not in path.relative_to(root).parts
    ]
    assert len(sources) > 50
    offenders = []
    for path in sources:
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = []
            if isinstance(node, ast.Name | ast.Attribute):
                names = [node.id if isinstance(node, ast.Name) else node.attr]
            elif isinstance(node, ast.ImportFrom | ast.Import):
                names = [alias.name.rsplit(".", 1)[-1] for alias in node.names]
            offenders += [
                f"{path.relative_to(root)}:{node.lineno}: {n}" for n in names if n in EXECUTOR_NAMES
            ]
    assert offenders == []


SERIAL_BLAS = textwrap.dedent(
    """
    import ctypes, json
    import numpy  # loads numpy's OpenBLAS
    from rockscreen.pipeline.execution import local


    def function(path, names):
        library = ctypes.CDLL(path)
        return next((getattr(library, n) for n in names if hasattr(library, n)), None)


    def counts():
        # Each loaded OpenBLAS library's thread count.
        getters = [function(p, local.OPENBLAS_GETTERS) for p in local.loaded_openblas()]
        return [int(getter()) for getter in getters if getter is not None]


    def work(shared, chunk):
        return counts()


    for path in local.loaded_openblas():
        function(path, local.OPENBLAS_SETTERS)(3)
    executor = local.SerialExecutor()
    with executor:
        executor.start(work, None)
        executor.submit(0)
        during = list(executor.completed())
    print(json.dumps({"before": [3] * len(counts()), "during": during[0], "after": counts()}))
    """
)


def test_the_serial_executor_computes_with_one_blas_thread_and_restores_the_count(tmp_path):
    """``--jobs 1``: each chunk runs with the loaded OpenBLAS at one thread; the process gets
    its own count back after it."""
    script = tmp_path / "serial_blas.py"
    script.write_text(SERIAL_BLAS, encoding="utf-8")
    env = {k: v for k, v in os.environ.items() if not k.endswith("_NUM_THREADS")}
    done = subprocess.run(
        [sys.executable, str(script)], capture_output=True, text=True, timeout=WAIT_S, env=env
    )
    assert done.returncode == 0, done.stderr
    report = json.loads(done.stdout)
    if not report["before"]:
        pytest.skip("numpy is not built on OpenBLAS")
    assert report["during"] == [1] * len(report["before"])
    assert report["after"] == report["before"]
