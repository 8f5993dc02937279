"""``rockscreen report``: one self-contained HTML page of an archive, for a browser."""

from __future__ import annotations

from pathlib import Path

import click

from rockscreen.pipeline.cli.options import out_option


@click.command("report")
@click.argument("archive", type=click.Path())
@out_option("HTML file (default: the archive's name with .html).")
@click.option(
    "--lang",
    type=click.Choice(["en", "it"]),
    default="en",
    show_default=True,
    help="Language of the page.",
)
def cli(archive: str, out: str | None, lang: str) -> None:
    """Write the HTML report of a run, assess, scenario or sweep archive.

    One file with everything inline (map, sortable table with CSV export, one sheet per
    tower, method and limits); it opens offline from a USB stick or an e-mail. A
    background map is fetched only if the reader ticks its box while online.
    """
    from rockscreen.pipeline.cli.inputs import check_archive_path

    check_archive_path(archive)  # before the heavy imports: a typo is refused at once
    from rockscreen.pipeline.archive.lock import check_output
    from rockscreen.pipeline.report.html import build_report

    out = out or Path(archive).with_suffix(".html")
    check_output(out, [archive], overwrite=True, keep_archives=True)
    path = build_report(archive, out, lang)
    size = path.stat().st_size / 1e6
    click.echo(f"rockscreen: report written to {path} ({size:.2f} MB)", err=True)
