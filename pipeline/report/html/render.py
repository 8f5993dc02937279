"""Render a :class:`ReportModel` into one self-contained HTML page.

Everything is inline: the styles, the scripts (``assets/*.js``, vanilla JavaScript, no
library), the data (one ``<script type="application/json">`` block) and the method text.
No request leaves the page unless the reader ticks the background-map box (then map
tiles are fetched from :data:`~rockscreen.pipeline.report.html.page_data.TILES`). Every
text from the archive is escaped with :func:`html.escape` in the static part and set through
``textContent`` by the scripts; the JSON block escapes ``<``, ``>`` and ``&`` so no archive
text can close the script.

This module writes the page's shell (header, answer, map, table, summary, method, footer);
the screening risk's ranked list is :mod:`~rockscreen.pipeline.report.html.risk_list`'s, the
data the scripts read :mod:`~rockscreen.pipeline.report.html.page_data`'s.
"""

from __future__ import annotations

import datetime as _dt
import html
import json
import re
from pathlib import Path

from rockscreen.pipeline import __version__
from rockscreen.pipeline.errors import ReportError
from rockscreen.pipeline.report.areas import area_columns, area_counts
from rockscreen.pipeline.report.html.answer import answer_lines, class_counts, class_text
from rockscreen.pipeline.report.html.i18n import LANGUAGES, tr
from rockscreen.pipeline.report.html.model import (
    HeaderItem,
    MethodParagraph,
    ModelNames,
    ReportModel,
)
from rockscreen.pipeline.report.html.page_data import OTHER_COLOUR, TILES, page_data
from rockscreen.pipeline.report.html.reduce import HISTORY_BINS
from rockscreen.pipeline.report.html.risk_list import risk_section
from rockscreen.pipeline.report.maps import RISK_COLOURS
from rockscreen.pipeline.verdict.messages import message

__all__ = ["SCRIPTS", "json_for_script", "render_html"]

ASSETS = Path(__file__).with_name("assets")
#: Scripts inlined in this order.
SCRIPTS = ("chart.js", "map.js", "report.js")
_UNSAFE_IN_SCRIPT = re.compile(r"</script|<!--", re.IGNORECASE)


def json_for_script(data: object) -> str:
    r"""Serialise ``data`` as JSON that is safe inside an HTML ``<script>`` element.

    ``data`` is plain data (a :data:`~rockscreen.pipeline.report.values.JSONValue`, or the
    :class:`~rockscreen.pipeline.report.html.page_data.PageData` of a page).

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
        colour = RISK_COLOURS.get(name, OTHER_COLOUR)
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


def _summary(model: ReportModel, lang: str) -> str:
    """Return the section ``#summary``: the archive's header and the run's assumptions.

    Collapsed; an archive with time histories adds how they were reduced (one assumption).
    """
    e = html.escape
    assumptions = list(model.assumptions)
    if any(f.kind == "history" for s in model.sheets.values() for f in s.figures):
        assumptions.append(
            HeaderItem("a_histories", tr("a_histories_text", lang, bins=HISTORY_BINS))
        )
    return f"""<section id="summary">
<details>
<summary><h2>{e(tr("sec_header", lang))}</h2> <span class="muted">{
        e(tr("sec_header_hint", lang))
    }</span></summary>
{_items(model.header, lang)}
<h3>{e(tr("sec_assumptions", lang))}</h3>
{_items(assumptions, lang)}
</details>
</section>"""


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

    title = f"{tr('report_title', lang)}: {tr(model.title, lang)}"
    css = _asset("report.css")
    scripts = "\n".join(_asset(name) for name in SCRIPTS)
    data = json_for_script(page_data(model, lang))
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
{risk_section(model, lang)}
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
{_summary(model, lang)}
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
