"""A tower's checks as typed results, and its verdict as a frozen record of them.

A :class:`CheckResult` is one check of one part of a tower (whole-tower rocking, a part
model's rocking, the shaft's LV1 flexure, a kinematic check): its :class:`Family`, whether
it was made (:class:`~rockscreen.pipeline.verdict.status.Status`), its capacity ``a_C``
[g] (ag on rock, read on the site's NTC hazard), its safety index ``I_S`` [-], whether those
are bounds (:class:`~rockscreen.pipeline.verdict.status.Bound`), why it was not made (a
:class:`~rockscreen.pipeline.verdict.messages.Message`) and its details (units declared in
:data:`DETAIL_UNITS`). A :class:`Verdict` holds a tower's check results and what
:mod:`rockscreen.pipeline.verdict.rules` finds in them: the governing check, the safety
class, the completeness, the basis compliance and where rocking and the code's checks
disagree. The code branches on these fields; text exists only when a message is rendered.
"""

from __future__ import annotations

import enum
import json
import math
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field

from rockscreen.pipeline.verdict.messages import Message, catalogue, dumps, loads, message
from rockscreen.pipeline.verdict.scales import UNDEFINED, Completeness
from rockscreen.pipeline.verdict.status import Bound, Status

__all__ = [
    "DETAIL_UNITS",
    "CheckResult",
    "Family",
    "Method",
    "Verdict",
    "check_label",
    "dumps_not_made",
    "family_label",
    "loads_not_made",
]


class Family(enum.Enum):
    """The family of a check: which mechanism it checks (the ``governing_kind`` column).

    Rendered from the catalogue (:func:`family_label`): ``shaft flexure``, ``tower
    rocking``, ``<part> rocking``, ``kinematic``, ``gable``. Every check of the bell gable
    (its rocking, its kinematic check) is of the ``GABLE`` family.
    """

    SHAFT_FLEXURE = "shaft_flexure"
    TOWER_ROCKING = "tower_rocking"
    PART_ROCKING = "part_rocking"
    KINEMATIC = "kinematic"
    GABLE = "gable"


class Method(enum.Enum):
    """How a check finds its capacity.

    ``ROCKING``: an IDA of a rocking model (the whole tower, a part model); ``KINEMATIC``:
    the code's kinematic analysis (Circolare 2019 §C8.7.1); ``LV1``: the Guidelines' LV1
    tower model (DPCM 9/2/2011 §5.4.4).
    """

    ROCKING = "rocking"
    KINEMATIC = "kinematic"
    LV1 = "lv1"


#: Units of the details a check may carry (schema words: ``g``, ``1``, ``s``, ``m``).
DETAIL_UNITS: dict[str, str] = {
    "fragility_median_g": "g",  # the collapse (overturning) median, ag on rock
    "fragility_beta": "1",
    "p_overturning_50y": "1",
    "alpha0": "1",  # load multiplier of activation
    "e_star": "1",  # participating mass fraction
    "a0_g": "g",  # spectral acceleration of activation a0*
    "du_star_m": "m",  # d_SLV
    "t_slv_s": "s",  # T_SLV
    "t0_s": "s",  # T0 of an element free to vibrate
    "period_s": "s",  # LV1: T1
    "compression_ratio": "1",  # LV1: sigma_0 / (0.85 f_d) at the critical section
}


@dataclass(frozen=True)
class CheckResult:
    """One check of one part of a tower.

    Raises
    ------
    ValueError
        On construction: a made check without a finite capacity, a check not made without
        its reason, or a detail whose units :data:`DETAIL_UNITS` does not declare.
    """

    #: The check's id, ``<part>.<what>`` (``"tower.rocking"``, ``"belfry.rocking"``,
    #: ``"tower.kinematic_nonlinear"``, ``"shaft.lv1"``).
    check: str
    #: The part checked (``"tower"``, ``"belfry"``, ``"gable"``, ``"shaft"``).
    part: str
    family: Family
    method: Method
    status: Status
    #: Capacity a_C [g], ag on rock; NaN when not made.
    capacity_ag_g: float = math.nan
    #: Safety index I_S [-]; NaN when not made.
    safety_index: float = math.nan
    #: Whether capacity and I_S are bounds of the true values.
    bound: Bound = Bound.NONE
    #: Why the check was not made (or failed); None for a made check.
    reason: Message | None = None
    #: Details, name -> value in the units of :data:`DETAIL_UNITS`.
    details: Mapping[str, float] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if self.status is Status.MADE and not math.isfinite(self.capacity_ag_g):
            raise ValueError(f"check {self.check}: made without a finite capacity")
        if self.status is not Status.MADE and self.reason is None:
            raise ValueError(f"check {self.check}: {self.status.value} without its reason")
        unknown = set(self.details) - set(DETAIL_UNITS)
        if unknown:
            raise ValueError(f"check {self.check}: details without units {sorted(unknown)}")

    @property
    def made(self) -> bool:
        """Whether the check was made (gave a capacity)."""
        return self.status is Status.MADE

    @property
    def label(self) -> Message:
        """Return the check's label (:func:`check_label`)."""
        return check_label(self.check, self.part)

    @property
    def kind(self) -> Message:
        """Return the check's family as printed (:func:`family_label`)."""
        return family_label(self.family, self.part)


def check_label(check: str, part: str) -> Message:
    """Return the label of a check (``"whole-tower rocking"``, ``"belfry rocking"``...).

    A part model's rocking check without its own entry (a third part model) is
    ``"<part> rocking"``; any other check without its entry ``check.<id>`` (a check added
    as a module whose catalogue entries are not loaded) is its id.
    """
    if check == "shaft.lv1":
        return message("check.lv1")
    code = f"check.{check}"

    if code in catalogue():
        return message(code)
    if check.endswith(".rocking"):
        return message("check.part.rocking", part=part)
    return message("check.unlabelled", check=check)


def family_label(family: Family, part: str = "") -> Message:
    """Return a family as printed (the ``governing_kind`` column's text)."""
    if family is Family.PART_ROCKING:
        return message("family.part_rocking", part=part)
    return message(f"family.{family.value}")


@dataclass(frozen=True)
class Verdict:
    """A tower's verdict: its check results and what the rules find in them.

    Built by :func:`rockscreen.pipeline.verdict.rules.verdict`.
    """

    checks: tuple[CheckResult, ...]
    #: The id of the check of lowest capacity; None when no check was made.
    governing: str | None
    #: Whether that check is shown to govern: a lower bound among other checks is not
    #: (the minimum is a lower bound of the governing capacity; which check governs is
    #: not known).
    governing_shown: bool
    #: The :data:`~rockscreen.pipeline.verdict.scales.SAFETY_CLASS` word of the governing
    #: I_S (``"undefined"`` without one).
    safety_class: str
    #: Which checks that could fail earlier were made.
    completeness: Completeness
    #: Why each check that could fail earlier was not made.
    not_made: tuple[Message, ...]
    #: Whether the record sets behind the verdict meet NTC 2018 §3.2.3.6.
    basis_compliant: bool = True
    #: Where rocking and the code's checks disagree in class, and why.
    disagreement: tuple[Message, ...] = ()

    @property
    def governing_check(self) -> CheckResult | None:
        """Return the governing check's result, None without one."""
        return next((c for c in self.checks if c.check == self.governing), None)

    @property
    def classified(self) -> bool:
        """Whether the verdict has a class (a governing check with a finite I_S)."""
        return self.safety_class != UNDEFINED


def dumps_not_made(checks: Iterable[CheckResult]) -> str:
    """Return the reasons of the checks not made as stored text (``checks_not_made_codes``).

    A JSON list of ``[check id, [code, {params}]]``, one per check not made (or failed), in
    order; ``"[]"`` for none. The printed ``checks_not_made`` is rendered from the same
    messages; this column lets a reader find one check's reason by its id.
    """
    out = []
    for c in checks:
        if not c.made and c.reason is not None:
            out.append([c.check, json.loads(dumps([c.reason]))[0]])
    return json.dumps(out, ensure_ascii=False, sort_keys=True)


def loads_not_made(text: str | bytes | None) -> dict[str, Message]:
    """Return check id -> reason from :func:`dumps_not_made`'s text (``{}`` for none).

    Raises
    ------
    ValueError
        For text that is not such a list or a message code not in the catalogue.
    """
    if isinstance(text, bytes):
        text = text.decode("utf-8")
    if not text:
        return {}
    try:
        items = json.loads(text)
    except json.JSONDecodeError as exc:
        raise ValueError(f"stored checks not made are not JSON: {exc.msg}") from None
    if not isinstance(items, list) or not all(
        isinstance(i, list) and len(i) == 2 and isinstance(i[0], str) for i in items
    ):
        raise ValueError("stored checks not made: expected a JSON list of [check, message]")
    return {check: loads(json.dumps([item]))[0] for check, item in items}
