"""A Dask distributed executor: a campaign's chunks computed on an existing cluster.

``rockscreen run ... --scheduler tcp://HOST:PORT`` computes the campaign on the
workers of a running Dask scheduler (a ``dask scheduler`` / ``dask worker`` set, a
``dask-jobqueue`` cluster on SLURM, ...). The interface is that of
:mod:`pipeline.execution.local`: the shared data (processed records and configuration) go
to every worker **once** with ``client.scatter(shared, broadcast=True)``, so no shared
file system is assumed; each chunk is a task ``work(shared_future, chunk)``; results
come back in completion order and the calling process (the client) alone writes the
archive.

The workers need rockscreen installed, at the same version as the client (the
work function and the campaign's classes are unpickled there); :meth:`connect`
checks it. Install the client side with ``pip install "rockscreen[distributed]"``.
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

from pipeline.errors import RockscreenError
from pipeline.execution.local import WorkFunction

#: Seconds to wait for the scheduler to answer, and for its first worker.
DEFAULT_TIMEOUT_S = 10.0
#: Address schemes a Dask scheduler listens on.
SCHEMES = ("tcp://", "tls://", "inproc://", "ucx://", "ws://", "wss://")
INSTALL_HINT = 'pip install "rockscreen[distributed]"'


class DistributedError(RockscreenError):
    """The Dask cluster cannot be used: not installed, unreachable, no or wrong workers."""


def _import_distributed() -> Any:
    try:
        import distributed
    except ImportError as exc:
        raise DistributedError(
            f"--scheduler needs dask.distributed, which is not installed ({exc}); "
            f"install it with: {INSTALL_HINT}"
        ) from exc
    return distributed


def check_address(address: Any) -> str:
    """Return a scheduler address after checking its form.

    Parameters
    ----------
    address : str
        ``tcp://HOST:PORT`` (or another Dask scheme: tls, inproc, ucx, ws, wss).

    Returns
    -------
    str
        The address, stripped.

    Raises
    ------
    DistributedError
        If the address is not a string of the form ``SCHEME://HOST[:PORT]``.
    """
    text = address.strip() if isinstance(address, str) else ""
    if not text.startswith(SCHEMES) or len(text.split("://", 1)[1]) == 0:
        raise DistributedError(
            f"--scheduler={address!r} is not a Dask scheduler address; "
            "expected tcp://HOST:PORT (e.g. tcp://10.0.0.5:8786)"
        )
    return text


def _worker_version() -> str:
    """Return the rockscreen version importable on a worker (run there by the client)."""
    from pipeline import __version__

    return __version__


class DaskExecutor:
    """Compute campaign chunks on the workers of a running Dask scheduler.

    Parameters
    ----------
    scheduler_address : str
        ``tcp://HOST:PORT`` of the scheduler.
    timeout : float, optional
        Seconds to wait for the scheduler to answer and for at least one worker [s];
        default :data:`DEFAULT_TIMEOUT_S`.

    Attributes
    ----------
    jobs : int
        Worker threads on the cluster once connected (sizes the chunks); 1 before.

    Raises
    ------
    DistributedError
        If dask.distributed is not installed, or the address or timeout is malformed.
    """

    def __init__(self, scheduler_address: str, *, timeout: float | None = None) -> None:
        self._distributed = _import_distributed()
        self.address = check_address(scheduler_address)
        timeout = DEFAULT_TIMEOUT_S if timeout is None else timeout
        if not (isinstance(timeout, int | float) and math.isfinite(timeout) and timeout > 0):
            raise DistributedError(f"timeout={timeout!r} must be a positive number of seconds")
        self.timeout = float(timeout)
        self.jobs = 1
        self._client: Any = None
        self._work: WorkFunction | None = None
        self._shared: Any = None
        self._futures: list[Any] = []

    # ----------------------------------------------------------------- connection

    def connect(self) -> DaskExecutor:
        """Connect to the scheduler; check workers are there and run this rockscreen.

        Idempotent; :meth:`__enter__` calls it. Call it early (before creating the
        archive) so that an unreachable cluster stops the run before anything is
        written.

        Returns
        -------
        DaskExecutor
            Itself.

        Raises
        ------
        DistributedError
            If the scheduler does not answer within the timeout, no worker joins it
            within the timeout, or a worker cannot import rockscreen or runs another
            version.
        """
        if self._client is not None:
            return self
        try:
            client = self._distributed.Client(
                self.address, timeout=self.timeout, set_as_default=False
            )
        except (OSError, TimeoutError) as exc:
            raise DistributedError(
                f"cannot reach the Dask scheduler at {self.address} within "
                f"{self.timeout:g} s ({type(exc).__name__}: {exc}); is it running, and is "
                "the address (tcp://HOST:PORT) right?"
            ) from exc
        self._client = client
        try:
            self._check_workers()
        except BaseException:
            self.close()
            raise
        return self

    def _check_workers(self) -> None:
        client = self._client
        try:
            client.wait_for_workers(1, timeout=self.timeout)
        except (OSError, TimeoutError) as exc:
            raise DistributedError(
                f"the Dask scheduler at {self.address} has no worker after {self.timeout:g} s; "
                "start some (e.g. 'dask worker " + self.address + "')"
            ) from exc
        from pipeline import __version__

        try:
            versions = client.run(_worker_version)
        except ImportError as exc:
            raise DistributedError(
                f"a worker of {self.address} cannot import rockscreen ({exc}); install "
                f"rockscreen {__version__} on every worker"
            ) from exc
        other = {worker: v for worker, v in versions.items() if v != __version__}
        if other:
            listed = ", ".join(f"{w}: {v}" for w, v in sorted(other.items()))
            raise DistributedError(
                f"workers of {self.address} run another rockscreen version than this "
                f"client's {__version__} ({listed}); install the same version everywhere"
            )
        info = client.scheduler_info()
        threads = sum(w.get("nthreads", 1) for w in info.get("workers", {}).values())
        self.jobs = max(1, threads)

    def close(self) -> None:
        """Cancel unfinished tasks, release the shared data and disconnect."""
        client, self._client = self._client, None
        if client is None:
            return
        try:
            if self._futures:
                client.cancel(self._futures)
        finally:
            self._futures = []
            self._shared = None
            client.close(timeout=self.timeout)

    def __enter__(self) -> DaskExecutor:
        return self.connect()

    def __exit__(self, *exc_info: object) -> None:
        self.close()

    # ----------------------------------------------------------------- executor interface

    def start(self, work: WorkFunction, shared: Any) -> None:
        """Send ``shared`` to every worker once and keep the work function.

        Parameters
        ----------
        work : callable
            ``work(shared, chunk) -> result``, importable on the workers.
        shared : object
            Picklable data every chunk needs.
        """
        self.connect()
        self._work = work
        # broadcast: a copy on each worker now, not fetched worker-to-worker per task.
        # In a list, so that a dict or list of shared data stays one object (scatter
        # would otherwise send each element as a separate piece of data).
        [self._shared] = self._client.scatter([shared], broadcast=True, hash=False)

    def submit(self, chunk: Any) -> None:
        """Submit one chunk as a task ``work(shared, chunk)``."""
        if self._work is None or self._client is None:
            raise RuntimeError("start() the executor before submitting chunks")
        # pure=False: two equal chunks are still two tasks (no key collision).
        self._futures.append(self._client.submit(self._work, self._shared, chunk, pure=False))

    def completed(self) -> Iterator[Any]:
        """Yield the results of the submitted chunks as they complete.

        A chunk that raised on a worker raises here with the worker's exception.
        """
        if not self._futures:
            return
        futures, self._futures = self._futures, []
        pending = set(futures)
        try:
            for future in self._distributed.as_completed(futures, loop=self._client.loop):
                result = future.result()
                pending.discard(future)
                future.release()  # the result lives on the cluster until released
                yield result
        finally:
            # A consumer that stops early (error, kill) leaves the rest to close().
            self._futures = list(pending)
