"""Checking an archive's tables: groups of 1-D columns of one length and declared type.

:func:`check_tables` reads shapes and dtypes only (and, for small tables a reader decodes
strictly, their text and number ranges) of a file that
:func:`rockscreen.pipeline.archive.safety.check_tree` passed, and refuses a malformed table
with one line (:class:`~rockscreen.pipeline.errors.ArchiveError`) naming the file, the
table, the column and what is wrong.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Mapping
from typing import Any

import h5py
import numpy as np

from rockscreen.pipeline.archive.safety import decode_codes
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.text import printable

__all__ = ["check_tables"]


def _name(path: Any) -> str:
    return printable(os.fspath(path))


def _column_problem(ds: Any, units: str | None, text: str) -> str | None:
    """Return why a table member is not a column of its declared type, or None."""
    if not isinstance(ds, h5py.Dataset):
        return "is a group where a column (1-D dataset) belongs"
    if ds.ndim != 1:
        return f"has shape {ds.shape}; a table column is 1-D"
    coded = "codes" in ds.attrs and ds.dtype.kind == "u"  # text as codes and a code table
    is_text = h5py.check_string_dtype(ds.dtype) is not None or ds.dtype.kind == "S" or coded
    if units is not None and units != text and (ds.dtype.kind not in "biuf" or coded):
        return "holds text where rockscreen writes numbers"
    if units == text and not (is_text or ds.dtype.kind == "b"):
        return "holds numbers where rockscreen writes text or flags"
    return None


def _text_problem(ds: h5py.Dataset) -> str | None:
    """Return why a text column does not decode as UTF-8, or None."""
    for start in range(0, ds.shape[0], 65536):
        for index, cell in enumerate(ds[start : start + 65536]):
            if isinstance(cell, bytes):
                try:
                    cell.decode("utf-8")
                except UnicodeDecodeError:
                    return f"row {start + index} is not valid UTF-8 text"
    return None


def _range_problem(ds: h5py.Dataset, low: float, high: float) -> str | None:
    """Return why a number column has a value outside [low, high] (NaN passes), or None."""
    values = np.asarray(ds[:], dtype=np.float64)
    bad = np.flatnonzero(~np.isnan(values) & ((values < low) | (values > high)))
    if bad.size:
        return f"row {int(bad[0])} holds {float(values[bad[0]])!r}, outside [{low:g}, {high:g}]"
    return None


def check_tables(
    f: h5py.File,
    path: Any,
    tables: Mapping[str, Mapping[str, str]],
    required: Mapping[str, Iterable[str]],
    *,
    text: str = "",
    decode: bool = False,
    present: Iterable[str] = (),
    ranges: Mapping[str, tuple[float, float]] | None = None,
) -> None:
    """Check the tables of an open archive: groups of 1-D columns of one length and type.

    Nothing but shapes and dtypes is read unless ``decode`` is set, so the check costs
    little on a campaign of any size.

    Parameters
    ----------
    f : h5py.File
        The open file (:func:`check_tree` passed).
    path : str or path-like
        Its path, for messages.
    tables : mapping
        Table (group path) -> column -> declared units. A table absent from the file is
        not checked unless it has required columns. A declared column of units ``text``
        must hold text (or flags); any other declared column numbers.
    required : mapping
        Table -> columns it must have when it is there (``summary``: at least ``id``).
    text : str
        The units spelling of text columns (:data:`rockscreen.pipeline.archive.schema.TEXT`).
    decode : bool
        Also read every text column and refuse one that is not valid UTF-8 (for small
        tables that a reader decodes strictly).
    present : iterable of str
        Tables that must be in the file.
    ranges : mapping, optional
        Column name -> (low, high): with ``decode``, a number of such a column (in any
        table) outside the range, infinities included, is refused; NaN (no value) passes.

    Raises
    ------
    ArchiveError
        One line naming the file, the table, the column and what is wrong: a table that
        is a dataset, a missing required column, a column that is not 1-D, of another
        length than the table's first column, or of the wrong type, invalid UTF-8.
    """
    present = frozenset(present)
    for table, units in tables.items():
        needed = tuple(required.get(table, ()))
        group = f.get(table)
        if group is None:
            if table in present:
                raise ArchiveError(f"{_name(path)}: table /{table} is missing")
            continue
        if not isinstance(group, h5py.Group):
            raise ArchiveError(
                f"{_name(path)}: /{table} is a dataset where a table (a group of columns) belongs"
            )
        missing = [column for column in needed if column not in group]
        if missing:
            raise ArchiveError(
                f"{_name(path)}: table /{table} lacks column(s) {printable(', '.join(missing))}"
            )
        rows = None
        first = ""
        for column in group:
            ds = group.get(column)
            where = f"/{table}/{printable(column)[:60]}"
            problem = _column_problem(ds, units.get(column), text)
            if problem is None and rows is not None and ds.shape[0] != rows:
                problem = f"has {ds.shape[0]} rows where /{table}/{first} has {rows}"
            if problem is None and decode and ds.dtype.kind in "OS":
                problem = _text_problem(ds)
            if problem is None and decode and "codes" in ds.attrs:
                decode_codes(ds, path, f"{table}/{printable(column)[:60]}")  # raises
            if problem is None and decode and ranges and column in ranges:
                problem = _range_problem(ds, *ranges[column])
            if problem:
                raise ArchiveError(f"{_name(path)}: column {where} {problem}")
            if rows is None:
                rows, first = ds.shape[0], printable(column)[:60]
