"""Class labels rendered from typed marks, the marks read from their own columns, never parsed."""

from __future__ import annotations

import copy
import math
import pickle
from xml.etree import ElementTree as ET

from rockscreen.pipeline.archive.risk_reader import legacy_completeness
from rockscreen.pipeline.archive.risk_schema import SCENARIO_TABLES, assess_tables, bound_columns
from rockscreen.pipeline.report.areas import area_counts
from rockscreen.pipeline.report.html.answer import class_text
from rockscreen.pipeline.report.qgis_style import INCOMPLETE_EXPRESSION, risk_style_qml
from rockscreen.pipeline.verdict.checks import (
    CheckResult,
    Family,
    Method,
    dumps_not_made,
    loads_not_made,
)
from rockscreen.pipeline.verdict.labels import ClassLabel, class_label, marks_of, row_class_label
from rockscreen.pipeline.verdict.messages import message, render
from rockscreen.pipeline.verdict.scales import (
    ClassBound,
    Completeness,
    class_marks,
    scenario_class_of,
)
from rockscreen.pipeline.verdict.status import Bound, Status

from rockscreen_testsupport.checks import BELFRY_MISSING, LV1_MISSING

NOT_MADE = (
    "rocking only: belfry not checked (no belfry columns in the inventory); "
    "LV1 not made (no wall_thickness_m and masonry_type in the inventory)"
)


def test_a_row_label_is_rendered_from_the_typed_columns():
    row = {
        "risk_class": "meets",
        "completeness": "rocking_only",
        "basis_compliant": False,
        "checks_not_made": NOT_MADE,
    }
    label = row_class_label(row)
    assert label == f"incomplete (basis not code-compliant) ({NOT_MADE})"
    assert isinstance(label, ClassLabel) and label.marks == class_marks(row)
    assert label.marks.cls == "meets" and label.marks.counted == "incomplete"
    # the same text without the typed mark is a partial meets, never guessed from the text
    partial = row_class_label({**row, "completeness": "partial"})
    assert partial.marks.counted == "meets" and partial.startswith("meets (")
    assert row_class_label({"risk_class": "high", "completeness": "rocking_only"}) == "high"
    assert "base non conforme" in class_text(label, "it")
    assert class_text(label, "it").endswith(
        "(solo ribaltamento rigido: cella campanaria non "
        "verificata (nessuna colonna della cella "
        "nell'inventario); LV1 non eseguita (wall_thickness_m "
        "e masonry_type assenti nell'inventario))"
    )


def test_a_label_keeps_its_marks_when_copied_or_pickled():
    label = class_label("high", False, bound=ClassBound.AT_MOST)
    assert label == "high (basis not code-compliant) (at most)"
    for other in (copy.deepcopy(label), pickle.loads(pickle.dumps(label))):
        assert other == label and other.marks == label.marks
    assert marks_of("moderate").cls == "moderate" and marks_of("moderate").basis_compliant


def test_a_scenario_class_read_on_a_bound_of_p_says_so_in_its_own_column():
    assert scenario_class_of(0.3, Bound.UPPER) == ("high", ClassBound.AT_MOST)
    assert scenario_class_of(0.01, Bound.UPPER) == ("low", ClassBound.NONE)  # settled
    assert scenario_class_of(0.6, Bound.LOWER) == ("very_high", ClassBound.NONE)
    assert scenario_class_of(0.1, Bound.LOWER) == ("moderate", ClassBound.AT_LEAST)
    assert scenario_class_of(math.nan, Bound.NONE) == ("undefined", ClassBound.NONE)
    assert "class_bound" in SCENARIO_TABLES["summary"]
    row = {"risk_class": "high", "class_bound": "at_most"}
    assert row_class_label(row) == "high (at most)"
    assert class_text(row_class_label(row), "it") == "alto (al più)"


def test_areas_count_the_typed_class():
    rows = [
        {"risk_class": "meets", "completeness": "rocking_only", "comune": "A"},
        {"risk_class": "meets", "completeness": "partial", "comune": "A"},
        {"risk_class": "meets", "basis_compliant": False, "comune": "B"},
    ]
    classes, areas = area_counts(rows, "comune")
    assert classes == ["incomplete", "meets"]
    assert areas == [("A", {"incomplete": 1, "meets": 1}, 2), ("B", {"meets": 1}, 1)]


def test_the_qgis_style_colours_a_rocking_only_meets_by_its_column():
    qml = risk_style_qml(["meets", "high"])
    root = ET.fromstring(qml.split("\n", 1)[1])
    values = [c.get("value") for c in root.iter("category")]
    assert values == ["high", "meets", ""]
    expressions = [o.get("value") for o in root.iter("Option") if o.get("name") == "expression"]
    assert expressions == [INCOMPLETE_EXPRESSION]
    assert "\"completeness\" = 'rocking_only'" in INCOMPLETE_EXPRESSION


def test_the_reasons_are_stored_by_check_id():
    lv1 = CheckResult(
        "shaft.lv1",
        "shaft",
        Family.SHAFT_FLEXURE,
        Method.LV1,
        Status.NOT_MADE,
        reason=message("not_made.lv1_column", column="masonry_type"),
    )
    made = CheckResult(
        "tower.rocking", "tower", Family.TOWER_ROCKING, Method.ROCKING, Status.MADE, 0.3, 1.2
    )
    text = dumps_not_made([made, lv1])
    assert loads_not_made(text) == {"shaft.lv1": lv1.reason}
    assert render(loads_not_made(text)["shaft.lv1"]) == (
        "LV1 not made (no masonry_type in the inventory)"
    )
    assert loads_not_made("") == {} and dumps_not_made([made]) == "[]"


def test_older_archives_get_their_completeness_through_one_adapter():
    assert legacy_completeness("") is Completeness.COMPLETE
    assert legacy_completeness(NOT_MADE) is Completeness.ROCKING_ONLY
    assert legacy_completeness("LV1 not made (x)") is Completeness.PARTIAL


def test_every_bound_pair_is_declared_in_the_schema():
    declared = set(assess_tables()["summary"]) | set(SCENARIO_TABLES["summary"])
    assert set(bound_columns().values()) <= declared
    assert set(bound_columns()) <= declared


def test_the_sheet_renders_the_checks_not_made_from_their_codes():
    from rockscreen.pipeline.report.html.adapters.risk_checks import checks_table
    from rockscreen.pipeline.verdict.rules import NotMadeText

    row = {
        "governing": "whole-tower rocking",
        "capacity_pga_g": 0.3,
        "safety_index": 1.2,
        "slv_bound": "",
        "collapse_median_g": math.nan,
        "completeness": "rocking_only",
        "checks_not_made": NOT_MADE,
        "checks_not_made_codes": dumps_not_made([BELFRY_MISSING, LV1_MISSING]),
    }
    rows, text = checks_table(row)
    why = {label: detail for label, _, _, detail in rows}
    assert render(why["c_belfry"], "it").startswith("cella campanaria non verificata")
    assert (
        render(why["c_lv1"])
        == "LV1 not made (no wall_thickness_m and masonry_type in the inventory)"
    )
    (not_made,) = [values["text"] for key, values in text if key == "c_not_made"]
    assert isinstance(not_made, NotMadeText) and not_made.render() == NOT_MADE
    assert not_made.render("it").startswith("solo ribaltamento rigido: cella campanaria")


def test_class_text_renders_checks_not_made_from_their_codes_in_the_page_language():
    """An Italian page says why checks were not made from the messages, not the English text.

    The stored English text is replaced by a sentinel: had the page translated the text
    (the older archives' adapter), the sentinel would show.
    """
    row = {
        "risk_class": "meets",
        "completeness": "rocking_only",
        "checks_not_made": "rocking only: SENTINEL ENGLISH TEXT",
        "checks_not_made_codes": dumps_not_made([BELFRY_MISSING, LV1_MISSING]),
    }
    label = row_class_label(row)
    italian = class_text(label, "it")
    assert "SENTINEL" not in italian
    assert render(message("not_made.belfry"), "it") in italian
    assert render(message("not_made.belfry"), "en") not in italian
    english = class_text(label, "en")
    assert render(message("not_made.belfry"), "en") in english
    # an older archive (no codes): its text goes through the adapter, as before
    del row["checks_not_made_codes"]
    assert "SENTINEL ENGLISH TEXT" in class_text(row_class_label(row), "it")
