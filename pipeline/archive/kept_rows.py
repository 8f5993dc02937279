"""A tower result as the assess work file keeps it: its exact text and its rows read back.

A finished tower of ``rockscreen assess`` is kept in the work file ``OUT.part``
(:class:`rockscreen.pipeline.archive.assess_part.AssessJournal`) as tagged JSON text
(:func:`encode_result`, :func:`decode_result`: exact for every float, NaN and infinities
kept, tuples, arrays and non-text keys tagged), so a resumed assessment writes the same
archive as an uninterrupted one. The main process keeps only each tower's summary row and
counts (:func:`light_result`, its tables as :class:`KeptRows`); the final archive's writer
reads the stripes, outcomes and IDA rows back a part at a time through :class:`JournalRows`,
so its memory grows with that part, not with the inventory.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from rockscreen.pipeline.archive import risk_reader

__all__ = [
    "TABLE_KEYS",
    "JournalRows",
    "JournalSummary",
    "SummarySource",
    "KeptRows",
    "RowSource",
    "decode_data",
    "decode_result",
    "encode_result",
    "light_result",
]

#: The tables of a tower result read back from the work file rather than kept in memory.
TABLE_KEYS = ("stripes", "outcomes", "ida")


def _encode(obj: Any) -> Any:
    """Return ``obj`` as JSON-ready data, tagging what JSON would lose (tuples, arrays)."""
    if obj is None or isinstance(obj, (bool, str)):
        return obj
    if isinstance(obj, np.bool_):
        return bool(obj)
    if isinstance(obj, (int, np.integer)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        return float(obj)
    if isinstance(obj, np.ndarray):
        return {"__array__": [_encode(v) for v in obj.tolist()], "dtype": obj.dtype.str}
    if isinstance(obj, tuple):
        return {"__tuple__": [_encode(v) for v in obj]}
    if isinstance(obj, list):
        return [_encode(v) for v in obj]
    if isinstance(obj, dict):
        if all(isinstance(k, str) and not k.startswith("__") for k in obj):
            return {k: _encode(v) for k, v in obj.items()}
        return {"__items__": [[_encode(k), _encode(v)] for k, v in obj.items()]}
    raise TypeError(f"a tower result holds a {type(obj).__name__}, which the work file cannot keep")


def decode_data(obj: Any) -> Any:
    """Return the data of :func:`encode_result`'s parsed JSON, its tags undone.

    Parameters
    ----------
    obj : Any
        Parsed JSON of the work file (the whole result or one of its entries, such as a
        table's rows).

    Returns
    -------
    Any
        The data with its tuples, numpy arrays and non-text dictionary keys restored.
    """
    if isinstance(obj, list):
        return [decode_data(v) for v in obj]
    if not isinstance(obj, dict):
        return obj
    if "__tuple__" in obj:
        return tuple(decode_data(v) for v in obj["__tuple__"])
    if "__array__" in obj:
        return np.asarray(decode_data(obj["__array__"]), dtype=np.dtype(obj["dtype"]))
    if "__items__" in obj:
        return {_decode_key(k): decode_data(v) for k, v in obj["__items__"]}
    return {k: decode_data(v) for k, v in obj.items()}


def _decode_key(key: Any) -> Any:
    value = decode_data(key)
    return tuple(value) if isinstance(value, list) else value


def encode_result(result: Any) -> str:
    """Return a tower result as tagged JSON text (floats exact, NaN and infinities kept).

    Parameters
    ----------
    result : dict
        What :func:`rockscreen.pipeline.risk.assess.run.run_assess` keeps of one tower: its
        stripes, outcomes, IDA rows, summary row and solve count (numbers, text, flags,
        None, tuples, lists, dicts and numpy arrays or scalars).

    Returns
    -------
    str

    Raises
    ------
    TypeError
        For a value of another type (a programming error, named).
    """
    return json.dumps(_encode(result), separators=(",", ":"))


def decode_result(text: str) -> Any:
    """Return the tower result of :func:`encode_result`'s text (numpy scalars as Python ones)."""
    return decode_data(json.loads(text))


def light_result(result: dict[str, Any]) -> dict[str, Any]:
    """Return a tower result without its table rows, each a :class:`KeptRows` reference.

    What the main process keeps of a tower written to the work file: its summary row, solve
    count and CPU time; its stripes, outcomes and IDA rows are read back from the file when
    the archive is written (:class:`JournalRows`), so the memory does not grow with them.
    """
    if "error" in result:
        return result
    light = {k: v for k, v in result.items() if k not in TABLE_KEYS}
    for table in (t for t in TABLE_KEYS if t in result):
        rows = result[table]
        columns = _shared(tuple(rows[0])) if len(rows) else ()
        light[table] = KeptRows(int(result["index"]), len(rows), columns)
    return light


#: One tuple per distinct column list (every tower's table has the same columns).
_COLUMN_LISTS: dict[tuple[str, ...], tuple[str, ...]] = {}


def _shared(columns: tuple[str, ...]) -> tuple[str, ...]:
    return _COLUMN_LISTS.setdefault(columns, columns)


class KeptRows:
    """A tower's rows of one table, kept in the work file (:func:`light_result`).

    Parameters
    ----------
    index : int
        The tower (inventory index).
    n : int
        Its rows in the table.
    columns : tuple of str
        The table's columns (its first row's keys; empty when it has no row). Only the
        names: a row of each table per tower, kept until the archive is written, cost
        about 4 kB a tower.
    """

    def __init__(self, index: int, n: int, columns: tuple[str, ...]) -> None:
        self.index, self.n, self.columns = index, n, columns


class RowSource(Protocol):
    """What :class:`JournalRows` reads its rows from: the assess work file.

    :class:`rockscreen.pipeline.archive.assess_part.AssessJournal` is one; a protocol, so
    this module does not import the journal's.
    """

    def tables(self, indices: Sequence[int], table: str) -> Iterator[list[dict[str, Any]]]:
        """Yield the rows of one table of the given towers, a part at a time, in order."""
        ...


class JournalRows(Sequence[dict[str, Any]]):
    """One table of an assessment whose towers are in the work file, read back in parts.

    Towers are added in the archive's order (:meth:`extend` with a :class:`KeptRows`);
    :meth:`chunks` reads their rows back a part at a time
    (:data:`~rockscreen.pipeline.archive.assess_part.READ_TOWERS` towers), so the archive
    writer (:func:`rockscreen.pipeline.archive.risk_archive.write_risk_archive`) never
    holds the whole table. Indexing and iterating read the file too.

    Parameters
    ----------
    journal : RowSource
        The work file (an :class:`~rockscreen.pipeline.archive.assess_part.AssessJournal`).
    table : {"stripes", "outcomes", "ida"}
        The table.
    """

    def __init__(self, journal: RowSource, table: str) -> None:
        self.journal, self.table = journal, table
        self._towers: list[int] = []
        self._n = 0
        self._columns: tuple[str, ...] = ()
        self._archive: Path | None = None

    def moved_to(self, archive: str | os.PathLike) -> None:
        """Read the rows from the written archive from now on (the work file is removed)."""
        self._archive = Path(archive)

    def extend(self, rows: KeptRows) -> None:  # type: ignore[override]
        """Add a tower's rows (its :class:`KeptRows`) after the others."""
        if not isinstance(rows, KeptRows):
            raise TypeError("JournalRows takes a tower's KeptRows (light_result)")
        if rows.n:
            self._towers.append(rows.index)
            self._n += rows.n
            self._columns = self._columns or rows.columns

    @property
    def columns(self) -> list[str] | None:
        """The table's columns (its first row's keys; None when it has no row)."""
        return list(self._columns) if self._columns else None

    def chunks(self) -> Iterator[list[dict[str, Any]]]:
        """Yield the rows a part (the work file's ``READ_TOWERS`` towers) at a time, in order."""
        if self._archive is not None:
            yield getattr(risk_reader, f"read_{self.table}")(self._archive)
        elif self._towers:
            yield from self.journal.tables(self._towers, self.table)

    def __len__(self) -> int:
        return self._n

    def __iter__(self) -> Iterator[dict[str, Any]]:
        for part in self.chunks():
            yield from part

    def __getitem__(self, index):  # type: ignore[override]
        return list(self)[index]


class SummarySource(Protocol):
    """What :class:`JournalSummary` reads its rows from: the assess work file."""

    def rows(self, indices: Sequence[int]) -> list[dict[str, Any]]:
        """Return the summary rows of the given towers, in that order."""
        ...


class JournalSummary(Sequence[dict[str, Any]]):
    """The summary rows of an assessment, its kept towers' read back from the work file.

    Rows are added in the archive's order: a tower kept in the work file by its index
    (:meth:`append_kept`: its row is not in memory), any other row as it is
    (:meth:`append`). :meth:`chunks` yields the rows a part at a time
    (:data:`~rockscreen.pipeline.archive.assess_part.READ_TOWERS` of them), each kept
    tower's row read back and completed by ``finish`` (what the main process adds to it
    after the tower finished), so the archive writer
    (:func:`rockscreen.pipeline.archive.long_stream.write_summary_in_parts`) never holds
    every row. Iterating and indexing read them too.

    Parameters
    ----------
    journal : SummarySource
        The work file (an :class:`~rockscreen.pipeline.archive.assess_part.AssessJournal`).
    finish : callable
        ``(index, row)``: completes a kept tower's row read back, in place.
    part : int
        Rows per part.
    """

    def __init__(
        self, journal: SummarySource, finish: Callable[[int, dict[str, Any]], None], part: int
    ) -> None:
        self.journal, self.finish, self.part = journal, finish, part
        self._entries: list[int | dict[str, Any]] = []
        self._archive: Path | None = None

    def append(self, row: dict[str, Any]) -> None:  # type: ignore[override]
        """Add a row kept in memory after the others."""
        self._entries.append(row)

    def append_kept(self, index: int) -> None:
        """Add the row of tower ``index`` (inventory index), kept in the work file."""
        self._entries.append(int(index))

    def moved_to(self, archive: str | os.PathLike) -> None:
        """Read the rows from the written archive from now on (the work file is removed)."""
        self._archive = Path(archive)

    def chunks(self) -> Iterator[list[dict[str, Any]]]:
        """Yield the rows a part at a time, in order."""
        if self._archive is not None:
            yield risk_reader.read_summary(self._archive)
            return
        for start in range(0, len(self._entries), self.part):
            entries = self._entries[start : start + self.part]
            kept = [e for e in entries if isinstance(e, int)]
            read = iter(self.journal.rows(kept) if kept else [])
            part = []
            for entry in entries:
                if isinstance(entry, int):
                    row = next(read)
                    self.finish(entry, row)
                    part.append(row)
                else:
                    part.append(entry)
            yield part

    def __len__(self) -> int:
        return len(self._entries)

    def __iter__(self) -> Iterator[dict[str, Any]]:
        for part in self.chunks():
            yield from part

    def __getitem__(self, index):  # type: ignore[override]
        return list(self)[index]
