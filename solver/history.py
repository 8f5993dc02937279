"""The kernel's growable arrays: the impact times and the state history.

:func:`rockscreen.solver.kernel.simulate` cannot know how many impacts or history samples a
record gives; these compiled helpers append to a preallocated array and, when it is full,
return a copy with room for about as many again (``2 * size + 16``). The history has six
rows: t [s], theta [rad], theta_dot [rad/s], u [m], u_dot [m/s] and the
:class:`~rockscreen.solver.codes.Regime` value, one column per recorded state.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from rockscreen.solver.codes import Regime

__all__ = ["append", "grow", "grow_columns", "record_rest", "record_state"]


@njit(cache=True)
def grow(arr, size):
    """Return a copy of the first ``size`` entries with room for more."""
    out = np.empty(2 * size + 16, dtype=arr.dtype)
    out[:size] = arr[:size]
    return out


@njit(cache=True)
def grow_columns(arr, size):
    """Return a copy of the first ``size`` columns with room for more."""
    out = np.empty((arr.shape[0], 2 * size + 16), dtype=arr.dtype)
    out[:, :size] = arr[:, :size]
    return out


@njit(cache=True)
def append(arr, size, value):
    """Append ``value`` after the first ``size`` entries; return ``(array, size + 1)``."""
    if size >= arr.size:
        arr = grow(arr, size)
    arr[size] = value
    return arr, size + 1


@njit(cache=True)
def record_state(hist, n_h, st, on):
    """Append the state to the history (rows t, theta, theta_dot, u, u_dot, regime)."""
    if not on:
        return hist, n_h
    if n_h >= hist.shape[1]:
        hist = grow_columns(hist, n_h)
    hist[0, n_h], hist[1, n_h], hist[2, n_h] = st.t, st.th, st.thd
    hist[3, n_h], hist[4, n_h], hist[5, n_h] = st.u, st.ud, st.reg.value
    return hist, n_h + 1


@njit(cache=True)
def record_rest(hist, n_h, k, j, dt, u, on):
    """Append the rest states at samples k+1 .. j to the history."""
    if not on:
        return hist, n_h
    while n_h + (j - k) >= hist.shape[1]:
        hist = grow_columns(hist, n_h)
    for i in range(k + 1, j + 1):
        hist[0, n_h], hist[1, n_h], hist[2, n_h] = i * dt, 0.0, 0.0
        hist[3, n_h], hist[4, n_h], hist[5, n_h] = u, 0.0, Regime.REST.value
        n_h += 1
    return hist, n_h
