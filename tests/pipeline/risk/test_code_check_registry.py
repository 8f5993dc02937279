"""The code checks as registered objects (issue 29): LV1 and the kinematic checks."""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

from rockscreen.pipeline.risk.checks.governing import tower_check_results
from rockscreen.pipeline.risk.checks.registry import code_check, code_checks, register
from rockscreen.pipeline.verdict.checks import Family, Method
from rockscreen.pipeline.verdict.status import Bound, Status


def test_lv1_and_the_kinematic_checks_are_registered_in_tie_breaking_order():
    assert [c.id for c in code_checks()] == [
        "shaft.lv1",
        "tower.kinematic_nonlinear",
        "belfry.kinematic_nonlinear",
        "gable.kinematic_nonlinear",
    ]
    lv1 = code_check("shaft.lv1")
    assert lv1.requires == ("wall_thickness_m", "masonry_type")
    assert lv1.family is Family.SHAFT_FLEXURE and lv1.method is Method.LV1
    assert lv1.governs_before_rocking and "§5.4.4" in lv1.covers
    assert not code_check("tower.kinematic_nonlinear").governs_before_rocking
    assert code_check("gable.kinematic_nonlinear").family is Family.GABLE
    assert "belfry_height_m" in code_check("belfry.kinematic_nonlinear").requires
    with pytest.raises(KeyError, match="registered: shaft.lv1"):
        code_check("spire.kinematic_nonlinear")


def test_a_check_without_its_result_is_not_made_with_a_message():
    lv1 = code_check("shaft.lv1").evaluate({"lv1_capacity_ag_g": math.nan})
    assert lv1.status is Status.NOT_MADE
    assert lv1.reason.render() == (
        "shaft flexure (LV1) not made (no wall_thickness_m, masonry_type in the inventory)"
    )
    assert "non eseguita" in lv1.reason.render("it")
    tower = code_check("tower.kinematic_nonlinear").evaluate({})
    assert tower.status is Status.NOT_MADE and tower.reason.render().endswith("(no result)")


def test_a_check_reads_its_result_and_details_off_the_row():
    row = {
        "lv1_capacity_ag_g": 0.12,
        "lv1_safety_index": 0.8,
        "lv1_bound": "lower",
        "lv1_period_s": 0.9,
        "lv1_compression_ratio": math.nan,
    }
    result = code_check("shaft.lv1").evaluate(row)
    assert result.made and result.capacity_ag_g == 0.12 and result.safety_index == 0.8
    assert result.bound is Bound.LOWER
    assert dict(result.details) == {"period_s": 0.9}  # a NaN detail is left out
    # governing's slot table reads the registered checks: the same result.
    (lv1,) = [r for r in tower_check_results(row) if r.check == "shaft.lv1"]
    assert lv1 == result


def test_an_id_is_registered_once():
    lv1 = code_check("shaft.lv1")
    assert register(lv1) is lv1  # the same declaration again: no change
    with pytest.raises(ValueError, match="registered twice"):
        register(replace(lv1, covers="something else"))
