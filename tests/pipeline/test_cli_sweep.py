"""``rockscreen sweep`` through click's test runner."""

from __future__ import annotations

from pathlib import Path

from click.testing import CliRunner

from rockscreen.pipeline.cli import main
from rockscreen.pipeline.study.sweep import is_sweep_archive, read_cases

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "seed_study"


def test_dry_run_lists_the_60_combinations():
    result = CliRunner().invoke(main, ["sweep", str(EXAMPLES / "tables_2_3.toml"), "--dry-run"])
    assert result.exit_code == 0, result.output
    lines = result.output.strip().splitlines()
    assert lines[-1] == "60 combinations"
    assert "A=0.4g f=3 Hz mu_s=1 mu_k=0.7" in lines[0]


def test_bad_study_is_one_line_error(tmp_path, small_study):
    study = small_study
    study.write_text(study.read_text().replace('model = "rocking"', 'model = "slab"'))
    result = CliRunner().invoke(main, ["sweep", str(study), "--out", str(tmp_path / "x.h5")])
    assert result.exit_code == 1
    assert "'model' = 'slab'" in result.output
    assert "Traceback" not in result.output
    assert not (tmp_path / "x.h5").exists()


def test_missing_study_file(tmp_path):
    result = CliRunner().invoke(main, ["sweep", str(tmp_path / "none.toml")])
    assert result.exit_code == 1
    assert f"study file {tmp_path / 'none.toml'}: no such file" in result.output


def test_sweep_runs_writes_archive_table_and_figures(tmp_path, small_study):
    study = small_study
    out = tmp_path / "small.h5"
    figs = tmp_path / "figs"
    result = CliRunner().invoke(
        main, ["sweep", str(study), "--out", str(out), "--figures", str(figs)]
    )
    assert result.exit_code == 0, result.output
    assert "theta_max [rad]" in result.output and "A [g]" in result.output
    assert is_sweep_archive(out)
    rows = read_cases(out)
    assert [r["group"] for r in rows] == ["single", "double", "double"]
    assert all(r["status"] != "no_motion" for r in rows)
    assert sorted(p.name for p in figs.iterdir()) == [
        "small_g1_2p25g.png",
        "small_g2_0p5g.png",
        "small_g2_theta_max.png",
    ]
