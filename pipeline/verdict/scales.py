"""The three class scales, each with its own name: what a class word means in each product.

"high" means three things in rockscreen, so each product's class has its own scale:

==================  ===========  ===============================================  ==========
scale               product      classes, worst first                             measure
==================  ===========  ===============================================  ==========
``record_class``    ``run``      ``collapse``, ``high``, ``moderate``, ``low``,   the records
                                 ``none``                                         (rotation,
                                                                                  safety factor)
``safety_class``    ``assess``   ``very_high``, ``high``, ``moderate``, ``meets``  ``I_S``
``scenario_class``  ``scenario`` ``very_high``, ``high``, ``moderate``, ``low``    ``P``
==================  ===========  ===============================================  ==========

A value that is not a number is ``undefined`` on every scale. The exports' ``risk_class``
column holds one word of its product's scale; the marks that qualify it are their own
columns and types, never text appended to the word:

- :class:`Completeness` (``completeness``): an ``assess`` verdict whose checks that can fail
  before rigid overturning were all left unmade for want of data is no code verdict: a
  ``meets`` on it is *counted and printed* as :data:`INCOMPLETE` (:func:`counted_safety_class`),
  which is a completeness mark, not a class of the scale;
- ``basis_compliant``: whether the record sets behind the verdict meet NTC 2018 §3.2.3.6;
- :class:`ClassBound` (``class_bound``): a scenario class read on a bound of ``P`` that
  leaves it open (``at_most``: the tower is at most that risky; ``at_least``).

Only the ``safety_class`` limit 1 comes from a code (MiC 2011 Guidelines §2.4: ``I_S >= 1``
is code safety); 0.6 and 0.3, and the scenario limits 0.5, 0.2 and 0.05, are rockscreen's
screening choices. The ``record_class`` rules are
:func:`rockscreen.pipeline.screening.risk.risk_class` (several measures, no single band).
"""

from __future__ import annotations

import enum
import math
from collections.abc import Sequence
from dataclasses import dataclass

from rockscreen.pipeline.verdict.status import Bound
from rockscreen.pipeline.vocabulary import RECORD_RISK_CLASSES

__all__ = [
    "INCOMPLETE",
    "RECORD_CLASS",
    "SAFETY_CLASS",
    "SAFETY_COUNTED",
    "SCALES",
    "SCENARIO_CLASS",
    "UNDEFINED",
    "ClassBound",
    "ClassMarks",
    "ClassScale",
    "Completeness",
    "band",
    "class_marks",
    "counted_safety_class",
    "scenario_class_of",
]

#: The class of a value that is not a number, on every scale.
UNDEFINED = "undefined"


@dataclass(frozen=True)
class ClassScale:
    """One product's class scale: its name, its classes and (banded scales) their limits.

    A banded scale lists its classes from the one of the highest measure down, with the
    lower limits of all but the last (:func:`band`).
    """

    #: The scale's name (``"safety_class"``).
    name: str
    #: The ``rockscreen`` command whose classes these are.
    product: str
    #: The classes in band order (``safety_class``: safest first; the others: worst first).
    classes: tuple[str, ...]
    #: Lower limits of all classes but the last, decreasing; ``()``: not a banded scale.
    limits: tuple[float, ...] = ()
    #: What the limits bound (``"I_S"``, ``"P(overturning)"``); ``""`` for no band.
    measure: str = ""

    @property
    def worst_first(self) -> tuple[str, ...]:
        """Return the classes from the worst down."""
        return self.classes[::-1] if self is SAFETY_CLASS else self.classes

    def classify(self, value: float, limits: Sequence[float] | None = None) -> str:
        """Return the class of ``value`` (:func:`band` with this scale's limits by default).

        Raises
        ------
        ValueError
            For a scale without bands (``record_class``).
        """
        if not self.limits:
            raise ValueError(f"{self.name} is not a banded scale")
        return band(value, self.classes, self.limits if limits is None else limits)


def band(value: float, names: Sequence[str], limits: Sequence[float]) -> str:
    """Return the first of ``names`` whose lower limit ``value`` reaches, else the last one.

    :data:`UNDEFINED` for NaN.

    Parameters
    ----------
    value : float
        The measure (``I_S``, ``P``).
    names : sequence of str
        The classes, highest measure first.
    limits : sequence of float
        Their lower limits, decreasing (one fewer than ``names``).

    Returns
    -------
    str
    """
    if math.isnan(value):
        return UNDEFINED
    for name, limit in zip(names, limits, strict=False):
        if value >= limit:
            return name
    return names[-1]


#: ``run``: record-based classes (:func:`rockscreen.pipeline.screening.risk.risk_class`).
RECORD_CLASS = ClassScale("record_class", "run", RECORD_RISK_CLASSES)
#: ``assess``: the band of the governing ``I_S`` = T_R,C / T_R,SLV (module docstring).
SAFETY_CLASS = ClassScale(
    "safety_class", "assess", ("meets", "moderate", "high", "very_high"), (1.0, 0.6, 0.3), "I_S"
)
#: ``scenario``: the band of the probability of overturning under one event (rockscreen's
#: choice: even odds, one in five, one in twenty).
SCENARIO_CLASS = ClassScale(
    "scenario_class",
    "scenario",
    ("very_high", "high", "moderate", "low"),
    (0.5, 0.2, 0.05),
    "P(overturning)",
)
#: Every scale by name.
SCALES = {scale.name: scale for scale in (RECORD_CLASS, SAFETY_CLASS, SCENARIO_CLASS)}


class Completeness(enum.Enum):
    """Which of a verdict's checks that can fail before rigid overturning were made.

    ``COMPLETE``: every one the tower has was made; ``PARTIAL``: some were not made for
    want of data (their messages say which); ``ROCKING_ONLY``: none was made (no bells'
    part checked and no shaft flexure): only the whole tower's rigid overturning, which
    never makes a tower meet the code. Stored as the ``completeness`` column's word.
    """

    COMPLETE = "complete"
    PARTIAL = "partial"
    ROCKING_ONLY = "rocking_only"

    @classmethod
    def parse(cls, value: object) -> Completeness:
        """Return the completeness of a stored word (bytes or str).

        Raises
        ------
        ValueError
            For any other word (a stored table is checked, not guessed).
        """
        if isinstance(value, Completeness):
            return value
        if isinstance(value, bytes):
            value = value.decode("utf-8")
        try:
            return cls(str(value).strip())
        except ValueError:
            words = ", ".join(repr(c.value) for c in cls)
            raise ValueError(f"completeness {value!r}: expected one of {words}") from None


class ClassBound(enum.Enum):
    """Whether a class is only a bound of the tower's (a scenario class read on a bound of P).

    ``AT_MOST``: the tower is at most that risky (P is an upper bound); ``AT_LEAST``: at
    least. Stored as the ``class_bound`` column's word (``""``, ``"at_most"``, ``"at_least"``).
    """

    NONE = ""
    AT_MOST = "at_most"
    AT_LEAST = "at_least"

    @classmethod
    def parse(cls, value: object) -> ClassBound:
        """Return the class bound of a stored word (bytes, str or None).

        Raises
        ------
        ValueError
            For any other word.
        """
        if isinstance(value, ClassBound):
            return value
        if value is None:
            return cls.NONE
        if isinstance(value, bytes):
            value = value.decode("utf-8")
        try:
            return cls(str(value).strip())
        except ValueError:
            raise ValueError(
                f"class bound {value!r}: expected '', 'at_most' or 'at_least'"
            ) from None


def scenario_class_of(
    p_overturning: float, p_bound: Bound, limits: Sequence[float] | None = None
) -> tuple[str, ClassBound]:
    """Return the scenario class of P and whether it is only a bound of the tower's class.

    ``AT_MOST`` for an upper bound of P whose class is not already the lowest, ``AT_LEAST``
    for a lower bound whose class is not already the highest, else ``NONE``.

    Parameters
    ----------
    p_overturning : float
        Probability of overturning under the event [-].
    p_bound : Bound
        Whether P is a bound (:class:`~rockscreen.pipeline.verdict.status.Bound`).
    limits : sequence of float, optional
        Lower limits of the classes (:data:`SCENARIO_CLASS`'s by default).
    """
    cls = SCENARIO_CLASS.classify(p_overturning, limits)
    names = SCENARIO_CLASS.classes
    if p_bound is Bound.UPPER and cls != names[-1]:
        return cls, ClassBound.AT_MOST
    if p_bound is Bound.LOWER and cls != names[0]:
        return cls, ClassBound.AT_LEAST
    return cls, ClassBound.NONE


#: How a ``meets`` resting on rigid overturning alone is printed and counted.
INCOMPLETE = "incomplete"
#: The ``assess`` classes as counted and printed (a ``meets`` split by completeness), worst first.
SAFETY_COUNTED = ("very_high", "high", "moderate", INCOMPLETE, "meets")


def counted_safety_class(cls: str, completeness: Completeness) -> str:
    """Return the class an ``assess`` tower is counted and printed under.

    A ``meets`` reached on rigid overturning alone (:attr:`Completeness.ROCKING_ONLY`) is
    :data:`INCOMPLETE`; every other class is itself (a missing check could only lower it).

    Parameters
    ----------
    cls : str
        A word of :data:`SAFETY_CLASS` (or ``undefined``).
    completeness : Completeness
        The verdict's completeness.

    Returns
    -------
    str
    """
    if cls == SAFETY_CLASS.classes[0] and completeness is Completeness.ROCKING_ONLY:
        return INCOMPLETE
    return cls


@dataclass(frozen=True)
class ClassMarks:
    """A row's class and the marks beside it, read from their own typed columns.

    Nothing is parsed: ``risk_class`` is one word of its scale, ``completeness``,
    ``basis_compliant`` and ``class_bound`` are their own columns (:func:`class_marks`).
    """

    #: The class word (:data:`UNDEFINED` when the row has none).
    cls: str
    completeness: Completeness = Completeness.COMPLETE
    basis_compliant: bool = True
    bound: ClassBound = ClassBound.NONE

    @property
    def counted(self) -> str:
        """Return the class the tower is counted and printed under.

        (:func:`counted_safety_class`.)
        """
        return counted_safety_class(self.cls, self.completeness)


def _flag(value: object) -> bool:
    """Return a stored flag (``True``, ``"True"``, ``np.True_``...); missing or ``""``: True."""
    if value is None or value == "":
        return True
    if isinstance(value, bytes):
        value = value.decode("utf-8")
    if isinstance(value, str):
        return value.strip().lower() not in ("false", "0", "no")
    return bool(value)


def class_marks(row: object) -> ClassMarks:
    """Return the class and marks of a summary row (a mapping).

    It reads ``risk_class`` (a word of its scale), ``completeness``, ``basis_compliant``
    and ``class_bound``. A row without a mark's column is unmarked for it (a ``run`` or
    ``scenario`` row has no ``completeness``; a ``run`` row no ``basis_compliant``).
    """
    get = row.get  # type: ignore[attr-defined]
    cls = get("risk_class", "")
    cls = cls.decode("utf-8") if isinstance(cls, bytes) else str(cls or "")
    completeness = get("completeness", "")
    return ClassMarks(
        cls=cls or UNDEFINED,
        completeness=Completeness.parse(completeness) if completeness else Completeness.COMPLETE,
        basis_compliant=_flag(get("basis_compliant")),
        bound=ClassBound.parse(get("class_bound") or None),
    )
