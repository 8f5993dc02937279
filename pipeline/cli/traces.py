"""Record options and trace choice shared by ``info``, ``spectrum`` and ``simulate``."""

from __future__ import annotations

import click

#: ``--help`` text of ``--units`` for commands that read record files.
UNITS_HELP = "Units of files that carry none (SAC; miniSEED without --stations): g, m/s2 or cm/s2."

#: Channel codes (or their last letters) that name a vertical component.
_VERTICAL_CODES = ("UD", "UP")


def check_units(ctx, param, value):
    """Click callback of ``--units``: refuse an unknown unit at parse time (exit code 2).

    Returns the unit unchanged (None when absent).

    Raises
    ------
    click.BadParameter
        Naming the unit and the allowed ones (``g``, ``m/s2``, ``cm/s2``, ``gal``).
    """
    if value is None:
        return None
    from rockscreen.pipeline.errors import UnitsError
    from rockscreen.pipeline.text import printable
    from rockscreen.pipeline.units import unit_factor

    try:
        unit_factor(value)
    except UnitsError as exc:
        raise click.BadParameter(
            f"unknown acceleration unit {printable(value)!r}; allowed: g, m/s2, cm/s2 (gal)"
        ) from exc
    return value


def units_option(help: str = UNITS_HELP):
    """Return the ``--units U`` option (units of record files that state none).

    An unknown unit is a usage error (exit code 2) before any file is read.
    """
    return click.option("--units", metavar="U", default=None, help=help, callback=check_units)


def expand_paths(args) -> list[str]:
    """Expand record arguments (folders, quoted globs, duplicates); notes go to stderr.

    See :func:`rockscreen.pipeline.records.paths.expand_record_paths`.
    """
    from rockscreen.pipeline.records.paths import expand_record_paths

    paths, notes = expand_record_paths(args)
    for note in notes:
        click.echo(f"rockscreen: note: {note}", err=True)
    return paths


def stations_option(help: str):
    """Return the ``--stations XML`` option (a StationXML file)."""
    return click.option(
        "--stations", metavar="XML", type=click.Path(dir_okay=False), default=None, help=help
    )


def is_vertical(channel: str) -> bool:
    """Whether a channel code names a vertical component (``HNZ``, ``UD``, ``Z``...)."""
    code = channel.strip().upper()
    return code.endswith("Z") or code.endswith(_VERTICAL_CODES) or code == "V"


def select_trace(stream, channel: str | None):
    """Pick the trace to analyse; return it with a note saying why it was chosen.

    Parameters
    ----------
    stream : obspy.Stream
        The traces of the file.
    channel : str, optional
        A channel code (``HNE``) or full id (``IT.AQV..HNE``); default the first
        horizontal trace (the first trace if all are vertical).

    Raises
    ------
    click.BadParameter
        If no trace has the requested channel.
    """
    traces = list(stream)
    if channel is not None:
        wanted = channel.strip().upper()
        for trace in traces:
            if wanted in (trace.stats.channel.upper(), trace.id.upper()):
                return trace, f"{trace.id} (--channel {channel})"
        from rockscreen.pipeline.text import printable

        available = ", ".join(trace.id for trace in traces) or "none"
        raise click.BadParameter(
            f"no trace with channel {printable(channel)!r}; the file holds: {available}",
            param_hint="--channel",
        )
    if len(traces) == 1:
        return traces[0], f"{traces[0].id} (the only trace)"
    horizontals = [trace for trace in traces if not is_vertical(trace.stats.channel)]
    if horizontals:
        chosen = horizontals[0]
        why = "first horizontal"
    else:
        chosen = traces[0]
        why = "no horizontal in the file, first trace"
    return chosen, f"{chosen.id} ({why} of {len(traces)} traces; choose with --channel)"


def read_trace(path, *, units: str | None, stations, channel: str | None):
    """Read a record file in m/s^2 and pick one of its traces (see :func:`select_trace`).

    Parameters
    ----------
    path : str or path-like
        The record file.
    units : str, optional
        Units of a file that states none (``g``, ``m/s2``, ``cm/s2``).
    stations : str or path-like, optional
        StationXML file (sensitivities, coordinates).
    channel : str, optional
        Channel code or trace id; default the first horizontal trace.

    Returns
    -------
    trace : obspy.Trace
        The chosen trace, data in m/s^2.
    note : str
        Which trace was chosen and why.
    """
    from rockscreen.pipeline.records.io import (
        read_stream,  # the readers load ObsPy: only when a command runs
    )

    # read_stream raises RecordFormatError for a file without traces.
    stream = read_stream(path, units=units, stations=stations)
    if len(stream) > 1:
        from rockscreen.pipeline.records.grouping import flag_vertical_ratio

        flag_vertical_ratio(stream)
    return select_trace(stream, channel)
