"""PNG maps: labels never overlap, the riskiest are labelled, the base map is drawn (issue 23)."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from rockscreen.pipeline.report.basemap import basemap_box, basemap_lines, covers
from rockscreen.pipeline.report.maps import risk_map_figure
from rockscreen.pipeline.report.risk_plots import safety_map_figure
from rockscreen.stations.pairing import StationSite

CLASSES = ("high", "moderate", "low", "none")


def _towers(lat0=42.30, lon0=13.30, spacing_km=5.0, n_side=4):
    """Towers on a grid ``spacing_km`` apart (16 by default, as around L'Aquila)."""
    dlat = spacing_km / 111.2
    dlon = spacing_km / (111.2 * np.cos(np.radians(lat0)))
    return [
        {
            "id": f"AQ-T{i * n_side + j:02d}",
            "lat_deg": lat0 + i * dlat,
            "lon_deg": lon0 + j * dlon,
            "risk_class": CLASSES[(i + j) % 4],
            "theta_max_over_alpha": 0.1 * (i + j),
            "safety_index": 0.5 + 0.2 * (i + j),
            "slv_bound": "",
        }
        for i in range(n_side)
        for j in range(n_side)
    ]


def _label_boxes(fig):
    """Rendered boxes [pixels] of every tower and station label of the map."""
    renderer = fig.canvas.get_renderer()
    ax = fig.axes[0]
    labels = [t for t in ax.texts if t.get_text().startswith(("AQ-", "IT."))]
    return [t.get_text() for t in labels], [t.get_window_extent(renderer) for t in labels]


def _overlaps(boxes):
    return [
        (i, j)
        for (i, a), (j, b) in itertools.combinations(enumerate(boxes), 2)
        if a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1
    ]


@pytest.mark.parametrize("spacing_km", [5.0, 1.0, 0.3])
def test_run_map_labels_never_overlap(spacing_km):
    towers = _towers(spacing_km=spacing_km)
    sites = [
        StationSite("IT.AQU", towers[5]["lat_deg"] + 0.01, towers[5]["lon_deg"] + 0.01),
        StationSite("IT.FAR", 40.5, 15.5),  # about 200 km away: outside the extent
        StationSite("IT.FAR2", 44.0, 12.0),
    ]
    fig = risk_map_figure(towers, sites)
    fig.draw_without_rendering()
    names, boxes = _label_boxes(fig)
    assert names, "no label drawn"
    assert _overlaps(boxes) == [], [(names[i], names[j]) for i, j in _overlaps(boxes)]
    ax = fig.axes[0]
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    assert all(x0 < t["lon_deg"] < x1 and y0 < t["lat_deg"] < y1 for t in towers)
    assert x1 - x0 < 1.0  # the far stations do not set the extent
    if spacing_km == 5.0:
        assert all(t["id"] in names for t in towers if t["risk_class"] == "high")


def test_assess_map_labels_never_overlap():
    fig = safety_map_figure(_towers(spacing_km=0.5))
    fig.draw_without_rendering()
    names, boxes = _label_boxes(fig)
    assert names and _overlaps(boxes) == []
    ax = fig.axes[0]
    corner = [t.get_text() for t in ax.texts if t.get_text().startswith("Not labelled")]
    assert len(names) + sum(t.count("AQ-") for t in corner) <= 16


def test_the_coastline_is_drawn_on_a_coastal_map():
    towers = _towers(lat0=40.80, lon0=14.15, spacing_km=4.0)  # Naples and its gulf
    fig = safety_map_figure(towers)
    ax = fig.axes[0]
    base = [line for line in ax.lines if line.get_label() == "_basemap"]
    assert base, "no coastline drawn near Naples"
    assert any("Natural Earth" in t.get_text() for t in ax.texts)


def test_outside_the_base_map_the_map_says_so():
    towers = _towers(lat0=-33.9, lon0=18.4)  # Cape Town: not in the shipped box
    fig = safety_map_figure(towers)
    ax = fig.axes[0]
    assert not [line for line in ax.lines if line.get_label() == "_basemap"]
    assert any(t.get_text().startswith("No coastline") for t in ax.texts)


def test_base_map_geometry_is_italy():
    lon0, lon1, lat0, lat1 = basemap_box()
    assert lon0 <= 6.6 and lon1 >= 18.6 and lat0 <= 35.5 and lat1 >= 47.1  # all of Italy
    assert covers((13.0, 13.5, 42.0, 42.5)) and not covers((30.0, 31.0, 42.0, 42.5))
    # Known coastal points lie within 2 km of a shipped line (Natural Earth 1:10m, simplified)
    for lon, lat in ((16.87, 41.125), (12.28, 41.73), (15.55, 38.19), (9.11, 39.21)):
        lines = basemap_lines((lon - 0.1, lon + 0.1, lat - 0.1, lat + 0.1))
        points = np.vstack(lines)
        km = np.hypot(
            (points[:, 0] - lon) * 111.2 * np.cos(np.radians(lat)), (points[:, 1] - lat) * 111.2
        )
        assert km.min() < 2.0, (lon, lat, km.min())
