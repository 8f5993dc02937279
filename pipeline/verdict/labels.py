"""A class as the reader sees it: the word of its scale with its marks, rendered, never parsed.

:func:`class_label` is the one place a class becomes text for a reader (the terminal table,
the HTML report): ``"meets (basis not code-compliant)"``, ``"incomplete (rocking only:
...)"``, ``"high (at most)"``. The text it returns is a :class:`ClassLabel`, a ``str`` that
carries its typed marks (:class:`~rockscreen.pipeline.verdict.scales.ClassMarks`), so a
consumer that counts or colours a label reads :attr:`ClassLabel.marks` instead of
splitting the text. The exports never write a label: their ``risk_class`` is the plain word
and the marks are their own columns (:func:`~rockscreen.pipeline.verdict.scales.class_marks`).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

from rockscreen.pipeline.verdict.checks import loads_not_made
from rockscreen.pipeline.verdict.messages import Message, message, render, render_all
from rockscreen.pipeline.verdict.scales import (
    ClassBound,
    ClassMarks,
    Completeness,
    class_marks,
)

__all__ = [
    "NONCOMPLIANT_MARK",
    "ClassLabel",
    "class_label",
    "marks_of",
    "not_made_reasons",
    "row_class_label",
]

#: What every class built on a record set that fails NTC 2018 §3.2.3.6 carries.
NONCOMPLIANT_MARK = render(message("class.mark.noncompliant"))


class ClassLabel(str):
    """A class as printed, carrying the typed marks it was rendered from.

    Attributes
    ----------
    marks : ClassMarks
        The class word and its marks.
    not_made : str
        The checks not made as stored (``checks_not_made``), ``""`` for none.
    reasons : tuple of Message or None
        The same checks' reasons as messages (``checks_not_made_codes``), so a reader renders
        them in its language; None for a label built from text alone (an archive written
        before the codes).
    """

    marks: ClassMarks
    not_made: str
    reasons: tuple[Message, ...] | None

    def __new__(
        cls,
        text: str,
        marks: ClassMarks,
        not_made: str = "",
        reasons: tuple[Message, ...] | None = None,
    ) -> ClassLabel:
        """Return the label ``text`` carrying ``marks``, ``not_made`` and its ``reasons``."""
        obj = super().__new__(cls, text)
        obj.marks = marks
        obj.not_made = not_made
        obj.reasons = reasons
        return obj

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle the label with its marks."""
        return (ClassLabel, (str(self), self.marks, self.not_made, self.reasons))

    def reasons_text(self, lang: str = "en") -> str | None:
        """Return the checks not made, without a heading, in ``lang`` (None: no messages)."""
        return None if self.reasons is None else render_all(self.reasons, lang)


def class_label(
    cls: str,
    basis_compliant: bool = True,
    checks_not_made: str = "",
    completeness: Completeness | None = None,
    bound: ClassBound = ClassBound.NONE,
    lang: str = "en",
    reasons: tuple[Message, ...] | None = None,
) -> ClassLabel:
    """Return the class as printed: ``cls``, marked when the verdict is not the code's.

    A verdict built on a non-compliant record set (``assess --allow-noncompliant``) never
    reads as a plain ``meets`` (``"meets (basis not code-compliant)"``); a ``meets`` when
    checks that could fail earlier were not made carries them (``"meets (LV1 not made
    ...)"``), and one on rigid overturning alone (``completeness`` ROCKING_ONLY) is no
    ``meets`` at all: it reads ``incomplete`` with the missing checks. A lower class is
    not marked for missing checks: a missing check can only lower it further. A scenario
    class read on a bound of P that leaves it open reads ``"high (at most)"``.

    Parameters
    ----------
    cls : str
        A class word of its scale (or ``"undefined"``).
    basis_compliant : bool
        Whether the record sets behind the verdict meet NTC 2018 §3.2.3.6.
    checks_not_made : str
        The checks not made and why, as stored (``checks_not_made``); ``""``: all made.
    completeness : Completeness, optional
        The verdict's completeness; by default complete without ``checks_not_made``,
        partial with it.
    bound : ClassBound
        Whether the class is only a bound of the tower's.
    lang : str
        ``"en"`` or ``"it"`` (the marks' language; ``checks_not_made`` is shown as stored).
    reasons : tuple of Message, optional
        The checks not made as messages (carried by the label: :meth:`ClassLabel.reasons_text`).

    Returns
    -------
    ClassLabel
    """
    if completeness is None:
        completeness = Completeness.PARTIAL if checks_not_made else Completeness.COMPLETE
    marks = ClassMarks(cls, completeness, basis_compliant, bound)
    words = [] if basis_compliant else [render(message("class.mark.noncompliant"), lang)]
    if bound is not ClassBound.NONE:
        words.append(render(message(f"class.bound.{bound.value}"), lang))
    if checks_not_made and cls == "meets":
        words.append(checks_not_made)
    text = " ".join([marks.counted, *(f"({word})" for word in words)])
    return ClassLabel(text, marks, checks_not_made, reasons)


def row_class_label(row: Mapping[str, Any], lang: str = "en") -> ClassLabel:
    """Return :func:`class_label` of a summary row, read from its typed columns.

    It reads ``risk_class``, ``basis_compliant``, ``completeness``, ``class_bound``,
    ``checks_not_made`` and ``checks_not_made_codes`` (the same reasons as messages, carried
    by the label; :func:`~rockscreen.pipeline.verdict.scales.class_marks`); a row without
    one of them is unmarked for it.
    """
    marks = class_marks(row)
    missing = row.get("checks_not_made", "")
    missing = missing if isinstance(missing, str) else ""
    codes = row.get("checks_not_made_codes")
    reasons = None
    if isinstance(codes, (str, bytes)) and codes:
        reasons = tuple(loads_not_made(codes).values())
    return class_label(
        marks.cls, marks.basis_compliant, missing, marks.completeness, marks.bound, lang, reasons
    )


def marks_of(label: object) -> ClassMarks:
    """Return the marks a label carries (a plain class word: unmarked)."""
    if isinstance(label, ClassLabel):
        return label.marks
    text = label.decode("utf-8") if isinstance(label, bytes) else str(label or "")
    return class_marks({"risk_class": text})


def not_made_reasons(label: ClassLabel) -> str:
    """Return the checks not made a label carries, without the ``rocking only`` heading.

    :func:`~rockscreen.pipeline.verdict.rules.not_made_text` writes the heading before the
    reasons when (and only when) the completeness is ROCKING_ONLY, so the typed mark says
    whether to remove it.
    """
    if label.marks.completeness is not Completeness.ROCKING_ONLY:
        return label.not_made
    heading = render(message("completeness.rocking_only")) + ": "
    return label.not_made.removeprefix(heading)
