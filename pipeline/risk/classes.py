"""Risk classes of towers from the safety index I_S, and the ranking of towers.

Default bands (checked from the top, ``I_S = T_R,C / T_R,SLV``):

==============  =================  =====================================================
class           rule               basis
==============  =================  =====================================================
``meets``       ``I_S >= 1``       the SLV action of the code does not reach the capacity
                                   (MiC 2011 Guidelines §2.4: I_S >= 1 is code safety)
``moderate``    ``0.6 <= I_S < 1``  rockscreen's choice
``high``        ``0.3 <= I_S < 0.6`` rockscreen's choice
``very_high``   ``I_S < 0.3``      rockscreen's choice
``undefined``   I_S not a number
==============  =================  =====================================================

A ``meets`` reached on the whole tower's rigid overturning alone (its rocking and its
kinematic check), when a check that can fail earlier was not made for want of data (the
belfry's, LV1's: the summary's ``checks_not_made`` starts with :data:`ROCKING_ONLY`), is
no code verdict: it is printed as :data:`INCOMPLETE` with the missing data named
(:func:`class_label`), and counted apart from ``meets`` wherever towers are counted.

Only the limit 1 comes from the Guidelines; 0.6 and 0.3 are screening choices of
rockscreen (roughly: the capacity's return period is below 60 % and below 30 % of the
code's), not values of a code or study; ``--class-limits`` replaces them. An I_S that is
a bound (the fragility median was a bound) is classed on the bound value: an upper bound
(the tower overturned at every stripe) gives a class the tower is at least as risky as,
a lower bound (never overturned) one it is at most as risky as.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from rockscreen.pipeline.errors import RiskError

__all__ = [
    "CLASS_NAMES",
    "DEFAULT_LIMITS",
    "INCOMPLETE",
    "SCENARIO_CLASS_NAMES",
    "NONCOMPLIANT_MARK",
    "PRINTED_CLASSES",
    "ROCKING_ONLY",
    "SCENARIO_LIMITS",
    "base_class",
    "class_label",
    "parse_limits",
    "rank_towers",
    "risk_class",
    "row_class_label",
    "scenario_class",
]

#: Class names, from the safest down, then the undefined one.
CLASS_NAMES = ("meets", "moderate", "high", "very_high")
#: Lower I_S limits of the first three classes [-].
DEFAULT_LIMITS = (1.0, 0.6, 0.3)


def parse_limits(text: str | Sequence[float] | None) -> tuple[float, float, float]:
    """Return three strictly decreasing positive I_S limits from ``"1,0.6,0.3"`` or a sequence.

    Raises
    ------
    RiskError
        When there are not three numbers, or they are not positive and strictly decreasing.
    """
    if text is None:
        return DEFAULT_LIMITS
    try:
        values = [float(v) for v in (text.split(",") if isinstance(text, str) else text)]
    except ValueError:
        raise RiskError(f"class limits {text!r}: expected three numbers like '1,0.6,0.3'") from None
    if len(values) != 3 or not all(math.isfinite(v) and v > 0 for v in values):
        raise RiskError(f"class limits {text!r}: expected three positive numbers like '1,0.6,0.3'")
    if not values[0] > values[1] > values[2]:
        raise RiskError(f"class limits {text!r}: must be strictly decreasing (e.g. 1,0.6,0.3)")
    return (values[0], values[1], values[2])


def risk_class(safety_index: float, limits: Sequence[float] = DEFAULT_LIMITS) -> str:
    """Return the class of a safety index I_S [-] (module docstring); ``"undefined"`` for NaN.

    A bound is classed on its value: an upper bound on I_S gives a class the tower is at
    least as risky as; a lower bound one it is at most as risky as.
    """
    return _band(safety_index, CLASS_NAMES, limits)


#: Scenario classes on the probability of overturning under one event, worst first.
SCENARIO_CLASS_NAMES = ("very_high", "high", "moderate", "low")
#: Lower probability limits of the first three scenario classes [-]: rockscreen's choice
#: (even odds, one in five, one in twenty), not values of a code or study.
SCENARIO_LIMITS = (0.5, 0.2, 0.05)


def scenario_class(p_overturning: float, limits: Sequence[float] = SCENARIO_LIMITS) -> str:
    """Return the scenario class of a probability of overturning [-]; ``"undefined"`` for NaN.

    ``very_high`` from ``P >= 0.5``, ``high`` from 0.2, ``moderate`` from 0.05, else ``low``
    (:data:`SCENARIO_LIMITS`, rockscreen's screening choice).
    """
    return _band(p_overturning, SCENARIO_CLASS_NAMES, limits)


#: What ``checks_not_made`` starts with when only the whole tower's rigid overturning (its
#: rocking and its kinematic check) was assessed (:mod:`rockscreen.pipeline.risk.tower_checks`).
ROCKING_ONLY = "rocking only"
#: How a ``meets`` on rigid overturning alone is printed and counted (module docstring).
INCOMPLETE = "incomplete"
#: The classes as printed and counted (:func:`class_label` without its marks), worst first.
PRINTED_CLASSES = ("very_high", "high", "moderate", INCOMPLETE, "meets")
#: What every class built on a record set that fails NTC 2018 §3.2.3.6 carries.
NONCOMPLIANT_MARK = "basis not code-compliant"


def class_label(cls: str, basis_compliant: bool = True, checks_not_made: str = "") -> str:
    """Return the class as printed: ``cls``, marked when the verdict is not the code's.

    The one place a class becomes text for a reader (terminal table, CSV/GeoJSON/JSON
    export, HTML report): a verdict built on a non-compliant record set
    (``assess --allow-noncompliant``) never reads as a plain ``meets``
    (``"meets (basis not code-compliant)"``), and a ``meets`` when checks that could fail
    earlier were not made is no ``meets`` at all: rigid whole-tower overturning alone never
    makes a tower meet the code, so it reads :data:`INCOMPLETE` with the missing checks
    (``"incomplete (rocking only: belfry not checked (...); LV1 not made (...))"``). A
    lower class is not marked: a missing check can only lower it further.

    Parameters
    ----------
    cls : str
        A class name (:data:`CLASS_NAMES`, ``"undefined"``, a scenario class).
    basis_compliant : bool
        Whether the record sets behind the verdict meet NTC 2018 §3.2.3.6.
    checks_not_made : str
        The checks not made and why (the summary's ``checks_not_made``); ``""``: all made.

    Returns
    -------
    str
    """
    marks = [] if basis_compliant else [NONCOMPLIANT_MARK]
    if checks_not_made and cls == CLASS_NAMES[0]:
        marks.append(checks_not_made)
        if checks_not_made.startswith(ROCKING_ONLY):
            cls = INCOMPLETE
    return " ".join([cls, *(f"({mark})" for mark in marks)])


def row_class_label(row: dict[str, Any]) -> str:
    """Return :func:`class_label` of a summary row.

    It reads ``risk_class``, ``basis_compliant`` and ``checks_not_made``.
    A row without ``basis_compliant`` (a scenario row, an older archive) is compliant; one
    without ``checks_not_made`` (an older archive) is not marked for it.
    """
    compliant = row.get("basis_compliant", True)
    compliant = True if compliant is None or compliant == "" else bool(compliant)
    missing = row.get("checks_not_made", "")
    missing = "" if missing is None or not isinstance(missing, str) else missing
    return class_label(str(row.get("risk_class", "") or "undefined"), compliant, missing)


def base_class(label: str) -> str:
    """Return the class name of a label of :func:`class_label` (its marks removed)."""
    return label.split(" (", 1)[0]


def _band(value: float, names: Sequence[str], limits: Sequence[float]) -> str:
    """Return the first of ``names`` whose lower limit ``value`` reaches, else the last one."""
    if math.isnan(value):
        return "undefined"
    for name, limit in zip(names, limits, strict=False):
        if value >= limit:
            return name
    return names[-1]


def _bound_group(row: dict[str, Any]) -> int:
    bound = row.get("collapse_bound", row.get("median_is_bound", ""))
    return {"upper": 0, "": 1, "lower": 2}.get(bound, 3)


def rank_towers(rows: Sequence[dict[str, Any]]) -> list[dict[str, Any]]:
    """Sort summary rows riskiest first.

    Order: towers that overturned at every stripe (upper-bound median), then the fitted
    ones by decreasing annual rate of overturning ``lambda_C``, then by increasing I_S;
    towers that never overturned (lower-bound median) last, by increasing I_S bound.
    """

    def key(row: dict[str, Any]) -> tuple:
        rate = row.get("annual_rate_overturning_per_y", math.nan)
        index = row.get("safety_index", math.nan)
        return (
            _bound_group(row),
            -rate if math.isfinite(rate) else math.inf,
            index if not math.isnan(index) else math.inf,
            str(row.get("id", "")),
        )

    return sorted(rows, key=key)
