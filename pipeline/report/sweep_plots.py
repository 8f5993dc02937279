"""Figures from a sweep archive, in the layout of the seed paper's Figures 10-12.

For every group of a study and every amplitude, one figure of rotation time histories
theta(t) [rad]: one panel per (mu_s, mu_k) pair (and eta, when the group varies it), one
colour per frequency, the overturning angle +-alpha dashed. Groups that vary the
frequency also get a summary figure theta_max/alpha against frequency.

Figures are built on :class:`matplotlib.figure.Figure` with the Agg canvas, never
through pyplot, so drawing needs no display and leaves no global state behind.
"""

from __future__ import annotations

import math
import os
import re
from collections import OrderedDict
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from rockscreen.pipeline.archive.kinds import SweepReader
from rockscreen.pipeline.engine.registry import solver_model
from rockscreen.pipeline.report.values import Row
from rockscreen.pipeline.study.sweep import (
    is_sweep_archive,
    read_archive_attrs,
    read_cases,
    read_histories,
)

__all__ = ["is_sweep_archive", "plot_sweep", "plot_sweep_reader", "sweep_figures"]

#: Below this fraction of alpha, the +-alpha lines would flatten the curves: they are
#: then left off scale and quoted in the panel instead.
_ALPHA_SCALE_FRACTION = 0.05


def _slug(text: str) -> str:
    return re.sub(r"[^A-Za-z0-9]+", "_", text.replace(".", "p")).strip("_").lower()


def _panel_label(
    row: Row, with_eta: bool, with_duration: bool = False, with_form: bool = False
) -> str:
    if solver_model(row["model"]).takes("mu_s"):
        label = f"$\\mu_s$ = {row['mu_s']:g}, $\\mu_k$ = {row['mu_k']:g}"
    else:
        label = "single block"
    if with_eta:
        label += f", $\\eta$ = {row['eta']:g}"
    if with_duration:
        label += f", {row['duration_s']:g} s"
    if with_form:
        label = f"{row.get('formulation', 'consistent')}\n{label}"
    return label


def _new_figure(n_panels: int, ncols: int = 3) -> tuple[Figure, list]:
    ncols = min(ncols, n_panels)
    nrows = math.ceil(n_panels / ncols)
    fig = Figure(figsize=(max(4.2 * ncols, 6.5), 2.9 * nrows + 0.6), layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(nrows, ncols, sharex=True, sharey=True, squeeze=False).ravel()
    for ax in axes[n_panels:]:
        ax.set_visible(False)
    return fig, list(axes[:n_panels])


def _history_figure(
    histories: Mapping[int, Mapping[str, np.ndarray]],
    rows: Sequence[Row],
    alpha: float,
    title: str,
    colours: Mapping[float, str],
) -> Figure:
    with_eta = len({r["eta"] for r in rows}) > 1
    with_duration = len({r["duration_s"] for r in rows}) > 1
    forms = list(OrderedDict.fromkeys(r.get("formulation", "consistent") for r in rows))
    panels: OrderedDict[tuple, list] = OrderedDict()
    # one column per formulation (side by side), one row per friction pair
    for row in sorted(rows, key=lambda r: forms.index(r.get("formulation", "consistent"))):
        key = (row["mu_s"], row["mu_k"], row["eta"], row["duration_s"], row.get("formulation"))
        panels.setdefault(key, []).append(row)
    if len(forms) > 1:
        order = {key: (i % (len(panels) // len(forms) or 1), i) for i, key in enumerate(panels)}
        panels = OrderedDict(sorted(panels.items(), key=lambda item: order[item[0]]))
    fig, axes = _new_figure(len(panels), len(forms) if len(forms) > 1 else 3)
    peak = 0.0
    for ax, runs in zip(axes, panels.values(), strict=True):
        for row in runs:
            hist = histories.get(int(row["index"]), {})
            if "t" not in hist or "theta" not in hist:
                continue
            peak = max(peak, float(np.max(np.abs(hist["theta"]), initial=0.0)))
            ax.plot(
                hist["t"],
                hist["theta"],
                lw=0.8,
                color=colours[row["frequency_hz"]],
                label=f"{row['frequency_hz']:g} Hz",
            )
        ax.set_title(_panel_label(runs[0], with_eta, with_duration, len(forms) > 1), fontsize=8)
        ax.grid(True, lw=0.3)
    show_alpha = peak >= _ALPHA_SCALE_FRACTION * alpha
    for ax in axes:
        ax.axhline(0.0, color="0.5", lw=0.4)
        if show_alpha:
            for sign in (1.0, -1.0):
                ax.axhline(sign * alpha, color="k", ls="--", lw=0.8)
        else:
            ax.text(
                0.98,
                0.04,
                f"$\\pm\\alpha$ = $\\pm${alpha:.3f} rad off scale",
                transform=ax.transAxes,
                ha="right",
                fontsize=7,
                color="0.3",
            )
    if show_alpha:
        axes[0].set_ylim(-1.15 * max(alpha, peak), 1.15 * max(alpha, peak))
    elif peak > 0.0:
        axes[0].set_ylim(-1.15 * peak, 1.15 * peak)
    for ax in axes:
        if ax.get_subplotspec().is_last_row():
            ax.set_xlabel("t [s]")
        if ax.get_subplotspec().is_first_col():
            ax.set_ylabel(r"$\theta$ [rad]")
    axes[0].legend(fontsize=7, title="frequency", title_fontsize=7, loc="upper right")
    fig.suptitle(title, fontsize=10)
    return fig


def _summary_figure(rows: Sequence[Row], title: str) -> Figure:
    fig, (ax,) = _new_figure(1)
    series: OrderedDict[tuple, list] = OrderedDict()
    for row in rows:
        key = (row["amplitude"], row["mu_s"], row["mu_k"], row["eta"], row["duration_s"])
        series.setdefault((*key, row.get("formulation")), []).append(row)
    markers = "osd^v<>p*h"
    amps = list(OrderedDict.fromkeys(r["amplitude"] for r in rows))
    with_eta = len({r["eta"] for r in rows}) > 1
    with_duration = len({r["duration_s"] for r in rows}) > 1
    with_form = len({r.get("formulation") for r in rows}) > 1
    for i, ((amp, *_), runs) in enumerate(series.items()):
        f = [r["frequency_hz"] for r in runs]
        y = [r["theta_max_over_alpha"] for r in runs]
        ax.plot(
            f,
            y,
            marker=markers[amps.index(amp) % len(markers)],
            ls="-" if amps.index(amp) == 0 else "--",
            color=f"C{i % 10}",
            ms=4,
            lw=0.9,
            label=f"{amp}, "
            + _panel_label(runs[0], with_eta, with_duration, with_form).replace("\n", ", "),
        )
    ax.set_xlabel("f [Hz]")
    ax.set_ylabel(r"$\theta_{max}/\alpha$ [-]")
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=6)
    fig.set_size_inches(7.0, 4.5)
    fig.suptitle(title, fontsize=10)
    return fig


def sweep_figures(archive: str | os.PathLike) -> list[tuple[str, Figure]]:
    """Build the figures of a sweep archive.

    Parameters
    ----------
    archive : str or path-like
        A sweep archive (see :func:`rockscreen.pipeline.study.sweep.is_sweep_archive`).

    Returns
    -------
    list of (str, Figure)
        A file stem for each figure and the figure.
    """
    archive = Path(archive)
    attrs = read_archive_attrs(archive)
    alpha = float(attrs["tower"]["alpha_rad"])
    tower = attrs["tower"].get("name", "tower")
    rows = read_cases(archive)
    histories = read_histories(archive)  # one open and check for all the figures
    stem = archive.stem
    groups: OrderedDict[int, list] = OrderedDict()
    for row in rows:
        groups.setdefault(row["group_index"], []).append(row)
    out = []
    for g_index, g_rows in groups.items():
        name = g_rows[0]["group"]
        freqs = list(OrderedDict.fromkeys(r["frequency_hz"] for r in g_rows))
        colours = {f: f"C{i % 10}" for i, f in enumerate(freqs)}
        by_amp: OrderedDict[str, list] = OrderedDict()
        for row in g_rows:
            by_amp.setdefault(row["amplitude"], []).append(row)
        for amp, a_rows in by_amp.items():
            title = f"{tower} - {name}: A = {amp}"
            fig = _history_figure(histories, a_rows, alpha, title, colours)
            out.append((f"{stem}_g{g_index + 1}_{_slug(amp)}", fig))
        if len(freqs) > 1:
            title = f"{tower} - {name}: peak rotation"
            out.append((f"{stem}_g{g_index + 1}_theta_max", _summary_figure(g_rows, title)))
    return out


def plot_sweep(
    archive: str | os.PathLike, out_dir: str | os.PathLike, *, dpi: int = 100
) -> list[Path]:
    """Draw every figure of a sweep archive into ``out_dir`` as PNG.

    Parameters
    ----------
    archive : str or path-like
        A sweep archive written by ``rockscreen sweep``.
    out_dir : str or path-like
        Folder for the PNG files (created if missing).
    dpi : int
        Resolution [dots per inch].

    Returns
    -------
    list of Path
        The files written.
    """
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    written = []
    for stem, fig in sweep_figures(archive):
        path = out_dir / f"{stem}.png"
        fig.savefig(path, dpi=dpi)
        written.append(path)
    return written


def plot_sweep_reader(
    reader: SweepReader, tower_id: str | None, as_map: bool, out: str | None
) -> list[Path]:
    """Draw every figure of a sweep archive (``rockscreen plot``) into the folder ``out``.

    ``tower_id`` and ``as_map`` are not used (a sweep has one tower and no map); ``out``
    defaults to the current folder. Returns the files written (:func:`plot_sweep`).
    """
    return plot_sweep(reader.path, out or ".")
