"""``rockscreen info``: what each record file holds, in SI units, one entry per trace."""

from __future__ import annotations

import json

import click

from rockscreen.pipeline.cli.traces import expand_paths, stations_option, units_option
from rockscreen.pipeline.report.risk_summary import json_number
from rockscreen.pipeline.text import printable

#: Table columns: name, width, format spec of the value.
_COLUMNS = (
    ("id", 22, "<"),
    ("format", 6, "<"),
    ("npts", 8, ">"),
    ("sampling_rate_hz", 16, ">.6g"),
    ("starttime", 27, "<"),
    ("units", 5, "<"),
    ("pga_m_s2", 10, ">.5g"),
    ("pgv_m_s", 10, ">.5g"),
    ("duration_s", 10, ">.6g"),
)


def _table_line(entry: dict | None = None) -> str:
    """One table row; the header row when ``entry`` is None."""
    cells = []
    for name, width, spec in _COLUMNS:
        if entry is None:
            cells.append(f"{name:{spec[0]}{width}}")
        elif isinstance(entry[name], str):
            cells.append(f"{printable(entry[name]):{spec[0]}{width}{spec[1:]}}")
        else:
            cells.append(f"{entry[name]:{spec[0]}{width}{spec[1:]}}")
    return "  ".join(cells).rstrip()


@click.command("info")
@click.argument("files", nargs=-1, required=True, type=click.Path())
@units_option()
@stations_option("StationXML: sensitivities for counts, station coordinates and orientations.")
@click.option("--json", "as_json", is_flag=True, help="Print a JSON list instead of a table.")
@click.pass_context
def cli(ctx: click.Context, files, units, stations, as_json) -> None:
    """Report every trace of FILE...: id, format, npts, rate, start, units, PGA, PGV, duration.

    FILE may be a folder (its record files) or a quoted glob pattern ('records/*.mseed');
    a file named twice is read once. Values are after conversion to m/s^2 and removal of
    the mean, nothing else. Samples that cannot be ground acceleration (NaN, inf, a peak
    above 5 g, an isolated spike) refuse the file. A file that cannot be read is reported
    on stderr as one line naming it and the reason; the others are still reported, and the
    exit code is 1. Quality flags (e.g. a vertical peak over twice the horizontals') are
    warnings on stderr and ``quality_flags`` in the JSON.
    """
    from obspy import Stream

    from rockscreen.pipeline.records.grouping import flag_vertical_ratio
    from rockscreen.pipeline.records.io import read_stream, trace_summary
    from rockscreen.stations.errors import RockscreenError
    from rockscreen.stations.stationxml import read_station_metadata

    meta = read_station_metadata(stations) if stations is not None else None
    paths = expand_paths(files)

    read, failed = [], 0
    for path in paths:
        try:
            read.append((path, read_stream(path, units=units, stations=meta)))
        except RockscreenError as exc:
            failed += 1
            click.echo(f"rockscreen: error: {printable(str(exc))}", err=True)
    everything = Stream([trace for _, stream in read for trace in stream])
    for key, flag in flag_vertical_ratio(everything):
        click.echo(f"rockscreen: warning: {printable(key)}: {printable(flag)}", err=True)
    entries = [
        {"file": str(path), **trace_summary(trace)} for path, stream in read for trace in stream
    ]

    if as_json:  # JSON has no NaN; an empty trace has no peak
        payload = [{key: json_number(value) for key, value in e.items()} for e in entries]
        click.echo(json.dumps(payload, indent=2))
    elif entries:
        click.echo(_table_line())
        for entry in entries:
            click.echo(_table_line(entry))
    if failed:
        ctx.exit(1)
