"""The assess archive's long tables (format 4): the wide summary rows split into them.

An assess result is one wide row per tower (about 180 columns,
:func:`rockscreen.pipeline.risk.assess.tower_summary.summarize_tower`). Format 4 stores it as
a slim ``/summary`` (the tower's own columns) and long tables, one row per tower x item:

- ``/fits``: one row per tower x fit (``collapse``, ``slv``, ``stripe``, each part model's
  ``<part>.collapse`` and ``<part>.slv``), the columns of ``FIT_FIELDS``;
- ``/checks``: one row per tower x check (each part model's ``<part>.rocking``,
  ``tower.rocking``, the code's checks, the linear kinematic checks beside), the columns of
  ``CHECK_FIELDS``: status, capacity a_C [g], I_S [-], bound, the reason a check was
  not made as a message code and its JSON parameters, and the check's details (units of
  :data:`rockscreen.pipeline.verdict.checks.DETAIL_UNITS`). A tower without a verdict (not
  assessed) has no rows;
- ``/messages``: one row per tower x note, the message code and its JSON parameters
  (``note_codes``: :func:`rockscreen.pipeline.verdict.messages.dumps`);
- ``/pivot``: one row per column of the wide row, in its order: its stored kind
  (``bool``, ``i8``, ``f8``, ``str``: :func:`~rockscreen.pipeline.archive.column_codec.
  stored_kind`) and where its value is (``table``, ``key``, ``field``; ``table`` empty: in
  ``/summary``).

The archive describes itself: :func:`rockscreen.pipeline.archive.long_pivot.pivot_summary`
rebuilds the wide rows (same keys, same order, same values and types as a format-3 archive
gives back) from the stored tables alone, without the registries that wrote them, so an
archive written with a third part model or a new code check reads anywhere. Which columns
move is declared here (the fits) and by the writer's caller (the checks:
:class:`CheckColumns`, from the check registry of
:mod:`rockscreen.pipeline.risk.checks.governing`); a column whose values the long tables
cannot hold exactly stays in ``/summary``. Units are declared once, per field, in
:mod:`rockscreen.pipeline.archive.long_schema` (``FIT_FIELDS``, ``CHECK_FIELDS``, ...).
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import h5py
import numpy as np

from rockscreen.pipeline.archive.column_codec import stored_kind, text_values, write_column
from rockscreen.pipeline.archive.long_pivot import stored_json
from rockscreen.pipeline.archive.long_schema import (
    CHECK_FIELDS,
    FIT_FIELDS,
    LONG_TABLES,
    MESSAGE_FIELDS,
    fit_cells,
)
from rockscreen.pipeline.archive.schema import TEXT
from rockscreen.pipeline.verdict.checks import DETAIL_UNITS
from rockscreen.pipeline.verdict.status import Status

__all__ = [
    "MESSAGE_COLUMNS",
    "NOT_MADE_COLUMN",
    "write_long_tables",
    "CheckColumns",
    "LongSummary",
    "split_summary",
    "stored_checks",
]

#: Summary columns holding a list of messages (:func:`~rockscreen.pipeline.verdict.messages.
#: dumps`) stored one message per row in ``/messages``.
MESSAGE_COLUMNS = ("note_codes",)
#: The summary column of the checks not made and why
#: (:func:`~rockscreen.pipeline.verdict.checks.dumps_not_made`), stored in ``/checks``.
NOT_MADE_COLUMN = "checks_not_made_codes"


@dataclass(frozen=True)
class CheckColumns:
    """Where one check's result is in a wide summary row (the writer's caller declares it)."""

    #: The check's id, ``<part>.<what>``.
    check: str
    part: str
    #: :class:`~rockscreen.pipeline.verdict.checks.Family` value.
    family: str
    #: :class:`~rockscreen.pipeline.verdict.checks.Method` value.
    method: str
    #: The columns of a_C [g], I_S [-] and their bound.
    keys: tuple[str, str, str]
    #: Detail name (:data:`~rockscreen.pipeline.verdict.checks.DETAIL_UNITS`) -> column.
    details: Mapping[str, str] = field(default_factory=dict)


def _check_cells(checks: Sequence[CheckColumns]) -> dict[str, list[tuple[str, str]]]:
    """Return column -> every (check, field) cell it fills (the first one it is read from)."""
    cells: dict[str, list[tuple[str, str]]] = {}
    for c in checks:
        pairs = zip(c.keys, ("capacity_ag_g", "safety_index", "bound"), strict=True)
        for column, name in [*pairs, *((col, name) for name, col in c.details.items())]:
            cells.setdefault(column, []).append((c.check, name))
    return cells


@dataclass
class LongSummary:
    """A wide summary split into its slim ``/summary`` and the long tables (numpy-free rows)."""

    summary: list[dict[str, Any]]
    #: Table -> column -> values (``fits``, ``checks``, ``messages``, ``pivot``).
    tables: dict[str, dict[str, list[Any]]]


def _fits_value(value: Any, units: str) -> bool:
    """Whether a long table's field of ``units`` holds ``value`` exactly."""
    if units == TEXT:
        return value is None or isinstance(value, str)
    return value is None or isinstance(value, (bool, int, float))


def _stored(value: Any, units: str) -> Any:
    if units == TEXT:
        return "" if value is None else value
    return math.nan if value is None else float(value)


def _message_items(text: Any) -> list[list[Any]] | None:
    """Return a message column's ``[[code, params], ...]`` if its text re-joins exactly."""
    if not isinstance(text, str):
        return None
    try:
        items = json.loads(text)
    except ValueError:
        return None
    if not (
        isinstance(items, list)
        and all(isinstance(i, list) and len(i) == 2 and isinstance(i[0], str) for i in items)
        and stored_json(items) == text
    ):
        return None
    return items


def _not_made_items(text: Any) -> dict[str, list[Any]] | None:
    """Return check -> [code, params] of a ``checks_not_made_codes`` value, if exact."""
    if text == "":
        return {}
    items = _message_items(text)
    if items is None or not all(isinstance(m, list) and len(m) == 2 for _, m in items):
        return None
    return dict((check, m) for check, m in items)


def split_summary(
    rows: Sequence[Mapping[str, Any]],
    parts: Sequence[str] = (),
    checks: Sequence[CheckColumns] = (),
) -> LongSummary:
    """Split wide summary rows into a slim ``/summary`` and the long tables (module docstring).

    Parameters
    ----------
    rows : sequence of mapping
        The wide rows, one per tower (the columns of the first row, in its order).
    parts : sequence of str
        The part models' names (:func:`~rockscreen.pipeline.archive.long_schema.fit_cells`).
    checks : sequence of CheckColumns
        The checks' columns, in the order the verdict lists them (tie-breaking order).

    Returns
    -------
    LongSummary
        Its tables rebuild ``rows`` exactly
        (:func:`~rockscreen.pipeline.archive.long_pivot.pivot_summary`): a column the long
        tables cannot hold exactly stays in ``summary``.
    """
    rows = list(rows)
    columns = list(rows[0]) if rows else []
    present = set(columns)
    # how a format-3 archive stored each column: from its first value that is not None
    kinds = {
        c: stored_kind([next((r[c] for r in rows if r.get(c) is not None), None)]) for c in columns
    }

    def movable(column: str, units: str) -> bool:
        kind_ok = (kinds[column] == "str") == (units == TEXT)
        return kind_ok and all(_fits_value(r.get(column), units) for r in rows)

    fits = {
        col: cell
        for col, cell in fit_cells(parts).items()
        if col in present and movable(col, FIT_FIELDS[cell[1]])
    }
    check_cells = {
        col: cells
        for col, cells in _check_cells(checks).items()
        if col in present and col not in fits and movable(col, CHECK_FIELDS[cells[0][1]])
    }
    messages = [
        c
        for c in MESSAGE_COLUMNS
        if c in present and all(_message_items(r.get(c)) is not None for r in rows)
    ]
    not_made = None
    if checks and NOT_MADE_COLUMN in present:
        not_made = [_not_made_items(r.get(NOT_MADE_COLUMN)) for r in rows]
        if any(items is None for items in not_made):
            not_made = None
    tables = {
        "fits": _fit_rows(rows, fits),
        "checks": _check_rows(rows, checks, check_cells, present, not_made),
        "messages": _message_rows(rows, messages),
    }
    if not_made is not None and _not_made_text(rows, tables["checks"]) != [
        r[NOT_MADE_COLUMN] for r in rows
    ]:
        not_made = None  # the rows' order does not give the stored list: the column stays
    check_cells = _kept_by_towers_without_checks(rows, check_cells, set(tables["checks"]["tower"]))
    where: dict[str, tuple[str, str, str]] = {
        **{col: ("fits", *cell) for col, cell in fits.items()},
        **{col: ("checks", *cells[0]) for col, cells in check_cells.items()},
        **{col: ("messages", col, "") for col in messages},
    }
    if not_made is not None:
        where[NOT_MADE_COLUMN] = ("checks", "", "reason")
    tables["pivot"] = {
        "column": columns,
        "kind": [kinds[c] for c in columns],
        "table": [where.get(c, ("",))[0] for c in columns],
        "key": [where[c][1] if c in where else "" for c in columns],
        "field": [where[c][2] if c in where else "" for c in columns],
    }
    slim = [{c: row.get(c) for c in columns if c not in where} for row in rows]
    return LongSummary(slim, tables)


def _kept_by_towers_without_checks(
    rows: Sequence[Mapping[str, Any]],
    cells: Mapping[str, list[tuple[str, str]]],
    with_checks: set[int],
) -> dict[str, list[tuple[str, str]]]:
    """Return the check cells every tower without ``/checks`` rows reads back exactly.

    A tower without a verdict has no rows: its check columns read back empty (NaN, ``""``),
    so a column with a value there stays in ``/summary``.
    """

    def empty(value: Any, units: str) -> bool:
        if units == TEXT:
            return value is None or value == ""
        return value is None or (isinstance(value, float) and math.isnan(value))

    return {
        col: pairs
        for col, pairs in cells.items()
        if all(
            i in with_checks or empty(row.get(col), CHECK_FIELDS[pairs[0][1]])
            for i, row in enumerate(rows)
        )
    }


def stored_checks(tables: Mapping[str, Mapping[str, Sequence[Any]]]) -> list[CheckColumns]:
    """Return the checks an archive stores and where they are in its wide rows.

    The reading side of the ``checks`` given to :func:`split_summary`: each check of
    ``/checks`` (in the order of its rows) with its part, family and method, and the wide
    columns ``/pivot`` maps to its capacity, I_S, bound and details (``""``: a field not
    in a column), so that the outputs show every check an archive holds without the
    registry that wrote it (a check added as a module included).

    Parameters
    ----------
    tables : mapping
        The long tables as read (:func:`~rockscreen.pipeline.archive.long_pivot.
        read_long_tables`); an archive without them has no checks.
    """
    checks, pivot = tables.get("checks", {}), tables.get("pivot", {})
    columns: dict[str, dict[str, str]] = {}
    for column, table, key, name in zip(
        *(pivot.get(c, ()) for c in ("column", "table", "key", "field")), strict=True
    ):
        if table == "checks" and key:
            columns.setdefault(key, {}).setdefault(name, column)
    out: dict[str, CheckColumns] = {}
    for check, part, family, method in zip(
        *(checks.get(c, ()) for c in ("check", "part", "family", "method")), strict=True
    ):
        if check in out:
            continue
        at = columns.get(check, {})
        keys = (at.get("capacity_ag_g", ""), at.get("safety_index", ""), at.get("bound", ""))
        details = {name: col for name, col in at.items() if name in DETAIL_UNITS}
        out[check] = CheckColumns(check, part, family, method, keys, details)
    return list(out.values())


def _empty(units: Mapping[str, str]) -> dict[str, list[Any]]:
    return {name: [] for name in units}


def _fit_rows(
    rows: Sequence[Mapping[str, Any]], cells: Mapping[str, tuple[str, str]]
) -> dict[str, list[Any]]:
    out = _empty(FIT_FIELDS)
    names = list(dict.fromkeys(fit for fit, _ in cells.values()))
    for i, row in enumerate(rows):
        values: dict[str, dict[str, Any]] = {fit: {} for fit in names}
        for column, (fit, name) in cells.items():
            values[fit][name] = row.get(column)
        for fit in names:
            out["tower"].append(i)
            out["fit"].append(fit)
            for name, units in list(FIT_FIELDS.items())[2:]:
                out[name].append(_stored(values[fit].get(name), units))
    return out


def _check_rows(
    rows: Sequence[Mapping[str, Any]],
    checks: Sequence[CheckColumns],
    cells: Mapping[str, list[tuple[str, str]]],
    present: set[str],
    not_made: list[dict[str, list[Any]]] | None,
) -> dict[str, list[Any]]:
    out = _empty(CHECK_FIELDS)
    declared = {c.check: c for c in checks}
    for i, row in enumerate(rows):
        reasons = not_made[i] if not_made is not None else {}
        if NOT_MADE_COLUMN in present and row.get(NOT_MADE_COLUMN) == "":
            continue  # no verdict (a tower not assessed): no rows
        values: dict[str, dict[str, Any]] = {c.check: {} for c in checks}
        values.update({check: {} for check in reasons if check not in values})
        for column, pairs in cells.items():
            for check, name in pairs:
                values[check][name] = row.get(column)
        for check, given in values.items():
            spec = declared.get(check)
            ag = given.get("capacity_ag_g")
            made = isinstance(ag, float) and math.isfinite(ag)
            code, params = reasons.get(check, ("", None))
            out["tower"].append(i)
            out["check"].append(check)
            out["part"].append(spec.part if spec else "")
            out["family"].append(spec.family if spec else "")
            out["method"].append(spec.method if spec else "")
            out["status"].append((Status.MADE if made else Status.NOT_MADE).value)
            out["reason_code"].append(code)
            out["reason_params"].append("" if params is None else stored_json(params))
            for name, units in list(CHECK_FIELDS.items())[6:]:
                if name not in ("reason_code", "reason_params"):
                    out[name].append(_stored(given.get(name), units))
    return out


def _not_made_text(rows: Sequence[Mapping[str, Any]], checks: Mapping[str, list[Any]]) -> list[str]:
    """Return each tower's ``checks_not_made_codes`` as :func:`pivot_summary` rebuilds it."""
    reasons: list[list[Any] | None] = [None] * len(rows)
    for i, check, code, params in zip(
        checks["tower"],
        checks["check"],
        checks["reason_code"],
        checks["reason_params"],
        strict=True,
    ):
        if reasons[i] is None:
            reasons[i] = []
        if code:
            reasons[i].append([check, [code, json.loads(params)]])
    return ["" if r is None else stored_json(r) for r in reasons]


def _message_rows(
    rows: Sequence[Mapping[str, Any]], columns: Sequence[str]
) -> dict[str, list[Any]]:
    out = _empty(MESSAGE_FIELDS)
    for i, row in enumerate(rows):
        for column in columns:
            for code, params in _message_items(row[column]) or []:
                out["tower"].append(i)
                out["column"].append(column)
                out["code"].append(code)
                out["params"].append(stored_json(params))
    return out


def write_long_tables(f: h5py.File, tables: Mapping[str, Mapping[str, list[Any]]]) -> None:
    """Write :attr:`LongSummary.tables` as groups of 1-D columns with their declared units.

    Each column through :func:`~rockscreen.pipeline.archive.column_codec.write_column`
    (compressed numbers, coded or fixed-length text); ``tower`` as integers, the other
    numbers as float64.
    """
    for table, columns in tables.items():
        group = f.create_group(table)
        units = LONG_TABLES[table]
        group.attrs["columns"] = json.dumps(list(columns))
        for name, values in columns.items():
            if units[name] == TEXT:
                write_column(group, name, text_values(values), TEXT)
            else:
                dtype = np.int64 if name == "tower" else np.float64
                write_column(group, name, np.asarray(values, dtype=dtype), units[name])
