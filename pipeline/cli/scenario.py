"""``rockscreen scenario``: post-event probability of overturning from a ShakeMap grid."""

from __future__ import annotations

from pathlib import Path

import click

from rockscreen.pipeline.cli.options import example_option, out_option, path_option

EXAMPLE_GRID = "rockscreen-example-grid.xml"
EXAMPLE_ASSESS = "rockscreen-assess-example.h5"


def _is_file(text: str | None) -> bool:
    """Whether ``--towers`` names an inventory file (not a list of ids, however long)."""
    try:
        return bool(text) and Path(text).is_file()
    except OSError:  # a name too long for the file system: a list of ids
        return False


def _tower_ids(text: str | None) -> list[str] | None:
    if not text:
        return None
    path = Path(text)
    if _is_file(text):
        from rockscreen.stations.inventory import read_inventory

        return [t.id for t in read_inventory(path)]
    return [t.strip() for t in text.split(",") if t.strip()]


@click.command("scenario")
@click.option(
    "--shakemap",
    type=click.Path(exists=True, dir_okay=False),
    help="ShakeMap 3 or 4 grid.xml of the event.",
)
@path_option(
    "--fragility", help="Assess archive (rockscreen assess) holding the towers' fragilities."
)
@click.option(
    "--towers",
    "towers",
    help="Restrict to these tower ids (comma-separated) or to the towers of an inventory CSV.",
)
@click.option(
    "--strict-grid",
    is_flag=True,
    help="Refuse a grid whose row count differs from its header (default: warn).",
)
@click.option(
    "--uncertainty",
    type=click.Path(exists=True, dir_okay=False),
    help="ShakeMap 4 uncertainty.xml (STDPGA); default the one beside the grid, if any.",
)
@click.option(
    "--no-gm-uncertainty",
    is_flag=True,
    help="Take the ShakeMap PGA as known (sigma_lnPGA = 0). Default: the grid's STDPGA, "
    "its uncertainty.xml, else sigma_lnPGA = 0.776 (ITA10, Bindi et al. 2011).",
)
@out_option("Scenario archive (default rockscreen-scenario.h5).")
@click.option("--overwrite", is_flag=True, help="Replace an existing file at --out.")
@path_option(
    "--map", "map_out", help="Write a map PNG of the event PGA and the towers' probabilities."
)
@example_option(
    f"Write the embedded hypothetical event grid to ./{EXAMPLE_GRID} and use "
    f"./{EXAMPLE_ASSESS} (computed first with 'assess --example' when missing).",
)
def cli(
    shakemap,
    fragility,
    towers,
    strict_grid,
    uncertainty,
    no_gm_uncertainty,
    out,
    overwrite,
    map_out,
    example,
) -> None:
    """Probability that each tower overturns under one event (ShakeMap PGA + fragility).

    PGA at the tower by bilinear interpolation on the grid (surface), divided by the soil
    factor S of the tower's site (the fragility's ag is on rock), and
    P = Phi(ln(ag_equiv / median) / beta_tot) with beta_tot = sqrt(beta^2 + sigma_lnPGA^2)
    (STDPGA of the grid or of its uncertainty.xml, else the ITA10 total sigma 0.776). Towers
    outside the grid or without a fragility are listed, not guessed. See docs/risk.md.
    """
    from rockscreen.pipeline.cli.inputs import check_archive_path

    # Before the heavy imports: a missing or non-HDF5 --fragility is refused at once
    # (click checked that --shakemap and --uncertainty exist).
    if fragility and not example:
        check_archive_path(fragility)
    from rockscreen.pipeline.archive.lock import check_output
    from rockscreen.pipeline.report.risk_summary import SCENARIO_LEGEND, scenario_lines
    from rockscreen.pipeline.risk.scenario.run import run_scenario
    from rockscreen.pipeline.text import printable

    def say(text: str) -> None:
        click.echo(f"rockscreen: {text}", err=True)

    out_path = Path(
        out or ("rockscreen-scenario-example.h5" if example else "rockscreen-scenario.h5")
    )
    towers_file = towers if _is_file(towers) else None
    inputs = [towers_file, uncertainty]
    if example:
        inputs += [shakemap or EXAMPLE_GRID, fragility or EXAMPLE_ASSESS]
    else:
        inputs += [shakemap, fragility]
    # Before any work (the example's assess included): never an input, never an existing
    # file without --overwrite; the map is never an input nor the archive.
    check_output(out_path, inputs, overwrite=overwrite)
    if map_out:
        check_output(map_out, [*inputs, out_path], overwrite=True, option="--map")
    if example:
        from rockscreen.pipeline.risk.scenario.example_shakemap import write_example_grid

        shakemap = shakemap or str(write_example_grid(EXAMPLE_GRID))
        say(f"example event grid (hypothetical, see docs/risk.md) written to {shakemap}")
        fragility = fragility or EXAMPLE_ASSESS
        if not Path(fragility).is_file():
            from rockscreen.pipeline.cli.assess import cli as assess_cli

            say(f"{fragility} missing: running 'rockscreen assess --example' first")
            click.get_current_context().invoke(assess_cli, example=True, out=fragility)
    if not shakemap or not fragility:
        raise click.UsageError("give --shakemap GRID.xml and --fragility ASSESS.h5 (or --example)")
    rows, failures, grid = run_scenario(
        shakemap,
        fragility,
        out_path,
        tower_ids=_tower_ids(towers),
        strict_grid=strict_grid,
        uncertainty=uncertainty,
        gm_uncertainty=not no_gm_uncertainty,
        overwrite=overwrite,
        inputs=[towers_file],
        notify=say,
    )
    if map_out:
        from rockscreen.pipeline.report.risk_plots import plot_scenario_map

        say(f"map written to {plot_scenario_map(rows, grid, map_out)}")
    event = {key: printable(value) for key, value in grid.event.items()}
    click.echo(
        f"event {event.get('event_id', '?')}: M {event.get('magnitude', '?')}, "
        f"lon {event.get('lon', '?')} lat {event.get('lat', '?')} "
        f"({event.get('event_description', '')})"
    )
    for line in scenario_lines(rows):
        click.echo(line)
    click.echo(SCENARIO_LEGEND)
    from rockscreen.pipeline.report.areas import area_lines
    from rockscreen.pipeline.risk.measures.classes import SCENARIO_CLASS_NAMES

    for line in area_lines(rows, SCENARIO_CLASS_NAMES):
        click.echo(line)
    for failure in failures:
        say(f"not estimated {printable(failure['subject'])}: {printable(failure['reason'])}")
