"""Parameter sweeps on one tower: study files, grid expansion, running and the sweep archive.

A *study file* (TOML) describes one tower and one or more *groups*; each group is a
model (``rocking`` or ``double-block``), an excitation type (``harmonic`` or ``pulse``)
and lists of excitation and model parameters. The cartesian product of a group's lists
is its run set; the study's run set is the concatenation of its groups' run sets, in
file order. The format is documented in ``docs/seed_study.md``; an example::

    title = "S. Anna in Cervino, Tables 2 and 3"

    [tower]
    name = "S. Anna in Cervino"
    width_m = 2.06                # full base width 2b
    height_m = 5.80               # full height 2h
    eta = 0.9                     # angular-velocity restitution
    tower_weight_kN = 339.0       # or tower_mass_kg
    building_weight_kN = 96840.67 # or building_mass_kg

    [[group]]
    name = "double block, harmonic"
    model = "double-block"
    excitation = "harmonic"       # A cos(2 pi f t) for 0 <= t <= duration_s
    amplitudes = ["0.4g", "0.5g"] # always with units
    frequencies_hz = [3, 4, 5, 6, 7]
    duration_s = 10.0             # or a list: one more grid dimension
    friction = [[1.0, 0.7], [1.25, 1.0]]   # (mu_s, mu_k) pairs

Results go to an HDF5 *sweep archive* (:func:`write_sweep_archive`): root attributes
(``kind = "rockscreen-sweep"``, version, the study text, creation time), ``/tower``,
a ``/cases`` table with one row per combination and ``/histories/<index>`` with the
time histories. Weights are converted to masses with ``solver.constants.G``.
"""

from __future__ import annotations

import datetime as _dt
import itertools
import math
import os
from collections.abc import Callable, Iterable, Iterator
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from pipeline.errors import ArchiveError, ConfigError, UnitsError
from pipeline.motion.excitations import PULSE_SHAPES, default_dt, harmonic, pulse, pulse_duration
from pipeline.units import parse_acceleration
from pipeline.vocabulary import STUDY_MODELS
from solver.constants import G

try:  # Python >= 3.11
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib

#: Model names a group may use.
MODELS = STUDY_MODELS
#: Excitation types a group may use.
EXCITATIONS = ("harmonic", "pulse")
#: Value of the root attribute ``kind`` that marks a sweep archive.
ARCHIVE_KIND = "rockscreen-sweep"
#: Layout version of the sweep archive.
ARCHIVE_FORMAT_VERSION = 1

_TOP_KEYS = ("title", "tower", "group")
_TOWER_KEYS = (
    "name",
    "width_m",
    "height_m",
    "eta",
    "tower_mass_kg",
    "tower_weight_kN",
    "building_mass_kg",
    "building_weight_kN",
)
_GROUP_KEYS = (
    "name",
    "model",
    "excitation",
    "shape",
    "amplitudes",
    "frequencies_hz",
    "duration_s",
    "dt_s",
    "friction",
    "eta",
)


# --------------------------------------------------------------------------- study model


@dataclass(frozen=True)
class Tower:
    """The rocking tower and the building it stands on.

    Attributes
    ----------
    name : str
        Label for tables and figures.
    width : float
        Full base width 2b [m].
    height : float
        Full height 2h [m].
    eta : float or None
        Angular-velocity restitution [-]; None for the solver's default.
    tower_mass : float or None
        Tower mass m [kg] (needed by the double block).
    building_mass : float or None
        Building mass M [kg] (needed by the double block).
    """

    name: str
    width: float
    height: float
    eta: float | None
    tower_mass: float | None
    building_mass: float | None

    @property
    def alpha(self) -> float:
        """Slenderness atan(b/h) [rad]."""
        return math.atan2(self.width, self.height)


@dataclass(frozen=True)
class Group:
    """One grid of runs: a model, an excitation type and parameter lists."""

    name: str
    model: str
    excitation: str
    shape: str
    amplitudes: tuple[tuple[str, float], ...]
    frequencies: tuple[float, ...]
    durations: tuple[float | None, ...]
    dt: float | None
    friction: tuple[tuple[float, float], ...]
    etas: tuple[float | None, ...]

    def size(self) -> int:
        """Return the number of combinations in this group."""
        lists = (self.amplitudes, self.friction, self.etas, self.durations, self.frequencies)
        return math.prod(len(values) for values in lists)


@dataclass(frozen=True)
class Case:
    """One combination of a group: everything needed to run it.

    ``mu_s``/``mu_k`` are NaN for the rocking model; ``eta`` None means the
    solver's default restitution.
    """

    index: int
    group_index: int
    group: str
    model: str
    excitation: str
    shape: str
    amplitude_text: str
    amplitude: float
    frequency: float
    duration: float | None
    dt: float | None
    mu_s: float
    mu_k: float
    eta: float | None


@dataclass(frozen=True)
class Study:
    """A parsed study file."""

    title: str
    tower: Tower
    groups: tuple[Group, ...]
    source_text: str
    source: str = "<string>"

    def cases(self) -> list[Case]:
        """Expand every group's grid into the study's run set, in file order.

        Within a group the order is amplitude, friction pair, eta, duration,
        frequency (the last varies fastest), so that one figure panel's runs are
        contiguous.
        """
        cases = []
        for g_index, group in enumerate(self.groups):
            grid = itertools.product(
                group.amplitudes, group.friction, group.etas, group.durations, group.frequencies
            )
            for (text, amp), (mu_s, mu_k), eta, duration, freq in grid:
                cases.append(
                    Case(
                        index=len(cases),
                        group_index=g_index,
                        group=group.name,
                        model=group.model,
                        excitation=group.excitation,
                        shape=group.shape,
                        amplitude_text=text,
                        amplitude=amp,
                        frequency=freq,
                        duration=duration,
                        dt=group.dt,
                        mu_s=mu_s,
                        mu_k=mu_k,
                        eta=eta,
                    )
                )
        return cases


# --------------------------------------------------------------------------- parsing


def load_study(path: str | os.PathLike) -> Study:
    """Read and validate a study file.

    Parameters
    ----------
    path : str or path-like
        The TOML study file.

    Returns
    -------
    Study

    Raises
    ------
    ConfigError
        If the file is missing, is not valid TOML, or a key or value is not allowed.
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise ConfigError(f"cannot read study file {str(path)!r}: {exc.strerror}") from exc
    return parse_study(text, source=str(path))


def parse_study(text: str, source: str = "<string>") -> Study:
    """Parse and validate the text of a study file (see the module docstring).

    Parameters
    ----------
    text : str
        TOML text.
    source : str
        Name of the file, for error messages.

    Returns
    -------
    Study

    Raises
    ------
    ConfigError
        Naming the key, the bad value and what is allowed.
    """
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"{source}: not valid TOML: {exc}") from exc
    _check_keys(data, _TOP_KEYS, f"{source}: top level")
    title = data.get("title", Path(source).stem)
    if not isinstance(title, str):
        raise ConfigError(f"{source}: key 'title' = {title!r} must be a string")
    if "tower" not in data or not isinstance(data["tower"], dict):
        raise ConfigError(f"{source}: a [tower] table is required")
    tower = _parse_tower(data["tower"], f"{source}: [tower]")
    groups_raw = data.get("group")
    if not isinstance(groups_raw, list) or not groups_raw:
        raise ConfigError(f"{source}: at least one [[group]] table is required")
    groups = tuple(
        _parse_group(raw, i, tower, f"{source}: [[group]] #{i + 1}")
        for i, raw in enumerate(groups_raw)
    )
    return Study(title=title, tower=tower, groups=groups, source_text=text, source=source)


def _check_keys(table: dict, allowed: Iterable[str], where: str) -> None:
    allowed = tuple(allowed)
    for key in table:
        if key not in allowed:
            raise ConfigError(f"{where}: unknown key {key!r}; allowed keys: {', '.join(allowed)}")


def _number(table: dict, key: str, where: str, *, required: bool = True) -> float | None:
    if key not in table:
        if required:
            raise ConfigError(f"{where}: key {key!r} is required")
        return None
    value = table[key]
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ConfigError(f"{where}: key {key!r} = {value!r} must be a finite number")
    return float(value)


def _positive(table: dict, key: str, where: str, *, required: bool = True) -> float | None:
    value = _number(table, key, where, required=required)
    if value is not None and value <= 0.0:
        raise ConfigError(f"{where}: key {key!r} = {value!r} must be > 0")
    return value


def _eta(value: Any, key: str, where: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not 0.0 < value <= 1.0:
        raise ConfigError(
            f"{where}: key {key!r} = {value!r} must be a number in (0, 1] "
            "(the angular-velocity ratio theta'+/theta'-)"
        )
    return float(value)


def _mass(table: dict, stem: str, where: str) -> float | None:
    """Mass [kg] from ``<stem>_mass_kg`` or ``<stem>_weight_kN`` (exactly one)."""
    mass = _positive(table, f"{stem}_mass_kg", where, required=False)
    weight = _positive(table, f"{stem}_weight_kN", where, required=False)
    if mass is not None and weight is not None:
        raise ConfigError(
            f"{where}: give either {stem}_mass_kg or {stem}_weight_kN, not both "
            f"({stem}_mass_kg = {mass!r}, {stem}_weight_kN = {weight!r})"
        )
    return mass if weight is None else weight * 1e3 / G


def _parse_tower(table: dict, where: str) -> Tower:
    _check_keys(table, _TOWER_KEYS, where)
    name = table.get("name", "tower")
    if not isinstance(name, str):
        raise ConfigError(f"{where}: key 'name' = {name!r} must be a string")
    eta = table.get("eta")
    return Tower(
        name=name,
        width=_positive(table, "width_m", where),
        height=_positive(table, "height_m", where),
        eta=None if eta is None else _eta(eta, "eta", where),
        tower_mass=_mass(table, "tower", where),
        building_mass=_mass(table, "building", where),
    )


def _choice(table: dict, key: str, allowed: tuple[str, ...], where: str) -> str:
    if key not in table:
        raise ConfigError(f"{where}: key {key!r} is required; allowed values: {', '.join(allowed)}")
    value = table[key]
    if value not in allowed:
        raise ConfigError(
            f"{where}: key {key!r} = {value!r} is not allowed; allowed values: {', '.join(allowed)}"
        )
    return value


def _nonempty_list(table: dict, key: str, where: str, example: str) -> list:
    if key not in table:
        raise ConfigError(f"{where}: key {key!r} is required, e.g. {key} = {example}")
    value = table[key]
    if not isinstance(value, list) or not value:
        raise ConfigError(
            f"{where}: key {key!r} = {value!r} must be a non-empty list, e.g. {example}"
        )
    return value


def _amplitudes(table: dict, where: str) -> tuple[tuple[str, float], ...]:
    out = []
    for item in _nonempty_list(table, "amplitudes", where, '["0.4g", "3.92m/s2"]'):
        if not isinstance(item, str):
            raise ConfigError(
                f"{where}: key 'amplitudes' item {item!r} must be a string with its unit, "
                f'e.g. "{item}g" or "{item}m/s2"; a bare number is refused'
            )
        try:
            value = parse_acceleration(item, name="amplitude")
        except UnitsError as exc:
            raise ConfigError(f"{where}: key 'amplitudes': {exc}") from exc
        if value <= 0.0:
            raise ConfigError(f"{where}: key 'amplitudes' item {item!r} must be > 0")
        out.append((item.strip(), value))
    return tuple(out)


def _frequencies(table: dict, where: str) -> tuple[float, ...]:
    out = []
    for item in _nonempty_list(table, "frequencies_hz", where, "[3, 4, 5]"):
        if isinstance(item, bool) or not isinstance(item, int | float) or not item > 0.0:
            raise ConfigError(
                f"{where}: key 'frequencies_hz' item {item!r} must be a number > 0 [Hz]"
            )
        out.append(float(item))
    return tuple(out)


def _durations(table: dict, where: str, *, required: bool) -> tuple[float | None, ...]:
    """``duration_s``: one number or a list (a grid dimension) of durations [s]."""
    if "duration_s" not in table:
        if required:
            raise ConfigError(f"{where}: key 'duration_s' is required, e.g. duration_s = 10.0")
        return (None,)
    raw = table["duration_s"]
    items = raw if isinstance(raw, list) else [raw]
    if not items:
        raise ConfigError(f"{where}: key 'duration_s' = [] must not be empty")
    return tuple(_positive({"duration_s": v}, "duration_s", where) for v in items)


def _friction(table: dict, where: str) -> tuple[tuple[float, float], ...]:
    out = []
    for item in _nonempty_list(table, "friction", where, "[[1.0, 0.7], [1.25, 1.0]]"):
        ok = (
            isinstance(item, list)
            and len(item) == 2
            and all(isinstance(v, int | float) and not isinstance(v, bool) for v in item)
        )
        if not ok:
            raise ConfigError(f"{where}: key 'friction' item {item!r} must be a pair [mu_s, mu_k]")
        mu_s, mu_k = float(item[0]), float(item[1])
        if not (math.isfinite(mu_s) and math.isfinite(mu_k)) or mu_k < 0.0:
            raise ConfigError(
                f"{where}: key 'friction' item {item!r}: mu_s and mu_k must be finite and >= 0"
            )
        if mu_k > mu_s:
            raise ConfigError(
                f"{where}: key 'friction' item {item!r}: mu_k={mu_k} must not exceed mu_s={mu_s}"
            )
        out.append((mu_s, mu_k))
    return tuple(out)


def _parse_group(table: Any, index: int, tower: Tower, where: str) -> Group:
    if not isinstance(table, dict):
        raise ConfigError(f"{where}: must be a table")
    _check_keys(table, _GROUP_KEYS, where)
    name = table.get("name", f"group {index + 1}")
    if not isinstance(name, str):
        raise ConfigError(f"{where}: key 'name' = {name!r} must be a string")
    where = f"{where} ({name!r})"
    model = _choice(table, "model", MODELS, where)
    excitation = _choice(table, "excitation", EXCITATIONS, where)
    if excitation == "pulse":
        shape = _choice(table, "shape", PULSE_SHAPES, where)
        durations = _durations(table, where, required=False)
    else:
        if "shape" in table:
            raise ConfigError(
                f"{where}: key 'shape' = {table['shape']!r} is only allowed with "
                "excitation = 'pulse' (a harmonic excitation is A cos(2 pi f t))"
            )
        shape = "cosine"
        durations = _durations(table, where, required=True)
    dt = _positive(table, "dt_s", where, required=False)
    if model == "double-block":
        friction = _friction(table, where)
        if tower.tower_mass is None or tower.building_mass is None:
            raise ConfigError(
                f"{where}: model 'double-block' needs the masses in [tower]: "
                "tower_mass_kg or tower_weight_kN, and building_mass_kg or building_weight_kN"
            )
    else:
        if "friction" in table:
            raise ConfigError(
                f"{where}: key 'friction' is only allowed with model = 'double-block' "
                f"(model is {model!r})"
            )
        friction = ((math.nan, math.nan),)
    if "eta" in table:
        raw = table["eta"]
        items = raw if isinstance(raw, list) else [raw]
        if not items:
            raise ConfigError(f"{where}: key 'eta' = [] must not be empty")
        etas = tuple(_eta(v, "eta", where) for v in items)
    else:
        etas = (tower.eta,)
    return Group(
        name=name,
        model=model,
        excitation=excitation,
        shape=shape,
        amplitudes=_amplitudes(table, where),
        frequencies=_frequencies(table, where),
        durations=durations,
        dt=dt,
        friction=friction,
        etas=etas,
    )


# --------------------------------------------------------------------------- running


@dataclass
class CaseResult:
    """Outcome of one case, with its histories (empty arrays when not kept)."""

    case: Case
    status: str
    overturned: bool
    theta_max: float
    theta_max_over_alpha: float
    n_impacts: int
    slip_max: float
    slip_residual: float
    eta: float
    alpha: float
    p: float
    t_end: float
    histories: dict[str, np.ndarray] = field(default_factory=dict)


#: History arrays kept per case, with their units.
HISTORY_UNITS = {"t": "s", "theta": "rad", "theta_dot": "rad/s", "u": "m", "regime": "-"}


def case_excitation(case: Case) -> tuple[np.ndarray, float]:
    """Sample the base acceleration of a case.

    Returns
    -------
    acc : ndarray, shape (n,)
        Acceleration [m/s^2].
    dt : float
        Sampling step [s].
    """
    if case.excitation == "harmonic":
        return harmonic(case.amplitude, case.frequency, case.duration, dt=case.dt)
    return pulse(case.shape, case.amplitude, case.frequency, dt=case.dt, duration=case.duration)


def solve_case(case: Case, tower: Tower):
    """Run one case with the project's solver and return its ``Response``."""
    from solver import RockingBlock, solve_double_block, solve_rocking

    acc, dt = case_excitation(case)
    block = RockingBlock.from_dimensions(tower.width, tower.height, eta=case.eta)
    if case.model == "rocking":
        return solve_rocking(block, acc, dt, history=True)
    return solve_double_block(
        block,
        acc,
        dt,
        tower_mass=tower.tower_mass,
        building_mass=tower.building_mass,
        mu_s=case.mu_s,
        mu_k=case.mu_k,
        history=True,
    )


def _float(value: Any) -> float:
    return math.nan if value is None else float(value)


def result_from_response(case: Case, response: Any) -> CaseResult:
    """Collect the scalars and histories of a solver ``Response`` for the archive."""
    histories = {}
    for name in HISTORY_UNITS:
        value = getattr(response, name, None)
        if value is not None:
            histories[name] = np.asarray(value)
    return CaseResult(
        case=case,
        status=str(response.status),
        overturned=bool(response.overturned),
        theta_max=_float(response.theta_max),
        theta_max_over_alpha=_float(response.theta_max_over_alpha),
        n_impacts=int(response.n_impacts),
        slip_max=_float(getattr(response, "slip_max", None)),
        slip_residual=_float(getattr(response, "slip_residual", None)),
        eta=_float(getattr(response, "eta", case.eta)),
        alpha=_float(getattr(response, "alpha", None)),
        p=_float(getattr(response, "p", None)),
        t_end=_float(getattr(response, "t_end", None)),
        histories=histories,
    )


def _run_one(args: tuple[Case, Tower, Callable]) -> CaseResult:
    case, tower, solve = args
    return result_from_response(case, solve(case, tower))


def run_study(
    study: Study,
    *,
    jobs: int = 1,
    solve: Callable[[Case, Tower], Any] = solve_case,
    cases: list[Case] | None = None,
) -> Iterator[CaseResult]:
    """Run every case of a study and yield the results in case order.

    Parameters
    ----------
    study : Study
        The parsed study.
    jobs : int
        Worker processes (1 runs in this process). With more than one, ``solve``
        must be a module-level function (it is pickled).
    solve : callable
        ``solve(case, tower) -> Response``; the default runs the project's solver.
    cases : list of Case, optional
        A subset of ``study.cases()`` to run.

    Yields
    ------
    CaseResult
    """
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise ConfigError(f"jobs={jobs!r} must be an integer >= 1")
    cases = study.cases() if cases is None else cases
    work = [(case, study.tower, solve) for case in cases]
    if jobs == 1 or len(work) <= 1:
        for item in work:
            yield _run_one(item)
        return
    with ProcessPoolExecutor(max_workers=jobs) as pool:
        yield from pool.map(_run_one, work)


# --------------------------------------------------------------------------- archive

#: Columns of ``/cases``: (name, numpy dtype, unit).
CASE_COLUMNS = (
    ("index", "i4", "-"),
    ("group_index", "i4", "-"),
    ("group", "S64", "-"),
    ("model", "S16", "-"),
    ("excitation", "S16", "-"),
    ("shape", "S16", "-"),
    ("amplitude", "S24", "-"),
    ("amplitude_m_s2", "f8", "m/s2"),
    ("amplitude_g", "f8", "g"),
    ("frequency_hz", "f8", "Hz"),
    ("duration_s", "f8", "s"),
    ("dt_s", "f8", "s"),
    ("mu_s", "f8", "-"),
    ("mu_k", "f8", "-"),
    ("eta", "f8", "-"),
    ("status", "S24", "-"),
    ("overturned", "?", "-"),
    ("theta_max_rad", "f8", "rad"),
    ("theta_max_over_alpha", "f8", "-"),
    ("n_impacts", "i4", "-"),
    ("slip_max_m", "f8", "m"),
    ("slip_residual_m", "f8", "m"),
    ("t_end_s", "f8", "s"),
)
CASES_DTYPE = np.dtype([(name, dtype) for name, dtype, _ in CASE_COLUMNS])


def _case_row(result: CaseResult) -> tuple:
    c = result.case
    dt = default_dt(c.frequency) if c.dt is None else c.dt
    duration = c.duration
    if duration is None:  # a pulse without padding lasts one period (half for the short shapes)
        duration = pulse_duration(c.shape, c.frequency)
    return (
        c.index,
        c.group_index,
        c.group.encode("utf-8")[:64],
        c.model.encode(),
        c.excitation.encode(),
        c.shape.encode(),
        c.amplitude_text.encode("utf-8")[:24],
        c.amplitude,
        c.amplitude / G,
        c.frequency,
        duration,
        dt,
        c.mu_s,
        c.mu_k,
        result.eta,
        result.status.encode()[:24],
        result.overturned,
        result.theta_max,
        result.theta_max_over_alpha,
        result.n_impacts,
        result.slip_max,
        result.slip_residual,
        result.t_end,
    )


def write_sweep_archive(
    path: str | os.PathLike,
    study: Study,
    results: Iterable[CaseResult],
    *,
    on_result: Callable[[CaseResult], None] | None = None,
) -> list[CaseResult]:
    """Write a sweep archive, streaming histories as results arrive.

    The file is written to ``<path>.part`` and moved to ``path`` only when complete,
    so an interrupted sweep never leaves a half-written archive at the final path.

    Parameters
    ----------
    path : str or path-like
        Final archive path (``.h5``).
    study : Study
        The study that was run (its text is stored).
    results : iterable of CaseResult
        Typically :func:`run_study`.
    on_result : callable, optional
        Called with each result after it is stored (progress reports).

    Returns
    -------
    list of CaseResult
        The results, histories dropped to save memory.
    """
    import h5py

    from pipeline import __version__
    from pipeline.archive.atomic import atomic_path

    kept: list[CaseResult] = []
    tower = study.tower
    with atomic_path(path, suffix=".part") as part:
        with h5py.File(part, "w") as h5:
            h5.attrs["kind"] = ARCHIVE_KIND
            h5.attrs["format_version"] = ARCHIVE_FORMAT_VERSION
            h5.attrs["rockscreen_version"] = __version__
            h5.attrs["created_utc"] = _dt.datetime.now(_dt.timezone.utc).isoformat(
                timespec="seconds"
            )
            h5.attrs["study_title"] = study.title
            h5.attrs["study_source"] = study.source
            h5.attrs["study_toml"] = study.source_text
            grp = h5.create_group("tower")
            grp.attrs["name"] = tower.name
            for key, value, unit in (
                ("width_m", tower.width, "m"),
                ("height_m", tower.height, "m"),
                ("alpha_rad", tower.alpha, "rad"),
                ("eta", _float(tower.eta), "-"),
                ("tower_mass_kg", _float(tower.tower_mass), "kg"),
                ("building_mass_kg", _float(tower.building_mass), "kg"),
            ):
                grp.attrs[key] = value
                grp.attrs[f"{key}.units"] = unit
            hist = h5.create_group("histories")
            rows = []
            for result in results:
                sub = hist.create_group(str(result.case.index))
                for name, data in result.histories.items():
                    ds = sub.create_dataset(
                        name, data=data, compression="gzip", shuffle=True, chunks=True
                    )
                    ds.attrs["units"] = HISTORY_UNITS[name]
                rows.append(_case_row(result))
                result.histories = {}
                kept.append(result)
                if on_result is not None:
                    on_result(result)
            table = np.array(rows, dtype=CASES_DTYPE)
            ds = h5.create_dataset("cases", data=table)
            ds.attrs["columns"] = [name for name, _, _ in CASE_COLUMNS]
            ds.attrs["units"] = [unit for _, _, unit in CASE_COLUMNS]
    return kept


def is_sweep_archive(path: str | os.PathLike) -> bool:
    """Return True if ``path`` is an HDF5 sweep archive written by rockscreen."""
    import h5py

    path = Path(path)
    if not path.is_file() or not h5py.is_hdf5(path):
        return False
    try:
        with h5py.File(path, "r") as h5:
            return h5.attrs.get("kind") == ARCHIVE_KIND and "cases" in h5
    except OSError:
        return False


def _decode(value: Any) -> Any:
    if isinstance(value, bytes):
        return value.decode("utf-8", errors="replace")
    if isinstance(value, np.generic):
        return value.item()
    return value


def read_cases(path: str | os.PathLike) -> list[dict[str, Any]]:
    """Read the ``/cases`` table of a sweep archive as a list of dicts (strings decoded).

    Raises
    ------
    ArchiveError
        If the file is not a sweep archive.
    """
    import h5py

    if not is_sweep_archive(path):
        raise ArchiveError(f"{str(path)!r} is not a rockscreen sweep archive")
    with h5py.File(path, "r") as h5:
        table = h5["cases"][()]
    return [{name: _decode(row[name]) for name in table.dtype.names} for row in table]


def read_history(path: str | os.PathLike, index: int) -> dict[str, np.ndarray]:
    """Read ``/histories/<index>`` of a sweep archive (arrays keyed t, theta, u, regime...).

    Raises
    ------
    ArchiveError
        If the file is not a sweep archive or holds no such case.
    """
    import h5py

    if not is_sweep_archive(path):
        raise ArchiveError(f"{str(path)!r} is not a rockscreen sweep archive")
    with h5py.File(path, "r") as h5:
        key = f"histories/{index}"
        if key not in h5:
            raise ArchiveError(f"{str(path)!r} holds no history for case {index}")
        return {name: ds[()] for name, ds in h5[key].items()}


def read_archive_attrs(path: str | os.PathLike) -> dict[str, Any]:
    """Return the root and ``/tower`` attributes of a sweep archive."""
    import h5py

    if not is_sweep_archive(path):
        raise ArchiveError(f"{str(path)!r} is not a rockscreen sweep archive")
    with h5py.File(path, "r") as h5:
        attrs = {k: _decode(v) for k, v in h5.attrs.items()}
        attrs["tower"] = {k: _decode(v) for k, v in h5["tower"].attrs.items()}
    return attrs


# --------------------------------------------------------------------------- table


def _fmt(value: float, spec: str) -> str:
    return (
        "-"
        if value is None or (isinstance(value, float) and math.isnan(value))
        else format(value, spec)
    )


def format_cases_table(rows: list[dict[str, Any]]) -> str:
    """Format ``/cases`` rows (as from :func:`read_cases`) as a plain-text table."""
    headers = (
        "#",
        "group",
        "model",
        "A [g]",
        "f [Hz]",
        "mu_s [-]",
        "mu_k [-]",
        "status",
        "theta_max [rad]",
        "theta_max/alpha [-]",
        "impacts",
        "slip_max [m]",
    )
    body = [
        (
            str(r["index"]),
            str(r["group"]),
            str(r["model"]),
            _fmt(r["amplitude_g"], ".3g"),
            _fmt(r["frequency_hz"], "g"),
            _fmt(r["mu_s"], "g"),
            _fmt(r["mu_k"], "g"),
            str(r["status"]),
            _fmt(r["theta_max_rad"], ".4g"),
            _fmt(r["theta_max_over_alpha"], ".4f"),
            str(r["n_impacts"]),
            _fmt(r["slip_max_m"], ".3g"),
        )
        for r in rows
    ]
    widths = [max([len(h)] + [len(b[i]) for b in body]) for i, h in enumerate(headers)]
    lines = ["  ".join(h.rjust(w) for h, w in zip(headers, widths, strict=True))]
    lines.append("  ".join("-" * w for w in widths))
    lines += ["  ".join(c.rjust(w) for c, w in zip(b, widths, strict=True)) for b in body]
    return "\n".join(lines)


def format_markdown_tables(rows: list[dict[str, Any]], title: str = "") -> str:
    """Format ``/cases`` rows as Markdown tables in the layout of the seed paper's tables.

    One table per (group, amplitude, duration): a row per (mu_s, mu_k, eta) and a
    column per frequency; each cell is theta_max [rad] followed by theta_max/alpha in
    parentheses, with the run's status when the tower overturned or never uplifted.

    Parameters
    ----------
    rows : list of dict
        As from :func:`read_cases`.
    title : str
        Heading put above the tables (omitted when empty).

    Returns
    -------
    str
        Markdown text.
    """
    tables: dict[tuple, list[dict[str, Any]]] = {}
    for row in rows:
        key = (row["group_index"], row["group"], row["amplitude"], row["duration_s"])
        tables.setdefault(key, []).append(row)
    parts = [f"### {title}\n"] if title else []
    for (_, group, amplitude, duration), t_rows in tables.items():
        freqs = list(dict.fromkeys(r["frequency_hz"] for r in t_rows))
        lines: dict[tuple, dict[float, str]] = {}
        for r in t_rows:
            cell = f"{r['theta_max_rad']:.4g} ({r['theta_max_over_alpha']:.3f})"
            if r["status"] in ("overturned", "no_motion"):
                cell = r["status"].replace("_", " ")
            # NaN friction (rocking rows) must compare equal to group into one line
            friction_key = (None, None) if r["model"] == "rocking" else (r["mu_s"], r["mu_k"])
            lines.setdefault((r["model"], *friction_key, r["eta"]), {})[r["frequency_hz"]] = cell
        parts.append(
            f"**{group}, A = {amplitude}, excitation {duration:.4g} s**: "
            "theta_max [rad] (theta_max/alpha [-])\n"
        )
        parts.append("| mu_s / mu_k | eta | " + " | ".join(f"{f:g} Hz" for f in freqs) + " |")
        parts.append("|---|---|" + "---|" * len(freqs))
        for (model, mu_s, mu_k, eta), cells in lines.items():
            friction = "single block" if model == "rocking" else f"{mu_s:g} / {mu_k:g}"
            values = " | ".join(cells.get(f, "") for f in freqs)
            parts.append(f"| {friction} | {eta:g} | {values} |")
        parts.append("")
    return "\n".join(parts)
