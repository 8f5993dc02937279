"""Figures of assess and scenario archives: fragility curve, I_S map, scenario map."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.colors import LogNorm

from rockscreen.pipeline.archive.atomic import atomic_path
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.risk.fragility import fragility_probability
from rockscreen.pipeline.risk.tower_ida import record_intensities

__all__ = ["plot_fragility", "plot_safety_map", "plot_scenario_map"]


def _figure():
    # Here, not at module level: the Agg backend is chosen before pyplot is imported, and
    # only when a figure is drawn (importing this module leaves the backend alone).
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    return plt


def _save(fig, out: str | Path) -> Path:
    out = Path(out)
    with atomic_path(out, suffix=".part") as work:
        fig.savefig(work, format="png", dpi=120)
    return out


def plot_fragility(
    tower_id: str,
    summary: Sequence[dict[str, Any]],
    stripes: Sequence[dict[str, Any]],
    out,
    ida: Sequence[dict[str, Any]] = (),
) -> Path:
    """Draw a tower's fragilities, its records' IDA intensities and the stripe fractions.

    The records' intensities (``/ida``, components combined) are drawn at their empirical
    plotting positions along each fitted curve's axis: filled markers for the observed
    intensities, open markers at the censoring intensity for the censored records. The
    fitted collapse and SLV curves (or their bound, dashed) and the stripe fractions
    (counts annotated) are drawn beside. An archive without ``/ida`` (or a row without the
    IDA columns) shows the stripe fit alone.

    Parameters
    ----------
    tower_id : str
    summary, stripes : sequence of dict
        The archive's ``/summary`` and ``/stripes`` rows.
    out : str or Path
        The PNG.
    ida : sequence of dict, optional
        The archive's ``/ida`` rows.
    """
    plt = _figure()

    rows = [r for r in summary if r["id"] == tower_id]
    if not rows:
        shown = ", ".join(r["id"] for r in summary[:10])
        raise ArchiveError(f"tower {tower_id!r} is not in the archive (towers: {shown}...)")
    row = rows[0]
    own = sorted((s for s in stripes if s["tower_id"] == tower_id), key=lambda s: s["ag_g"])
    fig, ax = plt.subplots(figsize=(7.0, 4.8))
    ag = np.array([s["ag_g"] for s in own])
    values = list(ag)
    if len(ag):
        k = np.array([s["n_overturned"] for s in own])
        n = np.array([s["n_records"] for s in own])
        ax.plot(ag, k / n, "s", color="k", label="stripes: fraction overturned")
        for a, ki, ni in zip(ag, k, n, strict=True):
            ax.annotate(
                f"{ki}/{ni}", (a, ki / ni), textcoords="offset points", xytext=(4, 6), fontsize=8
            )
    mine = [r for r in ida if r["tower_id"] == tower_id]
    levels = (("collapse", "C3", "collapse (overturning)"), ("slv", "C0", "SLV (theta/alpha 0.4)"))
    for level, color, label in levels:
        if not mine:
            break
        data = record_intensities(mine, level)
        order = np.argsort(data.ag_g)
        position = (np.arange(1, len(order) + 1) - 0.5) / len(order)
        x, cens = data.ag_g[order], data.censored[order]
        values.extend(x)
        ax.plot(x[~cens], position[~cens], "o", color=color, label=f"IDA {label}")
        if cens.any():
            ax.plot(
                x[cens],
                position[cens],
                "o",
                mfc="none",
                color=color,
                label=f"IDA {label}, censored (at the censoring ag)",
            )
    curves = [("collapse", "C3", "collapse")] if "collapse_median_g" in row else []
    curves += [("slv", "C0", "SLV")] if "slv_median_g" in row else []
    if not curves:  # an archive before the IDA: the stripe fit
        curves = [("fragility", "C3", "stripe fit")]
    for level, color, label in curves:
        median, beta = row[f"{level}_median_g"], row[f"{level}_beta"]
        bound = row.get(f"{level}_bound", row.get("median_is_bound", ""))
        values.append(median)
        if math.isfinite(median) and math.isfinite(beta) and beta > 0 and not bound:
            grid = np.geomspace(max(min(values) / 3, 1e-3), max(values) * 2, 200)
            ax.plot(
                grid,
                fragility_probability(grid, median, beta),
                color=color,
                label=f"{label}: median {median:.3g} g, beta {beta:.2f}",
            )
        elif math.isfinite(median):
            what = f"{bound} bound" if bound else "degenerate (beta 0)"
            ax.axvline(median, color=color, ls="--", label=f"{label} median {what} {median:.3g} g")
    ax.set_xscale("log")
    ax.set_ylim(-0.05, 1.05)
    ax.set_xlabel("site ag on rock [g]")
    ax.set_ylabel("P(level reached) [-]")
    ax.set_title(f"{tower_id}: fragilities (record-to-record variability only)")
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    path = _save(fig, out)
    plt.close(fig)
    return path


def _points(rows, key):
    good = [r for r in rows if math.isfinite(r["lat_deg"]) and math.isfinite(r["lon_deg"])]
    lon = np.array([r["lon_deg"] for r in good])
    lat = np.array([r["lat_deg"] for r in good])
    val = np.array([r[key] for r in good], dtype=float)
    return good, lon, lat, val


def plot_safety_map(summary: Sequence[dict[str, Any]], out) -> Path:
    """Map the towers coloured by the safety index I_S (log scale; grey = undefined)."""
    plt = _figure()

    good, lon, lat, val = _points(summary, "safety_index")
    fig, ax = plt.subplots(figsize=(6.4, 5.2))
    ok = np.isfinite(val) & (val > 0)
    if np.any(~ok):
        ax.scatter(lon[~ok], lat[~ok], c="0.6", marker="x", label="I_S undefined")
    if np.any(ok):
        sc = ax.scatter(
            lon[ok],
            lat[ok],
            c=val[ok],
            cmap="RdYlGn",
            s=50,
            edgecolors="k",
            norm=LogNorm(vmin=0.1, vmax=10.0),
        )
        fig.colorbar(sc, ax=ax, label="safety index I_S = T_R,C / T_R,SLV [-]")
    for r, x, y in zip(good, lon, lat, strict=True):
        ax.annotate(r["id"], (x, y), fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.set_xlabel("longitude [deg]")
    ax.set_ylabel("latitude [deg]")
    ax.set_title("towers by safety index (I_S >= 1 meets the code)")
    fig.tight_layout()
    path = _save(fig, out)
    plt.close(fig)
    return path


def plot_scenario_map(rows: Sequence[dict[str, Any]], grid: Any, out) -> Path:
    """Map the event PGA (grid nodes present) and the towers coloured by P(overturning)."""
    plt = _figure()
    fig, ax = plt.subplots(figsize=(6.8, 5.4))
    lons = grid.lon_min + np.arange(grid.nlon) * grid.dlon
    lats = grid.lat_min + np.arange(grid.nlat) * grid.dlat
    mesh = ax.pcolormesh(
        lons, lats, np.ma.masked_invalid(grid.pga_g), shading="nearest", cmap="Greys", alpha=0.6
    )
    fig.colorbar(mesh, ax=ax, label="event PGA (surface) [g]")
    good, lon, lat, val = _points(rows, "p_overturning")
    ok = np.isfinite(val)
    if np.any(ok):
        sc = ax.scatter(
            lon[ok], lat[ok], c=val[ok], cmap="inferno_r", vmin=0, vmax=1, s=60, edgecolors="k"
        )
        fig.colorbar(sc, ax=ax, label="P(overturning) [-]")
    if np.any(~ok):
        ax.scatter(lon[~ok], lat[~ok], c="C0", marker="x", label="no probability (see status)")
        ax.legend(fontsize=8)
    for r, x, y in zip(good, lon, lat, strict=True):
        ax.annotate(r["id"], (x, y), fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.set_xlabel("longitude [deg]")
    ax.set_ylabel("latitude [deg]")
    ax.set_title(f"event {grid.event.get('event_id', '')}: probability of overturning")
    fig.tight_layout()
    path = _save(fig, out)
    plt.close(fig)
    return path
