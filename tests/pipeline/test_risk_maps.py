"""The assess and scenario PNG maps and the fragility figure's log ticks (issue 23)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
from matplotlib.figure import Figure

from rockscreen.pipeline.report.risk_plots import (
    SCENARIO_TOWER_CMAP,
    log_ticks,
    safety_map_figure,
    scenario_map_figure,
)


def _rows():
    return [
        {"id": "A", "lat_deg": 41.00, "lon_deg": 14.40, "safety_index": 0.5, "slv_bound": ""},
        {"id": "B", "lat_deg": 41.02, "lon_deg": 14.43, "safety_index": 3.0, "slv_bound": "lower"},
        {"id": "C", "lat_deg": 41.04, "lon_deg": 14.45, "safety_index": math.nan, "slv_bound": ""},
    ]


def test_safety_map_marks_bounds_and_has_a_scale_bar():
    fig = safety_map_figure(_rows())
    ax = fig.axes[0]
    legend = [t.get_text() for t in ax.get_legend().get_texts()]
    assert "I_S lower bound (hollow: at least this)" in legend and "I_S undefined" in legend
    hollow = next(c for c in ax.collections if c.get_label().startswith("I_S lower bound"))
    assert len(hollow.get_offsets()) == 1 and len(hollow.get_facecolor()) == 0
    assert any(t.get_text().endswith(" km") for t in ax.texts)  # the scale bar
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    assert 14.3 < x0 < 14.4 and 14.45 < x1 < 14.55 and 40.9 < y0 < 41.0 and 41.04 < y1 < 41.15
    fig.draw_without_rendering()
    assert all(t.get_text().endswith("° E") for t in ax.get_xticklabels() if t.get_text())


def test_scenario_map_extent_from_the_towers_not_a_far_grid():
    grid = SimpleNamespace(
        lon_min=-70.0, lat_min=-30.0, dlon=1.0, dlat=1.0, nlon=86, nlat=40,
        pga_g=np.full((40, 86), 0.1), event={"event_id": "far"},
    )  # fmt: skip
    rows = [
        {"id": "A", "lat_deg": 41.0, "lon_deg": 14.4, "p_overturning": 0.9},
        {"id": "B", "lat_deg": 41.1, "lon_deg": 14.5, "p_overturning": math.nan},
    ]
    fig = scenario_map_figure(rows, grid)
    ax = fig.axes[0]
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    assert 14.2 < x0 < 14.4 and 14.5 < x1 < 14.7 and 40.8 < y0 < 41.0 and 41.1 < y1 < 41.3
    towers = next(c for c in ax.collections if c.get_cmap().name == SCENARIO_TOWER_CMAP)
    assert towers.get_cmap().name != "inferno_r"  # not black on the grey ShakeMap


def test_log_ticks_are_plain_and_not_crowded():
    fig = Figure()
    ax = fig.add_subplot()
    ax.set_xscale("log")
    ax.set_xlim(0.05, 0.4)
    log_ticks(ax.xaxis)
    fig.draw_without_rendering()
    lo, hi = ax.get_xlim()
    major = [t.get_text() for t in ax.get_xticklabels() if lo <= t.get_position()[0] <= hi]
    assert major == ["0.05", "0.1", "0.2"]
    assert all(not t.get_text() for t in ax.get_xticklabels(minor=True))
