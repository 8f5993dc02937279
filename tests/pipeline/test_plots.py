"""The tower history figure."""

from __future__ import annotations

import numpy as np
import pytest

from pipeline.plots import save_tower_histories, tower_history_figure


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
