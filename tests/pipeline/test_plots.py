"""The tower history figure."""

from __future__ import annotations

import numpy as np
import pytest

from rockscreen.pipeline.report.plots import (
    readable_ratio,
    save_tower_histories,
    tower_history_figure,
)


def histories():
    t = np.linspace(0, 10, 200)
    return [
        {
            "record_id": "XX.A..HN",
            "component": c,
            "model": m,
            "alpha_rad": 0.2,
            "t": t,
            "theta": 0.1 * np.sin(t + k),
        }
        for k, (c, m) in enumerate([("N", "ground"), ("E", "ground"), ("N", "double")])
    ]


def test_one_panel_per_model_with_overturning_lines():
    fig = tower_history_figure("T1", histories())
    axes = [ax for ax in fig.axes if ax.get_ylabel() == "θ/α [-]"]
    assert len(axes) == 2
    assert len(axes[0].get_lines()) == 2 + 3  # two curves, +-1 and 0
    ydata = axes[0].get_lines()[0].get_ydata()
    assert np.max(np.abs(ydata)) == pytest.approx(0.5, rel=1e-2)  # theta/alpha = 0.1/0.2


def test_png_written(tmp_path):
    path = save_tower_histories("T1", histories(), tmp_path / "t.png")
    assert path.read_bytes()[:4] == b"\x89PNG"


def test_no_histories_is_an_error():
    with pytest.raises(ValueError, match="no time histories"):
        tower_history_figure("T1", [])


def test_axes_zoom_on_the_motion_of_a_long_record():
    # 600 s of record, rocking between 30 and 40 s at 5 % of alpha.
    t = np.linspace(0.0, 600.0, 60001)
    theta = np.where((t > 30.0) & (t < 40.0), 0.01 * np.sin(3.0 * t), 0.0)
    h = {"record_id": "XX.A..HN", "component": "E", "model": "ground", "alpha_rad": 0.2}
    fig = tower_history_figure("T1", [{**h, "t": t, "theta": theta}])
    ax = next(ax for ax in fig.axes if ax.get_ylabel() == "θ/α [-]")
    lo, hi = ax.get_xlim()
    assert 25.0 < lo < 30.0 and 40.0 < hi < 45.0
    assert ax.get_ylim()[1] == pytest.approx(1.15 * 0.05, rel=1e-3)
    assert "off scale" in ax.get_title(loc="left")


def test_large_rotations_keep_the_overturning_lines_in_view():
    fig = tower_history_figure("T1", [{**histories()[0], "theta": 0.19 * np.ones(200)}])
    ax = next(ax for ax in fig.axes if ax.get_ylabel() == "θ/α [-]")
    assert ax.get_ylim()[1] == pytest.approx(1.15)


def test_each_panel_titles_its_own_peak():
    # ground peaks at 0.242, the floor model at 0.384: the ground panel says 0.242.
    t = np.linspace(0.0, 10.0, 400)
    h = {"record_id": "XX.A..HN", "component": "E", "alpha_rad": 0.2, "t": t}
    fig = tower_history_figure(
        "T1",
        [
            {**h, "model": "ground", "theta": 0.242 * 0.2 * np.sin(t)},
            {**h, "model": "floor", "theta": 0.384 * 0.2 * np.sin(t)},
        ],
    )
    titles = [ax.get_title(loc="left") for ax in fig.axes if ax.get_ylabel() == "θ/α [-]"]
    assert "peak θ/α = 0.242" in titles[0] and "0.384" not in titles[0]
    assert "peak θ/α = 0.384" in titles[1]


def test_time_axis_ignores_a_negligible_tail():
    # 563 s of record, rocking from 20 to 50 s, then a tail at 1e-9 of the peak.
    t = np.linspace(0.0, 563.0, 56301)
    theta = np.where((t > 20.0) & (t < 50.0), 0.05 * np.sin(2.0 * t), 1e-11)
    h = {"record_id": "XX.A..HN", "component": "E", "model": "ground", "alpha_rad": 0.2}
    fig = tower_history_figure("T1", [{**h, "t": t, "theta": theta}])
    lo, hi = fig.axes[0].get_xlim()
    assert 15.0 < lo < 20.0 and 50.0 < hi < 56.0


def test_small_ratios_are_readable():
    t = np.linspace(0.0, 10.0, 100)
    h = {"record_id": "XX.A..HN", "component": "E", "model": "ground", "alpha_rad": 0.2}
    fig = tower_history_figure("T1", [{**h, "t": t, "theta": 5.34e-5 * 0.2 * np.sin(t)}])
    title = fig.axes[0].get_title(loc="left")
    assert "5.34 × 10⁻⁵" in title and "e-05" not in title
    assert readable_ratio(5.34e-5) == "5.34 × 10⁻⁵"
    assert readable_ratio(0.0) == "0" and readable_ratio(0.384) == "0.384"
