"""``inspect``, ``plot`` and ``export`` of assess and scenario archives (the CLI dispatches here).

- :func:`inspect_risk`: metadata, tree and ranked summary; with JSON, every assessed tower
  carries ``fragility_median_g``, ``fragility_beta``, ``annual_rate_overturning``,
  ``p_overturning_50y``, ``capacity_pga_g``, ``capacity_return_period_y``,
  ``safety_index``, ``acceleration_factor`` (null with a ``<key>_note`` when undefined,
  a ``<key>_note`` naming the bound when the median is a bound);
- :func:`plot_risk`: fragility curve with stripe points (``--tower``) or the I_S map
  (``--map``) of an assess archive; the probability map of a scenario archive;
"""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path

from rockscreen.pipeline.archive.campaign import archive_tree
from rockscreen.pipeline.archive.risk_archive import (
    archive_kind,
    read_failures,
    read_metadata,
    read_stripes,
    read_summary,
)
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.risk.classes import rank_towers
from rockscreen.pipeline.risk.plots import plot_fragility, plot_safety_map, plot_scenario_map
from rockscreen.pipeline.risk.shakemap import read_shakemap_grid
from rockscreen.pipeline.risk.summary import (
    ASSESS_LEGEND,
    SCENARIO_LEGEND,
    assess_lines,
    json_number,
    scenario_lines,
    tower_json,
)

__all__ = ["inspect_risk", "plot_risk"]


def inspect_risk(archive: str | Path, as_json: bool, echo: Callable[[str], None]) -> None:
    """Print an assess or scenario archive (module docstring)."""
    meta = read_metadata(archive)
    rows = read_summary(archive)
    kind = meta["kind"]
    if as_json:
        towers = (
            [tower_json(r) for r in rank_towers(rows)]
            if kind == "assess"
            else [{k: json_number(v) for k, v in r.items()} for r in rows]
        )
        document = {
            "metadata": {k: json_number(v) for k, v in meta.items()},
            "towers": towers,
            "failures": read_failures(archive),
        }
        echo(json.dumps(document, indent=2))
        return
    echo(f"archive {archive} ({kind})")
    for key, value in meta.items():
        echo(f"  {key}: {value}")
    echo("tree:")
    try:
        for line in archive_tree(archive):
            echo(f"  {line}")
    except Exception:  # noqa: BLE001 - the tree is informative only
        pass
    echo("towers (riskiest first):" if kind == "assess" else "towers:")
    for line in assess_lines(rows) if kind == "assess" else scenario_lines(rows):
        echo(f"  {line}")
    echo(ASSESS_LEGEND if kind == "assess" else SCENARIO_LEGEND)


def plot_risk(archive: str | Path, tower_id: str | None, as_map: bool, out: str | None) -> Path:
    """Draw the figure of an assess or scenario archive and return its path."""
    kind = archive_kind(archive)
    summary = read_summary(archive)
    if kind == "scenario":
        source = read_metadata(archive)["shakemap_source"]
        if not Path(source).is_file():
            raise ArchiveError(f"the scenario's ShakeMap grid {source!r} is no longer there")
        return plot_scenario_map(
            summary, read_shakemap_grid(source), out or "rockscreen-scenario.png"
        )
    if as_map:
        return plot_safety_map(summary, out or "rockscreen-assess-map.png")
    safe = "".join(c if c.isalnum() or c in "-_." else "_" for c in str(tower_id))
    return plot_fragility(
        tower_id, summary, read_stripes(archive), out or f"rockscreen-{safe}-fragility.png"
    )
