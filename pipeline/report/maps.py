"""Risk map: towers by longitude and latitude coloured by risk class, with the stations.

Colours, fixed and ordered from the worst class down (a sequential red-to-green scale,
ColorBrewer "RdYlGn", readable in greyscale by lightness; ``collapse`` darkest):

==============  =========  ==============================
risk class      colour     meaning
==============  =========  ==============================
``collapse``    #67001f    overturned under some record
``high``        #d73027
``moderate``    #fc8d59
``low``         #fee08b    rocks, little
``none``        #1a9850    no appreciable rocking
``unknown``     #9e9e9e    not solved (no record paired)
==============  =========  ==============================

Any other class name is drawn grey and listed in the legend after these. The plot
uses an equirectangular projection with the aspect set to 1/cos(mean latitude), so
that a kilometre is as long east-west as north-south at the centre of the map.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import Any

from matplotlib import patheffects
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from pipeline.report.export import rows_without_coordinates
from stations.errors import RockscreenError
from stations.pairing import StationSite

__all__ = ["RISK_COLOURS", "plot_risk_map", "risk_map_figure"]

#: Risk class -> colour, in legend order (worst first).
RISK_COLOURS: dict[str, str] = {
    "collapse": "#67001f",
    "high": "#d73027",
    "moderate": "#fc8d59",
    "low": "#fee08b",
    "none": "#1a9850",
    "unknown": "#9e9e9e",
}
_OTHER_COLOUR = "#9e9e9e"
#: Towers are labelled with their id when there are at most this many on the map.
LABEL_TOWERS_UP_TO = 30
# A white halo keeps labels readable where they cross markers or grid lines.
_HALO = [patheffects.withStroke(linewidth=2.5, foreground="white")]


def _text(value: Any) -> str:
    return value.decode("utf-8") if isinstance(value, bytes) else str(value)


def risk_map_figure(
    summary_rows: Sequence[Mapping[str, Any]], station_sites: Sequence[StationSite]
) -> Figure:
    """Draw the risk map on a new figure (no pyplot state).

    Parameters
    ----------
    summary_rows : sequence of mapping
        Per-tower summary rows with ``id``, ``lat``, ``lon`` [deg] and ``risk_class``.
    station_sites : sequence of StationSite
        Stations, drawn as labelled triangles (those without coordinates are left out).

    Returns
    -------
    matplotlib.figure.Figure
        The map.

    Raises
    ------
    RockscreenError
        When neither a tower nor a station has coordinates.
    """
    unplaced = set(rows_without_coordinates(summary_rows))
    towers = [row for row in summary_rows if _text(row.get("id", "")) not in unplaced]
    sites = [site for site in station_sites if site.has_coordinates]
    if not towers and not sites:
        raise RockscreenError("risk map: no tower and no station has coordinates")
    figure = Figure(figsize=(8.0, 7.0), layout="constrained")
    FigureCanvasAgg(figure)
    ax = figure.add_subplot()
    by_class: dict[str, list[Mapping[str, Any]]] = {}
    for row in towers:
        by_class.setdefault(_text(row.get("risk_class", "unknown")) or "unknown", []).append(row)
    order = [name for name in RISK_COLOURS if name in by_class]
    order += sorted(name for name in by_class if name not in RISK_COLOURS)
    for name in order:
        rows = by_class[name]
        ax.scatter(
            [float(row["lon"]) for row in rows],
            [float(row["lat"]) for row in rows],
            s=50,
            c=RISK_COLOURS.get(name, _OTHER_COLOUR),
            edgecolors="black",
            linewidths=0.5,
            label=f"{name} ({len(rows)})",
            zorder=3,
        )
    if len(towers) <= LABEL_TOWERS_UP_TO:
        for row in towers:
            ax.annotate(
                _text(row["id"]),
                (float(row["lon"]), float(row["lat"])),
                xytext=(4, 4),
                textcoords="offset points",
                fontsize=7,
                path_effects=_HALO,
            )
    if sites:
        ax.scatter(
            [site.longitude for site in sites],
            [site.latitude for site in sites],
            marker="^",
            s=110,
            c="white",
            edgecolors="black",
            linewidths=1.2,
            label=f"station ({len(sites)})",
            zorder=4,
        )
        for site in sites:
            ax.annotate(
                site.key,
                (site.longitude, site.latitude),
                xytext=(0, -14),
                textcoords="offset points",
                ha="center",
                fontsize=8,
                fontweight="bold",
                path_effects=_HALO,
                zorder=5,
            )
    latitudes = [float(row["lat"]) for row in towers] + [site.latitude for site in sites]
    mean_latitude = sum(latitudes) / len(latitudes)
    ax.set_aspect(1.0 / max(math.cos(math.radians(mean_latitude)), 0.01))
    ax.margins(0.1)
    ax.set_xlabel("Longitude [° E]")
    ax.set_ylabel("Latitude [° N]")
    ax.grid(True, linewidth=0.3, alpha=0.5)
    title = f"Rocking risk of {len(towers)} tower(s)"
    if unplaced:
        title += f" ({len(unplaced)} without coordinates not shown)"
    ax.set_title(title)
    ax.legend(title="risk class", loc="best", fontsize=8)
    return figure


def plot_risk_map(
    summary_rows: Sequence[Mapping[str, Any]],
    station_sites: Sequence[StationSite],
    out_png: str | Path,
) -> Path:
    """Save the risk map (:func:`risk_map_figure`) as a PNG.

    Parameters
    ----------
    summary_rows : sequence of mapping
        Per-tower summary rows with ``id``, ``lat``, ``lon`` [deg] and ``risk_class``.
    station_sites : sequence of StationSite
        Stations drawn as labelled triangles.
    out_png : str or Path
        Output file.

    Returns
    -------
    Path
        The written PNG.
    """
    out_png = Path(out_png)
    risk_map_figure(summary_rows, station_sites).savefig(out_png, dpi=150)
    return out_png
