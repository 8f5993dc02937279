"""Acceleration units: parsing user amplitudes and converting records to m/s^2.

SI inside: every array of acceleration in rockscreen is in m/s^2. Units are
converted once, at the boundary, and never guessed.
"""

from __future__ import annotations

import math
import re

from rockscreen.pipeline.errors import UnitsError
from rockscreen.solver.constants import G

#: Accepted acceleration unit names -> factor to m/s^2.
ACCELERATION_UNITS = {
    "m/s2": 1.0,
    "m/s^2": 1.0,
    "m/s**2": 1.0,
    "cm/s2": 0.01,
    "cm/s^2": 0.01,
    "cm/s**2": 0.01,
    "gal": 0.01,
    "g": G,
}

_QUANTITY = re.compile(
    r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([A-Za-z][A-Za-z/^*0-9]*)?\s*$"
)


def unit_factor(unit: str) -> float:
    """Return the factor that converts an acceleration in ``unit`` to m/s^2.

    Parameters
    ----------
    unit : str
        One of ``g``, ``m/s2`` (also ``m/s^2``, ``m/s**2``), ``cm/s2`` (also ``gal``),
        case-insensitive.

    Returns
    -------
    float
        Multiply a value in ``unit`` by this to get m/s^2.

    Raises
    ------
    UnitsError
        If the unit is not an acceleration unit rockscreen knows.
    """
    key = unit.strip().lower()
    if key not in ACCELERATION_UNITS:
        allowed = "g, m/s2, cm/s2 (gal)"
        raise UnitsError(f"unknown acceleration unit {unit!r}; allowed: {allowed}")
    return ACCELERATION_UNITS[key]


def parse_acceleration(text: str, name: str = "amplitude") -> float:
    """Parse an acceleration with its unit, such as ``0.4g`` or ``3.92m/s2``, to m/s^2.

    Parameters
    ----------
    text : str
        A number immediately followed (optionally after spaces) by a unit.
    name : str
        Name of the parameter, for the error message.

    Returns
    -------
    float
        The acceleration [m/s^2].

    Raises
    ------
    UnitsError
        If the unit is missing (a bare number is refused) or unknown.
    """
    match = _QUANTITY.match(str(text))
    if match is None:
        raise UnitsError(
            f"{name} {text!r} is not a number with a unit; write e.g. 0.4g, 3.92m/s2 or 392cm/s2"
        )
    value, unit = match.groups()
    if not unit:
        raise UnitsError(
            f"{name} {text!r} has no unit; an amplitude without its unit is refused: "
            f"write e.g. {value}g or {value}m/s2"
        )
    try:
        factor = unit_factor(unit)
    except UnitsError as exc:
        raise UnitsError(f"{name} {text!r}: {exc}") from exc
    return float(value) * factor


def float_or_nan(value: object) -> float:
    """Return ``value`` as a float, NaN for ``None`` (an absent quantity, same units).

    Parameters
    ----------
    value : float, int, numpy scalar or None
        A quantity, or None when it is undefined.

    Returns
    -------
    float
        ``float(value)``, or NaN for None.
    """
    return math.nan if value is None else float(value)  # type: ignore[arg-type]
