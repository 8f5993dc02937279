"""The screening risk on the assess report (issue 31): the ranked list first, the code beside.

An assess archive written by the risk writer with the contract's ``risk_*`` columns, its
``/risk_fragility``, ``/risk_sensitivity`` and ``/risk_top_n`` tables and root attributes;
and one without them (an older archive), which still renders and says the screening risk
was not computed.
"""

from __future__ import annotations

import html
import json
import math
import re

import pytest

from rockscreen.pipeline.archive.risk_archive import write_risk_archive
from rockscreen.pipeline.report.html import render_html, report_model
from rockscreen.pipeline.report.html.adapters.risk_rank import band_sign, ranked_list
from rockscreen.pipeline.report.html.i18n import STRINGS
from rockscreen.pipeline.verdict.messages import dumps, message


def _row(tower_id: str, rank: int, best: float, lo: float, hi: float, **values) -> dict:
    row = {
        "id": tower_id,
        "name": tower_id,
        "lat_deg": 42.35,
        "lon_deg": 13.40,
        "soil_class": "B",
        "collapse_median_g": 1.4,
        "collapse_beta": 0.3,
        "collapse_bound": "",
        "safety_index": 0.05,
        "slv_bound": "",
        "risk_class": "very_high",
        "governing_check": "shaft.lv1",
        "governing": "shaft flexure (LV1)",
        "governing_shown": True,
        "governing_capacity_ag_g": 0.02,
        "governing_safety_index": 0.05,
        "governing_bound": "",
        "p_overturning_50y": 0.002,
        "lv1_capacity_ag_g": 0.02,
        "lv1_safety_index": 0.05,
        "lv1_bound": "",
        "lv1_period_s": 0.4,
        "lv1_compression_ratio": 0.8,
        "note": "",
        "risk_p50_best": best,
        "risk_p50_best_bound": "",
        "risk_p50_lo90": lo,
        "risk_p50_lo90_bound": "",
        "risk_p50_hi90": hi,
        "risk_p50_hi90_bound": "",
        "risk_rank": rank,
        "risk_band": "top_10" if rank == 1 else "rest",
        "risk_band_uncertain": "no",
        "risk_governing_mechanism": "shaft",
        "risk_governing_share": 0.8,
        "risk_survey_first": "period_s",
        "risk_survey_first_index": 0.6,
        "risk_survey_first_narrowing": 0.4,
        "risk_beta": 0.4,
        "risk_beta_source": "judgement_fema_p695",
        "risk_samples": 500,
        "risk_judgement_inputs": "masonry_type;beta",
        "risk_note_codes": dumps(
            [message("risk.judgement_prior", input="masonry_type", source="uniform")]
        ),
    }
    row.update(values)
    return row


def _summary() -> list[dict]:
    return [
        _row("T2", 2, 0.1, 0.03, 0.3, risk_band_uncertain="yes"),
        _row(
            "T1",
            1,
            0.4,
            0.2,
            0.9,
            risk_p50_hi90_bound="at_least",
            risk_survey_first="masonry_type",
            risk_governing_mechanism="tower_kinematic",
        ),
        _row(
            "T3",
            3,
            0.01,
            0.01,
            0.05,
            risk_p50_best_bound="at_most",
            risk_p50_lo90_bound="at_most",
            risk_class="meets",
            governing_check="tower.rocking",
        ),
        _row("T4", 4, math.nan, math.nan, 0.02, risk_p50_best_bound="both"),
        _row(
            "T5",
            0,
            math.nan,
            math.nan,
            math.nan,
            risk_band="",
            risk_survey_first="",
            risk_note_codes=dumps([message("risk.no_geometry", missing="height_m")]),
        ),
    ]


def _tables() -> dict:
    ag = [0.05 * 1.2**i for i in range(20)]
    fragility = [
        {
            "tower_id": tower,
            "ag_g": a,
            "p_median": min(1.0, a / 2),
            "p_lo90": min(1.0, a / 4),
            "p_hi90": min(1.0, a),
            "p_mean": min(1.0, a / 2),
            "bounded_share": 0.0,
        }
        for tower in ("T1", "T2")
        for a in ag
    ]
    sensitivity = [
        {
            "tower_id": "T1",
            "input": "masonry_type",
            "index": 0.5,
            "narrowing": 0.3,
            "judgement": "yes",
        },
        {"tower_id": "T1", "input": "period_s", "index": 0.2, "narrowing": 0.1, "judgement": "no"},
        {"tower_id": "T2", "input": "fm_pa", "index": 0.3, "narrowing": 0.2, "judgement": "no"},
    ]
    top_n = [
        {"tower_id": "T2", "side": "out", "input": "period_s", "p_crosses": 0.4},
        {"tower_id": "T3", "side": "out", "input": "fm_pa", "p_crosses": 0.25},
        {"tower_id": "T1", "side": "in", "input": "wall_m", "p_crosses": 0.0},
    ]
    return {"risk_fragility": fragility, "risk_sensitivity": sensitivity, "risk_top_n": top_n}


ATTRS = {
    "risk_methods": '["shaft_lv1_mean", "kinematic_mean", "rocking_ida", "hazard_integral"]',
    "risk_priors_source": "default",
    "risk_samples": 500,
    "risk_seed": 1,
    "risk_top_n": 2,
}


@pytest.fixture(scope="module")
def archives(tmp_path_factory):
    folder = tmp_path_factory.mktemp("risk-rank")
    with_risk, without = folder / "risk.h5", folder / "older.h5"
    write_risk_archive(with_risk, "assess", {"summary": _summary(), **_tables()}, ATTRS)
    older = [
        {k: v for k, v in row.items() if not k.startswith("risk_") or k == "risk_class"}
        for row in _summary()
    ]
    write_risk_archive(without, "assess", {"summary": older}, {})
    return with_risk, without


def _section(page: str, name: str) -> str:
    match = re.search(rf'<section id="{name}">(.*?)</section>', page, re.S)
    assert match, name
    return match.group(1)


def _text(fragment: str) -> str:
    return html.unescape(re.sub(r"<[^>]+>", " ", fragment))


def _page_data(page: str) -> dict:
    raw = re.search(r'<script id="report-data" type="application/json">(.*?)</script>', page, re.S)
    return json.loads(raw.group(1))


def test_bound_flags_print_as_signs():
    assert [band_sign(f) for f in ("", "at_most", "at_least", "both", None, b"at_most")] == [
        "",
        "<=",
        ">=",
        "both",
        "",
        "<=",
    ]


def test_the_ranked_list_of_the_model(archives):
    model = report_model(archives[0])
    risk = model.risk
    assert risk["computed"] is True
    assert [r["id"] for r in risk["rows"]] == ["T1", "T2", "T3", "T4"]  # by rank, T5 has none
    assert risk["unranked"] == ["T5"]
    t1 = risk["rows"][0]
    assert t1["hi"] == {"value": 0.9, "sign": ">="}
    assert t1["survey_judgement"] is True  # masonry_type's prior is a judgement
    assert t1["code_check"] == "shaft.lv1"
    assert risk["rows"][3]["p50"] == {"value": None, "sign": "both"}
    # the region's list: most likely change first, a zero left out
    assert [(s["id"], s["input"]) for s in risk["survey"]] == [("T2", "period_s"), ("T3", "fm_pa")]
    assert risk["masonry"]["id"] == "T3" and risk["masonry"]["basis"] == "top_n"
    # the towers table: the rank and the best estimate, a bound signed, "both" not a value
    cells = {t["id"]: t for t in model.towers}
    assert cells["T3"]["risk_p50_best"] == 0.01 and cells["T3"]["bounds"]["risk_p50_best"] == "≤"
    assert cells["T4"]["risk_p50_best"] is None and cells["T4"]["risk_rank"] == 4
    assert cells["T5"]["risk_rank"] is None and cells["T5"]["risk_p50_best"] is None
    # the sheets: the risk lines, the bars (largest index first), the band on the figure
    sheet = model.sheets["T1"]
    assert [key for key, _ in sheet.risk] == ["s_risk_p50", "s_risk_mech", "s_risk_note"]
    assert [bar[0] for bar in sheet.sensitivity] == ["inp_masonry_type", "inp_period_s"]
    assert sheet.sensitivity[0][3] is True
    (figure,) = [f for f in sheet.figures if f.kind == "xy"]
    labels = [c.label for c in figure.curves]
    assert {"fc_risk_median", "fc_risk_lo", "fc_risk_hi"} <= set(labels) and figure.logx


def test_masonry_tower_from_the_sensitivity_when_no_top_n_line_is_masonry():
    rows = _summary()
    tables = _tables()
    risk = ranked_list(ATTRS, rows, tables["risk_top_n"][:1], tables["risk_sensitivity"])
    assert risk["masonry"]["id"] == "T1" and risk["masonry"]["basis"] == "sensitivity"
    assert ranked_list(ATTRS, rows, (), ())["masonry"] is None


def test_the_first_screen_is_the_ranked_list_with_the_code_beside(archives):
    page = render_html(report_model(archives[0]), "en")
    assert page.index('<section id="risk">') < page.index('<section id="answer">')
    section = _section(page, "risk")
    text = _text(section)
    assert "The code's verdict" in text and "Screening risk (best estimate)" in text
    rows = re.findall(r'<tr data-id="([^"]+)"', section)
    assert rows == ["T1", "T2", "T3", "T4"]
    t1 = _text(re.search(r'<tr data-id="T1".*?</tr>', section, re.S).group(0))
    assert "0.2 – ≥ 0.9" in t1  # the bound kept as a bound
    assert "masonry type (judgement)" in t1 and "(30 %)" not in t1 and "(40 %)" in t1
    assert "whole-tower kinematic (80 %)" in t1
    assert "very high" in t1 and "shaft flexure (LV1)" in t1
    t3 = _text(re.search(r'<tr data-id="T3".*?</tr>', section, re.S).group(0))
    assert "≤ 0.01" in t3 and "whole-tower rocking" in t3  # the code's governing check
    t4 = _text(re.search(r'<tr data-id="T4".*?</tr>', section, re.S).group(0))
    assert "not a value (bounded both ways)" in t4
    assert 'class="band-uncertain"' in re.search(r'<tr data-id="T2"[^>]*>', section).group(0)
    t2 = re.search(r'<tr data-id="T2".*?</tr>', section, re.S).group(0)
    assert "◆ uncertain" in _text(t2) and "the 90 % interval reaches another band" in t2
    assert "T5" in text  # named among the towers without a risk
    assert "period T1 of T2 (now outside the top 2): P = 0.4" in text
    assert "Surveying the masonry changes T3's place most: masonry strength f_m, P = 0.25" in text
    # the sheet's data: risk lines, bars with the judgement marked
    sheet = _page_data(page)["sheets"]["T1"]
    assert sheet["risk"][0].startswith("P(collapse in 50 y) 0.4, 90 % interval 0.2 – ≥ 0.9")
    assert _page_data(page)["sheets"]["T5"]["risk"] == [
        "No screening risk for this tower.",
        "Note: no screening risk: height_m not given (needed: lat, lon, width_m, depth_m, "
        "height_m).",
    ]
    assert sheet["sensitivity"][0][0] == "masonry type" and sheet["sensitivity"][0][4] is True


def test_the_italian_first_screen_holds_no_english(archives):
    page = render_html(report_model(archives[0]), "it")
    text = _text(_section(page, "risk"))
    assert "Esito di norma" in text and "Rischio di screening (stima migliore)" in text
    assert "0,2 – ≥ 0,9" in text and "tipo di muratura (giudizio)" in text
    assert "non è un valore" in text
    entries = [
        STRINGS[key]
        for key in STRINGS
        if key.startswith(("rk_", "sv_", "band_", "mech_", "inp_", "risk_", "s_risk"))
        and STRINGS[key]["en"] != STRINGS[key]["it"]
    ]
    pieces = [
        p.strip(" .,:;()")
        for entry in entries
        for p in re.split(r"\{[^}]*\}", entry["en"])
        if len(p.split()) >= 2 and p.strip(" .,:;()") not in entry["it"]
    ]
    assert len(pieces) > 20
    assert [p for p in pieces if p in text] == []
    sheet = _page_data(page)["sheets"]["T1"]
    assert sheet["risk"][0].startswith("P(crollo in 50 anni) 0,4")
    assert "giudizio" in sheet["risk"][1]  # the judgement beta
    # the code's checks beside, in Italian too
    checks = {row[0]: row[1:] for row in sheet["checks"]}
    assert (
        checks["Ribaltamento della torre intera (IDA)"][2]
        == "mediana di fragilità 1,4 g, P50 0,002"
    )
    assert checks["Modello LV1 per torri"][2] == "flessione del fusto, T1 0,4 s, σ0/(0,85 f_d) 0,8"
    assert sheet["checks_text"][0].startswith("Governa: flessione del fusto (LV1), a_C 0,02 g")
    towers = {t["id"]: t for t in _page_data(page)["towers"]}
    assert towers["T1"]["governing"] == "flessione del fusto (LV1)"  # the table's column
    assert sheet["risk"][2] == (
        "Nota: la distribuzione a priori di masonry_type è un giudizio, non un adattamento a "
        "dati (uniform)."
    )


def test_an_archive_without_the_risk_says_it_was_not_computed(archives):
    for lang, words in (("en", "was not computed"), ("it", "non è stato calcolato")):
        page = render_html(report_model(archives[1]), lang)
        section = _section(page, "risk")
        assert words in _text(section) and "<table" not in section
        assert 'id="answer"' in page  # the code's verdict follows as before
        assert _page_data(page)["sheets"]["T1"]["risk"] == []


def test_the_png_fragility_draws_the_risk_band(archives, tmp_path):
    """``plot ASSESS.h5 --tower ID``: the screening risk's median and 5-95 % band beside the
    record-based fits, labelled as the screening risk's; none for an older archive."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rockscreen.pipeline.archive.kinds import open_archive
    from rockscreen.pipeline.report.risk_plots import draw_risk_band
    from rockscreen.pipeline.report.risk_text import plot_assess

    band = [r for r in _tables()["risk_fragility"] if r["tower_id"] == "T1"]
    fig, ax = plt.subplots()
    assert draw_risk_band(ax, band) is True
    labels = [line.get_label() for line in ax.get_lines()]
    assert labels == ["screening risk: median (best estimate)"]
    (poly,) = ax.collections
    assert poly.get_label() == "screening risk: 5-95 % band"
    assert draw_risk_band(ax, []) is False
    plt.close(fig)
    (png,) = plot_assess(open_archive(archives[0]), "T1", False, str(tmp_path / "t1.png"))
    assert png.stat().st_size > 0
    (png,) = plot_assess(open_archive(archives[1]), "T1", False, str(tmp_path / "old.png"))
    assert png.stat().st_size > 0  # an archive without the risk draws as before


def test_an_assess_run_without_the_risk_says_it_was_not_computed():
    """``risk_methods`` = ``[]`` (the risk switched off): the columns are there, rank 0."""
    rows = [{**row, "risk_rank": 0, "risk_p50_best": math.nan} for row in _summary()]
    risk = ranked_list({**ATTRS, "risk_methods": "[]"}, rows)
    assert risk["computed"] is False and risk["rows"] == []
    assert ranked_list({}, _summary())["computed"] is True  # no attribute: the ranks say


def test_every_sampled_input_has_its_name_in_both_languages():
    """A survey-first input or a sensitivity bar never shows a raw name on either page."""
    from rockscreen.pipeline.report.html.i18n import STRINGS
    from rockscreen.pipeline.risk.uncertainty.belfry import BELFRY_KEYS
    from rockscreen.pipeline.risk.uncertainty.sensitivity import INPUTS

    for name in (*INPUTS, *BELFRY_KEYS, "beta"):
        entry = STRINGS.get(f"inp_{name}")
        assert entry is not None, f"inp_{name} missing from strings.json"
        assert entry.get("en") and entry.get("it"), f"inp_{name} lacks a language"
