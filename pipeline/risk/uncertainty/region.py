"""A region's priors file: TOML replacing the default priors where the inventory is silent.

Four optional tables, each either a distribution or a fixed ``value``, each with its
``source`` (required: a prior without its source is refused) and ``judgement`` (optional,
default false; true labels the prior a judgement wherever it is shown)::

    region = "Diocese of Carpi"          # optional, a name for the output

    [wall_ratio]                         # base wall / smaller plan side
    median = 0.25                        # (0, 0.5]
    log_std = 0.30                       # (0, 2]
    source = "survey of 40 towers of the diocese, 2015"

    [taper]                              # top / base wall
    prismatic_share = 0.2                # [0, 1]
    beta_a = 1.8                         # (0, 100]
    beta_b = 1.1                         # (0, 100]
    source = "TURRIS"

    [masonry]                            # masonry type
    weights = { solid_brick = 0.8, rubble = 0.2 }   # Table C8.5.I keys, > 0, sum 1
    source = "Po valley: brick towers"
    judgement = true

    [period_ratio]                       # T1 / (0.0187 H)
    median = 0.95                        # [0.2, 5]
    log_std = 0.45                       # (0, 2]
    source = "TURRIS"

A fifth table, ``[belfry]``, sets the belfry the screening risk samples for a row without
the belfry columns (``docs/uncertainty.md`` "Belfry priors"; sampled by default)::

    [belfry]
    sampled = false                      # no belfry sampled (default true)
    # or: its presence for a region mixing civic towers
    presence = 0.65                      # [0, 1]
    source = "TURRIS: 71 of 109 Italian towers named a bell tower or a church's"
    judgement = true

A fixed value instead of a distribution: ``value = 1.0`` in ``[taper]`` (prismatic shafts),
``value = "solid_brick"`` in ``[masonry]``, ``value = 0.2`` in ``[wall_ratio]`` or
``[period_ratio]``. Any other table or key, or a value outside its range, is refused with a
:class:`~rockscreen.pipeline.errors.ConfigError` naming the file, the key and what is
allowed.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path
from typing import Any

from rockscreen.pipeline.errors import ConfigError
from rockscreen.pipeline.risk.checks.confidence import MASONRY_TYPES
from rockscreen.pipeline.risk.uncertainty.belfry import BelfryPriors
from rockscreen.pipeline.risk.uncertainty.distributions import Categorical, LogNormal, Point, Taper
from rockscreen.pipeline.risk.uncertainty.priors import WALL_RATIO_MAX, RegionPriors

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

__all__ = ["BELFRY_TABLE", "BELFRY_TABLE_KEYS", "PRIOR_TABLES", "read_region_priors"]

#: The priors file's table of the sampled belfry (a table name, not the part model's).
BELFRY_TABLE = "belfry"
#: Table -> its distribution's keys -> (low, high, low_open) of the allowed range.
PRIOR_TABLES: dict[str, dict[str, tuple[float, float, bool]]] = {
    "wall_ratio": {"median": (0.0, WALL_RATIO_MAX, True), "log_std": (0.0, 2.0, True)},
    "taper": {
        "prismatic_share": (0.0, 1.0, False),
        "beta_a": (0.0, 100.0, True),
        "beta_b": (0.0, 100.0, True),
    },
    "masonry": {},
    "period_ratio": {"median": (0.2, 5.0, False), "log_std": (0.0, 2.0, True)},
}
#: The range of a fixed ``value`` per table (masonry: a Table C8.5.I key).
_VALUE_RANGES = {
    "wall_ratio": (0.0, WALL_RATIO_MAX, True),
    "taper": (0.0, 1.0, True),
    "period_ratio": (0.2, 5.0, False),
}
_COMMON = ("source", "judgement", "value")
#: The keys of the ``[belfry]`` table (module docstring).
BELFRY_TABLE_KEYS = ("sampled", "presence", "source", "judgement")


def _fail(path: Path, key: str, problem: str, allowed: str) -> None:
    raise ConfigError(f"{path}: {key} {problem}; allowed: {allowed}")


def _number(path: Path, key: str, value: Any, low: float, high: float, low_open: bool) -> float:
    allowed = f"a number in {'(' if low_open else '['}{low:g}, {high:g}]"
    if isinstance(value, bool) or not isinstance(value, int | float):
        _fail(path, key, f"= {value!r} is not a number", allowed)
    value = float(value)
    if not math.isfinite(value) or value > high or value < low or (low_open and value == low):
        _fail(path, key, f"= {value!r} is out of range", allowed)
    return value


def _table(path: Path, name: str, table: Any) -> Any:
    if not isinstance(table, dict):
        _fail(path, name, "is not a table", f"a [{name}] table")
    dist = PRIOR_TABLES[name]
    keys = (*dist, "weights") if name == "masonry" else tuple(dist)
    allowed_keys = ", ".join((*keys, *_COMMON))
    for key in table:
        if key not in (*keys, *_COMMON):
            _fail(path, f"[{name}] {key}", "is not a key of this table", allowed_keys)
    source = table.get("source")
    if not isinstance(source, str) or not source.strip():
        _fail(path, f"[{name}] source", "is missing or empty", "a text naming the source")
    judgement = table.get("judgement", False)
    if not isinstance(judgement, bool):
        _fail(path, f"[{name}] judgement", f"= {judgement!r} is not a boolean", "true, false")
    given = [k for k in keys if k in table]
    if "value" in table:
        if given:
            _fail(path, f"[{name}] value", f"is given with {', '.join(given)}", "one or the other")
        value = table["value"]
        if name == "masonry":
            if value not in MASONRY_TYPES:
                _fail(path, f"[{name}] value", f"= {value!r} is unknown", ", ".join(MASONRY_TYPES))
        else:
            value = _number(path, f"[{name}] value", value, *_VALUE_RANGES[name])
        return Point(value, source, judgement)
    if name == "masonry":
        return _weights(path, table.get("weights"), source, judgement)
    missing = [k for k in keys if k not in table]
    if missing:
        _fail(path, f"[{name}] {', '.join(missing)}", "is missing", allowed_keys)
    v = {k: _number(path, f"[{name}] {k}", table[k], *dist[k]) for k in keys}
    if name == "taper":
        return Taper(v["prismatic_share"], v["beta_a"], v["beta_b"], source, judgement)
    upper = WALL_RATIO_MAX if name == "wall_ratio" else None
    return LogNormal(v["median"], v["log_std"], source, judgement, upper=upper)


def _weights(path: Path, weights: Any, source: str, judgement: bool) -> Categorical:
    key = "[masonry] weights"
    if not isinstance(weights, dict) or not weights:
        _fail(path, key, "is missing or not a table", "{ type = probability, ... }")
    for kind, w in weights.items():
        if kind not in MASONRY_TYPES:
            _fail(path, f"{key}.{kind}", "is not a masonry type", ", ".join(MASONRY_TYPES))
        _number(path, f"{key}.{kind}", w, 0.0, 1.0, True)
    total = sum(float(w) for w in weights.values())
    if abs(total - 1.0) > 1e-6:
        _fail(path, key, f"sum to {total:g}", "probabilities summing to 1")
    return Categorical(tuple(weights.items()), source, judgement)


def read_region_priors(path: str | Path) -> RegionPriors:
    """Return the priors of a region from its TOML file (module docstring).

    Parameters
    ----------
    path : str or Path
        The priors file.

    Returns
    -------
    RegionPriors
        The file's tables; the defaults for the tables it does not have.

    Raises
    ------
    ConfigError
        For an unreadable file, an unknown table or key, a missing ``source`` or
        distribution key, or a value outside its range: one line naming the file, the key
        and what is allowed.
    """
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise ConfigError(f"{path}: cannot read the priors file ({exc.strerror})") from exc
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"{path}: not valid TOML ({exc})") from exc
    allowed = ", ".join(("region", *PRIOR_TABLES, BELFRY_TABLE))
    values: dict[str, Any] = {}
    for key, table in data.items():
        if key == "region":
            if not isinstance(table, str):
                _fail(path, "region", f"= {table!r} is not a text", "a name")
            continue
        if key == BELFRY_TABLE:
            values["belfry"] = _belfry(path, table)
            continue
        if key not in PRIOR_TABLES:
            _fail(path, key, "is not a table of a priors file", allowed)
        values[key] = _table(path, key, table)
    return RegionPriors(**values, path=str(path))


def _belfry(path: Path, table: Any) -> BelfryPriors | None:
    """Return the ``[belfry]`` table's priors: None for ``sampled = false``."""
    if not isinstance(table, dict):
        _fail(path, "belfry", "is not a table", "a [belfry] table")
    for key in table:
        if key not in BELFRY_TABLE_KEYS:
            _fail(
                path, f"[belfry] {key}", "is not a key of this table", ", ".join(BELFRY_TABLE_KEYS)
            )
    sampled = table.get("sampled", True)
    if not isinstance(sampled, bool):
        _fail(path, "[belfry] sampled", f"= {sampled!r} is not a boolean", "true, false")
    judgement = table.get("judgement", False)
    if not isinstance(judgement, bool):
        _fail(path, "[belfry] judgement", f"= {judgement!r} is not a boolean", "true, false")
    if not sampled:
        if "presence" in table:
            _fail(path, "[belfry] presence", "is given with sampled = false", "one or the other")
        return None
    if "presence" not in table:
        return BelfryPriors()
    presence = _number(path, "[belfry] presence", table["presence"], 0.0, 1.0, False)
    source = table.get("source")
    if not isinstance(source, str) or not source.strip():
        _fail(path, "[belfry] source", "is missing or empty", "a text naming the source")
    return BelfryPriors(presence=presence, presence_source=source, presence_judgement=judgement)
