"""A record-based screening run from files to a complete archive (``rockscreen run``).

:func:`run_screening` is the whole job: it resolves the inputs (configuration, inventory,
station metadata, record files), refuses what would make the result mislead (an example
inventory standing in for the user's, towers paired with records from anywhere without
saying so), reads and pairs the records, computes the towers the archive does not hold
yet and finalises the archive. The command line only parses options and prints.
"""

from __future__ import annotations

import contextlib
import shlex
import sys
import threading
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import h5py

from rockscreen.pipeline import __version__
from rockscreen.pipeline.archive.campaign import ArchiveWriter, read_failures, read_summary
from rockscreen.pipeline.archive.lock import check_overwrite, claimed_output
from rockscreen.pipeline.config import load_config
from rockscreen.pipeline.engine.results import Failure
from rockscreen.pipeline.errors import RockscreenError
from rockscreen.pipeline.execution.dask_cluster import check_address
from rockscreen.pipeline.execution.job import Job
from rockscreen.pipeline.motion.synthetic import write_example_records
from rockscreen.pipeline.records.paths import expand_record_paths
from rockscreen.pipeline.screening.campaign import fingerprint, run_campaign
from rockscreen.pipeline.screening.cases import CampaignShared
from rockscreen.pipeline.screening.inputs import pair, prepare_records
from rockscreen.solver.cache import kernel_is_cached
from rockscreen.stations.inventory import (
    example_inventory_path,
    inventory_table,
    read_inventory_rows,
)
from rockscreen.stations.station_files import expand_station_paths

#: ``notify(level, message)``: ``"info"`` (progress of the run), ``"warning"`` (something
#: the user must read: it changes how the result is to be read), ``"detail"`` (--verbose).
Notify = Callable[[str, str], None]

#: At most this many lines per kind of skipped input; the rest is counted in one line.
MAX_LISTED = 10


@dataclass(frozen=True)
class RunRequest:
    """What ``rockscreen run`` was asked to do (the command-line options, unparsed paths)."""

    records: tuple[str, ...] = ()
    towers: str | None = None
    #: StationXML files, folders of StationXML or glob patterns (merged).
    stations: tuple[str, ...] = ()
    config_path: str | None = None
    out: str | None = None
    jobs: int | None = None
    scheduler: str | None = None
    units: str | None = None
    example: bool = False
    overwrite: bool = False
    #: Screen the valid towers of an inventory with invalid rows, listing the rows as
    #: failures of kind ``inventory`` (else the inventory is refused, every row named).
    skip_invalid: bool = False


@dataclass
class RunOutcome:
    """A finished run: where the archive is and what it holds."""

    #: The complete archive.
    out_path: Path
    #: Per-tower summary rows (:func:`rockscreen.pipeline.archive.campaign.read_summary`).
    rows: list[dict[str, Any]]
    #: Every failure of the archive (``kind``, ``subject``, ``reason``).
    failures: list[dict[str, Any]]
    #: Towers in the inventory.
    n_towers: int

    @property
    def n_screened(self) -> int:
        """Towers with a verdict (every class but ``unknown``)."""
        return sum(1 for row in self.rows if row["risk_class"] != "unknown")


def resolve_inventory(request: RunRequest, config: Any) -> tuple[Path, str]:
    """Return the inventory path and a sentence saying where it came from.

    The embedded example inventory is used only with ``--example``: when record files are
    given, screening fictional towers against them would print a risk table of towers
    that do not exist.

    Raises
    ------
    RockscreenError
        When record files are given and no inventory is named or found.
    """
    if request.towers:
        return Path(request.towers), "--towers"
    if request.example:
        return example_inventory_path(), "the embedded example inventory (--example)"
    if config.inventory:
        return Path(config.inventory), f"named in {config.source}"
    local = Path.cwd() / "towers.csv"
    if local.is_file():
        return local, "towers.csv in the current directory"
    raise RockscreenError(
        "no tower inventory: give --towers CSV, name `inventory` in rockscreen.toml, or put "
        "towers.csv in the current folder (rockscreen run --example screens the demo towers)"
    )


def _notify_listed(notify: Notify, lines: list[str], what: str) -> None:
    """Notify at most :data:`MAX_LISTED` warnings, then one line counting the rest."""
    for line in lines[:MAX_LISTED]:
        notify("warning", line)
    if len(lines) > MAX_LISTED:
        notify(
            "warning",
            f"... and {len(lines) - MAX_LISTED} more {what} (all listed in the archive's "
            "failures table: rockscreen inspect)",
        )


def _check_station_coordinates(towers: list[Any], motions: dict[str, Any], notify: Notify) -> None:
    """Warn loudly when towers have coordinates and no station has any."""
    if not any(t.has_coordinates for t in towers):
        return
    if any(m.latitude is not None for m in motions.values()):
        return
    notify(
        "warning",
        "WARNING: the towers have coordinates but no record station has any (miniSEED "
        "carries none: give --stations StationXML): every tower is paired with EVERY "
        "station, wherever it is; the summary's pairing column says so per tower",
    )


def complete_for(path: Path, print_: str) -> bool:
    """Whether ``path`` is a complete archive of the same inputs and configuration."""
    if not path.is_file():
        return False
    try:
        with h5py.File(path, "r") as f:
            return bool(f.attrs.get("complete")) and f.attrs.get("fingerprint") == print_
    except OSError:
        return False


def run_screening(
    request: RunRequest,
    notify: Notify,
    progress_factory: Callable[[int, int], Any] | None = None,
) -> RunOutcome:
    """Screen an inventory against records into a complete archive.

    Parameters
    ----------
    request : RunRequest
    notify : callable
        ``notify(level, message)`` for what the user should read while it runs.
    progress_factory : callable, optional
        ``progress_factory(total, done)`` returns an object called with the number of
        towers of each written chunk and closed with ``close(computed)``.

    Returns
    -------
    RunOutcome

    Raises
    ------
    RockscreenError
        For bad inputs (nothing is written), or when no tower can be paired.
    Interrupted
        On Ctrl-C, SIGTERM or SIGHUP while computing: the ``.part`` file keeps what was written
        (:meth:`rockscreen.pipeline.execution.job.Job.running`).
    """
    if request.example and request.records:
        raise RockscreenError("give either RECORD files or --example, not both")
    if not request.example and not request.records:
        raise RockscreenError("give RECORD files to screen against, or --example")
    if request.scheduler:
        check_address(request.scheduler)  # a malformed address: one line, before anything
    config = load_config(request.config_path)
    stations: list[str] = []
    given = request.stations or ((config.stations,) if config.stations else ())
    if given and not request.example:
        stations = [str(p) for p in expand_station_paths(given)]  # one line if one is missing
    elif given:
        stations = [str(p) for p in given]
    inventory_path, origin = resolve_inventory(request, config)
    towers, skipped = _read_towers(inventory_path, request.skip_invalid, notify)
    notify("info", f"inventory {inventory_path}: {origin}; {len(towers)} towers")
    records = request.records
    if records:
        expanded, notes = expand_record_paths(records)
        records = tuple(expanded)
        for note in notes:
            notify("info", note)
    if request.example:
        paths, xml = write_example_records(Path.cwd() / "rockscreen-example")
        records = tuple(str(p) for p in paths)
        stations = stations or [str(xml)]
        notify("info", f"example records written to {paths[0].parent}")
    default_out = "rockscreen-example.h5" if request.example else "rockscreen.h5"
    run = _Resolved(
        request,
        config,
        towers,
        inventory_path,
        stations,
        records,
        Path(request.out or default_out),
        skipped,
    )

    # Never one of the run's inputs, in a writable folder, one run per --out: before reading
    # anything (an existing archive is checked against this campaign by check_overwrite).
    inputs = [inventory_path, *stations, request.config_path, *records]
    with claimed_output(run.out_path, inputs, "run", overwrite=None):
        motions, tasks, failures = _read_and_pair(run, notify)
        _compute(run, motions, tasks, failures, notify, progress_factory)
    out_path = run.out_path
    return RunOutcome(out_path, read_summary(out_path), read_failures(out_path), len(towers))


@dataclass(frozen=True)
class _Resolved:
    """A request with its inputs resolved: configuration, towers, files, archive path."""

    request: RunRequest
    config: Any
    towers: list[Any]
    inventory_path: Path
    stations: list[str]
    records: tuple[str, ...]
    out_path: Path
    #: The inventory's invalid rows skipped (``--skip-invalid``), as failures.
    skipped: tuple[Any, ...] = ()


def _read_and_pair(run: _Resolved, notify: Notify) -> tuple[dict[str, Any], list[Any], list[Any]]:
    """Read, process and pair the records; return (motions, tasks, failures)."""
    records, config, towers = run.records, run.config, run.towers
    stations, request = run.stations, run.request
    motions, input_failures = prepare_records(
        records, units=request.units, stations=stations or None, processing=config.processing
    )
    _notify_listed(
        notify,
        [f"skipped {f.subject}: {f.reason.removeprefix(f'{f.subject}: ')}" for f in input_failures],
        "skipped inputs",
    )
    if not motions:
        raise RockscreenError(f"none of the {len(records)} record files could be used")
    _check_station_coordinates(towers, motions, notify)
    tasks, pair_failures = pair(towers, motions, max_distance_km=config.pairing.max_distance_km)
    _notify_listed(
        notify,
        [f"tower {f.subject} not screened: {f.reason}" for f in pair_failures],
        "unpaired towers",
    )
    if not tasks:
        raise RockscreenError(
            f"no tower could be paired with a record ({len(pair_failures)} towers unpaired; "
            f"pairing distance {config.pairing.max_distance_km:g} km, [pairing] in the "
            "configuration): nothing to screen"
        )
    return motions, tasks, [*run.skipped, *input_failures, *pair_failures]


def _read_towers(
    path: Path, skip_invalid: bool, notify: Notify
) -> tuple[list[Any], tuple[Failure, ...]]:
    """Return the inventory's towers and, with ``skip_invalid``, its invalid rows as failures.

    Without ``skip_invalid`` an invalid row stops here, every one named, nothing written.
    """
    reading = read_inventory_rows(path)
    if reading.invalid and (not skip_invalid or not reading.towers):
        raise reading.error()
    skipped = tuple(
        Failure(
            "inventory",
            bad.tower_id or f"row {bad.row}",
            f"{bad.detail}; skipped (--skip-invalid): fix the row and rerun",
        )
        for bad in reading.invalid
    )
    if skipped:
        notify("warning", f"skipping {len(skipped)} invalid row(s) of {path} (--skip-invalid)")
    return reading.towers, skipped


def _compute(
    run: _Resolved,
    motions: dict[str, Any],
    tasks: list[Any],
    failures: list[Any],
    notify: Notify,
    progress_factory: Callable[[int, int], Any] | None,
) -> None:
    """Write the archive of the run, resuming a ``.part`` of the same inputs."""
    config, towers, out_path = run.config, run.towers, run.out_path
    table = inventory_table(towers)
    print_ = fingerprint(table, motions, config, __version__)
    if complete_for(out_path, print_):
        notify("info", f"{out_path} is already complete for these inputs")
        return
    check_overwrite(
        out_path,
        print_,
        overwrite=run.request.overwrite,
        inventory_source=str(run.inventory_path),
    )
    metadata = {
        "rockscreen_version": __version__,
        "command_line": shlex.join(["rockscreen", *sys.argv[1:]]),
        "config_toml": config.to_toml(),
        "config_source": config.source,
        "inventory_source": str(run.inventory_path),
        "stations_source": ", ".join(run.stations),
        "record_files": [str(p) for p in run.records],
        "n_towers": len(towers),
        "n_records": len(motions),
    }
    with Job(
        lambda line: notify("info", line),
        jobs=run.request.jobs,
        scheduler=run.request.scheduler,  # connected before the archive is created
        n_tasks=len(tasks),
        warn=lambda line: notify("warning", line),
    ) as job:
        writer = ArchiveWriter(
            out_path,
            fingerprint=print_,
            metadata=metadata,
            towers_table=table,
            motions=motions,
            failures=failures,
        )
        job.keep(writer, len(tasks))
        compiling = _warn_if_compiling(notify)
        progress = progress_factory(len(tasks), len(writer.done)) if progress_factory else None
        with job.running(), compile_progress(notify, active=compiling):
            shared = CampaignShared(motions, config)
            computed = run_campaign(
                tasks, shared, writer, job.executor, jobs=job.workers, progress=progress
            )
    if progress is not None:
        progress.close(computed)
    writer.finalize()
    notify("info", f"archive written to {out_path}")


#: What the first compile costs, as measured (one figure for the CLI and the README).
COMPILE_TIME_NOTE = "about 20 s on a quiet 2-core machine, minutes when it is busy"
#: Seconds between two "still compiling" lines.
COMPILE_NOTE_EVERY_S = 30.0


def _warn_if_compiling(notify: Notify) -> bool:
    """Say so when the first solve will compile the solver; return whether it will."""
    if kernel_is_cached():
        return False
    notify(
        "info",
        f"compiling the solver on first use ({COMPILE_TIME_NOTE}; "
        "later runs load it from the cache)",
    )
    return True


@contextlib.contextmanager
def compile_progress(
    notify: Notify,
    *,
    active: bool = True,
    every_s: float = COMPILE_NOTE_EVERY_S,
    is_cached: Callable[[], bool] = kernel_is_cached,
) -> Iterator[None]:
    """Print a line every ``every_s`` seconds while the solver compiles in the block.

    A daemon thread polls ``is_cached`` (the kernel appears in numba's cache when the
    compile, in this process or in a worker, is done) and, until then, notifies
    ``"compiling the solver (first use) ... 30 s"`` every ``every_s`` seconds, so that a
    first run on a loaded machine does not sit silent for minutes.

    Parameters
    ----------
    notify : callable
        ``notify(level, message)``; lines go out at level ``"info"``.
    active : bool
        False: do nothing (the kernel was cached already).
    every_s : float
        Seconds between two lines.
    is_cached : callable
        Returns True once the kernel is compiled (default
        :func:`rockscreen.solver.cache.kernel_is_cached`).
    """
    if not active:
        yield
        return
    done = threading.Event()

    def tick() -> None:
        start = next_line = time.monotonic()
        next_line += every_s
        while not done.wait(min(1.0, every_s)):
            if is_cached():
                return
            now = time.monotonic()
            if now >= next_line:
                next_line += every_s
                notify("info", f"compiling the solver (first use) ... {now - start:.0f} s")

    thread = threading.Thread(target=tick, name="rockscreen-compile-progress", daemon=True)
    thread.start()
    try:
        yield
    finally:
        done.set()
        thread.join(timeout=2.0)
