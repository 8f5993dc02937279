"""Input checks of the code checks: every message names the parameter and its allowed range."""

from __future__ import annotations

import math

from rockscreen.pipeline.errors import RiskError

__all__ = ["check_number"]


def check_number(
    name: str,
    value: float,
    *,
    low: float = -math.inf,
    high: float = math.inf,
    low_open: bool = False,
    high_open: bool = False,
    unit: str = "",
) -> float:
    """Return ``value`` as a float if it is finite and inside the range, else raise.

    Parameters
    ----------
    name : str
        The parameter's name, written in the message.
    value : float
        The value to check.
    low, high : float
        Range ends.
    low_open, high_open : bool
        Whether the ends are excluded.
    unit : str
        Unit written after the range (``"m"``, ``"kg"``...).

    Returns
    -------
    float

    Raises
    ------
    RiskError
        For a non-number, a non-finite number or one outside the range.
    """
    left = "(" if low_open else "["
    right = ")" if high_open else "]"
    allowed = f"{left}{low:g}, {high:g}{right}" + (f" {unit}" if unit else "")
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise RiskError(f"{name}={value!r} is not a number; allowed: {allowed}") from None
    too_low = number <= low if low_open else number < low
    too_high = number >= high if high_open else number > high
    if not math.isfinite(number) or too_low or too_high:
        raise RiskError(f"{name}={value!r} is outside the allowed range {allowed}")
    return number
