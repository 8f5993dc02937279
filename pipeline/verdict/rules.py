"""The verdict's rules: pure functions over check results, no text compared.

- :func:`governing`: the made check of lowest capacity ``a_C`` (ties: the lower ``I_S``,
  then the first in the order given: the part models first, so a part whose capacity equals
  the whole tower's, the one that stopped the whole tower's IDA, is named), and whether it
  is *shown* to govern (a lower bound among other checks is not: docs/code_checks.md §8);
- :func:`completeness`: which checks that could fail earlier were not made, and whether
  only the whole tower's rigid overturning was (:class:`~.scales.Completeness`);
- :func:`disagreement`: where whole-tower rocking and the code's checks (the kinematic
  checks, the LV1 model) fall in different classes, and why (docs/code_checks.md §5);
- :func:`verdict`: the :class:`~.checks.Verdict` of a tower's check results.

The safety class is the band of the governing ``I_S`` on
:data:`~rockscreen.pipeline.verdict.scales.SAFETY_CLASS` (limits given, e.g.
``--class-limits``).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

from rockscreen.pipeline.verdict.checks import CheckResult, Family, Method, Verdict
from rockscreen.pipeline.verdict.messages import Message, message, render, render_all
from rockscreen.pipeline.verdict.scales import SAFETY_CLASS, UNDEFINED, Completeness
from rockscreen.pipeline.verdict.status import Bound

__all__ = [
    "NotMadeText",
    "completeness",
    "disagreement",
    "governing",
    "governing_label",
    "not_made_text",
    "verdict",
]


def governing(checks: Iterable[CheckResult]) -> tuple[CheckResult | None, bool]:
    """Return the made check of lowest capacity and whether it is shown to govern.

    Parameters
    ----------
    checks : iterable of CheckResult
        A tower's check results, in the order that breaks ties (module docstring).

    Returns
    -------
    check : CheckResult or None
        None when no check was made.
    shown : bool
        False when its capacity is a lower bound and another check was made: the minimum
        of a lower bound and other values is a lower bound of the governing capacity, but
        which check governs is not known.
    """
    made = [c for c in checks if c.made]
    if not made:
        return None, False
    chosen = min(made, key=lambda c: (c.capacity_ag_g, c.safety_index))
    return chosen, not (chosen.bound is Bound.LOWER and len(made) > 1)


def completeness(checks: Iterable[CheckResult]) -> tuple[Completeness, tuple[Message, ...]]:
    """Return which checks that could fail earlier were made, and why the others were not.

    The results passed are the tower's checks; those not made (or failed) carry their
    reason. Only the whole tower's rigid overturning was checked
    (:attr:`~.scales.Completeness.ROCKING_ONLY`) when both the bells' part (a part model's
    rocking) and the shaft's flexure (LV1) were not made.

    Returns
    -------
    completeness : Completeness
    reasons : tuple of Message
        The reasons, in the order of ``checks``.
    """
    missing = [c for c in checks if not c.made]
    reasons = tuple(c.reason for c in missing if c.reason is not None)
    if not missing:
        return Completeness.COMPLETE, reasons
    families = {c.family for c in missing}
    if {Family.PART_ROCKING, Family.SHAFT_FLEXURE} <= families:
        return Completeness.ROCKING_ONLY, reasons
    return Completeness.PARTIAL, reasons


def disagreement(checks: Sequence[CheckResult], limits: Sequence[float]) -> tuple[Message, ...]:
    """Return why whole-tower rocking and the code's checks differ in class, one message each.

    Rocking (the whole tower's IDA) against the kinematic checks (the lowest ``I_S`` of
    the non-linear checks, which are the code's verdict) and against the LV1 model.

    Parameters
    ----------
    checks : sequence of CheckResult
        A tower's check results.
    limits : sequence of float
        I_S limits of the safety classes.

    Returns
    -------
    tuple of Message
        Empty when the classes agree or rocking was not made.
    """
    rocking = next((c for c in checks if c.made and c.family is Family.TOWER_ROCKING), None)
    if rocking is None or not math.isfinite(rocking.safety_index):
        return ()
    a = float(rocking.safety_index)
    ca = SAFETY_CLASS.classify(a, limits)
    out = []
    kinematic = [c for c in checks if c.made and c.method is Method.KINEMATIC]
    lv1 = [c for c in checks if c.made and c.method is Method.LV1]
    for code, others in (("disagree.kinematic", kinematic), ("disagree.lv1", lv1)):
        if not others:
            continue
        b = float(min(others, key=lambda c: c.safety_index).safety_index)
        if not math.isfinite(b):
            continue
        cb = SAFETY_CLASS.classify(b, limits)
        if cb != ca:
            said = message(
                code,
                rocking=a,
                rocking_class=message(f"safety_class.{ca}"),
                other=b,
                other_class=message(f"safety_class.{cb}"),
            )
            out.append(said)
    return tuple(out)


def verdict(
    checks: Sequence[CheckResult], limits: Sequence[float], basis_compliant: bool = True
) -> Verdict:
    """Return the verdict of a tower's check results (module docstring).

    Parameters
    ----------
    checks : sequence of CheckResult
        The tower's checks, in tie-breaking order (the part models first).
    limits : sequence of float
        I_S limits of the safety classes.
    basis_compliant : bool
        Whether the record sets behind it meet NTC 2018 §3.2.3.6.
    """
    checks = tuple(checks)
    chosen, shown = governing(checks)
    complete, reasons = completeness(checks)
    return Verdict(
        checks=checks,
        governing=None if chosen is None else chosen.check,
        governing_shown=shown,
        safety_class=UNDEFINED
        if chosen is None
        else SAFETY_CLASS.classify(chosen.safety_index, limits),
        completeness=complete,
        not_made=reasons,
        basis_compliant=basis_compliant,
        disagreement=disagreement(checks, limits),
    )


def governing_label(result: Verdict, lang: str = "en") -> str:
    """Return the governing check's label as printed (``""`` without one).

    A check not shown to govern says so (``"... (a lower bound: not shown to govern)"``).
    """
    chosen = result.governing_check
    if chosen is None:
        return ""
    label = render(chosen.label, lang)
    if result.governing_shown:
        return label
    return render(message("check.not_shown_to_govern", label=label), lang)


@dataclass(frozen=True)
class NotMadeText:
    """The checks not made, rendered in the reader's language when shown (:func:`not_made_text`)."""

    completeness: Completeness
    reasons: tuple[Message, ...]

    def render(self, lang: str = "en") -> str:
        """Return the text in ``lang``."""
        return not_made_text(self.completeness, self.reasons, lang)


def not_made_text(complete: Completeness, reasons: Sequence[Message], lang: str = "en") -> str:
    """Return the checks not made as printed (``checks_not_made``; ``""`` for none).

    ``"rocking only: <reasons>"`` when only rigid overturning was checked.
    """
    text = render_all(reasons, lang)
    if complete is Completeness.ROCKING_ONLY:
        return f"{render(message('completeness.rocking_only'), lang)}: {text}"
    return text
