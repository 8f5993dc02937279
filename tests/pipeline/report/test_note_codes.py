"""A tower's note as codes (issue 29): stored beside the English text, rendered per language.

An archive's summary row holds ``note`` (English) and ``note_codes`` (the same messages as
codes); the report renders the note from the codes, and refuses a code its catalogue does not
know instead of showing an English clause on an Italian page. An archive written before the
codes reads through the adapter of older archives (``report/html/notes.py``).
"""

from __future__ import annotations

import json
import math

import h5py
import pytest

from rockscreen.pipeline.archive.risk_archive import write_column, write_risk_archive
from rockscreen.pipeline.archive.risk_reader import read_summary
from rockscreen.pipeline.archive.safety import read_column
from rockscreen.pipeline.errors import ReportError
from rockscreen.pipeline.report.export import summary_csv_text
from rockscreen.pipeline.report.html import render_html, report_model
from rockscreen.pipeline.verdict.messages import (
    loads,
    message,
    note_columns,
    render_all,
)

#: A note of several clauses, one with clauses inside it and one with a number.
NOTE = (
    message("knowledge.assumed", level="LC1", fc=1.35),
    message(
        "site.assumed",
        defaults=[
            message("site.default", name="soil_class", value="C"),
            message("site.default", name="nominal_life_y", value=50.0),
        ],
    ),
    message(
        "fit.collapse",
        notes=[
            message("fit.none", event=message("fit.event_overturned")),
            message("fit.censored_all", k=7, n=7, ag=0.45),
            message("fit.beta_undetermined"),
        ],
    ),
)


def _rows(note=NOTE):
    row = {
        "id": "T1",
        "name": "first",
        "lat_deg": 41.0,
        "lon_deg": 14.4,
        "soil_class": "C",
        "soil_class_source": "default",
        "fragility_median_g": 0.45,
        "fragility_beta": math.nan,
        "safety_index": 0.7,
        "risk_class": "moderate",
        **note_columns(note),
    }
    return [row]


def _page(path, lang):
    page = render_html(report_model(path), lang)
    head = '<script id="report-data" type="application/json">'
    start = page.index(head) + len(head)
    return json.loads(page[start : page.index("</script>", start)])


@pytest.fixture
def assess_archive(tmp_path):
    path = tmp_path / "assess.h5"
    write_risk_archive(path, "assess", {"summary": _rows()}, {"command_line": "test"})
    return path


def test_the_english_note_is_the_codes_rendered():
    row = _rows()[0]
    assert row["note"] == (
        "knowledge level LC1 (F_C = 1.35 divides the SLV capacity) assumed: not in the inventory "
        "(--knowledge-level); assumed soil_class=C (default), nominal_life_y=50.0 (default); "
        "collapse fit: no record overturned the tower; 7 of 7 records stand at 0.45 g, the "
        "smallest censoring intensity: the median is above it (lower bound); beta undetermined"
    )
    assert loads(row["note_codes"]) == NOTE


def test_note_codes_round_trip_through_the_assess_and_scenario_archives(tmp_path):
    for kind in ("assess", "scenario"):
        path = tmp_path / f"{kind}.h5"
        rows = _rows()
        if kind == "scenario":
            rows[0].pop("soil_class_source")
            rows[0].pop("safety_index")
        write_risk_archive(path, kind, {"summary": rows}, {"command_line": "test"})
        (row,) = read_summary(path, kind)
        assert loads(row["note_codes"]) == NOTE
        assert row["note"] == render_all(NOTE)


def test_the_italian_page_renders_the_note_from_its_codes(assess_archive):
    italian = _page(assess_archive, "it")
    note = italian["towers"][0]["note"]
    assert note == render_all(NOTE, "it")
    assert note.startswith("livello di conoscenza LC1 (F_C = 1,35 divide la capacità allo SLV)")
    assert "ipotizzati soil_class=C (predefinito), nominal_life_y=50,0 (predefinito)" in note
    assert (
        "stima al collasso: nessun accelerogramma ha ribaltato la torre; 7 accelerogrammi" in note
    )
    assert "knowledge level" not in note and "collapse fit" not in note
    assert italian["sheets"]["T1"]["notes"] == [note]
    assert "note_codes" not in italian["towers"][0]  # rendered, not shipped to the page
    english = _page(assess_archive, "en")
    assert english["towers"][0]["note"] == render_all(NOTE)


def test_a_note_code_missing_from_the_catalogue_fails_the_page(assess_archive):
    """Never a silent English clause: an unknown code stops the report, naming the code."""
    # format 4 stores the note one message a row (/messages): its last code is replaced
    with h5py.File(assess_archive, "r+") as f:
        messages = f["messages"]
        codes = list(read_column(messages["code"], assess_archive, "messages/code"))
        assert codes == [m.code for m in NOTE]
        codes[-1] = "no.such.note"
        del messages["code"]
        write_column(messages, "code", codes, "")
    for lang in ("it", "en"):
        with pytest.raises(ReportError, match="no.such.note"):
            render_html(report_model(assess_archive), lang)


def test_an_archive_without_note_codes_reads_through_the_adapter(tmp_path):
    """An archive written before the codes: its English note, translated clause by clause."""
    row = _rows()[0]
    del row["note_codes"]
    row["note"] = "no coordinates: the site hazard is unknown, the tower is not assessed"
    path = tmp_path / "older.h5"
    write_risk_archive(path, "assess", {"summary": [row]}, {"command_line": "test"})
    assert "note_codes" not in read_summary(path, "assess")[0]
    italian = _page(path, "it")
    assert italian["towers"][0]["note"] == (
        "nessuna coordinata: la pericolosità del sito è ignota, la torre non è valutata"
    )


def test_the_csv_exports_the_note_and_its_codes():
    text = summary_csv_text(_rows())
    header, line = text.splitlines()[:2]
    assert "note" in header.split(",") and "note_codes" in header.split(",")
    assert "collapse fit: no record overturned the tower" in line


def test_note_codes_round_trip_through_the_run_archive(tmp_path, write_archive):
    from rockscreen.pipeline.archive.reader import read_summary as read_run_summary

    path = tmp_path / "run.h5"
    write_archive(path, 3, chunk_size=2)
    rows = read_run_summary(path)
    assert len(rows) == 3
    for row in rows:
        said = loads(row["note_codes"])
        assert render_all(said) == row["note"]
    italian = _page(path, "it")
    for tower, row in zip(italian["towers"], rows, strict=True):
        assert tower["note"] == render_all(loads(row["note_codes"]), "it")


def test_the_run_note_says_the_safety_factors_limit():
    from rockscreen.pipeline.screening.evaluate import summary_note

    summary = {
        "safety_factor": math.inf,
        "safety_factor_lower": 3.0,
        "safety_factor_limit": "cap",
        "overturned": False,
        "pairing": "every station: the tower has no coordinates",
        "lat_deg": math.nan,
        "lon_deg": math.nan,
    }
    said = summary_note(summary, [message("run.record_flagged", record="XX.A", flag="clipped")])
    assert render_all(said) == (
        "record XX.A flagged: clipped; no overturning up to the search cap 3.00; paired with "
        "every station: the tower has no coordinates"
    )
    assert render_all(said, "it") == (
        "registrazione XX.A segnalata: clipped; nessun ribaltamento fino al limite della "
        "ricerca 3,00; abbinata a tutte le stazioni: la torre non ha coordinate"
    )


def test_a_scenario_note_holds_the_assessments_note_as_codes():
    """No fragility: the assessment's own messages inside the scenario's, in every language."""
    from types import SimpleNamespace

    from rockscreen.pipeline.risk.scenario.probability import tower_scenario

    grid = SimpleNamespace(at=lambda lon, lat: (0.2, 0.5), sigma_source="STDPGA of g.xml")
    row = {
        "id": "T1",
        "lat_deg": 41.0,
        "lon_deg": 14.4,
        "soil_class": "C",
        "tr_slv_y": 712.0,
        "collapse_median_g": math.nan,
        "collapse_beta": math.nan,
        "collapse_bound": "",
        **note_columns([message("site.hazard_failed", error="off the grid")]),
    }
    out = tower_scenario(row, grid)
    assert out["status"] == "no_fragility"
    assert out["note"] == "no fragility: site hazard: off the grid"
    (said,) = loads(out["note_codes"])
    assert said.render("it") == "nessuna fragilità: pericolosità del sito: off the grid"
    older = {k: v for k, v in row.items() if k != "note_codes"}  # an archive before codes
    assert tower_scenario(older, grid)["note"] == (
        "no fragility (the assessment archive's note says why)"
    )
    unassessed = {**row, **note_columns(())}
    assert tower_scenario(unassessed, grid)["note"] == "no fragility: not assessed"
