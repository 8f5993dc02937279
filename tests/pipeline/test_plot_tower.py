"""plot --tower: verdict on the figure, shared y-scale, input motion, still towers (issue 12)."""

from __future__ import annotations

import numpy as np
from click.testing import CliRunner

from rockscreen.pipeline.cli import main
from rockscreen.pipeline.report.motions import read_component_motion
from rockscreen.pipeline.report.plots import tower_figure_details, tower_history_figure


def _history(model, peak, alpha=0.1):
    t = np.linspace(0.0, 10.0, 501)
    return {
        "record_id": "XX.A..HN",
        "component": "E",
        "model": model,
        "alpha_rad": alpha,
        "t": t,
        "theta": peak * alpha * np.sin(t),
    }


def _texts(fig):
    return (
        " ".join(t.get_text() for ax in fig.axes for t in [ax.title, *ax.texts])
        + " "
        + (fig._suptitle.get_text() if fig._suptitle else "")
    )


def test_panels_share_one_y_scale_and_the_verdict_is_printed():
    summary = {
        "risk_class": "high",
        "safety_factor": 0.8,
        "safety_factor_limit": "overturning",
        "governing_record": "XX.A..HNE",
        "governing_model": "ground",
    }
    t = np.linspace(0.0, 10.0, 1001)
    fig = tower_history_figure(
        "T1",
        [_history("ground", 0.9), _history("double", 0.05)],
        summary=summary,
        motion=(t, np.sin(t), "XX.A..HNE"),
        pga_m_s2=2.0,
    )
    rotation_axes = [ax for ax in fig.axes if ax.get_ylabel() == "θ/α [-]"]
    assert len(rotation_axes) == 2
    assert rotation_axes[0].get_ylim() == rotation_axes[1].get_ylim()
    text = _texts(fig)
    assert "class high" in text and "safety factor 0.80" in text and "XX.A..HNE" in text
    assert "PGA 2.00 m/s²" in text
    assert any(ax.get_ylabel() == "a [m/s²]" for ax in fig.axes)  # the input motion


def test_a_tower_that_never_moved_says_so():
    still = _history("ground", 0.0)
    fig = tower_history_figure("T2", [still, dict(still, model="floor")])
    assert "did not rock" in _texts(fig)
    assert not any(ax.get_ylabel() == "θ/α [-]" for ax in fig.axes)


def test_plot_tower_reads_the_governing_motion_from_the_archive(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert CliRunner().invoke(main, ["run", "--example", "--jobs", "1", "-q"]).exit_code == 0
    archive = tmp_path / "rockscreen-example.h5"
    details = tower_figure_details(archive, "ARC-08")
    assert details["summary"]["id"] == "ARC-08"
    t, acc, label = details["motion"]
    assert len(t) == len(acc) > 100 and label.startswith(details["summary"]["governing_record"])
    assert details["pga_m_s2"] == float(np.max(np.abs(acc)))
    # A rotated component (X/Y) is rotated again exactly as the screening did.
    assert read_component_motion(archive, "ARC-03", "XX.SYN2..HN", "X") is not None
    result = CliRunner().invoke(main, ["plot", str(archive), "--tower", "ARC-08", "--out", "a.png"])
    assert result.exit_code == 0, result.output
    assert (tmp_path / "a.png").stat().st_size > 10_000
