"""One table column of an assess or scenario archive, stored compactly (HDF5).

Tables are groups of 1-D datasets, one per column, each written by :func:`write_column`
(or, for a table given in parts, created and filled through :class:`TextForm`):
non-empty columns chunked and compressed (gzip + shuffle, :func:`compressed_options`),
text of few distinct values as ``uint8`` codes with its code table (the JSON list of the
values in the ``codes`` attribute), other text as fixed-length UTF-8, a value over
:data:`MAX_FIXED_TEXT_BYTES` as variable-length UTF-8 (version 3 of both kinds; version 2
stored all text as variable-length strings, uncompressed, and is read as before). The
readers (:func:`rockscreen.pipeline.archive.safety.read_column`) give back the same
``str`` values whichever form was chosen. Which table a column belongs to, and its units,
is the layout's (:mod:`rockscreen.pipeline.archive.risk_archive`).
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from typing import Any

import h5py
import numpy as np

from rockscreen.pipeline.text import storable

__all__ = [
    "CHUNK_BYTES",
    "MAX_CODES",
    "MAX_CODE_TABLE_BYTES",
    "MAX_FIXED_TEXT_BYTES",
    "TextForm",
    "compressed_options",
    "stored_kind",
    "text_values",
    "write_column",
]

_STR = h5py.string_dtype("utf-8")
#: Most distinct values of a text column stored as codes (``uint8``) with its code table.
MAX_CODES = 255
#: Largest code table (its JSON text) [B]: an attribute, well under HDF5's 64 kB header.
MAX_CODE_TABLE_BYTES = 16 * 1024
#: Longest value [B, UTF-8] of a text column stored as fixed-length text (longer ones:
#: variable-length, as a long note may be).
MAX_FIXED_TEXT_BYTES = 4096
#: Largest chunk of a compressed table column [B]: several fit HDF5's default chunk cache
#: (1 MiB), so a table written in parts does not recompress a chunk at each part.
CHUNK_BYTES = 256 * 1024


def stored_kind(values: list[Any]) -> str:
    """Return how a column of ``values`` is stored, from its first value that is not None.

    Parameters
    ----------
    values : list
        The column's values (None: not given).

    Returns
    -------
    {"bool", "i8", "f8", "str"}
        Flags, integers, floats, or text (also when every value is None).
    """
    sample = next((v for v in values if v is not None), "")
    if isinstance(sample, (bool, np.bool_)):
        return "bool"
    if isinstance(sample, (int, np.integer)):
        return "i8"
    if isinstance(sample, (float, np.floating)):
        return "f8"
    return "str"


def write_column(group: h5py.Group, name: str, data: Any, units: str) -> h5py.Dataset:
    """Write one table column compactly: numbers and flags compressed, text coded or fixed.

    Every non-empty column is chunked and compressed (gzip + shuffle). Text with few
    distinct values (at most :data:`MAX_CODES`, each repeated on average) is stored as
    ``uint8`` codes with its code table, the JSON list of the values in the ``codes``
    attribute (row value = ``codes[code]``); other text as fixed-length UTF-8 (NUL-padded)
    up to :data:`MAX_FIXED_TEXT_BYTES` a value, longer as variable-length UTF-8. The
    readers (:func:`rockscreen.pipeline.archive.safety.read_column`) give back the same
    ``str`` values whichever form was chosen.

    Parameters
    ----------
    group : h5py.Group
        The table.
    name : str
        The column.
    data : numpy.ndarray or list of str
        Numbers or flags (a numpy array of kind ``b``, ``i``, ``u`` or ``f``), or the text
        values.
    units : str
        The ``units`` attribute.

    Returns
    -------
    h5py.Dataset
    """
    array = np.asarray(data) if not isinstance(data, list) else None
    if array is not None and array.dtype.kind in "biuf":
        ds = group.create_dataset(
            name, data=array, **compressed_options(array.size, array.dtype.itemsize)
        )
        ds.attrs["units"] = units
        return ds
    values = [storable(str(v)) for v in (data if array is None else array.tolist())]
    form = TextForm()
    form.add(values)
    ds = form.create(group, name, len(values), units)
    form.fill(ds, 0, values)
    return ds


class TextForm:
    """How a text column is stored, decided from all its values (seen in one or more parts).

    :meth:`add` takes the values in (all of them, part by part), :meth:`create` makes the
    dataset in the form they allow (codes, fixed-length or variable-length text) and
    :meth:`fill` writes them, a part at a time.
    """

    def __init__(self) -> None:
        self.distinct: set[str] | None = set()  # None: more than MAX_CODES
        self.width = 0  # longest value [B, UTF-8]
        self.codes: list[str] = []

    def add(self, values: Sequence[str]) -> None:
        """Take some of the column's values into account."""
        self.width = max([self.width, *(len(v.encode("utf-8")) for v in values)])
        if self.distinct is not None:
            self.distinct.update(values)
            if len(self.distinct) > MAX_CODES:
                self.distinct = None

    def create(self, group: h5py.Group, name: str, n: int, units: str) -> h5py.Dataset:
        """Create the column's dataset for ``n`` rows in the form its values allow."""
        self.codes = sorted(self.distinct) if self.distinct is not None else []
        table = json.dumps(self.codes, ensure_ascii=False)
        coded = (
            self.distinct is not None
            and 2 * len(self.codes) <= n
            and len(table.encode("utf-8")) <= MAX_CODE_TABLE_BYTES
        )
        if coded:
            self.code_of = {value: code for code, value in enumerate(self.codes)}
            ds = group.create_dataset(name, shape=(n,), dtype=np.uint8, **compressed_options(n, 1))
            ds.attrs["codes"] = table
        elif self.width <= MAX_FIXED_TEXT_BYTES:
            self.codes, width = [], max(self.width, 1)
            dtype = h5py.string_dtype("utf-8", width)
            ds = group.create_dataset(name, shape=(n,), dtype=dtype, **compressed_options(n, width))
        else:
            self.codes = []
            ds = group.create_dataset(name, shape=(n,), dtype=_STR)
        ds.attrs["units"] = units
        return ds

    def fill(self, ds: h5py.Dataset, start: int, values: Sequence[str]) -> None:
        """Write ``values`` at rows ``start``, ... of the column :meth:`create` made."""
        if not values:
            return
        stop = start + len(values)
        if "codes" in ds.attrs:
            ds[start:stop] = np.fromiter(
                (self.code_of[v] for v in values), dtype=np.uint8, count=len(values)
            )
        elif h5py.check_string_dtype(ds.dtype).length is not None:
            fixed = np.asarray([v.encode("utf-8") for v in values], dtype=f"S{ds.dtype.itemsize}")
            ds[start:stop] = fixed.astype(ds.dtype)
        else:
            ds[start:stop] = np.asarray(values, dtype=object)


def text_values(values: Sequence[Any]) -> list[str]:
    """Return a text column's values as storable text (None: ``""``).

    Parameters
    ----------
    values : sequence
        The column's values.

    Returns
    -------
    list of str
        Each value as :func:`rockscreen.pipeline.text.storable` text.
    """
    return [storable("" if v is None else str(v)) for v in values]


def compressed_options(size: int, itemsize: int) -> dict[str, Any]:
    """Return the dataset options of a compressed column (none for an empty one).

    Chunks of up to :data:`CHUNK_BYTES` (the whole column when smaller): a column is read
    whole, and larger chunks compress better than h5py's default guess.

    Parameters
    ----------
    size : int
        The column's rows.
    itemsize : int
        Bytes of one value.

    Returns
    -------
    dict
        Keyword arguments of :meth:`h5py.Group.create_dataset` (empty for no rows).
    """
    if not size:
        return {}
    rows = int(min(size, max(1, CHUNK_BYTES // max(itemsize, 1))))
    return {"compression": "gzip", "shuffle": True, "chunks": (rows,)}
