"""``rockscreen run``: screen a tower inventory against records into an HDF5 archive."""

from __future__ import annotations

import os
import sys
import time

import click

from rockscreen.pipeline.cli.options import (
    example_option,
    jobs_option,
    out_option,
    path_option,
    scheduler_option,
    towers_option,
)
from rockscreen.pipeline.cli.output import Output, output_options

#: Notes printed under the table, riskiest towers first; the rest are counted in one line.
MAX_NOTES = 20


class _Progress:
    """A live bar on a terminal; otherwise a line at least every few seconds, then a total."""

    #: Seconds between two progress lines when stderr is not a terminal.
    EVERY_S = 5.0

    def __init__(self, total: int, done: int, out: Output) -> None:
        self.total, self.done, self.out = total, done, out
        self.start = self.last = time.perf_counter()
        self.bar = None
        if out.level >= 1 and sys.stderr.isatty() and total > done:
            self.bar = click.progressbar(
                length=total, label="rockscreen: towers", file=sys.stderr, show_pos=True
            )
            self.bar.__enter__()
            self.bar.update(done)

    def __call__(self, n: int) -> None:
        self.done += n
        if self.bar is not None:
            self.bar.update(n)
            return
        now = time.perf_counter()
        if now - self.last >= self.EVERY_S:
            self.last = now
            self.out.info(f"{self.done}/{self.total} towers ({now - self.start:.0f} s)")

    def close(self, computed: int) -> None:
        if self.bar is not None:
            self.bar.__exit__(None, None, None)
        elapsed = time.perf_counter() - self.start
        self.out.info(
            f"{computed} towers computed in {elapsed:.1f} s "
            f"({self.done}/{self.total} in the archive)"
        )


def _check_some_record_exists(records: tuple[str, ...], towers: str | None) -> None:
    """Refuse at once, before the heavy imports, records of which none can be read.

    Files, folders and quoted globs are expanded as the run expands them
    (:func:`rockscreen.pipeline.records.paths.expand_record_paths`, standard library only);
    when one at least is a readable file the run goes on and reports the others, each once.
    The inventory (``--towers``, else ``./towers.csv``) is read first, as the run reads it:
    a bad row is the first thing to fix, and it is reported as the run reports it.

    Raises
    ------
    RockscreenError
        When no record argument names a readable file: one line naming the first ones.
    InventoryError
        For a bad inventory row (before the records are judged).
    """
    from rockscreen.pipeline.errors import RecordFormatError, RockscreenError
    from rockscreen.pipeline.records.paths import check_record_file, expand_record_paths

    if not records:
        return
    paths, _ = expand_record_paths(records)
    reasons = []
    for path in paths:
        try:
            check_record_file(path)
        except RecordFormatError as exc:
            reasons.append(str(exc))
            continue
        return
    inventory = towers or ("towers.csv" if os.path.isfile("towers.csv") else None)
    if inventory is not None:
        from rockscreen.stations.inventory import read_inventory

        read_inventory(inventory)  # numpy only; a bad row is the error to report first
    shown = "; ".join(reasons[:3]) + (f"; and {len(reasons) - 3} more" if len(reasons) > 3 else "")
    raise RockscreenError(f"none of the {len(paths)} record files can be read: {shown}")


@click.command("run")
@click.argument("records", nargs=-1, type=click.Path())
@towers_option()
@click.option(
    "--stations",
    multiple=True,
    metavar="XML",
    help="StationXML: coordinates, orientations. Repeatable (merged); a folder of StationXML "
    "or a quoted glob ('meta/*.xml') also works.",
)
@path_option(
    "--config",
    "config_path",
    help="TOML configuration (default: ./rockscreen.toml when present).",
)
@out_option("Archive (default rockscreen.h5).")
@jobs_option()
@scheduler_option(
    "Compute on the workers of a running Dask scheduler instead of local processes "
    '(needs pip install "rockscreen[distributed]"); --jobs is then ignored.',
)
@click.option(
    "--units",
    type=click.Choice(["g", "m/s2", "cm/s2"]),
    help="Units of records that state none.",
)
@click.option(
    "--overwrite",
    is_flag=True,
    help="Replace an existing archive of other inputs at --out (refused otherwise).",
)
@click.option(
    "--skip-invalid",
    is_flag=True,
    help="Screen the inventory's valid towers and list its invalid rows in the failures "
    "table (kind 'inventory') instead of refusing the inventory (every invalid row named).",
)
@example_option(
    "Write the embedded example records to ./rockscreen-example/ and screen the example "
    "inventory against them.",
)
@output_options
def cli(records: tuple[str, ...], example: bool, out_level: int, **options) -> None:
    """Screen towers against records; write an HDF5 archive, print the risk summary.

    RECORD files (any supported format; a folder or a quoted glob also works) are read,
    processed and paired with the towers (nearest station within the pairing distance,
    or the inventory's station column). Progress goes to stderr; the summary table,
    riskiest first, to stdout. Records that cannot be read or processed are listed and
    skipped. A run that screens no tower exits 1.
    """
    if example and records:
        raise click.UsageError("give either RECORD files or --example, not both")
    if not example and not records:
        raise click.UsageError("give RECORD files to screen against, or --example")
    from rockscreen.pipeline.cli.inputs import check_input_files
    from rockscreen.stations.station_files import expand_station_paths

    # Before the heavy imports: a mistyped inventory, StationXML or configuration, or
    # records none of which can be read, are refused at once.
    check_input_files([options.get("towers")], "inventory")
    stations = options.pop("stations") or ()
    check_input_files(expand_station_paths(stations), "StationXML")
    check_input_files([options.get("config_path")], "configuration")
    _check_some_record_exists(records, options.get("towers"))
    from rockscreen.pipeline.errors import RockscreenError
    from rockscreen.pipeline.report.summary import LEGEND, note_lines, summary_lines
    from rockscreen.pipeline.screening.batch import RunRequest, run_screening

    out = Output(out_level)
    request = RunRequest(records=records, example=example, stations=stations, **options)
    outcome = run_screening(request, out.notify, lambda total, done: _Progress(total, done, out))
    solve_failures = [f for f in outcome.failures if f["kind"] == "solve"]
    for failure in solve_failures:
        out.warning(f"failed {failure['subject']}: {failure['reason']}")
    for line in summary_lines(outcome.rows):
        click.echo(line)
    # Notes and legend explain the table; stderr keeps stdout a table a program can read.
    notes = note_lines(outcome.rows)
    for line in notes[:MAX_NOTES]:
        out.info("note:" + line)
    if len(notes) > MAX_NOTES:
        out.info(
            f"... and {len(notes) - MAX_NOTES} more notes (the summary's note column: "
            f"rockscreen inspect {outcome.out_path})"
        )
    for line in LEGEND:
        out.info(line)
    skipped = len(outcome.failures) - len(solve_failures)
    out.result(
        f"{outcome.n_screened} of {outcome.n_towers} towers screened; {skipped} inputs skipped "
        f"or towers unpaired, {len(solve_failures)} solve failures; archive {outcome.out_path}"
    )
    if outcome.n_screened == 0:
        raise RockscreenError(
            f"no tower was screened: every tower is 'unknown' (see the failures above and "
            f"`rockscreen inspect {outcome.out_path}`)"
        )
