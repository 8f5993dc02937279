"""Figures of assess and scenario archives: fragility curve, I_S map, scenario map."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.colors import LogNorm
from matplotlib.figure import Figure

from rockscreen.pipeline.archive.atomic import atomic_path
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.report.map_frame import (
    draw_scale_bar,
    label_points,
    map_extent,
    set_map_frame,
)
from rockscreen.pipeline.report.risk_summary import rank_towers
from rockscreen.pipeline.report.values import Row
from rockscreen.pipeline.risk.assess.tower_ida import record_intensities
from rockscreen.pipeline.risk.measures.fragility import fragility_probability
from rockscreen.pipeline.text import printable

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.axis import Axis
    from matplotlib.colors import Colormap

    from rockscreen.pipeline.hazard.shakemap import ShakeMapGrid

__all__ = [
    "draw_risk_band",
    "log_ticks",
    "plot_fragility",
    "plot_safety_map",
    "plot_scenario_map",
    "safety_map_figure",
    "scenario_map_figure",
]


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


def _plain(value: float, _position: int | None = None) -> str:
    """Return a tick label in plain decimals (``0.05``, ``0.2``, ``1``, ``20``)."""
    return f"{value:.6g}"


def log_ticks(axis: Axis) -> None:
    """Give a log axis readable ticks: labels at 1, 2 and 5 per decade, none in between.

    Matplotlib's default labels the minor ticks of an axis spanning less than a decade or
    two, and their labels (``2×10⁻¹``, ``3×10⁻¹``, ...) overlap; here the labelled ticks
    are at 1, 2 and 5 times a power of ten (at most about eight), written as plain decimals,
    and the minor ticks are unlabelled.

    Parameters
    ----------
    axis : matplotlib.axis.Axis
        A log-scaled axis (``ax.xaxis``).
    """
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    axis.set_major_locator(LogLocator(base=10.0, subs=(1.0, 2.0, 5.0), numticks=8))
    axis.set_major_formatter(FuncFormatter(_plain))
    axis.set_minor_locator(LogLocator(base=10.0, subs=np.arange(2, 10) * 1.0, numticks=12))
    axis.set_minor_formatter(NullFormatter())


def plot_fragility(
    tower_id: str,
    summary: Sequence[Row],
    stripes: Sequence[Row],
    out,
    ida: Sequence[Row] = (),
    risk_band: Sequence[Row] = (),
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
    summary, stripes : sequence of mapping
        The archive's ``/summary`` and ``/stripes`` rows.
    out : str or Path
        The PNG.
    ida : sequence of mapping, optional
        The archive's ``/ida`` rows.
    risk_band : sequence of mapping, optional
        The archive's ``/risk_fragility`` rows (the screening risk, issue 31): the tower's
        median curve and its 5-95 % band over the epistemic samples are drawn beside the
        record-based fits, labelled as the screening risk's (:func:`draw_risk_band`).
    """
    plt = _figure()

    rows = [r for r in summary if r["id"] == tower_id]
    if not rows:
        shown = ", ".join(r["id"] for r in summary[:10])
        raise ArchiveError(f"tower {tower_id!r} is not in the archive (towers: {shown}...)")
    row = rows[0]
    own = sorted((s for s in stripes if s["tower_id"] == tower_id), key=lambda s: s["ag_g"])
    fig, ax = plt.subplots(figsize=(7.0, 4.8))
    # Every intensity drawn, in the order drawn: the fitted curves span them.
    values = _draw_stripes(ax, own)
    values.extend(_draw_ida(ax, [r for r in ida if r["tower_id"] == tower_id]))
    _draw_fits(ax, row, values)
    banded = draw_risk_band(ax, [r for r in risk_band if r["tower_id"] == tower_id])
    ax.set_xscale("log")
    log_ticks(ax.xaxis)
    ax.set_ylim(-0.05, 1.05)
    ax.set_xlabel("site ag on rock [g]")
    ax.set_ylabel("P(level reached) [-]")
    ax.set_title(
        f"{tower_id}: fragilities (record-to-record variability only)"
        + ("; screening risk band (epistemic)" if banded else "")
    )
    ax.legend(fontsize=7, loc="upper left")
    fig.tight_layout()
    path = _save(fig, out)
    plt.close(fig)
    return path


def draw_risk_band(ax: Axes, band: Sequence[Row]) -> bool:
    """Draw the screening risk's fragility: its median curve and its 5-95 % band.

    The band is over the epistemic samples (best estimates at mean strengths, no partial
    factor: RISK_CONTRACT), a different question from the record-based fits beside it, and
    labelled so.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    band : sequence of mapping
        One tower's ``/risk_fragility`` rows: ``ag_g`` [g], ``p_median``, ``p_lo90``,
        ``p_hi90`` [1].

    Returns
    -------
    bool
        Whether anything was drawn (False: no band, an archive without the screening risk).
    """
    rows = sorted((r for r in band if r["ag_g"] > 0), key=lambda r: r["ag_g"])
    if not rows:
        return False
    ag = np.array([r["ag_g"] for r in rows])
    lo, hi = (np.array([r[key] for r in rows]) for key in ("p_lo90", "p_hi90"))
    ax.fill_between(ag, lo, hi, color="C2", alpha=0.2, label="screening risk: 5-95 % band")
    ax.plot(
        ag,
        [r["p_median"] for r in rows],
        color="C2",
        label="screening risk: median (best estimate)",
    )
    return True


def _draw_stripes(ax: Axes, own: Sequence[Row]) -> list[float]:
    """Draw a tower's stripes' fractions overturned, counts annotated; return their ag [g].

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    own : sequence of mapping
        The tower's ``/stripes`` rows by increasing ``ag_g``.
    """
    ag = np.array([s["ag_g"] for s in own])
    if len(ag):
        k = np.array([s["n_overturned"] for s in own])
        n = np.array([s["n_records"] for s in own])
        ax.plot(ag, k / n, "s", color="k", label="stripes: fraction overturned")
        for i, (a, ki, ni) in enumerate(zip(ag, k, n, strict=True)):
            # Staggered above and below: neighbouring stripes are close on a log axis.
            ax.annotate(
                f"{ki}/{ni}",
                (a, ki / ni),
                textcoords="offset points",
                xytext=(0, 7 if i % 2 == 0 else -12),
                ha="center",
                fontsize=7,
            )
    return list(ag)


def _draw_ida(ax: Axes, mine: Sequence[Row]) -> list[float]:
    """Draw a tower's records' collapse and SLV intensities; return them [g].

    Each at its empirical plotting position ``(i - 0.5) / n``: filled markers for the
    observed intensities, open ones at the censoring intensity for the censored records.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    mine : sequence of mapping
        The tower's ``/ida`` rows (none: nothing drawn).
    """
    values: list[float] = []
    if not mine:
        return values
    levels = (("collapse", "C3", "collapse (overturning)"), ("slv", "C0", "SLV (theta/alpha 0.4)"))
    for level, color, label in levels:
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
    return values


def _draw_fits(ax: Axes, row: Row, values: list[float]) -> None:
    """Draw a tower's fitted collapse and SLV fragilities, or their bound medians (dashed).

    An archive before the IDA (no ``collapse_median_g``/``slv_median_g``) has the stripe
    fit alone. Each curve spans ``values`` (the intensities drawn) and the medians drawn
    before it; each median is appended to ``values``.

    Parameters
    ----------
    ax : matplotlib.axes.Axes
    row : mapping
        The tower's ``/summary`` row.
    values : list of float
        The intensities drawn so far [g].
    """
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


def _points(rows, key):
    good = [r for r in rows if math.isfinite(r["lat_deg"]) and math.isfinite(r["lon_deg"])]
    lon = np.array([r["lon_deg"] for r in good])
    lat = np.array([r["lat_deg"] for r in good])
    val = np.array([r[key] for r in good], dtype=float)
    return good, lon, lat, val


def _new_figure(size: tuple[float, float]) -> Figure:
    figure = Figure(figsize=size, layout="constrained")
    FigureCanvasAgg(figure)
    return figure


def _label(ax: Axes, rows: Sequence[Row], lon: np.ndarray, lat: np.ndarray) -> None:
    """Label the towers where the labels collide with nothing (riskiest first)."""
    ax.figure.draw_without_rendering()  # the layout settled: pixel boxes are right
    order = rank_towers(list(rows)) if rows and "safety_index" in rows[0] else list(rows)
    if rows and "p_overturning" in rows[0]:
        order = sorted(
            rows,
            key=lambda r: -(r["p_overturning"] if r["p_overturning"] == r["p_overturning"] else -1),
        )
    where = {str(r["id"]): (x, y) for r, x, y in zip(rows, lon, lat, strict=True)}
    label_points(
        ax,
        [(printable(str(r["id"])), *where[str(r["id"])]) for r in order],
        list(zip(lon, lat, strict=True)),
    )


def _is_lower_bound(row: Row) -> bool:
    """Tell whether a row's I_S is a lower bound (its SLV median is one)."""
    return row.get("slv_bound", row.get("median_is_bound", "")) == "lower"


def safety_map_figure(summary: Sequence[Row]) -> Figure:
    """Return the map of the towers coloured by the safety index I_S.

    Log colour scale (red below 1, green above); a lower-bound I_S (no record reached
    the SLV level before its search ended) is a hollow ring in its colour, with a legend
    entry; grey crosses for an undefined I_S. The extent is fitted to the towers, with a
    scale bar and the graticule in degrees.

    Parameters
    ----------
    summary : sequence of mapping
        The assess archive's ``/summary`` rows.

    Returns
    -------
    matplotlib.figure.Figure

    Raises
    ------
    ArchiveError
        If no tower has coordinates.
    """
    good, lon, lat, val = _points(summary, "safety_index")
    if not good:
        raise ArchiveError("I_S map: no tower has coordinates")
    fig = _new_figure((6.8, 5.6))
    ax = fig.add_subplot()
    norm = LogNorm(vmin=0.1, vmax=10.0)
    ok = np.isfinite(val) & (val > 0)
    bound = np.array([_is_lower_bound(r) for r in good], dtype=bool)
    if np.any(~ok):
        ax.scatter(lon[~ok], lat[~ok], c="0.5", marker="x", s=40, label="I_S undefined", zorder=4)
    fitted, lower = ok & ~bound, ok & bound
    mappable = None
    if np.any(fitted):
        mappable = ax.scatter(
            lon[fitted],
            lat[fitted],
            c=val[fitted],
            cmap="RdYlGn",
            norm=norm,
            s=55,
            edgecolors="k",
            label="I_S (fitted)",
            zorder=4,
        )
    if np.any(lower):
        colours = plt_colormap("RdYlGn")(norm(np.clip(val[lower], 0.1, 10.0)))
        ax.scatter(
            lon[lower],
            lat[lower],
            s=70,
            facecolors="none",
            edgecolors=colours,
            linewidths=2.2,
            label="I_S lower bound (hollow: at least this)",
            zorder=4,
        )
    if mappable is None:
        from matplotlib.cm import ScalarMappable

        mappable = ScalarMappable(norm=norm, cmap="RdYlGn")
    fig.colorbar(mappable, ax=ax, label="safety index I_S = T_R,C / T_R,SLV [-]")
    mean_latitude = set_map_frame(ax, map_extent(list(lon), list(lat)))
    _label(ax, good, lon, lat)
    draw_scale_bar(ax, mean_latitude)
    ax.legend(fontsize=7, loc="upper left")
    ax.set_title("towers by safety index (I_S >= 1 meets the code)")
    return fig


def plot_safety_map(summary: Sequence[Row], out) -> Path:
    """Save :func:`safety_map_figure` as a PNG and return its path."""
    return _save(safety_map_figure(summary), out)


def plt_colormap(name: str) -> Colormap:
    """Return a registered matplotlib colormap by name (no pyplot)."""
    from matplotlib import colormaps

    return colormaps[name]


#: Colour ramp of the towers' P(overturning) on the scenario map: yellow to dark red,
#: readable on the light blue ShakeMap (the riskiest are dark red, not black on grey).
SCENARIO_TOWER_CMAP = "YlOrRd"
#: Colour ramp of the ShakeMap's PGA beneath (light, so that the towers stand out).
SCENARIO_PGA_CMAP = "Blues"


def scenario_map_figure(rows: Sequence[Row], grid: ShakeMapGrid) -> Figure:
    """Return the scenario map: the event PGA beneath, the towers by P(overturning).

    The extent is fitted to the towers (the ShakeMap is drawn where it overlaps them; a
    grid hundreds of kilometres away no longer sets the axes); the grid's extent only
    when no tower has coordinates.

    Parameters
    ----------
    rows : sequence of mapping
        The scenario archive's ``/summary`` rows.
    grid : ShakeMapGrid
        The event's grid (``lon_min``, ``lat_min``, ``dlon``, ``dlat``, ``nlon``,
        ``nlat``, ``pga_g``, ``event``).

    Returns
    -------
    matplotlib.figure.Figure
    """
    fig = _new_figure((7.2, 5.8))
    ax = fig.add_subplot()
    lons = grid.lon_min + np.arange(grid.nlon) * grid.dlon
    lats = grid.lat_min + np.arange(grid.nlat) * grid.dlat
    mesh = ax.pcolormesh(
        lons,
        lats,
        np.ma.masked_invalid(grid.pga_g),
        shading="nearest",
        cmap=SCENARIO_PGA_CMAP,
        alpha=0.55,
        zorder=1,
    )
    fig.colorbar(mesh, ax=ax, label="event PGA (surface) [g]", shrink=0.8)
    good, lon, lat, val = _points(rows, "p_overturning")
    ok = np.isfinite(val)
    if np.any(ok):
        sc = ax.scatter(
            lon[ok],
            lat[ok],
            c=val[ok],
            cmap=SCENARIO_TOWER_CMAP,
            vmin=0,
            vmax=1,
            s=70,
            edgecolors="k",
            linewidths=0.8,
            zorder=4,
        )
        fig.colorbar(sc, ax=ax, label="P(overturning) [-]", shrink=0.8)
    if np.any(~ok):
        ax.scatter(
            lon[~ok],
            lat[~ok],
            c="0.25",
            marker="x",
            s=40,
            label="no probability (see status)",
            zorder=4,
        )
        ax.legend(fontsize=8, loc="upper left")
    if good:
        extent = map_extent(list(lon), list(lat))
    else:
        extent = (lons[0], lons[-1], lats[0], lats[-1])
    mean_latitude = set_map_frame(ax, extent)
    _label(ax, good, lon, lat)
    draw_scale_bar(ax, mean_latitude)
    ax.set_title(
        f"event {printable(str(grid.event.get('event_id', '')))}: probability of overturning"
    )
    return fig


def plot_scenario_map(rows: Sequence[Row], grid: ShakeMapGrid, out) -> Path:
    """Save :func:`scenario_map_figure` as a PNG and return its path."""
    return _save(scenario_map_figure(rows, grid), out)
