"""Figures of a campaign archive: rotation time histories of one tower.

In the style of the seed paper's Figures 10-12 (Di Gennaro et al. 2023): one panel per
model, the normalised rotation theta/alpha against time, one colour per record
component, dashed lines at +-1 (theta = alpha, the static overturning limit). The
rotation in radians is on a secondary axis when the panel's curves share one alpha.
Matplotlib's object API only (``Figure``, Agg canvas): no pyplot state.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, TypeAlias, TypedDict

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from rockscreen.pipeline.archive.campaign import read_results, read_summary
from rockscreen.pipeline.engine import registry
from rockscreen.pipeline.report.motions import read_component_motion
from rockscreen.pipeline.report.values import Row
from rockscreen.pipeline.text import printable

if TYPE_CHECKING:
    from matplotlib.axes import Axes

#: Below this peak theta/alpha a panel is scaled to its own curves (the +-1 lines drop out
#: of view): a tower rocking at 5 % of alpha would otherwise be a flat line.
OFF_SCALE_BELOW = 0.5
#: Share of a history's own peak |θ| below which it counts as at rest (the time axis is
#: fitted to where the histories exceed it).
MOTION_THRESHOLD = 1e-3
#: One stored rotation history (:func:`rockscreen.pipeline.archive.campaign.read_histories`):
#: ``record_id``, ``channel_id``, ``component``, ``model`` (text), ``alpha_rad`` [rad], and
#: its arrays ``t`` [s] and ``theta`` [rad].
History: TypeAlias = Mapping[str, str | float | np.ndarray]


def readable_ratio(value: float) -> str:
    """Return θ/α (or any small dimensionless number) for a reader, not a parser.

    Three significant digits; below 0.001 as a power of ten with a superscript
    exponent (``5.34 × 10⁻⁵``), never in the ``5.34e-05`` notation.

    Parameters
    ----------
    value : float
        The number.

    Returns
    -------
    str
        The text.

    Examples
    --------
    >>> readable_ratio(0.384)
    '0.384'
    >>> readable_ratio(5.34e-5)
    '5.34 × 10⁻⁵'
    >>> readable_ratio(0.0)
    '0'
    """
    if value != value or value in (float("inf"), float("-inf")):
        return str(value)
    if value == 0.0 or 1e-3 <= abs(value) < 1e4:
        return f"{value:.3g}"
    exponent = int(np.floor(np.log10(abs(value))))
    mantissa = value / 10.0**exponent
    if round(abs(mantissa), 2) >= 10.0:
        mantissa, exponent = mantissa / 10.0, exponent + 1
    superscript = str(exponent).translate(str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹"))
    return f"{mantissa:.3g} × 10{superscript}"


def _rotation_limits(peak: float) -> tuple[float, float]:
    """Return symmetric y limits [-] for a panel whose largest |theta/alpha| is ``peak``."""
    if peak < OFF_SCALE_BELOW:
        half = 1.15 * peak if peak > 0.0 else 0.05
    else:
        half = 1.15 * max(peak, 1.0)
    return -half, half


def _motion_window(histories: Sequence[History]) -> tuple[float, float] | None:
    """Return the time span [s] where any history rocks, padded by 10 %; None if none moves.

    Real records are long (minutes of coda) while the rocking lasts seconds: plotting the
    whole record would squeeze the motion into a spike. A history "rocks" where its
    |θ| exceeds :data:`MOTION_THRESHOLD` of its own peak, so that a tail of round-off
    or of a free vibration decayed to nothing does not stretch the axis to the record's
    end.
    """
    starts, ends = [], []
    for h in histories:
        t = np.asarray(h["t"], dtype=float)
        theta = np.abs(np.asarray(h["theta"], dtype=float))
        peak = float(np.max(theta, initial=0.0))
        moving = np.flatnonzero(theta > MOTION_THRESHOLD * peak) if peak > 0.0 else theta[:0]
        if moving.size:
            starts.append(t[moving[0]])
            ends.append(t[moving[-1]])
    if not starts:
        return None
    start, end = min(starts), max(ends)
    pad = 0.1 * max(end - start, 1.0)
    return max(start - pad, 0.0), end + pad


def _verdict_text(summary: Row | None, pga_m_s2: float | None) -> str:
    """Return the figure's verdict line: class, safety factor, governing record, PGA."""
    if not summary:
        return ""
    try:
        sf = float(summary.get("safety_factor", float("nan")))
    except (TypeError, ValueError):  # a crafted archive: not a number
        sf = float("nan")
    limit = summary.get("safety_factor_limit", "")
    sf_text = "inf" if sf == float("inf") else ("-" if sf != sf else f"{sf:.2f}")
    if limit in ("vertical_limit", "cap"):
        sf_text += f" ({'vertical limit' if limit == 'vertical_limit' else 'cap'})"
    parts = [
        f"class {summary.get('risk_class', '?')}",
        f"safety factor {sf_text}",
        f"governing {summary.get('governing_record') or '-'} / "
        f"{summary.get('governing_model') or '-'}",
    ]
    if pga_m_s2 is not None:
        parts.append(f"ground PGA {pga_m_s2:.2f} m/s² ({pga_m_s2 / 9.81:.2f} g)")
    return printable("; ".join(parts))


def _still_figure(tower_id: str, verdict: str) -> Figure:
    """Return a figure that says the tower never moved (instead of flat panels)."""
    fig = Figure(figsize=(9.0, 2.2), layout="constrained")
    FigureCanvasAgg(fig)
    ax = fig.subplots()
    ax.set_axis_off()
    ax.text(
        0.5,
        0.55,
        f"tower {printable(tower_id)} did not rock under any stored record:\n"
        "θ = 0 throughout (no sample reached the uplift threshold)",
        ha="center",
        va="center",
        fontsize=11,
    )
    if verdict:
        ax.text(0.5, 0.1, verdict, ha="center", va="center", fontsize=9, color="0.3")
    return fig


def tower_history_figure(
    tower_id: str,
    histories: Sequence[History],
    summary: Row | None = None,
    motion: tuple[np.ndarray, np.ndarray, str] | None = None,
    pga_m_s2: float | None = None,
) -> Figure:
    """Return the rotation-history figure of one tower.

    One panel per model with the histories the archive keeps (by default the worst
    component of every record and model), θ/α on one y-scale shared by all panels, the
    verdict (class, safety factor, governing record, PGA) under the title, and the input
    ground motion of the governing case beneath.

    Parameters
    ----------
    tower_id : str
        Shown in the title.
    histories : sequence of mapping
        From :func:`pipeline.archive.campaign.read_histories`: ``record_id``, ``component``,
        ``model``, ``alpha_rad`` [rad], ``t`` [s], ``theta`` [rad].
    summary : mapping, optional
        The tower's summary row (class, safety factor and its limit, governing case).
    motion : (t [s], acceleration [m/s²], label), optional
        The governing case's ground motion, drawn in a panel beneath.
    pga_m_s2 : float, optional
        Peak ground acceleration of the governing case [m/s²].

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
    verdict = _verdict_text(summary, pga_m_s2)
    if all(not np.any(np.asarray(h["theta"], dtype=float)) for h in histories):
        return _still_figure(tower_id, verdict)
    models = [m.name for m in registry.models() if any(h["model"] == m.name for h in histories)]
    rows = len(models) + (motion is not None)
    fig = Figure(figsize=(9.0, 2.6 * rows + 0.8), layout="constrained")
    FigureCanvasAgg(fig)
    axes = fig.subplots(rows, 1, sharex=True, squeeze=False)[:, 0]
    peak = max(
        float(np.max(np.abs(np.asarray(h["theta"], dtype=float) / h["alpha_rad"]), initial=0.0))
        for h in histories
    )
    for ax, model in zip(axes, models, strict=False):
        _rotation_panel(ax, model, [h for h in histories if h["model"] == model], peak)
    if motion is not None:
        t, acc, label = motion
        ax = axes[-1]
        ax.plot(t, acc, color="0.25", lw=0.6)
        ax.set_ylabel("a [m/s²]")
        ax.set_title(f"input ground motion: {printable(label)}", fontsize=10, loc="left")
    window = _motion_window(histories)
    if window is not None:
        axes[-1].set_xlim(*window)
    axes[-1].set_xlabel("t [s]")
    title = f"tower {printable(tower_id)}: rotation histories (±1: θ = α; y-scale shared)"
    fig.suptitle(title + (f"\n{verdict}" if verdict else ""), fontsize=11)
    return fig


def _rotation_panel(ax: Axes, model: str, panel: list[History], peak: float) -> None:
    """Draw one model's θ/α histories on a y-scale set by ``peak`` (shared by all panels).

    The panel's title gives the panel's own peak θ/α (its cases only), not the tower's.
    """
    labels = sorted({f"{h['record_id']}{h['component']}" for h in panel})
    for i, label in enumerate(labels):
        for h in panel:
            if f"{h['record_id']}{h['component']}" == label:
                ratio = np.asarray(h["theta"], dtype=float) / h["alpha_rad"]
                ax.plot(h["t"], ratio, color=f"C{i % 10}", lw=0.9, label=printable(label))
    for level in (-1.0, 1.0):
        ax.axhline(level, color="k", ls="--", lw=0.8)
    ax.axhline(0.0, color="0.6", lw=0.5)
    ax.set_ylim(*_rotation_limits(peak))
    own = max(
        float(np.max(np.abs(np.asarray(h["theta"], dtype=float) / h["alpha_rad"]), initial=0.0))
        for h in panel
    )
    title = f"{registry.get(model).label}: peak θ/α = {readable_ratio(own)}"
    if peak < OFF_SCALE_BELOW:
        title += " (the ±1 lines are off scale)"
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


def save_tower_histories(
    tower_id: str,
    histories: Sequence[History],
    out_png: str | Path,
    summary: Row | None = None,
    motion: tuple[np.ndarray, np.ndarray, str] | None = None,
    pga_m_s2: float | None = None,
) -> Path:
    """Save :func:`tower_history_figure` as a PNG and return its path.

    ``summary``, ``motion`` and ``pga_m_s2`` are passed on (:func:`tower_figure_details`).
    """
    out_png = Path(out_png)
    figure = tower_history_figure(
        tower_id, histories, summary=summary, motion=motion, pga_m_s2=pga_m_s2
    )
    figure.savefig(out_png, dpi=130)
    return out_png


class FigureDetails(TypedDict, total=False):
    """What a tower's history figure shows besides the histories (:func:`tower_figure_details`)."""

    #: The tower's summary row; None when the archive has no row of that id.
    summary: Row | None
    #: Ground PGA of the governing case [m/s²]; None where the archive does not hold it.
    pga_m_s2: float | None
    #: The governing case's ground motion: (t [s], acceleration [m/s²], label); None where
    #: the archive does not hold it.
    motion: tuple[np.ndarray, np.ndarray, str] | None


def tower_figure_details(archive: str | Path, tower_id: str) -> FigureDetails:
    """Read what the figure shows besides the histories: verdict, PGA, input motion.

    Parameters
    ----------
    archive : str or Path
        A campaign archive.
    tower_id : str
        The tower.

    Returns
    -------
    FigureDetails
        ``summary`` (the tower's row), ``pga_m_s2`` and ``motion`` of the governing case
        (``None`` where the archive does not hold it), for :func:`save_tower_histories`.
    """
    summary = next((r for r in read_summary(archive) if r["id"] == tower_id), None)
    if summary is None or not summary.get("governing_record"):
        return {"summary": summary}
    component = summary.get("governing_component", "")
    record = str(summary["governing_record"])[: -len(component) or None]
    found = read_component_motion(archive, tower_id, record, component)
    if found is not None:
        label = str(summary["governing_record"])
        model = registry.get(str(summary.get("governing_model")))
        if model.base_motion is not None:
            label += (
                f" (ground; the {model.name} model is driven by the {model.name} motion derived "
                "from it)"
            )
        # The ground PGA: the peak of the motion shown (the results' pga_m_s2 is the peak of
        # the model's own input, for the floor model the floor motion).
        pga = float(np.max(np.abs(found[1]), initial=0.0))
        return {"summary": summary, "pga_m_s2": pga, "motion": (found[0], found[1], label)}
    # The stored motion is not there (a rotated component without azimuths): the ground
    # case's input peak, when the governing case is not the floor model's.
    pga = None
    if registry.get(str(summary.get("governing_model"))).base_motion is None:
        case = next(
            (
                r
                for r in read_results(archive)
                if r["tower_id"] == tower_id
                and r["record_id"] == record
                and r["component"] == component
                and r["model"] == summary.get("governing_model")
            ),
            None,
        )
        pga = None if case is None else float(case["pga_m_s2"])
    return {"summary": summary, "pga_m_s2": pga, "motion": None}
