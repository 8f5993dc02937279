"""The three generic import names must resolve to this project, never a foreign package."""

from __future__ import annotations

import importlib
import importlib.metadata
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest
from click.testing import CliRunner

from rockscreen.pipeline.cli import main

REPO_ROOT = Path(__file__).resolve().parents[1]


def _installed_files() -> set[Path]:
    dist = importlib.metadata.distribution("rockscreen")
    return {Path(dist.locate_file(f)).resolve() for f in dist.files or []}


@pytest.mark.parametrize("name", ["pipeline", "solver", "stations"])
def test_package_comes_from_rockscreen(name):
    module = importlib.import_module(f"rockscreen.{name}")
    path = Path(module.__file__).resolve()
    assert path.is_relative_to(REPO_ROOT) or path in _installed_files(), (
        f"rockscreen.{name} imported from {path}, which is not part of rockscreen"
    )


def test_imports_resolve_outside_checkout(tmp_path):
    code = (
        "import importlib.util, rockscreen; "
        "from rockscreen import pipeline, solver, stations; "
        "print(pipeline.__file__, solver.__file__, stations.__file__); "
        "print(*(importlib.util.find_spec(n) is not None and "
        "'rockscreen' in str(importlib.util.find_spec(n).origin) "
        "for n in ('pipeline', 'solver', 'stations')))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, check=True
    ).stdout.splitlines()
    installed = _installed_files()
    for path in map(Path, out[0].split()):
        assert path.resolve().is_relative_to(REPO_ROOT) or path.resolve() in installed
    # No generic top-level name of this project is importable outside the checkout.
    assert out[1].split() == ["False", "False", "False"]


def _wheel_names(tmp_path: Path) -> set[str]:
    """Build the wheel (no build isolation: the running environment's setuptools)."""
    setuptools = pytest.importorskip("setuptools", reason="setuptools is needed to build")
    major = int(setuptools.__version__.split(".")[0])
    if major < 68:
        pytest.skip(f"setuptools {setuptools.__version__} < 68 (the build requirement)")
    # A copy of the checkout: an in-tree build/ folder could carry stale modules into the wheel.
    source = tmp_path / "source"
    ignore = shutil.ignore_patterns(".git", "build", "*.egg-info", ".venv", "__pycache__", "*.h5")
    shutil.copytree(REPO_ROOT, source, ignore=ignore)
    subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q",
         "-w", str(tmp_path), str(source)],
        check=True, capture_output=True, text=True,
    )  # fmt: skip
    (wheel,) = tmp_path.glob("rockscreen-*.whl")
    with zipfile.ZipFile(wheel) as archive:
        return set(archive.namelist())


def test_wheel_installs_everything_under_rockscreen(tmp_path):
    names = _wheel_names(tmp_path)
    tops = {name.split("/")[0] for name in names}
    assert {t for t in tops if not t.endswith(".dist-info")} == {"rockscreen"}
    assert "rockscreen/__init__.py" not in names  # a namespace package
    # Every package folder of the checkout is in the wheel, with its data files.
    for init in REPO_ROOT.glob("*/**/__init__.py"):
        top = init.relative_to(REPO_ROOT).parts[0]
        if top in ("pipeline", "solver", "stations"):
            assert f"rockscreen/{init.relative_to(REPO_ROOT).as_posix()}" in names
    for data in ("pipeline/hazard/data/ntc2018_grid.csv.gz", "stations/data/example_towers.csv"):
        assert f"rockscreen/{data}" in names
    entry_points = next(n for n in names if n.endswith(".dist-info/entry_points.txt"))
    assert entry_points


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
    import rockscreen.solver.cache as cache

    monkeypatch.setenv("NUMBA_CACHE_DIR", str(tmp_path))
    assert cache.cache_dir() == tmp_path
    assert not cache.kernel_is_cached()  # another installation's cache would not count
    assert "site-packages" not in str(cache.cache_dir())
