"""Messages as codes: a code and its parameters, rendered from one catalogue.

Producers never write prose: they return :class:`Message` records (``message("lv1.not_made",
missing="wall_thickness_m")``). The archive stores the code and its parameters; the terminal,
the exports and the HTML report render them in English or Italian from the catalogue
(:data:`CATALOGUE`, filled by the modules of :mod:`rockscreen.pipeline.verdict.catalogue`,
one per subject). A code without both templates, or whose two templates take different
fields, is refused when it is registered, so a page can never fall back to a silent English
clause.

Templates are ``str.format`` strings; a number is written with the language's decimal
separator (a comma in Italian) through the template's own format spec (``{ag:.3f}``).

A parameter may itself be a message, or a tuple of messages: a clause inside a clause (the
source of f_m inside the LV1 model's clause, the notes of a fit after ``"collapse fit: "``).
It is rendered in the same language, a tuple joined by ``"; "`` (:data:`JOIN`) or by the
field's format spec (``{defaults:, }`` joins by ``", "``), and stored as
``{"code": ..., "params": {...}}``. Other parameters are numbers, strings (identifiers:
a tower id, a column name, a masonry type) and tuples of them.
"""

from __future__ import annotations

import json
import math
import numbers
import string
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any

__all__ = [
    "CATALOGUE",
    "DECIMAL",
    "LANGUAGES",
    "Message",
    "MessageSpec",
    "NOTE_COLUMNS",
    "catalogue",
    "dumps",
    "loads",
    "masked",
    "message",
    "note_columns",
    "note_messages",
    "register",
    "render",
    "render_all",
]

#: The languages every message is written in.
LANGUAGES = ("en", "it")
#: Decimal separator per language.
DECIMAL = {"en": ".", "it": ","}
#: Separator of several rendered messages in one text cell (CSV, terminal).
JOIN = "; "
#: A summary row's note: its messages in English (:func:`render_all`) and as codes
#: (:func:`dumps`), from which a report renders it in its own language.
NOTE_COLUMNS = ("note", "note_codes")


@dataclass(frozen=True)
class MessageSpec:
    """One catalogue entry: a code and its templates.

    The fields of both templates must be the same (checked by :func:`register`).
    """

    #: Dotted code, ``<subject>.<what>`` (``"lv1.not_made"``).
    code: str
    #: English template (``str.format``).
    en: str
    #: Italian template, with the same fields.
    it: str

    def fields(self, lang: str = "en") -> frozenset[str]:
        """Return the names of the template's fields."""
        template = self.en if lang == "en" else self.it
        return frozenset(_field_names(template))


def _field_names(template: str) -> set[str]:
    """Return the fields of a template, those nested in a format spec (``{v:.{digits}f}``) too."""
    names = set()
    for _, name, spec, _ in string.Formatter().parse(template):
        if name:
            names.add(name.split(".")[0].split("[")[0])
        if spec and "{" in spec:
            names |= _field_names(spec)
    return names


@dataclass(frozen=True)
class Message:
    """A message: its code and parameters (JSON-able values); text only when rendered."""

    #: A code of :data:`CATALOGUE`.
    code: str
    #: Parameters, sorted by name (hashable, so a message can be a set member).
    params: tuple[tuple[str, Any], ...] = field(default=())

    @property
    def kwargs(self) -> dict[str, Any]:
        """Return the parameters as a dict."""
        return dict(self.params)

    def render(self, lang: str = "en") -> str:
        """Return the message in ``lang`` (:func:`render`)."""
        return render(self, lang)


#: code -> entry; filled by :func:`register` from :mod:`rockscreen.pipeline.verdict.catalogue`.
CATALOGUE: dict[str, MessageSpec] = {}


def register(*specs: MessageSpec) -> None:
    """Add entries to :data:`CATALOGUE`.

    Raises
    ------
    ValueError
        For a code registered twice, an empty template or two templates whose fields differ.
    """
    for spec in specs:
        if spec.code in CATALOGUE and CATALOGUE[spec.code] != spec:
            raise ValueError(f"message code {spec.code!r} registered twice")
        if not spec.en or not spec.it:
            raise ValueError(f"message code {spec.code!r}: both 'en' and 'it' are required")
        if spec.fields("en") != spec.fields("it"):
            raise ValueError(
                f"message code {spec.code!r}: fields differ, en {sorted(spec.fields('en'))}, "
                f"it {sorted(spec.fields('it'))}"
            )
        CATALOGUE[spec.code] = spec


def catalogue() -> dict[str, MessageSpec]:
    """Return the whole catalogue, every subject's module loaded."""
    from rockscreen.pipeline.verdict import catalogue as subjects

    subjects.load()
    return CATALOGUE


def message(code: str, **params: Any) -> Message:
    """Return the message ``code`` with its parameters, checked against the catalogue.

    Raises
    ------
    KeyError
        For a code not in the catalogue.
    TypeError
        For parameters that are not the template's fields.
    """
    spec = catalogue().get(code)
    if spec is None:
        raise KeyError(f"message code {code!r} is not in the catalogue")
    if set(params) != spec.fields():
        raise TypeError(f"message {code!r} takes {sorted(spec.fields())}, got {sorted(params)}")
    return Message(code, tuple(sorted((k, _plain(v)) for k, v in params.items())))


def _plain(value: Any) -> Any:
    """Return a parameter as a plain, hashable value (NumPy numbers as int or float)."""
    if isinstance(value, (Message, str, bool)) or value is None:
        return value
    if isinstance(value, numbers.Integral):
        return int(value)
    if isinstance(value, numbers.Real):
        return float(value)
    if isinstance(value, (list, tuple)):
        return tuple(_plain(v) for v in value)
    raise TypeError(f"message parameter {value!r}: expected a number, a string or a message")


class _Formatter(string.Formatter):
    """Renders a message in one language; its numbers optionally collected or masked."""

    def __init__(self, lang: str, mask: str | None = None) -> None:
        if lang not in DECIMAL:
            raise KeyError(f"language {lang!r}: expected one of {', '.join(LANGUAGES)}")
        self.lang = lang
        self.decimal = DECIMAL[lang]
        self.mask = mask
        #: The numbers as written, in the order of the text.
        self.numbers: list[str] = []

    def text(self, msg: Message) -> str:
        spec = catalogue().get(msg.code)
        if spec is None:
            raise KeyError(f"message code {msg.code!r} is not in the catalogue")
        return self.vformat(spec.en if self.lang == "en" else spec.it, (), msg.kwargs)

    def format_field(self, value: Any, format_spec: str) -> str:
        if isinstance(value, Message):
            return self.text(value)
        if isinstance(value, tuple) and all(isinstance(v, Message) for v in value):
            return (format_spec or JOIN).join(self.text(v) for v in value)
        text = super().format_field(value, format_spec)
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            text = text.replace(".", self.decimal)
            self.numbers.append(text)
            return text if self.mask is None else self.mask
        return text


def render(msg: Message, lang: str = "en") -> str:
    """Return the text of ``msg`` in ``lang`` (``"en"`` or ``"it"``).

    Raises
    ------
    KeyError
        For a code not in the catalogue or a language not in :data:`LANGUAGES`.
    """
    return _Formatter(lang).text(msg)


def masked(msg: Message, lang: str = "en", mask: str = "#") -> tuple[str, list[str]]:
    """Return the text of ``msg`` with its numbers as ``mask``, and those numbers as written.

    What a list of towers reads as one line: the messages whose masked texts are equal say
    the same thing but for their numbers (``"no overturning up to the search cap #"``).

    Raises
    ------
    KeyError
        As :func:`render`.
    """
    formatter = _Formatter(lang, mask)
    return formatter.text(msg), formatter.numbers


def render_all(messages: Iterable[Message], lang: str = "en", sep: str = JOIN) -> str:
    """Return several messages rendered and joined by ``sep`` (``""`` for none)."""
    return sep.join(render(m, lang) for m in messages)


def _jsonable(value: Any) -> Any:
    if isinstance(value, float) and not math.isfinite(value):
        return repr(value)  # "nan", "inf": JSON has no spelling for them
    if isinstance(value, Message):
        return {"code": value.code, "params": {k: _jsonable(v) for k, v in value.params}}
    if isinstance(value, tuple):
        return [_jsonable(v) for v in value]
    return value


def dumps(messages: Iterable[Message]) -> str:
    """Return messages as stored text: a JSON list of ``[code, {params}]``.

    A parameter that is a message is stored as ``{"code": ..., "params": {...}}``.
    """
    return json.dumps(
        [[m.code, {k: _jsonable(v) for k, v in m.params}] for m in messages],
        ensure_ascii=False,
        sort_keys=True,
    )


def loads(text: str | bytes) -> tuple[Message, ...]:
    """Return the messages stored by :func:`dumps`.

    Raises
    ------
    ValueError
        For text that is not such a list, or a code not in the catalogue (a stored archive is
        checked, not trusted).
    """
    if isinstance(text, bytes):
        text = text.decode("utf-8")
    if not text:
        return ()
    try:
        items = json.loads(text)
    except json.JSONDecodeError as exc:
        raise ValueError(f"stored messages are not JSON: {exc.msg}") from None
    if not isinstance(items, list):
        raise ValueError("stored messages: expected a JSON list of [code, {params}]")
    out = []
    for item in items:
        if (
            not isinstance(item, list)
            or len(item) != 2
            or not isinstance(item[0], str)
            or not isinstance(item[1], Mapping)
        ):
            raise ValueError("stored messages: expected a JSON list of [code, {params}]")
        out.append(_restored(*item))
    return tuple(out)


def _restored(code: str, params: Mapping[str, Any]) -> Message:
    """Return a stored message, checked against the catalogue (:func:`loads`)."""
    spec = catalogue().get(code)
    if spec is None:
        raise ValueError(f"stored message code {code!r} is not in this rockscreen's catalogue")
    if set(params) != spec.fields():
        raise ValueError(f"stored message {code!r}: parameters {sorted(params)} do not fit")
    return Message(code, tuple(sorted((k, _value(v)) for k, v in params.items())))


def _value(value: Any) -> Any:
    """Return a stored parameter's value (a nested message restored and checked)."""
    if isinstance(value, str) and value in ("nan", "inf", "-inf"):
        return float(value)
    if isinstance(value, Mapping):
        if set(value) != {"code", "params"} or not isinstance(value["params"], Mapping):
            raise ValueError("stored message parameter: expected {code, params}")
        return _restored(str(value["code"]), value["params"])
    if isinstance(value, list):
        return tuple(_value(v) for v in value)
    return value


def note_columns(messages: Iterable[Message]) -> dict[str, str]:
    """Return a summary row's note columns (:data:`NOTE_COLUMNS`) for ``messages``.

    ``note`` is the messages in English joined by ``"; "`` (the text a CSV or a terminal
    shows), ``note_codes`` the same messages as stored text (:func:`dumps`).
    """
    messages = tuple(messages)
    return {"note": render_all(messages), "note_codes": dumps(messages)}


def note_messages(row: Mapping[str, Any]) -> tuple[Message, ...] | None:
    """Return the messages of a row's ``note_codes``, or None for a row without that column.

    None: a row of an archive written before notes were stored as codes (its ``note`` is
    English text only). An empty column is a row without a note (``()``).

    Raises
    ------
    ValueError
        For stored text that :func:`loads` refuses (a code not in this catalogue).
    """
    codes = row.get("note_codes")
    if codes is None or (isinstance(codes, float) and math.isnan(codes)):
        return None
    return loads(codes)
