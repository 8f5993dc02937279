"""The records of an assess archive's sets: ``/records`` and ``/set_records``, written and read.

Every record of the sets once, before its factor: ``/records/index`` (one row per record)
and its samples in the concatenated ``/records/{x,y,z}`` [m/s2] (version 3 on); the sets as
references in ``/set_records``. Version 2 kept one group per record
(``/records/<id>/{x,y,z}``), read by :func:`record_groups`. The layout is described in
:mod:`rockscreen.pipeline.archive.risk_archive`, whose writer calls :func:`write_records`;
:func:`rockscreen.pipeline.archive.risk_reader.read_records` reads them back.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Mapping, Sequence
from typing import Any

import h5py
import numpy as np

from rockscreen.pipeline.archive.column_codec import write_column
from rockscreen.pipeline.archive.reader import python_scalar
from rockscreen.pipeline.archive.risk_schema import assess_tables, table_units
from rockscreen.pipeline.archive.safety import read_table
from rockscreen.pipeline.archive.schema import ACCELERATION, DIMENSIONLESS, TEXT
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.text import printable

__all__ = [
    "RECORD_COMPONENTS",
    "concatenated_records",
    "record_groups",
    "record_samples",
    "sample_dtype",
    "write_records",
]

#: The components of a stored record: first and second horizontal, vertical.
RECORD_COMPONENTS = ("x", "y", "z")


def sample_dtype(records: Mapping[str, Mapping[str, Any]]) -> type:
    """Return the narrowest float type that holds every sample of ``records`` exactly.

    Parameters
    ----------
    records : mapping
        Record id -> ``{"x", "y", "z"}`` accelerations [m/s²] (None: component absent).

    Returns
    -------
    type
        :class:`numpy.float32` when every sample is a float32 exactly (the embedded pools'
        records are: they are rounded so when generated), else :class:`numpy.float64`.
        Read back as float64 either way, the samples are the ones the towers were computed
        with.
    """
    for record in records.values():
        for component in RECORD_COMPONENTS:
            acc = record.get(component)
            if acc is None:
                continue
            acc = np.asarray(acc, dtype=np.float64)
            if not np.array_equal(acc.astype(np.float32).astype(np.float64), acc):
                return np.float64
    return np.float32


def _write_columns(group: h5py.Group, columns: Mapping[str, np.ndarray]) -> None:
    """Write a table of numpy columns (:func:`write_column`), with units and column order."""
    table = group.name.lstrip("/")
    group.attrs["columns"] = json.dumps(list(columns))
    for name, array in columns.items():
        if array.dtype.kind in "OU":
            write_column(group, name, [str(v) for v in array], TEXT)
        else:
            units = table_units(assess_tables(), table, name)
            if units is None:  # every column here is declared (risk_schema's assess tables)
                raise ArchiveError(f"column {table}/{name} of the assess archive has no units")
            write_column(group, name, array, units or DIMENSIONLESS)


def write_records(
    f: h5py.File,
    records: dict[str, dict[str, Any]],
    set_records: Sequence[tuple[int, str, float]],
) -> None:
    """Write ``/records`` (each record once: index and concatenated samples) and ``/set_records``.

    Raises
    ------
    ArchiveError
        For a record without an ``x`` component, an empty component, or a set referring to
        a record not in ``records``.
    """
    ids = list(records)
    row_of = {record_id: row for row, record_id in enumerate(ids)}
    top = f.create_group("records")
    top.attrs["description"] = (
        "every record of the sets once, before its factor (/set_records/scale_factor): "
        "/records/index row i, samples /records/<c>[<c>_start:<c>_start + <c>_count]"
    )
    dtype = sample_dtype(records)
    index: dict[str, Any] = {
        "id": np.asarray(ids, dtype=object),
        "name": np.asarray([str(records[r].get("name", r)) for r in ids], dtype=object),
        "source": np.asarray([str(records[r].get("source", "")) for r in ids], dtype=object),
        "dt_s": np.asarray([float(records[r]["dt_s"]) for r in ids], dtype=np.float64),
    }
    for component in RECORD_COMPONENTS:
        parts = [records[r].get(component) for r in ids]
        for record_id, acc in zip(ids, parts, strict=True):
            if (acc is None and component == "x") or (acc is not None and np.size(acc) == 0):
                raise ArchiveError(
                    f"record {record_id!r} cannot be stored: its {component} component is "
                    f"{'absent' if acc is None else 'empty'} (x is required, no component empty)"
                )
        counts = np.array([0 if acc is None else np.size(acc) for acc in parts], dtype=np.int64)
        starts = np.cumsum(counts) - counts
        index[f"{component}_start"] = starts
        index[f"{component}_count"] = counts
        # one record at a time into the dataset: no concatenated copy of every sample
        total = int(counts.sum())
        options = {"compression": "gzip", "shuffle": True, "chunks": True} if total else {}
        ds = top.create_dataset(component, shape=(total,), dtype=dtype, **options)
        for start, count, acc in zip(starts, counts, parts, strict=True):
            if acc is not None:
                ds[start : start + count] = np.asarray(acc, dtype=dtype).ravel()
        ds.attrs["units"] = ACCELERATION
    _write_columns(top.create_group("index"), index)
    missing = sorted({record_id for _, record_id, _ in set_records} - set(row_of))
    if missing:
        raise ArchiveError(f"a set refers to record {missing[0]!r}, which is not stored")
    references = {
        "set": np.asarray([s for s, _, _ in set_records], dtype=np.int64),
        "record": np.asarray([row_of[r] for _, r, _ in set_records], dtype=np.int64),
        "scale_factor": np.asarray([x for _, _, x in set_records], dtype=np.float64),
    }
    _write_columns(f.create_group("set_records"), references)


def record_samples(ds: Any, where: str) -> Any:
    """Return a stored component's samples as float64, checked (1-D floats in m/s2)."""
    if not isinstance(ds, h5py.Dataset) or ds.ndim != 1 or ds.dtype.kind != "f":
        raise ArchiveError(f"{where} is not a 1-D float array")
    if python_scalar(ds.attrs.get("units", "")) != ACCELERATION:
        raise ArchiveError(f"{where} is not in {ACCELERATION}")
    return ds[:].astype("f8")


def concatenated_records(f: h5py.File, top: h5py.Group, path: Any) -> dict[str, dict[str, Any]]:
    """Read the version-3 ``/records``: the index table and the concatenated samples."""
    name = printable(os.fspath(path))
    index = read_table(top["index"], path)
    samples = {c: record_samples(top.get(c), f"{name}: /records/{c}") for c in RECORD_COMPONENTS}
    out: dict[str, dict[str, Any]] = {}
    for row, record_id in enumerate(index["id"]):
        record_id = str(record_id)
        dt = float(index["dt_s"][row])
        if not (math.isfinite(dt) and dt > 0):
            raise ArchiveError(f"{name}: /records/index row {row} has no positive dt_s")
        entry: dict[str, Any] = {
            "dt_s": dt,
            "name": str(index["name"][row]),
            "source": str(index["source"][row]),
        }
        for component in RECORD_COMPONENTS:
            start = int(index[f"{component}_start"][row])
            count = int(index[f"{component}_count"][row])
            if count == 0 and component != "x":
                entry[component] = None
                continue
            if count <= 0 or start < 0 or start + count > samples[component].size:
                raise ArchiveError(
                    f"{name}: /records/index row {row} points outside /records/{component}"
                )
            entry[component] = samples[component][start : start + count]
        out[record_id] = entry
    return out


def record_groups(top: h5py.Group, path: Any) -> dict[str, dict[str, Any]]:
    """Read the version-2 ``/records``: one group per record (the older layout)."""
    out: dict[str, dict[str, Any]] = {}
    for record_id, group in top.items():
        where = f"{str(path)!r}: /records/{record_id}"
        if not isinstance(group, h5py.Group):
            raise ArchiveError(f"{where} is not a group")
        dt = python_scalar(group.attrs.get("dt_s", math.nan))
        if not (isinstance(dt, float) and math.isfinite(dt) and dt > 0):
            raise ArchiveError(f"{where} has no positive dt_s")
        entry: dict[str, Any] = {
            "dt_s": dt,
            "name": str(python_scalar(group.attrs.get("name", record_id))),
            "source": str(python_scalar(group.attrs.get("source", ""))),
        }
        for component in RECORD_COMPONENTS:
            ds = group.get(component)
            entry[component] = None if ds is None else record_samples(ds, f"{where}/{component}")
        out[record_id] = entry
    return out
