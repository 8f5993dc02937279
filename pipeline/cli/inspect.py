"""``rockscreen inspect``: metadata, tree and per-tower summary of an archive.

The archive is opened by :func:`rockscreen.pipeline.archive.kinds.open_archive` (an
unknown kind or ``format_version`` is refused with one line) and printed by the
``inspect`` function of its kind (:mod:`rockscreen.pipeline.report.presenters`).
Everything printed that comes from the archive (ids, station codes, metadata, the tree,
failure reasons) goes through :func:`rockscreen.pipeline.text.printable` in the text view, and is
JSON-escaped in the ``--json`` view, so a crafted archive cannot send control sequences
to the terminal.
"""

from __future__ import annotations

from typing import Any

import click


@click.command("inspect")
@click.argument("archive", type=click.Path())
@click.option("--json", "as_json", is_flag=True, help="Print one JSON document instead.")
def cli(archive: str, as_json: bool) -> None:
    """Show an archive's run metadata, its tree and the per-tower summary.

    JSON keys: metadata, towers (id, name, lat_deg, lon_deg, theta_max_over_alpha,
    overturned, safety_factor, risk_class, governing_record = NET.STA.LOC.CHA,
    governing_model, ...), failures.
    An infinite safety factor is null with a safety_factor_note.
    """
    from rockscreen.pipeline.cli.inputs import check_archive_path

    check_archive_path(archive)  # before the heavy imports: a typo is refused at once
    from rockscreen.pipeline.archive.kinds import open_archive
    from rockscreen.pipeline.report.presenters import face
    from rockscreen.pipeline.text import printable

    def echo(line: Any) -> None:
        # Text read from the archive is escaped line by line (JSON escapes its own).
        click.echo("\n".join(printable(part) for part in str(line).split("\n")))

    reader = open_archive(archive)
    face(reader, "inspect")(reader, as_json, click.echo if as_json else echo)
