"""``inspect`` and ``plot`` of a campaign archive (``rockscreen run``; :mod:`.presenters`).

Everything printed that comes from the archive (ids, station codes, metadata, the tree,
failure reasons) goes through the ``echo`` the command gives (which escapes it with
:func:`rockscreen.pipeline.text.printable` in the text view); the ``--json`` view is
JSON-escaped, so a crafted archive cannot send control sequences to the terminal.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from pathlib import Path

from rockscreen.pipeline.archive.kinds import RunReader
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.report.risk_summary import json_number
from rockscreen.pipeline.report.summary import rank_towers, summary_lines
from rockscreen.pipeline.report.values import Attrs, JSONValue, Row

__all__ = ["inspect_run", "plot_run", "tower_json"]

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
#: Root attributes printed at the top of the text view, in this order.
_HEADER_KEYS = (
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
)


def tower_json(row: Row) -> dict[str, JSONValue]:
    """Return one summary row as JSON-ready dict (non-finite numbers -> null, with a note)."""
    out: dict[str, JSONValue] = {key: json_number(row.get(key)) for key in _JSON_KEYS}
    sf = row.get("safety_factor")
    if isinstance(sf, float) and math.isinf(sf):
        out["safety_factor_note"] = "no overturning up to the search cap (infinite)"
    elif isinstance(sf, float) and math.isnan(sf):
        out["safety_factor_note"] = "not searched"
    return out


def _metadata_json(meta: Attrs) -> dict[str, JSONValue]:
    out: dict[str, JSONValue] = {}
    for key, value in meta.items():
        if key in {"record_files"} and isinstance(value, str):
            try:
                value = json.loads(value)
            except ValueError:
                pass
        out[key] = json_number(value)
    return out


def inspect_run(reader: RunReader, as_json: bool, echo: Callable[[str], None]) -> None:
    """Print a campaign archive: metadata, configuration, tree, towers, failures.

    Parameters
    ----------
    reader : RunReader
        The archive.
    as_json : bool
        One JSON document (metadata, towers riskiest first, failures) instead of text.
    echo : callable
        Prints one line (the command escapes archive text in the text view).
    """
    meta = reader.metadata()
    rows = reader.summary()
    failures = reader.failures()
    if as_json:
        document = {
            "metadata": _metadata_json(meta),
            "towers": [tower_json(row) for row in rank_towers(rows)],
            "failures": failures,
        }
        echo(json.dumps(document, indent=2, default=str))
        return
    echo(f"archive {reader.path}")
    for key in _HEADER_KEYS:
        echo(f"  {key}: {meta.get(key, '')}")
    echo("configuration:")
    for line in str(meta.get("config_toml", "")).splitlines():
        echo(f"  {line}")
    echo("tree:")
    for line in reader.tree():
        echo(f"  {line}")
    echo("towers (riskiest first):")
    for line in summary_lines(rows):
        echo(f"  {line}")
    if failures:
        echo("failures:")
        for failure in failures:
            echo(f"  {failure['kind']}: {failure['subject']}: {failure['reason']}")


def plot_run(reader: RunReader, tower_id: str | None, as_map: bool, out: str | None) -> list[Path]:
    """Draw the risk map (``as_map``) or one tower's rotation histories; return the PNG path.

    Raises
    ------
    ArchiveError
        If the archive keeps no time histories of the tower.
    """
    if as_map:
        from rockscreen.pipeline.report.maps import plot_risk_map
        from rockscreen.stations.pairing import StationSite

        sites = [StationSite(s["key"], s["latitude"], s["longitude"]) for s in reader.stations()]
        return [Path(plot_risk_map(reader.summary(), sites, out or "rockscreen-map.png"))]
    from rockscreen.pipeline.report.plots import save_tower_histories, tower_figure_details

    histories = reader.histories(tower_id)
    if not histories:
        raise ArchiveError(
            f"tower {tower_id!r}: {reader.path} keeps no time histories "
            '(rerun with [output] histories = "decimated" or "full")'
        )
    safe = "".join(c if c.isalnum() or c in "-_." else "_" for c in tower_id)
    details = tower_figure_details(reader.path, tower_id)
    path = save_tower_histories(tower_id, histories, out or f"rockscreen-{safe}.png", **details)
    return [Path(path)]
