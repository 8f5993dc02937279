"""The campaign archive (HDF5): layout, crash-safe writing with resume, public readers.

Layout (every dataset carries a ``units`` attribute; ``""`` for text and flags,
``"1"`` for dimensionless numbers)::

    /                       attrs: format="rockscreen-archive", format_version,
                            rockscreen_version, created_utc, command_line,
                            config_toml (resolved configuration), fingerprint,
                            inventory_source, n_towers, n_records
    /towers/<column>        the tower inventory (id, name, station, lat_deg [deg],
                            lon_deg [deg], azimuth_deg [deg], width_m [m], height_m [m],
                            depth_m [m], eta [1], tower_mass_kg [kg], ...; NaN = absent)
    /records/<record_id>/   one group per processed record; attrs: station, dt [s],
                            starttime, latitude/longitude [deg], channels (JSON),
                            azimuths (JSON, deg), files (JSON), formats (JSON),
                            provenance (JSON)
        <component>         processed acceleration [m/s**2] per channel (h1, h2, z roles
                            named by their channel codes)
    /results/<column>       one row per tower-record-component-model case
                            (pipeline.screening.campaign.RESULT_COLUMNS, with units)
    /summary/<column>       one row per tower (pipeline.screening.campaign.SUMMARY_COLUMNS)
    /failures/<column>      kind (read|process|pair|solve), subject, reason
    /histories/index/<col>  tower_id, record_id, component, model, alpha_rad [rad],
                            start, count: rows [start, start+count) of the arrays below
    /histories/t            [s]   float32
    /histories/theta        [rad] float32 tower rotation
    /histories/u            [m]   float32 building slip (0 for single-block models)
    /histories/regime       [-]   int8: 0 rest, 1 tower rocking, 2 building sliding, 3 both

Crash safety and resume: the writer works on ``OUT.part`` beside ``OUT``, appends each
chunk, records the committed row counts in a root attribute and flushes. Only a
complete run is rewritten, sorted (towers in inventory order, cases in record,
component, model order), into ``OUT.tmp`` and moved to ``OUT`` with
:func:`os.replace`, so ``OUT`` is either absent or complete. A rerun with the same
fingerprint resumes a readable ``.part`` (rows beyond the committed counts are
dropped); an unreadable ``.part`` or one with another fingerprint is discarded.
"""

from __future__ import annotations

import datetime as _dt
import json
import math
import os
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import Any

import h5py
import numpy as np

from pipeline.archive.schema import (
    ACCELERATION,
    FAILURE_COLUMNS,
    FORMAT,
    FORMAT_VERSION,
    HISTORY_ARRAYS,
    HISTORY_INDEX_COLUMNS,
    RESULT_COLUMNS,
    SUMMARY_COLUMNS,
    SUMMARY_RENAMED_V1,
    check_format,
    units_from_name,
)
from pipeline.errors import ArchiveError
from pipeline.screening.cases import Failure, Motion, TowerOutcome

# Hidden ordering columns of the work file (dropped from the final archive).
_ORDER = {"_tower_index": ("i8", "1"), "_case_index": ("i8", "1")}
_TABLES = {
    "results": {**RESULT_COLUMNS, **_ORDER},
    "summary": {**SUMMARY_COLUMNS, "_tower_index": ("i8", "1")},
    "failures": {**FAILURE_COLUMNS, **_ORDER},
    "histories/index": {**HISTORY_INDEX_COLUMNS, **_ORDER},
}
_STR = h5py.string_dtype("utf-8")


def part_path(path: str | Path) -> Path:
    """Return the work file of an archive: ``OUT`` + ``.part``."""
    path = Path(path)
    return path.with_name(path.name + ".part")


def _h5dtype(kind: str) -> Any:
    return {"str": _STR, "f8": "f8", "i8": "i8", "bool": "?"}[kind]


def _create_table(group: h5py.Group, columns: dict[str, tuple[str, str]]) -> None:
    for name, (kind, units) in columns.items():
        ds = group.create_dataset(
            name, shape=(0,), maxshape=(None,), dtype=_h5dtype(kind), chunks=(1024,)
        )
        ds.attrs["units"] = units


def _columns(group: h5py.Group) -> list[tuple[str, h5py.Dataset, bool]]:
    """Return ``(name, dataset, is_text)`` of every column of a table group."""
    return [(name, group[name], group[name].dtype == _STR) for name in group]


def _append_table(
    group: h5py.Group | list[tuple[str, h5py.Dataset, bool]],
    rows: Sequence[dict[str, Any]],
    n: int,
) -> int:
    """Write ``rows`` after the first ``n`` rows of every column; return the new count.

    ``group`` may be the table's group or its :func:`_columns` (looked up once per run:
    the per-chunk lookups of datasets and dtypes were most of the writer's time).
    """
    if not rows:
        return n
    columns = _columns(group) if isinstance(group, h5py.Group) else group
    for name, ds, is_text in columns:
        ds.resize((n + len(rows),))
        ds[n:] = np.asarray([row[name] for row in rows], dtype=object if is_text else None)
    return n + len(rows)


def _read_table(group: h5py.Group, n: int | None = None) -> dict[str, np.ndarray]:
    out = {}
    for name in group:
        ds = group[name]
        if not isinstance(ds, h5py.Dataset):
            continue
        data = ds.asstr()[:] if h5py.check_string_dtype(ds.dtype) else ds[:]
        out[name] = data if n is None else data[:n]
    return out


class ArchiveWriter:
    """Writes one campaign archive through its ``.part`` work file.

    Parameters
    ----------
    path : str or Path
        Final archive path.
    fingerprint : str
        Hash of the inputs and configuration (:func:`pipeline.screening.campaign.fingerprint`).
    metadata : dict
        Root attributes (command line, version, config TOML, ...).
    towers_table : numpy.ndarray
        :func:`stations.inventory.inventory_table` of the inventory.
    motions : dict
        Record id -> :class:`pipeline.screening.campaign.Motion` (stored under /records).
    failures : sequence of Failure
        Failures known before solving (reading, processing, pairing).

    Attributes
    ----------
    done : set of str
        Ids of the towers already in the work file (resumed ones included).
    resumed : bool
        Whether an earlier ``.part`` was resumed.
    """

    def __init__(
        self,
        path: str | Path,
        *,
        fingerprint: str,
        metadata: dict[str, Any],
        towers_table: np.ndarray,
        motions: dict[str, Motion],
        failures: Sequence[Failure] = (),
    ) -> None:
        self.path = Path(path)
        self.part = part_path(self.path)
        self.fingerprint = fingerprint
        self.done: set[str] = set()
        self.resumed = False
        self._committed: dict[str, int] = {}
        self._file: h5py.File | None = None
        self._tables: dict[str, list[tuple[str, h5py.Dataset, bool]]] = {}
        if self._try_resume():
            return
        self.part.unlink(missing_ok=True)
        with h5py.File(self.part, "w") as f:
            _write_static(f, metadata, fingerprint, towers_table, motions)
            for name, columns in _TABLES.items():
                _create_table(f.require_group(name), columns)
            hist = f["histories"]
            for name, (dtype, units) in HISTORY_ARRAYS.items():
                ds = hist.create_dataset(
                    name,
                    shape=(0,),
                    maxshape=(None,),
                    dtype=dtype,
                    chunks=(16384,),
                    compression="gzip",
                    compression_opts=4,
                    shuffle=True,
                )
                ds.attrs["units"] = units
            self._committed = {name: 0 for name in (*_TABLES, "histories/data")}
            rows = [
                {**fl.as_row(), "_tower_index": -1, "_case_index": i}
                for i, fl in enumerate(failures)
            ]
            self._committed["failures"] = _append_table(f["failures"], rows, 0)
            f.attrs["committed"] = json.dumps(self._committed)
            f.attrs["complete"] = False

    def _try_resume(self) -> bool:
        if not self.part.exists():
            return False
        try:
            with h5py.File(self.part, "r") as f:
                if f.attrs.get("fingerprint") != self.fingerprint:
                    return False
                committed = json.loads(f.attrs["committed"])
                ids = f["summary/id"].asstr()[: committed["summary"]]
        except (OSError, KeyError, ValueError):
            return False  # unreadable or foreign: discarded by the caller
        self._committed = committed
        self.done = set(ids)
        self.resumed = True
        return True

    def __enter__(self) -> ArchiveWriter:
        self._file = h5py.File(self.part, "r+")
        # Rows written after the last commit (a kill mid-append) are dropped.
        for name in _TABLES:
            group = self._file[name]
            for column in group:
                group[column].resize((self._committed[name],))
        for name in HISTORY_ARRAYS:
            self._file["histories"][name].resize((self._committed["histories/data"],))
        self._tables = {name: _columns(self._file[name]) for name in _TABLES}
        return self

    def __exit__(self, *exc_info: object) -> None:
        self._tables = {}
        if self._file is not None:
            self._file.close()
            self._file = None

    def append(self, outcomes: Iterable[TowerOutcome]) -> None:
        """Append one chunk of tower outcomes, commit the row counts and flush."""
        f = self._file
        if f is None:
            raise ArchiveError("the archive writer is not open (use it in a with block)")
        outcomes = list(outcomes)
        results, summaries, failures, index = [], [], [], []
        arrays: dict[str, list[np.ndarray]] = {name: [] for name in HISTORY_ARRAYS}
        start = self._committed["histories/data"]
        for outcome in outcomes:
            for i, row in enumerate(outcome.rows):
                results.append({**row, "_tower_index": outcome.index, "_case_index": i})
            summary = {SUMMARY_RENAMED_V1.get(k, k): v for k, v in outcome.summary.items()}
            summaries.append({**summary, "_tower_index": outcome.index})
            for i, failure in enumerate(outcome.failures):
                failures.append(
                    {**failure.as_row(), "_tower_index": outcome.index, "_case_index": i}
                )
            for i, h in enumerate(outcome.histories):
                index.append(
                    {
                        "tower_id": h.tower_id,
                        "record_id": h.record_id,
                        "component": h.component,
                        "model": h.model,
                        "alpha_rad": h.alpha,
                        "start": start,
                        "count": len(h.t),
                        "_tower_index": outcome.index,
                        "_case_index": i,
                    }
                )
                start += len(h.t)
                for name in HISTORY_ARRAYS:
                    arrays[name].append(getattr(h, name))
        c = self._committed
        tables = self._tables
        c["results"] = _append_table(tables["results"], results, c["results"])
        c["failures"] = _append_table(tables["failures"], failures, c["failures"])
        c["histories/index"] = _append_table(tables["histories/index"], index, c["histories/index"])
        n = c["histories/data"]
        if start > n:
            for name, (dtype, _) in HISTORY_ARRAYS.items():
                ds = f["histories"][name]
                ds.resize((start,))
                ds[n:start] = np.concatenate(arrays[name]).astype(dtype)
        c["histories/data"] = start
        # The summary goes last: a tower counts as done only once its rows are in.
        c["summary"] = _append_table(tables["summary"], summaries, c["summary"])
        f.attrs["committed"] = json.dumps(c)
        f.flush()
        self.done.update(outcome.tower_id for outcome in outcomes)

    def finalize(self) -> Path:
        """Write the sorted final archive and move it to its path atomically.

        Returns
        -------
        Path
            The final archive.
        """
        if self._file is not None:
            self._file.close()
            self._file = None
        tmp = self.path.with_name(self.path.name + ".tmp")
        tmp.unlink(missing_ok=True)
        with h5py.File(self.part, "r") as src, h5py.File(tmp, "w") as dst:
            _write_final(src, dst, self._committed)
        os.replace(tmp, self.path)
        self.part.unlink(missing_ok=True)
        return self.path


def _write_static(
    f: h5py.File,
    metadata: dict[str, Any],
    fingerprint: str,
    towers_table: np.ndarray,
    motions: dict[str, Motion],
) -> None:
    f.attrs["format"] = FORMAT
    f.attrs["format_version"] = FORMAT_VERSION
    f.attrs["fingerprint"] = fingerprint
    for key, value in metadata.items():
        f.attrs[key] = value if isinstance(value, str | int | float | bool) else json.dumps(value)
    towers = f.create_group("towers")
    towers.attrs["description"] = "tower inventory; NaN = value absent"
    for name in towers_table.dtype.names:
        column = towers_table[name]
        if column.dtype.kind == "S":
            data = np.asarray([cell.decode("utf-8") for cell in column], dtype=object)
            ds = towers.create_dataset(name, data=data, dtype=_STR)
        else:
            ds = towers.create_dataset(name, data=column)
        ds.attrs["units"] = units_from_name(name)
    records = f.create_group("records")
    records.attrs["description"] = f"processed records as solved ({ACCELERATION})"
    for record_id in sorted(motions):
        motion = motions[record_id]
        group = records.create_group(record_id)
        group.attrs["station"] = motion.station
        group.attrs["dt"] = motion.dt
        group.attrs["dt_units"] = "s"
        group.attrs["latitude"] = math.nan if motion.latitude is None else motion.latitude
        group.attrs["longitude"] = math.nan if motion.longitude is None else motion.longitude
        group.attrs["coordinates_units"] = "deg"
        group.attrs["channels"] = json.dumps(list(motion.channels))
        group.attrs["azimuths"] = json.dumps(list(motion.azimuths))
        for key, value in motion.info.items():
            group.attrs[key] = value if isinstance(value, str) else json.dumps(value, default=str)
        names = list(motion.channels) + [motion.info.get("vertical_channel", "vertical")]
        for name, data in zip(names, (*motion.horizontals, motion.vertical), strict=False):
            if data is None:
                continue
            ds = group.create_dataset(name or "h", data=np.asarray(data, dtype=float))
            ds.attrs["units"] = ACCELERATION


def _write_final(src: h5py.File, dst: h5py.File, committed: dict[str, int]) -> None:
    for key, value in src.attrs.items():
        if key not in {"committed", "complete"}:
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


# --------------------------------------------------------------------------- readers


def _open(path: str | Path) -> h5py.File:
    path = Path(path)
    if not path.is_file():
        raise ArchiveError(f"archive {str(path)!r} does not exist")
    try:
        f = h5py.File(path, "r")
    except OSError as exc:
        raise ArchiveError(f"{str(path)!r} is not a readable HDF5 file: {exc}") from exc
    try:
        check_format(f, path)
    except BaseException:
        f.close()
        raise
    return f


def _python(value: Any) -> Any:
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.floating):
        return float(value)
    return value


def _rows(group: h5py.Group) -> list[dict[str, Any]]:
    table = _read_table(group)
    names = [name for name in table if not name.startswith("_")]
    n = len(table[names[0]]) if names else 0
    return [{name: _python(table[name][i]) for name in names} for i in range(n)]


def read_summary(path: str | Path) -> list[dict[str, Any]]:
    """Return the per-tower summary of an archive, in inventory order.

    Parameters
    ----------
    path : str or Path
        A complete archive.

    Returns
    -------
    list of dict
        One dict per tower with the keys of ``pipeline.screening.campaign.SUMMARY_COLUMNS``
        (``safety_factor`` is ``inf`` when nothing up to the cap overturned, NaN when
        not searched; ``lat``/``lon`` NaN when unknown).

    Raises
    ------
    ArchiveError
        If the file is missing or not a rockscreen archive.
    """
    with _open(path) as f:
        return _rows(f["summary"])


def read_results(path: str | Path) -> list[dict[str, Any]]:
    """Return every tower-record-component-model row of an archive (``/results``)."""
    with _open(path) as f:
        return _rows(f["results"])


def read_failures(path: str | Path) -> list[dict[str, Any]]:
    """Return the failures table of an archive: ``kind``, ``subject``, ``reason``."""
    with _open(path) as f:
        return _rows(f["failures"])


def read_metadata(path: str | Path) -> dict[str, Any]:
    """Return the root attributes of an archive (version, config, command line, ...)."""
    with _open(path) as f:
        meta = {key: _python(value) for key, value in f.attrs.items()}
        meta["n_cases"] = int(f["results/tower_id"].shape[0])
        meta["n_failures"] = int(f["failures/kind"].shape[0])
    return meta


def read_histories(path: str | Path, tower_id: str) -> list[dict[str, Any]]:
    """Return the stored time histories of one tower.

    Parameters
    ----------
    path : str or Path
        A complete archive.
    tower_id : str
        The tower.

    Returns
    -------
    list of dict
        Keys ``record_id``, ``component``, ``model``, ``alpha_rad`` [rad] and arrays
        ``t`` [s], ``theta`` [rad], ``u`` [m], ``regime``; in record, component,
        model order. Empty when the archive keeps no histories for the tower.

    Raises
    ------
    ArchiveError
        If the tower is not in the archive.
    """
    with _open(path) as f:
        ids = set(f["summary/id"].asstr()[:])
        if tower_id not in ids:
            shown = ", ".join(sorted(ids)[:10])
            raise ArchiveError(f"tower {tower_id!r} is not in {str(path)!r} (towers: {shown}...)")
        index = _read_table(f["histories/index"])
        out = []
        for i in np.flatnonzero(index["tower_id"] == tower_id):
            s, c = int(index["start"][i]), int(index["count"][i])
            item = {name: str(index[name][i]) for name in ("record_id", "component", "model")}
            item["alpha_rad"] = float(index["alpha_rad"][i])
            for name in HISTORY_ARRAYS:
                item[name] = f["histories"][name][s : s + c]
            out.append(item)
    return out


def archive_tree(path: str | Path) -> list[str]:
    """Return the archive's tree, one line per group or dataset with shape and units.

    Record groups and table columns are listed in full; the output is meant for
    ``rockscreen inspect``.
    """
    lines: list[str] = []
    with _open(path) as f:

        def visit(name: str, obj: Any) -> None:
            depth = name.count("/")
            label = name.rsplit("/", 1)[-1]
            if isinstance(obj, h5py.Dataset):
                units = obj.attrs.get("units", "")
                unit_text = f" [{units}]" if units else ""
                lines.append(f"{'  ' * depth}{label}  {obj.shape} {obj.dtype}{unit_text}")
            else:
                lines.append(f"{'  ' * depth}{label}/")

        lines.append("/")
        f.visititems(visit)
    return lines


def read_stations(path: str | Path) -> list[dict[str, Any]]:
    """Return the stations of an archive's records: ``key``, ``latitude``, ``longitude`` [deg].

    One entry per station (``NET.STA``), sorted by key; coordinates NaN when unknown.
    """
    stations: dict[str, dict[str, Any]] = {}
    with _open(path) as f:
        for record_id in f["records"]:
            attrs = f["records"][record_id].attrs
            key = str(attrs["station"])
            entry = {
                "key": key,
                "latitude": float(attrs["latitude"]),
                "longitude": float(attrs["longitude"]),
            }
            if key not in stations or math.isnan(stations[key]["latitude"]):
                stations[key] = entry
    return [stations[key] for key in sorted(stations)]
