"""The one choice of executor: ``--jobs`` and ``--scheduler`` of every command.

``rockscreen run``, ``assess`` and ``sweep`` (and their library functions) get their
executor from :func:`open_executor` and nowhere else:

- without a scheduler, local workers: ``--jobs`` (default: the number of CPUs) capped by
  :func:`rockscreen.pipeline.execution.local.cap_jobs` (per CPU and by the number of
  tasks), with a note when capped; one worker computes in this process
  (:class:`~rockscreen.pipeline.execution.local.SerialExecutor`), more in ``spawn``-ed
  processes with a single-threaded BLAS
  (:class:`~rockscreen.pipeline.execution.local.ProcessExecutor`);
- with ``scheduler`` (``tcp://HOST:PORT``), the Dask cluster there, connected at once so
  that an unreachable cluster stops the command before anything is written, with a note
  that ``--jobs`` is ignored when it was given
  (:class:`~rockscreen.pipeline.execution.dask_cluster.DaskExecutor`).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from rockscreen.pipeline.execution.dask_cluster import DaskExecutor
from rockscreen.pipeline.execution.local import default_jobs, make_executor

#: Receives one line of text for the user.
Say = Callable[[str], None]


def open_executor(
    *,
    jobs: int | None,
    scheduler: str | None = None,
    n_tasks: int | None = None,
    notify: Say | None = None,
) -> tuple[Any, int]:
    """Return the executor of a command (not started) and the worker count that sizes its chunks.

    Parameters
    ----------
    jobs : int or None
        Local worker processes (``--jobs``); None = :func:`default_jobs`. Ignored, with a
        note when given, if ``scheduler`` is.
    scheduler : str, optional
        ``tcp://HOST:PORT`` of a running Dask scheduler; None or ``""`` = local workers.
    n_tasks : int, optional
        Tasks to compute (towers, cases): no more local workers than that.
    notify : callable, optional
        ``notify(line)`` receives the cap note, the ``--jobs``-ignored note and the
        cluster's address and size.

    Returns
    -------
    (executor, int)
        A :class:`~rockscreen.pipeline.execution.local.SerialExecutor`,
        :class:`~rockscreen.pipeline.execution.local.ProcessExecutor` or connected
        :class:`~rockscreen.pipeline.execution.dask_cluster.DaskExecutor` (use it as a
        context manager: leaving it stops the workers or closes the client), and its
        number of workers (local processes, or the cluster's worker threads).

    Raises
    ------
    ValueError
        If ``jobs`` is not None and not an integer >= 1 (local workers).
    DistributedError
        If the scheduler address is malformed, the cluster cannot be reached, or its
        workers are missing or run another rockscreen version.
    """
    say = notify if notify is not None else _silent
    if not scheduler:
        executor = make_executor(default_jobs() if jobs is None else jobs, n_tasks=n_tasks)
        if executor.note:
            say(executor.note)  # the workers were capped (CPUs, tasks)
        return executor, executor.jobs

    if jobs is not None:
        say(f"--jobs {jobs} is ignored with --scheduler: the cluster's workers compute")
    executor = DaskExecutor(scheduler).connect()
    say(
        f"computing on the Dask cluster at {executor.address} ({executor.jobs} worker "
        "threads); this process writes the archive"
    )
    return executor, executor.jobs


def _silent(line: str) -> None:
    """Drop a note (no ``notify`` given)."""
