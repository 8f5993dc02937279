"""Every user-facing string of the HTML report, in English and Italian.

One table, :data:`STRINGS` (``assets/strings.json``): key -> {"en": ..., "it": ...}.
Python code and the page's scripts look strings up by key (the page receives the table
of its language as JSON).
Templates use ``str.format`` fields (``{value}``). A key missing from the table is shown
as itself, so raw archive text (column names, notes) passes through unchanged.

Plural forms: a counted sentence has two keys, ``<key>_one`` (n = 1) and ``<key>_other``
(every other n, zero included: "0 torri", "0 towers"), chosen by :func:`trn`. Numbers are
written by :func:`number` with the language's decimal separator (:data:`DECIMAL`: a comma
in Italian) and, for a bound, its sign (``> 0.254 g``).
"""

from __future__ import annotations

import json
import math
from collections.abc import Iterator, Mapping
from pathlib import Path

from rockscreen.pipeline.engine.registry import models

__all__ = ["DECIMAL", "LANGUAGES", "STRINGS", "number", "table", "tr", "trn"]

LANGUAGES = ("en", "it")
#: Decimal separator per language.
DECIMAL = {"en": ".", "it": ","}
#: The screening risk's bound signs (``at_most``, ``at_least``) as written.
_AT = {"<=": "≤", ">=": "≥"}

_ASSETS = Path(__file__).with_name("assets")
_FIXED: dict[str, dict[str, str]] = json.loads(
    (_ASSETS / "strings.json").read_text(encoding="utf-8")
)


class _Strings(Mapping[str, dict[str, str]]):
    """The translation table: ``assets/strings.json`` and one entry per registered model.

    ``model_<name>`` for every model of the registry, from its own labels, read on each use
    (a new model, a plugin's too, brings its translation with it:
    :class:`rockscreen.pipeline.engine.registry.TowerModel`).
    """

    def _models(self) -> dict[str, dict[str, str]]:
        return {
            f"model_{model.name}": {"en": model.label, "it": model.label_it or model.label}
            for model in models()
        }

    def __getitem__(self, key: str) -> dict[str, str]:
        if key in _FIXED:
            return _FIXED[key]
        return self._models()[key]

    def __iter__(self) -> Iterator[str]:
        return iter({**_FIXED, **self._models()})

    def __len__(self) -> int:
        return len({**_FIXED, **self._models()})


#: key -> {"en": text, "it": text}: ``assets/strings.json`` (long lines, one place), plus
#: ``model_<name>`` for every registered model (:class:`_Strings`).
STRINGS: Mapping[str, dict[str, str]] = _Strings()


def tr(key: str, lang: str, **values: object) -> str:
    """Translate ``key`` into ``lang`` and fill its fields.

    Parameters
    ----------
    key : str
        Key of :data:`STRINGS`; an unknown key is returned as itself (raw text).
    lang : str
        ``"en"`` or ``"it"``.
    **values
        Fields of the template.

    Returns
    -------
    str
        The text (raw: escape it before putting it into HTML).
    """
    entry = STRINGS.get(key)
    if entry is None:
        return key
    text = entry.get(lang, entry["en"])
    return text.format(**values) if values else text


def table(lang: str) -> dict[str, str]:
    """Return the whole table in one language (embedded in the page for its scripts)."""
    return {key: entry.get(lang, entry["en"]) for key, entry in STRINGS.items()}


def trn(key: str, n: int, lang: str, **values: object) -> str:
    """Translate the counted sentence ``key`` for ``n`` items (``{n}`` is filled too).

    Parameters
    ----------
    key : str
        Stem of the keys ``<key>_one`` and ``<key>_other`` in :data:`STRINGS`.
    n : int
        The count that decides the form (1: singular; any other, zero included: plural).
    lang : str
        ``"en"`` or ``"it"``.
    **values
        Further fields of the template.

    Returns
    -------
    str
        The text (raw).
    """
    return tr(f"{key}_one" if n == 1 else f"{key}_other", lang, n=n, **values)


def number(
    value: object,
    lang: str = "en",
    digits: int = 3,
    unit: str = "",
    bound: str = "",
    relation: bool = False,
) -> str:
    """Write a number with ``digits`` significant digits, its unit and bound, in ``lang``.

    Parameters
    ----------
    value : object
        The number (or its text); None, NaN or a non-number give ``"-"``; ``"inf"`` or
        infinity ``"∞"``.
    lang : str
        ``"en"`` (decimal point) or ``"it"`` (decimal comma).
    digits : int
        Significant digits.
    unit : str
        Unit appended after a space (``"g"``, ``"1/y"``); ``""`` for none.
    bound : str
        ``">"`` (a lower bound: the value is at least this), ``"<"`` (an upper bound),
        ``">="`` / ``"<="`` (the screening risk's ``at_least`` / ``at_most``: written ``≥`` /
        ``≤``) or ``""``.
    relation : bool
        Write ``"= "`` before a value that is not a bound (``a_C = 0.3 g``, ``a_C > 0.3 g``).

    Returns
    -------
    str
        E.g. ``"> 0.254 g"``, ``"0,254 g"`` in Italian, ``"2.1e-05 1/y"``, ``"600"`` (not
        ``"6e+02"``; exponents only from a million).
    """
    if value == "inf":
        value = math.inf
    try:
        x = float(value)  # type: ignore[arg-type]  # what float() refuses: "-"
    except (TypeError, ValueError):
        return "-"
    if math.isnan(x):
        return "-"
    if math.isinf(x):
        text = "∞" if x > 0 else "-∞"
    else:
        text = f"{x:.{digits}g}"
        if "e+" in text and abs(x) < 1e6:  # 6e+02 reads as 600: plain up to a million
            text = f"{float(text):.0f}"
        text = text.replace(".", DECIMAL.get(lang, "."))
    if bound in {">", "<"}:
        text = f"{bound} {text}"
    elif bound in _AT:
        text = f"{_AT[bound]} {text}"
    elif relation and text != "-":
        text = f"= {text}"
    return f"{text} {unit}".strip()
