"""Assess format 4's long tables pivoted back into one wide summary row per tower.

The reading side of :mod:`rockscreen.pipeline.archive.long_tables` (which writes them):
:func:`read_long_tables` reads ``/fits``, ``/checks``, ``/messages`` and ``/pivot`` checked,
:func:`pivot_summary` rebuilds the rows a format-3 archive gave back from them and the slim
``/summary``, without the registries that wrote them.
"""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from typing import Any

import h5py

from rockscreen.pipeline.archive.column_codec import text_values
from rockscreen.pipeline.archive.long_schema import LONG_TABLES, CheckColumns
from rockscreen.pipeline.archive.safety import read_column
from rockscreen.pipeline.verdict.checks import DETAIL_UNITS

__all__ = ["pivot_summary", "read_long_tables", "stored_checks", "stored_json"]


def stored_json(value: Any) -> str:
    """Return JSON text as the verdict's stored messages spell it (``verdict.messages.dumps``)."""
    return json.dumps(value, ensure_ascii=False, sort_keys=True)


#: The stored kinds of a wide column (:func:`~rockscreen.pipeline.archive.column_codec.
#: stored_kind`).
_KINDS = ("bool", "i8", "f8", "str")


def _cast(value: Any, kind: str) -> Any:
    """Return a stored value as a format-3 archive reads its column of ``kind`` back."""
    if kind == "f8":
        return value if type(value) is float else float("nan" if value is None else value)
    if kind == "str":
        return value if type(value) is str else text_values([value])[0]
    if kind == "bool":
        return bool(value)
    return int(value)


#: The long tables' key field (the fit, the check).
_KEYS = {"fits": "fit", "checks": "check"}


def _towers(columns: Mapping[str, Sequence[Any]], table: str, n: int) -> list[int]:
    """Return a long table's ``tower`` column, each a row of ``/summary`` (else ValueError)."""
    towers = list(columns.get("tower", ()))
    bad = next((i for i in towers if not (isinstance(i, int) and 0 <= i < n)), None)
    if bad is not None:
        raise ValueError(f"/{table} row of tower {bad!r}, not a row of /summary (0..{n - 1})")
    return towers


def pivot_summary(
    summary: Sequence[Mapping[str, Any]], tables: Mapping[str, Mapping[str, Sequence[Any]]]
) -> list[dict[str, Any]]:
    """Return the wide summary rows from the slim ``/summary`` and the long tables.

    Parameters
    ----------
    summary : sequence of mapping
        The slim ``/summary`` rows, one per tower.
    tables : mapping
        ``fits``, ``checks``, ``messages``, ``pivot``: each table's columns as read
        (column -> values; :attr:`~rockscreen.pipeline.archive.long_tables.
        LongSummary.tables`).

    Returns
    -------
    list of dict
        One row per tower: every column of ``/pivot`` in its order, each value of its
        stored kind (the rows a format-3 archive gives back).

    Raises
    ------
    ValueError
        For a row of a long table pointing at no tower, or a ``/pivot`` row of an unknown
        kind or table (:func:`rockscreen.pipeline.archive.risk_reader.summary_rows` says it
        as an :class:`~rockscreen.pipeline.errors.ArchiveError`); KeyError for a field or
        column named but not stored.
    """
    n = len(summary)
    pivot = tables["pivot"]
    spec = list(
        zip(
            pivot["column"],
            pivot["kind"],
            pivot["table"],
            pivot["key"],
            pivot["field"],
            strict=True,
        )
    )
    for column, kind, table, _, _ in spec:
        if kind not in _KINDS or table not in ("", "fits", "checks", "messages"):
            raise ValueError(f"/pivot row of column {column!r} is not one rockscreen writes")
    # (tower, key) -> row of each long table
    rows: dict[str, list[dict[str, int]]] = {}
    for table, key in _KEYS.items():
        columns = tables.get(table, {})
        rows[table] = [{} for _ in range(n)]
        towers = _towers(columns, table, n)
        for r, (i, name) in enumerate(zip(towers, columns.get(key, ()), strict=True)):
            rows[table][i][name] = r
    messages: list[dict[str, list[list[Any]]]] = [{} for _ in range(n)]
    columns = tables.get("messages", {})
    for i, column, code, params in zip(
        _towers(columns, "messages", n),
        *(columns.get(c, ()) for c in ("column", "code", "params")),
        strict=True,
    ):
        messages[i].setdefault(column, []).append([code, json.loads(params)])
    out = []
    for i, slim in enumerate(summary):
        wide: dict[str, Any] = {}
        for column, kind, table, key, name in spec:
            if table == "":
                wide[column] = slim[column]
            elif table == "messages":
                wide[column] = stored_json(messages[i].get(column, []))
            elif name == "reason":
                wide[column] = _reasons(tables["checks"], rows["checks"][i])
            else:
                r = rows[table][i].get(key)
                wide[column] = _cast(None if r is None else tables[table][name][r], kind)
        out.append(wide)
    return out


def _reasons(checks: Mapping[str, Sequence[Any]], rows: Mapping[str, int]) -> str:
    """Return a tower's ``checks_not_made_codes`` from its ``/checks`` rows ("": none)."""
    if not rows:
        return ""
    code, params = checks["reason_code"], checks["reason_params"]
    return stored_json(
        [
            [check, [code[r], json.loads(params[r])]]
            for check, r in sorted(rows.items(), key=lambda item: item[1])
            if code[r]
        ]
    )


def read_long_tables(f: h5py.File) -> dict[str, dict[str, list[Any]]]:
    """Return the long tables of an open archive: table -> column -> values ({} if absent).

    The columns are read checked (:func:`~rockscreen.pipeline.archive.safety.read_column`:
    1-D, numbers or text) as Python values, the form :func:`pivot_summary` takes.
    """
    out: dict[str, dict[str, list[Any]]] = {}
    for table in LONG_TABLES:
        group = f.get(table)
        if isinstance(group, h5py.Group):
            out[table] = {
                name: read_column(group[name], f.filename, f"{table}/{name}").tolist()
                for name in group
            }
    return out


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
        The long tables as read (:func:`read_long_tables`); an archive without them has no checks.
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
