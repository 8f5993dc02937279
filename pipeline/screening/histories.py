"""Time histories kept in the archive: which cases, and peak-preserving decimation."""

from __future__ import annotations

import math
from typing import Any

import numpy as np


def severity(row: dict[str, Any]) -> tuple[bool, float]:
    """Return the ordering key of a case: overturned first, then theta_max/alpha."""
    ratio = row["theta_max_over_alpha"]
    return (bool(row["overturned"]), -math.inf if math.isnan(ratio) else float(ratio))


def decimate(response: Any, points: int | None) -> tuple[np.ndarray, ...]:
    """Return (t, theta, u, regime), peak-preserving decimation to <= ``points`` samples.

    The points go to the motion window (from the sample before the first motion to the
    sample after the last), plus the record's first and last samples: a tower rocks for
    seconds of a record that may last minutes. Inside the window each bin of
    ``ceil(n / (points - 2))`` samples keeps the sample of largest ``|theta|``, so the
    plotted peaks equal the true ones.
    """
    t = np.asarray(response.t, dtype=float)
    theta = np.asarray(response.theta, dtype=float)
    u = getattr(response, "u", None)
    u = np.zeros_like(theta) if u is None else np.asarray(u, dtype=float)
    regime = getattr(response, "regime", None)
    regime = np.zeros(len(theta), dtype=np.int8) if regime is None else np.asarray(regime)
    if points is not None and len(theta) > points:
        keep = _decimated_indices(theta, regime, points)
        t, theta, u, regime = t[keep], theta[keep], u[keep], regime[keep]
    return (
        t.astype(np.float32),
        theta.astype(np.float32),
        u.astype(np.float32),
        regime.astype(np.int8),
    )


def _decimated_indices(theta: np.ndarray, regime: np.ndarray, points: int) -> np.ndarray:
    """Return at most ``points`` sample indices: the ends plus the peak-binned motion window."""
    n = len(theta)
    active = np.flatnonzero((theta != 0.0) | (regime != 0))
    if active.size == 0:
        return np.array([0, n - 1])
    lo, hi = max(active[0] - 1, 0), min(active[-1] + 1, n - 1)
    window = np.abs(theta[lo : hi + 1])
    step = math.ceil(window.size / max(points - 2, 1))
    n_bins = math.ceil(window.size / step)
    padded = np.full(n_bins * step, -1.0)
    padded[: window.size] = window
    peaks = lo + np.arange(n_bins) * step + np.argmax(padded.reshape(n_bins, step), axis=1)
    return np.unique(np.concatenate(([0], peaks, [n - 1])))


def kept_histories(rows: list[dict[str, Any]], mode: str) -> list[int]:
    """Return the indices of the cases whose history the archive keeps."""
    if mode == "none" or not rows:
        return []
    if mode == "full":
        return list(range(len(rows)))
    worst: dict[tuple[str, str], int] = {}
    for i, row in enumerate(rows):
        key = (row["record_id"], row["model"])
        if key not in worst or severity(row) > severity(rows[worst[key]]):
            worst[key] = i
    return sorted(worst.values())
