"""``rockscreen plot``: tower histories and the risk map as PNG files."""

from __future__ import annotations

import os

import pytest
from click.testing import CliRunner

from pipeline.cli import main


@pytest.fixture(scope="module")
def archive(tmp_path_factory):
    folder = tmp_path_factory.mktemp("plot")
    cwd = os.getcwd()
    os.chdir(folder)
    try:
        result = CliRunner().invoke(main, ["run", "--example", "--jobs", "1"])
    finally:
        os.chdir(cwd)
    assert result.exit_code == 0, result.output
    return folder / "rockscreen-example.h5"


def test_plot_tower_histories_png(archive, tmp_path):
    out = tmp_path / "tower.png"
    result = CliRunner().invoke(
        main, ["plot", str(archive), "--tower", "ARC-01", "--out", str(out)]
    )
    assert result.exit_code == 0, result.output
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_plot_map_png(archive, tmp_path):
    out = tmp_path / "map.png"
    result = CliRunner().invoke(main, ["plot", str(archive), "--map", "--out", str(out)])
    assert result.exit_code == 0, result.output
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_plot_unknown_tower_and_usage(archive):
    result = CliRunner().invoke(main, ["plot", str(archive), "--tower", "NOPE"])
    assert result.exit_code == 1 and "NOPE" in result.stderr
    assert CliRunner().invoke(main, ["plot", str(archive)]).exit_code == 2
