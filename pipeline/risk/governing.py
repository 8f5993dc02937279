"""The mechanism that governs a tower's verdict in ``assess`` (issue 22).

Among the capacities a tower's summary row holds (``a_C`` [g], ag on rock, each read on
the same NTC hazard: docs/code_checks.md §8) -- whole-tower rocking (the IDA SLV capacity),
each part model's rocking (:func:`rockscreen.pipeline.risk.tower_checks.part_fragility_columns`),
shaft flexure (LV1, :mod:`rockscreen.pipeline.risk.tower_lv1_checks`) and the non-linear
kinematic checks (:func:`rockscreen.pipeline.risk.tower_checks.kinematic_columns`) --
:func:`governing_columns` names the lowest, gives the class of its ``I_S``, lists the
checks that could fail earlier and were not made (``checks_not_made``, which
:func:`rockscreen.pipeline.risk.classes.class_label` prints), and says in one sentence
where rocking and the code's checks disagree, and why (:func:`disagreement`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from rockscreen.pipeline.risk.classes import ROCKING_ONLY, risk_class
from rockscreen.pipeline.risk.tower_checks import KINEMATIC_PARTS, part_model_names
from rockscreen.pipeline.risk.tower_lv1_checks import LV1_NOT_MADE

__all__ = [
    "BELFRY_MISSING",
    "DISAGREEMENT_SENTENCE",
    "GOVERNING_KINDS",
    "LV1_DISAGREEMENT_SENTENCE",
    "MECHANISMS",
    "disagreement",
    "governing_columns",
    "governing_kind",
]

#: Why the belfry checks are not made (no belfry columns, and no bell gable carrying the
#: bells instead): the whole tower alone was checked.
BELFRY_MISSING = "belfry not checked (no belfry columns in the inventory)"
#: Mechanism labels of the ``governing`` column (``<part>`` rocking is the part model's name).
MECHANISMS = {
    "rocking": "whole-tower rocking",
    "tower_nonlinear": "whole-tower kinematic (non-linear)",
    "belfry_nonlinear": "belfry kinematic (non-linear)",
    "gable_nonlinear": "bell gable kinematic (non-linear)",
    "lv1": "shaft flexure (LV1)",
}
#: What ``governing_kind`` says: the family of the governing mechanism.
GOVERNING_KINDS = ("shaft flexure", "tower rocking", "belfry rocking", "kinematic", "gable")
#: Why the kinematic checks and the rocking dynamics can disagree (docs/code_checks.md §5).
DISAGREEMENT_SENTENCE = (
    "the kinematic checks ignore rocking's size effect: a large block outlasts accelerations "
    "above alpha0 g too brief to overturn it (Makris & Konstantinidis 2003), while the IDA "
    "sees the records' pulses, their vertical motion and (belfry) the shaft's amplification"
)
#: Why the LV1 model and the rocking dynamics can disagree (docs/code_checks.md §5).
LV1_DISAGREEMENT_SENTENCE = (
    "the LV1 model checks the shaft's masonry sections in flexure under their own weight, "
    "which rigid rocking takes as infinitely strong: a tall shaft cracks at its critical "
    "section long before it could overturn as one block"
)


def _candidates(row: dict[str, Any]) -> list[tuple[str, float, float, str]]:
    """Return ``(mechanism, a_C [g], I_S, bound)`` of every check made on the row.

    The part models come first: the whole tower's IDA stops at the first model to reach the
    level, so a part whose capacity equals the whole tower's is the one that drove it, and
    the tie (``min`` keeps the first) names the part.
    """
    out = []
    for model in part_model_names():
        out.append(
            (
                f"{model} rocking",
                row.get(f"{model}_capacity_ag_g", math.nan),
                row.get(f"{model}_safety_index", math.nan),
                row.get(f"{model}_slv_bound", ""),
            )
        )
    out.append(
        (MECHANISMS["rocking"], row["capacity_pga_g"], row["safety_index"], row["slv_bound"])
    )
    out.append(
        (
            MECHANISMS["lv1"],
            row.get("lv1_capacity_ag_g", math.nan),
            row.get("lv1_safety_index", math.nan),
            row.get("lv1_bound", ""),
        )
    )
    for part in KINEMATIC_PARTS:
        out.append(
            (
                MECHANISMS[f"{part}_nonlinear"],
                row.get(f"{part}_kinematic_nonlinear_capacity_ag_g", math.nan),
                row.get(f"{part}_kinematic_nonlinear_safety_index", math.nan),
                row.get(f"{part}_kinematic_nonlinear_bound", ""),
            )
        )
    return [c for c in out if isinstance(c[1], float) and math.isfinite(c[1])]


def governing_columns(
    row: dict[str, Any], class_limits: Sequence[float], missing: Sequence[str]
) -> dict[str, Any]:
    """Return the governing mechanism, its a_C and I_S, the class, and what was not made.

    Parameters
    ----------
    row : dict
        A summary row with the rocking, part and kinematic columns.
    class_limits : sequence of float
        I_S limits of the classes.
    missing : sequence of str
        The checks that could fail earlier and were not made, each with why.

    Returns
    -------
    dict
        ``governing``, ``governing_capacity_ag_g`` [g], ``governing_safety_index`` [-],
        ``governing_bound``, ``risk_class`` (from the governing I_S), ``checks_not_made``,
        ``checks_disagree``.
    """
    candidates = _candidates(row)
    text = "; ".join(missing)
    if BELFRY_MISSING in missing and any(m.startswith(LV1_NOT_MADE) for m in missing):
        # only the whole tower's rigid overturning (its rocking, its kinematic check) made
        text = f"{ROCKING_ONLY}: {text}"
    if not candidates:
        return {"checks_not_made": text}
    chosen = min(candidates, key=lambda c: (c[1], c[2]))
    name, ag, index, bound = chosen
    if bound == "lower" and any(c is not chosen for c in candidates):
        # min(a lower bound, other values or bounds) is a lower bound of the governing
        # capacity, but which mechanism governs is not known: said, not guessed.
        name = f"{name} (a lower bound: not shown to govern)"
    return {
        "governing": name,
        "governing_kind": governing_kind(name),
        "governing_capacity_ag_g": ag,
        "governing_safety_index": index,
        "governing_bound": bound or "",
        "risk_class": risk_class(index, class_limits),
        "checks_not_made": text,
        "checks_disagree": disagreement(row, class_limits),
    }


def governing_kind(label: str) -> str:
    """Return the family of a ``governing`` label, one of :data:`GOVERNING_KINDS`.

    ``shaft flexure`` (LV1), ``gable`` (the bell gable's kinematic checks or its rocking,
    the ``gable`` part model), ``kinematic``
    (the whole tower's or the belfry's), ``tower rocking`` (the whole tower's IDA),
    ``<part> rocking`` (a part model's IDA: ``belfry rocking``); ``""`` for no label.

    Parameters
    ----------
    label : str
        A ``governing`` label.

    Returns
    -------
    str
    """
    if not label:
        return ""
    if label.startswith(MECHANISMS["lv1"]):
        return "shaft flexure"
    if label.startswith(("bell gable", "gable ")):  # its kinematic checks, its rocking
        return "gable"
    if "kinematic" in label:
        return "kinematic"
    if label.startswith(MECHANISMS["rocking"]):
        return "tower rocking"
    return label.split(" (")[0]


def disagreement(row: dict[str, Any], class_limits: Sequence[float]) -> str:
    """Return why rocking and the code's checks differ in class (one sentence each), else ``""``.

    Rocking against the kinematic checks (:data:`DISAGREEMENT_SENTENCE`) and against the LV1
    model (:data:`LV1_DISAGREEMENT_SENTENCE`).

    Parameters
    ----------
    row : dict
        A summary row (``safety_index``, ``kinematic_safety_index``, ``lv1_safety_index``).
    class_limits : sequence of float
        I_S limits of the classes.

    Returns
    -------
    str
        The sentences joined by ``"; "``, ``""`` when the classes agree.
    """
    rocking = row.get("safety_index", math.nan)
    if not math.isfinite(rocking):
        return ""
    rocking_class = risk_class(rocking, class_limits)
    out = []
    for key, what, why in (
        ("kinematic_safety_index", "the kinematic checks", DISAGREEMENT_SENTENCE),
        ("lv1_safety_index", "the LV1 model", LV1_DISAGREEMENT_SENTENCE),
    ):
        other = row.get(key)
        if other is None or not math.isfinite(other):
            continue
        other_class = risk_class(other, class_limits)
        if other_class != rocking_class:
            out.append(
                f"rocking (I_S {rocking:.2f}, {rocking_class}) and {what} "
                f"(I_S {other:.2f}, {other_class}) disagree: {why}"
            )
    return "; ".join(out)
