"""The page's data: the towers, their classes and their sheets, in the page's language.

:func:`page_data` turns a :class:`~rockscreen.pipeline.report.html.model.ReportModel` into
the JSON the page's scripts read (``<script type="application/json">``, serialised by
:func:`~rockscreen.pipeline.report.html.render.json_for_script`): the towers-table rows and
columns, the classes with their colours, each tower's sheet (inputs, figures, verdict, notes,
checks, sensitivity) written in ``lang``, the stations, the map's extent and surroundings.
"""

from __future__ import annotations

from dataclasses import asdict
from typing import TypedDict

from rockscreen.pipeline.report.basemap import BASEMAP_SOURCE, clipped_lines
from rockscreen.pipeline.report.html.answer import class_text
from rockscreen.pipeline.report.html.i18n import STRINGS, number, table, tr
from rockscreen.pipeline.report.html.model import (
    CheckCell,
    Contour,
    ReportModel,
    Sentence,
    Sheet,
    SheetValue,
    Station,
    TowerCells,
    tower_extent,
)
from rockscreen.pipeline.report.html.notes import note_text, translate_note
from rockscreen.pipeline.report.maps import RISK_COLOURS
from rockscreen.pipeline.report.values import JSONValue
from rockscreen.pipeline.verdict.labels import ClassLabel, marks_of
from rockscreen.pipeline.verdict.messages import Message
from rockscreen.pipeline.verdict.rules import NotMadeText

__all__ = ["OTHER_COLOUR", "TILES", "PageData", "SheetData", "page_data"]

#: Optional background tiles (only when the reader asks for them, and online).
TILES = {
    "url": "https://tile.openstreetmap.org/{z}/{x}/{y}.png",
    "attribution": "© OpenStreetMap contributors (openstreetmap.org/copyright)",
}
#: Colour of a class without its own in :data:`~rockscreen.pipeline.report.maps.RISK_COLOURS`.
OTHER_COLOUR = "#999999"


class SheetData(TypedDict):
    """One tower's sheet as the page's scripts read it, every text in the page's language."""

    #: ``[label, value]`` lines.
    inputs: list[list[str]]
    #: The charts (:class:`~rockscreen.pipeline.report.html.model.Figure` as a dict, titles,
    #: axes and curve labels translated).
    figures: list[dict[str, JSONValue]]
    verdict: list[str]
    notes: list[str]
    #: ``[label, a_C, I_S, details]`` rows.
    checks: list[list[str]]
    risk: list[str]
    #: ``[input, index, index text, narrowing text, judgement]`` bars.
    sensitivity: list[list[str | float | bool | None]]
    checks_text: list[str]


class PageData(TypedDict):
    """The data the page's scripts read (:func:`page_data`)."""

    lang: str
    kind: str
    #: The translation table in the page's language.
    strings: dict[str, str]
    #: The towers table's columns (:class:`~rockscreen.pipeline.report.html.model.Column`
    #: as a dict, the label translated).
    columns: list[dict[str, str | int]]
    #: The towers' rows: column key -> value (``bounds``: column key -> sign).
    towers: list[dict[str, JSONValue]]
    #: ``{"key", "label", "colour"}`` per class, in legend order.
    classes: list[dict[str, str]]
    sheets: dict[str, SheetData]
    stations: list[Station]
    contours: list[Contour]
    #: Shared input motions (:class:`~rockscreen.pipeline.report.html.model.Series` as a dict).
    motions: dict[str, dict[str, str | float]]
    tiles: dict[str, str]
    #: ``[lon_min, lat_min, lon_max, lat_max]`` [deg]; None: nothing to fit.
    extent: list[float] | None
    #: Coastlines and borders around the extent: lines of ``[lon, lat]`` [deg].
    basemap: list[list[list[float]]]
    basemap_source: str


def _translate_value(value: SheetValue, lang: str) -> str:
    """Write a sheet value: a number, a translation key, a message or text.

    A number is a dict with ``num``; a translation key a dict with ``key`` (and ``raw``); a
    message (:class:`~rockscreen.pipeline.verdict.messages.Message`,
    :class:`~rockscreen.pipeline.verdict.rules.NotMadeText`) is rendered from the catalogue.
    """
    if isinstance(value, (Message, NotMadeText)):
        return value.render(lang)
    if isinstance(value, dict) and "num" in value:
        return number(
            value["num"],
            lang,
            value.get("digits", 3),
            value.get("unit", ""),
            value.get("bound", ""),
            bool(value.get("relation")),
        )
    if isinstance(value, dict):
        key = value.get("key", "")
        if isinstance(value.get("raw"), ClassLabel):  # a class with its typed marks
            return class_text(value["raw"], lang)
        return tr(key, lang) if key in STRINGS else str(value.get("raw", key))
    return str(value)


def _detail(detail: CheckCell, lang: str) -> str:
    """Write a check's details: text, a value, or (translation key, values) filled in ``lang``."""
    if isinstance(detail, str):
        return detail
    if isinstance(detail, tuple):
        key, values = detail
        return tr(key, lang, **{name: _translate_value(v, lang) for name, v in values.items()})
    return _translate_value(detail, lang)


def _verdict(lines: list[Sentence], lang: str) -> list[str]:
    return [
        tr(key, lang, **{name: _translate_value(v, lang) for name, v in values.items()})
        for key, values in lines
    ]


def _tower(tower: TowerCells, lang: str) -> dict[str, JSONValue]:
    """Return a towers-table row for the page: its note in ``lang``, its codes dropped."""
    out: dict[str, JSONValue] = {
        k: v.render(lang) if isinstance(v, Message) else v
        for k, v in tower.items()
        if k != "note_codes"
    }
    if tower.get("note") or tower.get("note_codes"):
        out["note"] = note_text(tower.get("note", ""), tower.get("note_codes"), lang)
    return out


def _classes(model: ReportModel, lang: str) -> list[dict[str, str]]:
    names = list(model.classes)
    names += sorted({t["risk_class"] for t in model.towers} - set(names))
    out = []
    for name in names:
        label = class_text(name, lang)
        # a marked class keeps its colour (its typed marks, never its text)
        colour = RISK_COLOURS.get(marks_of(name).counted, OTHER_COLOUR)
        out.append({"key": name, "label": label, "colour": colour})
    return out


def _sheet(sheet: Sheet, lang: str) -> SheetData:
    """Return one tower's sheet for the page, every text in ``lang``.

    Its inputs, figures (titles, axes and curve labels translated), verdict, notes, checks
    (with the sentences under them), screening risk and sensitivity.
    """
    figures = []
    for figure in sheet.figures:
        item = asdict(figure)
        for key in ("title", "xlabel", "ylabel"):
            item[key] = tr(item[key], lang)
        for curve in item["curves"]:
            values = curve.pop("values")
            fields = {name: _translate_value(v, lang) for name, v in values.items()}
            curve["label"] = tr(curve["label"], lang, **fields)
        figures.append(item)
    return {
        "inputs": [
            [tr(label, lang), _translate_value(value, lang)] for label, value in sheet.inputs
        ],
        "figures": figures,
        "verdict": _verdict(sheet.verdict, lang),
        "notes": [note_text(note.text, note.codes, lang) for note in sheet.notes],
        "checks": [
            [
                tr(label, lang) if isinstance(label, str) else label.render(lang),
                _translate_value(ac, lang),
                _translate_value(si, lang),
                _detail(detail, lang),
            ]
            for label, ac, si, detail in sheet.checks
        ],
        "risk": _verdict(sheet.risk, lang),
        "sensitivity": [
            [
                tr(key, lang) if key in STRINGS else key.removeprefix("inp_"),
                index,
                number(index, lang, 2),
                "-" if narrowing is None else f"{number(100 * narrowing, lang, 2)} %",
                judgement,
            ]
            for key, index, narrowing, judgement in sheet.sensitivity
        ],
        "checks_text": [
            tr(
                key,
                lang,
                **{
                    name: translate_note(v, lang)
                    if isinstance(v, str)
                    else _translate_value(v, lang)
                    for name, v in values.items()
                },
            )
            for key, values in sheet.checks_text
        ],
    }


def page_data(model: ReportModel, lang: str) -> PageData:
    """Return the data the page's scripts read, every text in ``lang``.

    Parameters
    ----------
    model : ReportModel
        What to show (from an adapter).
    lang : str
        ``"en"`` or ``"it"``.

    Returns
    -------
    PageData
        The language and the kind, the translation table, the towers' columns and rows,
        the classes (key, label, colour), the sheets by tower id, the stations, contours
        and motions, the tiles, the map's extent [deg] and its coastlines and borders.
    """
    sheets = {tower_id: _sheet(sheet, lang) for tower_id, sheet in model.sheets.items()}
    columns = [{**asdict(column), "label": tr(column.label, lang)} for column in model.columns]
    extent = tower_extent(
        model.towers,
        [(s["lon"], s["lat"]) for s in model.stations if s["lat"] is not None],
    )
    return {
        "lang": lang,
        "kind": model.kind,
        "strings": table(lang),
        "columns": columns,
        "towers": [_tower(t, lang) for t in model.towers],
        "classes": _classes(model, lang),
        "sheets": sheets,
        "stations": model.stations,
        "contours": model.contours,
        "motions": {key: asdict(series) for key, series in model.motions.items()},
        "tiles": TILES,
        "extent": extent,
        "basemap": _basemap(extent),
        "basemap_source": BASEMAP_SOURCE,
    }


def _basemap(extent: list[float] | None) -> list[list[list[float]]]:
    """Return the coastlines and borders of the map's surroundings [deg].

    The initial extent widened by twice its span, at least 1° each way, so that panning
    and zooming out keep the context.
    """
    if extent is None:
        return []
    x0, y0, x1, y1 = extent
    pad_x, pad_y = max(2 * (x1 - x0), 1.0), max(2 * (y1 - y0), 1.0)
    return clipped_lines((x0 - pad_x, x1 + pad_x, y0 - pad_y, y1 + pad_y))
