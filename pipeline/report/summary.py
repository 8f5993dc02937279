"""The per-tower summary of a record-based run as text: ranked table, notes and legend.

Used by ``rockscreen run`` and ``rockscreen inspect``; everything that comes from the
inventory or the records goes through :func:`rockscreen.pipeline.text.printable`, so a crafted id
cannot send control sequences to the terminal.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence

from rockscreen.pipeline.report.risk_summary import table_lines
from rockscreen.pipeline.report.values import Row, RowT
from rockscreen.pipeline.text import printable
from rockscreen.pipeline.verdict.messages import masked, note_messages

#: Order of the risk classes in the summary table (riskiest first).
CLASS_RANK = {"collapse": 0, "high": 1, "moderate": 2, "low": 3, "none": 4, "unknown": 5}

#: What the summary's columns and classes mean (printed under the table).
LEGEND = (
    "risk classes (record-based, thresholds in docs/campaign.md): collapse = overturned under "
    "a paired record; high = theta_max/alpha >= 0.5 or safety factor < 1.5; moderate = "
    "theta_max/alpha >= 0.2 or safety factor < 2.5; low = rocked (theta_max/alpha >= 0.01); "
    "none = did not rock; unknown = no case could be solved.",
    "safety factor: smallest scale factor of the governing record that overturns the tower "
    "(inf: none up to the search limit, which the 'limit' column names: cap, or vertical = "
    "the scaled vertical reaches -g, where the rigid-block model stops holding).",
    "components: X along the tower's width axis (its azimuth), Y 90 deg clockwise from it; "
    "otherwise the recorded channel (E, N, ...). theta: rotation of the tower [rad]; alpha: "
    "its slenderness angle [rad].",
)

_LIMIT_LABEL = {"overturning": "overturn", "vertical_limit": "vertical", "cap": "cap", "": "-"}


def _float(row: Row, key: str) -> float:
    value = row.get(key, math.nan)
    try:
        return float(value)
    except (TypeError, ValueError):
        return math.nan


def rank_towers(rows: Sequence[RowT]) -> list[RowT]:
    """Sort summary rows riskiest first: class, then safety factor, then theta_max/alpha.

    Parameters
    ----------
    rows : sequence of mapping
        Summary rows (:func:`rockscreen.pipeline.archive.campaign.read_summary`).

    Returns
    -------
    list of mapping
    """

    def key(row: Row) -> tuple[int, float, float, str]:
        sf = _float(row, "safety_factor")
        ratio = _float(row, "theta_max_over_alpha")
        return (
            CLASS_RANK.get(row["risk_class"], 9),
            math.inf if math.isnan(sf) else sf,
            -(ratio if not math.isnan(ratio) else -math.inf),
            str(row["id"]),
        )

    return sorted(rows, key=key)


def _number(value: float, digits: int = 3) -> str:
    if math.isnan(value):
        return "-"
    if math.isinf(value):
        return "inf"
    return f"{value:.{digits}f}"


def summary_lines(rows: Sequence[Row]) -> list[str]:
    """Return the summary table (riskiest first, units in the headers) as text lines."""
    header = (
        "tower",
        "risk",
        "theta_max/alpha [-]",
        "theta_max [rad]",
        "safety_factor [-]",
        "limit",
        "overturned",
        "governing record",
        "model",
        "pairing [km]",
    )
    body = []
    for row in rank_towers(rows):
        body.append(
            (
                printable(str(row["id"])),
                row["risk_class"],
                _number(_float(row, "theta_max_over_alpha")),
                _number(_float(row, "theta_max_rad"), 4),
                _number(_float(row, "safety_factor"), 2),
                _LIMIT_LABEL.get(str(row.get("safety_factor_limit", "")), "-"),
                "yes" if row["overturned"] else "no",
                printable(str(row["governing_record"] or "-")),
                row["governing_model"] or "-",
                _pairing_cell(row),
            )
        )
    return table_lines(header, body)


def _pairing_cell(row: Row) -> str:
    distance = _float(row, "pairing_distance_km")
    pairing = str(row.get("pairing", ""))
    if pairing.startswith("every station"):
        return "all stations"
    return _number(distance, 1)


#: A number standing alone in a note stored as text only (an archive written before the
#: note's codes; not inside a code such as ``IV.T0501``).
_NUMBER = re.compile(r"(?<![\w.])-?\d+(?:\.\d+)?(?![\w])")
#: Ids listed in a grouped note line before "and N more".
_MAX_IDS = 6


def _ids(items: list[str]) -> str:
    shown = ", ".join(items[:_MAX_IDS])
    return shown + (f" and {len(items) - _MAX_IDS} more" if len(items) > _MAX_IDS else "")


def _note_parts(row: Row) -> list[tuple[str, str, list[str]]]:
    """Return a row's note as parts: (text, text with its numbers as ``#``, the numbers).

    From the note's codes, one part per message, its parameters' numbers masked
    (:func:`rockscreen.pipeline.verdict.messages.masked`). An archive written before the
    codes: its text split at ``"; "``, the numbers found in the words.
    """
    said = note_messages(row)
    if said is not None:
        out = []
        for m in said:
            template, numbers = masked(m)
            out.append((printable(m.render()), printable(template), numbers))
        return out
    note = str(row.get("note") or "")
    parts = [printable(part) for part in note.split("; ")] if note else []
    return [(part, _NUMBER.sub("#", part), _NUMBER.findall(part)) for part in parts]


def note_lines(rows: Sequence[Row]) -> list[str]:
    """Return the towers' notes (why their verdicts read so), identical notes grouped.

    A tower's note is one or more parts (its messages, :mod:`rockscreen.pipeline.verdict`).
    Parts that read the same but for their numbers are one line for all the towers that
    carry them: the towers' count, the text (numbers as ``#`` where they differ) and the
    towers with their numbers, e.g. ``" 13 towers: safety factor >= #: the search stopped
    ... (ARC-02 6.20, ...)"``. A part only one tower carries is ``" ID: text"`` as before.
    Lines come in the order of the ranked table.

    Parameters
    ----------
    rows : sequence of mapping
        Summary rows (with ``id``, ``note`` and, from archives that store them,
        ``note_codes``).

    Returns
    -------
    list of str
        One line per distinct note, each starting with a space.
    """
    groups: dict[str, list[tuple[str, str, list[str]]]] = {}
    for row in rank_towers(rows):
        tower = printable(str(row["id"]))
        for part, template, numbers in _note_parts(row):
            groups.setdefault(template, []).append((tower, part, numbers))
    lines = []
    for template, members in groups.items():
        if len(members) == 1:
            tower, part, _ = members[0]
            lines.append(f" {tower}: {part}")
            continue
        towers = [tower for tower, _, _ in members]
        if len({part for _, part, _ in members}) == 1:
            lines.append(f" {len(members)} towers: {members[0][1]} ({_ids(towers)})")
            continue
        labelled = [f"{tower} {' '.join(numbers)}" for tower, _, numbers in members]
        lines.append(f" {len(members)} towers: {template} ({_ids(labelled)})")
    return lines
