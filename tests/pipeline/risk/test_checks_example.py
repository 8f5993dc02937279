"""``assess --example``: every tower's code checks in ``inspect --json`` and the CSV (issue 22).

The example inventory has a tower with a belfry and the shaft's data (ARC-03), one with the
shaft's data only (ARC-02) and a bell gable on a facade (ARC-08).
"""

from __future__ import annotations

import csv
import json

import pytest
from click.testing import CliRunner

from rockscreen.pipeline.cli import main
from rockscreen.pipeline.report.risk_summary import CHECKS_JSON_KEYS
from rockscreen.pipeline.risk.checks.governing import GOVERNING_KINDS

#: The keys the issue asks of every tower (null with a ``<key>_note`` when not made).
ISSUE_KEYS = (
    "kinematic_alpha0",
    "kinematic_e_star",
    "confidence_factor",
    "kinematic_a0_g",
    "kinematic_linear_capacity_ag_g",
    "kinematic_nonlinear_capacity_ag_g",
    "kinematic_safety_index",
    "lv1_capacity_ag_g",
    "lv1_safety_index",
    "belfry_fragility_median_g",
    "belfry_fragility_beta",
    "belfry_p_overturning_50y",
    "governing",
)


@pytest.fixture(scope="module")
def example(tmp_path_factory):
    """``assess --example`` (three stripes), its ``inspect --json`` towers and CSV rows."""
    folder = tmp_path_factory.mktemp("checks-example")
    runner = CliRunner()
    fast = ["--return-periods", "101,475,2475", "--records", "3", "--allow-noncompliant"]
    with pytest.MonkeyPatch.context() as patch:
        patch.chdir(folder)
        result = runner.invoke(main, ["assess", "--example", "--jobs", "1", *fast])
        assert result.exit_code == 0, result.output
        inspected = runner.invoke(main, ["inspect", "--json", "rockscreen-assess-example.h5"])
        assert inspected.exit_code == 0, inspected.output
        exported = runner.invoke(main, ["export", "rockscreen-assess-example.h5", "--csv", "a.csv"])
        assert exported.exit_code == 0, exported.output
    towers = {t["id"]: t for t in json.loads(inspected.stdout)["towers"]}
    with (folder / "a.csv").open(newline="", encoding="utf-8") as handle:
        rows = {r["id"]: r for r in csv.DictReader(handle)}
    return result.stdout, towers, rows


def test_every_tower_has_the_check_keys_or_says_why_not(example):
    _, towers, _ = example
    assert set(ISSUE_KEYS) <= set(CHECKS_JSON_KEYS)
    located = [t for t in towers.values() if t["lat_deg"] is not None]
    assert len(located) == 8
    for tower in located:
        for key in ISSUE_KEYS:
            assert key in tower, (tower["id"], key)
            if tower[key] is None:
                assert tower[f"{key}_note"], (tower["id"], key)
        assert tower["governing_kind"] in GOVERNING_KINDS, tower["governing"]
    # the tower with a belfry and the shaft's data: every check made
    arc03 = towers["ARC-03"]
    for key in ISSUE_KEYS:
        assert arc03[key] is not None, key
    assert arc03["confidence_factor"] == 1.20  # its own LC2, from the inventory
    # a tower without them: null, and the note names the missing columns
    plain = towers["CE-SANNA"]
    assert plain["lv1_capacity_ag_g"] is None
    assert "wall_thickness_m and masonry_type" in plain["lv1_capacity_ag_g_note"]
    assert "no belfry columns" in plain["belfry_fragility_median_g_note"]
    # the shaft's data alone: LV1 made
    assert towers["ARC-02"]["lv1_safety_index"] is not None
    # the bell gable is checked and takes part in the governing choice
    gable = towers["ARC-08"]
    assert gable["gable_kinematic_alpha0"] is not None
    # the gable takes part in the governing choice: its own rocking (the gable model's IDA)
    # and its non-linear kinematic check (the code's verdict) are candidates; ARC-08's
    # "tower" is the gable's own block, so the whole tower's rocking may govern as well
    assert gable["gable_fragility_median_g"] is not None and gable["gable_ida_n_solves"] > 0
    candidates = [
        gable[k]
        for k in (
            "capacity_pga_g",
            "gable_capacity_ag_g",
            "gable_kinematic_nonlinear_capacity_ag_g",
            "tower_kinematic_nonlinear_capacity_ag_g",
        )
    ]
    assert gable["governing_capacity_ag_g"] == pytest.approx(min(candidates), rel=1e-12)
    assert gable["governing_kind"] in {"gable", "tower rocking", "kinematic"}


def test_the_terminal_and_the_csv_carry_the_checks(example):
    stdout, _, rows = example
    assert "the code's checks beside the rocking dynamics" in stdout
    assert "LV1 a_C [g]" in stdout and "bell gable" in stdout
    arc03 = rows["ARC-03"]
    for column in ("lv1_capacity_ag_g", "belfry_fragility_median_g", "governing_kind"):
        assert arc03[column] not in ("", "nan"), column
    assert rows["ARC-08"]["gable_kinematic_linear_capacity_ag_g"] not in ("", "nan")


def test_the_notes_rendered_from_their_codes_are_the_stored_notes(example):
    """Every tower's note is its codes rendered (issue 29), in English and in Italian."""
    from rockscreen.pipeline.verdict.messages import loads, render_all

    _, towers, rows = example
    assert len(towers) >= 9
    for tower_id, tower in towers.items():
        said = loads(tower["note_codes"])
        assert said, tower_id  # every tower's verdict says something (a default, a bound)
        assert render_all(said) == tower["note"], tower_id
        assert rows[tower_id]["note"] == tower["note"]  # the CSV's
        assert render_all(said, "it") != tower["note"], tower_id


def test_the_disagreement_clause_is_the_governing_sentence(example):
    """The note's disagreement codes read as ``checks_disagree`` (risk/checks/governing.py)."""
    from rockscreen.pipeline.risk.assess.tower_summary import disagreement_messages
    from rockscreen.pipeline.risk.measures.classes import DEFAULT_LIMITS
    from rockscreen.pipeline.verdict.messages import render_all

    _, towers, _ = example
    for tower_id, tower in towers.items():
        row = {k: (float("nan") if v is None else v) for k, v in tower.items()}
        said = disagreement_messages(row, DEFAULT_LIMITS)
        assert render_all(said) == (tower.get("checks_disagree") or ""), tower_id
