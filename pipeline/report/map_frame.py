"""The frame of every PNG map: extent, graticule, scale bar, north arrow, labels.

Shared by the run's risk map (:mod:`rockscreen.pipeline.report.maps`) and the assess and
scenario maps (:mod:`rockscreen.pipeline.report.risk_plots`). The extent is fitted to the
towers with a margin (:func:`map_extent`), not to the stations or a ShakeMap; the plot uses
an equirectangular projection with the aspect set to 1/cos(mean latitude), so that a
kilometre is as long east-west as north-south at the centre of the map; the graticule is
labelled in degrees (``14.5° E``); coastlines and national borders come from the shipped
offline base map (:mod:`rockscreen.pipeline.report.basemap`, Natural Earth); labels take
the first of eight positions around their marker that overlaps no label placed before them
(:func:`label_points`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

from matplotlib import patheffects

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = [
    "HALO",
    "MIN_HALF_WIDTH_KM",
    "boxes_overlap",
    "degrees_text",
    "draw_basemap",
    "draw_north_arrow",
    "draw_scale_bar",
    "in_axes",
    "label_points",
    "map_extent",
    "set_map_frame",
]


# A white halo keeps labels readable where they cross markers or grid lines.
HALO = [patheffects.withStroke(linewidth=2.5, foreground="white")]


# Label positions tried around a marker [points], nearest first: NE, NW, SE, SW, E, W, N, S.
_OFFSETS = ((7, 7), (-7, 7), (7, -9), (-7, -9), (10, 0), (-10, 0), (0, 11), (0, -13))


def label_points(
    ax: Axes,
    labels: Sequence[tuple[str, float, float]],
    markers: Sequence[tuple[float, float]] = (),
    obstacles: Sequence[tuple[float, float, float, float]] = (),
    fontsize: float = 7,
) -> list[tuple[float, float, float, float]]:
    """Label points, each where its label overlaps no marker, obstacle or earlier label.

    Greedy, in the order given (the most important first): each label takes the first
    of eight positions around its point (NE, NW, SE, SW, E, W, N, S) whose box
    (estimated from the font size) stays in the axes and overlaps nothing placed; then
    the same twice and three times as far out with a leader line; a label that finds no
    free place is left out and named in the upper left corner ("Not labelled (no
    room): ..."), so no two labels ever overlap.

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
    omitted = []
    for text, lon, lat in labels:
        x, y = ax.transData.transform((lon, lat))
        width, height = 0.65 * fontsize * len(text) * dpi_scale, fontsize * 1.2 * dpi_scale
        placement = None
        for factor in (1, 2, 3):
            for dx, dy in _OFFSETS:
                ox, oy = dx * factor * dpi_scale, dy * factor * dpi_scale
                left = x + ox - (width if dx < 0 else width / 2 if dx == 0 else 0)
                bottom = y + oy - (height if dy < 0 else 0)
                box = (left, bottom, left + width, bottom + height)
                if in_axes(ax, box) and not any(boxes_overlap(box, other) for other in boxes):
                    placement = (dx * factor, dy * factor, box)
                    break
            if placement is not None:
                break
        if placement is None:
            omitted.append(text)
            continue
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
            path_effects=HALO,
            arrowprops={"arrowstyle": "-", "linewidth": 0.5, "color": "0.3"} if far else None,
            zorder=6,
        )
    if omitted:
        shown = ", ".join(omitted[:4]) + (
            f" and {len(omitted) - 4} more" if len(omitted) > 4 else ""
        )
        ax.text(
            0.005,
            0.995,
            f"Not labelled (no room): {shown}",
            transform=ax.transAxes,
            ha="left",
            va="top",
            fontsize=6,
            path_effects=HALO,
            zorder=6,
        )
    return boxes


def in_axes(ax: Axes, box: tuple[float, float, float, float]) -> bool:
    """Tell whether a box [pixels] lies within the axes."""
    x0, y0, x1, y1 = ax.bbox.extents
    return x0 <= box[0] and box[2] <= x1 and y0 <= box[1] and box[3] <= y1


def boxes_overlap(a: tuple[float, ...], b: tuple[float, ...]) -> bool:
    """Whether two boxes ``(left, bottom, right, top)`` [pixels] overlap."""
    return a[0] < b[2] and b[0] < a[2] and a[1] < b[3] and b[1] < a[3]


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


def set_map_frame(ax: Axes, extent: tuple[float, float, float, float]) -> float:
    """Set a map's limits, its aspect and its graticule in degrees.

    Equirectangular: the aspect is 1/cos(mean latitude), so that a kilometre is as long
    east-west as north-south at the centre. Coastlines and borders are drawn by
    :func:`draw_basemap`.

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
    draw_basemap(ax, extent)
    return mean_latitude


def draw_basemap(ax: Axes, extent: tuple[float, float, float, float]) -> bool:
    """Draw the coastlines and national borders that cross a map (Natural Earth, offline).

    Grey lines under every marker, clipped to the axes, with the source in the lower right
    corner; outside the shipped box (:func:`rockscreen.pipeline.report.basemap.basemap_box`)
    the corner says that no base map is drawn.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    extent : (lon_min, lon_max, lat_min, lat_max)
        [deg].

    Returns
    -------
    bool
        Whether any line was drawn.
    """
    from rockscreen.pipeline.report.basemap import BASEMAP_SOURCE, basemap_lines, covers

    lines = basemap_lines(extent) if covers(extent) else []
    for line in lines:
        ax.plot(
            line[:, 0],
            line[:, 1],
            color="#8c8c8c",
            linewidth=0.7,
            zorder=0.5,
            solid_joinstyle="round",
            label="_basemap",
        )
    ax.text(
        0.995,
        0.005,
        BASEMAP_SOURCE if lines else "No coastline in this extent (base map: Italy)",
        transform=ax.transAxes,
        ha="right",
        va="bottom",
        fontsize=6,
        color="#555555",
        path_effects=HALO,
        zorder=6,
    )
    return bool(lines)


def draw_scale_bar(ax: Axes, latitude: float) -> None:
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
        path_effects=HALO,
        zorder=6,
    )


def draw_north_arrow(ax: Axes) -> None:
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
