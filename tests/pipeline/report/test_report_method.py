"""The report's "Method, references and limits" section describes what THAT archive computed.

Two assess archives written by the risk writer, one as an older ``assess`` wrote it (a
multiple-stripe fit, no part modelled, no code check made, no screening risk) and one with
the IDA's censored fit, the belfry modelled, the LV1 check made and the screening risk's
root attributes (``risk_methods``, ``risk_priors_source``, ``risk_samples``, ``risk_seed``):
their Method sections differ, in English and in Italian, and each Italian sentence is the
catalogue's.
"""

from __future__ import annotations

import html
import math
import re

import pytest

from rockscreen.pipeline.archive.risk_archive import write_risk_archive
from rockscreen.pipeline.report.html import render_html, report_model
from rockscreen.pipeline.report.html.adapters.risk import risk_model
from rockscreen.pipeline.report.html.adapters.risk_method import method_paragraphs
from rockscreen.pipeline.verdict.messages import catalogue


def _row(tower_id: str, **values) -> dict:
    row = {
        "id": tower_id,
        "name": tower_id,
        "lat_deg": 42.35,
        "lon_deg": 13.40,
        "soil_class": "B",
        "fragility_median_g": 0.3,
        "fragility_beta": 0.4,
        "p_overturning_50y": 0.01,
        "safety_index": 1.2,
        "risk_class": "meets",
        "note": "",
    }
    row.update(values)
    return row


def _older(path):
    """An assess archive of the stripes' fit alone: no IDA, no part, no check, no risk."""
    summary = [_row("T1"), _row("T2")]
    write_risk_archive(
        path,
        "assess",
        {"summary": summary},
        {"return_periods_y": "[101.0, 475.0, 2475.0]", "models": '["ground"]'},
    )
    return path


def _newer(path):
    """An assess archive with the IDA, the belfry, LV1 and the screening risk's attributes."""
    nan = math.nan
    ida = {
        "collapse_median_g": 0.5,
        "collapse_bound": "",
        "stripe_median_g": 0.45,
        "knowledge_level": "LC1",
        "governing_check": "shaft.lv1",
    }
    summary = [
        _row("T1", **ida, belfry_fragility_median_g=0.2, lv1_safety_index=0.4),
        _row(
            "T2",
            **{**ida, "collapse_bound": "lower"},
            belfry_fragility_median_g=nan,
            lv1_safety_index=nan,
        ),
    ]
    write_risk_archive(
        path,
        "assess",
        {"summary": summary},
        {
            "return_periods_y": "[30.0, 475.0, 2475.0]",
            "models": '["ground", "double", "belfry"]',
            "suite_kind": "stochastic",
            "n_records_per_stripe": 11,
            "seed": 3,
            "ida_ratio": 1.2,
            "ida_tolerance": 0.01,
            "ida_cap_pga_g": 3.0,
            "slv_theta_ratio": 0.4,
            "bootstrap_resamples": 200,
            "risk_methods": '["shaft_lv1_mean", "kinematic_mean", "rocking_ida", '
            '"hazard_integral"]',
            "risk_priors_source": "default",
            "risk_samples": 256,
            "risk_seed": 7,
        },
    )
    return path


def _method(page: str) -> list[str]:
    """Return the method section's paragraphs as text."""
    section = re.search(r'<div class="method">(.*?)</div>', page, re.S).group(1)
    return [
        html.unescape(re.sub(r"<[^>]+>", "", p)) for p in re.findall(r"<p[^>]*>.*?</p>", section)
    ]


@pytest.fixture(scope="module")
def pages(tmp_path_factory):
    folder = tmp_path_factory.mktemp("method")
    older, newer = _older(folder / "older.h5"), _newer(folder / "newer.h5")
    return {
        (name, lang): _method(render_html(report_model(path), lang))
        for name, path in (("older", older), ("newer", newer))
        for lang in ("en", "it")
    }


def test_two_archives_give_two_method_sections(pages):
    for lang in ("en", "it"):
        assert pages["older", lang] != pages["newer", lang]
    older, newer = " ".join(pages["older", "en"]), " ".join(pages["newer", "en"])
    # the fragility: the stripes' fit alone, or the IDA's censored fit with the stripes beside
    assert "multiple-stripe analysis" in older and "incremental dynamic analysis" not in older
    assert "incremental dynamic analysis (IDA)" in newer and "censored" in newer
    assert "Towers whose collapse median is only a bound: 1 of 2." in newer
    assert "200 bootstrap resamples" in newer and "bootstrap" not in older
    # the parts: the belfry modelled for one tower, or not at all
    assert (
        "Belfry rocking: its own rigid block on its support, with its own IDA (towers: 1 of 2)"
        in newer
    )
    assert "Belfry rocking: not modelled" in older
    # the code's checks made
    assert "Shaft flexure (LV1): made (towers: 1 of 2)." in newer
    assert "Shaft flexure (LV1): made for no tower" in older
    assert "LC1 (2)" in newer
    # the screening risk: computed with its samples, priors and seed, or said not computed
    assert "256 epistemic samples" in newer and "seed 7" in newer
    assert "the shaft in compression and flexure with the LV1 mechanics" in newer
    assert "was not computed for this archive" in older and "not computed" not in newer
    # the models of the whole tower: the registry's labels, the part models apart
    assert "double block" in newer and "double block" not in older
    # no fixed prose: the older text's "belfries are not modelled" is gone
    assert "partial mechanisms (belfry, cusp)" not in older + newer


def test_the_italian_method_is_the_catalogues(pages):
    italian = " ".join(pages["newer", "it"])
    assert "analisi dinamica incrementale (IDA)" in italian
    assert "256 campioni epistemici" in italian and "seme 7" in italian
    assert "Flessione del fusto (LV1): eseguita (torri: 1 su 2)." in italian
    assert "non è stato calcolato" in " ".join(pages["older", "it"])
    # no English sentence of the method catalogue on the Italian pages
    english = [
        piece.strip(" .,:;()")
        for spec in catalogue().values()
        if spec.code.startswith("method.") and spec.en != spec.it
        for piece in re.split(r"\{[^}]*\}", spec.en)
        if len(piece.split()) >= 3 and piece not in spec.it
    ]
    assert len(english) > 30
    for key in ("older", "newer"):
        text = " ".join(pages[key, "it"])
        assert [e for e in english if e in text] == []


def test_an_unknown_risk_method_is_named_not_dropped():
    paragraphs = method_paragraphs(
        "assess", {"risk_methods": '["rocking_ida", "new_method"]'}, [_row("T1")]
    )
    (risk,) = [p for p in paragraphs if p.heading == "method.h_risk"]
    codes = dict(risk.sentences)
    methods = codes["method.risk_methods"]["methods"]
    assert [m.code for m in methods] == ["method.risk.rocking_ida", "method.risk.other"]
    assert methods[1].kwargs == {"method": "new_method"}


def test_a_scenario_method_names_its_shakemap_and_fragility():
    attrs = {
        "shakemap_source": "/data/events/grid.xml",
        "shakemap_event": "us7000abcd",
        "fragility_source": "/tmp/assess.h5",
        "gm_uncertainty": False,
    }
    page = render_html(risk_model("scenario", attrs, [_row("T1", p_overturning=0.1)]), "it")
    text = " ".join(_method(page))
    assert "grid.xml" in text and "us7000abcd" in text and "assess.h5" in text
    assert "/data/events" not in text  # file names, not a machine's folders
    assert "nessuna incertezza del moto del suolo" in text
