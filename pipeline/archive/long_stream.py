"""The assess summary given in parts, written as its slim ``/summary`` and long tables.

An assessment's wide summary rows (one per tower) need not all be in memory to be stored:
given as an object whose ``chunks()`` yields them a part at a time, in order (the towers'
rows read back from the work file, :class:`rockscreen.pipeline.archive.kept_rows.
JournalSummary`), :func:`write_summary_in_parts` decides where each column goes from every
row (:func:`~rockscreen.pipeline.archive.long_tables.plan_split`, one pass), then writes the
slim ``/summary`` and the ``/fits``, ``/checks``, ``/messages`` tables part by part (two
passes each: the text columns' forms from all their values, then the rows) and ``/pivot``.
The datasets are those :func:`~rockscreen.pipeline.archive.long_tables.split_summary` and
:func:`~rockscreen.pipeline.archive.long_tables.write_long_tables` write from the same rows
in one piece (same dtypes, shapes, values and attributes).
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterator, Sequence
from typing import Any, Protocol

import h5py
import numpy as np

from rockscreen.pipeline.archive.column_codec import TextForm, compressed_options, text_values
from rockscreen.pipeline.archive.long_schema import LONG_TABLES
from rockscreen.pipeline.archive.long_tables import (
    CheckColumns,
    LongSummary,
    plan_split,
    split_part,
    write_long_tables,
)
from rockscreen.pipeline.archive.schema import TEXT
from rockscreen.pipeline.text import storable

__all__ = ["RowParts", "write_summary_in_parts"]

#: The long tables written part by part (``/pivot`` is one row per column: written whole).
_PART_TABLES = ("fits", "checks", "messages")


class RowParts(Protocol):
    """Rows given a part at a time (a :class:`~.kept_rows.JournalSummary`)."""

    def chunks(self) -> Iterator[list[dict[str, Any]]]:
        """Yield the rows a part at a time, in order."""
        ...


class _Slim:
    """The slim ``/summary`` rows of every part, as a table writer reads a table in parts."""

    def __init__(self, parts: Callable[[], Iterator[LongSummary]], columns: list[str]) -> None:
        self._parts, self.columns = parts, columns

    def chunks(self) -> Iterator[list[dict[str, Any]]]:
        for split in self._parts():
            yield split.summary


def _text(values: Sequence[Any]) -> list[str]:
    """Return a long table's text values as :func:`write_column` stores a list of text."""
    return [storable(str(v)) for v in text_values(values)]


def _write_parts(f: h5py.File, parts: Callable[[], Iterator[LongSummary]]) -> None:
    """Write ``/fits``, ``/checks`` and ``/messages`` from the parts' rows (two passes)."""
    counts = dict.fromkeys(_PART_TABLES, 0)
    forms = {
        t: {name: TextForm() for name, units in LONG_TABLES[t].items() if units == TEXT}
        for t in _PART_TABLES
    }
    for split in parts():
        for table in _PART_TABLES:
            columns = split.tables[table]
            counts[table] += len(columns["tower"])
            for name, form in forms[table].items():
                form.add(_text(columns[name]))
    datasets: dict[str, dict[str, h5py.Dataset]] = {}
    for table in _PART_TABLES:
        units = LONG_TABLES[table]
        if not counts[table]:  # as the one-piece writer stores an empty table
            write_long_tables(f, {table: {name: [] for name in units}})
            continue
        group = f.create_group(table)
        group.attrs["columns"] = json.dumps(list(units))
        datasets[table] = {}
        n = counts[table]
        for name, unit in units.items():
            if unit == TEXT:
                datasets[table][name] = forms[table][name].create(group, name, n, TEXT)
                continue
            dtype = np.dtype(np.int64 if name == "tower" else np.float64)
            ds = group.create_dataset(
                name, shape=(n,), dtype=dtype, **compressed_options(n, dtype.itemsize)
            )
            ds.attrs["units"] = unit
            datasets[table][name] = ds
    starts = dict.fromkeys(datasets, 0)
    for split in parts():
        for table, columns in datasets.items():
            rows = split.tables[table]
            start, k = starts[table], len(rows["tower"])
            for name, ds in columns.items():
                if name in forms[table]:
                    forms[table][name].fill(ds, start, _text(rows[name]))
                elif k:
                    ds[start : start + k] = np.asarray(rows[name], dtype=ds.dtype)
            starts[table] = start + k


def write_summary_in_parts(
    f: h5py.File,
    rows: RowParts,
    part_models: Sequence[str],
    checks: Sequence[CheckColumns],
    write_table: Callable[[h5py.Group, Any, list[str]], None],
) -> None:
    """Write a wide summary given in parts as ``/summary`` and the long tables.

    Parameters
    ----------
    f : h5py.File
        The archive being written.
    rows : RowParts
        The wide rows, a part at a time (``chunks()``, read again for each pass).
    part_models : sequence of str
        The part models' names (their fits move to ``/fits``).
    checks : sequence of CheckColumns
        The checks' columns, in the verdict's order.
    write_table : callable
        ``(group, table, columns)``: writes a table given in parts (its ``chunks()``) in
        the form of a table given whole: the slim ``/summary``.
    """
    plan = plan_split(rows.chunks(), part_models, checks)

    def parts() -> Iterator[LongSummary]:
        offset = 0
        for part in rows.chunks():
            yield split_part(part, plan, checks, offset)
            offset += len(part)

    write_table(f.create_group("summary"), _Slim(parts, plan.slim), plan.slim)
    _write_parts(f, parts)
    write_long_tables(f, {"pivot": plan.pivot})
