"""A pre-event assessment from an inventory to its archive (``rockscreen assess``).

:func:`assess_to_archive` opens the executor (local processes or a Dask cluster, chosen by
:func:`rockscreen.pipeline.execution.choose.open_executor`), runs
the multiple-stripe assessment (:func:`rockscreen.pipeline.risk.assess.run.run_assess`) and writes
the assess archive with the resolved inputs. The command line only parses options and prints.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import shlex
import sys
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from rockscreen.pipeline import __version__
from rockscreen.pipeline.archive.assess_part import AssessJournal, suite_digest
from rockscreen.pipeline.archive.kept_rows import JournalRows, JournalSummary
from rockscreen.pipeline.archive.risk_archive import write_risk_archive
from rockscreen.pipeline.archive.risk_schema import assess_tables
from rockscreen.pipeline.execution.job import Job
from rockscreen.pipeline.hazard.suite import DEFAULT_SUITE_KIND, default_n_records
from rockscreen.pipeline.risk.assess.pool_samples import stored_samples
from rockscreen.pipeline.risk.assess.run import AssessOptions, AssessResult, run_assess
from rockscreen.pipeline.risk.assess.screening_risk import RISK_METHODS
from rockscreen.pipeline.risk.checks.governing import check_columns
from rockscreen.pipeline.risk.checks.knowledge import check_measured_strengths
from rockscreen.pipeline.risk.uncertainty.priors import RegionPriors
from rockscreen.stations.inventory_table import inventory_table

__all__ = [
    "EMBEDDED_SUITE_LABELS",
    "AssessInputs",
    "assess_inputs",
    "assess_to_archive",
    "inventory_failures",
    "record_arrays",
    "risk_metadata",
]

#: Root attributes of the assess archive that differ between two runs of the same inputs
#: (an interrupted and resumed run against an uninterrupted one): when and how long.
RUN_ATTRIBUTES = ("created_utc", "elapsed_s")

#: What the x and y record components stand for (stored with the archive).
COMPONENTS_RULE = (
    "record x along the tower's x axis (width_m), y along its y axis (plan depth); the "
    "azimuth is not used (suite records carry no orientation)"
)


#: What the archive says the embedded suites are (``suite_source``), by kind.
EMBEDDED_SUITE_LABELS = {
    "stochastic": "embedded stochastic suite (rockscreen.pipeline.hazard.stochastic_suite: "
    "Rezaeian & Der Kiureghian 2010 records with velocity pulses, selected and scaled, "
    "never matched)",
    "matched": "embedded matched suite (rockscreen.pipeline.hazard.suite: spectrum-matched "
    "synthetic records)",
}


@dataclass(frozen=True)
class AssessInputs:
    """Where an assessment's towers and records come from (stored with the archive)."""

    #: Where the towers came from.
    inventory: Path
    #: The user's records (list of SuiteRecord); None = the embedded suite of
    #: ``AssessOptions.selection["kind"]`` (stochastic by default).
    suite: Any = None
    #: What the suite is, for the archive and messages.
    suite_label: str = EMBEDDED_SUITE_LABELS["stochastic"]
    #: Seed of the embedded suite.
    seed: int = 0
    #: Inventory rows not read (``--skip-invalid``): ``/failures`` rows of kind
    #: ``inventory`` (:func:`inventory_failures`), listed before the towers' own.
    skipped_rows: tuple[dict[str, Any], ...] = ()


def inventory_failures(invalid: Sequence[Any]) -> tuple[dict[str, Any], ...]:
    """Return the ``/failures`` rows of an inventory's invalid rows (kind ``inventory``).

    Parameters
    ----------
    invalid : sequence of rockscreen.stations.inventory.InvalidRow
        :attr:`rockscreen.stations.inventory.InventoryRows.invalid`.

    Returns
    -------
    tuple of dict
        ``kind`` ``"inventory"``, ``subject`` the tower id as written (``"row N"`` when the
        row has none), ``reason`` the row, line, column, value and rule, and that the tower
        was skipped.
    """
    return tuple(
        {
            "kind": "inventory",
            "subject": bad.tower_id or f"row {bad.row}",
            "reason": f"{bad.detail}; skipped (--skip-invalid): fix the row and rerun",
        }
        for bad in invalid
    )


def record_arrays(records: dict[str, Any]) -> dict[str, dict[str, Any]]:
    """Return the records of an assessment as the archive stores them (``/records``).

    Parameters
    ----------
    records : dict
        Record id -> :class:`rockscreen.pipeline.hazard.selection.SuiteRecord`
        (:attr:`rockscreen.pipeline.risk.assess.run.AssessResult.records`).

    Returns
    -------
    dict
        Record id -> ``{"x", "y", "z"}`` [m/s²] (None when absent; a pool record's
        float32 samples: :func:`~rockscreen.pipeline.risk.assess.pool_samples.
        stored_samples`), ``"dt_s"`` [s], ``"name"``, ``"source"``: the ``records`` argument of
        :func:`rockscreen.pipeline.archive.risk_archive.write_risk_archive`.
    """
    out = {}
    for rid, r in records.items():
        x, y, z = stored_samples(r)  # a pool record's float32 views: no float64 copy
        out[rid] = {"x": x, "y": y, "z": z, "dt_s": r.dt_s, "name": r.name, "source": r.source}
    return out


def _flat(value: Any, prefix: str = "") -> dict[str, Any]:
    """Return a dataclass or dict as one level of JSON-ready ``dotted.name -> value``."""
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        value = {f.name: getattr(value, f.name) for f in dataclasses.fields(value)}
    if isinstance(value, dict):
        out: dict[str, Any] = {}
        for key in sorted(value, key=str):
            out.update(_flat(value[key], f"{prefix}{key}."))
        return out
    if isinstance(value, (tuple, list)):
        value = [json.loads(json.dumps(v, default=str)) for v in value]
    elif not isinstance(value, (str, int, float, bool, type(None))):
        value = str(value)
    return {prefix.rstrip("."): value}


def _towers_digest(towers: Sequence[Any]) -> str:
    """Return the SHA-256 of the towers as read (every field, in inventory order)."""
    rows = [_flat(t) if dataclasses.is_dataclass(t) else {"repr": repr(t)} for t in towers]
    text = json.dumps(rows, sort_keys=True, default=str, allow_nan=True)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def assess_inputs(
    options: AssessOptions, inputs: AssessInputs, towers: Sequence[Any] = ()
) -> dict[str, Any]:
    """Return what determines an assessment's tower results, for its work file.

    Parameters
    ----------
    options : AssessOptions
    inputs : AssessInputs
    towers : sequence of rockscreen.stations.inventory.Tower
        The towers as read from the inventory.

    Returns
    -------
    dict
        ``rockscreen_version``; ``inventory`` and ``suite``, each its ``source`` (shown in
        messages, not fingerprinted) and the SHA-256 of its content (every field of every
        tower as read, in order; the suite records' names, time steps and samples;
        ``"embedded"`` for the embedded synthetic suite, which the seed option determines);
        ``options``, every resolved option by dotted name
        (:func:`rockscreen.pipeline.archive.assess_part.inputs_fingerprint`).
    """
    suite = inputs.suite
    if suite is None:
        suite_hash = "embedded"
    else:
        suite_hash = suite_digest(
            (r.name, float(r.dt_s), (r.acc_x_m_s2, r.acc_y_m_s2, r.acc_z_m_s2)) for r in suite
        )
    return {
        "rockscreen_version": __version__,
        "inventory": {"source": str(inputs.inventory), "sha256": _towers_digest(towers)},
        "suite": {"source": inputs.suite_label, "sha256": suite_hash},
        "options": {
            **_flat(options),
            "return_periods_resolved": list(options.resolved_return_periods()),
            "seed_of_suite": inputs.seed,
        },
    }


def _metadata(
    inputs: AssessInputs, options: AssessOptions, result: AssessResult, elapsed: float
) -> dict[str, Any]:
    """Return the root attributes of the assess archive (the resolved inputs)."""
    kind = options.selection.get("kind", DEFAULT_SUITE_KIND)
    return {
        "command_line": shlex.join(["rockscreen", *sys.argv[1:]]),
        "inventory_source": str(inputs.inventory),
        "suite_source": inputs.suite_label,
        "return_periods_y": list(options.resolved_return_periods()),
        "suite_kind": "" if inputs.suite is not None else kind,
        "n_records_per_stripe": options.selection.get("n_records")
        or default_n_records(inputs.suite, kind),
        "models": list(options.stripe.models),
        "damage_levels": list(options.stripe.damage_levels),
        "site_resolution_deg": options.site_resolution_deg,
        "class_limits": list(options.class_limits),
        "scale_limits": list(options.selection.get("scale_limits", ())),
        "allow_noncompliant": bool(options.allow_noncompliant),
        "knowledge_level": options.knowledge_level or "",
        "bootstrap_resamples": options.bootstrap_resamples,
        "ida_record_set": "the site's set at each tower's T_R,SLV; scale 1 = ag(T_R,SLV)",
        "ida_cap_pga_g": options.ida_options().cap_pga_g,
        "ida_ratio": options.ida_options().ratio,
        "ida_tolerance": options.ida_options().tolerance,
        "slv_theta_ratio": options.ida_options().slv_theta_ratio,
        "basis_compliant": all(row.get("basis_compliant", True) for row in result.summary),
        "seed": inputs.seed,
        "components": COMPONENTS_RULE,
        "n_solves": result.n_solves,
        "n_sites": result.n_sites,
        "elapsed_s": round(elapsed, 3),
        **risk_metadata(options, result),
    }


def risk_metadata(options: AssessOptions, result: AssessResult) -> dict[str, Any]:
    """Return the root attributes that say how the screening risk was computed.

    ``risk_priors_source`` (the priors file's name or ``default``), ``risk_seed``,
    ``risk_samples``, ``risk_methods`` (what was computed, ``belfry_sampled`` when a row
    without the belfry columns samples one; none when the risk was not) and
    ``risk_top_n`` (N of ``/risk_top_n``).
    """
    risk = options.risk
    methods = list(RISK_METHODS) if risk.enabled else []
    if methods and (risk.region or RegionPriors()).belfry is not None:
        methods.append("belfry_sampled")  # rows without belfry columns sample one
    return {
        "risk_priors_source": risk.priors_source,
        "risk_seed": options.seed,
        "risk_samples": int(risk.samples) if risk.enabled else 0,
        "risk_methods": methods,
        "risk_top_n": result.risk.top_n,
    }


def assess_to_archive(
    towers: Sequence[Any],
    options: AssessOptions,
    out_path: str | Path,
    inputs: AssessInputs,
    *,
    scheduler: str | None = None,
    jobs: int | None = None,
    notify: Callable[[str], None] = lambda text: None,
    discard_other: bool = False,
) -> AssessResult:
    """Assess every tower and write the assess archive, resuming ``OUT.part``.

    Finished towers are kept in the work file ``OUT.part``
    (:class:`rockscreen.pipeline.archive.assess_part.AssessJournal`) as they come; the same
    command after an interruption computes only the others, and the archive is the same
    as an uninterrupted run's but for :data:`RUN_ATTRIBUTES`. The archive keeps the
    towers as read (``/inventory``, the run archive's columns and units).

    Parameters
    ----------
    towers : sequence of rockscreen.stations.inventory.Tower
    options : AssessOptions
        Return periods, stripe options, record selection, site resolution, class limits.
    out_path : str or Path
        The archive (written atomically).
    inputs : AssessInputs
        The inventory file and the record suite (stored).
    scheduler, jobs : optional
        A Dask scheduler address, or the number of local worker processes.
    notify : callable
        Called with each progress message.
    discard_other : bool
        Discard a work file of other inputs (``--overwrite``) instead of refusing.

    Returns
    -------
    AssessResult

    Raises
    ------
    ArchiveError
        When ``OUT.part`` holds towers of other inputs (and not ``discard_other``): the
        differences named, the file kept.
    Interrupted
        On Ctrl-C, SIGTERM or SIGHUP: the towers finished so far are kept in ``OUT.part``.
    RiskError
        Before the work file is opened, for a measured ``masonry_strength_mpa`` on a tower
        assessed at LC1 or LC2
        (:func:`rockscreen.pipeline.risk.checks.knowledge.check_measured_strengths`).
    """
    check_measured_strengths(towers, options.knowledge_level)
    with Job(notify, jobs=jobs, scheduler=scheduler, verb="assessed") as job:
        fingerprinted = assess_inputs(options, inputs, towers)
        journal = job.keep(
            AssessJournal(out_path, fingerprinted, discard_other=discard_other), len(towers)
        )
        notify(
            f"assessing {len(towers)} tower(s) of {inputs.inventory} with the "
            f"{inputs.suite_label}, {job.workers} worker(s)"
        )
        start = time.perf_counter()
        with job.running():
            result = run_assess(
                towers,
                options,
                job.executor,
                suite=inputs.suite,
                jobs=job.workers,
                progress=notify,
                journal=journal,
            )
    elapsed = time.perf_counter() - start
    result.failures[:0] = [dict(row) for row in inputs.skipped_rows]
    _write_archive(out_path, towers, options, inputs, result, elapsed)
    for table in (result.summary, result.stripes, result.outcomes, result.ida):
        if isinstance(table, (JournalRows, JournalSummary)):  # read from the archive now
            table.moved_to(out_path)
    journal.remove()
    notify(
        f"{len(towers)} tower(s), {result.n_sites} site(s), {result.n_solves} solves in "
        f"{elapsed:.1f} s; archive written to {out_path}"
    )
    return result


def _write_archive(
    out_path: str | Path,
    towers: Sequence[Any],
    options: AssessOptions,
    inputs: AssessInputs,
    result: AssessResult,
    elapsed: float,
) -> None:
    """Write the assess archive: the result's tables, the resolved inputs, records and towers.

    Parameters
    ----------
    out_path : str or Path
        The archive (written atomically).
    towers : sequence of rockscreen.stations.inventory.Tower
        The towers as read (``/inventory``).
    options : AssessOptions
    inputs : AssessInputs
    result : AssessResult
        The finished assessment, its ``failures`` including the skipped inventory rows.
    elapsed : float
        Wall time of the assessment [s].
    """
    tables = {
        "summary": result.summary,
        "stripes": result.stripes,
        "outcomes": result.outcomes,
        "selection": result.selection,
        "failures": result.failures,
        "ida": result.ida,
        "risk_fragility": result.risk.fragility,  # a RowTable: written by column
        "risk_sensitivity": result.risk.sensitivity,
        "risk_top_n": list(result.risk.top_n_rows),
    }
    tables_of = assess_tables()
    write_risk_archive(
        out_path,
        "assess",
        tables,
        _metadata(inputs, options, result, elapsed),
        empty_columns={
            "failures": ("kind", "subject", "reason"),
            **{
                name: tuple(tables_of[name])
                for name in ("ida", "risk_fragility", "risk_sensitivity", "risk_top_n")
            },
        },
        records=record_arrays(result.records),
        set_records=result.set_records,
        # The towers as read: a resumed run re-reads them, and its work file's fingerprint
        # (the inventory's content) refused other ones, so both write the same /inventory.
        inventory=inventory_table(towers),
        checks=check_columns(),
    )
