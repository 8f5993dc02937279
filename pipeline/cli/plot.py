"""``rockscreen plot``: rotation histories of one tower, or the risk map, from an archive.

The archive is opened by :func:`rockscreen.pipeline.archive.kinds.open_archive`; the
figures are drawn by the ``plot`` function of its kind
(:mod:`rockscreen.pipeline.report.presenters`).
"""

from __future__ import annotations

from pathlib import Path

import click


@click.command("plot")
@click.argument("archive", type=click.Path())
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
    from rockscreen.pipeline.cli.inputs import check_archive_path

    check_archive_path(archive)  # before the heavy imports: a typo is refused at once
    from rockscreen.pipeline.archive.kinds import open_archive
    from rockscreen.pipeline.archive.lock import check_output
    from rockscreen.pipeline.report.presenters import face, presenter

    if out is not None and not Path(out).is_dir():  # a sweep's figures go into a folder
        check_output(out, [archive], overwrite=True, keep_archives=True)
    reader = open_archive(archive)
    if presenter(reader).plot_needs_choice and bool(tower_id) == as_map:
        raise click.UsageError("give exactly one of --tower ID or --map")
    for path in face(reader, "plot")(reader, tower_id, as_map, out):
        click.echo(f"rockscreen: figure written to {path}", err=True)
