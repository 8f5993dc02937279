"""What each command shows of each archive kind: the presenter registry.

The commands (``inspect``, ``plot``, ``export``, ``report``) open an archive with
:func:`rockscreen.pipeline.archive.kinds.open_archive` and ask :func:`face` for the
function of their command; none of them looks at the kind. :data:`PRESENTERS` names,
for each kind of :data:`~rockscreen.pipeline.archive.kinds.ARCHIVE_KINDS`, the function of
each command as ``"module:function"`` (imported when used, so that ``inspect`` loads no
plotting library):

- ``inspect(reader, as_json, echo)``: print the archive through ``echo`` (one call per
  line; one JSON document when ``as_json``);
- ``plot(reader, tower_id, as_map, out)``: draw the figures, return their paths;
- ``export(reader)``: the per-tower rows written as CSV or GeoJSON;
- ``report(reader)``: the HTML report model
  (:class:`~rockscreen.pipeline.report.html.model.ReportModel`).

A kind without a function for a command makes that command refuse it in one line.
"""

from __future__ import annotations

import importlib
import os
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from rockscreen.pipeline.archive.kinds import ArchiveReader
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.report.values import ColumnValue, Row, RowT
from rockscreen.pipeline.text import printable

__all__ = ["COMMANDS", "PRESENTERS", "Presenter", "face", "presenter", "summary_rows"]

#: The commands a presenter serves (the fields of :class:`Presenter` holding a function).
COMMANDS = ("inspect", "plot", "export", "report")

_REPORT = "rockscreen.pipeline.report"


@dataclass(frozen=True)
class Presenter:
    """The functions that show one archive kind (``"module:function"``, None: not shown)."""

    #: ``inspect(reader, as_json, echo)``.
    inspect: str | None
    #: ``plot(reader, tower_id, as_map, out) -> list of Path``.
    plot: str | None
    #: ``export(reader) -> list of dict`` (one row per tower).
    export: str | None
    #: ``report(reader) -> ReportModel``.
    report: str | None
    #: True when ``plot`` needs exactly one of a tower id or the map.
    plot_needs_choice: bool = False


def summary_rows(reader: ArchiveReader, order: str = "inventory") -> list[dict[str, ColumnValue]]:
    """Return the per-tower summary rows of an archive (what ``export`` writes).

    Parameters
    ----------
    reader : ArchiveReader
    order : {"inventory", "risk"}
        The inventory's order, or the riskiest first (:func:`risk_ordered`).
    """
    rows = reader.summary()
    return risk_ordered(rows) if order == "risk" else rows


def risk_ordered(rows: list[RowT]) -> list[RowT]:
    """Return summary rows riskiest first, by what the rows hold.

    A scenario (``p_overturning``): by decreasing probability, undefined last; an assess
    (``safety_index``): :func:`rockscreen.pipeline.report.risk_summary.rank_towers` (lambda_C, then
    I_S, bounds last); a run: :func:`rockscreen.pipeline.report.summary.rank_towers` (class,
    then theta/alpha). Ties keep the inventory order.
    """
    if not rows:
        return rows
    if "p_overturning" in rows[0]:

        def key(row: Row) -> float:
            p = row.get("p_overturning")
            return -p if isinstance(p, float | int) and p == p else 1.0

        return sorted(rows, key=key)
    if "safety_index" in rows[0]:
        from rockscreen.pipeline.report.risk_summary import rank_towers

        return rank_towers(rows)
    from rockscreen.pipeline.report.summary import rank_towers as rank_run

    return rank_run(rows)


#: The registry: archive kind -> its presenter. A new archive kind adds one entry.
PRESENTERS: dict[str, Presenter] = {
    "run": Presenter(
        inspect=f"{_REPORT}.run_text:inspect_run",
        plot=f"{_REPORT}.run_text:plot_run",
        export=f"{_REPORT}.presenters:summary_rows",
        report=f"{_REPORT}.html.adapters.run:run_reader_model",
        plot_needs_choice=True,
    ),
    "sweep": Presenter(
        inspect=None,
        plot=f"{_REPORT}.sweep_plots:plot_sweep_reader",
        export=None,
        report=f"{_REPORT}.html.adapters.sweep:sweep_reader_model",
    ),
    "assess": Presenter(
        inspect=f"{_REPORT}.risk_text:inspect_assess",
        plot=f"{_REPORT}.risk_text:plot_assess",
        export=f"{_REPORT}.presenters:summary_rows",
        report=f"{_REPORT}.html.adapters.risk:risk_reader_model",
        plot_needs_choice=True,
    ),
    "scenario": Presenter(
        inspect=f"{_REPORT}.risk_text:inspect_scenario",
        plot=f"{_REPORT}.risk_text:plot_scenario",
        export=f"{_REPORT}.presenters:summary_rows",
        report=f"{_REPORT}.html.adapters.risk:risk_reader_model",
    ),
}


def presenter(reader: ArchiveReader) -> Presenter:
    """Return the presenter of an archive's kind.

    Raises
    ------
    ArchiveError
        If no presenter is registered for the kind.
    """
    found = PRESENTERS.get(reader.kind)
    if found is None:
        raise ArchiveError(
            f"{printable(os.fspath(reader.path))}: no presenter for {reader.kind} archives"
        )
    return found


def face(reader: ArchiveReader, command: str) -> Callable[..., Any]:
    """Return the function of ``command`` (one of :data:`COMMANDS`) for an archive.

    Raises
    ------
    ArchiveError
        If the command does not show archives of this kind (the message names those it
        shows).
    """
    target = getattr(presenter(reader), command)
    if target is None:
        shown = [kind for kind, p in PRESENTERS.items() if getattr(p, command)]
        raise ArchiveError(
            f"{printable(os.fspath(reader.path))}: rockscreen {command} does not read "
            f"{reader.kind} archives (it reads {', '.join(shown)} archives)"
        )
    module, name = target.split(":")
    return getattr(importlib.import_module(module), name)
