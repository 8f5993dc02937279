"""Checks of user input at the solver's boundary; each names the parameter, value and range."""

from __future__ import annotations

import math

import numpy as np

from rockscreen.solver.constants import G
from rockscreen.solver.errors import ParameterError


def check_positive(name: str, value: float, unit: str = "") -> None:
    """Raise :class:`ParameterError` unless ``value`` is a finite number > 0."""
    unit = f" {unit}" if unit else ""
    try:
        ok = math.isfinite(value) and value > 0.0
    except TypeError:
        ok = False
    if not ok:
        raise ParameterError(f"{name}={value!r}{unit} must be a finite number > 0")


def check_alpha(alpha: float) -> None:
    """Raise unless the slenderness ``alpha`` [rad] is finite and in (0, pi/2)."""
    if not (math.isfinite(alpha) and 0.0 < alpha < 0.5 * math.pi):
        raise ParameterError(f"alpha={alpha!r} rad must be in (0, pi/2)")


def check_eta(eta: float) -> None:
    """Raise unless the angular-velocity restitution ``eta`` lies in (0, 1]."""
    try:
        ok = math.isfinite(eta) and 0.0 < eta <= 1.0
    except TypeError:
        ok = False
    if not ok:
        raise ParameterError(
            f"eta={eta!r} must be in (0, 1] (angular-velocity ratio theta_dot+/theta_dot-)"
        )


def check_friction(mu_s: float, mu_k: float) -> None:
    """Raise unless ``0 <= mu_k <= mu_s`` and both are finite."""
    for name, value in (("mu_s", mu_s), ("mu_k", mu_k)):
        try:
            ok = math.isfinite(value) and value >= 0.0
        except TypeError:
            ok = False
        if not ok:
            raise ParameterError(f"{name}={value!r} must be a finite number >= 0")
    if mu_k > mu_s:
        raise ParameterError(f"mu_k={mu_k!r} must not exceed mu_s={mu_s!r}")


def as_record(name: str, acc) -> np.ndarray:
    """Return ``acc`` as a contiguous 1-D float64 array of finite values [m/s^2]."""
    try:
        arr = np.ascontiguousarray(acc, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ParameterError(f"{name} must be a 1-D array of numbers [m/s^2]") from exc
    if arr.ndim != 1 or arr.size == 0:
        raise ParameterError(f"{name} must be a non-empty 1-D array, got shape {arr.shape}")
    if not np.isfinite(arr).all():
        bad = int(np.flatnonzero(~np.isfinite(arr))[0])
        raise ParameterError(
            f"{name}[{bad}]={float(arr[bad])!r}: a record must hold finite values only "
            "(NaN/inf found)"
        )
    return arr


def as_vertical(acc_v, n: int) -> np.ndarray:
    """Return the vertical record [m/s^2] (empty array when absent) checked to hold ``n`` samples.

    Whether it stays above -g is :func:`check_vertical_min`'s test.
    """
    if acc_v is None:
        return np.empty(0, dtype=np.float64)
    arr = as_record("acc_v", acc_v)
    if arr.size != n:
        raise ParameterError(f"acc_v has {arr.size} samples but acc has {n}; they must match")
    return arr


def check_vertical_min(acc_v_min: float, scale: float = 1.0) -> None:
    """Raise unless the smallest vertical acceleration [m/s^2] times ``scale`` [-] exceeds -g."""
    low = scale * acc_v_min
    if not low > -G:
        scaled = "" if scale == 1.0 else f" (scaled by {scale!r})"
        raise ParameterError(
            f"acc_v{scaled} reaches {low!r} m/s^2: the vertical ground acceleration must stay "
            f"above -g = {-G} m/s^2 (the base would leave the block)"
        )


def check_dt(dt: float) -> float:
    """Return ``dt`` [s] as float after checking it is finite and > 0."""
    check_positive("dt", dt, "s")
    return float(dt)
