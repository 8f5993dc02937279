"""The model registry, the one ground-motion type, one case solved, and a new model.

The last tests add a toy model as one module in a folder of its own, as a developer adds
the next model (``docs/architecture.md``): ``run``'s evaluation and ``assess``'s stripes
pick it up by name without any other file changing.
"""

from __future__ import annotations

import math
import textwrap

import numpy as np
import pytest

from rockscreen.pipeline.config import CampaignConfig, ModelsConfig
from rockscreen.pipeline.engine import registry
from rockscreen.pipeline.engine.cases import BlockCache, screen_case
from rockscreen.pipeline.engine.motion import GroundMotion, tower_components
from rockscreen.pipeline.engine.registry import (
    CAMPAIGN,
    SIMULATE,
    STUDY,
    available_models,
    ground_input_model,
    model_names,
    solver_model,
)
from rockscreen.pipeline.engine.solvers import Solvers
from rockscreen.pipeline.risk.assess.stripes import StripeOptions, evaluate_stripe
from rockscreen.pipeline.screening.cases import CampaignShared, TowerTask
from rockscreen.pipeline.screening.evaluate import evaluate_tower
from rockscreen.solver.constants import G
from rockscreen.stations.inventory import Tower

FLOOR_DATA = {"building_height_m": 10.0, "base_height_m": 8.0}
DOUBLE_DATA = {"tower_mass_kg": 3e4, "building_mass_kg": 1e6, "mu_s": 1.0, "mu_k": 0.7}


def test_the_models_and_their_spellings():
    assert model_names(CAMPAIGN) == ("ground", "floor", "double", "belfry", "gable")
    assert model_names(STUDY) == ("rocking", "double-block")
    assert model_names(SIMULATE) == ("rocking", "double-block", "sliding")
    assert solver_model("double-block").name == "double"
    assert ground_input_model().name == "ground"
    with pytest.raises(KeyError, match="registered: ground, floor, double"):
        registry.get("spire")
    with pytest.raises(KeyError, match="rocking, double-block, sliding"):
        solver_model("ground")


def test_a_model_runs_where_the_inventory_has_what_it_requires():
    enabled = model_names()
    bare = Tower(id="T", width_m=2.0, height_m=6.0)
    full = Tower(id="F", width_m=2.0, height_m=6.0, **FLOOR_DATA, **DOUBLE_DATA)
    assert [m.name for m in available_models(bare, enabled)] == ["ground"]
    assert [m.name for m in available_models(full, enabled)] == ["ground", "floor", "double"]
    assert registry.get("double").parameters_of(full) == {
        "tower_mass": 3e4,
        "building_mass": 1e6,
        "mu_s": 1.0,
        "mu_k": 0.7,
    }


def test_a_suite_record_is_along_the_tower_axes():
    tower = Tower(id="T", width_m=2.0, height_m=6.0, depth_m=3.0, azimuth_deg=40.0)
    x, y = np.ones(5), 2 * np.ones(5)
    motion = GroundMotion.along_tower_axes("R1", x, y, None, 0.01)
    components = tower_components(tower, motion)
    # Neither rotated by the azimuth nor given the smaller dimension: X = width, Y = depth.
    assert [(c, w, a) for c, _, w, a in components] == [("X", 2.0, "x"), ("Y", 3.0, "y")]
    assert components[1].acc is y and components[1].width_m == 3.0
    only_x = GroundMotion.along_tower_axes("R2", x, None, None, 0.01)
    assert [(c.component, c.axis) for c in tower_components(tower, only_x)] == [("X", "x")]


def test_screen_case_leaves_a_motionless_case_unsolved_and_names_the_vertical_limit():
    tower = Tower(id="T", width_m=1.0, height_m=5.0, **DOUBLE_DATA)
    block = BlockCache(tower)(1.0)
    t = np.arange(500) * 0.01
    quiet = 0.01 * G * np.sin(2 * np.pi * t)  # far below g tan(alpha)
    for model, status in (("ground", "no_motion"), ("double", "no_uplift")):
        verdict = screen_case(registry.get(model), tower, block, quiet, None, 0.01, 5.0)
        assert verdict == (status, False, 0.0, False)
    strong = 0.5 * G * np.sin(2 * np.pi * t)
    falling = -1.2 * G * np.ones_like(t)
    verdict = screen_case(registry.get("ground"), tower, block, strong, falling, 0.01, 5.0)
    assert verdict.status == "vertical_limit" and not verdict.solved
    assert math.isnan(verdict.theta_max_over_alpha)


TOY_MODULE = '''
"""``toy``: the tower rocking on half the ground motion (a test's model)."""

from rockscreen.pipeline.engine.models.ground import solve_single_block
from rockscreen.pipeline.engine.registry import TowerModel


def half(tower, acc, dt):
    return 0.5 * acc


MODEL = TowerModel(
    name="toy",
    order=10,
    label="single block on half the ground motion",
    solve=solve_single_block,
    requires=("building_height_m",),
    base_motion=half,
)
'''


@pytest.fixture
def toy_model(tmp_path, monkeypatch):
    """Add the toy model as one module in a plugin folder of the models package."""
    from rockscreen.pipeline.engine import models

    folder = tmp_path / "plugins"
    folder.mkdir()
    (folder / "toy.py").write_text(textwrap.dedent(TOY_MODULE), encoding="utf-8")
    monkeypatch.setattr(models, "__path__", [*models.__path__, str(folder)])
    registry.clear()
    yield registry.get("toy")
    monkeypatch.undo()
    registry.clear()
    import sys

    sys.modules.pop("rockscreen.pipeline.engine.models.toy", None)


def _pulse_motion(peak_m_s2: float) -> GroundMotion:
    t = np.arange(400) * 0.01
    acc = peak_m_s2 * np.sin(2 * np.pi * 1.5 * t) * (t < 1.0)
    return GroundMotion.along_tower_axes("P", acc, acc.copy(), None, 0.01)


def test_a_new_model_is_one_module(toy_model):
    assert model_names()[-1] == "toy"
    tower = Tower(id="T", width_m=1.0, height_m=6.0, **FLOOR_DATA)
    bare = Tower(id="B", width_m=1.0, height_m=6.0)
    assert toy_model in available_models(tower, model_names())
    assert toy_model not in available_models(bare, model_names())

    # run: every case of the toy model is solved and listed by its name.
    motion = _pulse_motion(4.0)
    config = CampaignConfig(models=ModelsConfig(run=("ground", "toy")))
    shared = CampaignShared({"P": motion}, config, Solvers().resolved())
    outcome = evaluate_tower(TowerTask(0, tower, ("P",)), shared)
    rows = {(r["component"], r["model"]): r for r in outcome.rows}
    assert set(rows) == {("X", "ground"), ("Y", "ground"), ("X", "toy"), ("Y", "toy")}
    # Half the motion: the toy case's input peak is half the ground case's.
    assert rows["X", "toy"]["pga_m_s2"] == pytest.approx(0.5 * rows["X", "ground"]["pga_m_s2"])

    # assess: the stripe counts the toy model in a column of its own.
    record_set = type("Set", (), {})()
    record_set.records = [
        type("R", (), {"name": "P", "acc_x_m_s2": motion.horizontals[0],
                       "acc_y_m_s2": None, "acc_z_m_s2": None, "dt_s": 0.01})()
    ]  # fmt: skip
    record_set.scale_factors = [3.0]
    stripe, outcomes, _ = evaluate_stripe(
        tower, record_set, 475.0, 0.3, StripeOptions(models=("ground", "toy"))
    )
    assert stripe["models"] == "ground,toy"
    assert "n_overturned_toy" in stripe
    assert {row["model"] for row in outcomes} == {"ground", "toy"}


def test_no_model_name_is_compared_outside_the_models():
    """Only the models' own modules spell model names in code (docstrings aside)."""
    import ast
    from pathlib import Path

    root = Path(__file__).resolve().parents[3]
    spelled = {m.name for m in registry.models()} | {
        m.solver_name for m in registry.models() if m.solver_name
    }
    found = []
    for path in sorted((root / "pipeline").rglob("*.py")):
        if path.parent.name == "models" and path.parent.parent.name == "engine":
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if not isinstance(node, ast.Compare):
                continue
            for part in [node.left, *node.comparators]:
                values = part.elts if isinstance(part, (ast.Tuple, ast.List, ast.Set)) else [part]
                for value in values:
                    if isinstance(value, ast.Constant) and value.value in spelled:
                        found.append(f"{path.relative_to(root)}:{node.lineno} {value.value!r}")
    assert not found, f"model names compared outside pipeline/engine/models: {found}"


SPIRE_MODULE = '''
"""``spire``: a toy part model, a slender spire rocking on the ground motion."""

from rockscreen.pipeline.engine.models.ground import solve_single_block
from rockscreen.pipeline.engine.registry import TowerModel


def spire_block(tower, tower_width_m, axis):
    from rockscreen.solver import RockingBlock

    return RockingBlock.from_dimensions(0.25, 3.0)


MODEL = TowerModel(
    name="spire",
    order=11,
    label="spire rocking on the top of the shaft",
    label_it="guglia che oscilla sulla sommità del fusto",
    solve=solve_single_block,
    own_block=spire_block,
)
'''


@pytest.fixture
def spire_model(tmp_path, monkeypatch):
    """Add a third part model (own block) as one module in a plugin folder."""
    import sys

    from rockscreen.pipeline.engine import models

    folder = tmp_path / "part-plugins"
    folder.mkdir()
    (folder / "spire.py").write_text(textwrap.dedent(SPIRE_MODULE), encoding="utf-8")
    monkeypatch.setattr(models, "__path__", [*models.__path__, str(folder)])
    registry.clear()
    yield registry.get("spire")
    monkeypatch.undo()
    registry.clear()
    sys.modules.pop("rockscreen.pipeline.engine.models.spire", None)


def test_a_third_part_model_is_one_module(spire_model, tmp_path):
    """A part model added as one module is assessed, archived, inspected, exported, shown."""
    import csv
    import json

    from click.testing import CliRunner

    from rockscreen.pipeline.archive.risk_reader import read_summary
    from rockscreen.pipeline.cli import main
    from rockscreen.pipeline.risk.checks.tower_checks import PART_SUFFIXES, part_model_names

    assert part_model_names()[-1] == "spire"
    inventory = tmp_path / "towers.csv"
    inventory.write_text("id;lat;lon;width_m;height_m\nA;41,04;14,42;2;8\n", encoding="utf-8")
    out = tmp_path / "a.h5"
    runner = CliRunner()
    args = ["assess", "--towers", str(inventory), "--return-periods", "475", "--records", "3"]
    args += ["--models", "ground,spire", "--bootstrap", "0", "--jobs", "1", "--out", str(out)]
    args += ["--allow-noncompliant"]
    result = runner.invoke(main, args)
    assert result.exit_code == 0, result.output

    (row,) = read_summary(out, "assess")
    spire_columns = {f"spire_{suffix}" for suffix in PART_SUFFIXES}
    assert spire_columns <= set(row)
    assert math.isfinite(row["spire_capacity_ag_g"]) and row["spire_ida_n_solves"] > 0
    # The slender spire (alpha = atan(0.25 / 3)) overturns before the 2 m x 8 m tower: the
    # whole tower's IDA stops at it, and of equal capacities the part governs.
    assert row["spire_capacity_ag_g"] == pytest.approx(row["capacity_pga_g"])
    assert row["governing_check"] == "spire.rocking"
    assert "spire" in row["governing"]
    # The archive stores the spire as rows of its long tables, not as columns of /summary.
    import h5py

    from rockscreen.pipeline.archive.safety import read_column

    with h5py.File(out, "r") as f:
        assert spire_columns.isdisjoint(f["summary"])
        fits = list(read_column(f["fits/fit"], out, "fits/fit"))
        checks = list(read_column(f["checks/check"], out, "checks/check"))
        ag = f["checks/capacity_ag_g"][checks.index("spire.rocking")]
    assert {"spire.collapse", "spire.slv"} <= set(fits)
    assert ag == row["spire_capacity_ag_g"]

    inspected = runner.invoke(main, ["inspect", "--json", str(out)])
    assert inspected.exit_code == 0, inspected.output
    (tower,) = json.loads(inspected.stdout)["towers"]
    assert tower["spire_capacity_ag_g"] == pytest.approx(row["spire_capacity_ag_g"])

    exported = runner.invoke(main, ["export", str(out), "--csv", str(tmp_path / "a.csv")])
    assert exported.exit_code == 0, exported.output
    with (tmp_path / "a.csv").open(newline="", encoding="utf-8") as handle:
        (csv_row,) = list(csv.DictReader(handle))
    assert spire_columns <= set(csv_row)

    report = runner.invoke(main, ["report", str(out), "--out", str(tmp_path / "a.html")])
    assert report.exit_code == 0, report.output
    # The tower sheet's checks table has the spire's row, labelled by the model itself.
    from rockscreen.pipeline.report.html.adapters.risk_checks import checks_table
    from rockscreen.pipeline.verdict.messages import render

    rows, text = checks_table(row)
    labels = [r[0] for r in rows]
    assert "model_spire" in labels
    spire_row = rows[labels.index("model_spire")]
    # its details: the part's fragility (median, beta, P50) as the page's string code
    detail, values = spire_row[3]
    assert spire_row[1] != "-" and detail == "c_d_part"
    assert values["median"]["num"] == pytest.approx(row["spire_fragility_median_g"])
    assert text[0][0] == "c_governing" and "spire" in render(text[0][1]["label"])
    page = (tmp_path / "a.html").read_text(encoding="utf-8")
    assert "spire rocking on the top of the shaft" in page
