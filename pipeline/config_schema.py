"""Checking and documenting configuration values against the key table.

Each :class:`pipeline.config_keys.Key` of :data:`pipeline.config_keys.KEYS` names its
table, its TOML type, its default, its bounds or allowed values and a sentence of
documentation. :func:`check_value` checks a value read from a file against its key (type
first, then finiteness, bounds and allowed values) and raises
:class:`rockscreen.pipeline.errors.ConfigError` with one line naming the file, the section, the key,
the value found and what was expected, e.g.::

    rockscreen.toml: [processing] baseline_correction = "false": expected a boolean
    (true or false), got a string

:func:`key_table_markdown` writes the key table of docs/campaign.md from the same specs
(a test checks that the documentation matches).
"""

from __future__ import annotations

import datetime
import json
import math
import sys
from typing import Any

from rockscreen.pipeline.config_keys import HISTORY_MODES, KEYS, TABLES, Key, keys_of, spec_for
from rockscreen.pipeline.errors import ConfigError

# The TOML parser every reader of rockscreen uses: configurations, study files, the
# configuration stored in archives (a light module: readers need not import the config).
if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover - Python 3.10
    import tomli as tomllib

__all__ = [
    "tomllib",
    "HISTORY_MODES",
    "KEYS",
    "TABLES",
    "Key",
    "check_value",
    "fail",
    "key_table_markdown",
    "keys_of",
    "spec_for",
    "toml_text",
    "toml_type",
]

_TYPE_TEXT = {
    "bool": "a boolean (true or false)",
    "int": "an integer",
    "float": "a number",
    "path": "a path (a string)",
    "choice": "a string",
    "choices": "an array of strings",
}
_DOC_TYPE = {
    "bool": "boolean",
    "int": "integer",
    "float": "number",
    "path": "string (path)",
    "choice": "string",
    "choices": "array of strings",
}


#: The Python types a TOML parser returns, in words; ``bool`` before ``int`` (a bool is an int).
_TOML_TYPES: tuple[tuple[Any, str], ...] = (
    (bool, "a boolean"),
    (int, "an integer"),
    (float, "a float"),
    (str, "a string"),
    (list, "an array"),
    (dict, "a table"),
    (datetime.date | datetime.time, "a date/time"),
)


def toml_type(value: Any) -> str:
    """Return the TOML type of a parsed value in words (``"a string"``, ``"a table"``)."""
    for python_type, words in _TOML_TYPES:
        if isinstance(value, python_type):
            return words
    return f"a {type(value).__name__}"  # pragma: no cover - TOML has no other types


def toml_text(value: Any) -> str:
    """Return ``value`` written as TOML (for messages; never raises)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        return json.dumps(value, ensure_ascii=False)
    if isinstance(value, list | tuple):
        return "[" + ", ".join(toml_text(v) for v in value) + "]"
    if isinstance(value, dict):
        return "{" + ", ".join(f"{k} = {toml_text(v)}" for k, v in value.items()) + "}"
    if isinstance(value, datetime.date | datetime.time):
        return value.isoformat()
    return repr(value)  # pragma: no cover - TOML has no other types


def fail(source: str, where: str, value: Any, problem: str) -> ConfigError:
    """Return the one-line error ``source: where = value: problem``."""
    return ConfigError(f"{source}: {where} = {toml_text(value)}: {problem}")


def _type_error(key: Key, value: Any, source: str, expected: str = "") -> ConfigError:
    expected = expected or _TYPE_TEXT[key.kind]
    # A number key says so in Python words too (integers are accepted for floats).
    tail = f" ({key.name} must be of type float)" if key.kind == "float" else ""
    return fail(source, key.where, value, f"expected {expected}, got {toml_type(value)}{tail}")


def _check_number(key: Key, value: Any, source: str) -> Any:
    if key.kind == "int":
        if not isinstance(value, int) or isinstance(value, bool):
            raise _type_error(key, value, source)
    elif not isinstance(value, int | float) or isinstance(value, bool):
        raise _type_error(key, value, source)
    else:
        value = float(value)
        if not math.isfinite(value):
            raise fail(
                source, key.where, value, f"must be a finite number {key.bounds_text()}".rstrip()
            )
    too_low = key.low is not None and (value <= key.low if key.low_open else value < key.low)
    too_high = key.high is not None and (value >= key.high if key.high_open else value > key.high)
    if too_low or too_high:
        raise fail(source, key.where, value, f"must be {key.bounds_text()}")
    return value


def _check_choices(key: Key, value: Any, source: str) -> tuple[str, ...]:
    expected = f"an array of strings from {key.allowed_text()}"
    if not isinstance(value, list | tuple):
        raise _type_error(key, value, source, expected)
    for item in value:
        if not isinstance(item, str):
            raise fail(
                source,
                key.where,
                value,
                f"expected {expected}, got an array holding {toml_type(item)} ({toml_text(item)})",
            )
    if not value:
        raise fail(source, key.where, value, "must name at least one model (an empty array)")
    unknown = [item for item in value if item not in key.choices]
    if unknown:
        raise fail(
            source,
            key.where,
            value,
            f"may only name {', '.join(key.choices)} (got {toml_text(unknown[0])})",
        )
    if len(set(value)) != len(value):
        raise fail(source, key.where, value, "names a model twice")
    return tuple(value)


def check_value(key: Key, value: Any, source: str) -> Any:
    """Check one value against its key and return it (ints become floats for numbers).

    Parameters
    ----------
    key : Key
        The specification.
    value : object
        The parsed TOML value.
    source : str
        The configuration file, for messages.

    Returns
    -------
    object
        The value, with the Python type of the default (a tuple for arrays).

    Raises
    ------
    ConfigError
        One line: file, section, key, value found, and the expected type or rule.
    """
    if value is None and key.optional:
        return None
    if key.kind == "bool":
        if not isinstance(value, bool):
            raise _type_error(key, value, source)
        return value
    if key.kind in ("int", "float"):
        return _check_number(key, value, source)
    if key.kind == "choices":
        return _check_choices(key, value, source)
    if not isinstance(value, str):
        expected = _TYPE_TEXT[key.kind]
        if key.kind == "choice":
            expected = f"a string, one of {key.allowed_text()}"
        raise _type_error(key, value, source, expected)
    if key.kind == "choice" and value not in key.choices:
        raise fail(
            source,
            key.where,
            value,
            f"must be one of {key.allowed_text()} (got {key.name}={value!r})",
        )
    return value


def _doc_default(key: Key) -> str:
    if key.default is None:
        return "absent (off)"
    return f"`{toml_text(key.default)}`"


def key_table_markdown() -> str:
    """Return the Markdown table of every key (docs/campaign.md holds it verbatim)."""
    lines = [
        "| key | type | default | allowed | meaning |",
        "|---|---|---|---|---|",
    ]
    for key in KEYS:
        allowed = key.allowed_text() or "any"
        if key.kind == "choices":
            allowed = f"non-empty, distinct, from {allowed}"
        lines.append(
            f"| `{key.where}` | {_DOC_TYPE[key.kind]} | {_doc_default(key)} | {allowed} "
            f"| {key.doc} |"
        )
    return "\n".join(lines) + "\n"
