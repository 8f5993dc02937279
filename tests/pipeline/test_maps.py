"""The PNG risk map: extent fitted to the towers, stations labelled where there is room."""

from __future__ import annotations

from rockscreen.pipeline.report.map_frame import degrees_text, map_extent
from rockscreen.pipeline.report.maps import risk_map_figure
from rockscreen.stations.pairing import StationSite


def _towers():
    return [
        {"id": f"T{i}", "lat_deg": 41.0 + 0.01 * i, "lon_deg": 14.4 + 0.01 * i, "risk_class": c}
        for i, c in enumerate(["high", "low", "none", "none"])
    ]


def test_extent_fits_the_towers_not_a_far_station():
    far = StationSite("XX.FAR", 43.5, 12.0)  # some 300 km away
    near = StationSite("XX.NEAR", 41.01, 14.41)
    fig = risk_map_figure(_towers(), [far, near])
    ax = fig.axes[0]
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    assert 14.3 < x0 < 14.4 and 14.43 < x1 < 14.5
    assert 40.9 < y0 < 41.0 and 41.03 < y1 < 41.1
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any(t.startswith("station (2; 1 outside the map") for t in legend)
    assert "XX.FAR" not in [t.get_text() for t in ax.texts]


def test_graticule_in_degrees():
    fig = risk_map_figure(_towers(), [])
    ax = fig.axes[0]
    fig.draw_without_rendering()
    labels = [t.get_text() for t in ax.get_xticklabels() if t.get_text()]
    assert labels and all(label.endswith("° E") for label in labels)
    assert degrees_text(-3.25, "E", "W") == "3.25° W"


def test_extent_has_a_minimum_size():
    x0, x1, y0, y1 = map_extent([14.0], [41.0])
    assert x1 - x0 > 0.04 and y1 - y0 > 0.03
