"""``inspect`` and ``plot`` of assess and scenario archives (:mod:`.presenters` names them).

- :func:`inspect_assess`, :func:`inspect_scenario`: metadata, tree and ranked summary;
  with JSON, every assessed tower carries ``fragility_median_g``, ``fragility_beta``,
  ``annual_rate_overturning``, ``p_overturning_50y``, ``capacity_pga_g``,
  ``capacity_return_period_y``, ``safety_index``, ``acceleration_factor`` (null with a
  ``<key>_note`` when undefined, a ``<key>_note`` naming the bound when the median is a
  bound), and its screening risk as a ``risk`` object
  (:func:`~rockscreen.pipeline.report.risk_ranking.risk_json`; the text view lists the ranks);
- :func:`plot_assess`: fragility curve with stripe points (``--tower``) or the I_S map
  (``--map``); :func:`plot_scenario`: the probability map of a scenario archive.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Sequence
from pathlib import Path

from rockscreen.pipeline.archive.kinds import AssessReader, ScenarioReader
from rockscreen.pipeline.archive.long_schema import CheckColumns
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.hazard.shakemap import read_shakemap_grid
from rockscreen.pipeline.report.risk_plots import (
    plot_fragility,
    plot_safety_map,
    plot_scenario_map,
)
from rockscreen.pipeline.report.risk_ranking import RANKING_LEGEND, ranking_lines, risk_json
from rockscreen.pipeline.report.risk_summary import (
    ASSESS_LEGEND,
    SCENARIO_LEGEND,
    assess_lines,
    json_number,
    rank_towers,
    scenario_lines,
    tower_json,
)
from rockscreen.pipeline.report.values import ColumnValue, JSONValue, Row

__all__ = ["inspect_assess", "inspect_scenario", "plot_assess", "plot_scenario"]


def _inspect(
    reader: AssessReader | ScenarioReader,
    as_json: bool,
    echo: Callable[[str], None],
    towers: Callable[[list[dict[str, ColumnValue]]], list[dict[str, JSONValue]]],
    heading: str,
    lines: Callable[[Sequence[Row]], list[str]],
    legend: str,
) -> None:
    meta = reader.metadata()
    rows = reader.summary()
    if as_json:
        document = {
            "metadata": {k: json_number(v) for k, v in meta.items()},
            "towers": towers(rows),
            "failures": reader.failures(),
        }
        echo(json.dumps(document, indent=2))
        return
    echo(f"archive {reader.path} ({reader.kind})")
    for key, value in meta.items():
        echo(f"  {key}: {value}")
    echo("tree:")
    try:
        for line in reader.tree():
            echo(f"  {line}")
    except Exception:  # noqa: BLE001 - the tree is informative only
        pass
    echo(heading)
    for line in lines(rows):
        echo(f"  {line}")
    echo(legend)
    failures = reader.failures()
    if failures:
        echo(f"not assessed ({len(failures)}, /failures):")
        for failure in failures:
            echo(f"  {failure['kind']}: {failure['subject']}: {failure['reason']}")


def inspect_assess(reader: AssessReader, as_json: bool, echo: Callable[[str], None]) -> None:
    """Print an assess archive: towers riskiest first (module docstring)."""
    checks = reader.checks()  # every check it stores (a check added as a module too)
    _inspect(
        reader,
        as_json,
        echo,
        lambda rows: [_with_risk(r, checks) for r in rank_towers(rows)],
        "towers (riskiest first):",
        lambda rows: [*assess_lines(rows, checks), *ranking_lines(rows, top=len(rows))],
        f"{ASSESS_LEGEND}\n{RANKING_LEGEND}",
    )


def _with_risk(row: Row, checks: Sequence[CheckColumns]) -> dict[str, JSONValue]:
    """Return a tower's JSON with its screening risk as the ``risk`` object (None: older)."""
    risk = risk_json(row) if "risk_p50_best" in row else None
    return {**tower_json(row, checks), "risk": risk}


def inspect_scenario(reader: ScenarioReader, as_json: bool, echo: Callable[[str], None]) -> None:
    """Print a scenario archive: towers by probability of overturning (module docstring)."""
    _inspect(
        reader,
        as_json,
        echo,
        lambda rows: [{k: json_number(v) for k, v in r.items()} for r in rows],
        "towers:",
        scenario_lines,
        SCENARIO_LEGEND,
    )


def plot_assess(
    reader: AssessReader, tower_id: str | None, as_map: bool, out: str | None
) -> list[Path]:
    """Draw the I_S map (``as_map``) or one tower's fragility curve; return the PNG path."""
    summary = reader.summary()
    if as_map:
        return [plot_safety_map(summary, out or "rockscreen-assess-map.png")]
    safe = "".join(c if c.isalnum() or c in "-_." else "_" for c in str(tower_id))
    return [
        plot_fragility(
            tower_id,
            summary,
            reader.stripes(),
            out or f"rockscreen-{safe}-fragility.png",
            ida=reader.ida(),
            risk_band=reader.risk_fragility(),
        )
    ]


def plot_scenario(
    reader: ScenarioReader, tower_id: str | None, as_map: bool, out: str | None
) -> list[Path]:
    """Draw the scenario map (event PGA, towers' probabilities); return the PNG path.

    Raises
    ------
    ArchiveError
        If the scenario's ShakeMap grid (``shakemap_source``) is no longer there.
    """
    summary = reader.summary()
    source = reader.metadata()["shakemap_source"]
    if not Path(source).is_file():
        raise ArchiveError(f"the scenario's ShakeMap grid {source!r} is no longer there")
    return [
        plot_scenario_map(summary, read_shakemap_grid(source), out or "rockscreen-scenario.png")
    ]
