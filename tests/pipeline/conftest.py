"""Fixtures shared by the pipeline tests."""

from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from click.testing import CliRunner

from rockscreen.pipeline.archive.campaign import ArchiveWriter
from rockscreen.pipeline.cli import main
from rockscreen.pipeline.config import CampaignConfig
from rockscreen.pipeline.engine.motion import GroundMotion
from rockscreen.pipeline.engine.results import Failure
from rockscreen.pipeline.engine.solvers import Solvers
from rockscreen.pipeline.motion.synthetic import write_example_records
from rockscreen.pipeline.screening.campaign import chunk_tasks
from rockscreen.pipeline.screening.cases import CampaignShared, TowerTask
from rockscreen.pipeline.screening.evaluate import run_chunk
from rockscreen.solver.constants import G
from rockscreen.stations.inventory import Tower, example_inventory_path, inventory_table
from rockscreen.stations.inventory_columns import TEXT_COLUMNS
from rockscreen.stations.inventory_table import TABLE_COLUMNS, TABLE_RESOLVED


@pytest.fixture(scope="session")
def example_archive(tmp_path_factory):
    """The archive of ``rockscreen run --example`` (run once; tests only read it)."""
    folder = tmp_path_factory.mktemp("example-run")
    cwd = os.getcwd()
    os.chdir(folder)  # the run writes rockscreen-example.h5 into the current folder
    try:
        result = CliRunner().invoke(main, ["run", "--example", "--jobs", "1"])
    finally:
        os.chdir(cwd)
    assert result.exit_code == 0, result.output
    return folder / "rockscreen-example.h5"


# ------------------------------------------------------------ running the command line

KILL_AFTER_CHUNKS = Path(__file__).with_name("kill_after_chunks.py")


@pytest.fixture
def rockscreen(tmp_path, monkeypatch):
    """``rockscreen(*args)``: the command line, in-process, in ``tmp_path`` as current folder."""
    monkeypatch.chdir(tmp_path)
    return lambda *args: CliRunner().invoke(main, [str(arg) for arg in args])


@pytest.fixture
def example_records(tmp_path):
    """The synthetic example records and their StationXML, written to ``tmp_path/records``."""
    return write_example_records(tmp_path / "records")


@pytest.fixture
def run_args(example_records):
    """``run_args(*extra, records=, stations=, towers=, jobs=)``: ``rockscreen run`` arguments.

    By default the example records, their StationXML, the example inventory and one job;
    ``extra`` follows the records, and None leaves an option out.
    """
    example, xml = example_records
    inventory = example_inventory_path()

    def make(*extra, records=example, stations=xml, towers=inventory, jobs=1):
        args = ["run", *map(str, records), *extra]
        for option, value in (("--stations", stations), ("--towers", towers), ("--jobs", jobs)):
            if value is not None:
                args += [option, str(value)]
        return args

    return make


@pytest.fixture(scope="session")
def run_process():
    """``run_process(args, cwd, kill_after=None)``: ``rockscreen ARGS`` as a child process.

    ``kill_after`` (``N`` or ``"N:SIGNAL"``) signals it right after its Nth archive chunk.
    """

    def run(args, cwd, kill_after=None):
        command = [sys.executable, "-m", "rockscreen.pipeline"]
        if kill_after is not None:
            command = [sys.executable, str(KILL_AFTER_CHUNKS), str(kill_after)]
        return subprocess.run(
            [*command, *args],
            cwd=cwd,
            env=dict(os.environ),
            capture_output=True,
            text=True,
            timeout=600,
        )

    return run


# ------------------------------------------------------------ record files


@pytest.fixture(scope="session")
def write_at2():
    """``write_at2(path, data, dt=0.01, units="G")``: a PEER AT2 file of ``data``; its path."""

    def write(path, data, dt=0.01, units="G"):
        lines = [
            "PEER NGA STRONG MOTION DATABASE RECORD",
            "Test, 1/2/2003, Somewhere, 90",
            f"ACCELERATION TIME SERIES IN UNITS OF {units}",
            f"NPTS= {len(data)}, DT= {dt} SEC",
        ]
        lines += [" ".join(f"{v:.7E}" for v in data[i : i + 5]) for i in range(0, len(data), 5)]
        path.write_text("\n".join(lines) + "\n")
        return path

    return write


# ------------------------------------------------------------ a small sweep study

SMALL_STUDY = """
title = "small"

[tower]
width_m = 2.06
height_m = 5.80
eta = 0.9
tower_weight_kN = 339.0
building_weight_kN = 96840.67

[[group]]
name = "single"
model = "rocking"
excitation = "pulse"
shape = "one-sine"
amplitudes = ["2.25g"]
frequencies_hz = [7.98]

[[group]]
name = "double"
model = "double-block"
excitation = "harmonic"
amplitudes = ["0.5g"]
frequencies_hz = [5, 7]
duration_s = 0.5
friction = [[1.25, 1.0]]
"""


@pytest.fixture
def small_study(tmp_path):
    """A two-group study file (three cases, seconds to run): ``tmp_path/small.toml``."""
    path = tmp_path / "small.toml"
    path.write_text(SMALL_STUDY)
    return path


# ------------------------------------------------------------ stand-ins for the solver
# A transparent stand-in: theta_max/alpha grows with the peak of the excitation over the
# uplift threshold, overturning beyond twice the threshold.


def _fake_block(width, height, *, eta=None):
    return SimpleNamespace(alpha=math.atan(width / height), width=width)


def _fake_rocking(block, acc, dt, *, acc_v=None, history=True, max_free_time=60.0):
    ratio = float(np.max(np.abs(acc))) / (G * math.tan(block.alpha))
    over = max(0.0, ratio - 1.0)
    t = np.arange(len(acc)) * dt
    return SimpleNamespace(
        status="overturned" if ratio > 2 else ("no_motion" if ratio <= 1 else "came_to_rest"),
        overturned=ratio > 2,
        uplifted=ratio > 1,
        slipped=False,
        theta_max=over * block.alpha,
        theta_max_over_alpha=over,
        n_impacts=3 if ratio > 1 else 0,
        t_overturn=math.nan,
        slip_max=0.0,
        slip_residual=0.0,
        friction_demand_max=0.1,
        alpha=block.alpha,
        p=2.0,
        eta=0.9,
        t=t if history else None,
        theta=(acc / G) if history else None,
        u=np.zeros_like(t) if history else None,
        regime=np.zeros(len(t), dtype=np.int8) if history else None,
    )


def _fake_double(block, acc, dt, *, tower_mass, building_mass, mu_s, mu_k, **kwargs):
    # Sliding caps the base acceleration at mu_k g: the double block rocks less.
    return _fake_rocking(block, np.clip(acc, -mu_k * G, mu_k * G), dt, **kwargs)


def _fake_floor(acc, dt, *, building_period, mode_shape_at_base=1.0):
    return acc * (1.0 + 0.5 * mode_shape_at_base)


@pytest.fixture(scope="session")
def fake_solvers() -> Solvers:
    """Pure-Python stand-ins for the solvers (``dataclasses.replace`` swaps one)."""
    return Solvers(block=_fake_block, rocking=_fake_rocking, double=_fake_double, floor=_fake_floor)


@pytest.fixture(scope="session")
def make_motion():
    """``make_motion(record_id, peak_n, peak_e, ...)``: a short pulse record, peaks in m/s2."""

    def make(
        record_id="XX.S1..HN",
        peak_n=2.0,
        peak_e=1.0,
        azimuths=(0.0, 90.0),
        station=None,
        info=None,
    ) -> GroundMotion:
        t = np.arange(400) * 0.01
        shape = np.sin(2 * np.pi * 1.5 * t) * np.exp(-(((t - 2) / 0.8) ** 2))
        shape /= np.max(np.abs(shape))
        return GroundMotion(
            record_id=record_id,
            station=station or record_id.rsplit(".", 2)[0],
            dt=0.01,
            channels=("HNN", "HNE"),
            horizontals=(peak_n * shape, peak_e * shape),
            azimuths=azimuths,
            vertical=0.1 * shape,
            latitude=42.0,
            longitude=13.0,
            **({} if info is None else {"info": info}),
        )

    return make


# ------------------------------------------------------------ a small campaign archive


def archive_towers(n: int) -> list[Tower]:
    return [
        Tower(id=f"T{i:02d}", width_m=1.5 + 0.25 * i, height_m=6.0, lat=42.0, lon=13.0)
        for i in range(n)
    ]


@pytest.fixture(scope="session")
def write_archive(fake_solvers, make_motion):
    """``write_archive(path, n_towers)``: an archive of towers T00... on one record.

    It is written chunk by chunk in reverse order (as parallel workers deliver them) and
    stops, as a crash would, after ``stop_after`` chunks; returns the writer.
    """

    def write(path, n_towers, *, chunk_size, stop_after=None, fingerprint="abc"):
        motions = {"XX.A..HN": make_motion("XX.A..HN", 4.0, 2.0, info={"files": ["a.mseed"]})}
        writer = ArchiveWriter(
            path,
            fingerprint=fingerprint,
            metadata={
                "rockscreen_version": "test",
                "inventory_source": "towers.csv",
                "config_toml": CampaignConfig().to_toml(),
            },
            towers_table=inventory_table(archive_towers(n_towers)),
            motions=motions,
            failures=[Failure("read", "bad.mseed", "empty file")],
        )
        shared = CampaignShared(motions, CampaignConfig(), fake_solvers)
        tasks = [TowerTask(i, t, ("XX.A..HN",)) for i, t in enumerate(archive_towers(n_towers))]
        todo = [task for task in tasks if task.tower.id not in writer.done]
        with writer:
            for n, chunk in enumerate(reversed(chunk_tasks(todo, 1, size=chunk_size)), start=1):
                writer.append(run_chunk(shared, chunk))
                if stop_after is not None and n >= stop_after:
                    return writer
        writer.finalize()
        return writer

    return write


def _stored_row(tower: Tower) -> dict[str, object]:
    """The inventory row an archive stores for a tower: every column, resolved depths,
    NaN or "" where not given."""
    row: dict[str, object] = {}
    for name, (column, _) in TABLE_COLUMNS.items():
        value = getattr(tower, TABLE_RESOLVED.get(column, column))
        if column in TEXT_COLUMNS:
            row[name] = value or ""
        else:
            row[name] = math.nan if value is None else float(value)
    return row


def _same_row(a: dict[str, object], b: dict[str, object]) -> bool:
    """Rows equal, NaN equal to NaN."""
    if a.keys() != b.keys():
        return False
    return all(
        (isinstance(v, float) and math.isnan(v) and isinstance(b[k], float) and math.isnan(b[k]))
        or v == b[k]
        for k, v in a.items()
    )


@pytest.fixture
def inventory_rows():
    """``expected(tower)``: the row an archive stores of a tower's inventory (``/towers`` of
    a run, ``/inventory`` of an assess); ``same(a, b)``: two rows equal, NaN equal to NaN."""
    return SimpleNamespace(expected=_stored_row, same=_same_row)
