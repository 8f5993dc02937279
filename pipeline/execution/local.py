"""Executors: where the chunks of a campaign are computed.

An executor receives a *work function* ``work(shared, chunk) -> result`` and the
*shared* data every chunk needs (the processed records and the configuration). It
ships ``shared`` to its workers **once**, then computes submitted chunks and yields
their results in completion order. The campaign (one process) consumes the results
and alone writes the archive.

Interface (what every backend implements; :class:`pipeline.execution.dask_cluster.DaskExecutor`,
for ``--scheduler tcp://...``, scatters ``shared`` with ``client.scatter(...,
broadcast=True)`` and submits ``work(shared_future, chunk)``)::

    with Executor(...) as ex:
        ex.start(work, shared)        # ship shared data once
        for chunk in chunks:
            ex.submit(chunk)
        for result in ex.completed(): # every submitted chunk, in completion order
            ...

Both local backends here are deterministic in *content*; only the order of completion may
vary, and the archive sorts on finalising.
"""

from __future__ import annotations

import multiprocessing
import os
from collections import deque
from collections.abc import Callable, Iterator
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from typing import Any

#: ``work(shared, chunk) -> result``: a module-level (picklable) function.
WorkFunction = Callable[[Any, Any], Any]


class SerialExecutor:
    """Compute chunks one by one in this process (``--jobs 1``).

    Chunks run lazily, as :meth:`completed` is iterated, so the caller writes each
    result before the next chunk starts (the same flow as the parallel executor).
    """

    def __init__(self) -> None:
        self._work: WorkFunction | None = None
        self._shared: Any = None
        self._pending: deque[Any] = deque()

    def __enter__(self) -> SerialExecutor:
        return self

    def __exit__(self, *exc_info: object) -> None:
        self._pending.clear()

    def start(self, work: WorkFunction, shared: Any) -> None:
        """Keep the work function and the shared data."""
        self._work, self._shared = work, shared

    def submit(self, chunk: Any) -> None:
        """Queue one chunk."""
        self._pending.append(chunk)

    def completed(self) -> Iterator[Any]:
        """Compute and yield the queued chunks' results in submission order."""
        if self._work is None:
            raise RuntimeError("start() the executor before iterating over results")
        while self._pending:
            yield self._work(self._shared, self._pending.popleft())


# The worker side of ProcessExecutor: set once per worker process by the initializer.
_WORKER_STATE: dict[str, Any] = {}


def _init_worker(work: WorkFunction, shared: Any) -> None:
    _WORKER_STATE["work"] = work
    _WORKER_STATE["shared"] = shared


def _run_in_worker(chunk: Any) -> Any:
    return _WORKER_STATE["work"](_WORKER_STATE["shared"], chunk)


class ProcessExecutor:
    """Compute chunks in ``jobs`` local worker processes.

    The shared data travel to each worker once, through the pool initializer; a
    chunk carries only its own tasks. Workers are started with the ``spawn`` method:
    no inherited locks or threads, and a worker whose parent is killed sees its pipe
    close and exits instead of lingering.

    Parameters
    ----------
    jobs : int
        Number of worker processes, >= 1.
    """

    def __init__(self, jobs: int) -> None:
        if jobs < 1:
            raise ValueError(f"jobs={jobs!r} must be >= 1")
        self.jobs = jobs
        self._pool: ProcessPoolExecutor | None = None
        self._futures: set[Future] = set()

    def __enter__(self) -> ProcessExecutor:
        return self

    def __exit__(self, *exc_info: object) -> None:
        if self._pool is not None:
            for future in self._futures:
                future.cancel()
            self._pool.shutdown(wait=True, cancel_futures=True)
            self._pool = None

    def start(self, work: WorkFunction, shared: Any) -> None:
        """Start the worker processes and ship ``shared`` to each of them once."""
        self._pool = ProcessPoolExecutor(
            max_workers=self.jobs,
            mp_context=multiprocessing.get_context("spawn"),
            initializer=_init_worker,
            initargs=(work, shared),
        )

    def submit(self, chunk: Any) -> None:
        """Send one chunk to the pool."""
        if self._pool is None:
            raise RuntimeError("start() the executor before submitting chunks")
        self._futures.add(self._pool.submit(_run_in_worker, chunk))

    def completed(self) -> Iterator[Any]:
        """Yield the results of the submitted chunks as they complete."""
        while self._futures:
            done, self._futures = wait(self._futures, return_when=FIRST_COMPLETED)
            for future in done:
                yield future.result()


def default_jobs() -> int:
    """Return the default number of worker processes: ``os.cpu_count()`` (at least 1)."""
    return max(1, os.cpu_count() or 1)


def make_executor(jobs: int | None = None) -> SerialExecutor | ProcessExecutor:
    """Return the local executor for ``jobs`` workers (serial for one).

    Parameters
    ----------
    jobs : int, optional
        Worker processes; None = :func:`default_jobs`.

    Returns
    -------
    SerialExecutor or ProcessExecutor
    """
    jobs = default_jobs() if jobs is None else jobs
    if jobs < 1:
        raise ValueError(f"--jobs={jobs!r} must be >= 1")
    return SerialExecutor() if jobs == 1 else ProcessExecutor(jobs)
