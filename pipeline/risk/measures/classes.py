"""Risk classes of towers from the safety index I_S (the ranking is the report's).

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
belfry's, LV1's: the summary's ``completeness`` is ``rocking_only``), is no code verdict:
it is printed as :data:`INCOMPLETE` with the missing data named (:func:`class_label`), and
counted apart from ``meets`` wherever towers are counted.

The scales, their names and bands live in :mod:`rockscreen.pipeline.verdict.scales` (the
report reads them without importing the risk computation) and the printed labels in
:mod:`rockscreen.pipeline.verdict.labels`; this module names them for the risk products.

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

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.verdict.labels import (
    NONCOMPLIANT_MARK,
    class_label,
    marks_of,
    row_class_label,
)
from rockscreen.pipeline.verdict.messages import message, render
from rockscreen.pipeline.verdict.scales import (
    INCOMPLETE,
    SAFETY_CLASS,
    SAFETY_COUNTED,
    SCENARIO_CLASS,
)

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
    "risk_class",
    "row_class_label",
    "scenario_class",
]

#: Class names, from the safest down, then the undefined one.
CLASS_NAMES = SAFETY_CLASS.classes
#: Lower I_S limits of the first three classes [-].
DEFAULT_LIMITS = (SAFETY_CLASS.limits[0], SAFETY_CLASS.limits[1], SAFETY_CLASS.limits[2])


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
    return SAFETY_CLASS.classify(safety_index, limits)


#: Scenario classes on the probability of overturning under one event, worst first.
SCENARIO_CLASS_NAMES = SCENARIO_CLASS.classes
#: Lower probability limits of the first three scenario classes [-]: rockscreen's choice
#: (even odds, one in five, one in twenty), not values of a code or study.
SCENARIO_LIMITS = SCENARIO_CLASS.limits


def scenario_class(p_overturning: float, limits: Sequence[float] = SCENARIO_LIMITS) -> str:
    """Return the scenario class of a probability of overturning [-]; ``"undefined"`` for NaN.

    ``very_high`` from ``P >= 0.5``, ``high`` from 0.2, ``moderate`` from 0.05, else ``low``
    (:data:`SCENARIO_LIMITS`, rockscreen's screening choice).
    """
    return SCENARIO_CLASS.classify(p_overturning, limits)


#: The heading of ``checks_not_made`` when only the whole tower's rigid overturning (its
#: rocking and its kinematic check) was assessed (``completeness`` ``rocking_only``).
ROCKING_ONLY = render(message("completeness.rocking_only"))
#: The classes as printed and counted (:func:`class_label` without its marks), worst first.
PRINTED_CLASSES = SAFETY_COUNTED


def base_class(label: object) -> str:
    """Return the class a label of :func:`class_label` is counted under (its typed marks).

    A plain class word is itself; nothing is split.
    """
    return marks_of(label).counted
