"""The verdict's rules over typed check results, and the three class scales."""

from __future__ import annotations

import math

import pytest

from rockscreen.pipeline.verdict.checks import CheckResult, Family, Method, check_label
from rockscreen.pipeline.verdict.messages import message, render
from rockscreen.pipeline.verdict.rules import (
    completeness,
    disagreement,
    governing,
    governing_label,
    not_made_text,
    verdict,
)
from rockscreen.pipeline.verdict.scales import (
    INCOMPLETE,
    RECORD_CLASS,
    SAFETY_CLASS,
    SCALES,
    SCENARIO_CLASS,
    ClassBound,
    Completeness,
    counted_safety_class,
)
from rockscreen.pipeline.verdict.status import Bound, Status

from rockscreen_testsupport.checks import BELFRY_MISSING, LV1_MISSING

LIMITS = (1.0, 0.6, 0.3)


def made(check, family, method, ag, index, bound=Bound.NONE, part="tower"):
    return CheckResult(check, part, family, method, Status.MADE, ag, index, bound)


def rocking(ag=0.5, index=2.0, bound=Bound.NONE):
    return made("tower.rocking", Family.TOWER_ROCKING, Method.ROCKING, ag, index, bound)


def kinematic(ag=0.2, index=0.4, bound=Bound.NONE):
    return made("tower.kinematic_nonlinear", Family.KINEMATIC, Method.KINEMATIC, ag, index, bound)


def lv1(ag=0.1, index=0.5, bound=Bound.NONE):
    return made("shaft.lv1", Family.SHAFT_FLEXURE, Method.LV1, ag, index, bound, "shaft")


def test_a_check_result_refuses_what_it_cannot_be():
    with pytest.raises(ValueError, match="made without a finite capacity"):
        made("tower.rocking", Family.TOWER_ROCKING, Method.ROCKING, math.nan, 1.0)
    with pytest.raises(ValueError, match="without its reason"):
        CheckResult("shaft.lv1", "shaft", Family.SHAFT_FLEXURE, Method.LV1, Status.NOT_MADE)
    with pytest.raises(ValueError, match="details without units"):
        CheckResult(
            "tower.rocking",
            "tower",
            Family.TOWER_ROCKING,
            Method.ROCKING,
            Status.MADE,
            0.3,
            1.0,
            details={"speed_kmh": 3.0},
        )


def test_governing_is_the_made_check_of_lowest_capacity_first_on_ties():
    part = made("belfry.rocking", Family.PART_ROCKING, Method.ROCKING, 0.5, 2.0, part="belfry")
    chosen, shown = governing([part, rocking(0.5, 2.0), kinematic(0.6, 3.0), LV1_MISSING])
    assert chosen is part and shown  # the part model comes first: it drove the tie
    chosen, shown = governing([rocking(), kinematic(0.2, 0.4), lv1(0.1, 0.5)])
    assert chosen.check == "shaft.lv1" and shown
    assert governing([LV1_MISSING, BELFRY_MISSING]) == (None, False)


def test_a_lower_bound_among_other_checks_is_not_shown_to_govern():
    low = kinematic(0.26, 3.48, Bound.LOWER)
    chosen, shown = governing([rocking(0.55, 40.0), low])
    assert chosen is low and not shown
    assert governing([low]) == (low, True)  # alone, it is the only capacity known
    result = verdict([rocking(0.55, 40.0), low], LIMITS)
    assert governing_label(result) == (
        "whole-tower kinematic (non-linear) (a lower bound: not shown to govern)"
    )
    assert "non è dimostrato che governi" in governing_label(result, "it")


def test_completeness_names_what_was_not_made_and_when_rocking_alone_was():
    assert completeness([rocking(), lv1()]) == (Completeness.COMPLETE, ())
    state, reasons = completeness([rocking(), LV1_MISSING])
    assert state is Completeness.PARTIAL and reasons == (LV1_MISSING.reason,)
    state, reasons = completeness([BELFRY_MISSING, rocking(), LV1_MISSING])
    assert state is Completeness.ROCKING_ONLY
    assert not_made_text(state, reasons) == (
        "rocking only: belfry not checked (no belfry columns in the inventory); "
        "LV1 not made (no wall_thickness_m and masonry_type in the inventory)"
    )
    assert not_made_text(state, reasons, "it").startswith("solo ribaltamento rigido: cella")


def test_disagreement_is_one_message_per_check_family_of_another_class():
    assert disagreement([rocking(0.5, 2.0), kinematic(0.6, 1.5)], LIMITS) == ()
    (msg,) = disagreement([rocking(0.5, 2.0), kinematic(0.2, 0.4)], LIMITS)
    assert msg.code == "disagree.kinematic"
    assert msg.kwargs["other_class"] == message("safety_class.high")
    assert render(msg).startswith("rocking (I_S 2.00, meets) and the kinematic checks (I_S 0.40")
    assert "I_S 2,00, soddisfa la norma" in render(msg, "it")  # the class in Italian too
    both = disagreement([rocking(0.5, 2.0), kinematic(0.2, 0.4), lv1(0.1, 0.2)], LIMITS)
    assert [m.code for m in both] == ["disagree.kinematic", "disagree.lv1"]
    assert disagreement([kinematic(0.2, 0.4), lv1(0.1, 0.2)], LIMITS) == ()  # no rocking


def test_the_verdict_classes_the_governing_index():
    result = verdict([BELFRY_MISSING, rocking(0.5, 2.0), LV1_MISSING], LIMITS)
    assert result.governing == "tower.rocking" and result.governing_shown
    assert result.safety_class == "meets" and result.classified
    assert result.completeness is Completeness.ROCKING_ONLY
    assert counted_safety_class(result.safety_class, result.completeness) == INCOMPLETE
    assert counted_safety_class("high", Completeness.ROCKING_ONLY) == "high"
    assert verdict([LV1_MISSING], LIMITS).safety_class == "undefined"


def test_three_scales_three_names():
    assert set(SCALES) == {"record_class", "safety_class", "scenario_class"}
    assert RECORD_CLASS.worst_first[0] == "collapse"
    assert SAFETY_CLASS.worst_first == ("very_high", "high", "moderate", "meets")
    assert [SAFETY_CLASS.classify(v) for v in (1.0, 0.6, 0.59, 0.29, math.nan)] == [
        "meets",
        "moderate",
        "high",
        "very_high",
        "undefined",
    ]
    assert SAFETY_CLASS.classify(0.7, (2.0, 1.0, 0.5)) == "high"
    assert [SCENARIO_CLASS.classify(p) for p in (0.5, 0.2, 0.05, 0.01)] == [
        "very_high",
        "high",
        "moderate",
        "low",
    ]
    with pytest.raises(ValueError, match="not a banded scale"):
        RECORD_CLASS.classify(0.5)
    assert Completeness.parse(b"rocking_only") is Completeness.ROCKING_ONLY
    assert ClassBound.parse(None) is ClassBound.NONE
    with pytest.raises(ValueError, match="expected one of"):
        Completeness.parse("incomplete")


def test_labels_and_families_come_from_the_catalogue():
    assert render(check_label("tower.rocking", "tower")) == "whole-tower rocking"
    assert render(check_label("spire.rocking", "spire")) == "spire rocking"  # a third part
    assert render(lv1().kind) == "shaft flexure"
    part = made("spire.rocking", Family.PART_ROCKING, Method.ROCKING, 0.3, 1.0, part="spire")
    assert render(part.kind) == "spire rocking"


def test_the_row_s_checks_carry_their_details_in_declared_units():
    from rockscreen.pipeline.risk.checks.governing import belfry_not_made, tower_check_results
    from rockscreen.pipeline.verdict.checks import DETAIL_UNITS

    row = {
        "capacity_pga_g": 0.5,
        "safety_index": 2.0,
        "slv_bound": "lower",
        "collapse_median_g": 0.61,
        "collapse_beta": 0.4,
        "p_overturning_50y": math.nan,
        "tower_kinematic_nonlinear_capacity_ag_g": 0.2,
        "tower_kinematic_nonlinear_safety_index": 0.4,
        "tower_kinematic_nonlinear_bound": "",
        "tower_kinematic_alpha0": 0.12,
    }
    belfry, tower, kinematic = tower_check_results(row, [belfry_not_made()])
    assert belfry.status is Status.NOT_MADE and belfry.reason.code == "not_made.belfry"
    assert tower.bound is Bound.LOWER
    assert tower.details == {"fragility_median_g": 0.61, "fragility_beta": 0.4}  # NaN left out
    assert kinematic.details == {"alpha0": 0.12} and set(tower.details) <= set(DETAIL_UNITS)
