"""The Dask executor: a real scheduler and worker processes on loopback, same results."""

from __future__ import annotations

import math
import re
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from rockscreen.pipeline.archive import risk_reader, sweep_archive
from rockscreen.pipeline.archive.campaign import read_results, read_summary
from rockscreen.pipeline.cli import main
from rockscreen.pipeline.errors import DistributedError
from rockscreen.pipeline.execution.dask_cluster import DaskExecutor, check_address

distributed = pytest.importorskip("distributed")

# distributed warns (UserWarning) when creating a worker's scratch directory takes long,
# which happens on a loaded CI machine; it says nothing about the results compared here.
pytestmark = pytest.mark.filterwarnings(
    "ignore:Creating scratch directories is taking a surprisingly long time:UserWarning"
)

# Seconds the cluster may take to start or stop before the test fails instead of hanging.
CLUSTER_TIMEOUT_S = 60


def run_cli(folder: Path, *options: str) -> list[dict]:
    """``rockscreen run --example`` in ``folder``; return the archive's summary rows."""
    folder.mkdir()
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(folder)
        result = CliRunner().invoke(main, ["run", "--example", *options])
    assert result.exit_code == 0, result.output
    return read_summary(folder / "rockscreen-example.h5")


def same(a, b) -> bool:
    if isinstance(a, float) and isinstance(b, float):
        return (math.isnan(a) and math.isnan(b)) or a == b
    return a == b


@pytest.fixture(scope="module")
def cluster():
    """A scheduler and two single-threaded worker processes, on 127.0.0.1 only."""
    cluster = distributed.LocalCluster(
        n_workers=2,
        threads_per_worker=1,
        processes=True,
        host="127.0.0.1",
        dashboard_address="127.0.0.1:0",  # a free port: never the shared default 8787
        timeout=CLUSTER_TIMEOUT_S,
    )
    try:
        yield cluster
    finally:
        cluster.close(timeout=CLUSTER_TIMEOUT_S)


# Worker processes are spawned while pytest runs: the multiprocessing resource tracker
# and distributed's nanny may warn about leaked semaphores or a slow shutdown of the
# throwaway cluster; neither concerns the results compared here.
@pytest.mark.slow
def test_scheduler_run_matches_the_local_run_tower_by_tower(cluster, tmp_path):
    local = run_cli(tmp_path / "local", "--jobs", "1")
    remote = run_cli(tmp_path / "dask", "--scheduler", cluster.scheduler_address, "--jobs", "3")

    assert [row["id"] for row in remote] == [row["id"] for row in local]
    assert len(local) >= 5
    for mine, theirs in zip(remote, local, strict=True):
        for column, value in theirs.items():
            assert same(mine[column], value), (mine["id"], column, mine[column], value)
    # Every case, not only the governing ones.
    cases = [read_results(tmp_path / name / "rockscreen-example.h5") for name in ("dask", "local")]
    assert len(cases[0]) == len(cases[1]) > len(local)
    for mine, theirs in zip(*cases, strict=True):
        assert all(same(mine[k], v) for k, v in theirs.items()), (mine, theirs)


@pytest.mark.slow
def test_assess_on_the_scheduler_matches_the_local_assess(cluster, tmp_path):
    """The risk stage's chunks (record sets, then stripes) give the same tables on Dask."""
    assess = ["assess", "--example", "--return-periods", "101,475,2475", "--records", "3"]
    assess.append("--allow-noncompliant")  # 3 records: not NTC 2018 §7.3.5, run marked
    tables = {}
    for name, options in (
        ("local", ["--jobs", "1"]),
        ("dask", ["--scheduler", cluster.scheduler_address]),
    ):
        (tmp_path / name).mkdir()
        with pytest.MonkeyPatch.context() as mp:
            mp.chdir(tmp_path / name)
            result = CliRunner().invoke(main, [*assess, *options])
        assert result.exit_code == 0, result.output
        archive = tmp_path / name / "rockscreen-assess-example.h5"
        tables[name] = (risk_reader.read_summary(archive), risk_reader.read_stripes(archive))
    (local_summary, local_stripes), (dask_summary, dask_stripes) = tables["local"], tables["dask"]
    assert "Dask cluster at" in result.output
    assert len(local_summary) >= 5 and len(local_stripes) > len(local_summary)
    for mine, theirs in zip(
        [*dask_summary, *dask_stripes], [*local_summary, *local_stripes], strict=True
    ):
        assert mine.keys() == theirs.keys()
        for column, value in theirs.items():
            assert same(mine[column], value), (theirs.get("id"), column, mine[column], value)


def test_scheduler_option_notes_that_jobs_is_ignored(cluster, tmp_path):
    (tmp_path / "run").mkdir()
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(tmp_path / "run")
        result = CliRunner().invoke(
            main, ["run", "--example", "--scheduler", cluster.scheduler_address, "--jobs", "4"]
        )
    assert result.exit_code == 0, result.output
    assert "--jobs 4 is ignored with --scheduler" in result.output
    assert f"Dask cluster at {cluster.scheduler_address} (2 worker threads)" in result.output


SWEEP_STUDY = """
[tower]
name = "dask sweep"
width_m = 2.06
height_m = 5.80

[[group]]
name = "pulse"
model = "rocking"
excitation = "pulse"
shape = "one-sine"
amplitudes = ["1.5g", "2.25g", "3g"]
frequencies_hz = [4, 7.98]
"""


@pytest.mark.slow
def test_sweep_on_the_scheduler_matches_the_local_sweep(cluster, tmp_path):
    """``rockscreen sweep --scheduler`` takes the same route as run and assess."""
    study = tmp_path / "study.toml"
    study.write_text(SWEEP_STUDY, encoding="utf-8")
    rows = {}
    for name, options in (
        ("local", ["--jobs", "1"]),
        ("dask", ["--scheduler", cluster.scheduler_address, "--jobs", "2"]),
    ):
        out = tmp_path / f"{name}.h5"
        result = CliRunner().invoke(main, ["sweep", str(study), "--out", str(out), *options])
        assert result.exit_code == 0, result.output
        rows[name] = sweep_archive.read_cases(out)
    assert "--jobs 2 is ignored with --scheduler" in result.output
    assert f"Dask cluster at {cluster.scheduler_address} (2 worker threads)" in result.output
    assert len(rows["local"]) == 6
    for mine, theirs in zip(rows["dask"], rows["local"], strict=True):
        assert all(same(mine[k], v) for k, v in theirs.items()), (mine, theirs)


def test_unreachable_scheduler_stops_the_run_before_writing(tmp_path, monkeypatch):
    monkeypatch.setattr("rockscreen.pipeline.execution.dask_cluster.DEFAULT_TIMEOUT_S", 1.0)
    monkeypatch.chdir(tmp_path)
    result = CliRunner().invoke(main, ["run", "--example", "--scheduler", "tcp://127.0.0.1:9"])
    assert result.exit_code == 1
    assert "cannot reach the Dask scheduler at tcp://127.0.0.1:9 within 1 s" in result.output
    assert not list(tmp_path.glob("*.h5*"))


@pytest.mark.slow
def test_a_failing_chunk_raises_in_the_client(cluster):
    def work(shared, chunk):
        if chunk == "bad":
            raise ValueError(f"bad chunk with {shared}")
        return chunk.upper()

    with DaskExecutor(cluster.scheduler_address) as executor:
        executor.start(work, {"shared": "data"})
        executor.submit("ok")
        executor.submit("bad")
        with pytest.raises(ValueError, match=re.escape("bad chunk with {'shared': 'data'}")):
            list(executor.completed())


def test_unreachable_scheduler_names_the_address():
    # Port 9 (discard) on loopback: nothing listens there in a test environment.
    with pytest.raises(DistributedError, match=r"tcp://127\.0\.0\.1:9 within 1 s"):
        DaskExecutor("tcp://127.0.0.1:9", timeout=1).connect()


@pytest.mark.parametrize("address", ["127.0.0.1:8786", "", "http://host:8786", "tcp://", None])
def test_malformed_addresses_are_refused(address):
    with pytest.raises(DistributedError, match="not a Dask scheduler address"):
        check_address(address)


@pytest.mark.parametrize("timeout", [0, -1.0, math.nan, "10"])
def test_bad_timeout_is_refused(timeout):
    with pytest.raises(DistributedError, match="timeout"):
        DaskExecutor("tcp://127.0.0.1:8786", timeout=timeout)


def test_missing_distributed_says_how_to_install(monkeypatch):
    monkeypatch.setitem(sys.modules, "distributed", None)  # import raises ImportError
    with pytest.raises(DistributedError, match=r'pip install "rockscreen\[distributed\]"'):
        DaskExecutor("tcp://127.0.0.1:8786")


@pytest.mark.parametrize(
    "address", ["tcp://127.0.0.1:99999", "tcp://[::1", "tcp://256.1.1.1:1", "tcp://a b:1"]
)
def test_malformed_hosts_and_ports_are_refused_at_parse_time(address):
    with pytest.raises(DistributedError, match="not a Dask scheduler address") as info:
        check_address(address)
    assert "\n" not in str(info.value)


def test_valid_addresses_pass():
    for address in (
        "tcp://10.0.0.5:8786",
        "tcp://[::1]:8786",
        "tcp://node-01.cluster",
        "inproc://x",
    ):
        assert check_address(f" {address} ") == address


def test_a_port_that_accepts_but_never_answers_is_given_up(tmp_path):
    """A silent TCP server on loopback: one line after the timeout, not a hang."""
    import socket
    import threading

    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(8)
    server.settimeout(0.2)
    stop = threading.Event()
    accepted = []

    def accept() -> None:
        while not stop.is_set():
            try:
                accepted.append(server.accept()[0])  # accept, never answer
            except OSError:
                pass

    thread = threading.Thread(target=accept, daemon=True)
    thread.start()
    address = f"tcp://127.0.0.1:{server.getsockname()[1]}"
    outcome = []

    def connect() -> None:
        try:
            DaskExecutor(address, timeout=1).connect()
        except DistributedError as exc:
            outcome.append(exc)

    try:
        attempt = threading.Thread(target=connect, daemon=True)
        attempt.start()
        attempt.join(CLUSTER_TIMEOUT_S)  # generous bound: the call gives up after ~2 s
        assert not attempt.is_alive(), "connect() did not give up"
        assert accepted and len(outcome) == 1
        message = str(outcome[0])
        assert f"cannot reach the Dask scheduler at {address} within 1 s" in message
        assert "does not answer as a Dask scheduler" in message and "\n" not in message
    finally:
        stop.set()
        thread.join(CLUSTER_TIMEOUT_S)
        for conn in accepted:
            conn.close()
        server.close()


@pytest.mark.slow
def test_a_scheduler_killed_mid_run_is_one_line(tmp_path):
    import json
    import os
    import signal
    import subprocess
    import time

    dask = Path(sys.executable).parent / "dask"
    if not dask.exists():
        pytest.skip("the dask command is not installed beside this Python")
    # Port 0: the scheduler binds a free port itself and writes its address to a file (a
    # port probed free here could be taken by a concurrent test run before it binds).
    info_file = tmp_path / "scheduler.json"
    options = {"stdout": subprocess.DEVNULL, "stderr": subprocess.DEVNULL, "cwd": tmp_path}
    scheduler = subprocess.Popen(
        [dask, "scheduler", "--host", "127.0.0.1", "--port", "0"]
        + ["--dashboard-address", "127.0.0.1:0", "--no-show", "--scheduler-file", str(info_file)],
        start_new_session=True,
        **options,
    )
    deadline, address = time.monotonic() + CLUSTER_TIMEOUT_S, None
    while address is None and scheduler.poll() is None and time.monotonic() < deadline:
        try:
            address = json.loads(info_file.read_text())["address"]
        except (OSError, ValueError, KeyError):  # not written yet, or half written
            time.sleep(0.1)
    if address is None:
        os.killpg(scheduler.pid, signal.SIGKILL)
        scheduler.wait(CLUSTER_TIMEOUT_S)
        pytest.fail("the Dask scheduler did not start (no scheduler file)")
    worker = subprocess.Popen(
        [dask, "worker", address, "--nthreads", "1", "--no-dashboard", "--no-nanny"],
        start_new_session=True,
        **options,
    )

    def work(shared, seconds):
        import time

        time.sleep(seconds)
        return seconds

    try:
        executor = DaskExecutor(address, timeout=CLUSTER_TIMEOUT_S)
        with executor:
            executor.start(work, None)
            executor.submit(0)
            for seconds in (30, 30, 30):
                executor.submit(seconds)
            results = executor.completed()
            assert next(results) == 0
            os.killpg(scheduler.pid, signal.SIGKILL)
            with pytest.raises(DistributedError) as info:
                next(results)
        message = str(info.value)
        assert message == (
            f"the Dask scheduler at {address} stopped answering; the partial archive is "
            "kept; rerun to resume"
        )
    finally:
        for process in (scheduler, worker):
            if process.poll() is None:
                os.killpg(process.pid, signal.SIGKILL)
            process.wait(CLUSTER_TIMEOUT_S)


def test_a_worker_lost_mid_run_is_one_line_not_a_traceback():
    """A task cancelled for lost dependencies (a worker SIGKILLed with the scattered data,
    as the reliability audit's area 6 does) or one that killed its workers: one line."""
    import concurrent.futures
    import types

    class KilledWorker(Exception):
        pass

    class Future:
        def __init__(self, exc):
            self.exc = exc

        def result(self):
            raise self.exc

        def release(self):
            pass

    lost = concurrent.futures.CancelledError(
        "run_with_single_threaded_blas-567d cancelled for reason: lost dependencies."
    )
    for exc, reason in ((lost, "lost dependencies."), (KilledWorker("task x"), "task x")):
        executor = DaskExecutor.__new__(DaskExecutor)
        executor.address = "tcp://127.0.0.1:8786"
        executor._client = types.SimpleNamespace(status="running", loop=None)
        executor._distributed = types.SimpleNamespace(
            as_completed=lambda futures, loop: iter(futures), KilledWorker=KilledWorker
        )
        executor._futures = [Future(exc)]
        with pytest.raises(DistributedError) as info:
            next(executor.completed())
        assert str(info.value) == (
            "a worker of the Dask cluster at tcp://127.0.0.1:8786 was lost during the run "
            f"({reason}); the partial archive is kept; rerun to resume"
        )
