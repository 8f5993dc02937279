"""The assess and scenario archives (HDF5): the readers.

Every reader opens the file through one door (:func:`open_risk_archive`), which checks
``format``, ``kind`` and ``format_version``, the tree (no external links, external or virtual
storage: :mod:`rockscreen.pipeline.archive.safety`) and every table (:func:`check_risk_tables`),
and refuses anything else in one line. The layout, its units and the writer are in
:mod:`rockscreen.pipeline.archive.risk_archive`.
"""

from __future__ import annotations

import json
import math
import os
from pathlib import Path
from typing import Any

import h5py

from rockscreen.pipeline.archive.inventory_group import with_absent_columns
from rockscreen.pipeline.archive.long_pivot import pivot_summary, read_long_tables, stored_checks
from rockscreen.pipeline.archive.long_schema import CheckColumns
from rockscreen.pipeline.archive.reader import python_scalar
from rockscreen.pipeline.archive.record_store import concatenated_records, record_groups
from rockscreen.pipeline.archive.risk_archive import (
    COORDINATE_RANGES,
    FORMAT,
    KINDS,
    READ_VERSIONS,
    REQUIRED_COLUMNS,
    TABLE_NAMES,
    TABLES,
)
from rockscreen.pipeline.archive.risk_schema import RISK_TABLES
from rockscreen.pipeline.archive.safety import (
    check_attribute_sizes,
    check_tree,
    closed_on_failure,
    read_column,
    read_table,
    reading,
)
from rockscreen.pipeline.archive.schema import TEXT
from rockscreen.pipeline.archive.table_checks import check_tables
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.text import printable
from rockscreen.pipeline.verdict.messages import message, render
from rockscreen.pipeline.verdict.scales import Completeness, scenario_class_of
from rockscreen.pipeline.verdict.status import Bound

__all__ = [
    "check_risk_tables",
    "column_order",
    "legacy_completeness",
    "open_risk_archive",
    "read_checks",
    "read_failures",
    "read_ida",
    "read_risk_table",
    "read_inventory",
    "read_metadata",
    "read_outcomes",
    "read_records",
    "read_selection",
    "read_set_records",
    "read_stripes",
    "read_summary",
    "summary_rows",
]


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


def open_risk_archive(path: str | Path, kind: str | None = None) -> h5py.File:
    """Open an assess or scenario archive for reading, checked (module docstring).

    Parameters
    ----------
    path : str or Path
        The archive.
    kind : {"assess", "scenario"}, optional
        The kind required; None: either.

    Returns
    -------
    h5py.File
        Open read-only; the caller closes it.

    Raises
    ------
    ArchiveError
        One line naming the file and what is wrong.
    """
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
    elif version not in READ_VERSIONS[found_kind]:
        read = " and ".join(repr(v) for v in READ_VERSIONS[found_kind])
        problem = (
            f"has format_version {version!r}; this rockscreen reads {found_kind} "
            f"archives of version {read} only"
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
    for column in order:  # text as str, whether stored coded, fixed or variable-length
        data[column] = read_column(group[column], f.filename, f"{name}/{column}")
    n = len(next(iter(data.values()))) if data else 0
    return [{c: python_scalar(v[i]) for c, v in data.items()} for i in range(n)]


def summary_rows(f: h5py.File) -> list[dict[str, Any]]:
    """Return the wide summary rows of an open, checked assess or scenario archive.

    Format 4 of assess: ``/summary`` and the long tables pivoted back into one row per
    tower (:func:`~rockscreen.pipeline.archive.long_pivot.pivot_summary`); an older
    archive (no ``/pivot``: its ``/summary`` is the wide row) and a scenario archive as
    stored, the one adapter of the older layout. ArchiveError (one line naming the file)
    for long tables that do not pivot (a row pointing at no tower, a field not stored).
    """
    rows = _rows(f, "summary")
    if "pivot" not in f:
        return rows
    try:
        return pivot_summary(rows, read_long_tables(f))
    except (KeyError, IndexError, ValueError, TypeError) as exc:
        raise ArchiveError(
            f"{printable(str(f.filename))}: the long tables /fits, /checks, /messages and "
            f"/pivot do not pivot into the summary ({type(exc).__name__}: "
            f"{printable(str(exc))[:80]})"
        ) from None


def read_summary(path: str | Path, kind: str | None = None) -> list[dict[str, Any]]:
    """Return the per-tower summary rows (inventory order) of an assess or scenario archive.

    The wide rows, one per tower (:func:`summary_rows`: format 4's long tables pivoted
    back, the same keys and values as the summary of format 3).

    An assess archive written before the typed verdict has no ``completeness`` and no
    ``governing_check`` column: they are added from ``checks_not_made``
    (:func:`legacy_completeness`) and ``governing_kind`` (its one family of one check,
    ``tower rocking``; the id is left empty for the others, whose check the older archive
    does not name). A scenario archive written before ``class_bound`` held the bound in
    ``risk_class`` (``"high (at most)"``): both are recomputed from ``p_overturning`` and
    ``p_overturning_bound`` by the same rule (:func:`~rockscreen.pipeline.verdict.scales.
    scenario_class_of`).
    """
    with open_risk_archive(path, kind) as f:
        rows = summary_rows(f)
    for row in rows:
        if "checks_not_made" in row and "completeness" not in row:
            row["completeness"] = legacy_completeness(row["checks_not_made"]).value
        if "p_overturning" in row and "class_bound" not in row:  # scenario: plain class
            bound = Bound.parse(row.get("p_overturning_bound", ""))
            cls, side = scenario_class_of(float(row["p_overturning"]), bound)
            row.update(risk_class=cls, class_bound=side.value)
        if "governing_kind" in row and "governing_check" not in row:
            tower = row["governing_kind"] == render(message("family.tower_rocking"))
            row["governing_check"] = "tower.rocking" if tower else ""
    return rows


def read_checks(path: str | Path) -> list[CheckColumns]:
    """Return the checks an assess archive stores, with their wide columns (none: older).

    :func:`~rockscreen.pipeline.archive.long_pivot.stored_checks` of its long tables.
    """
    with open_risk_archive(path) as f:
        return stored_checks(read_long_tables(f))


def legacy_completeness(checks_not_made: str) -> Completeness:
    """Return the completeness of an archive written before the ``completeness`` column.

    The one adapter of older assess archives: their ``checks_not_made`` is the printed
    list of the checks not made, which began with ``"rocking only: "`` when only rigid
    overturning was checked (:func:`rockscreen.pipeline.verdict.rules.not_made_text`);
    newer archives store the word and are never read this way.
    """
    if not checks_not_made:
        return Completeness.COMPLETE
    prefix = render(message("completeness.rocking_only")) + ": "
    if str(checks_not_made).startswith(prefix):
        return Completeness.ROCKING_ONLY
    return Completeness.PARTIAL


def read_stripes(path: str | Path) -> list[dict[str, Any]]:
    """Return the stripe rows of an assess archive (tower, return period [y], ag [g], counts)."""
    with open_risk_archive(path, "assess") as f:
        return _rows(f, "stripes")


def read_outcomes(path: str | Path) -> list[dict[str, Any]]:
    """Return the record x component x model rows of an assess archive."""
    with open_risk_archive(path, "assess") as f:
        return _rows(f, "outcomes")


def read_ida(path: str | Path) -> list[dict[str, Any]]:
    """Return the IDA rows (tower x record x component) of an assess archive ([] if none)."""
    with open_risk_archive(path, "assess") as f:
        return _rows(f, "ida")


def read_risk_table(path: str | Path, table: str) -> list[dict[str, Any]]:
    """Return the rows of a screening-risk table of an assess archive ([] if none).

    Parameters
    ----------
    path : str or Path
    table : {"risk_fragility", "risk_sensitivity", "risk_top_n"}
        ``/risk_fragility`` (tower x ag: the fragility band), ``/risk_sensitivity`` (tower
        x input: first-order index and narrowing), ``/risk_top_n`` (the region's list). An
        archive written before the screening risk lacks them.
    """
    if table not in RISK_TABLES:
        raise ArchiveError(f"screening-risk table {table!r}; allowed: {', '.join(RISK_TABLES)}")
    with open_risk_archive(path, "assess") as f:
        return _rows(f, table)


def read_selection(path: str | Path) -> list[dict[str, Any]]:
    """Return the record-set rows (site x return period) of an assess archive."""
    with open_risk_archive(path, "assess") as f:
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
    with open_risk_archive(path, "assess") as f, reading(path):
        if "inventory" not in f:
            return []
        table = read_table(f["inventory"], path)
    n = len(table["id"])
    rows = [{name: python_scalar(column[i]) for name, column in table.items()} for i in range(n)]
    return with_absent_columns(rows)


def read_records(path: str | Path) -> dict[str, dict[str, Any]]:
    """Return the records of an assess archive's sets, each once ({} if none stored).

    Version 3 keeps them in ``/records/index`` and the concatenated ``/records/{x,y,z}``;
    version 2 one group per record (``/records/<id>/{x,y,z}``), read the same way here
    (the one adapter of the older layout).

    Parameters
    ----------
    path : str or Path
        The assess archive.

    Returns
    -------
    dict
        Record id -> ``{"x", "y", "z"}`` accelerations [m/s²] as float64 (None for an
        absent component), ``"dt_s"`` [s], ``"name"``, ``"source"``; in the stored order.

    Raises
    ------
    ArchiveError
        For a record without a positive ``dt_s``, samples that are not 1-D floats in m/s2,
        or a record index pointing outside them (one line naming the file).
    """
    with open_risk_archive(path, "assess") as f, reading(path):
        top = f.get("records")
        if not isinstance(top, h5py.Group):
            return {}
        if "index" in top:
            return concatenated_records(f, top, path)
        return record_groups(top, path)


def read_set_records(path: str | Path) -> list[list[tuple[str, float]]]:
    """Return each record set of an assess archive as references: (record id, factor).

    Parameters
    ----------
    path : str or Path
        The assess archive (version 3).

    Returns
    -------
    list of list of (str, float)
        One list per ``/selection`` row, in its order: the set's records in their order,
        each its id (a key of :func:`read_records`) and its scale factor [-] exactly as the
        towers were computed with (float64).

    Raises
    ------
    ArchiveError
        For an archive of version 2, whose factors are rounded to 6 digits (rebuilt by the
        same ``rockscreen assess`` command), a reference to a set or record not stored, or
        references out of the sets' order (one line naming the file).
    """
    name = printable(os.fspath(path))
    with open_risk_archive(path, "assess") as f, reading(path):
        version = str(python_scalar(f.attrs.get("format_version", "")))
        if "set_records" not in f:
            if version == "2":
                command = str(python_scalar(f.attrs.get("command_line", ""))) or "rockscreen assess"
                raise ArchiveError(
                    f"{name}: an assess archive of format_version '2' keeps its sets' scale "
                    f"factors rounded to 6 digits, not exactly; rebuild it with: {command}"
                )
            return []
        table = read_table(f["set_records"], path)
        columns = list(f["selection"].values()) if "selection" in f else []
        n_sets = columns[0].shape[0] if columns else 0  # the columns' one length (checked)
        ids = read_table(f["records/index"], path)["id"] if "records/index" in f else []
    sets: list[list[tuple[str, float]]] = [[] for _ in range(n_sets)]
    previous = 0
    for s, r, factor in zip(table["set"], table["record"], table["scale_factor"], strict=True):
        if not (previous <= s < n_sets and 0 <= r < len(ids)):
            raise ArchiveError(
                f"{name}: /set_records refers to set {int(s)} or record {int(r)}, not stored "
                "or out of order"
            )
        previous = int(s)
        sets[int(s)].append((str(ids[int(r)]), float(factor)))
    return sets


def read_failures(path: str | Path) -> list[dict[str, Any]]:
    """Return the failures of an assess or scenario archive (kind, subject, reason)."""
    with open_risk_archive(path) as f:
        return _rows(f, "failures")


def read_metadata(path: str | Path) -> dict[str, Any]:
    """Return the root attributes of an assess or scenario archive."""
    with open_risk_archive(path) as f:
        out = {key: python_scalar(value) for key, value in f.attrs.items()}
    return {k: (None if isinstance(v, float) and math.isnan(v) else v) for k, v in out.items()}
