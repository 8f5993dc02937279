"""Render a :class:`ReportModel` into one self-contained HTML page.

Everything is inline: the styles, the scripts (``assets/*.js``, vanilla JavaScript, no
library), the data (one ``<script type="application/json">`` block) and the method text.
No request leaves the page unless the reader ticks the background-map box (then map
tiles are fetched from :data:`TILES`). Every text from the archive is escaped with
:func:`html.escape` in the static part and set through ``textContent`` by the scripts;
the JSON block escapes ``<``, ``>`` and ``&`` so no archive text can close the script.
"""

from __future__ import annotations

import datetime as _dt
import html
import json
import math
import re
from dataclasses import asdict
from pathlib import Path
from typing import Any

from rockscreen.pipeline import __version__
from rockscreen.pipeline.errors import ReportError
from rockscreen.pipeline.report.areas import area_columns, area_counts
from rockscreen.pipeline.report.basemap import BASEMAP_SOURCE, clipped_lines
from rockscreen.pipeline.report.html.answer import answer_lines, class_counts, class_text
from rockscreen.pipeline.report.html.i18n import LANGUAGES, STRINGS, number, table, tr
from rockscreen.pipeline.report.html.model import (
    HeaderItem,
    MethodParagraph,
    ModelNames,
    ReportModel,
    tower_extent,
)
from rockscreen.pipeline.report.html.notes import note_text, translate_note
from rockscreen.pipeline.report.html.reduce import HISTORY_BINS
from rockscreen.pipeline.report.maps import RISK_COLOURS
from rockscreen.pipeline.verdict.checks import check_label
from rockscreen.pipeline.verdict.labels import ClassLabel, marks_of
from rockscreen.pipeline.verdict.messages import Message, message
from rockscreen.pipeline.verdict.rules import NotMadeText

__all__ = ["SCRIPTS", "TILES", "json_for_script", "render_html"]

ASSETS = Path(__file__).with_name("assets")
#: Scripts inlined in this order.
SCRIPTS = ("chart.js", "map.js", "report.js")
#: Optional background tiles (only when the reader asks for them, and online).
TILES = {
    "url": "https://tile.openstreetmap.org/{z}/{x}/{y}.png",
    "attribution": "© OpenStreetMap contributors (openstreetmap.org/copyright)",
}
_OTHER_COLOUR = "#999999"
_UNSAFE_IN_SCRIPT = re.compile(r"</script|<!--", re.IGNORECASE)


def json_for_script(data: Any) -> str:
    r"""Serialise ``data`` as JSON that is safe inside an HTML ``<script>`` element.

    ``<``, ``>`` and ``&`` become ``\\u003c``, ``\\u003e``, ``\\u0026`` (so neither
    ``</script>`` nor ``<!--`` can appear); U+2028 and U+2029 are escaped as well.
    NaN and infinity are refused (the model stores None or ``"inf"``).
    """
    text = json.dumps(data, ensure_ascii=False, separators=(",", ":"), allow_nan=False)
    for char, code in (("<", "\\u003c"), (">", "\\u003e"), ("&", "\\u0026")):
        text = text.replace(char, code)
    return text.replace("\u2028", "\\u2028").replace("\u2029", "\\u2029")


def _asset(name: str) -> str:
    text = (ASSETS / name).read_text(encoding="utf-8")
    if name.endswith(".js") and _UNSAFE_IN_SCRIPT.search(text):
        raise ReportError(f"report asset {name} contains '</script' or '<!--' (cannot be inlined)")
    return text


def _method(kind: str, lang: str) -> str:
    """Return the blocks of ``assets/method.<lang>.html`` marked for ``kind`` (trusted HTML)."""
    text = _asset(f"method.{lang}.html")
    blocks = re.split(r"<!-- for: ([a-z ]+) -->\n", text)
    wanted = "risk" if kind in {"assess", "scenario"} else kind
    return "".join(
        body for marks, body in zip(blocks[1::2], blocks[2::2], strict=True) if wanted in marks
    )


def _method_text(paragraphs: list[MethodParagraph], lang: str) -> str:
    """Return the method section built from an archive: catalogue sentences in ``lang``.

    A :class:`ModelNames` parameter is written with the registry's labels in ``lang``.
    """
    e = html.escape
    out = []
    for paragraph in paragraphs:
        sentences = []
        for code, params in paragraph.sentences:
            values = {
                name: ", ".join(tr(f"model_{m}", lang) for m in value.names)
                if isinstance(value, ModelNames)
                else value
                for name, value in params.items()
            }
            text = message(code, **values).render(lang)
            sentences.append(text[:1].upper() + text[1:])  # a label may open the sentence
        heading = message(paragraph.heading).render(lang)
        out.append(
            f'<p data-method="{e(paragraph.heading)}"><strong>{e(heading)}</strong> '
            f"{e(' '.join(sentences))}</p>"
        )
    return "".join(out)


def _translate_value(value: Any, lang: str) -> str:
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


def _detail(detail: Any, lang: str) -> str:
    """Write a check's details: text, a value, or (translation key, values) filled in ``lang``."""
    if isinstance(detail, str):
        return detail
    if isinstance(detail, tuple):
        key, values = detail
        return tr(key, lang, **{name: _translate_value(v, lang) for name, v in values.items()})
    return _translate_value(detail, lang)


def _verdict(lines: list[tuple[str, dict[str, Any]]], lang: str) -> list[str]:
    return [
        tr(key, lang, **{name: _translate_value(v, lang) for name, v in values.items()})
        for key, values in lines
    ]


def _tower(tower: dict[str, Any], lang: str) -> dict[str, Any]:
    """Return a towers-table row for the page: its note in ``lang``, its codes dropped."""
    out = {
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
        colour = RISK_COLOURS.get(marks_of(name).counted, _OTHER_COLOUR)
        out.append({"key": name, "label": label, "colour": colour})
    return out


def _page_data(model: ReportModel, lang: str) -> dict[str, Any]:
    sheets = {}
    for tower_id, sheet in model.sheets.items():
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
        sheets[tower_id] = {
            "inputs": [
                [tr(label, lang), _translate_value(value, lang)] for label, value in sheet.inputs
            ],
            "figures": figures,
            "verdict": _verdict(sheet.verdict, lang),
            "notes": [note_text(note.text, note.codes, lang) for note in sheet.notes],
            "checks": [
                [
                    tr(label, lang),
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


def _items(items: list[HeaderItem], lang: str) -> str:
    rows = []
    for item in items:
        value = tr(item.value, lang) if item.translate else item.value
        title = f' title="{html.escape(item.title)}"' if item.title else ""
        rows.append(
            f"<dt>{html.escape(tr(item.label, lang))}</dt><dd{title}>{html.escape(value)}</dd>"
        )
    return '<dl class="kv">' + "".join(rows) + "</dl>"


def _answer(model: ReportModel, lang: str) -> str:
    """Return the page's first section: the answer sentences and the towers per class."""
    e = html.escape
    lines = "".join(f"<p>{e(line)}</p>" for line in answer_lines(model, lang))
    counts = []
    for name, n in class_counts(model):
        colour = RISK_COLOURS.get(name, _OTHER_COLOUR)
        muted = ' class="zero"' if n == 0 else ""
        counts.append(
            f'<li{muted} data-class="{e(name)}"><span class="sw" style="background:{colour}">'
            f"</span>{e(class_text(name, lang))} <b>{n}</b></li>"
        )
    return (
        f'<section id="answer"><h2 class="sr-only">{e(tr("sec_answer", lang))}</h2>'
        f'<div class="answer">{lines}</div>'
        f'<ul id="counts" class="counts" aria-label="{e(tr("sec_counts", lang))}">'
        f"{''.join(counts)}</ul>{_areas(model, lang)}</section>"
    )


def _risk_number(item: dict[str, Any], lang: str) -> str:
    """Write a screening-risk value: ``≤``/``≥`` for a bound, never ``both`` as a value."""
    if item["sign"] == "both":
        return tr("rk_both", lang)
    return number(item["value"], lang, 2, "", item["sign"])


def _whisker(row: dict[str, Any], lo: float, hi: float) -> str:
    """Return the row's 90 % interval as an inline SVG bar on a log scale (best as a dot).

    A bounded end runs to the edge of the scale with an arrow (the interval goes on); a
    best estimate that is a bound is a hollow dot, one bounded both ways has none.
    """
    width, height, pad = 130.0, 14.0, 4.0

    def x(value: float | None) -> float:
        if value is None or value <= 0:
            return pad
        t = (math.log10(value) - math.log10(lo)) / ((math.log10(hi) - math.log10(lo)) or 1.0)
        return pad + min(max(t, 0.0), 1.0) * (width - 2 * pad)

    x0 = pad if row["lo"]["sign"] in ("<=", "both") else x(row["lo"]["value"])
    x1 = width - pad if row["hi"]["sign"] in (">=", "both") else x(row["hi"]["value"])
    mid = height / 2
    parts = [
        f'<line x1="{x0:.1f}" y1="{mid}" x2="{x1:.1f}" y2="{mid}" stroke="#555" stroke-width="2"/>',
    ]
    for end, open_end in (
        (x0, row["lo"]["sign"] in ("<=", "both")),
        (x1, row["hi"]["sign"] in (">=", "both")),
    ):
        if open_end:
            tip = -3 if end < width / 2 else 3
            parts.append(
                f'<path d="M{end + tip:.1f},{mid} L{end - tip:.1f},{mid - 4} '
                f'L{end - tip:.1f},{mid + 4} Z" fill="#555"/>'
            )
        else:
            parts.append(
                f'<line x1="{end:.1f}" y1="{mid - 4}" x2="{end:.1f}" y2="{mid + 4}" '
                'stroke="#555" stroke-width="1.5"/>'
            )
    sign = row["p50"]["sign"]
    if sign != "both" and row["p50"]["value"] is not None:
        fill = "#fff" if sign else "#d55e00"
        parts.append(
            f'<circle cx="{x(row["p50"]["value"]):.1f}" cy="{mid}" r="4" fill="{fill}" '
            'stroke="#d55e00" stroke-width="1.5"/>'
        )
    return (
        f'<svg class="whisker" width="{width:.0f}" height="{height:.0f}" '
        f'viewBox="0 0 {width:.0f} {height:.0f}" aria-hidden="true">{"".join(parts)}</svg>'
    )


def _scale(rows: list[dict[str, Any]]) -> tuple[float, float]:
    """Return the log scale's ends [1] over every row's interval and best estimate."""
    values = [
        row[key]["value"]
        for row in rows
        for key in ("lo", "p50", "hi")
        if row[key]["value"] is not None and row[key]["value"] > 0
    ]
    if not values:
        return 1e-4, 1.0
    lo, hi = max(min(values), 1e-8), min(max(max(values), 1e-8), 1.0)
    return (lo / 1.5, hi * 1.5) if hi > lo else (lo / 10, hi * 10)


def _ink(colour: str) -> str:
    """Return black or white, whichever reads on ``colour`` (``#rrggbb``)."""
    r, g, b = (int(colour[i : i + 2], 16) for i in (1, 3, 5))
    return "#000" if 0.299 * r + 0.587 * g + 0.114 * b > 140 else "#fff"


def _risk_row(row: dict[str, Any], label: Any, scale: tuple[float, float], lang: str) -> str:
    """Return one row of the ranked list: the screening risk, then the code's verdict."""
    e = html.escape
    mechanism = row["mechanism"]
    mech = tr(f"mech_{mechanism}", lang) if f"mech_{mechanism}" in STRINGS else mechanism
    if row["share"] is not None:
        mech += f" ({number(100 * row['share'], lang, 2)} %)"
    if row["survey"]:
        key = f"inp_{row['survey']}"
        survey = tr(key, lang) if key in STRINGS else row["survey"]
        if row["survey_judgement"]:
            survey += f" ({tr('judgement', lang)})"
        if row["narrowing"] is not None:
            survey += f" ({number(100 * row['narrowing'], lang, 2)} %)"
    else:
        survey = tr("rk_nothing_varies", lang)
    band = tr(f"band_{row['band']}", lang) if f"band_{row['band']}" in STRINGS else row["band"]
    uncertain = (
        f' <span class="uncertain" title="{e(tr("rk_uncertain_title", lang))}">'
        f"◆ {e(tr('rk_uncertain', lang))}</span>"
        if row["uncertain"]
        else ""
    )
    check = row["code_check"]
    check_text = check_label(check, check.split(".")[0]).render(lang) if check else "-"
    colour = RISK_COLOURS.get(marks_of(label).counted, _OTHER_COLOUR) if label else _OTHER_COLOUR
    # the class as counted in the badge; its marks (incomplete: why) in the tooltip
    code_class = class_text(marks_of(label).counted, lang) if label else "-"
    code_title = class_text(label, lang) if label else ""
    interval = tr(
        "rk_interval", lang, lo=_risk_number(row["lo"], lang), hi=_risk_number(row["hi"], lang)
    )
    css = ' class="band-uncertain"' if row["uncertain"] else ""
    return (
        f'<tr data-id="{e(row["id"])}"{css}><td class="num">{row["rank"]}</td>'
        f'<th scope="row">{e(row["id"])}</th>'
        f'<td class="num">{e(_risk_number(row["p50"], lang))}</td>'
        f'<td class="num">{e(interval)}</td><td>{_whisker(row, *scale)}</td>'
        f"<td>{e(band)}{uncertain}</td><td>{e(mech)}</td><td>{e(survey)}</td>"
        f'<td class="code"><span class="cls" title="{e(code_title)}" '
        f'style="background:{colour};color:{_ink(colour)}">'
        f"{e(code_class)}"
        f'</span></td><td class="code">{e(check_text)}</td></tr>'
    )


def _survey(risk: dict[str, Any], lang: str) -> str:
    """Return the region's "what to survey first" list and the masonry sentence."""
    e = html.escape
    n = risk["top_n"]

    def input_text(line: dict[str, Any]) -> str:
        name = line["input"]
        text = tr(f"inp_{name}", lang) if f"inp_{name}" in STRINGS else name
        return f"{text} ({tr('judgement', lang)})" if line.get("judgement") else text

    items = [
        tr(
            "sv_line",
            lang,
            input=input_text(line),
            tower=line["id"],
            side=tr("sv_in" if line["side"] == "in" else "sv_out", lang, n=n),
            p=number(line["p"], lang, 2),
            n=n,
        )
        for line in risk["survey"]
    ]
    body = (
        "<ol>" + "".join(f"<li>{e(item)}</li>" for item in items) + "</ol>"
        if items
        else f"<p>{e(tr('sv_none', lang, n=n))}</p>"
    )
    masonry = risk["masonry"]
    if masonry is None:
        sentence = ""
    elif masonry["basis"] == "top_n":
        sentence = tr(
            "sv_masonry",
            lang,
            tower=masonry["id"],
            input=input_text(masonry),
            p=number(masonry["p"], lang, 2),
            n=n,
        )
    else:
        sentence = tr(
            "sv_masonry_index",
            lang,
            tower=masonry["id"],
            input=input_text(masonry),
            index=number(masonry["index"], lang, 2),
            narrowing=number(masonry["narrowing"], lang, 2),
        )
    masonry_html = f'<p class="masonry">{e(sentence)}</p>' if sentence else ""
    return (
        f'<div id="survey-first"><h3>{e(tr("sv_title", lang, n=n))}</h3>{body}{masonry_html}</div>'
    )


def _risk_section(model: ReportModel, lang: str) -> str:
    """Return the first screen of an assess report: the screening risk's ranked list.

    Beside each row, the code's verdict (its class and governing check), labelled as the
    code's; an archive without the screening risk says it was not computed.
    """
    risk = model.risk
    if risk is None:
        return ""
    e = html.escape
    head = f'<section id="risk"><h2>{e(tr("sec_risk", lang))}</h2>'
    if not risk["computed"]:
        return head + f'<p class="risk-none">{e(tr("risk_not_computed", lang))}</p></section>'
    labels = {t["id"]: t.get("risk_class") for t in model.towers}
    scale = _scale(risk["rows"])
    rows = "".join(_risk_row(row, labels.get(row["id"]), scale, lang) for row in risk["rows"])
    columns = (
        "rk_rank",
        "rk_tower",
        "rk_p50",
        "rk_interval_head",
        "rk_bar",
        "rk_band",
        "rk_mechanism",
        "rk_survey",
    )
    heads = "".join(
        f'<th scope="col"><span class="sr-only">{e(tr(key, lang))}</span></th>'
        if key == "rk_bar"  # the drawn interval: its numbers are the column before
        else f'<th scope="col">{e(tr(key, lang))}</th>'
        for key in columns
    )
    code_heads = "".join(
        f'<th scope="col" class="code">{e(tr(key, lang))}</th>'
        for key in ("rk_code_class", "rk_code_check")
    )
    table = (
        '<div class="risk-wrap"><table id="risk-list" class="risk">'
        f'<thead><tr><th colspan="{len(columns)}" class="group">{e(tr("rk_group_risk", lang))}'
        f'</th><th colspan="2" class="group code">{e(tr("rk_group_code", lang))}</th></tr>'
        f"<tr>{heads}{code_heads}</tr></thead><tbody>{rows}</tbody></table></div>"
        if rows
        else f"<p>{e(tr('risk_none_ranked', lang))}</p>"
    )
    unranked = (
        f'<p class="muted">{e(tr("rk_unranked", lang, ids=", ".join(risk["unranked"])))}</p>'
        if risk["unranked"]
        else ""
    )
    return (
        head
        + f'<p class="risk-intro">{e(tr("risk_intro", lang))}</p>'
        + table
        + unranked
        + _survey(risk, lang)
        + "</section>"
    )


def _areas(model: ReportModel, lang: str) -> str:
    """Return the towers per class per comune/provincia (collapsed), ``""`` without areas."""
    e = html.escape
    out = []
    for column in area_columns(model.towers):
        met, areas = area_counts(model.towers, column)
        order = [name for name, _ in class_counts(model)]
        classes = [c for c in order if c in met] + [c for c in met if c not in order]
        head = "".join(f"<th>{e(class_text(c, lang))}</th>" for c in classes)
        body = "".join(
            f"<tr><td>{e(area)}</td>"
            + "".join(f"<td>{counts.get(c, 0)}</td>" for c in classes)
            + f"<td>{total}</td></tr>"
            for area, counts, total in areas
        )
        title = tr("areas_by", lang, column=column)
        out.append(
            f'<details class="areas" data-column="{e(column)}"><summary>{e(title)}</summary>'
            f"<table><thead><tr><th>{e(column)}</th>{head}<th>{e(tr('areas_total', lang))}"
            f"</th></tr></thead><tbody>{body}</tbody></table></details>"
        )
    return "".join(out)


def render_html(model: ReportModel, lang: str = "en", *, generated: str | None = None) -> str:
    """Return the whole page.

    Parameters
    ----------
    model : ReportModel
        What to show (from an adapter).
    lang : str
        ``"en"`` or ``"it"``.
    generated : str, optional
        Generation time shown in the footer (default: now, UTC, ISO 8601).

    Returns
    -------
    str
        The HTML document.

    Raises
    ------
    ReportError
        For an unknown language or an asset that cannot be inlined.
    """
    if lang not in LANGUAGES:
        raise ReportError(
            f"language {lang!r} is not available (choose from {', '.join(LANGUAGES)})"
        )
    if generated is None:
        generated = _dt.datetime.now(_dt.timezone.utc).isoformat(timespec="seconds")
    e = html.escape

    def t(key: str) -> str:
        return e(tr(key, lang))

    assumptions = list(model.assumptions)
    if any(f.kind == "history" for s in model.sheets.values() for f in s.figures):
        assumptions.append(
            HeaderItem("a_histories", tr("a_histories_text", lang, bins=HISTORY_BINS))
        )
    title = f"{tr('report_title', lang)}: {tr(model.title, lang)}"
    css = _asset("report.css")
    scripts = "\n".join(_asset(name) for name in SCRIPTS)
    data = json_for_script(_page_data(model, lang))
    return f"""<!DOCTYPE html>
<html lang="{lang}">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta name="generator" content="rockscreen {e(__version__)}">
<title>{e(title)}</title>
<style>{css}</style>
</head>
<body>
<header>
<h1>{t("report_title")}</h1>
<p class="subtitle">{t(model.title)} · rockscreen {e(__version__)} ·
{t("generated")} {e(generated)}</p>
</header>
{_risk_section(model, lang)}
{_answer(model, lang)}
<section id="map-section">
<h2>{t("sec_map")}</h2>
<div class="map-tools">
<label><input type="checkbox" id="background">
{t("map_background")}: {e(TILES["attribution"])}</label>
<button type="button" id="reset">{t("map_reset")}</button>
<span>{t("map_help")}</span>
</div>
<div id="legend" class="legend"></div>
<div id="map"></div>
</section>
<section id="table-section">
<h2>{t("sec_table")}</h2>
<div class="table-tools">
<label>{t("filter")} <input type="search" id="filter"></label>
<label>{t("filter_class")} <select id="class-filter"></select></label>
<button type="button" id="export">{t("export_csv")}</button>
<span id="count" class="muted"></span>
</div>
<div class="table-wrap"><table id="towers" class="towers"></table></div>
<p class="muted">{t("skip_sheet")}</p>
<section id="sheet" hidden aria-live="polite"></section>
</section>
<section id="summary">
<details>
<summary><h2>{t("sec_header")}</h2> <span class="muted">{t("sec_header_hint")}</span></summary>
{_items(model.header, lang)}
<h3>{t("sec_assumptions")}</h3>
{_items(assumptions, lang)}
</details>
</section>
<section id="method">
<h2>{t("sec_method")}</h2>
<div class="method">{
        _method_text(model.method_text, lang) if model.method_text else _method(model.method, lang)
    }</div>
</section>
<footer>rockscreen {e(__version__)} · {t("generated")} {e(generated)}</footer>
<script id="report-data" type="application/json">{data}</script>
<script>{scripts}</script>
</body>
</html>
"""
