"""``rockscreen run``: screen a tower inventory against records into an HDF5 archive."""

from __future__ import annotations

import math
import shlex
import sys
import time
from pathlib import Path
from typing import Any

import click

#: Order of the risk classes in the summary table (riskiest first).
CLASS_RANK = {"collapse": 0, "high": 1, "moderate": 2, "low": 3, "none": 4, "unknown": 5}


def rank_towers(rows: list[dict[str, Any]]) -> list[dict[str, Any]]:
    """Sort summary rows riskiest first: class, then safety factor, then theta_max/alpha.

    Parameters
    ----------
    rows : list of dict
        Summary rows (:func:`pipeline.archive.campaign.read_summary`).

    Returns
    -------
    list of dict
    """

    def key(row: dict[str, Any]) -> tuple:
        sf = row["safety_factor"]
        ratio = row["theta_max_over_alpha"]
        return (
            CLASS_RANK.get(row["risk_class"], 9),
            math.inf if math.isnan(sf) else sf,
            -(ratio if not math.isnan(ratio) else -math.inf),
            row["id"],
        )

    return sorted(rows, key=key)


def _number(value: float, digits: int = 3) -> str:
    if math.isnan(value):
        return "-"
    if math.isinf(value):
        return "inf"
    return f"{value:.{digits}f}"


def summary_lines(rows: list[dict[str, Any]]) -> list[str]:
    """Return the summary table (riskiest first, units in the headers) as text lines."""
    header = (
        "tower",
        "risk",
        "theta_max/alpha [-]",
        "theta_max [rad]",
        "safety_factor [-]",
        "overturned",
        "governing record",
        "model",
    )
    table = [header]
    for row in rank_towers(rows):
        table.append(
            (
                row["id"],
                row["risk_class"],
                _number(row["theta_max_over_alpha"]),
                _number(row["theta_max_rad"], 4),
                _number(row["safety_factor"], 2),
                "yes" if row["overturned"] else "no",
                row["governing_record"] or "-",
                row["governing_model"] or "-",
            )
        )
    widths = [max(len(str(line[i])) for line in table) for i in range(len(header))]
    return [
        "  ".join(str(c).ljust(w) for c, w in zip(line, widths, strict=True)).rstrip()
        for line in table
    ]


def _resolve_inventory(towers: str | None, config: Any, example: bool) -> tuple[Path, str]:
    """Return the inventory path and a sentence saying where it came from."""
    from stations.inventory import example_inventory_path

    if towers:
        return Path(towers), "--towers"
    if example:
        return example_inventory_path(), "the embedded example inventory (--example)"
    if config.inventory:
        return Path(config.inventory), f"named in {config.source}"
    local = Path.cwd() / "towers.csv"
    if local.is_file():
        return local, "towers.csv in the current directory"
    return example_inventory_path(), "the embedded example inventory (no --towers, no towers.csv)"


class _Progress:
    """A live progress bar on a terminal; a single final line otherwise."""

    def __init__(self, total: int, done: int) -> None:
        self.total, self.done = total, done
        self.start = time.perf_counter()
        self.bar = None
        if sys.stderr.isatty() and total > done:
            self.bar = click.progressbar(
                length=total, label="rockscreen: towers", file=sys.stderr, show_pos=True
            )
            self.bar.__enter__()
            self.bar.update(done)

    def __call__(self, n: int) -> None:
        self.done += n
        if self.bar is not None:
            self.bar.update(n)

    def close(self, computed: int) -> None:
        if self.bar is not None:
            self.bar.__exit__(None, None, None)
        elapsed = time.perf_counter() - self.start
        click.echo(
            f"rockscreen: {computed} towers computed in {elapsed:.1f} s "
            f"({self.done}/{self.total} in the archive)",
            err=True,
        )


@click.command("run")
@click.argument("records", nargs=-1, type=click.Path(dir_okay=False))
@click.option("--towers", type=click.Path(dir_okay=False), help="Tower inventory CSV.")
@click.option(
    "--stations", type=click.Path(dir_okay=False), help="StationXML: coordinates, orientations."
)
@click.option(
    "--config",
    "config_path",
    type=click.Path(dir_okay=False),
    help="TOML configuration (default: ./rockscreen.toml when present).",
)
@click.option("--out", type=click.Path(dir_okay=False), help="Archive (default rockscreen.h5).")
@click.option(
    "--jobs",
    type=click.IntRange(min=1),
    default=None,
    help="Worker processes (default: the number of CPUs).",
)
@click.option(
    "--scheduler",
    metavar="TCP://HOST:PORT",
    help="Compute on the workers of a running Dask scheduler instead of local processes "
    '(needs pip install "rockscreen[distributed]"); --jobs is then ignored.',
)
@click.option("--units", help="Units of records that state none: g, m/s2 or cm/s2.")
@click.option(
    "--example",
    is_flag=True,
    help="Write the embedded example records to ./rockscreen-example/ and screen the example "
    "inventory against them.",
)
def cli(
    records: tuple[str, ...],
    towers: str | None,
    stations: str | None,
    config_path: str | None,
    out: str | None,
    jobs: int | None,
    scheduler: str | None,
    units: str | None,
    example: bool,
) -> None:
    """Screen towers against records; write an HDF5 archive, print the risk summary.

    RECORD files (any supported format) are read, processed and paired with the
    towers (nearest station within the pairing distance, or the inventory's station
    column). Progress goes to stderr; the summary table, riskiest first, to stdout.
    Records that cannot be read or processed are listed and skipped.
    """
    from pipeline import __version__
    from pipeline.archive.campaign import ArchiveWriter, read_failures, read_summary
    from pipeline.config import load_config
    from pipeline.errors import RockscreenError
    from pipeline.screening.campaign import fingerprint, run_campaign
    from pipeline.screening.cases import CampaignShared
    from pipeline.screening.inputs import pair, prepare_records
    from stations.inventory import inventory_table, read_inventory

    if example and records:
        raise click.UsageError("give either RECORD files or --example, not both")
    if not example and not records:
        raise click.UsageError("give RECORD files to screen against, or --example")
    config = load_config(config_path)
    inventory_path, origin = _resolve_inventory(towers, config, example)
    tower_list = read_inventory(inventory_path)  # a bad row stops here: nothing written
    click.echo(
        f"rockscreen: inventory {inventory_path}: {origin}; {len(tower_list)} towers", err=True
    )
    if example:
        from pipeline.motion.synthetic import write_example_records

        paths, xml = write_example_records(Path.cwd() / "rockscreen-example")
        records = tuple(str(p) for p in paths)
        stations = stations or str(xml)
        click.echo(f"rockscreen: example records written to {paths[0].parent}", err=True)
    stations = stations or (config.stations or None)
    out_path = Path(out or ("rockscreen-example.h5" if example else "rockscreen.h5"))

    motions, input_failures = prepare_records(
        records, units=units, stations=stations, processing=config.processing
    )
    for failure in input_failures:
        click.echo(f"rockscreen: skipped {failure.subject}: {failure.reason}", err=True)
    if not motions:
        raise RockscreenError(f"none of the {len(records)} record files could be used")
    tasks, pair_failures = pair(tower_list, motions, max_distance_km=config.pairing.max_distance_km)
    for failure in pair_failures:
        click.echo(f"rockscreen: tower {failure.subject} not screened: {failure.reason}", err=True)

    table = inventory_table(tower_list)
    print_ = fingerprint(table, motions, config, __version__)
    if _complete(out_path, print_):
        click.echo(f"rockscreen: {out_path} is already complete for these inputs", err=True)
    else:
        metadata = {
            "rockscreen_version": __version__,
            "command_line": shlex.join(["rockscreen", *sys.argv[1:]]),
            "config_toml": config.to_toml(),
            "config_source": config.source,
            "inventory_source": str(inventory_path),
            "stations_source": str(stations or ""),
            "record_files": [str(p) for p in records],
            "n_towers": len(tower_list),
            "n_records": len(motions),
        }
        executor, jobs = _executor(scheduler, jobs)
        try:
            writer = ArchiveWriter(
                out_path,
                fingerprint=print_,
                metadata=metadata,
                towers_table=table,
                motions=motions,
                failures=[*input_failures, *pair_failures],
            )
        except BaseException:
            executor.__exit__(None, None, None)  # a connected Dask client is closed
            raise
        if writer.resumed:
            click.echo(
                f"rockscreen: resuming {writer.part} ({len(writer.done)} towers done)", err=True
            )
        progress = _Progress(len(tasks), len(writer.done))
        with writer:
            computed = run_campaign(
                tasks,
                CampaignShared(motions, config),
                writer,
                executor,
                jobs=jobs,
                progress=progress,
            )
        progress.close(computed)
        writer.finalize()
        click.echo(f"rockscreen: archive written to {out_path}", err=True)
    rows = read_summary(out_path)
    for line in summary_lines(rows):
        click.echo(line)
    solve_failures = [f for f in read_failures(out_path) if f["kind"] == "solve"]
    for failure in solve_failures:
        click.echo(f"rockscreen: failed {failure['subject']}: {failure['reason']}", err=True)


def _executor(scheduler: str | None, jobs: int | None) -> tuple[Any, int]:
    """Return the executor of the run and the worker count that sizes its chunks.

    With ``--scheduler`` the Dask cluster is connected here, before the archive is
    created, so an unreachable scheduler stops the run with nothing written.
    """
    from pipeline.execution.local import default_jobs, make_executor

    if not scheduler:
        jobs = jobs or default_jobs()
        return make_executor(jobs), jobs
    from pipeline.execution.dask_cluster import DaskExecutor

    if jobs is not None:
        click.echo(
            f"rockscreen: --jobs {jobs} is ignored with --scheduler: the cluster's workers compute",
            err=True,
        )
    executor = DaskExecutor(scheduler).connect()
    click.echo(
        f"rockscreen: computing on the Dask cluster at {executor.address} "
        f"({executor.jobs} worker threads); this process writes the archive",
        err=True,
    )
    return executor, executor.jobs


def _complete(path: Path, print_: str) -> bool:
    """Whether ``path`` is a complete archive of the same inputs and configuration."""
    import h5py

    if not path.is_file():
        return False
    try:
        with h5py.File(path, "r") as f:
            return bool(f.attrs.get("complete")) and f.attrs.get("fingerprint") == print_
    except OSError:
        return False
