"""The work of ``assess``'s workers: a site's record set, or a chunk of towers of one site.

A chunk's towers each get their stripes, IDA, summary row and screening risk
(``docs/risk.md``).

:func:`work` is the executor's work function (:func:`rockscreen.pipeline.risk.assess.run.
run_assess` starts the executor with it and a :class:`WorkerInputs`); the main process alone
collects what it returns and writes the archive.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any

from rockscreen.pipeline.engine.cases import BlockCache
from rockscreen.pipeline.hazard.suite import site_record_set
from rockscreen.pipeline.risk.assess.options import AssessOptions
from rockscreen.pipeline.risk.assess.record_sets import failed_set
from rockscreen.pipeline.risk.assess.screening_risk import risk_item
from rockscreen.pipeline.risk.assess.sites import TowerSite
from rockscreen.pipeline.risk.assess.stripes import evaluate_stripe
from rockscreen.pipeline.risk.assess.tower_ida import tower_ida
from rockscreen.pipeline.risk.assess.tower_summary import summarize_tower
from rockscreen.pipeline.risk.checks.tower_checks import part_models
from rockscreen.stations.errors import RockscreenError

__all__ = ["WorkerInputs", "isolated_tower_work", "record_set_task", "tower_work", "work"]


@dataclass(frozen=True)
class WorkerInputs:
    """What every worker is started with: the candidate suite and the options."""

    suite: Any
    options: AssessOptions


def work(shared: WorkerInputs, chunk: tuple) -> Any:
    """Executor work function: a record-set task or a chunk of towers of one site."""
    kind = chunk[0]
    if kind == "set":
        _, key, tr = chunk
        clock = time.thread_time()
        made = record_set_task(shared, key, tr)
        return ("set", key, tr, made, time.thread_time() - clock)
    _, sets, members = chunk
    return (
        "towers",
        [isolated_tower_work(shared, site, sets, hazard) for site, hazard in members],
    )


def isolated_tower_work(
    shared: WorkerInputs, site: TowerSite, sets: dict, hazard: dict
) -> dict[str, Any]:
    """Return :func:`tower_work`'s result, or the error of a tower whose work raised.

    An unexpected exception in one tower's work is that tower's failure, not the run's:
    the result is ``{"index", "error", "n_solves": 0}``, listed in ``/failures`` (kind
    ``error``, the exception named) by :mod:`rockscreen.pipeline.risk.assess.run`; the other
    towers go on. Ctrl-C and the signals that stop a command (``BaseException``, not
    ``Exception``) still stop the run.
    """
    try:
        return tower_work(shared, site, sets, hazard)
    except Exception as exc:  # noqa: BLE001 - one tower's failure, reported, the run goes on
        said = " ".join(str(exc).split()) or "no message"
        return {"index": site.index, "error": f"{type(exc).__name__}: {said}", "n_solves": 0}


def record_set_task(shared: WorkerInputs, key: tuple, tr: float) -> Any:
    """Return the site's record set at ``tr`` [y], or a :class:`FailedSet` saying why not."""
    lon, lat, soil, topography = key
    options = dict(shared.options.selection)
    try:
        return site_record_set(lon, lat, tr, soil, topography, suite=shared.suite, **options)
    except Exception as exc:  # noqa: BLE001 - reported per site, the run goes on
        if isinstance(exc, (RockscreenError, ValueError, ArithmeticError)):
            return failed_set(key, tr, exc)
        raise


def tower_work(shared: WorkerInputs, site: TowerSite, sets: dict, hazard: dict) -> dict[str, Any]:
    """Stripes, IDA and the summary row of one tower (in the worker)."""
    options = shared.options
    stripes, outcomes, n_solves = [], [], 0
    cpu_s = {"stripes": -time.thread_time()}
    blocks = BlockCache(site.tower)
    for tr in options.resolved_return_periods():
        stripe, rows, solves = evaluate_stripe(
            site.tower, sets[tr], tr, hazard["ags"][tr], options.stripe, blocks
        )
        stripes.append(stripe)
        outcomes.extend(rows)
        n_solves += solves
    tr_slv = hazard["tr_slv"]
    cpu_s["stripes"] += time.thread_time()
    cpu_s["ida"] = -time.thread_time()
    ida, ida_solves = tower_ida(
        site.tower, sets[tr_slv], tr_slv, hazard["ag_slv"], options.ida_options(), blocks
    )
    # Each part model (the belfry, the bell gable) alone: its own fragility, beside the tower's.
    parts = {}
    for model in part_models(site.tower, options.stripe.models):
        rows, solves = tower_ida(
            site.tower,
            sets[tr_slv],
            tr_slv,
            hazard["ag_slv"],
            options.ida_options(models=(model.name,)),
            blocks,
        )
        parts[model.name] = rows
        n_solves += solves
    cpu_s["ida"] += time.thread_time()
    row = summarize_tower(
        site,
        stripes,
        hazard["curve"],
        tr_slv,
        hazard["ag_slv"],
        options.class_limits,
        ida=ida,
        knowledge_level=options.knowledge_level,
        bootstrap_resamples=options.bootstrap_resamples,
        seed=options.seed,
        parts=parts,
        fit_method=options.fit_method,
        cpu_s=cpu_s,
    )
    row["n_solves"] = n_solves + ida_solves
    row["ida_n_solves"] = ida_solves
    cpu_s["risk"] = -time.thread_time()  # the screening risk (issue 31)
    risk = risk_item(site, row, hazard["curve"], options.seed, options.risk, tuple(parts))
    cpu_s["risk"] += time.thread_time()
    return {
        "index": site.index,
        "stripes": stripes,
        "outcomes": outcomes,
        "ida": ida,
        "row": row,
        "n_solves": n_solves + ida_solves,
        **risk,
        "cpu_s": cpu_s,
    }
