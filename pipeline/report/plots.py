"""Figures of a campaign archive: rotation time histories of one tower.

In the style of the seed paper's Figures 10-12 (Di Gennaro et al. 2023): one panel per
model, the normalised rotation theta/alpha against time, one colour per record
component, dashed lines at +-1 (theta = alpha, the static overturning limit). The
rotation in radians is on a secondary axis when the panel's curves share one alpha.
Matplotlib's object API only (``Figure``, Agg canvas): no pyplot state.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

#: Panel titles of the models.
MODEL_TITLES = {
    "ground": "single block on the ground",
    "floor": "single block on the floor motion",
    "double": "double block (tower on a sliding building)",
}


#: Below this peak theta/alpha a panel is scaled to its own curves (the +-1 lines drop out
#: of view): a tower rocking at 5 % of alpha would otherwise be a flat line.
OFF_SCALE_BELOW = 0.5


def _rotation_limits(peak: float) -> tuple[float, float]:
    """Return symmetric y limits [-] for a panel whose largest |theta/alpha| is ``peak``."""
    if peak < OFF_SCALE_BELOW:
        half = 1.15 * peak if peak > 0.0 else 0.05
    else:
        half = 1.15 * max(peak, 1.0)
    return -half, half


def _motion_window(histories: Sequence[dict[str, Any]]) -> tuple[float, float] | None:
    """Return the time span [s] where any history moves, padded by 10 %; None if none moves.

    Real records are long (minutes of coda) while the rocking lasts seconds: plotting the
    whole record would squeeze the motion into a spike.
    """
    starts, ends = [], []
    for h in histories:
        t = np.asarray(h["t"], dtype=float)
        moving = np.flatnonzero(np.asarray(h["theta"], dtype=float) != 0.0)
        if moving.size:
            starts.append(t[moving[0]])
            ends.append(t[moving[-1]])
    if not starts:
        return None
    start, end = min(starts), max(ends)
    pad = 0.1 * max(end - start, 1.0)
    return max(start - pad, 0.0), end + pad


def tower_history_figure(tower_id: str, histories: Sequence[dict[str, Any]]) -> Figure:
    """Return the rotation-history figure of one tower.

    Parameters
    ----------
    tower_id : str
        Shown in the title.
    histories : sequence of dict
        From :func:`pipeline.archive.campaign.read_histories`: ``record_id``, ``component``,
        ``model``, ``alpha_rad`` [rad], ``t`` [s], ``theta`` [rad].

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ValueError
        If ``histories`` is empty.
    """
    if not histories:
        raise ValueError(f"tower {tower_id!r}: the archive keeps no time histories")
    models = [m for m in MODEL_TITLES if any(h["model"] == m for h in histories)]
    fig = Figure(figsize=(9.0, 2.8 * len(models) + 0.6), layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(len(models), 1, sharex=True, squeeze=False)[:, 0]
    labels = sorted({f"{h['record_id']}{h['component']}" for h in histories})
    colours = {label: f"C{i % 10}" for i, label in enumerate(labels)}
    for ax, model in zip(axes, models, strict=True):
        panel = [h for h in histories if h["model"] == model]
        peak = 0.0
        for h in panel:
            label = f"{h['record_id']}{h['component']}"
            ratio = np.asarray(h["theta"], dtype=float) / h["alpha_rad"]
            peak = max(peak, float(np.max(np.abs(ratio), initial=0.0)))
            ax.plot(h["t"], ratio, color=colours[label], lw=0.9, label=label)
        for level in (-1.0, 1.0):
            ax.axhline(level, color="k", ls="--", lw=0.8)
        ax.axhline(0.0, color="0.6", lw=0.5)
        ax.set_ylim(*_rotation_limits(peak))
        title = MODEL_TITLES[model]
        if peak < OFF_SCALE_BELOW:
            title += f" (peak θ/α = {peak:.3g}; the ±1 lines are off scale)"
        ax.set_ylabel("θ/α [-]")
        ax.set_title(title, fontsize=10, loc="left")
        ax.legend(fontsize=7, loc="upper right", ncols=2)
        alphas = {round(h["alpha_rad"], 12) for h in panel}
        if len(alphas) == 1:
            alpha = panel[0]["alpha_rad"]
            secondary = ax.secondary_yaxis(
                "right", functions=(lambda r, a=alpha: r * a, lambda th, a=alpha: th / a)
            )
            secondary.set_ylabel("θ [rad]")
    window = _motion_window(histories)
    if window is not None:
        axes[-1].set_xlim(*window)
    axes[-1].set_xlabel("t [s]")
    fig.suptitle(f"tower {tower_id}: rotation histories (±1: θ = α)")
    return fig


def save_tower_histories(
    tower_id: str, histories: Sequence[dict[str, Any]], out_png: str | Path
) -> Path:
    """Save :func:`tower_history_figure` as a PNG and return its path."""
    out_png = Path(out_png)
    tower_history_figure(tower_id, histories).savefig(out_png, dpi=130)
    return out_png
