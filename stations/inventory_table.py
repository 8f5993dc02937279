"""The tower inventory as a numpy structured array (what the HDF5 archive stores)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from rockscreen.stations.tower import Tower

__all__ = ["inventory_table"]

#: Numeric columns of :func:`inventory_table`: table column -> Tower attribute.
_TABLE_NUMBERS: dict[str, str] = {
    "lat_deg": "lat",
    "lon_deg": "lon",
    "azimuth_deg": "azimuth_deg",
    "width_m": "width_m",
    "height_m": "height_m",
    "depth_m": "plan_depth_m",
    "eta": "eta",
    "tower_mass_kg": "tower_mass_kg",
    "building_mass_kg": "building_mass_kg",
    "mu_s": "mu_s",
    "mu_k": "mu_k",
    "building_height_m": "building_height_m",
    "base_height_m": "base_height_m",
    "building_period_s": "building_period_s",
    "belfry_height_m": "belfry_height_m",
    "belfry_width_m": "belfry_width_m",
    "belfry_depth_m": "belfry_plan_depth_m",
    "belfry_mass_kg": "belfry_mass_kg",
    "bells_mass_kg": "bells_mass_kg",
    "bells_height_m": "bells_height_m",
    "shaft_period_s": "shaft_period_s",
    "nominal_life_y": "nominal_life_y",
}


def inventory_table(towers: Sequence[Tower]) -> np.ndarray:
    """Return the towers as a numpy structured array for the archive.

    Parameters
    ----------
    towers : sequence of Tower
        The towers.

    Returns
    -------
    numpy.ndarray
        Shape ``(len(towers),)``. Text fields ``id``, ``name``, ``station``,
        ``use_class``, ``soil_class``, ``topography`` are
        UTF-8 encoded fixed-length bytes (``S`` dtype, which h5py stores directly;
        decode with ``.decode()``); numeric fields are float64 with the unit in the
        name (``lat_deg``, ``width_m``, ...) and NaN where a value is absent.
        ``depth_m`` holds the resolved plan depth (``width_m`` for a square plan), and
        ``belfry_depth_m`` the resolved belfry depth (``belfry_width_m`` when absent).
    """
    text = {
        name: [(getattr(t, name) or "").encode("utf-8") for t in towers]
        for name in ("id", "name", "station", "use_class", "soil_class", "topography")
    }
    dtype = [(name, f"S{max([1, *map(len, cells)])}") for name, cells in text.items()]
    dtype += [(name, "f8") for name in _TABLE_NUMBERS]
    table = np.zeros(len(towers), dtype=dtype)
    for name, cells in text.items():
        table[name] = cells
    for name, attribute in _TABLE_NUMBERS.items():
        table[name] = [_number(getattr(t, attribute)) for t in towers]
    return table


def _number(value: float | None) -> float:
    return math.nan if value is None else float(value)
