"""``rockscreen plot``: rotation histories of one tower, or the risk map, from an archive."""

from __future__ import annotations

from pathlib import Path

import click


@click.command("plot")
@click.argument("archive", type=click.Path(dir_okay=False))
@click.option("--tower", "tower_id", help="Tower id: plot its rotation time histories.")
@click.option("--map", "as_map", is_flag=True, help="Plot the towers coloured by risk class.")
@click.option(
    "--out",
    type=click.Path(),
    help="PNG file (default from the id); for a sweep archive, the folder of the figures.",
)
def cli(archive: str, tower_id: str | None, as_map: bool, out: str | None) -> None:
    """Plot theta/alpha time histories of a tower (--tower ID) or the risk map (--map).

    The histories are those the archive keeps (``[output] histories``): by default the
    worst component of every record and model, decimated with peaks preserved.
    A sweep archive (``rockscreen sweep``) needs neither option: its figures (rotation
    histories per group, one colour per frequency) are written to the folder ``--out``.
    """
    from rockscreen.pipeline.archive.risk_archive import archive_kind

    if archive_kind(archive) in ("assess", "scenario"):  # rockscreen.pipeline.risk: issue 14
        from rockscreen.pipeline.risk.inspect import plot_risk

        if archive_kind(archive) == "assess" and bool(tower_id) == as_map:
            raise click.UsageError("give exactly one of --tower ID or --map")
        path = plot_risk(archive, tower_id, as_map, out)
        click.echo(f"rockscreen: figure written to {path}", err=True)
        return
    from rockscreen.pipeline.archive.campaign import read_histories, read_stations, read_summary
    from rockscreen.pipeline.errors import ArchiveError
    from rockscreen.pipeline.study.sweep import is_sweep_archive

    if Path(archive).is_file() and is_sweep_archive(archive):
        from rockscreen.pipeline.report.sweep_plots import plot_sweep

        for path in plot_sweep(archive, out or "."):
            click.echo(f"rockscreen: figure written to {path}", err=True)
        return
    if bool(tower_id) == as_map:
        raise click.UsageError("give exactly one of --tower ID or --map")
    if as_map:
        from rockscreen.pipeline.report.maps import plot_risk_map
        from rockscreen.stations.pairing import StationSite

        sites = [
            StationSite(s["key"], s["latitude"], s["longitude"]) for s in read_stations(archive)
        ]
        path = plot_risk_map(read_summary(archive), sites, out or "rockscreen-map.png")
    else:
        from rockscreen.pipeline.report.plots import save_tower_histories, tower_figure_details

        histories = read_histories(archive, tower_id)
        if not histories:
            raise ArchiveError(
                f"tower {tower_id!r}: {archive} keeps no time histories "
                '(rerun with [output] histories = "decimated" or "full")'
            )
        safe = "".join(c if c.isalnum() or c in "-_." else "_" for c in tower_id)
        details = tower_figure_details(archive, tower_id)
        path = save_tower_histories(tower_id, histories, out or f"rockscreen-{safe}.png", **details)
    click.echo(f"rockscreen: figure written to {Path(path)}", err=True)
