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

Worker processes end with their parent: on Linux each worker asks the kernel for SIGKILL
when its parent dies (``prctl(PR_SET_PDEATHSIG)``); everywhere a daemon thread in each
worker also polls ``os.getppid()`` and exits once the parent is gone, so a SIGKILLed or
SIGTERMed run leaves no idle workers holding memory.

The number of workers is capped (:func:`cap_jobs`): at most :data:`JOBS_PER_CPU` per CPU
and never more than there are chunks to compute; ``--jobs 10000`` runs with the cap and
a note, it does not start 10,000 processes.

Every worker computes with a single-threaded BLAS (:func:`limit_blas_threads`): the worker
initializer sets :data:`BLAS_THREAD_VARIABLES` to 1 *before* it unpickles the work function
and the shared data (they travel as bytes), so numpy, imported by that unpickling, loads its
BLAS single-threaded; libraries already loaded (numpy imported by a script's main module,
which a spawned worker imports again first) are limited at run time too, by
``threadpoolctl`` where importable, else through OpenBLAS's own setter. ``jobs`` workers
each using every core would oversubscribe the CPUs. The serial executor computes each chunk
with the loaded OpenBLAS at one thread too (:func:`single_threaded_blas`; ``docs/scaling.md``).

Callers do not construct these executors themselves:
:func:`rockscreen.pipeline.execution.choose.open_executor` is the one choice of executor for
every command.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import multiprocessing
import os
import pickle
import signal
import sys
import threading
import time
from collections import deque
from collections.abc import Callable, Iterator
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from contextlib import contextmanager
from multiprocessing import resource_tracker
from typing import Any

from rockscreen.pipeline.signals import blocked_in_children, ignore_interrupts

#: ``work(shared, chunk) -> result``: a module-level (picklable) function.
WorkFunction = Callable[[Any, Any], Any]

#: Most worker processes per CPU: more only adds memory (each worker holds the shared
#: records) and start-up time, since the solver is CPU-bound.
JOBS_PER_CPU = 4
#: Seconds between two checks of a worker that its parent is still alive (fallback of
#: the Linux parent-death signal).
PARENT_POLL_S = 1.0
_PR_SET_PDEATHSIG = 1
#: Environment variables read by OpenMP, OpenBLAS and MKL when they load: set to ``"1"`` in
#: every worker (one single-threaded worker per core, not ``jobs`` x ``cores`` threads).
BLAS_THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS")
# The process that limited its BLAS threads, and threadpoolctl's limiter kept alive there.
_BLAS_STATE: dict[str, Any] = {"pid": None, "limiter": None}


class SerialExecutor:
    """Compute chunks one by one in this process (``--jobs 1``).

    Chunks run lazily, as :meth:`completed` is iterated, so the caller writes each
    result before the next chunk starts (the same flow as the parallel executor).

    Attributes
    ----------
    jobs : int
        1.
    note : str
        Why fewer workers than asked are used (set by :func:`make_executor`), or ``""``.
    """

    jobs = 1

    def __init__(self) -> None:
        self.note = ""
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
            chunk = self._pending.popleft()
            with single_threaded_blas():
                result = self._work(self._shared, chunk)
            yield result


# The worker side of ProcessExecutor: set once per worker process by the initializer.
_WORKER_STATE: dict[str, Any] = {}


def set_parent_death_signal(sig: int = signal.SIGKILL) -> bool:
    """Ask Linux to send ``sig`` to this process when its parent dies.

    Returns
    -------
    bool
        Whether the request was accepted (False off Linux or without ``prctl``).
    """
    if not sys.platform.startswith("linux"):
        return False
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or None, use_errno=True)
        return libc.prctl(_PR_SET_PDEATHSIG, int(sig), 0, 0, 0) == 0
    except (OSError, AttributeError):
        return False


def _exit_when_orphaned(parent_pid: int, interval: float) -> None:
    while os.getppid() == parent_pid:
        time.sleep(interval)
    os._exit(1)


def watch_parent(
    parent_pid: int, interval: float = PARENT_POLL_S, *, death_signal: bool = True
) -> None:
    """End this (worker) process when the process ``parent_pid`` is no longer its parent.

    Sets the Linux parent-death signal, then starts a daemon thread polling
    ``os.getppid()`` every ``interval`` seconds (the portable fallback, which also
    covers a parent that died before the signal was set).

    Parameters
    ----------
    parent_pid : int
        The parent's process id, taken by the parent when it started the worker.
    interval : float
        Seconds between two polls.
    death_signal : bool
        Whether to set the Linux parent-death signal. Linux sends it when the *thread*
        that started the worker ends, so the executor sets it only for workers started
        from the main thread.
    """
    if death_signal:
        set_parent_death_signal()
    if os.getppid() != parent_pid:
        os._exit(1)
    thread = threading.Thread(
        target=_exit_when_orphaned,
        args=(parent_pid, interval),
        name="rockscreen-parent-watch",
        daemon=True,
    )
    thread.start()


def start_resource_tracker() -> None:
    """Start multiprocessing's resource tracker with SIGHUP ignored (POSIX, main thread).

    The tracker ignores SIGINT and SIGTERM, not SIGHUP: a closed terminal would kill it
    while the run, which stops cleanly on SIGHUP, releases its locks, and the tracker
    started again in its place would print a traceback for locks it never saw. Started
    with SIGHUP ignored (kept through exec), it lives until the run closes its pipe.
    """
    main = threading.current_thread() is threading.main_thread()
    if os.name != "posix" or not hasattr(signal, "SIGHUP") or not main:
        return
    previous = signal.signal(signal.SIGHUP, signal.SIG_IGN)
    try:
        resource_tracker.ensure_running()
    finally:
        signal.signal(signal.SIGHUP, previous)


def limit_blas_threads() -> bool:
    """Make the BLAS and OpenMP libraries of this (worker) process single-threaded.

    Sets :data:`BLAS_THREAD_VARIABLES` to ``"1"`` in ``os.environ``, which the libraries
    read when they load (so call it before numpy is imported); then limits the libraries
    already loaded to one thread at run time: with ``threadpoolctl`` if importable, else
    the loaded OpenBLAS libraries directly (:func:`limit_loaded_openblas`). Meant for
    worker processes: it changes the environment of the calling process.

    Returns
    -------
    bool
        Whether a run-time limit is in place for the loaded libraries; False means only
        the environment variables are set.
    """
    for name in BLAS_THREAD_VARIABLES:
        os.environ[name] = "1"
    _BLAS_STATE["pid"] = os.getpid()
    try:
        from threadpoolctl import threadpool_limits
    except ImportError:
        # A script that imported numpy at its top has it loaded already in a spawned worker
        # (the main module is imported again before the initializer runs): its OpenBLAS
        # kept its threads. Limit the loaded OpenBLAS libraries directly.
        return limit_loaded_openblas()
    # Applied now, kept until the process ends (the limiter object restores on exit only).
    _BLAS_STATE["limiter"] = threadpool_limits(limits=1)
    return True


#: Thread-count setters of the OpenBLAS builds numpy and scipy ship (and the plain one).
OPENBLAS_SETTERS = (
    "scipy_openblas_set_num_threads64_",
    "scipy_openblas_set_num_threads",
    "openblas_set_num_threads64_",
    "openblas_set_num_threads",
)


#: Thread-count getters of the same builds, in the order of :data:`OPENBLAS_SETTERS`.
OPENBLAS_GETTERS = tuple(name.replace("_set_", "_get_") for name in OPENBLAS_SETTERS)


def loaded_openblas() -> list[str] | None:
    """Return the loaded OpenBLAS libraries' paths (``/proc/self/maps``; None: unreadable)."""
    try:
        with open("/proc/self/maps", encoding="utf-8", errors="replace") as maps:
            paths = {
                line.split()[-1]
                for line in maps
                if "openblas" in line.lower() and ".so" in line.rsplit("/", 1)[-1]
            }
    except OSError:
        return None
    return sorted(paths)


def _first(library: ctypes.CDLL, names: tuple[str, ...]) -> Any:
    """Return the first function of ``names`` ``library`` exports, or None."""
    return next((getattr(library, n) for n in names if hasattr(library, n)), None)


def limit_loaded_openblas() -> bool:
    """Set every OpenBLAS library loaded in this process to one thread (Linux).

    The loaded libraries are read from ``/proc/self/maps``; each is given one thread
    through the first of :data:`OPENBLAS_SETTERS` it exports (what ``threadpoolctl`` does
    for OpenBLAS). Libraries loaded later read the environment variables instead.

    Returns
    -------
    bool
        Whether every loaded OpenBLAS library was limited (True when none is loaded; False
        where ``/proc`` cannot be read).
    """
    paths = loaded_openblas()
    if paths is None:
        return False
    limited = True
    for path in paths:
        try:
            library = ctypes.CDLL(path)
        except OSError:
            limited = False
            continue
        setter = _first(library, OPENBLAS_SETTERS)
        if setter is None:
            limited = False
            continue
        setter(1)
    return limited


@contextmanager
def single_threaded_blas() -> Iterator[None]:
    """Run a block with the loaded OpenBLAS libraries at one thread, then restore them.

    Each loaded library (:func:`loaded_openblas`) with a getter and a setter
    (:data:`OPENBLAS_GETTERS`, :data:`OPENBLAS_SETTERS`) gets its own count back after the
    block, also when it raises. The serial executor computes its chunks in it: small linear
    algebra gains nothing from threads, whose waiting cost a stripe fit 160 ms of CPU
    instead of 4 ms (measured, ``docs/scaling.md``).
    """
    saved = []
    for path in loaded_openblas() or []:
        try:
            library = ctypes.CDLL(path)
        except OSError:
            continue
        getter, setter = _first(library, OPENBLAS_GETTERS), _first(library, OPENBLAS_SETTERS)
        if getter is None or setter is None:
            continue
        saved.append((setter, int(getter())))
        setter(1)
    try:
        yield
    finally:
        for setter, threads in saved:
            setter(threads)


def run_with_single_threaded_blas(work: WorkFunction, shared: Any, chunk: Any) -> Any:
    """Return ``work(shared, chunk)`` computed with the BLAS limited to one thread.

    The task a Dask worker runs: the first task in a worker process calls
    :func:`limit_blas_threads` (the environment variables then only reach libraries not
    loaded yet; threadpoolctl, if importable, limits the loaded ones), later tasks in that
    process skip it.

    Parameters
    ----------
    work : callable
        ``work(shared, chunk) -> result``.
    shared, chunk : object
        Its arguments.

    Returns
    -------
    object
        What ``work`` returns.
    """
    if _BLAS_STATE["pid"] != os.getpid():
        limit_blas_threads()
    return work(shared, chunk)


def _init_worker(payload: bytes, parent_pid: int | None = None, death_signal: bool = True) -> None:
    ignore_interrupts()  # Ctrl-C is the parent's; SIGINT stayed blocked until here
    if parent_pid is not None:
        watch_parent(parent_pid, death_signal=death_signal)
    limit_blas_threads()  # before the payload imports numpy
    _WORKER_STATE["work"], _WORKER_STATE["shared"] = pickle.loads(payload)


def _run_in_worker(chunk: Any) -> Any:
    return _WORKER_STATE["work"](_WORKER_STATE["shared"], chunk)


class ProcessExecutor:
    """Compute chunks in ``jobs`` local worker processes.

    The shared data travel to each worker once, through the pool initializer; a
    chunk carries only its own tasks. Workers are started with the ``spawn`` method
    (no inherited locks or threads), compute with a single-threaded BLAS
    (:func:`limit_blas_threads`, before the shared data are unpickled) and end when this
    process dies, however it dies (:func:`watch_parent`).

    Parameters
    ----------
    jobs : int
        Number of worker processes, >= 1.

    Attributes
    ----------
    note : str
        Why fewer workers than asked are used (set by :func:`make_executor`), or ``""``.
    """

    def __init__(self, jobs: int) -> None:
        if jobs < 1:
            raise ValueError(f"jobs={jobs!r} must be >= 1")
        self.jobs = jobs
        self.note = ""
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
        start_resource_tracker()
        # Pickled here, unpickled by the initializer after it limits the BLAS threads.
        payload = pickle.dumps((work, shared), protocol=pickle.HIGHEST_PROTOCOL)
        self._pool = ProcessPoolExecutor(
            max_workers=self.jobs,
            mp_context=multiprocessing.get_context("spawn"),
            initializer=_init_worker,
            initargs=(
                payload,
                os.getpid(),
                threading.current_thread() is threading.main_thread(),
            ),
        )

    def submit(self, chunk: Any) -> None:
        """Send one chunk to the pool."""
        if self._pool is None:
            raise RuntimeError("start() the executor before submitting chunks")
        # The pool starts its workers inside submit(): they start with SIGINT blocked.
        with blocked_in_children():
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


def cap_jobs(jobs: int, n_tasks: int | None = None) -> tuple[int, str]:
    """Return the number of workers to start for ``jobs`` asked, and a note if fewer.

    Parameters
    ----------
    jobs : int
        Workers asked for (``--jobs``), >= 1.
    n_tasks : int, optional
        Chunks to compute: more workers than chunks would idle.

    Returns
    -------
    (int, str)
        ``min(jobs, JOBS_PER_CPU * CPUs, n_tasks)`` (at least 1), and ``""`` or a note
        such as ``"--jobs 10000 capped at 8 (4 per CPU, 2 CPUs)"``.
    """
    cpus = default_jobs()
    limit = JOBS_PER_CPU * cpus
    capped, reason = jobs, ""
    if capped > limit:
        capped, reason = limit, f"{JOBS_PER_CPU} per CPU, {cpus} CPU{'s' * (cpus > 1)}"
    if n_tasks is not None and capped > max(1, n_tasks):
        capped = max(1, n_tasks)
        reason = f"{n_tasks} chunk{'s' * (n_tasks != 1)} to compute"
    if capped == jobs:
        return jobs, ""
    return capped, f"--jobs {jobs} capped at {capped} ({reason})"


def make_executor(
    jobs: int | None = None, n_tasks: int | None = None
) -> SerialExecutor | ProcessExecutor:
    """Return the local executor for ``jobs`` workers (serial for one).

    Parameters
    ----------
    jobs : int, optional
        Worker processes; None = :func:`default_jobs`. Capped by :func:`cap_jobs`; the
        executor's ``note`` says so (print it).
    n_tasks : int, optional
        Chunks to compute (caps the workers too).

    Returns
    -------
    SerialExecutor or ProcessExecutor

    Raises
    ------
    ValueError
        If ``jobs`` is not an integer >= 1.
    """
    jobs = default_jobs() if jobs is None else jobs
    if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
        raise ValueError(f"--jobs={jobs!r} must be an integer >= 1")
    capped, note = cap_jobs(jobs, n_tasks)
    executor = SerialExecutor() if capped == 1 else ProcessExecutor(capped)
    executor.note = note
    return executor
