"""The campaign archive (HDF5): layout, crash-safe writing with resume.

The readers live in :mod:`rockscreen.pipeline.archive.reader` (re-exported here); the column specs
and units in :mod:`rockscreen.pipeline.archive.schema`.

Layout, format version 2 (every dataset carries a ``units`` attribute, UDUNITS
spelling: ``""`` for text, flags and codes, ``"1"`` for dimensionless numbers)::

    /                       attrs: format="rockscreen-archive", format_version,
                            rockscreen_version, created_utc, command_line,
                            config_toml (resolved configuration), fingerprint,
                            inventory_source, n_towers, n_records
    /towers/<column>        the tower inventory, every column of the inventory's
                            registry (id, name, comune, provincia, lat_deg [deg],
                            lon_deg [deg], azimuth_deg [deg], width_m [m], height_m [m],
                            depth_m [m], eta [1], tower_mass_kg [kg], mu_s [1], ...,
                            wall_thickness_m [m], wall_thickness_top_m [m], masonry_type,
                            masonry_strength_mpa [MPa], knowledge_level,
                            gable_height_m [m], ..., gable_axis;
                            NaN or "" = absent; rockscreen.pipeline.archive.schema.TOWER_COLUMNS)
    /records/<record_id>/   one group per processed record; attrs: station, dt [s],
                            starttime, latitude/longitude [deg], channels (JSON),
                            azimuths (JSON, deg), files (JSON), formats (JSON),
                            provenance (JSON)
        <component>         processed acceleration [m/s2] per channel (h1, h2, z roles
                            named by their channel codes)
    /results/<column>       one row per tower-record-component-model case
                            (rockscreen.pipeline.archive.schema.RESULT_COLUMNS, with units)
    /summary/<column>       one row per tower (rockscreen.pipeline.archive.schema.SUMMARY_COLUMNS;
                            lat_deg, lon_deg [deg])
    /failures/<column>      kind (read|process|pair|solve), subject, reason
    /histories/index/<col>  tower_id, record_id (the channel id of the component,
                            IT.AQV..HNX), component, model, alpha_rad [rad],
                            start, count: rows [start, start+count) of the arrays below
    /histories/t            [s]   float32
    /histories/theta        [rad] float32 tower rotation
    /histories/u            [m]   float32 building slip (0 for single-block models)
    /histories/regime       [""]  int8 code: 0 rest, 1 tower rocking, 2 building sliding, 3 both

Crash safety and resume: the writer works on ``OUT.part`` beside ``OUT``, appends each
chunk, records the committed row counts in a root attribute and flushes. Only a
complete run is rewritten, sorted (towers in inventory order, cases in record,
component, model order), into ``OUT.tmp`` and moved to ``OUT`` by
:func:`rockscreen.pipeline.archive.atomic.atomic_path`, so ``OUT`` is either absent or complete.
A rerun with the same fingerprint resumes a ``.part`` only after a child process has
read every committed row of it (:func:`rockscreen.pipeline.archive.resume.verify_part`: a damaged
file that crashes libhdf5 kills the child, not the run); rows beyond the committed
counts are dropped; a damaged ``.part`` or one with another fingerprint is discarded
(:attr:`ArchiveWriter.discarded` says why). Before each chunk and before finalising the
writer checks the free disk space; a full disk ends the run with one
:class:`~rockscreen.pipeline.errors.ArchiveError` line naming the file and the space needed, the
``.part`` kept only if a check finds it sound.
"""

from __future__ import annotations

import contextlib
import json
import math
import shutil
from collections.abc import Iterable, Iterator, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import h5py
import numpy as np

from rockscreen.pipeline.archive import reader
from rockscreen.pipeline.archive.atomic import atomic_path
from rockscreen.pipeline.archive.finalize import write_final
from rockscreen.pipeline.archive.inventory_group import write_inventory_group
from rockscreen.pipeline.archive.reader import *  # noqa: F403  (the readers, re-exported: reader.__all__)
from rockscreen.pipeline.archive.resume import PartFile, is_disk_full, part_path, verify_part
from rockscreen.pipeline.archive.schema import (
    ACCELERATION,
    FAILURE_COLUMNS,
    FORMAT,
    FORMAT_VERSION,
    HISTORY_ARRAYS,
    HISTORY_INDEX_COLUMNS,
    RESULT_COLUMNS,
    SUMMARY_COLUMNS,
    SUMMARY_RENAMED_V1,
)
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.text import printable, storable
from rockscreen.pipeline.vocabulary import channel_id

if TYPE_CHECKING:  # the writer stores them; importing screening would load ObsPy and scipy
    from rockscreen.pipeline.engine.motion import GroundMotion
    from rockscreen.pipeline.engine.results import Failure, TowerOutcome

__all__ = ["ArchiveWriter", "part_path", *reader.__all__]

# Hidden ordering columns of the work file (dropped from the final archive).
_ORDER = {"_tower_index": ("i8", "1"), "_case_index": ("i8", "1")}
_TABLES = {
    "results": {**RESULT_COLUMNS, **_ORDER},
    "summary": {**SUMMARY_COLUMNS, "_tower_index": ("i8", "1")},
    "failures": {**FAILURE_COLUMNS, **_ORDER},
    "histories/index": {**HISTORY_INDEX_COLUMNS, **_ORDER},
}
_STR = h5py.string_dtype("utf-8")
# Disk-space estimates: bytes per history sample (t, theta, u float32 + regime int8,
# before compression) and per table row; a spare margin for HDF5 metadata.
_SAMPLE_BYTES = 13
_ROW_BYTES = 400
_SPARE_BYTES = 1 << 20


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


class ArchiveWriter(PartFile):
    """Writes one campaign archive through its ``.part`` work file.

    Parameters
    ----------
    path : str or Path
        Final archive path.
    fingerprint : str
        Hash of the inputs and configuration (:func:`pipeline.screening.campaign.fingerprint`).
    metadata : dict
        Root attributes (command line, version, config TOML, ``n_towers``, ...).
    towers_table : numpy.ndarray
        :func:`rockscreen.stations.inventory.inventory_table` of the inventory.
    motions : dict
        Record id -> :class:`rockscreen.pipeline.screening.cases.Motion` (stored under /records).
    failures : sequence of Failure
        Failures known before solving (reading, processing, pairing).

    Attributes
    ----------
    done : set of str
        Ids of the towers already in the work file (resumed ones included).

    The rest (``part``, ``resumed``, ``discarded``, e.g. ``"reading it crashed the HDF5
    library (SIGSEGV)"``, ``write_failed`` on a full disk, :meth:`remove`) is
    :class:`~rockscreen.pipeline.archive.resume.PartFile`'s.

    Raises
    ------
    ArchiveError
        When the disk is full (one line naming the file and the space needed).
    """

    def __init__(
        self,
        path: str | Path,
        *,
        fingerprint: str,
        metadata: dict[str, Any],
        towers_table: np.ndarray,
        motions: dict[str, GroundMotion],
        failures: Sequence[Failure] = (),
    ) -> None:
        super().__init__(path)
        self.fingerprint = fingerprint
        self.done: set[str] = set()
        self._n_towers = len(towers_table)
        self._static_bytes = 0
        self._committed: dict[str, int] = {}
        self._tables: dict[str, list[tuple[str, h5py.Dataset, bool]]] = {}
        if self._try_resume():
            return
        self.part.unlink(missing_ok=True)
        with self._disk_full_guard(created=True):
            self._create(metadata, towers_table, motions, failures)

    def _create(
        self,
        metadata: dict[str, Any],
        towers_table: np.ndarray,
        motions: dict[str, GroundMotion],
        failures: Sequence[Failure],
    ) -> None:
        with h5py.File(self.part, "w") as f:
            _write_static(f, metadata, self.fingerprint, towers_table, motions)
            for name, columns in _TABLES.items():
                _create_table(f.require_group(name), columns)
            hist = f["histories"]
            for name, (dtype, units) in HISTORY_ARRAYS.items():
                ds = hist.create_dataset(
                    name,
                    shape=(0,),
                    maxshape=(None,),
                    dtype=dtype,
                    # Uncompressed in the work file: a compressed chunk is re-encoded and may
                    # move on every append, so a kill during that write can tear samples
                    # already committed (seen once in 24 audit kills); an uncompressed
                    # chunk keeps its place and the committed bytes are rewritten as they
                    # were. The final archive is compressed (finalize.write_final).
                    chunks=(16384,),
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
            f.flush()
            self._static_bytes = self.part.stat().st_size
            f.attrs["static_bytes"] = self._static_bytes

    def _try_resume(self) -> bool:
        """Resume a sound ``.part`` of the same inputs; return whether one was resumed."""
        if not self.part.exists():
            return False
        verdict, reason = verify_part(self.part, self.fingerprint)
        if verdict is None:
            self.discarded = reason
            return False
        committed = verdict["committed"]
        try:
            with h5py.File(self.part, "r+") as f:
                # Rows written after the last commit (a kill mid-append) are dropped.
                for name in _TABLES:
                    group = f[name]
                    for column in group:
                        group[column].resize((committed[name],))
                for name in HISTORY_ARRAYS:
                    f["histories"][name].resize((committed["histories/data"],))
                self._static_bytes = int(f.attrs.get("static_bytes", 0))
        except (OSError, KeyError, ValueError, RuntimeError) as exc:
            self.discarded = f"it could not be reopened for writing ({str(exc)[:120]})"
            return False
        self._committed = committed
        self.done = set(verdict["done"])
        self.resumed = True
        return True

    def __enter__(self) -> ArchiveWriter:
        super().__enter__()
        self._tables = {name: _columns(self._file[name]) for name in _TABLES}
        return self

    def _close(self) -> None:
        self._tables = {}
        super()._close()

    @property
    def n_done(self) -> int:
        """Towers in the work file (resumed ones included)."""
        return len(self.done)

    def append(self, outcomes: Iterable[TowerOutcome]) -> None:
        """Append one chunk of tower outcomes, commit the row counts and flush.

        Raises
        ------
        ArchiveError
            When the disk has too little space left for the chunk.
        """
        if self._file is None:
            raise ArchiveError("the archive writer is not open (use it in a with block)")
        outcomes = list(outcomes)
        samples = sum(len(h.t) for o in outcomes for h in o.histories)
        rows = sum(len(o.rows) + len(o.histories) + 1 for o in outcomes)
        self._ensure_space(2 * (samples * _SAMPLE_BYTES + rows * _ROW_BYTES), "the next chunk")
        with self._disk_full_guard():
            self._append(outcomes)
        self.done.update(outcome.tower_id for outcome in outcomes)

    def _append(self, outcomes: list[TowerOutcome]) -> None:
        f = self._file
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
                        "record_id": channel_id(h.record_id, h.component),
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

    def finalize(self) -> Path:
        """Write the sorted final archive and move it to its path atomically.

        Returns
        -------
        Path
            The final archive.

        Raises
        ------
        ArchiveError
            When the disk has no room for the final archive (the ``.part`` is kept).
        """
        self._close()
        self._ensure_space(int(self.part.stat().st_size * 1.1), "the final archive")
        with self._disk_full_guard(final=True):
            with atomic_path(self.path, suffix=".tmp") as tmp:
                with h5py.File(self.part, "r") as src, h5py.File(tmp, "w") as dst:
                    write_final(src, dst, self._committed)
        self.part.unlink(missing_ok=True)
        return self.path

    # ----------------------------------------------------------------- full disk

    def _needed_bytes(self) -> int:
        """Estimate the free space the rest of the run needs: rest of .part + final copy."""
        try:
            size = self.part.stat().st_size
        except OSError:
            size = 0
        static = min(self._static_bytes, size)
        per_tower = (size - static) / max(len(self.done), 1)
        projected = max(size, static + per_tower * max(self._n_towers, 1))
        return int(projected - size + projected * 1.1)

    def _ensure_space(self, needed: int, what: str) -> None:
        free = shutil.disk_usage(self.part.parent).free
        if free >= needed + _SPARE_BYTES:
            return
        self._close()
        self.write_failed = True
        raise ArchiveError(self._full_message(free, what, kept=self.part.exists()))

    def _full_message(self, free: int, what: str, *, kept: bool) -> str:
        fate = (
            f"the partial archive {printable(str(self.part))} is kept: rerun to resume"
            if kept
            else "no partial archive is kept"
        )
        return (
            f"{printable(str(self.path))}: not enough disk space for {what} "
            f"({free / 1e6:.1f} MB free; the run needs about "
            f"{(self._needed_bytes() + _SPARE_BYTES) / 1e6:.0f} MB more); {fate}"
        )

    @contextlib.contextmanager
    def _disk_full_guard(self, *, created: bool = False, final: bool = False) -> Iterator[None]:
        """Turn a write failing on a full disk into one ArchiveError line."""
        try:
            yield
        except (OSError, RuntimeError) as exc:
            if not is_disk_full(exc):
                raise
            self._close()
            self.write_failed = True
            free = shutil.disk_usage(self.part.parent).free
            kept = False
            if not created and self.part.exists():
                kept = final or verify_part(self.part, self.fingerprint)[0] is not None
                if not kept:
                    self.part.unlink(missing_ok=True)
            else:
                self.part.unlink(missing_ok=True)
            what = "the final archive" if final else "the archive"
            raise ArchiveError(self._full_message(free, what, kept=kept)) from exc


def _write_static(
    f: h5py.File,
    metadata: dict[str, Any],
    fingerprint: str,
    towers_table: np.ndarray,
    motions: dict[str, GroundMotion],
) -> None:
    f.attrs["format"] = FORMAT
    f.attrs["format_version"] = FORMAT_VERSION
    f.attrs["fingerprint"] = fingerprint
    for key, value in metadata.items():
        if not isinstance(value, str | int | float | bool):
            value = json.dumps(value)
        # storable(): a non-UTF-8 file name in the command line or the record list.
        f.attrs[key] = storable(value) if isinstance(value, str) else value
    write_inventory_group(f, "towers", towers_table)
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
