"""The tower inventory as a numpy structured array (what the HDF5 archive stores).

The table's columns are derived from the one column registry,
:data:`rockscreen.stations.inventory_columns.COLUMNS`: every inventory column a
:class:`~rockscreen.stations.tower.Tower` carries is stored, so a column added to the
registry (and to ``Tower``) reaches the archive with no edit here.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from rockscreen.stations.inventory_columns import COLUMNS, TEXT_COLUMNS

if TYPE_CHECKING:
    from rockscreen.stations.tower import Tower

__all__ = ["TABLE_COLUMNS", "TABLE_RESOLVED", "inventory_table", "table_column_name"]

#: Table columns that hold a resolved value (the ``Tower`` property read instead of the
#: inventory's cell): ``depth_m`` is the plan depth (``width_m`` for a square plan),
#: ``belfry_depth_m`` the belfry's (``belfry_width_m`` when absent).
TABLE_RESOLVED: dict[str, str] = {
    "depth_m": "plan_depth_m",
    "belfry_depth_m": "belfry_plan_depth_m",
}


def table_column_name(column: str) -> str:
    """Return the table name of an inventory column: the unit appended when it is not in it.

    Parameters
    ----------
    column : str
        A column of :data:`rockscreen.stations.inventory_columns.COLUMNS`.

    Returns
    -------
    str
        ``lat`` -> ``lat_deg``, ``lon`` -> ``lon_deg``; a text column, a dimensionless
        number (unit ``"-"``) or a name that already ends with its unit (``width_m``,
        ``masonry_strength_mpa``, ``nominal_life_y``) is kept.
    """
    unit = COLUMNS[column][0]
    if column in TEXT_COLUMNS or unit == "-":
        return column
    suffix = "_" + unit.lower()
    return column if column.endswith(suffix) else column + suffix


#: Columns of :func:`inventory_table`, in the registry's order: table column ->
#: (inventory column, unit as the registry spells it: ``"-"`` dimensionless or text).
TABLE_COLUMNS: dict[str, tuple[str, str]] = {
    table_column_name(column): (column, unit) for column, (unit, _) in COLUMNS.items()
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
        Shape ``(len(towers),)``, one field per inventory column
        (:data:`TABLE_COLUMNS`, in the order of
        :data:`rockscreen.stations.inventory_columns.COLUMNS`). Text fields (``id``,
        ``name``, ``comune``, ``provincia``, ``masonry_type``, ``knowledge_level``,
        ``gable_axis``, ``station``, ``use_class``, ``soil_class``, ``topography``) are
        UTF-8 encoded fixed-length bytes (``S`` dtype, which h5py stores directly; decode
        with ``.decode()``), empty when absent; numeric fields are float64 with the unit in
        the name (``lat_deg``, ``width_m``, ``masonry_strength_mpa``, ...; ``eta``,
        ``mu_s``, ``mu_k`` and ``gable_opening_ratio`` are dimensionless) and NaN where a
        value is absent. ``depth_m`` holds the resolved plan depth (``width_m`` for a
        square plan), and ``belfry_depth_m`` the resolved belfry depth
        (``belfry_width_m`` when absent): :data:`TABLE_RESOLVED`.
    """
    text = {
        name: [(getattr(t, column) or "").encode("utf-8") for t in towers]
        for name, (column, _) in TABLE_COLUMNS.items()
        if column in TEXT_COLUMNS
    }
    dtype = [
        (name, f"S{max([1, *map(len, text[name])])}" if name in text else "f8")
        for name in TABLE_COLUMNS
    ]
    table = np.zeros(len(towers), dtype=dtype)
    for name, (column, _) in TABLE_COLUMNS.items():
        if name in text:
            table[name] = text[name]
        else:
            attribute = TABLE_RESOLVED.get(column, column)
            table[name] = [_number(getattr(t, attribute)) for t in towers]
    return table


def _number(value: float | None) -> float:
    return math.nan if value is None else float(value)
