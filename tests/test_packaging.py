"""The three generic import names must resolve to this project, never a foreign package."""

from __future__ import annotations

import importlib
import importlib.metadata
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from pipeline.cli import main

REPO_ROOT = Path(__file__).resolve().parents[1]


def _installed_files() -> set[Path]:
    dist = importlib.metadata.distribution("rockscreen")
    return {Path(dist.locate_file(f)).resolve() for f in dist.files or []}


@pytest.mark.parametrize("name", ["pipeline", "solver", "stations"])
def test_package_comes_from_rockscreen(name):
    module = importlib.import_module(name)
    path = Path(module.__file__).resolve()
    assert path.is_relative_to(REPO_ROOT) or path in _installed_files(), (
        f"{name} imported from {path}, which is not part of rockscreen"
    )


def test_imports_resolve_outside_checkout(tmp_path):
    code = (
        "import pipeline, solver, stations; "
        "print(pipeline.__file__, solver.__file__, stations.__file__)"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, check=True
    ).stdout.split()
    installed = _installed_files()
    for path in map(Path, out):
        assert path.resolve().is_relative_to(REPO_ROOT) or path.resolve() in installed


def test_version_and_help():
    runner = CliRunner()
    result = runner.invoke(main, ["--version"])
    assert result.exit_code == 0
    assert importlib.metadata.version("rockscreen") in result.output
    result = runner.invoke(main, ["--help"])
    assert result.exit_code == 0
    assert "rocking" in result.output


def test_unknown_command_is_a_usage_error():
    result = CliRunner().invoke(main, ["no-such-command"])
    assert result.exit_code == 2


def test_numba_cache_is_per_user_and_per_installation(tmp_path, monkeypatch):
    import solver.cache as cache

    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    assert cache.cache_dir() == tmp_path
    assert not cache.kernel_is_cached()  # another installation's cache would not count
    assert "site-packages" not in str(cache.cache_dir())
