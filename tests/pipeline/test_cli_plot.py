"""``rockscreen plot``: tower histories and the risk map as PNG files."""

from __future__ import annotations

from click.testing import CliRunner

from rockscreen.pipeline.cli import main


def test_plot_tower_histories_png(example_archive, tmp_path):
    out = tmp_path / "tower.png"
    result = CliRunner().invoke(
        main, ["plot", str(example_archive), "--tower", "ARC-01", "--out", str(out)]
    )
    assert result.exit_code == 0, result.output
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_plot_map_png(example_archive, tmp_path):
    out = tmp_path / "map.png"
    result = CliRunner().invoke(main, ["plot", str(example_archive), "--map", "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_plot_unknown_tower_and_usage(example_archive):
    result = CliRunner().invoke(main, ["plot", str(example_archive), "--tower", "NOPE"])
    assert result.exit_code == 1 and "NOPE" in result.stderr
    assert CliRunner().invoke(main, ["plot", str(example_archive)]).exit_code == 2


def test_plot_draws_the_figures_of_a_sweep_archive(tmp_path, small_study):
    study = small_study
    archive = tmp_path / "small.h5"
    runner = CliRunner()
    assert runner.invoke(main, ["sweep", str(study), "--out", str(archive)]).exit_code == 0
    result = runner.invoke(main, ["plot", str(archive), "--out", str(tmp_path / "figs")])
    assert result.exit_code == 0, result.output
    pngs = sorted((tmp_path / "figs").glob("*.png"))
    assert pngs and all(p.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" for p in pngs)
