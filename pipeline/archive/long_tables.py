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
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
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
    CheckColumns,
    fit_cells,
)
from rockscreen.pipeline.archive.schema import TEXT
from rockscreen.pipeline.verdict.status import Status

__all__ = [
    "MESSAGE_COLUMNS",
    "NOT_MADE_COLUMN",
    "write_long_tables",
    "LongSummary",
    "SplitPlan",
    "plan_split",
    "split_part",
    "split_summary",
]

#: Summary columns holding a list of messages (:func:`~rockscreen.pipeline.verdict.messages.
#: dumps`) stored one message per row in ``/messages``.
MESSAGE_COLUMNS = ("note_codes",)
#: The summary column of the checks not made and why
#: (:func:`~rockscreen.pipeline.verdict.checks.dumps_not_made`), stored in ``/checks``.
NOT_MADE_COLUMN = "checks_not_made_codes"


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


@dataclass
class SplitPlan:
    """Where each column of wide summary rows goes, decided from all of them (:func:`plan_split`).

    The same plan splits every part of the rows (:func:`split_part`), so a summary given in
    parts is stored as the one-piece :func:`split_summary` stores it.
    """

    #: The wide row's columns (its first row's keys, in order).
    columns: list[str]
    #: Column -> how a format-3 archive stored it (``bool``, ``i8``, ``f8``, ``str``).
    kinds: dict[str, str]
    #: Column -> (fit, field) of the columns moved to ``/fits``.
    fits: dict[str, tuple[str, str]]
    #: Column -> its (check, field) cells: what the ``/checks`` rows are filled from.
    check_cells: dict[str, list[tuple[str, str]]]
    #: Message columns moved to ``/messages``.
    messages: list[str]
    #: Whether the ``/checks`` rows take their reasons from ``checks_not_made_codes``.
    reasons: bool
    #: Column -> (table, key, field) of every column moved out of ``/summary``.
    where: dict[str, tuple[str, str, str]]

    @property
    def slim(self) -> list[str]:
        """The columns left in ``/summary``, in the wide row's order."""
        return [c for c in self.columns if c not in self.where]

    @property
    def pivot(self) -> dict[str, list[Any]]:
        """The ``/pivot`` table: one row per column of the wide row."""
        where = self.where
        return {
            "column": list(self.columns),
            "kind": [self.kinds[c] for c in self.columns],
            "table": [where.get(c, ("",))[0] for c in self.columns],
            "key": [where[c][1] if c in where else "" for c in self.columns],
            "field": [where[c][2] if c in where else "" for c in self.columns],
        }


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
    plan = plan_split([rows], parts, checks)
    split = split_part(rows, plan, checks)
    return LongSummary(split.summary, {**split.tables, "pivot": plan.pivot})


class _Tally:
    """What :func:`plan_split` learns of the rows, a part at a time."""

    def __init__(self, columns: list[str], parts: Sequence[str], checks: Sequence[CheckColumns]):
        present = set(columns)
        self.columns, self.present, self.checks = columns, present, checks
        self.samples: dict[str, Any] = {}
        self.fit_cells = {c: cell for c, cell in fit_cells(parts).items() if c in present}
        self.check_cells = {c: cells for c, cells in _check_cells(checks).items() if c in present}
        self.fit_ok = dict.fromkeys(self.fit_cells, True)
        self.check_ok = dict.fromkeys(self.check_cells, True)
        self.empty_ok = dict.fromkeys(self.check_cells, True)
        self.message_ok = {c: True for c in MESSAGE_COLUMNS if c in present}
        self.reasons = self.text_ok = bool(checks) and NOT_MADE_COLUMN in present

    def _has_check_rows(self, row: Mapping[str, Any]) -> bool:
        """Whether a tower has ``/checks`` rows (:func:`_check_rows`: one without a verdict not)."""
        skipped = NOT_MADE_COLUMN in self.present and row.get(NOT_MADE_COLUMN) == ""
        return bool(self.checks) and not skipped

    def add(self, rows: Sequence[Mapping[str, Any]]) -> None:
        """Take a part of the rows into account."""
        for c in self.columns:
            if c not in self.samples:
                sample = next((r[c] for r in rows if r.get(c) is not None), None)
                if sample is not None:
                    self.samples[c] = sample
        for col, (_, name) in self.fit_cells.items():
            units = FIT_FIELDS[name]
            self.fit_ok[col] = self.fit_ok[col] and all(
                _fits_value(r.get(col), units) for r in rows
            )
        for col, cells in self.check_cells.items():
            units = CHECK_FIELDS[cells[0][1]]
            self.check_ok[col] = self.check_ok[col] and all(
                _fits_value(r.get(col), units) for r in rows
            )
            self.empty_ok[col] = self.empty_ok[col] and all(
                self._has_check_rows(r) or _is_empty(r.get(col), units) for r in rows
            )
        for col in self.message_ok:
            self.message_ok[col] = self.message_ok[col] and all(
                _message_items(r.get(col)) is not None for r in rows
            )
        if self.reasons:
            items = [_not_made_items(r.get(NOT_MADE_COLUMN)) for r in rows]
            if any(i is None for i in items):
                self.reasons = self.text_ok = False
            elif self.text_ok:
                table = _check_rows(rows, self.checks, {}, self.present, items)
                given = [r[NOT_MADE_COLUMN] for r in rows]
                self.text_ok = _not_made_text(rows, table) == given

    def plan(self) -> SplitPlan:
        """Return the plan of all the rows taken in."""
        kinds = {c: stored_kind([self.samples.get(c)]) for c in self.columns}

        def movable(column: str, units: str, ok: bool) -> bool:
            return ok and (kinds[column] == "str") == (units == TEXT)

        fits = {
            col: cell
            for col, cell in self.fit_cells.items()
            if movable(col, FIT_FIELDS[cell[1]], self.fit_ok[col])
        }
        check_cells = {
            col: cells
            for col, cells in self.check_cells.items()
            if col not in fits and movable(col, CHECK_FIELDS[cells[0][1]], self.check_ok[col])
        }
        messages = [c for c, ok in self.message_ok.items() if ok]
        where: dict[str, tuple[str, str, str]] = {
            **{col: ("fits", *cell) for col, cell in fits.items()},
            **{
                col: ("checks", *cells[0])
                for col, cells in check_cells.items()
                if self.empty_ok[col]
            },
            **{col: ("messages", col, "") for col in messages},
        }
        if self.reasons and self.text_ok:
            where[NOT_MADE_COLUMN] = ("checks", "", "reason")
        return SplitPlan(self.columns, kinds, fits, check_cells, messages, self.reasons, where)


def plan_split(
    row_parts: Iterable[Sequence[Mapping[str, Any]]],
    parts: Sequence[str] = (),
    checks: Sequence[CheckColumns] = (),
) -> SplitPlan:
    """Decide where each column of wide summary rows goes, from all of them, part by part.

    Parameters
    ----------
    row_parts : iterable of sequence of mapping
        The wide rows, a part at a time, in order (the columns of the first row).
    parts : sequence of str
        The part models' names.
    checks : sequence of CheckColumns
        The checks' columns, in the verdict's order.

    Returns
    -------
    SplitPlan
        What :func:`split_summary` decides for the same rows given in one piece: a column
        moves to a long table only when every row's value is held there exactly.
    """
    tally: _Tally | None = None
    for rows in row_parts:
        rows = list(rows)
        if not rows:
            continue
        if tally is None:
            tally = _Tally(list(rows[0]), parts, checks)
        tally.add(rows)
    return (tally or _Tally([], parts, checks)).plan()


def split_part(
    rows: Sequence[Mapping[str, Any]],
    plan: SplitPlan,
    checks: Sequence[CheckColumns] = (),
    offset: int = 0,
) -> LongSummary:
    """Split a part of the wide rows by ``plan``: its slim rows and long-table rows.

    Parameters
    ----------
    rows : sequence of mapping
        Consecutive wide rows.
    plan : SplitPlan
        :func:`plan_split` of all the rows.
    checks : sequence of CheckColumns
        The checks' columns the plan was made with.
    offset : int
        The first row's position in the whole summary (the long tables' ``tower``).

    Returns
    -------
    LongSummary
        The slim rows and the ``fits``, ``checks`` and ``messages`` rows (no ``pivot``:
        :attr:`SplitPlan.pivot`).
    """
    rows = list(rows)
    present = set(plan.columns)
    not_made = [_not_made_items(r.get(NOT_MADE_COLUMN)) for r in rows] if plan.reasons else None
    tables = {
        "fits": _fit_rows(rows, plan.fits, offset),
        "checks": _check_rows(rows, checks, plan.check_cells, present, not_made, offset),
        "messages": _message_rows(rows, plan.messages, offset),
    }
    slim_columns = plan.slim
    slim = [{c: row.get(c) for c in slim_columns} for row in rows]
    return LongSummary(slim, tables)


def _is_empty(value: Any, units: str) -> bool:
    """Whether a check field reads back empty (NaN, ``""``) from a tower without check rows."""
    if units == TEXT:
        return value is None or value == ""
    return value is None or (isinstance(value, float) and math.isnan(value))


def _empty(units: Mapping[str, str]) -> dict[str, list[Any]]:
    return {name: [] for name in units}


def _fit_rows(
    rows: Sequence[Mapping[str, Any]], cells: Mapping[str, tuple[str, str]], offset: int = 0
) -> dict[str, list[Any]]:
    out = _empty(FIT_FIELDS)
    names = list(dict.fromkeys(fit for fit, _ in cells.values()))
    for i, row in enumerate(rows):
        values: dict[str, dict[str, Any]] = {fit: {} for fit in names}
        for column, (fit, name) in cells.items():
            values[fit][name] = row.get(column)
        for fit in names:
            out["tower"].append(offset + i)
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
    offset: int = 0,
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
            out["tower"].append(offset + i)
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
    rows: Sequence[Mapping[str, Any]], columns: Sequence[str], offset: int = 0
) -> dict[str, list[Any]]:
    out = _empty(MESSAGE_FIELDS)
    for i, row in enumerate(rows):
        for column in columns:
            for code, params in _message_items(row[column]) or []:
                out["tower"].append(offset + i)
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
