"""The assess and scenario archives (HDF5): their layout, units and writer.

Layout (every dataset carries a ``units`` attribute in UDUNITS spelling: ``"1"``
dimensionless, ``"deg"``, ``"9.81 m/s2"`` for accelerations in g (rockscreen's
``G = 9.81`` m/s²), ``"year"``, ``"1/year"``, ``""`` for text and flags; every column's
units are declared in :data:`TABLES`, from :mod:`rockscreen.pipeline.archive.schema`)::

    /               attrs: format="rockscreen-archive", kind ("assess" | "scenario"),
                    format_version (assess "4", scenario "3"), rockscreen_version,
                    created_utc, command_line, and the resolved inputs (JSON text where
                    structured)
    /summary/<col>  one row per tower (assess: the tower, its site, class, governing check,
                    completeness, screening risk...; scenario: event PGA, probability of
                    overturning)
    /fits, /checks, /messages, /pivot
                    assess: one row per tower x fit, check, note, and per column of the
                    wide summary row (:mod:`rockscreen.pipeline.archive.long_tables`)
    /stripes/<col>  assess: one row per tower x return period (counts per stripe)
    /outcomes/<col> assess: one row per tower x return period x record x component x model
    /selection/<col> assess: one row per site x return period (match, compliance and
                    the period range it is measured over; its records: /set_records)
    /set_records/<col>
                    assess: the sets as references, one row per record of each set (in
                    /selection order, then the set's): ``set`` (its /selection row),
                    ``record`` (its /records/index row) and ``scale_factor`` (float64,
                    exact: the factor the towers were computed with)
    /ida/<col>      assess: one row per tower x record x component of the set at the
                    tower's T_R,SLV (collapse and SLV scale and ag, censoring)
    /records/index/<col>
                    assess: every record of the sets, stored once (however many sets
                    hold it): ``id`` (the record's name and a digest of its samples),
                    ``name``, ``source``, ``dt_s`` [s], and per component ``<c>_start``,
                    ``<c>_count``: its samples in /records/<c> (count 0: no such component)
    /records/{x,y,z}
                    assess: the records' samples concatenated, before their factors
                    [m/s2]; float32 when every sample is a float32 exactly (the
                    embedded pools' records are), else float64 (a user suite's): read
                    back as float64, the same numbers the towers were computed with
    /failures/<col> kind, subject, reason
    /inventory/<col>
                    assess: the tower inventory as read, one row per tower in inventory
                    order, every column with the run archive's units (its ``/towers``:
                    :data:`rockscreen.pipeline.archive.schema.TOWER_COLUMNS`, written by
                    :func:`rockscreen.pipeline.archive.inventory_group.write_inventory_group`);
                    NaN or ``""`` = not given. An assess archive written before it lacks
                    the table (:func:`read_inventory` returns no rows)

Version 4 (assess) stores the per-tower summary as long tables (``/summary`` slim,
``/fits``, ``/checks``, ``/messages``, ``/pivot``:
:mod:`rockscreen.pipeline.archive.long_tables`);
:func:`rockscreen.pipeline.archive.risk_reader.read_summary` pivots them back into one wide
row per tower, the rows of version 3, whose wide ``/summary`` is read as it is (the one
adapter of versions 2 and 3).

Version 3 (assess) stores each record once and the sets as references; an assess
archive of version 2 (``/records/<id>/{x,y,z}``, one group per record, the sets as
comma-separated ``records``, ``record_ids`` and ``scale_factors`` (rounded to 6 digits) in
``/selection``)
is read by :func:`rockscreen.pipeline.archive.risk_reader.read_records` as before, and
refused by :func:`~rockscreen.pipeline.archive.risk_reader.read_set_records` (its factors
are not exact): the same ``rockscreen assess`` command rebuilds it.

Tables are groups of 1-D datasets, one per column, each stored compactly by
:mod:`rockscreen.pipeline.archive.column_codec` (:func:`write_column`: compressed numbers,
coded or fixed-length text; its names :data:`MAX_CODES`, :data:`MAX_CODE_TABLE_BYTES`,
:data:`MAX_FIXED_TEXT_BYTES` and :func:`write_column` are importable from here too). The
file is written through :func:`rockscreen.pipeline.archive.atomic.atomic_path` (``OUT.tmp``
renamed when complete; ``OUT.part`` is the work file of an assessment in progress,
:mod:`.assess_part`).
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
from rockscreen.pipeline.archive.column_codec import (
    MAX_CODE_TABLE_BYTES,
    MAX_CODES,
    MAX_FIXED_TEXT_BYTES,
    TextForm,
    compressed_options,
    stored_kind,
    text_values,
    write_column,
)
from rockscreen.pipeline.archive.inventory_group import write_inventory_group
from rockscreen.pipeline.archive.long_schema import LONG_TABLES
from rockscreen.pipeline.archive.long_stream import write_summary_in_parts
from rockscreen.pipeline.archive.long_tables import (
    CheckColumns,
    split_summary,
    write_long_tables,
)
from rockscreen.pipeline.archive.record_store import (
    RECORD_COMPONENTS,
    sample_dtype,
    write_records,
)
from rockscreen.pipeline.archive.risk_schema import (
    SCENARIO_TABLES,
    UnitsTable,
    assess_tables,
    part_model_names,
    table_units,
)
from rockscreen.pipeline.archive.schema import (
    DIMENSIONLESS,
    FAILURE_COLUMNS,
    G_UNITS,
    TEXT,
)
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.text import storable

__all__ = [
    "FORMAT",
    "FORMAT_VERSIONS",
    "MAX_CODES",
    "MAX_CODE_TABLE_BYTES",
    "MAX_FIXED_TEXT_BYTES",
    "READ_VERSIONS",
    "RECORD_COMPONENTS",
    "G_UNITS",
    "COORDINATE_RANGES",
    "KINDS",
    "REQUIRED_COLUMNS",
    "TABLES",
    "TABLE_NAMES",
    "sample_dtype",
    "units_of",
    "write_column",
    "write_risk_archive",
]

FORMAT = "rockscreen-archive"
KINDS = ("assess", "scenario")
#: Layout version written, by kind (3: compact tables, :func:`write_column`; assess 3 also
#: stores each record once and the sets as references; assess 4 the summary as long
#: tables, :mod:`.long_tables`).
FORMAT_VERSIONS = {"assess": "4", "scenario": "3"}
#: Versions read, by kind, oldest first (the last is the one written).
READ_VERSIONS = {"assess": ("2", "3", "4"), "scenario": ("2", "3")}


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
        "set_records",
        "records/index",
        "risk_fragility",
        "risk_sensitivity",
        "risk_top_n",
        *LONG_TABLES,
    ),
    "scenario": ("summary", "failures"),
}
#: Columns each table must have (when the table is there; ``summary`` always is).
REQUIRED_COLUMNS: dict[str, tuple[str, ...]] = {
    "summary": ("id",),
    "failures": tuple(FAILURE_COLUMNS),
    "inventory": ("id",),
    "fits": ("tower", "fit"),
    "checks": ("tower", "check", "reason_code", "reason_params"),
    "messages": ("tower", "column", "code", "params"),
    "pivot": ("column", "kind", "table", "key", "field"),
    "set_records": ("set", "record", "scale_factor"),
    "records/index": tuple(
        ["id", "name", "source", "dt_s"]
        + [f"{c}_{part}" for c in RECORD_COMPONENTS for part in ("start", "count")]
    ),
}
#: Coordinates a reader checks (NaN: a tower without coordinates).
COORDINATE_RANGES: dict[str, tuple[float, float]] = {
    "lat_deg": (-90.0, 90.0),
    "lon_deg": (-180.0, 180.0),
    "site_lat_deg": (-90.0, 90.0),
    "site_lon_deg": (-180.0, 180.0),
}


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
                data = array.astype({"b": "?", "i": "i8", "f": "f8"}[array.dtype.kind])
                units = (
                    TEXT
                    if data.dtype.kind == "b"
                    else (units_of(kind, table, name) or DIMENSIONLESS)
                )
                write_column(group, name, data, units)
                continue
            values = array.tolist()
        else:
            values = [row.get(name) for row in rows]
        units = units_of(kind, table, name)
        stored = stored_kind(values)
        if not values and units != TEXT:  # an empty column of numbers: numbers, not text
            stored = "f8"
        if stored == "str":
            write_column(group, name, text_values(values), TEXT)
            continue
        data = np.asarray(values, dtype={"bool": "?", "i8": "i8", "f8": "f8"}[stored])
        write_column(group, name, data, TEXT if stored == "bool" else (units or DIMENSIONLESS))


def _write_streamed_table(group: h5py.Group, rows: Any, columns: Sequence[str], kind: str) -> None:
    """Write a table given in parts (``rows.chunks()``), in the form of :func:`_write_table`.

    Two passes over the parts: the first decides each column's type and form (codes,
    fixed or variable-length text: all its values), the second writes the rows part by
    part, so no more than one part is in memory.
    """
    table = group.name.lstrip("/")
    group.attrs["columns"] = json.dumps(list(columns))
    n = 0
    samples: dict[str, Any] = {}
    forms = {name: TextForm() for name in columns}
    for part in rows.chunks():
        for name in columns:
            values = [row.get(name) for row in part]
            if name not in samples:
                sample = next((v for v in values if v is not None), None)
                if sample is not None:
                    samples[name] = sample
            if stored_kind([samples.get(name)]) == "str":
                forms[name].add(text_values(values))
        n += len(part)
    if n == 0:
        _write_table(group, [], columns, kind)
        return
    datasets = {}
    for name in columns:
        stored = stored_kind([samples.get(name)])
        if stored == "str":
            datasets[name] = forms[name].create(group, name, n, TEXT)
            continue
        dtype = {"bool": "?", "i8": "i8", "f8": "f8"}[stored]
        units = TEXT if stored == "bool" else (units_of(kind, table, name) or DIMENSIONLESS)
        ds = group.create_dataset(
            name, shape=(n,), dtype=dtype, **compressed_options(n, np.dtype(dtype).itemsize)
        )
        ds.attrs["units"] = units
        datasets[name] = ds
    start = 0
    for part in rows.chunks():
        for name, ds in datasets.items():
            values = [row.get(name) for row in part]
            if "codes" in ds.attrs or h5py.check_string_dtype(ds.dtype) is not None:
                forms[name].fill(ds, start, text_values(values))
            elif values:
                ds[start : start + len(values)] = np.asarray(values, dtype=ds.dtype)
        start += len(part)


def _write_tables(
    f: h5py.File,
    kind: str,
    tables: dict[str, Sequence[dict[str, Any]]],
    empty_columns: dict[str, Sequence[str]],
    checks: Sequence[CheckColumns],
) -> None:
    """Write the row tables; an assess summary given in parts as ``/summary`` and long tables.

    A table given in parts (``chunks()``) is written a part at a time, never all in memory;
    an assess summary given so (the work file's rows) is split a part at a time too
    (:func:`~rockscreen.pipeline.archive.long_stream.write_summary_in_parts`).
    """
    for name, rows in tables.items():
        in_parts = hasattr(rows, "chunks")
        if kind == "assess" and name == "summary" and in_parts and len(rows):
            write_summary_in_parts(
                f,
                rows,  # type: ignore[arg-type]
                part_model_names(),
                checks,
                lambda group, table, columns: _write_streamed_table(group, table, columns, kind),
            )
            continue
        group = f.create_group(name)
        columns = getattr(rows, "columns", None) or _columns(rows, empty_columns.get(name, ()))
        if in_parts:
            _write_streamed_table(group, rows, columns, kind)
        else:
            _write_table(group, rows, columns, kind)


def _columns(rows: Sequence[dict[str, Any]], default: Sequence[str]) -> list[str]:
    return list(rows[0]) if rows else list(default)


def _write_root_attrs(f: h5py.File, kind: str, metadata: dict[str, Any]) -> None:
    """Write the root attributes: format, kind, version, creation time and ``metadata``."""
    f.attrs["format"] = FORMAT
    f.attrs["kind"] = kind
    f.attrs["format_version"] = FORMAT_VERSIONS[kind]
    f.attrs["rockscreen_version"] = __version__
    f.attrs["created_utc"] = _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")
    for key, value in metadata.items():
        if isinstance(value, (dict, list, tuple)):
            value = json.dumps(value)
        value = "" if value is None else value
        f.attrs[key] = storable(value) if isinstance(value, str) else value


def write_risk_archive(
    path: str | Path,
    kind: str,
    tables: dict[str, Sequence[dict[str, Any]]],
    metadata: dict[str, Any],
    empty_columns: dict[str, Sequence[str]] | None = None,
    arrays: dict[str, tuple[Any, str]] | None = None,
    records: dict[str, dict[str, Any]] | None = None,
    inventory: np.ndarray | None = None,
    set_records: Sequence[tuple[int, str, float]] | None = None,
    checks: Sequence[CheckColumns] = (),
) -> Path:
    """Write an assess or scenario archive atomically.

    Parameters
    ----------
    path : str or Path
        The archive.
    kind : {"assess", "scenario"}
    tables : dict
        Table name (``summary``, ``stripes``, ``outcomes``, ``selection``, ``failures``) ->
        rows (dicts with the same keys, in order), or an object giving them a part at a
        time (``chunks()``, ``columns``, ``len()``: the work file's
        :class:`~rockscreen.pipeline.archive.kept_rows.JournalRows` and, for the assess
        summary, :class:`~rockscreen.pipeline.archive.kept_rows.JournalSummary`), written
        a part at a time into the same datasets.
    metadata : dict
        Root attributes (strings or numbers; dicts and lists are stored as JSON text).
    empty_columns : dict, optional
        Columns of tables that may be empty.
    arrays : dict, optional
        Dataset path (e.g. ``"shakemap/pga_g"``) -> (array, units): gridded data such as the
        scenario's ShakeMap PGA grid, stored compressed with a ``units`` attribute.
    records : dict, optional
        Record id -> ``{"x", "y", "z"}`` accelerations [m/s²] (None: component absent),
        ``"dt_s"`` [s], ``"name"`` and ``"source"``: stored once each, in
        ``/records/index`` and the concatenated ``/records/{x,y,z}`` (module docstring).
    inventory : numpy.ndarray, optional
        :func:`rockscreen.stations.inventory_table.inventory_table` of the towers as read
        (assess only): stored as ``/inventory``, the columns and units of the run
        archive's ``/towers``.
    set_records : sequence of (int, str, float), optional
        The sets as references (assess): (row of the set in ``tables["selection"]``,
        record id, scale factor) per record of each set, stored as ``/set_records``; each
        id must be a key of ``records``.
    checks : sequence of CheckColumns, optional
        Where each check's result is in the assess summary rows, in the verdict's order
        (:func:`rockscreen.pipeline.risk.checks.governing.check_columns`): stored one row
        per tower x check in ``/checks`` (:mod:`.long_tables`). The fits
        (:func:`~rockscreen.pipeline.archive.long_schema.fit_cells`) and the notes' codes
        move to ``/fits`` and ``/messages`` without it.

    Returns
    -------
    Path

    Raises
    ------
    ArchiveError
        For an unknown kind, an inventory or records given to a kind that keeps none, a
        column without declared units, a record without samples or a set referring to a
        record not given.
    """
    if kind not in KINDS:
        raise ArchiveError(f"archive kind {kind!r}; allowed: {', '.join(KINDS)}")
    if inventory is not None and "inventory" not in TABLE_NAMES[kind]:
        raise ArchiveError(f"a {kind} archive keeps no inventory (only an assess archive does)")
    if (records or set_records) and "set_records" not in TABLE_NAMES[kind]:
        raise ArchiveError(f"a {kind} archive keeps no records (only an assess archive does)")

    empty_columns = empty_columns or {}
    long_tables: dict[str, dict[str, list[Any]]] = {}
    summary = tables.get("summary")
    if kind == "assess" and summary and not hasattr(summary, "chunks"):
        split = split_summary(summary, part_model_names(), checks)
        tables = {**tables, "summary": split.summary}
        long_tables = split.tables
    path = Path(path)
    with atomic_path(path, suffix=".tmp") as work:
        with h5py.File(work, "w") as f:
            _write_root_attrs(f, kind, metadata)
            _write_tables(f, kind, tables, empty_columns, checks)
            write_long_tables(f, long_tables)
            for name, (data, units) in (arrays or {}).items():
                ds = f.create_dataset(name, data=np.asarray(data, dtype=float), compression="gzip")
                ds.attrs["units"] = units
            if records or set_records:
                write_records(f, records or {}, set_records or ())
            if inventory is not None:
                write_inventory_group(f, "inventory", inventory)
    return path
