"""A table of rows kept as column arrays: the assessment's large tables in little memory.

``/outcomes`` holds one row per tower, return period, record, component and model (about
200 per tower); as Python dicts a row costs about 650 bytes, so 10,000 towers would hold
1.3 GB in the main process until the archive is written. :class:`RowTable` keeps each
added block of rows as one numpy array per column (8 bytes a number, a shared pointer a
text) and still reads as a sequence of dict rows for the code that iterates it;
:meth:`RowTable.column` gives a whole column to the archive writer at once
(:func:`rockscreen.pipeline.archive.risk_archive.write_risk_archive`).
"""

from __future__ import annotations

from collections.abc import Iterable, Iterator, Mapping, Sequence
from typing import Any

import numpy as np

__all__ = ["RowTable"]


def _array(values: list[Any]) -> np.ndarray:
    """One column of a block: bool, int64 or float64 when every value is one, else objects."""
    kinds = {type(v) for v in values}
    if kinds <= {bool, np.bool_}:
        return np.asarray(values, dtype=bool)
    if kinds <= {int, np.int64, np.int32}:
        return np.asarray(values, dtype=np.int64)
    if kinds <= {float, np.float64, np.float32}:
        return np.asarray(values, dtype=np.float64)
    out = np.empty(len(values), dtype=object)
    out[:] = values
    return out


def _python(value: Any) -> Any:
    """Return a numpy scalar as its Python value, an object column's value as it is."""
    return value.item() if isinstance(value, np.generic) else value


class RowTable(Sequence[dict[str, Any]]):
    """Rows with the same keys, stored by column (module docstring).

    Parameters
    ----------
    rows : iterable of mapping, optional
        First rows.
    """

    def __init__(self, rows: Iterable[Mapping[str, Any]] = ()) -> None:
        self._keys: list[str] = []
        self._blocks: list[dict[str, np.ndarray]] = []
        self._starts: list[int] = []
        self._n = 0
        self.extend(rows)

    def extend(self, rows: Iterable[Mapping[str, Any]]) -> None:
        """Append rows (a list of dicts or another :class:`RowTable`)."""
        if isinstance(rows, RowTable):
            for block in rows._blocks:
                self._add(block, len(next(iter(block.values()))) if block else 0)
            if not self._keys:
                self._keys = list(rows._keys)
            return
        rows = list(rows)
        if not rows:
            return
        if not self._keys:
            self._keys = list(rows[0])
        keys = self._keys + [k for k in rows[0] if k not in self._keys]
        self._keys = keys
        self._add({k: _array([row.get(k) for row in rows]) for k in keys}, len(rows))

    def _add(self, block: dict[str, np.ndarray], n: int) -> None:
        if n == 0:
            return
        self._blocks.append(block)
        self._starts.append(self._n)
        self._n += n

    def __len__(self) -> int:
        return self._n

    def __eq__(self, other: object) -> bool:
        """Whether ``other`` holds the same rows in the same order (a table or a list)."""
        if not isinstance(other, Sequence) or isinstance(other, str):
            return NotImplemented
        return len(self) == len(other) and list(self) == list(other)

    __hash__ = None  # type: ignore[assignment]  # mutable

    def _row(self, i: int) -> dict[str, Any]:
        b = int(np.searchsorted(self._starts, i, side="right")) - 1
        j = i - self._starts[b]
        block = self._blocks[b]
        return {k: (_python(block[k][j]) if k in block else None) for k in self._keys}

    def __getitem__(self, index):  # type: ignore[override]
        if isinstance(index, slice):
            return [self._row(i) for i in range(*index.indices(self._n))]
        i = index + self._n if index < 0 else index
        if not 0 <= i < self._n:
            raise IndexError("row index out of range")
        return self._row(i)

    def __iter__(self) -> Iterator[dict[str, Any]]:
        for block in self._blocks:
            n = len(next(iter(block.values())))
            columns = {k: (block[k].tolist() if k in block else [None] * n) for k in self._keys}
            for j in range(n):
                yield {k: columns[k][j] for k in self._keys}

    def column(self, key: str) -> list[Any]:
        """Return one column as a list of Python values (None where a block lacks it)."""
        out: list[Any] = []
        for block in self._blocks:
            if key in block:
                out.extend(block[key].tolist())
            else:
                out.extend([None] * len(next(iter(block.values()))))
        return out

    def column_array(self, key: str) -> np.ndarray:
        """Return one column as one numpy array (objects where blocks differ or lack it)."""
        parts = [
            block[key] if key in block else np.full(len(next(iter(block.values()))), None)
            for block in self._blocks
        ]
        if not parts:
            return np.empty(0, dtype=object)
        kinds = {p.dtype.kind for p in parts}
        if len(kinds) == 1 or kinds <= {"i", "f"}:
            return np.concatenate(parts)
        return np.concatenate([p.astype(object) for p in parts])

    @property
    def nbytes(self) -> int:
        """Bytes held by the column arrays (object columns: their pointers) [B]."""
        return sum(a.nbytes for block in self._blocks for a in block.values())
