"""The LV1 tower model at knowledge level LC3: the inventory's measured masonry strength.

Circolare 2019 §C8.5.4.1: LC3 rests on tests, so the LV1 model takes ``f_m`` from the
row's ``masonry_strength_mpa`` (F_C = 1); without it LV1 is not made, naming the column; a
measured value at LC1 or LC2 is refused (docs/code_checks.md §3, §4; docs/inventory.md).
"""

from __future__ import annotations

from dataclasses import replace

import pytest

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.execution.local import SerialExecutor
from rockscreen.pipeline.risk.assess.run import AssessOptions, run_assess
from rockscreen.pipeline.risk.assess.sites import tower_sites
from rockscreen.pipeline.risk.checks import (
    SiteConditions,
    confidence_factor,
    design_compressive_strength,
    lv1_tower,
)
from rockscreen.pipeline.risk.checks.knowledge import (
    check_measured_strengths,
    tower_knowledge_level,
)
from rockscreen.pipeline.risk.checks.tower_lv1_checks import (
    LV1_NOT_MADE,
    lv1_columns,
    lv1_masonry_strength,
    lv1_tower_model,
)
from rockscreen.stations.inventory import Tower

from rockscreen_testsupport.towers import lv1_shaft_tower

LAQUILA = (13.40, 42.35)  # lon, lat [deg]
SHAFT = lv1_shaft_tower(
    "T-LC3",
    lat=LAQUILA[1],
    lon=LAQUILA[0],
    masonry_strength_mpa=3.2,
    knowledge_level="LC3",
)


def _lv1(tower: Tower, level: str, lang: str = "en"):
    """Return the LV1 columns, notes (rendered in ``lang``) and why it was not made."""
    columns, notes, missing = lv1_columns(tower_sites([tower])[0], confidence_factor(level), level)
    return columns, [n.render(lang) for n in notes], missing


def test_lv1_at_lc3_takes_the_measured_strength():
    fm, source = lv1_masonry_strength(SHAFT, "LC3")
    assert fm == 3.2e6
    assert source.render() == "f_m = 3.2 MPa measured (masonry_strength_mpa, LC3)"
    model = lv1_tower_model(SHAFT, 1.0, "LC3")
    assert model.fd_pa == pytest.approx(design_compressive_strength(3.2e6, 1.0))
    assert model.fd_pa == pytest.approx(3.2e6 / 2.0)  # gamma_M = 2, F_C = 1 (LC3)
    columns, notes, missing = _lv1(SHAFT, "LC3")
    assert missing == []
    site = SiteConditions(*LAQUILA)
    worst = min(
        lv1_tower(lv1_tower_model(SHAFT, 1.0, "LC3", across=a), site).capacity.ag_g
        for a in (False, True)
    )
    assert columns["lv1_capacity_ag_g"] == pytest.approx(worst, rel=1e-12)
    assert "solid_brick, f_m = 3.2 MPa measured (masonry_strength_mpa, LC3)" in notes[0]
    # a stronger measured masonry holds longer: the strength is used
    stronger, _, _ = _lv1(replace(SHAFT, masonry_strength_mpa=12.0), "LC3")
    weaker, _, _ = _lv1(replace(SHAFT, masonry_strength_mpa=0.5), "LC3")
    assert weaker["lv1_capacity_ag_g"] < columns["lv1_capacity_ag_g"]
    assert columns["lv1_capacity_ag_g"] <= stronger["lv1_capacity_ag_g"]


def test_lv1_at_lc1_and_lc2_keeps_the_table_value():
    plain = replace(SHAFT, masonry_strength_mpa=None, knowledge_level=None)
    fm, source = lv1_masonry_strength(plain, "LC1")
    assert (fm, source.render()) == (
        2.6e6,
        "f_m = 2.6 MPa (Table C8.5.I, LC1: the range's lower end)",
    )
    fm, source = lv1_masonry_strength(plain, "lc2")
    assert fm == pytest.approx(3.45e6)
    assert source.render() == "f_m = 3.45 MPa (Table C8.5.I, LC2: the range's mean)"
    _, notes, _ = _lv1(plain, "LC2")
    assert "solid_brick, f_m = 3.45 MPa (Table C8.5.I, LC2: the range's mean)" in notes[0]


def test_lv1_strength_notes_read_in_italian_on_the_report():
    from rockscreen.pipeline.report.html.notes import translate_note

    _, notes, _ = _lv1(SHAFT, "LC3", "it")
    assert "f_m = 3,2 MPa misurata (masonry_strength_mpa, LC3)" in notes[0]
    plain = replace(SHAFT, masonry_strength_mpa=None, knowledge_level=None)
    italian = _lv1(plain, "LC1", "it")[1][0]
    assert "f_m = 2,6 MPa (Tabella C8.5.I, LC1: estremo inferiore dell'intervallo)" in italian
    _, _, missing = _lv1(replace(SHAFT, masonry_strength_mpa=None), "LC3")
    assert translate_note(missing[0], "it") == (
        "LV1 non eseguita (LC3 richiede una f_m misurata: masonry_strength_mpa assente "
        "nell'inventario)"
    )


def test_lv1_at_lc3_without_the_measured_strength_is_not_made_naming_the_column():
    tower = replace(SHAFT, masonry_strength_mpa=None)
    columns, notes, missing = _lv1(tower, "LC3")
    assert (columns, notes) == ({}, [])
    assert missing == [
        f"{LV1_NOT_MADE} (LC3 rests on a measured f_m: no masonry_strength_mpa in the inventory)"
    ]
    with pytest.raises(RiskError, match="no masonry_strength_mpa in the inventory"):
        lv1_masonry_strength(tower, "LC3")


def test_lv1_refuses_a_measured_strength_below_lc3():
    tower = replace(SHAFT, knowledge_level=None)  # the row leaves the level to the run
    with pytest.raises(RiskError, match=r"masonry_strength_mpa=3.2 MPa is a measured f_m, used"):
        lv1_masonry_strength(tower, "LC2")
    with pytest.raises(RiskError, match="only at knowledge level LC3"):
        lv1_tower_model(tower, 1.35, "LC1")


def test_assess_refuses_a_measured_strength_at_the_runs_lc1_or_lc2_before_any_work():
    tower = replace(SHAFT, knowledge_level=None)
    assert tower_knowledge_level(tower, "lc2") == ("LC2", "run")
    assert tower_knowledge_level(tower) == ("LC1", "assumed")
    assert tower_knowledge_level(SHAFT, "LC1") == ("LC3", "inventory")
    with pytest.raises(RiskError) as info:
        check_measured_strengths([SHAFT, tower], "LC2")
    message = str(info.value)
    assert "masonry_strength_mpa is a measured f_m, used only at knowledge level LC3" in message
    assert "tower(s) 'T-LC3' with it are assessed at LC2 (the run's --knowledge-level" in message
    assert "set knowledge_level=LC3 in their rows, run with --knowledge-level LC3" in message
    with pytest.raises(RiskError, match=r"at LC1 \(the default: no knowledge_level in the row"):
        check_measured_strengths([tower], None)
    # the row's LC3 wins over the run's level; LC3 for the run covers the row without one
    check_measured_strengths([SHAFT], "LC1")
    check_measured_strengths([tower], "LC3")
    check_measured_strengths([replace(tower, masonry_strength_mpa=None)], "LC1")
    # run_assess refuses before it computes anything
    with pytest.raises(RiskError, match="used only at knowledge level LC3"):
        run_assess([tower], AssessOptions(knowledge_level="LC2"), SerialExecutor())


def test_cli_assess_refuses_it_before_the_work_file(tmp_path):
    from click.testing import CliRunner

    from rockscreen.pipeline.cli import main

    inventory = tmp_path / "towers.csv"
    inventory.write_text(
        "id,lat,lon,width_m,height_m,wall_thickness_m,masonry_type,masonry_strength_mpa\n"
        "T-1,42.35,13.40,4,20,0.9,solid_brick,3.2\n",
        encoding="utf-8",
    )
    out = tmp_path / "a.h5"
    args = ["assess", "--towers", str(inventory), "--knowledge-level", "lc2", "--out", str(out)]
    result = CliRunner().invoke(main, args)
    assert result.exit_code == 1
    assert "rockscreen: error: masonry_strength_mpa is a measured f_m" in result.output
    assert "'T-1' with it are assessed at LC2 (the run's --knowledge-level" in result.output
    assert sorted(p.name for p in tmp_path.iterdir()) == ["towers.csv"]  # no archive, no .part
