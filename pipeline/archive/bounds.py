"""Which summary values are bounds, and which way: the one rule every output follows.

A fragility median that no record reached (every record right-censored) is a lower bound,
and so is every quantity that grows with it (the capacity a_C, its return period T_R,C,
the safety index I_S, the acceleration factor f_a); a kinematic check that still holds at
the 2475-year hazard gives a lower bound of its capacity and index. Each such value column
has a bound column holding ``"lower"``, ``"upper"`` or ``""`` (:func:`bound_column`: the
pairs are declared in :func:`rockscreen.pipeline.archive.risk_schema.bound_columns`);
:func:`relation` turns the pair into the sign every output prints before the number
(``>`` at least, ``<`` at most): the terminal tables, ``inspect`` (a ``<key>_note`` in
JSON), the CSV and GeoJSON exports (``>1.67``) and the HTML report.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from rockscreen.pipeline.archive.risk_schema import bound_columns
from rockscreen.pipeline.verdict.status import Bound

__all__ = ["bound_column", "bounded_columns", "relation"]

#: Bound columns that archives written before the IDA fragility lack: there, the one
#: fragility's ``median_is_bound`` holds for all of them.
_BEFORE_IDA = frozenset({"collapse_bound", "slv_bound"})


def bound_column(column: str) -> str | None:
    """Return the name of the column that says whether ``column`` is a bound, or None.

    Parameters
    ----------
    column : str
        A summary column (``"safety_index"``, ``"belfry_capacity_ag_g"``, ...).

    Returns
    -------
    str or None
        E.g. ``"slv_bound"``; None for a column that is never a bound.

    Examples
    --------
    >>> bound_column("capacity_pga_g")
    'slv_bound'
    >>> bound_column("belfry_kinematic_linear_safety_index")
    'belfry_kinematic_linear_bound'
    >>> bound_column("belfry_safety_index")
    'belfry_slv_bound'
    >>> bound_column("lv1_safety_index")
    'lv1_bound'
    >>> bound_column("p_overturning_50y") is None
    True
    """
    return bound_columns().get(column)


def relation(row: Mapping[str, Any], column: str) -> str:
    """Return ``">"`` (the value is at least this), ``"<"`` (at most) or ``""`` (a value).

    Parameters
    ----------
    row : mapping
        A summary row.
    column : str
        One of its value columns.
    """
    key = bound_column(column)
    if key is None:
        return ""
    if key not in row and key in _BEFORE_IDA:  # an archive with one (stripe) fragility
        key = "median_is_bound"
    try:
        return Bound.parse(row.get(key) or "").sign
    except ValueError:  # not a bound's spelling: no relation claimed
        return ""


def bounded_columns(row: Mapping[str, Any]) -> dict[str, str]:
    """Return ``{column: ">" or "<"}`` for every value of ``row`` that is a bound."""
    out = {}
    for column in row:
        sign = relation(row, column)
        if sign:
            out[column] = sign
    return out
