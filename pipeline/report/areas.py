"""Towers per risk class per area (comune, provincia): what a regional office counts.

An assess or scenario summary whose inventory had the optional ``comune`` or ``provincia``
columns (:data:`rockscreen.stations.inventory_columns.AREA_COLUMNS`) is counted per area:
the terminal prints one table per column after the towers, ``export --by COLUMN`` writes
it as CSV, and the HTML report shows it under the class counts. Classes are counted
from the typed columns (:func:`rockscreen.pipeline.verdict.scales.class_marks`): a ``meets``
on a non-compliant basis counts as ``meets``, one on rigid overturning alone as
``incomplete``; a tower
without the column's value counts under ``(none)``.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from rockscreen.pipeline.verdict.scales import UNDEFINED, class_marks
from rockscreen.stations.inventory_columns import AREA_COLUMNS

__all__ = ["NO_AREA", "area_columns", "area_counts", "area_lines"]

#: The area of a tower whose row has no value in the column.
NO_AREA = "(none)"


def _text(value: object) -> str:
    return value.decode("utf-8") if isinstance(value, bytes) else str(value or "")


def area_columns(rows: Sequence[Mapping[str, object]]) -> list[str]:
    """Return the area columns (``comune``, ``provincia``) that some row has a value in."""
    return [c for c in AREA_COLUMNS if any(_text(row.get(c, "")).strip() for row in rows)]


def area_counts(
    rows: Sequence[Mapping[str, object]], column: str
) -> tuple[list[str], list[tuple[str, dict[str, int], int]]]:
    """Count the towers per class in each area of ``column``.

    Parameters
    ----------
    rows : sequence of mapping
        Summary rows (assess or scenario) with ``risk_class``.
    column : str
        ``"comune"`` or ``"provincia"``.

    Returns
    -------
    classes : list of str
        The classes met, in order of first appearance in ``rows`` ranked by the caller.
    areas : list of (area, {class: count}, total)
        One entry per area, the areas with the most towers first (then by name);
        :data:`NO_AREA` for rows without a value.
    """
    classes: list[str] = []
    by_area: dict[str, dict[str, int]] = {}
    for row in rows:
        cls = class_marks(row).counted if "risk_class" in row else UNDEFINED
        if cls not in classes:
            classes.append(cls)
        area = _text(row.get(column, "")).strip() or NO_AREA
        counts = by_area.setdefault(area, {})
        counts[cls] = counts.get(cls, 0) + 1
    areas = [(area, counts, sum(counts.values())) for area, counts in by_area.items()]
    areas.sort(key=lambda item: (-item[2], item[0]))
    return classes, areas


def area_lines(rows: Sequence[Mapping[str, object]], class_order: Sequence[str] = ()) -> list[str]:
    """Return the terminal tables of towers per class per area (none without area columns).

    Parameters
    ----------
    rows : sequence of mapping
        Summary rows.
    class_order : sequence of str, optional
        Classes in display order (worst first); classes not listed follow.
    """
    from rockscreen.pipeline.report.risk_summary import table_lines
    from rockscreen.pipeline.text import printable

    out: list[str] = []
    for column in area_columns(rows):
        met, areas = area_counts(rows, column)
        classes = [c for c in class_order if c in met] + [c for c in met if c not in class_order]
        header = [column, *classes, "towers"]
        body = [
            [printable(area), *(str(counts.get(c, 0)) for c in classes), str(total)]
            for area, counts, total in areas
        ]
        out += ["", f"towers per class by {column}:", *table_lines(header, body)]
    return out
