"""``rockscreen assess``: per-tower fragility, annual rate of overturning and LV1 indices.

Flow (``docs/risk.md``):

1. **Sites** (:func:`tower_sites`): each tower's site is its location rounded to
   ``site_resolution_deg`` (default 0.01 deg, about 1 km; 0 keeps it exact) with its soil
   class and topography (inventory columns ``soil_class``/``topography`` when present,
   else the tower defaults of :data:`rockscreen.pipeline.hazard.TOWER_DEFAULTS`, recorded as an
   assumption). Towers sharing a site share its record sets. A tower without coordinates
   has no site hazard and is reported, not assessed.
2. **Record sets** (one task per site and return period, in parallel): the site's
   spectrum-compatible set (:func:`pipeline.hazard.site_record_set`) from the user suite or
   the embedded one (``selection["kind"]``: the stochastic suite by default, or the
   matched one), each measured against NTC 2018 §3.2.3.6/§7.3.5
   (:mod:`rockscreen.pipeline.risk.assess.compliance`). A site whose set could not be made, or
   fails the code, stops only its own towers (``/failures``); every other tower goes on.
3. **Stripes** (chunks of towers of one site, in parallel, each chunk carrying its site's
   record sets): :func:`rockscreen.pipeline.risk.assess.stripes.evaluate_stripe` at every return
   period.
4. **Per tower, in the worker** (:func:`rockscreen.pipeline.risk.assess.tower_ida.tower_ida`): the
   collapse and SLV intensity of every record of the site's set at the tower's T_R,SLV
   (incremental dynamic analysis, in the site's ag on rock); then
   :func:`rockscreen.pipeline.risk.assess.tower_summary.summarize_tower`:
   the censored lognormal fits of collapse and SLV, I_S and f_a from the SLV median
   divided by F_C, the annual rate of overturning and P(overturning in 50 years) from the
   collapse fragility, bootstrap intervals over the records, the stripe fit beside as a
   check, and the risk class; then the screening risk
   (:func:`rockscreen.pipeline.risk.assess.screening_risk.risk_item`: best estimates over the
   epistemic samples, issue 31).
5. **After all towers**: the screening risk's ranks, bands and top-N list
   (:func:`rockscreen.pipeline.risk.assess.screening_region.assess_risk`), from every
   tower's record.

The executor is chosen as for ``rockscreen run``
(:func:`rockscreen.pipeline.execution.choose.open_executor`: local processes, or Dask): the
main process alone collects results and writes the archive.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rockscreen.pipeline.archive.assess_part import READ_TOWERS
from rockscreen.pipeline.archive.kept_rows import (
    TABLE_KEYS,
    JournalRows,
    JournalSummary,
    KeptRows,
    light_result,
)
from rockscreen.pipeline.risk.assess.compliance import (
    check_record_basis,
    mark_noncompliant_row,
    noncompliance_reason,
)
from rockscreen.pipeline.risk.assess.options import AssessOptions
from rockscreen.pipeline.risk.assess.plan import (
    KeptRecords,
    References,
    hazard_of,
    locate_sites,
    record_id,
    refused_towers,
    selection_row,
    set_references,
)
from rockscreen.pipeline.risk.assess.pool_samples import forget_float64_copies
from rockscreen.pipeline.risk.assess.record_sets import is_failed
from rockscreen.pipeline.risk.assess.row_table import RowTable
from rockscreen.pipeline.risk.assess.screening_region import AssessRisk, assess_risk
from rockscreen.pipeline.risk.assess.sites import TowerSite, tower_defaults, tower_sites
from rockscreen.pipeline.risk.assess.tower_summary import base_summary_row
from rockscreen.pipeline.risk.assess.worker import WorkerInputs, work
from rockscreen.pipeline.risk.checks.knowledge import check_measured_strengths
from rockscreen.pipeline.verdict.messages import message

__all__ = [
    "AssessOptions",
    "AssessResult",
    "TowerSite",
    "record_id",
    "run_assess",
    "tower_defaults",
    "tower_sites",
]

#: Towers per chunk of the stripe phase (a chunk carries its site's record sets).
MAX_CHUNK_TOWERS = 32
#: ``/selection`` rows added to their table as one block of columns.
_SELECTION_BLOCK = 1024


# ------------------------------------------------------------------------ main side


def _compact(item: dict[str, Any]) -> dict[str, Any]:
    """Return a tower's result with its outcome rows as columns (:class:`RowTable`).

    They wait in memory until the whole assessment is written. A tower kept in the work
    file keeps neither its rows nor its summary row (read back when the archive is
    written: :class:`~rockscreen.pipeline.archive.kept_rows.JournalSummary`). A tower
    whose work raised (``error``) has no rows.
    """
    if "error" in item:
        return item
    if isinstance(item["outcomes"], KeptRows):  # kept in the work file
        return {k: v for k, v in item.items() if k != "row"}
    return {**item, "outcomes": RowTable(item["outcomes"])}


#: One tuple per distinct list of columns added to kept towers' rows.
_ADDED_KEYS: dict[tuple[str, ...], tuple[str, ...]] = {}


class _KeptRow:
    """A kept tower's summary row while it stays in the work file: what is added to it.

    The non-compliant sets it rests on (marked when it is read back) and the columns
    :func:`~rockscreen.pipeline.risk.assess.screening_region.assess_risk` adds
    (:meth:`update`, as on a row), kept as one tuple of values.
    """

    __slots__ = ("basis", "keys", "values")

    def __init__(self, basis: dict[float, Any] | None) -> None:
        self.basis = basis
        self.keys: tuple[str, ...] = ()
        self.values: tuple[Any, ...] = ()

    def update(self, columns: dict[str, Any]) -> None:
        """Add columns to the row (as :meth:`dict.update`)."""
        merged = dict(zip(self.keys, self.values, strict=True))
        merged.update(columns)
        keys = tuple(merged)
        self.keys = _ADDED_KEYS.setdefault(keys, keys)
        self.values = tuple(merged.values())

    def finish(self, row: dict[str, Any]) -> None:
        """Complete the row read back: the non-compliance mark, then the added columns."""
        if self.basis:
            mark_noncompliant_row(row, self.basis)
        row.update(zip(self.keys, self.values, strict=True))


def _summary_table(summary: dict[int, Any], journal: Any) -> Sequence[dict[str, Any]]:
    """Return the summary rows in inventory order (kept towers' read back from ``journal``)."""
    if journal is None:
        return [summary[i] for i in sorted(summary)]
    kept = {i: entry for i, entry in summary.items() if isinstance(entry, _KeptRow)}
    table = JournalSummary(journal, lambda i, row: kept[i].finish(row), READ_TOWERS)
    for i in sorted(summary):
        if i in kept:
            table.append_kept(i)
        else:
            table.append(summary[i])
    return table


# ------------------------------------------------------------------------ orchestration


@dataclass
class AssessResult:
    """Tables of an assessment, in inventory order (stripes by return period)."""

    #: Rows of ``/summary``, ``/stripes``, ``/outcomes``, ``/selection`` (a
    #: :class:`~rockscreen.pipeline.risk.assess.row_table.RowTable`), ``/failures``. With a
    #: work file, ``summary`` is a
    #: :class:`~rockscreen.pipeline.archive.kept_rows.JournalSummary`: the kept towers'
    #: rows read back a part at a time.
    summary: Sequence[dict[str, Any]]
    stripes: Sequence[dict[str, Any]]
    #: ``/outcomes`` is a :class:`~rockscreen.pipeline.risk.assess.row_table.RowTable` (columns in
    #: numpy arrays: about 200 rows per tower) that reads as dict rows. With a work file
    #: (``journal``) ``stripes``, ``outcomes`` and ``ida`` are
    #: :class:`~rockscreen.pipeline.archive.kept_rows.JournalRows`: the rows stay in the
    #: file and are read back a part at a time (the archive writer, iteration), so the main
    #: process's memory does not grow with them.
    outcomes: Sequence[dict[str, Any]]
    selection: Sequence[dict[str, Any]]
    failures: list[dict[str, Any]]
    #: Rows of ``/ida`` (tower x record x component of the set at T_R,SLV).
    ida: Sequence[dict[str, Any]] = field(default_factory=list)
    #: The records of the selected sets by id (:func:`record_id`), before their selection
    #: factor: ``/records`` of the archive, each stored once.
    records: dict[str, Any] = field(default_factory=dict)
    #: The sets as references: (``/selection`` row, record id, exact factor) per record of
    #: each set (:func:`~rockscreen.pipeline.risk.assess.plan.set_references`), kept by
    #: column (:class:`~rockscreen.pipeline.risk.assess.plan.References`):
    #: ``/set_records`` of the archive.
    set_records: Sequence[tuple[int, str, float]] = field(default_factory=References)
    #: Solver calls made.
    n_solves: int = 0
    #: Distinct sites (record-set keys).
    n_sites: int = 0
    #: The screening risk's long tables and top-N list (:mod:`.screening_risk`).
    risk: AssessRisk = field(default_factory=lambda: AssessRisk((), (), (), 0))
    #: CPU time of the work computed in this run [s], summed over the workers' threads:
    #: ``record_sets``, ``stripes`` and ``ida`` (the solves), ``fits``, ``checks``, ``risk``
    #: (the screening risk) (not the towers kept in a work file; the benchmark's CPU split).
    cpu_s: dict[str, float] = field(default_factory=dict)


def run_assess(
    towers: Sequence[Any],
    options: AssessOptions,
    executor: Any,
    *,
    suite: Any = None,
    jobs: int = 1,
    progress: Callable[[str], None] | None = None,
    journal: Any = None,
    record_sets: dict[tuple, Any] | None = None,
) -> AssessResult:
    """Assess every tower of an inventory (module docstring).

    Parameters
    ----------
    towers : sequence of rockscreen.stations.inventory.Tower
    options : AssessOptions
    executor : executor
        :func:`rockscreen.pipeline.execution.choose.open_executor`'s executor (not started).
    suite : sequence of SuiteRecord, optional
        Candidate records; None = the embedded suite (``options.selection["kind"]``).
    jobs : int
        Workers (sizes the chunks).
    progress : callable, optional
        Receives one line of progress text at a time.
    journal : rockscreen.pipeline.archive.assess_part.AssessJournal, optional
        Open work file: its ``done`` towers (by inventory index) are not computed again,
        every finished chunk is appended to it (committed and flushed) before it counts,
        and every tower's result is the one it reads back.
    record_sets : dict, optional
        Record sets to take instead of selecting them: (lon [deg], lat [deg], soil class,
        topography, return period [y]) -> RecordSet, e.g. an archive's sets
        (:func:`rockscreen.pipeline.risk.assess.archived_sets.archived_record_sets`), so that a
        rerun reproduces its verdicts; a site and return period not in it is selected as
        usual.

    Returns
    -------
    AssessResult

    Raises
    ------
    RiskError
        Before any work, for a measured ``masonry_strength_mpa`` on a tower assessed at LC1
        or LC2
        (:func:`rockscreen.pipeline.risk.checks.knowledge.check_measured_strengths`); and
        before any solve when every located tower rests on a record set that fails NTC 2018
        §3.2.3.6/§7.3.5 and ``allow_noncompliant`` is False (nothing left to assess).
        Otherwise such towers are listed in ``failures`` (kind ``compliance``, the measured
        values and the fix: :func:`rockscreen.pipeline.risk.assess.compliance.noncompliance_reason`)
        and every other tower is assessed.
    """
    check_measured_strengths(towers, options.knowledge_level)
    say = progress or (lambda text: None)
    trs = options.resolved_return_periods()
    sites = tower_sites(towers, options.site_resolution_deg)
    located = locate_sites(sites, trs)
    hazards, groups = located.hazards, located.groups
    # The stripes' return periods and, per site, the T_R,SLV of its towers (the IDA's set).
    set_trs = {
        key: sorted(set(trs) | {hazard_of(hazards, site)["tr_slv"] for site in members})
        for key, members in groups.items()
    }
    shared = WorkerInputs(suite, options)
    result = AssessResult([], [], RowTable(), [], located.failures, n_sites=len(groups))
    if journal is not None:  # the towers' tables stay in the work file until written
        result.stripes, result.outcomes, result.ida = (
            JournalRows(journal, table) for table in TABLE_KEYS
        )
    kept = KeptRecords()  # each record once in this process, whatever the sets
    with executor as ex:
        ex.start(work, shared)
        sets = _compute_sets(ex, groups, set_trs, say, result.cpu_s, record_sets or {}, kept)
        forget_float64_copies()  # the sets' pool records are kept as float32 views
        basis = check_record_basis(groups, sets, set_trs, options, say)
        refused = refused_towers(
            sites, trs, located, sets, basis, options.allow_noncompliant, options.selection
        )
        computed = {
            key: [m for m in members if m.index not in refused] for key, members in groups.items()
        }
        done_by_index = _compute_towers(
            ex, computed, sets, hazards, set_trs, jobs, say, result, journal
        )
    _collect_selection(result, groups, set_trs, sets, basis, kept)
    summary = located.summary
    for site in sites:
        if site.index not in summary:
            own = (*trs, hazard_of(hazards, site)["tr_slv"])
            summary[site.index] = _tower_row(
                site, own, sets, basis, refused, done_by_index, options, result
            )
    result.risk = assess_risk(
        sites, summary, done_by_index, located.hazard_or_none, options.seed, options.risk
    )
    result.summary = _summary_table(summary, journal)
    return result


def _collect_selection(
    result: AssessResult, groups: dict, set_trs: dict, sets: dict, basis: dict, kept: KeptRecords
) -> None:
    """Append every record set made to the result: rows, references and records.

    Its ``/selection`` row to ``selection``, its references to ``set_records`` and its
    records to ``records`` (each once; ``kept`` digests each record once).
    """
    selection = RowTable()  # 10 rows a tower at one site per tower: kept by column
    rows: list[dict[str, Any]] = []
    for key in groups:
        for tr in set_trs[key]:
            if not is_failed(sets[key][tr]):
                row = len(selection) + len(rows)
                rows.append(selection_row(key, tr, sets[key][tr], basis[key][tr]))
                result.set_records.extend(set_references(row, sets[key][tr], kept.id_of))
                for record in sets[key][tr].records:
                    result.records.setdefault(kept.id_of(record), record)
                if len(rows) == _SELECTION_BLOCK:
                    selection.extend(rows)
                    rows = []
    selection.extend(rows)
    result.selection = selection


def _tower_row(
    site: TowerSite,
    own: Sequence[float],
    sets: dict,
    basis: dict,
    refused: dict,
    done_by_index: dict[int, Any],
    options: AssessOptions,
    result: AssessResult,
) -> dict[str, Any]:
    """Return the summary row of a located tower; add its tables or its failure to ``result``.

    A tower whose record set at one of its return periods ``own`` (the stripes' and its
    T_R,SLV) could not be made is a ``selection`` failure, one refused for a non-compliant
    set a ``compliance`` failure; any other was assessed and its stripes, outcomes and IDA
    rows are appended.
    """
    failed = [sets[site.key][tr] for tr in own if is_failed(sets[site.key][tr])]
    if failed:
        reason = failed[0].reason_text
        result.failures.append({"kind": "selection", "subject": site.tower.id, "reason": reason})
        return base_summary_row(site, [failed[0].reason])
    if site.index in refused:
        reason = noncompliance_reason(site.key, refused[site.index], options.selection)
        detail = [
            message("records.set_problems", tr=tr, problems=c.problems)
            for tr, c, _ in refused[site.index]
        ]
        result.failures.append({"kind": "compliance", "subject": site.tower.id, "reason": reason})
        return base_summary_row(site, [message("records.not_assessed", detail=detail)])
    done = done_by_index[site.index]
    if "error" in done:
        reason = f"tower {site.tower.id}: {done['error']}"
        result.failures.append({"kind": "error", "subject": site.tower.id, "reason": reason})
        return base_summary_row(site, [message("site.tower_error", error=done["error"])])
    result.stripes.extend(done["stripes"])
    result.outcomes.extend(done["outcomes"])
    result.ida.extend(done["ida"])
    sets_basis = {tr: basis[site.key][tr] for tr in own}
    if "row" not in done:  # kept in the work file: marked when read back
        return _KeptRow(sets_basis if any(not c.compliant for c in sets_basis.values()) else None)
    row = done["row"]
    mark_noncompliant_row(row, sets_basis)
    return row


def _compute_sets(
    ex: Any, groups: dict, set_trs: dict, say: Callable, cpu_s: dict, given: dict, kept: Any
) -> dict:
    """Return every site's sets: those ``given`` (by site key and TR), the others selected.

    The workers' CPU time of the sets selected is added to ``cpu_s["record_sets"]`` [s].
    Each set's records are ``kept``'s (:class:`~.plan.KeptRecords`): one object per record.
    """
    sets: dict[tuple, dict[float, Any]] = {key: {} for key in groups}
    for key in groups:
        for tr in set_trs[key]:
            if (*key, tr) in given:
                sets[key][tr] = _kept(given[(*key, tr)], kept)
            else:
                ex.submit(("set", key, tr))
    total = sum(len(set_trs[key]) for key in groups)
    done = sum(len(sets[key]) for key in groups)
    for _, key, tr, record_set, cpu in ex.completed():
        sets[key][tr] = _kept(record_set, kept)
        cpu_s["record_sets"] = cpu_s.get("record_sets", 0.0) + cpu
        done += 1
        if done == total or done % max(1, total // 10) == 0:
            say(f"record sets: {done}/{total} (sites x return periods)")
    return sets


def _kept(record_set: Any, kept: KeptRecords) -> Any:
    """Return a set with ``kept``'s record objects (a set that failed as it is)."""
    return record_set if is_failed(record_set) else kept.kept(record_set)


def _compute_towers(
    ex, groups, sets, hazards, set_trs, jobs, say, result, journal=None
) -> dict[int, Any]:
    """Submit the towers in chunks of one site; return each tower's stripes, IDA and row.

    Towers the ``journal`` holds already are taken from it, not computed again.
    """
    kept = dict(journal.done) if journal is not None else {}
    todo = {
        key: [m for m in members if m.index not in kept]
        for key, members in groups.items()
        if not any(is_failed(sets[key][tr]) for tr in set_trs[key])
    }
    n_towers = sum(len(members) for key, members in groups.items() if key in todo)
    n_todo = sum(len(v) for v in todo.values())
    size = int(np.clip(math.ceil(n_todo / (8 * max(jobs, 1))), 1, MAX_CHUNK_TOWERS))
    for key, members in todo.items():
        for start in range(0, len(members), size):
            chunk = [(m, hazard_of(hazards, m)) for m in members[start : start + size]]
            ex.submit(("towers", sets[key], chunk))
    out: dict[int, Any] = {}
    for key in todo:
        for member in groups[key]:
            if member.index in kept:
                out[member.index] = _compact(kept[member.index])
                result.n_solves += kept[member.index]["n_solves"]
    if out:
        say(f"towers: {len(out)}/{n_towers} assessed (kept in the work file)")
    for _, towers in ex.completed():
        failed = [item for item in towers if "error" in item]  # computed again on a resume
        if journal is not None:
            towers = journal.append([item for item in towers if "error" not in item])
        for item in [*towers, *failed]:
            out[item["index"]] = _compact(light_result(item) if journal is not None else item)
            result.n_solves += item["n_solves"]
            for phase, cpu in item.get("cpu_s", {}).items():
                result.cpu_s[phase] = result.cpu_s.get(phase, 0.0) + cpu
        if len(out) == n_towers or len(out) % max(1, n_towers // 10) < len(towers):
            say(f"towers: {len(out)}/{n_towers} assessed")
    return out
