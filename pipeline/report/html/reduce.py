"""Reduce time histories for the page: min/max per bin on a uniform grid, int16, base64.

A history of any length becomes ``bins`` pairs (minimum, maximum) of the samples in
equal time bins, quantised to int16 relative to the largest absolute value. Drawn as
a polyline through min and max of every bin, the envelope and every peak are exact to
1/32767 of the largest value; only the timing inside a bin (``duration / bins`` [s])
is lost. 200 bins cost about 1.1 kB of text per history.
"""

from __future__ import annotations

import base64

import numpy as np

from rockscreen.pipeline.report.html.model import Series

__all__ = ["HISTORY_BINS", "MOTION_BINS", "expand_series", "reduce_series"]

#: Bins of a tower's rotation history (one per model kept).
HISTORY_BINS = 200
#: Bins of an input motion (stored once per record component, shared by towers).
MOTION_BINS = 400
_CODE = 32767


def reduce_series(
    t: np.ndarray,
    values: np.ndarray,
    *,
    label: str,
    unit: str,
    bins: int = HISTORY_BINS,
    ref: str = "",
) -> Series:
    """Reduce one history to ``bins`` min/max pairs on a uniform time grid.

    Parameters
    ----------
    t : numpy.ndarray
        Sample times [s], shape (n,), non-decreasing.
    values : numpy.ndarray
        Values at ``t`` (any units), shape (n,).
    label : str
        Legend text.
    unit : str
        Units of ``values``.
    bins : int
        Number of time bins (>= 1).
    ref : str
        Key of the shared input motion to draw beneath, or ``""``.

    Returns
    -------
    Series
        The reduced history (empty data when ``t`` is empty).
    """
    t = np.asarray(t, dtype=float).ravel()
    values = np.asarray(values, dtype=float).ravel()
    finite = np.isfinite(t) & np.isfinite(values)
    t, values = t[finite], values[finite]
    if t.size == 0:
        return Series(label=label, t0=0.0, dt=1.0, scale=1.0, data="", unit=unit, ref=ref)
    t0, t1 = float(t[0]), float(t[-1])
    width = (t1 - t0) / bins if t1 > t0 else 1.0
    index = np.minimum(((t - t0) / width).astype(np.int64), bins - 1)
    lows = np.full(bins, np.inf)
    highs = np.full(bins, -np.inf)
    np.minimum.at(lows, index, values)
    np.maximum.at(highs, index, values)
    # An empty bin (sparser samples than bins) repeats its left neighbour's last value.
    empty = ~np.isfinite(lows)
    if empty.any():
        filled = np.flatnonzero(~empty)
        source = filled[np.maximum(np.searchsorted(filled, np.arange(bins), side="right") - 1, 0)]
        lows = np.where(empty, highs[source], lows)
        highs = np.where(empty, highs[source], highs)
    scale = float(max(np.max(np.abs(lows)), np.max(np.abs(highs)))) or 1.0
    pairs = np.column_stack([lows, highs]).ravel() / scale * _CODE
    codes = np.clip(np.rint(pairs), -_CODE, _CODE).astype("<i2")
    data = base64.b64encode(codes.tobytes()).decode("ascii")
    return Series(label=label, t0=t0, dt=width, scale=scale, data=data, unit=unit, ref=ref)


def expand_series(series: Series) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Decode a :class:`Series` (the inverse the page's script computes; for tests).

    Returns
    -------
    tuple of numpy.ndarray
        Bin start times [s], bin minima and maxima (the series' units).
    """
    codes = np.frombuffer(base64.b64decode(series.data), dtype="<i2").astype(float)
    pairs = codes.reshape(-1, 2) * series.scale / _CODE
    times = series.t0 + series.dt * np.arange(len(pairs))
    return times, pairs[:, 0], pairs[:, 1]
