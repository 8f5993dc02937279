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
(riskiest first), with a leader line; stations are labelled afterwards, only where the
label overlaps nothing (the legend counts the others). The extent is fitted to the
towers with a margin (:func:`map_extent`), not to the stations, which may lie far
away (those outside are counted in the legend). A scale bar (kilometres at the map's
mean latitude) and a north arrow are drawn in the corners; the graticule is labelled
in degrees (``14.5° E``). There is no coastline or boundary layer: rockscreen works
offline and ships no such data.

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

__all__ = [
    "RISK_COLOURS",
    "degrees_text",
    "draw_scale_bar",
    "label_points",
    "map_extent",
    "plot_risk_map",
    "risk_map_figure",
    "set_map_frame",
]

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
    _north_arrow(ax)
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
) -> list[tuple[float, float, float, float]]:
    """Label the riskiest :data:`LABEL_TOWERS` towers where their labels overlap nothing placed.

    Labels are placed greedily, riskiest first, each at the first of :data:`_OFFSETS`
    whose box (estimated from the font size: 0.6 em per character) overlaps no earlier
    label, no tower marker and no station marker (station labels are placed afterwards,
    where there is room: :func:`_label_stations`); when all eight overlap, the label goes
    twice as far out with a leader line. Returns the boxes taken [pixels].
    """
    rank = {name: i for i, name in enumerate(order)}

    def key(row: Mapping[str, Any]) -> tuple[int, float]:
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


def label_points(
    ax: Any,
    labels: Sequence[tuple[str, float, float]],
    markers: Sequence[tuple[float, float]] = (),
    obstacles: Sequence[tuple[float, float, float, float]] = (),
    fontsize: float = 7,
) -> list[tuple[float, float, float, float]]:
    """Label points, each where its label overlaps no marker, obstacle or earlier label.

    Greedy, in the order given (the most important first): each label takes the first
    of eight positions around its point (NE, NW, SE, SW, E, W, N, S) whose box
    (estimated from the font size) stays in the axes and overlaps nothing placed; then
    the same twice as far out with a leader line; else three times out.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        With its limits and layout settled (e.g. after ``figure.draw_without_rendering``).
    labels : sequence of (text, lon, lat)
        The labels and their points [deg], most important first.
    markers : sequence of (lon, lat), optional
        Every marker drawn (labels keep off them).
    obstacles : sequence of (x0, y0, x1, y1), optional
        Other boxes to keep off [pixels].
    fontsize : float, optional
        [points].

    Returns
    -------
    list of (x0, y0, x1, y1)
        The boxes taken [pixels]: markers, obstacles and labels.
    """
    dpi_scale = ax.figure.dpi / 72.0
    marker = 5 * dpi_scale  # marker radius [pixels]
    boxes: list[tuple[float, float, float, float]] = list(obstacles)
    for lon, lat in markers:
        x, y = ax.transData.transform((lon, lat))
        boxes.append((x - marker, y - marker, x + marker, y + marker))
    for text, lon, lat in labels:
        x, y = ax.transData.transform((lon, lat))
        width, height = 0.65 * fontsize * len(text) * dpi_scale, fontsize * 1.2 * dpi_scale
        placement = None
        for factor in (1, 2):
            for dx, dy in _OFFSETS:
                ox, oy = dx * factor * dpi_scale, dy * factor * dpi_scale
                left = x + ox - (width if dx < 0 else width / 2 if dx == 0 else 0)
                bottom = y + oy - (height if dy < 0 else 0)
                box = (left, bottom, left + width, bottom + height)
                if _in_axes(ax, box) and not any(_overlap(box, other) for other in boxes):
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
            (lon, lat),
            xytext=(dx, dy),
            textcoords="offset points",
            ha="right" if dx < 0 else "center" if dx == 0 else "left",
            va="top" if dy < 0 else "bottom" if dy > 0 else "center",
            fontsize=fontsize,
            path_effects=_HALO,
            arrowprops={"arrowstyle": "-", "linewidth": 0.5, "color": "0.3"} if far else None,
            zorder=6,
        )
    return boxes


def _label_stations(
    ax: Any, sites: Sequence[StationSite], boxes: list[tuple[float, float, float, float]]
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
            if _in_axes(ax, (left, bottom, left + width, bottom + height))
            and not any(_overlap((left, bottom, left + width, bottom + height), b) for b in boxes)
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
            path_effects=_HALO,
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


def _in_axes(ax: Any, box: tuple[float, float, float, float]) -> bool:
    """Tell whether a box [pixels] lies within the axes."""
    x0, y0, x1, y1 = ax.bbox.extents
    return x0 <= box[0] and box[2] <= x1 and y0 <= box[1] and box[3] <= y1


def _inside(lon: float, lat: float, extent: tuple[float, float, float, float]) -> bool:
    return extent[0] <= lon <= extent[1] and extent[2] <= lat <= extent[3]


#: Smallest half-width of a map [km] (a single tower is not a map of a metre).
MIN_HALF_WIDTH_KM = 2.0


def map_extent(
    lons: Sequence[float], lats: Sequence[float], margin: float = 0.18
) -> tuple[float, float, float, float]:
    """Return the map extent fitted to points: their box widened by a margin.

    Parameters
    ----------
    lons, lats : sequence of float
        The points [deg] (the towers; not the stations or a ShakeMap, which can lie
        hundreds of kilometres away and would shrink the towers into one blob).
    margin : float, optional
        Share of the box's larger side added on every side.

    Returns
    -------
    (lon_min, lon_max, lat_min, lat_max) : tuple of float
        [deg]; at least :data:`MIN_HALF_WIDTH_KM` on each side of the centre, and
        room below for the scale bar and above for the north arrow.

    Raises
    ------
    ValueError
        If there are no points.
    """
    if not len(lons):
        raise ValueError("map extent: no point")
    lat_c = (min(lats) + max(lats)) / 2
    cos = max(math.cos(math.radians(lat_c)), 0.01)
    width_km = (max(lons) - min(lons)) * 111.32 * cos
    height_km = (max(lats) - min(lats)) * 111.32
    pad_km = max(margin * max(width_km, height_km), 0.5)
    half_w = max(width_km / 2 + pad_km, MIN_HALF_WIDTH_KM) / (111.32 * cos)
    half_h = max(height_km / 2 + pad_km, MIN_HALF_WIDTH_KM) / 111.32
    lon_c = (min(lons) + max(lons)) / 2
    # Room for the scale bar below the data and the north arrow above it.
    return (lon_c - half_w, lon_c + half_w, lat_c - 1.2 * half_h, lat_c + 1.2 * half_h)


def degrees_text(value: float, positive: str, negative: str) -> str:
    """Return a graticule label in degrees: ``14.5° E``, ``3.25° W``.

    Parameters
    ----------
    value : float
        [deg].
    positive, negative : str
        Hemisphere letters (``"E"``, ``"W"`` or ``"N"``, ``"S"``).

    Returns
    -------
    str

    Examples
    --------
    >>> degrees_text(14.5, "E", "W")
    '14.5° E'
    >>> degrees_text(-0.25, "N", "S")
    '0.25° S'
    """
    text = f"{abs(value):.6f}".rstrip("0").rstrip(".")
    hemisphere = "" if text == "0" else (positive if value > 0 else negative)
    return f"{text}°" + (f" {hemisphere}" if hemisphere else "")


def set_map_frame(ax: Any, extent: tuple[float, float, float, float]) -> float:
    """Set a map's limits, its aspect and its graticule in degrees.

    Equirectangular: the aspect is 1/cos(mean latitude), so that a kilometre is as long
    east-west as north-south at the centre. No coastline or boundary is drawn (there is
    no such data offline).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    extent : (lon_min, lon_max, lat_min, lat_max)
        [deg], e.g. from :func:`map_extent`.

    Returns
    -------
    float
        The mean latitude [deg] (for :func:`draw_scale_bar`).
    """
    from matplotlib.ticker import FuncFormatter, MaxNLocator

    lon0, lon1, lat0, lat1 = extent
    mean_latitude = (lat0 + lat1) / 2
    ax.set_xlim(lon0, lon1)
    ax.set_ylim(lat0, lat1)
    ax.set_aspect(1.0 / max(math.cos(math.radians(mean_latitude)), 0.01))
    ax.xaxis.set_major_locator(MaxNLocator(nbins=6, steps=[1, 2, 2.5, 5, 10]))
    ax.yaxis.set_major_locator(MaxNLocator(nbins=7, steps=[1, 2, 2.5, 5, 10]))
    ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: degrees_text(v, "E", "W")))
    ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: degrees_text(v, "N", "S")))
    ax.set_xlabel("Longitude [° E]")
    ax.set_ylabel("Latitude [° N]")
    ax.grid(True, linewidth=0.3, alpha=0.5)
    return mean_latitude


def _overlap(a: tuple[float, ...], b: tuple[float, ...]) -> bool:
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


def draw_scale_bar(ax: Any, latitude: float) -> None:
    """Draw a scale bar [km] in the lower left corner (at the map's mean latitude).

    Parameters
    ----------
    ax : matplotlib.axes.Axes
        A map in degrees with its limits set.
    latitude : float
        The latitude [deg] at which a degree of longitude is measured.
    """
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
