"""Identical notes of many towers are one line, not one line per tower (issue 24)."""

from __future__ import annotations

from rockscreen.pipeline.report.summary import note_lines

VERTICAL = (
    "safety factor >= {:.2f}: the search stopped where the scaled vertical acceleration "
    "reaches -g, the rigid-block model's validity limit, not at overturning"
)


def _row(tower: str, note: str) -> dict:
    return {"id": tower, "note": note, "risk_class": "low", "safety_factor": 9.0}


def test_thirteen_vertical_limit_notes_are_one_line():
    rows = [_row(f"T{i:02d}", VERTICAL.format(2 + i / 10)) for i in range(13)]
    rows.append(_row("LONE", "no overturning up to the search cap 10.00"))
    lines = note_lines(rows)
    assert len(lines) == 2
    grouped = next(line for line in lines if "13 towers" in line)
    assert "safety factor >= #" in grouped and "validity limit" in grouped
    assert "T00 2.00" in grouped and "and 7 more" in grouped
    assert " LONE: no overturning up to the search cap 10.00" in lines


def test_identical_notes_list_their_towers_and_parts_are_grouped_apart():
    cap = "no overturning up to the search cap 10.00"
    rows = [_row("A", cap), _row("B", cap + "; paired with every station: IV.T0501")]
    lines = note_lines(rows)
    assert " 2 towers: no overturning up to the search cap 10.00 (A, B)" in lines
    assert " B: paired with every station: IV.T0501" in lines


def test_a_single_note_reads_as_before():
    assert note_lines([_row("A", "x 1.5")]) == [" A: x 1.5"]


def test_notes_from_codes_group_by_message_their_numbers_listed():
    from rockscreen.pipeline.verdict.messages import message, note_columns

    def coded(tower, *said):
        return {"id": tower, "risk_class": "low", "safety_factor": 9.0, **note_columns(said)}

    period = [message("kinematic.tower_period", period=p) for p in (0.26, 0.41, 0.26)]
    fit = message(
        "fit.collapse",
        notes=[
            message("fit.none", event=message("fit.event_overturned")),
            message("fit.beta_undetermined"),
        ],
    )
    rows = [coded("A", period[0], fit), coded("B", period[1], fit), coded("C", period[2])]
    lines = note_lines(rows)
    # the literal 0.0187 of the template is not a tower's number; the fit's clauses one part
    assert (
        " 3 towers: tower period 0.0187 H = # s assumed (no shaft_period_s) "
        "(A 0.26, B 0.41, C 0.26)" in lines
    )
    assert (
        " 2 towers: collapse fit: no record overturned the tower; beta undetermined (A, B)" in lines
    )
    assert len(lines) == 2
