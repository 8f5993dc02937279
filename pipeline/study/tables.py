"""Tables of a sweep: the plain-text table printed by ``rockscreen sweep`` and Markdown tables."""

from __future__ import annotations

import math
from typing import Any

from rockscreen.pipeline.engine.registry import solver_model


def _has_friction(model: str) -> bool:
    """Whether the study model ``model`` (its solver name) has friction coefficients."""
    return solver_model(model).takes("mu_s")


def _fmt(value: float, spec: str) -> str:
    return (
        "-"
        if value is None or (isinstance(value, float) and math.isnan(value))
        else format(value, spec)
    )


def format_cases_table(rows: list[dict[str, Any]]) -> str:
    """Format ``/cases`` rows (as from :func:`read_cases`) as a plain-text table."""
    headers = (
        "#",
        "group",
        "model",
        "A [g]",
        "f [Hz]",
        "mu_s [-]",
        "mu_k [-]",
        "status",
        "theta_max [rad]",
        "theta_max/alpha [-]",
        "impacts",
        "slip_max [m]",
    )
    body = [
        (
            str(r["index"]),
            str(r["group"]),
            str(r["model"]),
            _fmt(r["amplitude_g"], ".3g"),
            _fmt(r["frequency_hz"], "g"),
            _fmt(r["mu_s"], "g"),
            _fmt(r["mu_k"], "g"),
            str(r["status"]),
            _fmt(r["theta_max_rad"], ".4g"),
            _fmt(r["theta_max_over_alpha"], ".4f"),
            str(r["n_impacts"]),
            _fmt(r["slip_max_m"], ".3g"),
        )
        for r in rows
    ]
    widths = [max([len(h)] + [len(b[i]) for b in body]) for i, h in enumerate(headers)]
    lines = ["  ".join(h.rjust(w) for h, w in zip(headers, widths, strict=True))]
    lines.append("  ".join("-" * w for w in widths))
    lines += ["  ".join(c.rjust(w) for c, w in zip(b, widths, strict=True)) for b in body]
    return "\n".join(lines)


def format_markdown_tables(rows: list[dict[str, Any]], title: str = "") -> str:
    """Format ``/cases`` rows as Markdown tables in the layout of the seed paper's tables.

    One table per (group, amplitude, duration): a row per (mu_s, mu_k, eta) and a
    column per frequency; each cell is theta_max [rad] followed by theta_max/alpha in
    parentheses, with the run's status when the tower overturned or never uplifted.

    Parameters
    ----------
    rows : list of dict
        As from :func:`read_cases`.
    title : str
        Heading put above the tables (omitted when empty).

    Returns
    -------
    str
        Markdown text.
    """
    tables: dict[tuple, list[dict[str, Any]]] = {}
    for row in rows:
        key = (row["group_index"], row["group"], row["amplitude"], row["duration_s"])
        tables.setdefault(key, []).append(row)
    parts = [f"### {title}\n"] if title else []
    for (_, group, amplitude, duration), t_rows in tables.items():
        freqs = list(dict.fromkeys(r["frequency_hz"] for r in t_rows))
        lines: dict[tuple, dict[float, str]] = {}
        for r in t_rows:
            cell = f"{r['theta_max_rad']:.4g} ({r['theta_max_over_alpha']:.3f})"
            if r["status"] in ("overturned", "no_motion"):
                cell = r["status"].replace("_", " ")
            # NaN friction (rocking rows) must compare equal to group into one line
            friction_key = (r["mu_s"], r["mu_k"]) if _has_friction(r["model"]) else (None, None)
            form = r.get("formulation", "consistent")
            key = (r["model"], form, *friction_key, r["eta"])
            lines.setdefault(key, {})[r["frequency_hz"]] = cell
        parts.append(
            f"**{group}, A = {amplitude}, excitation {duration:.4g} s**: "
            "theta_max [rad] (theta_max/alpha [-])\n"
        )
        parts.append("| mu_s / mu_k | eta | " + " | ".join(f"{f:g} Hz" for f in freqs) + " |")
        parts.append("|---|---|" + "---|" * len(freqs))
        with_form = len({key[1] for key in lines}) > 1
        if with_form:
            parts[-2] = parts[-2].replace("| mu_s / mu_k |", "| formulation | mu_s / mu_k |", 1)
            parts[-1] = "|---" + parts[-1]
        for (model, form, mu_s, mu_k, eta), cells in lines.items():
            friction = f"{mu_s:g} / {mu_k:g}" if _has_friction(model) else "single block"
            if with_form:
                friction = f"{form} | {friction}"
            values = " | ".join(cells.get(f, "") for f in freqs)
            parts.append(f"| {friction} | {eta:g} | {values} |")
        parts.append("")
    return "\n".join(parts)
