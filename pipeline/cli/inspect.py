"""``rockscreen inspect``: metadata, tree and per-tower summary of a campaign archive.

Everything printed that comes from the archive (ids, station codes, metadata, the tree,
failure reasons) goes through :func:`rockscreen.pipeline.text.printable` in the text view, and is
JSON-escaped in the ``--json`` view, so a crafted archive cannot send control sequences
to the terminal. An archive of an unknown ``format_version`` is refused with one line.
"""

from __future__ import annotations

import json
import math
from typing import Any

import click

from rockscreen.pipeline.risk.summary import json_number

#: Summary keys shown in the JSON output of every tower.
_JSON_KEYS = (
    "id",
    "name",
    "lat_deg",
    "lon_deg",
    "stations",
    "n_records",
    "theta_max_over_alpha",
    "theta_max_rad",
    "alpha_rad",
    "overturned",
    "safety_factor",
    "risk_class",
    "governing_record",
    "governing_model",
    "governing_component",
)


def tower_json(row: dict[str, Any]) -> dict[str, Any]:
    """Return one summary row as JSON-ready dict (non-finite numbers -> null, with a note)."""
    out = {key: json_number(row.get(key)) for key in _JSON_KEYS}
    sf = row.get("safety_factor")
    if isinstance(sf, float) and math.isinf(sf):
        out["safety_factor_note"] = "no overturning up to the search cap (infinite)"
    elif isinstance(sf, float) and math.isnan(sf):
        out["safety_factor_note"] = "not searched"
    return out


def _metadata_json(meta: dict[str, Any]) -> dict[str, Any]:
    out = {}
    for key, value in meta.items():
        if key in {"record_files"} and isinstance(value, str):
            try:
                value = json.loads(value)
            except ValueError:
                pass
        out[key] = json_number(value)
    return out


@click.command("inspect")
@click.argument("archive", type=click.Path(dir_okay=False))
@click.option("--json", "as_json", is_flag=True, help="Print one JSON document instead.")
def cli(archive: str, as_json: bool) -> None:
    """Show an archive's run metadata, its tree and the per-tower summary.

    JSON keys: metadata, towers (id, name, lat_deg, lon_deg, theta_max_over_alpha,
    overturned, safety_factor, risk_class, governing_record = NET.STA.LOC.CHA,
    governing_model, ...), failures.
    An infinite safety factor is null with a safety_factor_note.
    """
    from rockscreen.pipeline.archive.risk_archive import archive_kind
    from rockscreen.pipeline.text import printable

    def echo(line: Any) -> None:
        # Text read from the archive is escaped line by line (JSON escapes its own).
        click.echo("\n".join(printable(part) for part in str(line).split("\n")))

    if archive_kind(archive) in ("assess", "scenario"):  # rockscreen.pipeline.risk: issue 14
        from rockscreen.pipeline.risk.inspect import inspect_risk

        return inspect_risk(archive, as_json, click.echo if as_json else echo)
    from rockscreen.pipeline.archive.campaign import (
        archive_tree,
        read_failures,
        read_metadata,
        read_summary,
    )
    from rockscreen.pipeline.report.summary import rank_towers, summary_lines

    meta = read_metadata(archive)
    rows = read_summary(archive)
    failures = read_failures(archive)
    if as_json:
        document = {
            "metadata": _metadata_json(meta),
            "towers": [tower_json(row) for row in rank_towers(rows)],
            "failures": failures,
        }
        click.echo(json.dumps(document, indent=2, default=str))
        return
    echo(f"archive {archive}")
    for key in (
        "rockscreen_version",
        "format_version",
        "created_utc",
        "command_line",
        "inventory_source",
        "stations_source",
        "n_towers",
        "n_records",
        "n_cases",
        "n_failures",
    ):
        echo(f"  {key}: {meta.get(key, '')}")
    click.echo("configuration:")
    for line in str(meta.get("config_toml", "")).splitlines():
        echo(f"  {line}")
    click.echo("tree:")
    for line in archive_tree(archive):
        echo(f"  {line}")
    click.echo("towers (riskiest first):")
    for line in summary_lines(rows):
        echo(f"  {line}")
    if failures:
        click.echo("failures:")
        for failure in failures:
            echo(f"  {failure['kind']}: {failure['subject']}: {failure['reason']}")
