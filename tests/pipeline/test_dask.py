"""The Dask executor: a real scheduler and worker processes on loopback, same results."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import pytest

from pipeline import __version__
from pipeline.archive import ArchiveWriter, read_results, read_summary
from pipeline.campaign import CampaignShared, fingerprint, pair, prepare_records, run_campaign
from pipeline.config import CampaignConfig
from pipeline.dask_executor import DaskExecutor, DistributedError, check_address
from pipeline.executors import SerialExecutor
from pipeline.synthetic import write_example_records
from stations.inventory import example_inventory_path, inventory_table, read_inventory

distributed = pytest.importorskip("distributed")

# distributed warns (UserWarning) when creating a worker's scratch directory takes long,
# which happens on a loaded CI machine; it says nothing about the results compared here.
pytestmark = pytest.mark.filterwarnings(
    "ignore:Creating scratch directories is taking a surprisingly long time:UserWarning"
)

# Seconds the cluster may take to start or stop before the test fails instead of hanging.
CLUSTER_TIMEOUT_S = 60


def screen(records: list[Path], xml: Path, out: Path, executor) -> list[dict]:
    """Run the example campaign as ``rockscreen run`` does; return the summary rows."""
    towers = read_inventory(example_inventory_path())
    motions, failures = prepare_records([str(p) for p in records], stations=str(xml))
    assert not failures
    config = CampaignConfig()
    tasks, pair_failures = pair(towers, motions, max_distance_km=config.pairing.max_distance_km)
    table = inventory_table(towers)
    writer = ArchiveWriter(
        out,
        fingerprint=fingerprint(table, motions, config, __version__),
        metadata={"rockscreen_version": __version__},
        towers_table=table,
        motions=motions,
        failures=pair_failures,
    )
    with writer:
        run_campaign(tasks, CampaignShared(motions, config), writer, executor, jobs=2, chunk_size=2)
    writer.finalize()
    return read_summary(out)


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
        dashboard_address=None,
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
def test_dask_run_matches_the_local_run_tower_by_tower(cluster, tmp_path):
    records, xml = write_example_records(tmp_path / "records")
    local = screen(records, xml, tmp_path / "local.h5", SerialExecutor())
    with DaskExecutor(cluster.scheduler_address) as executor:
        assert executor.jobs == 2
        remote = screen(records, xml, tmp_path / "dask.h5", executor)

    assert [row["id"] for row in remote] == [row["id"] for row in local]
    assert len(local) >= 5
    for mine, theirs in zip(remote, local, strict=True):
        for column, value in theirs.items():
            assert same(mine[column], value), (mine["id"], column, mine[column], value)
    # Every case, not only the governing ones.
    for mine, theirs in zip(
        read_results(tmp_path / "dask.h5"), read_results(tmp_path / "local.h5"), strict=True
    ):
        assert all(same(mine[k], v) for k, v in theirs.items()), (mine, theirs)


@pytest.mark.slow
def test_a_failing_chunk_raises_in_the_client(cluster):
    def work(shared, chunk):
        if chunk == "bad":
            raise ValueError(f"bad chunk with {shared}")
        return chunk.upper()

    with DaskExecutor(cluster.scheduler_address) as executor:
        executor.start(work, "shared data")
        executor.submit("ok")
        executor.submit("bad")
        with pytest.raises(ValueError, match="bad chunk with shared data"):
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
