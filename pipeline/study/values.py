"""Validators of the list values of a study file group (amplitudes, frequencies, friction...)."""

from __future__ import annotations

import math

from rockscreen.pipeline.engine.registry import solver_model
from rockscreen.pipeline.errors import ConfigError, UnitsError
from rockscreen.pipeline.units import parse_acceleration
from rockscreen.solver.docstrings import fill_doc
from rockscreen.solver.errors import ParameterError
from rockscreen.solver.paper_formulation import parse_formulation

__all__ = [
    "read_amplitudes",
    "read_durations",
    "read_formulations",
    "read_frequencies",
    "read_friction",
]


#: Docstring blocks the group readers share (:func:`rockscreen.solver.docstrings.fill_doc`).
_DOCS = {
    "table_where": """
table : dict
    One ``[[group]]`` table of the study file.
where : str
    The group's place in the file, for messages.
""",
    "config_error": """
ConfigError
    Naming the key, the item and the rule.
""",
}


def _nonempty_list(table: dict, key: str, where: str, example: str) -> list:
    if key not in table:
        raise ConfigError(f"{where}: key {key!r} is required, e.g. {key} = {example}")
    value = table[key]
    if not isinstance(value, list) or not value:
        raise ConfigError(
            f"{where}: key {key!r} = {value!r} must be a non-empty list, e.g. {example}"
        )
    return value


def _positive_item(value, where: str) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float) or not math.isfinite(value):
        raise ConfigError(f"{where}: key 'duration_s' = {value!r} must be a finite number")
    if value <= 0.0:
        raise ConfigError(f"{where}: key 'duration_s' = {float(value)!r} must be > 0")
    return float(value)


@fill_doc(_DOCS)
def read_amplitudes(table: dict, where: str) -> tuple[tuple[str, float], ...]:
    """Return the ``amplitudes`` of a group: texts with their unit (``"0.4g"``), > 0.

    Parameters
    ----------
    %(table_where)s

    Returns
    -------
    tuple of (str, float)
        Each amplitude as written and in m/s^2.

    Raises
    ------
    %(config_error)s
    """
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


@fill_doc(_DOCS)
def read_frequencies(table: dict, where: str) -> tuple[float, ...]:
    """Return the ``frequencies_hz`` of a group: numbers > 0 [Hz].

    Parameters
    ----------
    %(table_where)s

    Returns
    -------
    tuple of float
        The frequencies [Hz].

    Raises
    ------
    %(config_error)s
    """
    out = []
    for item in _nonempty_list(table, "frequencies_hz", where, "[3, 4, 5]"):
        if isinstance(item, bool) or not isinstance(item, int | float) or not item > 0.0:
            raise ConfigError(
                f"{where}: key 'frequencies_hz' item {item!r} must be a number > 0 [Hz]"
            )
        out.append(float(item))
    return tuple(out)


@fill_doc(_DOCS)
def read_durations(table: dict, where: str, *, required: bool) -> tuple[float | None, ...]:
    """Return the ``duration_s`` of a group: one number or a list (a grid dimension) [s].

    Parameters
    ----------
    %(table_where)s
    required : bool
        Whether the key must be given.

    Returns
    -------
    tuple of float or None
        The durations [s], each > 0; ``(None,)`` when absent and not required.

    Raises
    ------
    %(config_error)s
    """
    if "duration_s" not in table:
        if required:
            raise ConfigError(f"{where}: key 'duration_s' is required, e.g. duration_s = 10.0")
        return (None,)
    raw = table["duration_s"]
    items = raw if isinstance(raw, list) else [raw]
    if not items:
        raise ConfigError(f"{where}: key 'duration_s' = [] must not be empty")
    return tuple(_positive_item(v, where) for v in items)


@fill_doc(_DOCS)
def read_friction(table: dict, where: str) -> tuple[tuple[float, float], ...]:
    """Return the ``friction`` pairs ``[mu_s, mu_k]`` of a group (``0 <= mu_k <= mu_s``).

    Parameters
    ----------
    %(table_where)s

    Returns
    -------
    tuple of (float, float)
        The ``(mu_s, mu_k)`` pairs [-].

    Raises
    ------
    %(config_error)s
    """
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


@fill_doc(_DOCS)
def read_formulations(table: dict, model: str, where: str) -> tuple[str, ...]:
    """Return the ``formulation`` of a group: one name or a list (a grid dimension).

    Parameters
    ----------
    table : dict
        One ``[[group]]`` table of the study file.
    model : str
        The group's model; the key is allowed with ``"double-block"`` only.
    where : str
        The group's place in the file, for messages.

    Returns
    -------
    tuple of str
        Texts that :func:`rockscreen.solver.paper_formulation.parse_formulation`
        accepts; ``("consistent",)`` when absent.

    Raises
    ------
    %(config_error)s
    """
    if "formulation" not in table:
        return ("consistent",)
    if not solver_model(model).paper_formulations:
        raise ConfigError(
            f"{where}: key 'formulation' is only allowed with model = 'double-block' "
            f"(model is {model!r})"
        )
    raw = table["formulation"]
    items = raw if isinstance(raw, list) else [raw]
    if not items:
        raise ConfigError(f"{where}: key 'formulation' = [] must not be empty")
    for item in items:
        try:
            parse_formulation(item)
        except ParameterError as exc:
            raise ConfigError(f"{where}: key 'formulation': {exc}") from exc
    return tuple(items)
