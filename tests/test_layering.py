"""The dependency rules of docs/architecture.md, checked on the source text.

Every import counts, at module level, inside a function or under ``TYPE_CHECKING``: the
rules are about what a module needs, not when it loads it. Besides the stage rules: no
import cycle among the modules of ``rockscreen.pipeline``, ``.solver`` and ``.stations``
(a strongly connected component of more than one module fails, naming a cycle), and no
module imports a private name (``_name``) of another rockscreen module.
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
    # The typed verdict (check results, messages as codes): below every product and face.
    "verdict": set(),
    # The case engine (one case solved, the model registry, the stored result types).
    "engine": {"records", "processing", "motion", "verdict"},
    # The archive stores the result types, which live in the engine below every product.
    "archive": {"engine", "verdict"},
    "screening": {"records", "processing", "motion", "engine", "execution", "archive", "verdict"},
    "study": {"motion", "engine", "execution", "archive"},
    "risk": {
        "records",
        "processing",
        "motion",
        "hazard",
        "engine",
        "execution",
        "archive",
        "verdict",
    },
    "report": {
        "records",
        "motion",
        "hazard",
        "engine",
        "screening",
        "study",
        "risk",
        "archive",
        "verdict",
    },
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


# --------------------------------------------------------------------------- import graph

#: The packages whose modules form the import graph, by folder.
PACKAGES = ("pipeline", "solver", "stations")
#: Folders whose modules may not import a private name of another module.
PRIVATE_CHECKED = (*PACKAGES, "tests", "benchmarks")


def _module_files() -> dict[str, tuple[Path, bool]]:
    """Return ``rockscreen.`` module name -> (file, whether it is a package's ``__init__``)."""
    modules = {}
    for package in PACKAGES:
        for path in sorted((REPO_ROOT / package).rglob("*.py")):
            parts = list(path.relative_to(REPO_ROOT).with_suffix("").parts)
            is_package = parts[-1] == "__init__"
            if is_package:
                parts.pop()
            modules[".".join(["rockscreen", *parts])] = (path, is_package)
    return modules


def _imported_from(node: ast.ImportFrom, module: str, is_package: bool) -> str:
    """The absolute module a ``from ... import`` statement of ``module`` names."""
    if not node.level:
        return node.module or ""
    base = module.split(".") if is_package else module.split(".")[:-1]
    base = base[: len(base) - (node.level - 1)]
    return ".".join([*base, node.module] if node.module else base)


def _import_targets(path: Path, module: str, is_package: bool) -> set[str]:
    """Every module ``module`` imports (``from pkg import module`` names the module)."""
    targets = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            targets.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            source = _imported_from(node, module, is_package)
            targets.add(source)
            targets.update(f"{source}.{alias.name}" for alias in node.names)
    return targets


def _import_graph() -> dict[str, set[str]]:
    """Module -> the modules of the three packages it imports, at any level of the code."""
    modules = _module_files()
    return {
        module: (_import_targets(path, module, is_package) & modules.keys()) - {module}
        for module, (path, is_package) in modules.items()
    }


def _strongly_connected(graph: dict[str, set[str]]) -> list[list[str]]:
    """Return the strongly connected components of ``graph`` (Tarjan, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    components = []
    for root in sorted(graph):
        if root in index:
            continue
        work = [(root, iter(sorted(graph[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, successors = work[-1]
            for successor in successors:
                if successor not in index:
                    index[successor] = low[successor] = len(index)
                    stack.append(successor)
                    on_stack.add(successor)
                    work.append((successor, iter(sorted(graph[successor]))))
                    break
                if successor in on_stack:
                    low[node] = min(low[node], index[successor])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    component = []
                    while True:
                        member = stack.pop()
                        on_stack.discard(member)
                        component.append(member)
                        if member == node:
                            break
                    components.append(sorted(component))
    return components


def _cycle_through(graph: dict[str, set[str]], component: list[str]) -> list[str]:
    """Return one shortest import chain from the component's first module back to itself."""
    start, members = component[0], set(component)
    previous: dict[str, str] = {}
    frontier = [start]
    while frontier:
        following = []
        for node in frontier:
            for successor in sorted(graph[node] & members):
                if successor == start:
                    chain = [node]
                    while chain[-1] != start:
                        chain.append(previous[chain[-1]])
                    return [start, *reversed(chain[:-1]), start]
                if successor not in previous:
                    previous[successor] = node
                    following.append(successor)
        frontier = following
    raise AssertionError(f"no cycle through {start}")  # pragma: no cover


def test_the_graph_resolves_relative_and_package_imports():
    modules = _module_files()
    path, is_package = modules["rockscreen.solver.reference.api"]
    targets = _import_targets(path, "rockscreen.solver.reference.api", is_package)
    assert "rockscreen.solver.reference.integrator" in targets
    graph = _import_graph()
    assert "rockscreen.solver.cache" in graph["rockscreen.solver"]  # from pkg import module
    assert len(graph) == len(modules) > 100


def test_strongly_connected_components_are_found():
    graph = {"a": {"b"}, "b": {"c"}, "c": {"a", "d"}, "d": set()}
    components = _strongly_connected(graph)
    assert sorted(map(tuple, components)) == [("a", "b", "c"), ("d",)]
    assert _cycle_through(graph, ["a", "b", "c"]) == ["a", "b", "c", "a"]


def test_no_import_cycle():
    graph = _import_graph()
    cycles = [
        " -> ".join(name.removeprefix("rockscreen.") for name in _cycle_through(graph, component))
        + (f" (component of {len(component)} modules)" if len(component) > 2 else "")
        for component in _strongly_connected(graph)
        if len(component) > 1
    ]
    assert not cycles, "import cycles:\n" + "\n".join(cycles)


# --------------------------------------------------------------------------- private names


def _private_imports(path: Path) -> list[str]:
    """``module:line name`` of every private name a file imports from a rockscreen module."""
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.ImportFrom):
            ours = node.level > 0 or (node.module or "").split(".")[0] == "rockscreen"
            names = [alias.name for alias in node.names] if ours else []
        elif isinstance(node, ast.Import):
            names = [alias.name for alias in node.names if alias.name.startswith("rockscreen.")]
            names = [part for name in names for part in name.split(".")]
        else:
            continue
        found += [f"line {node.lineno}: {name}" for name in names if _is_private(name)]
    return found


def _is_private(name: str) -> bool:
    return name.startswith("_") and not name.startswith("__")


@pytest.mark.parametrize("folder", PRIVATE_CHECKED)
def test_no_private_name_is_imported_from_another_module(folder):
    bad = {
        str(path.relative_to(REPO_ROOT)): found
        for path in sorted((REPO_ROOT / folder).rglob("*.py"))
        if (found := _private_imports(path))
    }
    assert not bad, f"private names imported across modules: {bad}"


# --------------------------------------------------------------------------- errors

#: The modules that define exceptions: the user-facing hierarchy (``pipeline/errors.py``,
#: with the ``stations`` errors it re-exports) and the solver's own ``ParameterError``.
ERROR_MODULES = {"pipeline/errors.py", "stations/errors.py", "solver/errors.py"}


def _raisable(name: str) -> bool:
    return name.endswith(("Error", "Exception", "Interrupt", "Interrupted", "Warning"))


@pytest.mark.parametrize("package", PACKAGES)
def test_exceptions_are_defined_only_in_the_errors_modules(package):
    for path in sorted((REPO_ROOT / package).rglob("*.py")):
        where = str(path.relative_to(REPO_ROOT))
        if where in ERROR_MODULES:
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ClassDef):
                bases = [ast.unparse(base).split(".")[-1] for base in node.bases]
                assert not any(map(_raisable, bases)), (
                    f"{where} defines the exception {node.name}: define it in pipeline/errors.py"
                )


def test_pipeline_errors_export_every_user_facing_error():
    from rockscreen.pipeline import errors
    from rockscreen.stations import errors as station_errors

    defined = {
        name
        for module in (errors, station_errors)
        for name, value in vars(module).items()
        if isinstance(value, type) and issubclass(value, errors.RockscreenError)
    }
    assert defined <= set(errors.__all__)


# --------------------------------------------------------------------------- infrastructure

#: The solver's two infrastructure modules, which pipeline uses too (docs/architecture.md,
#: "Infrastructure"): the standard library only, so that importing them costs nothing and
#: pulls no physics (nor numba) into ``rockscreen --help``.
INFRASTRUCTURE = ("solver/lazy.py", "solver/docstrings.py")


@pytest.mark.parametrize("module", INFRASTRUCTURE)
def test_infrastructure_imports_only_the_standard_library(module):
    import sys

    roots = {name.split(".")[0] for name in _imports(REPO_ROOT / module)}
    assert roots <= set(sys.stdlib_module_names) | {"__future__"}, f"{module} imports {roots}"


# --------------------------------------------------------------------------- risk roles

#: The roles inside ``pipeline/risk/`` (docs/architecture.md): each role imports only the
#: roles listed for it. ``measures`` is the bottom.
RISK_ROLES = {
    "measures": set(),
    "scenario": {"measures"},
    "checks": {"measures"},
    "assess": {"measures", "checks", "uncertainty"},
    "uncertainty": {"measures", "checks"},
}
#: Imports across roles that the table does not allow, each named: the code checks' wiring
#: reads the fits of one tower's IDA (``collapse_rate``, ``fit_level``).
RISK_ROLE_EXCEPTIONS = {("checks", "pipeline.risk.assess.tower_ida")}


def _risk_role(name: str) -> str | None:
    parts = name.split(".")
    if parts[:2] != ["pipeline", "risk"] or len(parts) < 3:
        return None
    return parts[2] if parts[2] in RISK_ROLES else None


@pytest.mark.parametrize("role", sorted(RISK_ROLES))
def test_risk_roles_import_only_the_roles_below(role):
    folder = REPO_ROOT / "pipeline" / "risk" / role
    assert folder.is_dir(), f"pipeline/risk/{role}/ is missing"
    for path in folder.rglob("*.py"):
        for name in _imports(path):
            other = _risk_role(name)
            if other is None or other == role:
                continue
            module = ".".join(name.split(".")[:4])
            if (role, module) in RISK_ROLE_EXCEPTIONS or (role, name) in RISK_ROLE_EXCEPTIONS:
                continue
            where = path.relative_to(REPO_ROOT)
            assert other in RISK_ROLES[role], f"{where} imports {name}: {role} may not use {other}"


@pytest.mark.parametrize("role", ("assess", "measures", "scenario"))
def test_risk_role_packages_import_nothing_at_import(role):
    assert not _imports(REPO_ROOT / "pipeline" / "risk" / role / "__init__.py")
