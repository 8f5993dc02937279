"""The assess and scenario archives (HDF5): writer and readers.

Layout (every dataset carries a ``units`` attribute in UDUNITS spelling: ``"1"``
dimensionless, ``"deg"``, ``"9.81 m/s2"`` for accelerations in g (rockscreen's
``G = 9.81`` m/s²), ``"year"``, ``"1/year"``, ``""`` for text and flags; every column's
units are declared in :data:`TABLES`, from :mod:`rockscreen.pipeline.archive.schema`)::

    /               attrs: format="rockscreen-archive", kind ("assess" | "scenario"),
                    format_version="2", rockscreen_version, created_utc, command_line,
                    and the resolved inputs (JSON text where structured)
    /summary/<col>  one row per tower (assess: fragility, risk, LV1; scenario: event PGA,
                    probability of overturning)
    /stripes/<col>  assess: one row per tower x return period (counts per stripe)
    /outcomes/<col> assess: one row per tower x return period x record x component x model
    /selection/<col> assess: one row per site x return period (records, factors, match)
    /ida/<col>      assess: one row per tower x record x component of the set at the
                    tower's T_R,SLV (collapse and SLV scale and ag, censoring)
    /records/<id>/{x,y,z}
                    assess: every record of the selected sets, as the selection holds it
                    (before its factor in /selection/scale_factors) [m/s2]; group
                    attributes dt_s [s], name, source; ``<id>`` is the record's name and
                    a digest of its samples (listed per set in /selection/record_ids);
                    a component the record lacks is absent
    /failures/<col> kind, subject, reason
    /inventory/<col>
                    assess: the tower inventory as read, one row per tower in inventory
                    order, every column with the run archive's units (its ``/towers``:
                    :data:`rockscreen.pipeline.archive.schema.TOWER_COLUMNS`, written by
                    :func:`rockscreen.pipeline.archive.inventory_group.write_inventory_group`);
                    NaN or ``""`` = not given. An assess archive written before it lacks
                    the table (:func:`read_inventory` returns no rows)

Tables are groups of 1-D datasets, one per column, text as UTF-8 variable-length strings
(as in the campaign archive, :mod:`rockscreen.pipeline.archive.campaign`). The file is written
through :func:`rockscreen.pipeline.archive.atomic.atomic_path` (``OUT.tmp`` renamed when complete;
``OUT.part`` is the work file of an assessment in progress, :mod:`.assess_part`).
Readers check ``format``, ``kind`` and ``format_version`` on open and refuse anything else
in one line.
"""

from __future__ import annotations

import datetime as _dt
import json
import math
import os
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import h5py
import numpy as np

from rockscreen.pipeline import __version__
from rockscreen.pipeline.archive.atomic import atomic_path
from rockscreen.pipeline.archive.inventory_group import with_absent_columns, write_inventory_group
from rockscreen.pipeline.archive.reader import python_scalar
from rockscreen.pipeline.archive.risk_schema import (
    ASSESS_TABLES,
    SCENARIO_TABLES,
    UnitsTable,
    table_units,
)
from rockscreen.pipeline.archive.safety import (
    check_attribute_sizes,
    check_tables,
    check_tree,
    closed_on_failure,
    read_table,
    reading,
)
from rockscreen.pipeline.archive.schema import (
    ACCELERATION,
    DIMENSIONLESS,
    FAILURE_COLUMNS,
    G_UNITS,
    TEXT,
)
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.text import printable, storable

__all__ = [
    "FORMAT",
    "FORMAT_VERSION",
    "G_UNITS",
    "COORDINATE_RANGES",
    "KINDS",
    "REQUIRED_COLUMNS",
    "TABLES",
    "TABLE_NAMES",
    "check_risk_tables",
    "column_order",
    "read_failures",
    "read_ida",
    "read_inventory",
    "read_metadata",
    "read_outcomes",
    "read_records",
    "read_selection",
    "read_stripes",
    "read_summary",
    "units_of",
    "write_risk_archive",
]

FORMAT = "rockscreen-archive"
FORMAT_VERSION = "2"
KINDS = ("assess", "scenario")
#: Units of every column of each kind, per table (explicit: :mod:`.schema`).
TABLES: dict[str, dict[str, UnitsTable]] = {"assess": ASSESS_TABLES, "scenario": SCENARIO_TABLES}
#: The tables of each kind that are groups of equal-length 1-D columns.
TABLE_NAMES: dict[str, tuple[str, ...]] = {
    "assess": ("summary", "stripes", "outcomes", "selection", "ida", "failures", "inventory"),
    "scenario": ("summary", "failures"),
}
#: Columns each table must have (when the table is there; ``summary`` always is).
REQUIRED_COLUMNS: dict[str, tuple[str, ...]] = {
    "summary": ("id",),
    "failures": tuple(FAILURE_COLUMNS),
    "inventory": ("id",),
}
#: Coordinates a reader checks (NaN: a tower without coordinates).
COORDINATE_RANGES: dict[str, tuple[float, float]] = {
    "lat_deg": (-90.0, 90.0),
    "lon_deg": (-180.0, 180.0),
    "site_lat_deg": (-90.0, 90.0),
    "site_lon_deg": (-180.0, 180.0),
}
_STR = h5py.string_dtype("utf-8")


def units_of(kind: str, table: str, column: str) -> str:
    """Return the units attribute of a column of an assess or scenario archive.

    Parameters
    ----------
    kind : {"assess", "scenario"}
        The archive kind.
    table, column : str
        The table (``summary``, ``stripes``, ...) and the column.

    Returns
    -------
    str
        The units spelling of :data:`TABLES` (``""`` for text and flags).

    Raises
    ------
    ArchiveError
        If the column is not declared in :data:`TABLES` (a new column is declared in
        :mod:`rockscreen.pipeline.archive.schema` first).
    """
    units = table_units(TABLES.get(kind, {}), table, column)
    if units is None:
        raise ArchiveError(
            f"column {table}/{column} of the {kind} archive has no declared units "
            "(declare it in rockscreen.pipeline.archive.schema)"
        )
    return units


def _kind_of(values: list[Any]) -> str:
    sample = next((v for v in values if v is not None), "")
    if isinstance(sample, (bool, np.bool_)):
        return "bool"
    if isinstance(sample, (int, np.integer)):
        return "i8"
    if isinstance(sample, (float, np.floating)):
        return "f8"
    return "str"


def _write_table(
    group: h5py.Group, rows: Sequence[dict[str, Any]], columns: Sequence[str], kind: str
) -> None:
    table = group.name.lstrip("/")
    group.attrs["columns"] = json.dumps(list(columns))  # HDF5 lists members alphabetically
    column_array = getattr(rows, "column_array", None)  # a RowTable: whole numpy columns
    for name in columns:
        if column_array is not None:
            array = column_array(name)
            if array.dtype.kind in "bif":  # numbers as they are, no Python list in between
                ds = group.create_dataset(
                    name, data=array.astype({"b": "?", "i": "i8", "f": "f8"}[array.dtype.kind])
                )
                ds.attrs["units"] = (
                    TEXT
                    if array.dtype.kind == "b"
                    else (units_of(kind, table, name) or DIMENSIONLESS)
                )
                continue
            values = array.tolist()
        else:
            values = [row.get(name) for row in rows]
        units = units_of(kind, table, name)
        stored = _kind_of(values)
        if stored == "str":
            data = np.asarray(["" if v is None else str(v) for v in values], dtype=object)
            ds = group.create_dataset(name, data=data, dtype=_STR)
        else:
            dtype = {"bool": "?", "i8": "i8", "f8": "f8"}[stored]
            ds = group.create_dataset(name, data=np.asarray(values, dtype=dtype))
        if stored in ("i8", "f8"):
            ds.attrs["units"] = units or DIMENSIONLESS
        else:
            ds.attrs["units"] = TEXT


def _columns(rows: Sequence[dict[str, Any]], default: Sequence[str]) -> list[str]:
    return list(rows[0]) if rows else list(default)


def write_risk_archive(
    path: str | Path,
    kind: str,
    tables: dict[str, Sequence[dict[str, Any]]],
    metadata: dict[str, Any],
    empty_columns: dict[str, Sequence[str]] | None = None,
    arrays: dict[str, tuple[Any, str]] | None = None,
    records: dict[str, dict[str, Any]] | None = None,
    inventory: np.ndarray | None = None,
) -> Path:
    """Write an assess or scenario archive atomically.

    Parameters
    ----------
    path : str or Path
        The archive.
    kind : {"assess", "scenario"}
    tables : dict
        Table name (``summary``, ``stripes``, ``outcomes``, ``selection``, ``failures``) ->
        rows (dicts with the same keys, in order).
    metadata : dict
        Root attributes (strings or numbers; dicts and lists are stored as JSON text).
    empty_columns : dict, optional
        Columns of tables that may be empty.
    arrays : dict, optional
        Dataset path (e.g. ``"shakemap/pga_g"``) -> (array, units): gridded data such as the
        scenario's ShakeMap PGA grid, stored compressed with a ``units`` attribute.
    records : dict, optional
        Record id -> ``{"x", "y", "z"}`` accelerations [m/s²] (None: component absent),
        ``"dt_s"`` [s], ``"name"`` and ``"source"``: stored under ``/records/<id>``.
    inventory : numpy.ndarray, optional
        :func:`rockscreen.stations.inventory_table.inventory_table` of the towers as read
        (assess only): stored as ``/inventory``, the columns and units of the run
        archive's ``/towers``.

    Returns
    -------
    Path

    Raises
    ------
    ArchiveError
        For an unknown kind, an inventory given to a kind that keeps none, or a column
        without declared units.
    """
    if kind not in KINDS:
        raise ArchiveError(f"archive kind {kind!r}; allowed: {', '.join(KINDS)}")
    if inventory is not None and "inventory" not in TABLE_NAMES[kind]:
        raise ArchiveError(f"a {kind} archive keeps no inventory (only an assess archive does)")

    empty_columns = empty_columns or {}
    path = Path(path)
    with atomic_path(path, suffix=".tmp") as work:
        with h5py.File(work, "w") as f:
            f.attrs["format"] = FORMAT
            f.attrs["kind"] = kind
            f.attrs["format_version"] = FORMAT_VERSION
            f.attrs["rockscreen_version"] = __version__
            f.attrs["created_utc"] = _dt.datetime.now(_dt.timezone.utc).isoformat(
                timespec="seconds"
            )
            for key, value in metadata.items():
                if isinstance(value, (dict, list, tuple)):
                    value = json.dumps(value)
                value = "" if value is None else value
                f.attrs[key] = storable(value) if isinstance(value, str) else value
            for name, rows in tables.items():
                group = f.create_group(name)
                _write_table(group, rows, _columns(rows, empty_columns.get(name, ())), kind)
            for name, (data, units) in (arrays or {}).items():
                ds = f.create_dataset(name, data=np.asarray(data, dtype=float), compression="gzip")
                ds.attrs["units"] = units
            if records:
                _write_records(f, records)
            if inventory is not None:
                write_inventory_group(f, "inventory", inventory)
    return path


def _write_records(f: h5py.File, records: dict[str, dict[str, Any]]) -> None:
    """Write ``/records/<id>/{x,y,z}`` [m/s²] with ``dt_s``, ``name``, ``source``."""
    top = f.create_group("records")
    top.attrs["description"] = (
        "records of the selected sets, before their selection factor (/selection/scale_factors)"
    )
    for record_id, record in records.items():
        if not record_id or "/" in record_id or record_id in (".", ".."):
            raise ArchiveError(f"record id {record_id!r} cannot name an HDF5 group")
        group = top.create_group(record_id)
        group.attrs["dt_s"] = float(record["dt_s"])
        group.attrs["name"] = storable(str(record.get("name", record_id)))
        group.attrs["source"] = storable(str(record.get("source", "")))
        for component in ("x", "y", "z"):
            acc = record.get(component)
            if acc is None:
                continue
            ds = group.create_dataset(
                component,
                data=np.asarray(acc, dtype=float),
                compression="gzip",
                shuffle=True,
            )
            ds.attrs["units"] = ACCELERATION


def check_risk_tables(f: h5py.File, path: Any, kind: str) -> None:
    """Check the tables of an open assess or scenario archive (shapes, types, text).

    Every column of :data:`TABLE_NAMES` is 1-D, of its table's length and of its declared
    type (:data:`TABLES`); the :data:`REQUIRED_COLUMNS` are there; text is valid UTF-8;
    coordinates lie in :data:`COORDINATE_RANGES`; a text column of ``/inventory`` holds
    text (not flags); no root text attribute exceeds
    :data:`~rockscreen.pipeline.archive.safety.MAX_ATTRIBUTE_BYTES`.

    Parameters
    ----------
    f : h5py.File
        The open archive (its tree checked).
    path : str or path-like
        Its path, for messages.
    kind : {"assess", "scenario"}
        Its kind.

    Raises
    ------
    ArchiveError
        One line naming the file, the table, the column and what is wrong.
    """
    check_attribute_sizes(f, path)
    check_tables(
        f,
        path,
        {table: TABLES[kind].get(table, {}) for table in TABLE_NAMES[kind]},
        REQUIRED_COLUMNS,
        text=TEXT,
        decode=True,
        present=("summary",),
        ranges=COORDINATE_RANGES,
    )
    for table in TABLE_NAMES[kind]:
        if isinstance(f.get(table), h5py.Group):
            column_order(f[table], path, table)
    inventory = f.get("inventory") if "inventory" in TABLE_NAMES[kind] else None
    if isinstance(inventory, h5py.Group):  # check_tables let flags pass as text
        units = TABLES[kind]["inventory"]
        for column in inventory:
            if units.get(column) == TEXT and inventory[column].dtype.kind == "b":
                raise ArchiveError(
                    f"{printable(os.fspath(path))}: column /inventory/{printable(column)[:60]} "
                    "holds flags where rockscreen writes text"
                )


def _open(path: str | Path, kind: str | None = None) -> h5py.File:
    path = Path(path)
    if not path.is_file():
        raise ArchiveError(f"archive {str(path)!r} does not exist")
    try:
        f = h5py.File(path, "r")
    except OSError as exc:
        raise ArchiveError(f"{str(path)!r} is not a readable HDF5 file: {exc}") from exc
    found_kind = str(f.attrs.get("kind", ""))
    version = str(f.attrs.get("format_version", ""))
    problem = ""
    if f.attrs.get("format") != FORMAT:
        problem = f"is not a rockscreen archive (no format={FORMAT!r})"
    elif found_kind not in KINDS or (kind is not None and found_kind != kind):
        wanted = kind or " or ".join(KINDS)
        problem = f"is a {found_kind or 'campaign'!r} archive, not an {wanted!r} archive"
    elif version != FORMAT_VERSION:
        problem = (
            f"has format_version {version!r}; this rockscreen reads {kind or found_kind} "
            f"archives of version {FORMAT_VERSION!r} only"
        )
    if problem:
        f.close()
        raise ArchiveError(f"{str(path)!r} {problem}")
    with closed_on_failure(f), reading(path):
        check_tree(f, path)  # no external links, external or virtual storage, ...
        check_risk_tables(f, path, found_kind)
    return f


def column_order(group: h5py.Group, path: Any, table: str) -> list[str]:
    """Return a table's columns in their written order (its ``columns`` attribute).

    The writer stores the order as a JSON list because HDF5 lists a group's members
    alphabetically; without the attribute the members' order is taken.

    Parameters
    ----------
    group : h5py.Group
        The table.
    path : str or path-like
        The archive's path, for messages.
    table : str
        The table's name, for messages.

    Returns
    -------
    list of str

    Raises
    ------
    ArchiveError
        When the attribute is not a JSON list of the group's members' names (one line
        naming the file and the table).
    """
    if "columns" not in group.attrs:
        return list(group)
    raw = group.attrs["columns"]
    try:
        order = json.loads(raw.decode("utf-8") if isinstance(raw, bytes) else str(raw))
    except (ValueError, UnicodeDecodeError):
        order = None
    members = set(group)
    if not (
        isinstance(order, list)
        and all(isinstance(c, str) for c in order)
        and len(set(order)) == len(order)
        and set(order) <= members
    ):
        raise ArchiveError(
            f"{printable(os.fspath(path))}: /{printable(table)[:60]} has a 'columns' attribute "
            "that is not the JSON list of its columns rockscreen writes"
        )
    return order


def _rows(f: h5py.File, name: str) -> list[dict[str, Any]]:
    if name not in f:
        return []
    group = f[name]
    data = {}
    order = column_order(group, f.filename, name)
    for column in order:
        ds = group[column]
        data[column] = ds.asstr()[:] if h5py.check_string_dtype(ds.dtype) else ds[:]
    n = len(next(iter(data.values()))) if data else 0
    return [{c: python_scalar(v[i]) for c, v in data.items()} for i in range(n)]


def read_summary(path: str | Path, kind: str | None = None) -> list[dict[str, Any]]:
    """Return the per-tower summary rows (inventory order) of an assess or scenario archive."""
    with _open(path, kind) as f:
        return _rows(f, "summary")


def read_stripes(path: str | Path) -> list[dict[str, Any]]:
    """Return the stripe rows of an assess archive (tower, return period [y], ag [g], counts)."""
    with _open(path, "assess") as f:
        return _rows(f, "stripes")


def read_outcomes(path: str | Path) -> list[dict[str, Any]]:
    """Return the record x component x model rows of an assess archive."""
    with _open(path, "assess") as f:
        return _rows(f, "outcomes")


def read_ida(path: str | Path) -> list[dict[str, Any]]:
    """Return the IDA rows (tower x record x component) of an assess archive ([] if none)."""
    with _open(path, "assess") as f:
        return _rows(f, "ida")


def read_selection(path: str | Path) -> list[dict[str, Any]]:
    """Return the record-set rows (site x return period) of an assess archive."""
    with _open(path, "assess") as f:
        return _rows(f, "selection")


def read_inventory(path: str | Path) -> list[dict[str, Any]]:
    """Return the tower inventory an assess archive stores (``/inventory``), in its order.

    Parameters
    ----------
    path : str or Path
        The assess archive.

    Returns
    -------
    list of dict
        One dict per tower with every key of
        :data:`rockscreen.pipeline.archive.schema.TOWER_COLUMNS` (the run archive's
        ``/towers``: ``width_m`` [m], ``masonry_strength_mpa`` [MPa], ``gable_axis``, ...),
        then any column a newer rockscreen stored; NaN (numbers) or ``""`` (text) where a
        value was not given. Empty for an assess archive written before the inventory
        was kept.

    Raises
    ------
    ArchiveError
        If the file is not a sound assess archive (one line; a malformed ``/inventory``
        included).
    """
    with _open(path, "assess") as f, reading(path):
        if "inventory" not in f:
            return []
        table = read_table(f["inventory"], path)
    n = len(table["id"])
    rows = [{name: python_scalar(column[i]) for name, column in table.items()} for i in range(n)]
    return with_absent_columns(rows)


def read_records(path: str | Path) -> dict[str, dict[str, Any]]:
    """Return the records of an assess archive's selected sets ({} if none stored).

    Parameters
    ----------
    path : str or Path
        The assess archive.

    Returns
    -------
    dict
        Record id -> ``{"x", "y", "z"}`` accelerations [m/s²] (None for an absent
        component), ``"dt_s"`` [s], ``"name"``, ``"source"``.

    Raises
    ------
    ArchiveError
        For a record without a positive ``dt_s`` or a component that is not 1-D in m/s2.
    """
    out: dict[str, dict[str, Any]] = {}
    with _open(path, "assess") as f:
        top = f.get("records")
        if not isinstance(top, h5py.Group):
            return out
        for record_id, group in top.items():
            if not isinstance(group, h5py.Group):
                raise ArchiveError(f"{str(path)!r}: /records/{record_id} is not a group")
            dt = python_scalar(group.attrs.get("dt_s", math.nan))
            if not (isinstance(dt, float) and math.isfinite(dt) and dt > 0):
                raise ArchiveError(f"{str(path)!r}: /records/{record_id} has no positive dt_s")
            entry: dict[str, Any] = {
                "dt_s": dt,
                "name": str(python_scalar(group.attrs.get("name", record_id))),
                "source": str(python_scalar(group.attrs.get("source", ""))),
            }
            for component in ("x", "y", "z"):
                ds = group.get(component)
                if ds is None:
                    entry[component] = None
                    continue
                if not isinstance(ds, h5py.Dataset) or ds.ndim != 1 or ds.dtype.kind != "f":
                    raise ArchiveError(
                        f"{str(path)!r}: /records/{record_id}/{component} is not a 1-D float array"
                    )
                if python_scalar(ds.attrs.get("units", "")) != ACCELERATION:
                    raise ArchiveError(
                        f"{str(path)!r}: /records/{record_id}/{component} is not in {ACCELERATION}"
                    )
                entry[component] = ds[:]
            out[record_id] = entry
    return out


def read_failures(path: str | Path) -> list[dict[str, Any]]:
    """Return the failures of an assess or scenario archive (kind, subject, reason)."""
    with _open(path) as f:
        return _rows(f, "failures")


def read_metadata(path: str | Path) -> dict[str, Any]:
    """Return the root attributes of an assess or scenario archive."""
    with _open(path) as f:
        out = {key: python_scalar(value) for key, value in f.attrs.items()}
    return {k: (None if isinstance(v, float) and math.isnan(v) else v) for k, v in out.items()}
