"""The tower inventory as the archives store it: one group of columns with their units.

The run archive keeps it as ``/towers`` (:mod:`rockscreen.pipeline.archive.campaign`), the
assess archive as ``/inventory`` (:mod:`rockscreen.pipeline.archive.risk_archive`); both
write it with :func:`write_inventory_group` and read it back through
:func:`with_absent_columns`, so the two hold the same columns, text and units
(:data:`rockscreen.pipeline.archive.schema.TOWER_COLUMNS`).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import Any

import h5py
import numpy as np

from rockscreen.pipeline.archive.schema import TOWER_COLUMNS, units_from_name

__all__ = ["INVENTORY_DESCRIPTION", "with_absent_columns", "write_inventory_group"]

#: The ``description`` attribute of an inventory group.
INVENTORY_DESCRIPTION = "tower inventory; NaN = value absent"
_STR = h5py.string_dtype("utf-8")


def write_inventory_group(parent: h5py.Group, name: str, table: np.ndarray) -> h5py.Group:
    """Write the tower inventory as a group of 1-D columns, each with its ``units``.

    Parameters
    ----------
    parent : h5py.Group
        Where the group is made (the file's root).
    name : str
        The group's name (``"towers"`` in a run archive, ``"inventory"`` in an assess one).
    table : numpy.ndarray
        :func:`rockscreen.stations.inventory_table.inventory_table` of the towers: its
        ``S`` fields are stored as UTF-8 text, its numbers as float64 (NaN: not given).

    Returns
    -------
    h5py.Group
        The new group. Every column's ``units`` attribute is the inventory's
        (:data:`~rockscreen.pipeline.archive.schema.TOWER_COLUMNS`: ``width_m`` ``"m"``,
        ``masonry_strength_mpa`` ``"MPa"``, ``gable_opening_ratio`` ``"1"``, text ``""``);
        a field it does not declare takes the units its name ends with
        (:func:`~rockscreen.pipeline.archive.schema.units_from_name`).
    """
    group = parent.create_group(name)
    group.attrs["description"] = INVENTORY_DESCRIPTION
    for column_name in table.dtype.names or ():
        column = table[column_name]
        if column.dtype.kind == "S":
            data = np.asarray([cell.decode("utf-8") for cell in column], dtype=object)
            ds = group.create_dataset(column_name, data=data, dtype=_STR)
        else:
            ds = group.create_dataset(column_name, data=column)
        spec = TOWER_COLUMNS.get(column_name)
        ds.attrs["units"] = units_from_name(column_name) if spec is None else spec[1]
    return group


def with_absent_columns(rows: Iterable[dict[str, Any]]) -> list[dict[str, Any]]:
    """Return inventory rows with every column, a column not stored taken as not given.

    Parameters
    ----------
    rows : iterable of dict
        Rows as read from an inventory group (one dict per tower).

    Returns
    -------
    list of dict
        Each row with every key of
        :data:`~rockscreen.pipeline.archive.schema.TOWER_COLUMNS` first, in their order
        (NaN for a number, ``""`` for text when the archive lacks the column: one written
        before it was stored), then the row's other columns.
    """
    absent = {
        column: "" if kind == "str" else math.nan for column, (kind, _) in TOWER_COLUMNS.items()
    }
    return [{**absent, **row} for row in rows]
