"""The offline base map: coastlines and national borders around Italy.

The lines are Natural Earth's 1:10m Admin 0 countries, version 4.1.0 (public domain), as
redistributed by the npm package ``world-atlas`` 2.0.2 (ISC licence), cut to the box of
Italy and its neighbours, simplified to about 200 m and stored in
``pipeline/report/data/basemap_italy.json`` by ``tools/build_basemap.py`` (docs/report.md).
Outside that box (:func:`basemap_box`) nothing is drawn, and the maps say so. Regions and
provinces are not shipped (see docs/report.md).

Used by the PNG maps (:func:`rockscreen.pipeline.report.map_frame.draw_basemap`) and by the
HTML map (the lines crossing its extent go into the page).
"""

from __future__ import annotations

import json
from functools import lru_cache
from importlib import resources

import numpy as np

__all__ = ["BASEMAP_SOURCE", "basemap_box", "basemap_lines", "clipped_lines", "covers"]

#: The attribution printed on every map that draws the base map.
BASEMAP_SOURCE = "Coastlines and borders: Natural Earth (public domain)"


@lru_cache(maxsize=1)
def _load() -> tuple[tuple[float, ...], tuple[np.ndarray, ...]]:
    text = resources.files("rockscreen.pipeline.report").joinpath("data/basemap_italy.json")
    payload = json.loads(text.read_text(encoding="utf-8"))
    quantum = float(payload["quantum_deg"])
    lines = []
    for flat in payload["lines"]:
        delta = np.asarray(flat, dtype=np.int64).reshape(-1, 2)
        line = np.cumsum(delta, axis=0) * quantum
        line.setflags(write=False)
        lines.append(line)
    return tuple(float(v) for v in payload["box_deg"]), tuple(lines)


def basemap_box() -> tuple[float, float, float, float]:
    """Return the box the shipped base map covers: (lon_min, lon_max, lat_min, lat_max) [deg]."""
    lon0, lon1, lat0, lat1 = _load()[0]
    return lon0, lon1, lat0, lat1


def covers(extent: tuple[float, float, float, float]) -> bool:
    """Whether a map extent (lon_min, lon_max, lat_min, lat_max) [deg] overlaps the base map."""
    lon0, lon1, lat0, lat1 = basemap_box()
    x0, x1, y0, y1 = extent
    return x0 < lon1 and lon0 < x1 and y0 < lat1 and lat0 < y1


def basemap_lines(extent: tuple[float, float, float, float]) -> list[np.ndarray]:
    """Return the coastline and border lines that cross a map extent.

    Parameters
    ----------
    extent : (lon_min, lon_max, lat_min, lat_max)
        [deg].

    Returns
    -------
    list of numpy.ndarray
        Polylines of shape (n, 2): longitude, latitude [deg]; whole lines (the caller
        clips), read-only. Empty when the extent lies outside :func:`basemap_box`.
    """
    x0, x1, y0, y1 = extent
    out = []
    for line in _load()[1]:
        lon, lat = line[:, 0], line[:, 1]
        if lon.max() < x0 or lon.min() > x1 or lat.max() < y0 or lat.min() > y1:
            continue
        out.append(line)
    return out


def clipped_lines(
    extent: tuple[float, float, float, float], decimals: int = 3
) -> list[list[list[float]]]:
    """Return the base map's lines cut to an extent, as rounded lists (for the HTML map).

    A line leaving the extent is cut there: each run of consecutive points inside, plus
    the first point outside at each end (so that the line reaches the edge), is one piece.

    Parameters
    ----------
    extent : (lon_min, lon_max, lat_min, lat_max)
        [deg].
    decimals : int, optional
        Decimals kept [deg] (3: about 100 m, the data's own quantum).

    Returns
    -------
    list of list of [lon, lat]
        [deg].
    """
    if not covers(extent):
        return []
    x0, x1, y0, y1 = extent
    pieces = []
    for line in basemap_lines(extent):
        inside = (line[:, 0] >= x0) & (line[:, 0] <= x1) & (line[:, 1] >= y0) & (line[:, 1] <= y1)
        keep = inside.copy()
        keep[1:] |= inside[:-1]
        keep[:-1] |= inside[1:]
        edges = np.flatnonzero(np.diff(np.r_[0, keep.astype(np.int8), 0]))
        for start, stop in zip(edges[::2], edges[1::2], strict=True):
            if stop - start >= 2:
                piece = np.round(line[start:stop], decimals)
                pieces.append(piece.tolist())
    return pieces
