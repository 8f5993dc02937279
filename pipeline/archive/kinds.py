"""One door to every archive: :func:`open_archive` and the registry of archive kinds.

Every archive rockscreen writes is an HDF5 file whose root attributes say what it is:
``format = "rockscreen-archive"``, ``kind`` and ``format_version``. :func:`open_archive`
reads them once, checks the format, the kind and the version once (one
:class:`~rockscreen.pipeline.errors.ArchiveError` line naming the file, what it found and
what this rockscreen reads), checks the whole tree (:func:`~.safety.check_tree`) and
checks the shapes, types and lengths of the kind's tables
(:func:`~.table_checks.check_tables`) and returns a reader of the right kind from
:data:`ARCHIVE_KINDS`:

============  ==================================  ==========================================
kind          root ``kind`` attribute             reader
============  ==================================  ==========================================
``run``       absent (or ``"run"``)               :class:`RunReader` (``rockscreen run``)
``sweep``     ``"sweep"``; ``"rockscreen-sweep"``  :class:`SweepReader` (``rockscreen sweep``)
              without ``format`` (version 1)
``assess``    ``"assess"``                        :class:`AssessReader`
``scenario``  ``"scenario"``                      :class:`ScenarioReader`
============  ==================================  ==========================================

Every reader has the small protocol of :class:`ArchiveReader` (``kind``, ``path``,
``attrs``, ``version``, ``schema``, :meth:`~ArchiveReader.metadata`,
:meth:`~ArchiveReader.summary`, :meth:`~ArchiveReader.failures`,
:meth:`~ArchiveReader.tree`) and the tables of its kind; the commands find what to do
with a reader in :data:`rockscreen.pipeline.report.presenters.PRESENTERS`. A new archive
kind is one reader class here, added to :data:`ARCHIVE_KINDS`, and one presenter there.

The readers' methods call the checked function readers of each kind
(:mod:`.reader`, :mod:`.sweep_archive`, :mod:`.risk_reader`), which stay public.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any, ClassVar

import h5py
import numpy as np

from rockscreen.pipeline.archive import reader as run_archive
from rockscreen.pipeline.archive import risk_archive, risk_reader, sweep_archive
from rockscreen.pipeline.archive.long_schema import CheckColumns
from rockscreen.pipeline.archive.risk_schema import UnitsTable
from rockscreen.pipeline.archive.safety import (
    check_attribute_sizes,
    check_tree,
    open_checked,
    open_hdf5,
    reading,
)
from rockscreen.pipeline.archive.schema import (
    FAILURE_COLUMNS,
    FORMAT,
    HISTORY_ARRAYS,
    HISTORY_INDEX_COLUMNS,
    RESULT_COLUMNS,
    SUMMARY_COLUMNS,
    SUPPORTED_VERSIONS,
    TEXT,
    TOWER_COLUMNS,
    ColumnSpec,
)
from rockscreen.pipeline.archive.table_checks import check_tables
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.text import printable

__all__ = [
    "ARCHIVE_KINDS",
    "ArchiveReader",
    "AssessReader",
    "RunReader",
    "ScenarioReader",
    "SweepReader",
    "archive_kind",
    "open_archive",
]


def _units(columns: ColumnSpec) -> UnitsTable:
    return {name: units for name, (_, units) in columns.items()}


def _text(value: Any) -> str | None:
    """Return a root attribute as text (None when absent or not a scalar text or integer)."""
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    if isinstance(value, np.generic) and value.shape == ():
        value = value.item()
    if isinstance(value, bool) or value is None:
        return None
    if isinstance(value, (str, int)):
        return str(value)
    return None


def _shown(value: str | None) -> str:
    if value is None:
        return "none"
    text = printable(value)
    return repr(text if len(text) <= 40 else text[:37] + "...")


class ArchiveReader:
    """An archive of one kind, checked on open: the protocol the commands use.

    Readers are made by :func:`open_archive`; they hold no open file (each method opens,
    checks and closes it).

    Parameters
    ----------
    path : str or path-like
        The archive, as the user gave it (messages and printed lines show it so).
    attrs : dict
        The root attributes, read once on open (values as h5py returns them).
    version : str
        The format version found (one of :attr:`versions`).
    """

    #: The kind's name (a key of :data:`ARCHIVE_KINDS`).
    kind: ClassVar[str] = ""
    #: Root ``kind`` attribute values of this kind -> the ``format`` attribute each comes
    #: with (None: no ``format`` attribute, a layout older than the common one).
    stored_kinds: ClassVar[Mapping[str, str | None]] = {}
    #: ``format_version`` values this rockscreen reads, oldest first.
    versions: ClassVar[tuple[str, ...]] = ()
    #: Units of every column: table (or array group) -> column -> units (UDUNITS).
    schema: ClassVar[Mapping[str, UnitsTable]] = {}
    #: The tables of :attr:`schema` that are groups of equal-length 1-D columns, checked
    #: on open (:func:`~.table_checks.check_tables`).
    tables: ClassVar[tuple[str, ...]] = ()
    #: Table -> columns it must have, checked on open.
    required: ClassVar[Mapping[str, tuple[str, ...]]] = {}
    #: Whether the open also reads every text column of the tables and refuses invalid
    #: UTF-8 (small tables that the readers decode strictly).
    decode_on_open: ClassVar[bool] = False
    #: Column -> (low, high) its numbers must lie in, checked on open with the decoding.
    ranges: ClassVar[Mapping[str, tuple[float, float]]] = {}

    def __init__(self, path: str | os.PathLike, attrs: dict[str, Any], version: str) -> None:
        self.path = path
        self.attrs = attrs
        self.version = version

    @classmethod
    def check_tables(cls, f: h5py.File, path: str | os.PathLike) -> None:
        """Check the kind's tables in an open file (:func:`~.table_checks.check_tables`).

        Raises
        ------
        ArchiveError
            One line naming the file, the table and the column.
        """
        check_tables(
            f,
            path,
            {table: cls.schema.get(table, {}) for table in cls.tables},
            cls.required,
            text=TEXT,
            decode=cls.decode_on_open,
            present=[table for table in cls.tables if table == "summary"],
            ranges=cls.ranges,
        )

    def __repr__(self) -> str:
        return f"{type(self).__name__}({os.fspath(self.path)!r}, version={self.version!r})"

    def metadata(self) -> dict[str, Any]:
        """Return the root attributes as Python values (what ``inspect`` prints)."""
        raise NotImplementedError

    def summary(self) -> list[dict[str, Any]]:
        """Return the rows of the archive's main table (one per tower; a sweep's cases)."""
        raise NotImplementedError

    def failures(self) -> list[dict[str, Any]]:
        """Return the failures table: ``kind``, ``subject``, ``reason`` (empty if none)."""
        return []

    def tree(self) -> list[str]:
        """Return the archive's tree, one line per group or dataset with shape and units."""
        with open_checked(self.path) as f:
            return run_archive.tree_of(f)


class RunReader(ArchiveReader):
    """A campaign archive (``rockscreen run``): :mod:`rockscreen.pipeline.archive.campaign`."""

    kind = "run"
    stored_kinds = {"": FORMAT, "run": FORMAT}
    versions = SUPPORTED_VERSIONS
    schema = {
        "summary": _units(SUMMARY_COLUMNS),
        "results": _units(RESULT_COLUMNS),
        "failures": _units(FAILURE_COLUMNS),
        "towers": _units(TOWER_COLUMNS),
        "histories/index": _units(HISTORY_INDEX_COLUMNS),
        "histories": {name: units for name, (_, units) in HISTORY_ARRAYS.items()},
    }
    tables = ("summary", "results", "failures", "towers", "histories/index")
    required = {"summary": ("id",)}

    def metadata(self) -> dict[str, Any]:
        """Return the root attributes, with ``n_cases`` and ``n_failures``."""
        return run_archive.read_metadata(self.path)

    def summary(self) -> list[dict[str, Any]]:
        """Return the per-tower summary, in inventory order."""
        return run_archive.read_summary(self.path)

    def failures(self) -> list[dict[str, Any]]:
        """Return the failures table."""
        return run_archive.read_failures(self.path)

    def results(self) -> list[dict[str, Any]]:
        """Return every tower-record-component-model row."""
        return run_archive.read_results(self.path)

    def towers(self) -> list[dict[str, Any]]:
        """Return the stored inventory, one dict per tower (absent: NaN or ``""``)."""
        return run_archive.read_towers(self.path)

    def stations(self) -> list[dict[str, Any]]:
        """Return the stations of the records: ``key``, ``latitude``, ``longitude`` [deg]."""
        return run_archive.read_stations(self.path)

    def histories(self, tower_id: str) -> list[dict[str, Any]]:
        """Return the stored time histories of one tower (``t`` [s], ``theta`` [rad], ...)."""
        return run_archive.read_histories(self.path, tower_id)


class SweepReader(ArchiveReader):
    """A sweep archive (``rockscreen sweep``): :mod:`rockscreen.pipeline.archive.sweep_archive`."""

    kind = "sweep"
    stored_kinds = {sweep_archive.ARCHIVE_KIND: FORMAT, sweep_archive.LEGACY_KIND: None}
    versions = sweep_archive.SUPPORTED_SWEEP_VERSIONS
    schema = {
        "cases": {name: units for name, _, units in sweep_archive.CASE_COLUMNS},
        "histories": dict(sweep_archive.HISTORY_UNITS),
        "tower": dict(sweep_archive.TOWER_UNITS),
    }

    @classmethod
    def check_tables(cls, f: h5py.File, path: str | os.PathLike) -> None:
        """Check ``/cases`` and the histories (:func:`.sweep_archive.check_sweep_tables`).

        A file without ``/cases`` is left to the readers, which refuse it as no sweep
        archive.
        """
        if "cases" in f:
            sweep_archive.check_sweep_tables(f, path)

    def metadata(self) -> dict[str, Any]:
        """Return the root attributes and the ``/tower`` attributes (key ``tower``)."""
        return sweep_archive.read_archive_attrs(self.path)

    def summary(self) -> list[dict[str, Any]]:
        """Return the cases table (one row per case)."""
        return sweep_archive.read_cases(self.path)

    def histories(self) -> dict[int, dict[str, np.ndarray]]:
        """Return every case's histories: case index -> ``t`` [s], ``theta`` [rad], ..."""
        return sweep_archive.read_histories(self.path)


class _RiskReader(ArchiveReader):
    """The tables both risk archives have (:mod:`rockscreen.pipeline.archive.risk_archive`)."""

    required = risk_archive.REQUIRED_COLUMNS
    decode_on_open = True
    ranges = risk_archive.COORDINATE_RANGES

    @classmethod
    def check_tables(cls, f: h5py.File, path: str | os.PathLike) -> None:
        """Check the kind's tables as its function readers do.

        :func:`.risk_reader.check_risk_tables`: the generic check, and the text columns
        of ``/inventory`` hold text.

        Raises
        ------
        ArchiveError
            One line naming the file, the table and the column.
        """
        risk_reader.check_risk_tables(f, path, cls.kind)

    def metadata(self) -> dict[str, Any]:
        """Return the root attributes (NaN as None)."""
        return risk_reader.read_metadata(self.path)

    def summary(self) -> list[dict[str, Any]]:
        """Return the per-tower summary rows, in inventory order."""
        return risk_reader.read_summary(self.path, self.kind)

    def failures(self) -> list[dict[str, Any]]:
        """Return the failures table."""
        return risk_reader.read_failures(self.path)


class AssessReader(_RiskReader):
    """An assess archive (``rockscreen assess``): fragility, risk and LV1 per tower."""

    kind = "assess"
    versions = risk_archive.READ_VERSIONS["assess"]
    stored_kinds = {"assess": FORMAT}
    schema = risk_archive.TABLES["assess"]
    tables = risk_archive.TABLE_NAMES["assess"]

    def checks(self) -> list[CheckColumns]:
        """Return the checks stored (``/checks``) and their wide columns (none: older)."""
        return risk_reader.read_checks(self.path)

    def stripes(self) -> list[dict[str, Any]]:
        """Return the stripe rows (tower, return period [y], ag [g], counts)."""
        return risk_reader.read_stripes(self.path)

    def outcomes(self) -> list[dict[str, Any]]:
        """Return the record x component x model rows."""
        return risk_reader.read_outcomes(self.path)

    def selection(self) -> list[dict[str, Any]]:
        """Return the record-set rows (site x return period)."""
        return risk_reader.read_selection(self.path)

    def ida(self) -> list[dict[str, Any]]:
        """Return the IDA rows (tower x record x component of the set at T_R,SLV)."""
        return risk_reader.read_ida(self.path)

    def inventory(self) -> list[dict[str, Any]]:
        """Return the stored inventory, one dict per tower (none in an older archive)."""
        return risk_reader.read_inventory(self.path)

    def records(self) -> dict[str, dict[str, Any]]:
        """Return the records of the sets by id, each stored once (samples in m/s²)."""
        return risk_reader.read_records(self.path)

    def set_records(self) -> list[list[tuple[str, float]]]:
        """Return each ``/selection`` row's set as (record id, exact scale factor) pairs."""
        return risk_reader.read_set_records(self.path)

    def risk_fragility(self) -> list[dict[str, Any]]:
        """Return the screening risk's fragility bands (tower x ag; none in an older archive)."""
        return risk_reader.read_risk_table(self.path, "risk_fragility")

    def risk_sensitivity(self) -> list[dict[str, Any]]:
        """Return the screening risk's first-order indices (tower x input)."""
        return risk_reader.read_risk_table(self.path, "risk_sensitivity")

    def risk_top_n(self) -> list[dict[str, Any]]:
        """Return the region's top-N list (which survey moves which tower across the line)."""
        return risk_reader.read_risk_table(self.path, "risk_top_n")


class ScenarioReader(_RiskReader):
    """A scenario archive (``rockscreen scenario``): probability of overturning per tower."""

    kind = "scenario"
    versions = risk_archive.READ_VERSIONS["scenario"]
    stored_kinds = {"scenario": FORMAT}
    schema = risk_archive.TABLES["scenario"]
    tables = risk_archive.TABLE_NAMES["scenario"]


#: The registry: kind -> reader class. A new archive kind is one class added here.
ARCHIVE_KINDS: dict[str, type[ArchiveReader]] = {
    cls.kind: cls for cls in (RunReader, SweepReader, AssessReader, ScenarioReader)
}


def _reader_class(stored_kind: str | None) -> type[ArchiveReader] | None:
    key = stored_kind or ""
    return next((cls for cls in ARCHIVE_KINDS.values() if key in cls.stored_kinds), None)


def open_archive(path: str | os.PathLike) -> ArchiveReader:
    """Open any rockscreen archive: check it once and return the reader of its kind.

    Parameters
    ----------
    path : str or path-like
        A run, sweep, assess or scenario archive.

    Returns
    -------
    ArchiveReader
        An instance of the class :data:`ARCHIVE_KINDS` registers for the archive's kind.

    Raises
    ------
    ArchiveError
        One line naming the file: missing, not a regular file, not HDF5, not a rockscreen
        archive (and the format found), an unknown kind (and the kinds this rockscreen
        reads), an unsupported ``format_version`` (and the versions read), a tree that
        reads outside the file (:func:`~rockscreen.pipeline.archive.safety.check_tree`),
        a root text attribute over the size limit, or a malformed table of the kind's
        :attr:`ArchiveReader.tables`
        (:func:`~rockscreen.pipeline.archive.table_checks.check_tables`:
        a table stored as a dataset, a missing required column, a column not 1-D, of
        another length or type, invalid UTF-8 or a coordinate out of range in the risk
        kinds), naming the table and the column.
    """
    name = printable(os.fspath(path))
    f = open_hdf5(Path(path), name)
    with f, reading(path):
        stored_kind, found_format = _text(f.attrs.get("kind")), _text(f.attrs.get("format"))
        version = _text(f.attrs.get("format_version"))
        cls = _reader_class(stored_kind)
        wanted = FORMAT if cls is None else cls.stored_kinds[stored_kind or ""]
        if found_format != wanted:
            raise ArchiveError(
                f"{name}: not a rockscreen archive (format attribute: {_shown(found_format)}; "
                f"this reader takes {FORMAT})"
            )
        if cls is None:
            raise ArchiveError(
                f"{name}: archive kind {_shown(stored_kind)} is not known "
                f"(this rockscreen reads {', '.join(ARCHIVE_KINDS)} archives)"
            )
        if version not in cls.versions:
            raise ArchiveError(
                f"{name}: {cls.kind} archive format_version {_shown(version)} is not supported "
                f"(this rockscreen reads {', '.join(cls.versions)})"
            )
        check_tree(f, path)  # attributes' sizes and types too, before they are read
        check_attribute_sizes(f, path)
        cls.check_tables(f, path)
        attrs = dict(f.attrs.items())
    return cls(path, attrs, version)


def archive_kind(path: str | os.PathLike) -> str:
    """Return the kind of an archive (a key of :data:`ARCHIVE_KINDS`), after the checks.

    Raises
    ------
    ArchiveError
        As :func:`open_archive`.
    """
    return open_archive(path).kind
