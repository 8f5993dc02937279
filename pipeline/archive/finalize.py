"""Finalising a campaign archive: the committed rows of the work file, sorted, into OUT.

Towers come in inventory order, cases in record, component, model order; the hidden
ordering columns of the work file are dropped and the history arrays are rewritten in
the sorted order, compressed.
"""

from __future__ import annotations

import datetime as _dt

import h5py
import numpy as np

from rockscreen.pipeline.archive.schema import HISTORY_ARRAYS

__all__ = ["write_final"]

_STR = h5py.string_dtype("utf-8")


def _read_table(group: h5py.Group, n: int | None = None) -> dict[str, np.ndarray]:
    out = {}
    for name in group:
        ds = group[name]
        if not isinstance(ds, h5py.Dataset):
            continue
        data = ds.asstr()[:] if h5py.check_string_dtype(ds.dtype) else ds[:]
        out[name] = data if n is None else data[:n]
    return out


def write_final(src: h5py.File, dst: h5py.File, committed: dict[str, int]) -> None:
    """Copy the committed rows of the work file ``src`` into ``dst``, sorted.

    Parameters
    ----------
    src : h5py.File
        The work file (``OUT.part``), open for reading.
    dst : h5py.File
        The final file, open for writing.
    committed : dict of str to int
        The committed row count of each table and of the history arrays.
    """
    for key, value in src.attrs.items():
        if key not in {"committed", "complete", "static_bytes"}:
            dst.attrs[key] = value
    dst.attrs["created_utc"] = _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")
    src.copy(src["towers"], dst, "towers")
    src.copy(src["records"], dst, "records")
    for name in ("results", "summary", "failures"):
        table = _read_table(src[name], committed[name])
        order = _order(table)
        group = dst.create_group(name)
        _write_sorted(group, src[name], table, order)
    index = _read_table(src["histories/index"], committed["histories/index"])
    order = _order(index)
    hist = dst.create_group("histories")
    hist.attrs["description"] = "time histories of the kept cases; see /histories/index"
    n = committed["histories/data"]
    pieces = [
        slice(int(s), int(s) + int(c)) for s, c in zip(index["start"], index["count"], strict=True)
    ]
    new_start = np.zeros(len(order), dtype=np.int64)
    position = 0
    for k, i in enumerate(order):
        new_start[k] = position
        position += int(index["count"][i])
    index_sorted = {name: column[order] for name, column in index.items()}
    index_sorted["start"] = new_start
    idx_group = hist.create_group("index")
    _write_sorted(idx_group, src["histories/index"], index_sorted, np.arange(len(order)))
    for name, (dtype, units) in HISTORY_ARRAYS.items():
        # One array at a time: the peak memory of finalising is two copies of one history
        # array (~80 MB for 10,000 towers), not all of them at once.
        data = src["histories"][name][:n]
        parts = [data[pieces[i]] for i in order]
        array = np.concatenate(parts) if parts else np.zeros(0, dtype=dtype)
        del data, parts
        ds = hist.create_dataset(
            name,
            data=array.astype(dtype),
            chunks=True if len(array) else None,
            compression="gzip" if len(array) else None,
            shuffle=bool(len(array)),
            maxshape=(None,) if len(array) else None,
        )
        ds.attrs["units"] = units
    dst.attrs["complete"] = True


def _order(table: dict[str, np.ndarray]) -> np.ndarray:
    keys = [table["_case_index"]] if "_case_index" in table else []
    keys.append(table["_tower_index"])
    return np.lexsort(keys)


def _write_sorted(
    group: h5py.Group, source: h5py.Group, table: dict[str, np.ndarray], order: np.ndarray
) -> None:
    for name, column in table.items():
        if name.startswith("_"):
            continue
        sorted_column = column[order]
        src = source[name]
        if h5py.check_string_dtype(src.dtype):
            ds = group.create_dataset(
                name, data=np.asarray(sorted_column, dtype=object), dtype=_STR
            )
        else:
            ds = group.create_dataset(name, data=sorted_column.astype(src.dtype))
        ds.attrs["units"] = src.attrs["units"]
