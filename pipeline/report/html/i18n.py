"""Every user-facing string of the HTML report, in English and Italian.

One table, :data:`STRINGS` (``assets/strings.json``): key -> {"en": ..., "it": ...}.
Python code and the page's scripts look strings up by key (the page receives the table
of its language as JSON).
Templates use ``str.format`` fields (``{value}``). A key missing from the table is shown
as itself, so raw archive text (column names, notes) passes through unchanged.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

__all__ = ["LANGUAGES", "STRINGS", "table", "tr"]

LANGUAGES = ("en", "it")

_ASSETS = Path(__file__).with_name("assets")
#: key -> {"en": text, "it": text}; kept in ``assets/strings.json`` (long lines, one place).
STRINGS: dict[str, dict[str, str]] = json.loads(
    (_ASSETS / "strings.json").read_text(encoding="utf-8")
)


def tr(key: str, lang: str, **values: Any) -> str:
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
