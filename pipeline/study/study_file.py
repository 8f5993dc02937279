"""Study files: the TOML description of a parameter sweep on one tower, parsed and validated.

A *study file* (TOML) describes one tower and one or more *groups*; each group is a
model (``rocking`` or ``double-block``), an excitation type (``harmonic`` or ``pulse``)
and lists of excitation and model parameters. The cartesian product of a group's lists
is its run set; the study's run set is the concatenation of its groups' run sets, in
file order. The format is documented in ``examples/seed_study/README.md``; an example::

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

Weights are converted to masses with ``rockscreen.solver.constants.G``.
"""

from __future__ import annotations

import itertools
import math
import os
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from rockscreen.pipeline.config_schema import tomllib
from rockscreen.pipeline.engine.registry import STUDY, model_names, solver_model
from rockscreen.pipeline.errors import ConfigError
from rockscreen.pipeline.study.values import (
    read_amplitudes,
    read_durations,
    read_formulations,
    read_frequencies,
    read_friction,
)
from rockscreen.pipeline.vocabulary import PULSE_SHAPES
from rockscreen.solver.constants import G

#: Excitation types a group may use.
EXCITATIONS = ("harmonic", "pulse")

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
    "formulation",
)


# --------------------------------------------------------------------------- study model


@dataclass(frozen=True)
class Tower:
    """The rocking tower and the building it stands on."""

    #: Label for tables and figures.
    name: str
    #: Full base width 2b [m].
    width: float
    #: Full height 2h [m].
    height: float
    #: Angular-velocity restitution [-]; None for the solver's default.
    eta: float | None
    #: Tower mass m [kg] (needed by the double block).
    tower_mass: float | None
    #: Building mass M [kg] (needed by the double block).
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
    formulations: tuple[str, ...] = ("consistent",)

    def axes(self) -> tuple[tuple[Any, ...], ...]:
        """Return the grid's parameter lists, slowest first.

        Amplitude, formulation, friction pair, eta, duration, frequency: so that one
        figure panel's runs are contiguous.
        """
        return (
            self.amplitudes,
            self.formulations,
            self.friction,
            self.etas,
            self.durations,
            self.frequencies,
        )

    def size(self) -> int:
        """Return the number of combinations in this group."""
        return math.prod(len(values) for values in self.axes())


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
    formulation: str = "consistent"


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

        Within a group the order is that of :meth:`Group.axes` (the last varies fastest).
        """
        cases = []
        for g_index, group in enumerate(self.groups):
            grid = itertools.product(*group.axes())
            for (text, amp), formulation, (mu_s, mu_k), eta, duration, freq in grid:
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
                        formulation=formulation,
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
        As :func:`parse_study` makes it, with ``source`` the file's path.

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


def _parse_group(table: Any, index: int, tower: Tower, where: str) -> Group:
    if not isinstance(table, dict):
        raise ConfigError(f"{where}: must be a table")
    _check_keys(table, _GROUP_KEYS, where)
    name = table.get("name", f"group {index + 1}")
    if not isinstance(name, str):
        raise ConfigError(f"{where}: key 'name' = {name!r} must be a string")
    where = f"{where} ({name!r})"
    model = _choice(table, "model", model_names(STUDY), where)
    excitation = _choice(table, "excitation", EXCITATIONS, where)
    if excitation == "pulse":
        shape = _choice(table, "shape", PULSE_SHAPES, where)
        durations = read_durations(table, where, required=False)
    else:
        if "shape" in table:
            raise ConfigError(
                f"{where}: key 'shape' = {table['shape']!r} is only allowed with "
                "excitation = 'pulse' (a harmonic excitation is A cos(2 pi f t))"
            )
        shape = "cosine"
        durations = read_durations(table, where, required=True)
    dt = _positive(table, "dt_s", where, required=False)
    if solver_model(model).takes("mu_s"):
        friction = read_friction(table, where)
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
    formulations = read_formulations(table, model, where)
    return Group(
        name=name,
        model=model,
        excitation=excitation,
        shape=shape,
        amplitudes=read_amplitudes(table, where),
        frequencies=read_frequencies(table, where),
        durations=durations,
        dt=dt,
        friction=friction,
        etas=etas,
        formulations=formulations,
    )
