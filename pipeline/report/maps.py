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

The classes of assess and scenario archives (safety index I_S,
rockscreen.pipeline.risk.measures.classes) use the same ramp: ``very_high`` black, ``high``,
``moderate``, ``meets`` bluish green, ``undefined`` grey.

Labels: only the riskiest :data:`LABEL_TOWERS` towers are labelled; each label takes
the first of eight positions around its marker that overlaps no label placed before it
(riskiest first), with a leader line; stations are labelled afterwards, only where the
label overlaps nothing (the legend counts the others). The extent is fitted to the
towers with a margin, not to the stations, which may lie far away (those outside are
counted in the legend); the frame is :mod:`rockscreen.pipeline.report.map_frame`'s.
A scale bar (kilometres at the map's mean latitude) and a north arrow are drawn in the
corners; the graticule is labelled in degrees (``14.5° E``). There is no coastline or
boundary layer: rockscreen works offline and ships no such data.

Any other class name is drawn grey and listed in the legend after these. The plot
uses an equirectangular projection with the aspect set to 1/cos(mean latitude), so
that a kilometre is as long east-west as north-south at the centre of the map.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from rockscreen.pipeline.report.export import rows_without_coordinates
from rockscreen.pipeline.report.map_frame import (
    HALO,
    boxes_overlap,
    draw_north_arrow,
    draw_scale_bar,
    in_axes,
    label_points,
    map_extent,
    set_map_frame,
)
from rockscreen.pipeline.report.values import Row
from rockscreen.stations.errors import RockscreenError
from rockscreen.stations.pairing import StationSite

if TYPE_CHECKING:
    from matplotlib.axes import Axes

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
    "incomplete": "#56b4e9",
    "meets": "#009e73",
    "undefined": "#999999",
}
_OTHER_COLOUR = "#999999"
#: The riskiest towers labelled with their id (the others are identified by colour only).
LABEL_TOWERS = 12


def _text(value: object) -> str:
    return value.decode("utf-8") if isinstance(value, bytes) else str(value)


def _lat(row: Row) -> float:
    """Latitude [deg] of a summary row: ``lat_deg`` (archive format 2) or ``lat`` (1)."""
    return float(row["lat_deg"] if "lat_deg" in row else row["lat"])


def _lon(row: Row) -> float:
    """Longitude [deg] of a summary row: ``lon_deg`` (archive format 2) or ``lon`` (1)."""
    return float(row["lon_deg"] if "lon_deg" in row else row["lon"])


def risk_map_figure(summary_rows: Sequence[Row], station_sites: Sequence[StationSite]) -> Figure:
    """Draw the risk map on a new figure (no pyplot state).

    Parameters
    ----------
    summary_rows : sequence of mapping
        Per-tower summary rows with ``id``, ``lat_deg``, ``lon_deg`` [deg] (or ``lat``,
        ``lon``) and ``risk_class``.
    station_sites : sequence of StationSite
        Stations, drawn as triangles, labelled where there is room (those without
        coordinates or outside the towers' extent are left out and counted).

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
    by_class: dict[str, list[Row]] = {}
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
    station_handle = None
    if sites:
        station_handle = ax.scatter(
            [site.longitude for site in sites],
            [site.latitude for site in sites],
            marker="^",
            s=110,
            c="white",
            edgecolors="black",
            linewidths=1.2,
            zorder=4,
        )
    lons = [_lon(row) for row in towers] or [site.longitude for site in sites]
    lats = [_lat(row) for row in towers] or [site.latitude for site in sites]
    extent = map_extent(lons, lats)
    mean_latitude = set_map_frame(ax, extent)
    inside = [site for site in sites if _inside(site.longitude, site.latitude, extent)]
    figure.draw_without_rendering()  # the layout and aspect settled: pixel boxes are right
    boxes = _label_riskiest(ax, towers, order, inside)
    labelled = _label_stations(ax, inside, boxes)
    if station_handle is not None:
        station_handle.set_label(_station_legend(len(sites), len(inside), labelled))
    draw_scale_bar(ax, mean_latitude)
    draw_north_arrow(ax)
    title = f"Rocking risk of {len(towers)} tower(s)"
    if unplaced:
        title += f" ({len(unplaced)} without coordinates not shown)"
    ax.set_title(title)
    ax.legend(title="risk class", loc="best", fontsize=8)
    return figure


def _label_riskiest(
    ax: Axes, towers: list[Row], order: list[str], sites: Sequence[StationSite]
) -> list[tuple[float, float, float, float]]:
    """Label the riskiest :data:`LABEL_TOWERS` towers where their labels overlap nothing placed.

    Labels are placed greedily, riskiest first, each at the first of :data:`_OFFSETS`
    whose box (estimated from the font size: 0.6 em per character) overlaps no earlier
    label, no tower marker and no station marker (station labels are placed afterwards,
    where there is room: :func:`_label_stations`); when all eight overlap, the label goes
    twice as far out with a leader line. Returns the boxes taken [pixels].
    """
    rank = {name: i for i, name in enumerate(order)}

    def key(row: Row) -> tuple[int, float]:
        ratio = row.get("theta_max_over_alpha", math.nan)
        ratio = float(ratio) if isinstance(ratio, int | float) else math.nan
        return (rank.get(_text(row.get("risk_class", "unknown")) or "unknown", 99), -(ratio or 0))

    chosen = sorted(towers, key=key)[:LABEL_TOWERS]
    dpi_scale = ax.figure.dpi / 72.0
    obstacles = []
    for site in sites:
        x, y = ax.transData.transform((site.longitude, site.latitude))
        triangle = 7 * dpi_scale
        obstacles.append((x - triangle, y - triangle, x + triangle, y + triangle))
    return label_points(
        ax,
        [(_text(row["id"]), _lon(row), _lat(row)) for row in chosen],
        [(_lon(row), _lat(row)) for row in towers],
        obstacles,
    )


def _label_stations(
    ax: Axes, sites: Sequence[StationSite], boxes: list[tuple[float, float, float, float]]
) -> int:
    """Label the stations (below, above, right or left of the marker) where there is room.

    A label goes to the first position whose box overlaps nothing placed and stays in
    the axes. Returns the number labelled (the others are counted in the legend).
    """
    dpi_scale = ax.figure.dpi / 72.0
    labelled = 0
    for site in sites:
        x, y = ax.transData.transform((site.longitude, site.latitude))
        width, height = 0.62 * 7 * len(site.key) * dpi_scale, 9 * dpi_scale
        candidates = (
            ((0, -9), "center", "top", (x - width / 2, y - 9 * dpi_scale - height)),
            ((0, 9), "center", "bottom", (x - width / 2, y + 9 * dpi_scale)),
            ((9, 0), "left", "center", (x + 9 * dpi_scale, y - height / 2)),
            ((-9, 0), "right", "center", (x - 9 * dpi_scale - width, y - height / 2)),
        )
        free = [
            (candidate, (left, bottom, left + width, bottom + height))
            for *candidate, (left, bottom) in candidates
            if in_axes(ax, (left, bottom, left + width, bottom + height))
            and not any(
                boxes_overlap((left, bottom, left + width, bottom + height), b) for b in boxes
            )
        ]
        if not free:
            continue
        (offset, ha, va), box = free[0]
        boxes.append(box)
        labelled += 1
        ax.annotate(
            site.key,
            (site.longitude, site.latitude),
            xytext=offset,
            textcoords="offset points",
            ha=ha,
            va=va,
            fontsize=7,
            fontweight="bold",
            path_effects=HALO,
            zorder=5,
        )
    return labelled


def _station_legend(total: int, inside: int, labelled: int) -> str:
    """Return the stations' legend entry: how many, outside the map, unlabelled."""
    notes = []
    if inside < total:
        notes.append(f"{total - inside} outside the map")
    if labelled < inside:
        notes.append(f"{inside - labelled} unlabelled for want of room")
    return f"station ({total}" + (f"; {', '.join(notes)})" if notes else ")")


def _inside(lon: float, lat: float, extent: tuple[float, float, float, float]) -> bool:
    return extent[0] <= lon <= extent[1] and extent[2] <= lat <= extent[3]


def plot_risk_map(
    summary_rows: Sequence[Row],
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
