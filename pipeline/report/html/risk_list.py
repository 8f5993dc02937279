"""The screening risk's ranked list: the first screen of an assess report.

:func:`risk_section` writes the section ``#risk`` of the page: the towers ranked by their
screening risk (median and 90 % interval, drawn as a bar on a log scale), the band, the
mechanism and the input to survey, and beside each row the code's verdict (its class and
governing check), labelled as the code's; then the region's "what to survey first" list.
Every text is escaped with :func:`html.escape`. docs/report.md describes the list.
"""

from __future__ import annotations

import html
import math

from rockscreen.pipeline.report.html.answer import class_text
from rockscreen.pipeline.report.html.i18n import STRINGS, number, tr
from rockscreen.pipeline.report.html.model import (
    Masonry,
    RankedList,
    RankedRow,
    ReportModel,
    RiskValue,
    SurveyLine,
    TowerCell,
)
from rockscreen.pipeline.report.html.page_data import OTHER_COLOUR
from rockscreen.pipeline.report.maps import RISK_COLOURS
from rockscreen.pipeline.verdict.checks import check_label
from rockscreen.pipeline.verdict.labels import marks_of

__all__ = ["risk_section"]


def _risk_number(item: RiskValue, lang: str) -> str:
    """Write a screening-risk value: ``≤``/``≥`` for a bound, never ``both`` as a value."""
    if item["sign"] == "both":
        return tr("rk_both", lang)
    return number(item["value"], lang, 2, "", item["sign"])


def _whisker(row: RankedRow, lo: float, hi: float) -> str:
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


def _scale(rows: list[RankedRow]) -> tuple[float, float]:
    """Return the log scale's ends [1] over every row's interval and best estimate."""
    values = [
        value
        for row in rows
        for value in (row["lo"]["value"], row["p50"]["value"], row["hi"]["value"])
        if value is not None and value > 0
    ]
    if not values:
        return 1e-4, 1.0
    lo, hi = max(min(values), 1e-8), min(max(max(values), 1e-8), 1.0)
    return (lo / 1.5, hi * 1.5) if hi > lo else (lo / 10, hi * 10)


def _ink(colour: str) -> str:
    """Return black or white, whichever reads on ``colour`` (``#rrggbb``)."""
    r, g, b = (int(colour[i : i + 2], 16) for i in (1, 3, 5))
    return "#000" if 0.299 * r + 0.587 * g + 0.114 * b > 140 else "#fff"


def _risk_row(
    row: RankedRow, label: TowerCell | None, scale: tuple[float, float], lang: str
) -> str:
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
    colour = RISK_COLOURS.get(marks_of(label).counted, OTHER_COLOUR) if label else OTHER_COLOUR
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


def _survey(risk: RankedList, lang: str) -> str:
    """Return the region's "what to survey first" list and the masonry sentence."""
    e = html.escape
    n = risk["top_n"]

    def input_text(line: SurveyLine | Masonry) -> str:
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


def risk_section(model: ReportModel, lang: str) -> str:
    """Return the first screen of an assess report: the screening risk's ranked list.

    Beside each row, the code's verdict (its class and governing check), labelled as the
    code's; an archive without the screening risk says it was not computed.

    Parameters
    ----------
    model : ReportModel
        What to show (from an adapter); its ``risk`` is None for a kind without the list.
    lang : str
        ``"en"`` or ``"it"``.

    Returns
    -------
    str
        The section ``#risk`` (escaped HTML), ``""`` when the model has no screening risk.
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
