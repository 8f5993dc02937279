"""Risk map: towers by longitude and latitude coloured by risk class, with the stations.

Colours, fixed and ordered from the worst class down, from the colour-blind-safe
palette of Okabe & Ito (2008) (the HTML report uses the same): black for the worst,
then vermillion, orange, yellow and bluish green, told apart with every common colour
vision deficiency and by lightness in greyscale. Markers have a black edge so that the
yellow reads on white.

==============  =========  ==============================
risk class      colour     meaning
==============  =========  ==============================
``collapse``    #000000    overturned under some record
``high``        #d55e00
``moderate``    #e69f00
``low``         #f0e442    rocks, little
``none``        #009e73    no appreciable rocking
``unknown``     #999999    not solved (no record paired)
==============  =========  ==============================

The classes of assess and scenario archives (safety index I_S, rockscreen.pipeline.risk.classes)
use the same ramp: ``very_high`` black, ``high``, ``moderate``, ``meets`` bluish green,
``undefined`` grey.

Labels: only the riskiest :data:`LABEL_TOWERS` towers are labelled; each label takes
the first of eight positions around its marker that overlaps no label placed before it
(riskiest first), with a leader line; stations are always labelled. A scale bar
(kilometres at the map's mean latitude) and a north arrow are drawn in the corners.

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

from rockscreen.pipeline.report.export import rows_without_coordinates
from rockscreen.stations.errors import RockscreenError
from rockscreen.stations.pairing import StationSite

__all__ = ["RISK_COLOURS", "plot_risk_map", "risk_map_figure"]

#: Risk class -> colour, in legend order (worst first).
RISK_COLOURS: dict[str, str] = {
    "collapse": "#000000",
    "high": "#d55e00",
    "moderate": "#e69f00",
    "low": "#f0e442",
    "none": "#009e73",
    "unknown": "#999999",
    "very_high": "#000000",
    "meets": "#009e73",
    "undefined": "#999999",
}
_OTHER_COLOUR = "#999999"
#: The riskiest towers labelled with their id (the others are identified by colour only).
LABEL_TOWERS = 12
# A white halo keeps labels readable where they cross markers or grid lines.
_HALO = [patheffects.withStroke(linewidth=2.5, foreground="white")]


def _text(value: Any) -> str:
    return value.decode("utf-8") if isinstance(value, bytes) else str(value)


def _lat(row: Mapping[str, Any]) -> float:
    """Latitude [deg] of a summary row: ``lat_deg`` (archive format 2) or ``lat`` (1)."""
    return float(row["lat_deg"] if "lat_deg" in row else row["lat"])


def _lon(row: Mapping[str, Any]) -> float:
    """Longitude [deg] of a summary row: ``lon_deg`` (archive format 2) or ``lon`` (1)."""
    return float(row["lon_deg"] if "lon_deg" in row else row["lon"])


def risk_map_figure(
    summary_rows: Sequence[Mapping[str, Any]], station_sites: Sequence[StationSite]
) -> Figure:
    """Draw the risk map on a new figure (no pyplot state).

    Parameters
    ----------
    summary_rows : sequence of mapping
        Per-tower summary rows with ``id``, ``lat_deg``, ``lon_deg`` [deg] (or ``lat``,
        ``lon``) and ``risk_class``.
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
            [_lon(row) for row in rows],
            [_lat(row) for row in rows],
            s=50,
            c=RISK_COLOURS.get(name, _OTHER_COLOUR),
            edgecolors="black",
            linewidths=0.5,
            label=f"{name} ({len(rows)})",
            zorder=3,
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
    latitudes = [_lat(row) for row in towers] + [site.latitude for site in sites]
    mean_latitude = sum(latitudes) / len(latitudes)
    ax.set_aspect(1.0 / max(math.cos(math.radians(mean_latitude)), 0.01))
    ax.margins(0.1)
    ax.autoscale_view()
    # Room for the scale bar below the data and the north arrow above it.
    y0, y1 = ax.get_ylim()
    ax.set_ylim(y0 - 0.1 * (y1 - y0), y1 + 0.1 * (y1 - y0))
    _label_riskiest(ax, towers, order, sites)
    _scale_bar(ax, mean_latitude)
    _north_arrow(ax)
    ax.set_xlabel("Longitude [° E]")
    ax.set_ylabel("Latitude [° N]")
    ax.grid(True, linewidth=0.3, alpha=0.5)
    title = f"Rocking risk of {len(towers)} tower(s)"
    if unplaced:
        title += f" ({len(unplaced)} without coordinates not shown)"
    ax.set_title(title)
    ax.legend(title="risk class", loc="best", fontsize=8)
    return figure


# Label positions tried around a marker [points], nearest first: NE, NW, SE, SW, E, W, N, S.
_OFFSETS = ((7, 7), (-7, 7), (7, -9), (-7, -9), (10, 0), (-10, 0), (0, 11), (0, -13))


def _label_riskiest(
    ax: Any, towers: list[Mapping[str, Any]], order: list[str], sites: Sequence[StationSite]
) -> None:
    """Label the riskiest :data:`LABEL_TOWERS` towers where their labels overlap nothing placed.

    Labels are placed greedily, riskiest first, each at the first of :data:`_OFFSETS`
    whose box (estimated from the font size: 0.6 em per character) overlaps no earlier
    label, no tower marker and no station with its label; when all eight overlap, the
    label goes twice as far out with a leader line.
    """
    rank = {name: i for i, name in enumerate(order)}

    def key(row: Mapping[str, Any]) -> tuple[int, float]:
        ratio = row.get("theta_max_over_alpha", math.nan)
        ratio = float(ratio) if isinstance(ratio, int | float) else math.nan
        return (rank.get(_text(row.get("risk_class", "unknown")) or "unknown", 99), -(ratio or 0))

    chosen = sorted(towers, key=key)[:LABEL_TOWERS]
    dpi_scale = ax.figure.dpi / 72.0
    boxes: list[tuple[float, float, float, float]] = []
    fontsize = 7
    marker = 5 * dpi_scale  # marker radius [pixels]
    for row in towers:
        x, y = ax.transData.transform((_lon(row), _lat(row)))
        boxes.append((x - marker, y - marker, x + marker, y + marker))
    for site in sites:
        x, y = ax.transData.transform((site.longitude, site.latitude))
        half = 0.6 * 8 * len(site.key) * dpi_scale / 2
        boxes.append((x - max(half, marker), y - 22 * dpi_scale, x + max(half, marker), y + marker))
    for row in chosen:
        text = _text(row["id"])
        x, y = ax.transData.transform((_lon(row), _lat(row)))
        width, height = 0.6 * fontsize * len(text) * dpi_scale, fontsize * 1.2 * dpi_scale
        placement = None
        for factor in (1, 2):
            for dx, dy in _OFFSETS:
                ox, oy = dx * factor * dpi_scale, dy * factor * dpi_scale
                left = x + ox - (width if dx < 0 else width / 2 if dx == 0 else 0)
                bottom = y + oy - (height if dy < 0 else 0)
                box = (left, bottom, left + width, bottom + height)
                if not any(_overlap(box, other) for other in boxes):
                    placement = (dx * factor, dy * factor, box)
                    break
            if placement is not None:
                break
        if placement is None:
            dx, dy = _OFFSETS[0][0] * 3, _OFFSETS[0][1] * 3
            placement = (dx, dy, (x, y, x, y))
        dx, dy, box = placement
        boxes.append(box)
        far = abs(dx) > 12 or abs(dy) > 14
        ax.annotate(
            text,
            (_lon(row), _lat(row)),
            xytext=(dx, dy),
            textcoords="offset points",
            ha="right" if dx < 0 else "center" if dx == 0 else "left",
            va="top" if dy < 0 else "bottom" if dy > 0 else "center",
            fontsize=fontsize,
            path_effects=_HALO,
            arrowprops={"arrowstyle": "-", "linewidth": 0.5, "color": "0.3"} if far else None,
            zorder=6,
        )


def _overlap(a: tuple[float, ...], b: tuple[float, ...]) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def _scale_bar(ax: Any, latitude: float) -> None:
    """Draw a scale bar [km] in the lower left corner (at the map's mean latitude)."""
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    km_per_degree = 111.32 * max(math.cos(math.radians(latitude)), 0.01)
    target = (x1 - x0) * km_per_degree / 5
    exponent = 10 ** math.floor(math.log10(target))
    length = next(v * exponent for v in (5, 2, 1) if v * exponent <= target)
    width = length / km_per_degree
    left, bottom = x0 + 0.04 * (x1 - x0), y0 + 0.05 * (y1 - y0)
    ax.plot([left, left + width], [bottom, bottom], color="black", linewidth=3, zorder=6)
    label = f"{length:g} km" if length >= 1 else f"{length * 1000:g} m"
    ax.text(
        left + width / 2,
        bottom + 0.015 * (y1 - y0),
        label,
        ha="center",
        va="bottom",
        fontsize=8,
        path_effects=_HALO,
        zorder=6,
    )


def _north_arrow(ax: Any) -> None:
    """Draw a north arrow in the upper right corner (north is up in this projection)."""
    ax.annotate(
        "N",
        xy=(0.97, 0.98),
        xytext=(0.97, 0.9),
        xycoords="axes fraction",
        ha="center",
        va="top",
        fontsize=10,
        fontweight="bold",
        arrowprops={"arrowstyle": "-|>", "color": "black", "linewidth": 1.5},
        zorder=6,
    )


def plot_risk_map(
    summary_rows: Sequence[Mapping[str, Any]],
    station_sites: Sequence[StationSite],
    out_png: str | Path,
) -> Path:
    """Save the risk map (:func:`risk_map_figure`) as a PNG.

    Parameters
    ----------
    summary_rows, station_sites
        As in :func:`risk_map_figure`.
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
