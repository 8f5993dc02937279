"""Parameter sweeps on one tower: running a study's cases on the project's solver.

The study file (:mod:`pipeline.study.study_file`) gives the grid; :func:`run_study` runs it
on the executor of every command (:func:`rockscreen.pipeline.execution.choose.open_executor`:
this process, local worker processes or a Dask cluster) and yields one :class:`CaseResult`
per case, in case order, which
:func:`rockscreen.pipeline.archive.sweep_archive.write_sweep_archive` streams into the sweep archive
and :mod:`pipeline.study.tables` formats. The names of those modules are re-exported here.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterator
from typing import Any

import numpy as np

from rockscreen.pipeline.archive.sweep_archive import HISTORY_UNITS
from rockscreen.pipeline.engine.registry import solver_model
from rockscreen.pipeline.engine.results import CaseResult
from rockscreen.pipeline.errors import ConfigError
from rockscreen.pipeline.execution.job import Job
from rockscreen.pipeline.motion.excitations import default_dt, harmonic, pulse, pulse_duration
from rockscreen.pipeline.study.study_file import (  # noqa: F401  (re-exported)
    EXCITATIONS,
    Case,
    Group,
    Study,
    Tower,
    load_study,
    parse_study,
)
from rockscreen.pipeline.units import float_or_nan
from rockscreen.solver import RockingBlock
from rockscreen.solver.paper_formulation import solve_paper_double_block

# --------------------------------------------------------------------------- running


def case_timing(case: Case) -> tuple[float, float]:
    """Return ``(duration [s], dt [s])`` of a case's excitation, defaults resolved.

    Parameters
    ----------
    case : Case
        A case of a study (``dt`` and ``duration`` may be None: the defaults).

    Returns
    -------
    tuple of float
        The duration and the sampling step the excitation is sampled with [s].
    """
    dt = default_dt(case.frequency) if case.dt is None else case.dt
    duration = case.duration
    if duration is None:  # a pulse without padding lasts one period (half for the short shapes)
        duration = pulse_duration(case.shape, case.frequency)
    return float(duration), float(dt)


def case_excitation(case: Case) -> tuple[np.ndarray, float]:
    """Sample the base acceleration of a case.

    Returns
    -------
    acc : ndarray, shape (n,)
        Acceleration [m/s^2].
    dt : float
        Sampling step [s].
    """
    if case.excitation == "harmonic":
        return harmonic(case.amplitude, case.frequency, case.duration, dt=case.dt)
    return pulse(case.shape, case.amplitude, case.frequency, dt=case.dt, duration=case.duration)


def solve_case(case: Case, tower: Tower):
    """Run one case and return its ``Response``.

    The case engine's model (:func:`rockscreen.pipeline.engine.registry.solver_model`)
    with the compiled solver for the consistent formulation;
    :mod:`rockscreen.solver.paper_formulation` for ``di-gennaro-2023`` and the
    one-at-a-time switches.
    """
    acc, dt = case_excitation(case)
    block = RockingBlock.from_dimensions(tower.width, tower.height, eta=case.eta)
    model = solver_model(case.model)
    study_values = {
        "tower_mass": tower.tower_mass,
        "building_mass": tower.building_mass,
        "mu_s": case.mu_s,
        "mu_k": case.mu_k,
    }
    parameters = {keyword: study_values[keyword] for keyword in model.parameters}
    if case.formulation != "consistent":
        return solve_paper_double_block(block, acc, dt, **parameters, formulation=case.formulation)
    return model.solve(block, acc, dt, parameters, history=True)


def result_from_response(case: Case, response: Any) -> CaseResult:
    """Collect the scalars and histories of a solver ``Response`` for the archive."""
    histories = {}
    for name in HISTORY_UNITS:
        value = getattr(response, name, None)
        if value is not None:
            histories[name] = np.asarray(value)
    duration, dt = case_timing(case)
    return CaseResult(
        case=case,
        status=str(response.status),
        overturned=bool(response.overturned),
        theta_max=float_or_nan(response.theta_max),
        theta_max_over_alpha=float_or_nan(response.theta_max_over_alpha),
        n_impacts=int(response.n_impacts),
        slip_max=float_or_nan(getattr(response, "slip_max", None)),
        slip_residual=float_or_nan(getattr(response, "slip_residual", None)),
        eta=float_or_nan(getattr(response, "eta", case.eta)),
        alpha=float_or_nan(getattr(response, "alpha", None)),
        p=float_or_nan(getattr(response, "p", None)),
        t_end=float_or_nan(getattr(response, "t_end", None)),
        histories=histories,
        duration=duration,
        dt=dt,
    )


#: Most cases per chunk of a parallel sweep: a few, so that the slow cases (the paper
#: formulation's solve_ivp runs take seconds) spread over the workers.
MAX_CASES_PER_CHUNK = 8


def _run_cases(
    shared: tuple[Tower, Callable], chunk: list[tuple[int, Case]]
) -> list[tuple[int, CaseResult]]:
    """Work function of a sweep: solve a chunk of ``(position, case)``; keep the positions."""
    tower, solve = shared
    return [(position, result_from_response(case, solve(case, tower))) for position, case in chunk]


def run_study(
    study: Study,
    *,
    jobs: int | None = 1,
    solve: Callable[[Case, Tower], Any] = solve_case,
    cases: list[Case] | None = None,
    scheduler: str | None = None,
    notify: Callable[[str], None] | None = None,
) -> Iterator[CaseResult]:
    """Run every case of a study and yield the results in case order.

    The executor is :class:`rockscreen.pipeline.execution.job.Job`'s, as for every
    command: the tower and ``solve`` are shipped to the workers once, the cases go
    in chunks, and results that complete early wait until every earlier case is yielded.

    Parameters
    ----------
    study : Study
        The parsed study.
    jobs : int or None
        Worker processes (1 runs in this process; capped per CPU and by the number of
        cases, with a note); None = 1. With more than one, ``solve`` must be picklable
        (a module-level function).
    solve : callable
        ``solve(case, tower) -> Response``; the default runs the project's solver.
    cases : list of Case, optional
        A subset of ``study.cases()`` to run.
    scheduler : str, optional
        ``tcp://HOST:PORT`` of a running Dask scheduler whose workers compute the cases
        (``jobs`` is then ignored, with a note unless it is None).
    notify : callable, optional
        ``notify(line)`` receives the executor's notes (workers capped, the cluster).

    Yields
    ------
    CaseResult

    Raises
    ------
    ConfigError
        If ``jobs`` is not None or an integer >= 1.
    """
    if jobs is not None and (isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1):
        raise ConfigError(f"jobs={jobs!r} must be an integer >= 1")
    cases = study.cases() if cases is None else cases
    if not cases:
        return
    local_jobs = 1 if jobs is None and not scheduler else jobs
    # The executor, closed when the generator ends.
    with Job(notify, jobs=local_jobs, scheduler=scheduler, n_tasks=len(cases)) as job:
        ex, workers = job.executor, job.workers
        # One case per chunk in this process (each result is yielded as soon as it is
        # solved); with workers about eight chunks each, at most MAX_CASES_PER_CHUNK cases.
        size = min(MAX_CASES_PER_CHUNK, math.ceil(len(cases) / (8 * workers)))
        size = 1 if workers == 1 else size
        ex.start(_run_cases, (study.tower, solve))
        for first in range(0, len(cases), size):
            ex.submit(list(enumerate(cases[first : first + size], start=first)))
        waiting: dict[int, CaseResult] = {}  # reorder buffer: completed, not yet yielded
        following = 0
        for chunk_results in ex.completed():
            waiting.update(chunk_results)
            while following in waiting:
                yield waiting.pop(following)
                following += 1


# Re-exports: the archive and the tables of a sweep.
from rockscreen.pipeline.archive.sweep_archive import (  # noqa: E402, F401
    ARCHIVE_FORMAT_VERSION,
    ARCHIVE_KIND,
    CASE_COLUMNS,
    is_sweep_archive,
    read_archive_attrs,
    read_cases,
    read_histories,
    read_history,
    write_sweep_archive,
)
from rockscreen.pipeline.study.tables import format_cases_table, format_markdown_tables  # noqa: E402, F401
