"""``rockscreen spectrum``: elastic SA and PSA of one trace of a record file."""

from __future__ import annotations

import json

import click
import numpy as np

from rockscreen.pipeline.cli.traces import expand_paths, read_trace, stations_option, units_option
from rockscreen.pipeline.cli.traces import is_vertical as is_vertical  # re-exported
from rockscreen.pipeline.cli.traces import select_trace as select_trace  # re-exported

#: Default period grid: 100 log-spaced periods from 0.01 to 10 s.
DEFAULT_PERIOD_RANGE = (0.01, 10.0, 100)


def parse_periods(text: str) -> np.ndarray:
    """Parse ``--periods``, a comma-separated list of periods [s] (0 allowed, for the PGA).

    Raises
    ------
    click.BadParameter
        If an item is not a number or is negative.
    """
    items = [item.strip() for item in text.split(",") if item.strip()]
    if not items:
        raise click.BadParameter(f"{text!r} lists no period", param_hint="--periods")
    values = []
    for item in items:
        try:
            value = float(item)
        except ValueError as exc:
            raise click.BadParameter(
                f"{item!r} is not a number; write e.g. 0,0.1,0.2,0.5", param_hint="--periods"
            ) from exc
        if not np.isfinite(value) or value < 0.0:
            raise click.BadParameter(
                f"period {item} must be >= 0 s (0 gives the PGA)", param_hint="--periods"
            )
        values.append(value)
    return np.array(values)


def period_range(start: float, stop: float, count: int) -> np.ndarray:
    """Return ``count`` log-spaced periods [s] from ``start`` to ``stop`` inclusive.

    Raises
    ------
    click.BadParameter
        Unless ``0 < start < stop`` and ``count >= 2``.
    """
    if not (np.isfinite(start) and np.isfinite(stop)) or not 0.0 < start < stop:
        raise click.BadParameter(
            f"A={start!r} and B={stop!r} must satisfy 0 < A < B [s]", param_hint="--period-range"
        )
    if count < 2:
        raise click.BadParameter(f"N={count} must be >= 2", param_hint="--period-range")
    return np.geomspace(start, stop, count)


def _table(result: dict) -> str:
    from rockscreen.pipeline.text import printable

    lines = [
        f"# {printable(result['id'])}  damping {result['damping']:g}  "
        "(SA total, PSA pseudo; m/s^2)",
        f"{'period_s':>10}  {'sa_m_s2':>12}  {'psa_m_s2':>12}",
    ]
    for period, sa, psa in zip(
        result["periods_s"], result["sa_m_s2"], result["psa_m_s2"], strict=True
    ):
        lines.append(f"{period:>10.4g}  {sa:>12.6g}  {psa:>12.6g}")
    return "\n".join(lines)


def plot_spectrum(result: dict, path: str) -> None:
    """Draw SA and PSA against period (log axis) into a PNG file with the Agg canvas."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    periods = np.asarray(result["periods_s"])
    shown = periods > 0.0  # a log axis has no room for the PGA at T = 0
    figure = Figure(figsize=(7.0, 4.5), layout="constrained")
    FigureCanvasAgg(figure)
    axes = figure.add_subplot()
    axes.plot(periods[shown], np.asarray(result["sa_m_s2"])[shown], label="SA (total)")
    axes.plot(periods[shown], np.asarray(result["psa_m_s2"])[shown], "--", label="PSA (pseudo)")
    axes.set_xscale("log")
    axes.set_xlabel("period T [s]")
    axes.set_ylabel("spectral acceleration [m/s$^2$]")
    axes.set_title(f"{result['id']}, damping {100 * result['damping']:g} %")
    axes.grid(True, which="both", alpha=0.3)
    axes.legend()
    figure.savefig(path, dpi=120)


@click.command("spectrum")
@click.argument("file", type=click.Path())
@click.option(
    "--channel", metavar="CHA", default=None, help="Channel code or id; default first horizontal."
)
@click.option(
    "--damping",
    type=float,
    default=0.05,
    show_default=True,
    help="Damping ratio in [0, 1) (0.05 = 5 %).",
)
@click.option(
    "--periods", "periods_text", metavar="LIST", default=None, help="Periods [s]: 0,0.1,0.2,..."
)
@click.option(
    "--period-range",
    nargs=3,
    type=(float, float, int),
    metavar="A B N",
    default=None,
    help="N log-spaced periods from A to B [s]; default 0.01 10 100.",
)
@units_option()
@stations_option("StationXML: sensitivities for counts, station coordinates.")
@click.option("--json", "as_json", is_flag=True, help="Print JSON instead of a table.")
@click.option("--plot", metavar="OUT.png", default=None, help="Draw SA and PSA into a PNG.")
def cli(file, channel, damping, periods_text, period_range, units, stations, as_json, plot):
    """Elastic response spectra (SA total, PSA pseudo) of one trace of FILE, in m/s^2.

    The trace is converted to m/s^2 and its mean removed, nothing else; process the
    record first if it needs filtering. Several traces: --channel selects, default the
    first horizontal (the choice is said on stderr). FILE may be a quoted glob pattern or a
    folder that holds exactly one record file.
    """
    from rockscreen.pipeline.motion.spectra import response_spectrum

    if periods_text is not None and period_range is not None:
        raise click.UsageError("give --periods or --period-range, not both")
    if as_json and plot is not None:
        raise click.UsageError("give --json or --plot, not both")
    if periods_text is not None:
        periods = parse_periods(periods_text)
    else:
        periods = period_range_or_default(period_range)

    from rockscreen.pipeline.text import printable

    paths = expand_paths([file])
    if len(paths) != 1:
        raise click.BadParameter(
            f"{printable(file)!r} gives {len(paths)} files; spectrum reads one", param_hint="FILE"
        )
    file = paths[0]
    trace, note = read_trace(file, units=units, stations=stations, channel=channel)
    click.echo(f"rockscreen spectrum: {printable(note)}", err=True)
    for flag in trace.stats.rockscreen.get("quality_flags", []):
        click.echo(f"rockscreen: warning: {printable(trace.id)}: {printable(flag)}", err=True)

    acc = np.asarray(trace.data, dtype=float)
    acc = acc - acc.mean()  # an offset is never ground motion
    sa, psa = response_spectrum(acc, float(trace.stats.delta), periods, damping=damping)
    result = {
        "id": trace.id,
        "file": str(file),
        "damping": damping,
        "periods_s": periods.tolist(),
        "sa_m_s2": sa.tolist(),
        "psa_m_s2": psa.tolist(),
    }
    if as_json:
        click.echo(json.dumps(result, indent=2))
    elif plot is not None:
        plot_spectrum(result, plot)
        click.echo(f"wrote {printable(plot)}")
    else:
        click.echo(_table(result))


def period_range_or_default(period_range_option) -> np.ndarray:
    """Periods from ``--period-range A B N`` or, when absent, the default grid."""
    start, stop, count = period_range_option or DEFAULT_PERIOD_RANGE
    return period_range(start, stop, count)
