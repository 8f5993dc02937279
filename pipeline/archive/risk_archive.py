"""The assess and scenario archives (HDF5): their layout, units and writer.

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
from collections.abc import Iterator, Mapping, Sequence
from pathlib import Path
from typing import Any

import h5py
import numpy as np

from rockscreen.pipeline import __version__
from rockscreen.pipeline.archive.atomic import atomic_path
from rockscreen.pipeline.archive.inventory_group import write_inventory_group
from rockscreen.pipeline.archive.risk_schema import (
    SCENARIO_TABLES,
    UnitsTable,
    assess_tables,
    table_units,
)
from rockscreen.pipeline.archive.schema import (
    ACCELERATION,
    DIMENSIONLESS,
    FAILURE_COLUMNS,
    G_UNITS,
    TEXT,
)
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.text import storable

__all__ = [
    "FORMAT",
    "FORMAT_VERSION",
    "G_UNITS",
    "COORDINATE_RANGES",
    "KINDS",
    "REQUIRED_COLUMNS",
    "TABLES",
    "TABLE_NAMES",
    "units_of",
    "write_risk_archive",
]

FORMAT = "rockscreen-archive"
FORMAT_VERSION = "2"
KINDS = ("assess", "scenario")


class _AssessTables(Mapping[str, UnitsTable]):
    """The assess archive's tables, read from the engine's registry on each use.

    The summary's part-model columns follow the registry
    (:func:`~rockscreen.pipeline.archive.risk_schema.assess_tables`): a part model added
    as one module is declared without this module changing.
    """

    def __getitem__(self, table: str) -> UnitsTable:
        return assess_tables()[table]

    def __iter__(self) -> Iterator[str]:
        return iter(assess_tables())

    def __len__(self) -> int:
        return len(assess_tables())


#: Units of every column of each kind, per table (explicit: :mod:`.risk_schema`).
TABLES: dict[str, Mapping[str, UnitsTable]] = {
    "assess": _AssessTables(),
    "scenario": SCENARIO_TABLES,
}

#: The tables of each kind that are groups of equal-length 1-D columns.
TABLE_NAMES: dict[str, tuple[str, ...]] = {
    "assess": (
        "summary",
        "stripes",
        "outcomes",
        "selection",
        "ida",
        "failures",
        "inventory",
        "risk_fragility",
        "risk_sensitivity",
        "risk_top_n",
    ),
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
        if not values and units != TEXT:  # an empty column of numbers: numbers, not text
            stored = "f8"
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
