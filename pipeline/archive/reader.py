"""Public readers of the campaign archive: every one checks format, version and tree first.

Each reader opens the archive with :func:`rockscreen.pipeline.archive.safety.open_campaign` (format
and ``format_version`` checked, external links, soft links, virtual or external storage,
references and oversized datasets refused before any data is read), checks every table
column's dtype and length before reading it, and raises
:class:`~rockscreen.pipeline.errors.ArchiveError` (one line) for anything malformed. Archives of
format version 1 are read too: their summary columns ``lat``/``lon`` come back as
``lat_deg``/``lon_deg``.
"""

from __future__ import annotations

import math
import os
from typing import Any

import h5py
import numpy as np

from rockscreen.pipeline.archive.inventory_group import with_absent_columns
from rockscreen.pipeline.archive.safety import open_campaign, read_column, read_table, reading
from rockscreen.pipeline.archive.schema import (
    FAILURE_COLUMNS,
    HISTORY_ARRAYS,
    HISTORY_INDEX_COLUMNS,
    RESULT_COLUMNS,
    SUMMARY_COLUMNS,
    SUMMARY_RENAMED_V1,
    SUMMARY_REQUIRED,
    TOWER_COLUMNS,
)
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.text import printable
from rockscreen.pipeline.vocabulary import channel_id
from rockscreen.solver.docstrings import fill_doc

__all__ = [
    "archive_tree",
    "read_failures",
    "read_histories",
    "read_metadata",
    "read_results",
    "read_stations",
    "read_summary",
    "read_summary_table",
    "read_towers",
]  # tree_of takes an open file: public, but not one of the path readers re-exported


def python_scalar(value: Any) -> Any:
    """Return a NumPy bool, integer or float as the Python one; anything else unchanged."""
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.floating):
        return float(value)
    return value


def _python(value: Any) -> Any:
    value = python_scalar(value)
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    if isinstance(value, np.ndarray):
        return [_python(item) for item in value.ravel()[:1000]]
    return value


#: Docstring blocks the public readers share (:func:`rockscreen.solver.docstrings.fill_doc`).
_DOCS = {
    "archive_error": """
ArchiveError
    If the file is missing, not a rockscreen archive, of an unknown format version,
    or malformed.
""",
}

_REQUIRED: dict[str, tuple[str, ...]] = {
    "summary": SUMMARY_REQUIRED,
    "results": tuple(RESULT_COLUMNS),
    "failures": tuple(FAILURE_COLUMNS),
    "histories/index": tuple(HISTORY_INDEX_COLUMNS),
    "towers": ("id",),
}


def _table(f: h5py.File, path: Any, name: str, version: str) -> dict[str, np.ndarray]:
    group = f.get(name)
    if not isinstance(group, h5py.Group):
        raise ArchiveError(f"{printable(os.fspath(path))}: table /{name} is missing")
    table = read_table(group, path)
    if version == "1" and name == "summary":
        table = {SUMMARY_RENAMED_V1.get(key, key): column for key, column in table.items()}
    specs = {"summary": SUMMARY_COLUMNS, "results": RESULT_COLUMNS, "towers": TOWER_COLUMNS}
    for column, (kind, _) in specs.get(name, {}).items():
        values = table.get(column)
        if values is not None and kind != "str" and values.dtype.kind not in "biuf":
            raise ArchiveError(
                f"{printable(os.fspath(path))}: column /{name}/{column} holds "
                f"{values.dtype.kind == 'O' and 'text' or values.dtype} where rockscreen "
                "writes numbers"
            )
        if values is not None and name == "towers" and kind == "str" and values.dtype != object:
            raise ArchiveError(
                f"{printable(os.fspath(path))}: column /{name}/{column} holds numbers "
                "where rockscreen writes text"
            )
    missing = [column for column in _REQUIRED.get(name, ()) if column not in table]
    if missing:
        raise ArchiveError(
            f"{printable(os.fspath(path))}: table /{name} lacks column(s) "
            f"{printable(', '.join(missing[:5]))}"
        )
    return {key: column for key, column in table.items() if not key.startswith("_")}


def _rows(table: dict[str, np.ndarray]) -> list[dict[str, Any]]:
    names = list(table)
    n = len(table[names[0]]) if names else 0
    return [{name: _python(table[name][i]) for name in names} for i in range(n)]


def _read(path: str | os.PathLike, name: str) -> dict[str, np.ndarray]:
    f, version = open_campaign(path)
    with f, reading(path):
        return _table(f, path, name, version)


@fill_doc(_DOCS)
def read_summary_table(path: str | os.PathLike) -> dict[str, np.ndarray]:
    """Return the per-tower summary as columns: ``pandas.DataFrame(read_summary_table(p))``.

    Parameters
    ----------
    path : str or path-like
        A complete archive.

    Returns
    -------
    dict of str to numpy.ndarray
        Column name (``rockscreen.pipeline.archive.schema.SUMMARY_COLUMNS``) -> values in inventory
        order; text columns are object arrays of ``str`` (never bytes), numbers and flags
        as stored.

    Raises
    ------
    %(archive_error)s
    """
    return _read(path, "summary")


@fill_doc(_DOCS)
def read_summary(path: str | os.PathLike) -> list[dict[str, Any]]:
    """Return the per-tower summary of an archive, in inventory order.

    Parameters
    ----------
    path : str or path-like
        A complete archive.

    Returns
    -------
    list of dict
        One dict per tower with the keys of ``rockscreen.pipeline.archive.schema.SUMMARY_COLUMNS``
        (``safety_factor`` is ``inf`` when nothing up to the cap overturned, NaN when
        not searched; ``lat_deg``/``lon_deg`` NaN when unknown).

    Raises
    ------
    %(archive_error)s
    """
    return _rows(read_summary_table(path))


@fill_doc(_DOCS)
def read_towers(path: str | os.PathLike) -> list[dict[str, Any]]:
    """Return the tower inventory an archive stores (``/towers``), in inventory order.

    Parameters
    ----------
    path : str or path-like
        A complete archive.

    Returns
    -------
    list of dict
        One dict per tower with every key of
        ``rockscreen.pipeline.archive.schema.TOWER_COLUMNS`` (the inventory's columns, units
        in the names: ``width_m`` [m], ``masonry_strength_mpa`` [MPa], ...), then any
        column a newer rockscreen stored. A value not given is NaN (numbers) or ``""``
        (text); so is every value of a column the archive lacks (an archive written
        before the column was stored, e.g. without ``comune`` or the bell gable's
        columns). ``depth_m`` and ``belfry_depth_m`` are the resolved depths.

    Raises
    ------
    %(archive_error)s
    """
    return with_absent_columns(_rows(_read(path, "towers")))


def read_results(path: str | os.PathLike) -> list[dict[str, Any]]:
    """Return every tower-record-component-model row of an archive (``/results``)."""
    return _rows(_read(path, "results"))


def read_failures(path: str | os.PathLike) -> list[dict[str, Any]]:
    """Return the failures table of an archive: ``kind``, ``subject``, ``reason``."""
    return _rows(_read(path, "failures"))


def _rows_of(f: h5py.File, name: str) -> int:
    ds = f.get(name)
    if not isinstance(ds, h5py.Dataset) or ds.ndim != 1:
        return 0
    return int(ds.shape[0])


def read_metadata(path: str | os.PathLike) -> dict[str, Any]:
    """Return the root attributes of an archive (version, config, command line, ...).

    Adds ``n_cases`` (rows of ``/results``) and ``n_failures`` (rows of ``/failures``).
    """
    f, _ = open_campaign(path)
    with f, reading(path):
        meta = {key: _python(value) for key, value in f.attrs.items()}
        meta["n_cases"] = _rows_of(f, "results/tower_id")
        meta["n_failures"] = _rows_of(f, "failures/kind")
    return meta


def _history_ids(stored: str, component: str, version: str) -> tuple[str, str]:
    """Return ``(record_id, channel_id)`` of a history index row."""
    if version == "1":
        return stored, channel_id(stored, component)
    record = stored[: -len(component)] if component and stored.endswith(component) else stored
    return record, stored


@fill_doc(_DOCS)
def read_histories(path: str | os.PathLike, tower_id: str) -> list[dict[str, Any]]:
    """Return the stored time histories of one tower.

    Parameters
    ----------
    path : str or path-like
        A complete archive.
    tower_id : str
        The tower.

    Returns
    -------
    list of dict
        Keys ``record_id`` (``IT.AQV..HN``), ``channel_id`` (``IT.AQV..HNX``),
        ``component``, ``model``, ``alpha_rad`` [rad] and arrays ``t`` [s],
        ``theta`` [rad], ``u`` [m], ``regime``; in record, component, model order.
        Empty when the archive keeps no histories for the tower.

    Raises
    ------
    ArchiveError
        If the tower is not in the archive, or the index points outside the arrays.
    """
    f, version = open_campaign(path)
    with f, reading(path):
        ids = set(read_column(f.get("summary/id"), path, "summary/id"))
        if tower_id not in ids:
            shown = ", ".join(printable(i) for i in sorted(ids)[:10])
            raise ArchiveError(
                f"tower {printable(tower_id)!r} is not in {printable(os.fspath(path))!r} "
                f"(towers: {shown}...)"
            )
        index = _table(f, path, "histories/index", version)
        arrays = {}
        for name in HISTORY_ARRAYS:
            ds = f.get(f"histories/{name}")
            if not isinstance(ds, h5py.Dataset) or ds.ndim != 1:
                raise ArchiveError(f"{printable(os.fspath(path))}: /histories/{name} is missing")
            arrays[name] = ds
        size = min(ds.shape[0] for ds in arrays.values())
        out = []
        for i in np.flatnonzero(index["tower_id"] == tower_id):
            s, c = int(index["start"][i]), int(index["count"][i])
            if s < 0 or c < 0 or s + c > size:
                raise ArchiveError(
                    f"{printable(os.fspath(path))}: /histories/index row {i} points to rows "
                    f"[{s}, {s + c}) of arrays of {size} rows"
                )
            component = str(index["component"][i])
            record, channel = _history_ids(str(index["record_id"][i]), component, version)
            item: dict[str, Any] = {
                "record_id": record,
                "channel_id": channel,
                "component": component,
                "model": str(index["model"][i]),
                "alpha_rad": float(index["alpha_rad"][i]),
            }
            for name, ds in arrays.items():
                item[name] = ds[s : s + c]
            out.append(item)
    return out


def tree_of(f: h5py.File) -> list[str]:
    """Return the tree of an open archive, one line per group or dataset with shape and units.

    Record groups and table columns are listed in full; names and units are escaped
    with :func:`rockscreen.pipeline.text.printable`.
    """
    lines: list[str] = ["/"]

    def visit(name: str, obj: Any) -> None:
        depth = name.count("/")
        label = printable(name.rsplit("/", 1)[-1])
        if isinstance(obj, h5py.Dataset):
            units = printable(_python(obj.attrs.get("units", "")))[:40]
            unit_text = f" [{units}]" if units else ""
            lines.append(f"{'  ' * depth}{label}  {obj.shape} {obj.dtype}{unit_text}")
        else:
            lines.append(f"{'  ' * depth}{label}/")

    f.visititems(visit)
    return lines


def archive_tree(path: str | os.PathLike) -> list[str]:
    """Return the archive's tree, one line per group or dataset with shape and units.

    Record groups and table columns are listed in full; names and units are escaped
    with :func:`rockscreen.pipeline.text.printable`. The output is meant for ``rockscreen inspect``.
    """
    f, _ = open_campaign(path)
    with f, reading(path):
        return tree_of(f)


def read_stations(path: str | os.PathLike) -> list[dict[str, Any]]:
    """Return the stations of an archive's records: ``key``, ``latitude``, ``longitude`` [deg].

    One entry per station (``NET.STA``), sorted by key; coordinates NaN when unknown.
    """
    stations: dict[str, dict[str, Any]] = {}
    f, _ = open_campaign(path)
    with f, reading(path):
        records = f.get("records")
        if not isinstance(records, h5py.Group):
            raise ArchiveError(f"{printable(os.fspath(path))}: group /records is missing")
        for record_id in records:
            attrs = records[record_id].attrs
            key = str(_python(attrs["station"]))
            entry = {
                "key": key,
                "latitude": float(attrs["latitude"]),
                "longitude": float(attrs["longitude"]),
            }
            if key not in stations or math.isnan(stations[key]["latitude"]):
                stations[key] = entry
    return [stations[key] for key in sorted(stations)]
