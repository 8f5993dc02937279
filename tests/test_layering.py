"""The dependency rules of docs/architecture.md, checked on the source text.

Every import counts, at module level or inside a function: the rules are about what a
module needs, not when it loads it.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[1]

#: Top-level packages and the import roots they must never use.
FORBIDDEN = {
    "solver": {"pipeline", "stations", "obspy", "h5py", "click", "matplotlib"},
    "stations": {"solver", "pipeline", "h5py", "click", "matplotlib"},
}

#: The stages of pipeline/, upstream first: a stage imports only itself, the stages
#: listed for it, the shared modules (errors, units, vocabulary, text, signals, config) and
#: solver/stations. Nothing but cli imports cli.
SHARED = {"errors", "units", "vocabulary", "text", "signals", "__init__", "__version__"}
#: The configuration reads the processing and quality settings it validates, and the model
#: registry's names (``[models] run``).
CONFIG = {"config", "config_keys", "config_schema"}
STAGES = {
    "records": set(),
    "processing": {"records"},
    "motion": {"records", "processing"},
    "hazard": {"records", "processing", "motion"},
    "execution": set(),
    # The case engine (one case solved, the model registry, the stored result types).
    "engine": {"records", "processing", "motion"},
    # The archive stores the result types of the stages that write one (cases, studies).
    "archive": {"records", "motion", "engine", "screening", "study", "risk"},
    "screening": {"records", "processing", "motion", "engine", "execution", "archive"},
    "study": {"motion", "engine", "execution", "archive"},
    "risk": {"records", "processing", "motion", "hazard", "engine", "execution", "archive"},
    "report": {"records", "motion", "hazard", "engine", "screening", "study", "risk", "archive"},
    "cli": None,  # the top: may import every stage
}


def _imports(path: Path) -> set[str]:
    """Return every module (and ``module.name``) a file imports, without ``rockscreen.``."""
    names = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names.add(node.module)
            names.update(f"{node.module}.{alias.name}" for alias in node.names)
    return {name.removeprefix("rockscreen.") for name in names}


@pytest.mark.parametrize("package", sorted(FORBIDDEN))
def test_package_respects_layering(package):
    for path in (REPO_ROOT / package).rglob("*.py"):
        roots = {name.split(".")[0] for name in _imports(path)}
        bad = roots & FORBIDDEN[package]
        assert not bad, f"{path.relative_to(REPO_ROOT)} imports {sorted(bad)}"


def _stage_of(name: str) -> str | None:
    parts = name.split(".")
    if parts[0] != "pipeline" or len(parts) < 2:
        return None
    return parts[1]


@pytest.mark.parametrize("stage", sorted(STAGES))
def test_pipeline_stages_import_only_upstream(stage):
    folder = REPO_ROOT / "pipeline" / stage
    assert folder.is_dir(), f"pipeline/{stage}/ is missing"
    allowed = STAGES[stage]
    for path in folder.rglob("*.py"):
        for name in _imports(path):
            other = _stage_of(name)
            if other is None or other == stage or other in SHARED or name == "pipeline":
                continue
            if other in CONFIG and stage not in ("records", "processing"):
                continue
            where = path.relative_to(REPO_ROOT)
            assert other != "cli" or stage == "cli", f"{where} imports the CLI ({name})"
            if allowed is not None:
                assert other in allowed, f"{where} imports {name}: {stage} may not use {other}"


def test_shared_modules_import_no_stage():
    for module in SHARED - {"__init__", "__version__"}:
        path = REPO_ROOT / "pipeline" / f"{module}.py"
        if not path.exists():
            continue
        stages = {_stage_of(name) for name in _imports(path)} - SHARED - {None}
        assert not stages, f"pipeline/{module}.py imports the stages {sorted(stages)}"


@pytest.mark.parametrize("module", sorted(CONFIG))
def test_configuration_reads_only_records_and_processing(module):
    path = REPO_ROOT / "pipeline" / f"{module}.py"
    if not path.exists():
        pytest.skip(f"pipeline/{module}.py does not exist")
    stages = {_stage_of(name) for name in _imports(path)} - SHARED - CONFIG - {None}
    assert stages <= {"records", "processing", "engine"}, (
        f"pipeline/{module}.py imports {sorted(stages)}"
    )
