"""The value types the faces read: a table's cells and rows, an archive's attributes, JSON.

The archive readers (:mod:`rockscreen.pipeline.archive`) return each table as rows of plain
Python scalars (NumPy numbers unwrapped, text decoded) and the root attributes as scalars or
lists of them; the report's functions take them with these types, and the JSON they print
(``inspect --json``, the page's data) is a :data:`JSONValue`.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TypeAlias, TypeVar

__all__ = ["AttrValue", "Attrs", "ColumnValue", "JSONValue", "Row", "RowT"]

#: One cell of an archive table as the readers return it: a number (a missing one NaN), a
#: flag or text; None where a caller's plain row leaves a value out.
ColumnValue: TypeAlias = float | int | str | bool | None
#: One row of an archive table (a tower's summary row, a stripe, an inventory row): column
#: name -> cell.
Row: TypeAlias = Mapping[str, ColumnValue]
#: Rows of one type, kept as given (a function that orders rows returns the caller's own).
RowT = TypeVar("RowT", bound=Row)
#: An HDF5 attribute as plain Python (:func:`~rockscreen.pipeline.report.html.adapters.common.
#: python_value`): a scalar, or the list of an array's (possibly nested) items.
AttrValue: TypeAlias = ColumnValue | list["AttrValue"]
#: An archive's root attributes: name -> value.
Attrs: TypeAlias = Mapping[str, AttrValue]
#: A JSON document: what :func:`json.dumps` writes without a ``default``.
JSONValue: TypeAlias = str | int | float | bool | None | list["JSONValue"] | dict[str, "JSONValue"]
