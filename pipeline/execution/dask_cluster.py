"""A Dask distributed executor: a campaign's chunks computed on an existing cluster.

``rockscreen run ... --scheduler tcp://HOST:PORT`` computes the campaign on the
workers of a running Dask scheduler (a ``dask scheduler`` / ``dask worker`` set, a
``dask-jobqueue`` cluster on SLURM, ...). The interface is that of
:mod:`rockscreen.pipeline.execution.local`: the shared data (processed records and configuration) go
to every worker **once** with ``client.scatter(shared, broadcast=True)``, so no shared
file system is assumed; each chunk is a task ``work(shared_future, chunk)``; results
come back in completion order and the calling process (the client) alone writes the
archive. Each task runs :func:`rockscreen.pipeline.execution.local.run_with_single_threaded_blas`:
the worker process's BLAS is limited to one thread on its first task (distributed's nanny
also starts workers with ``OMP_NUM_THREADS``, ``OPENBLAS_NUM_THREADS`` and
``MKL_NUM_THREADS`` at 1 by default, its ``distributed.nanny.pre-spawn-environ``).

The workers need rockscreen installed, at the same version as the client (the
work function and the campaign's classes are unpickled there); :meth:`connect`
checks it. Install the client side with ``pip install "rockscreen[distributed]"``.

Failures are one line (:class:`DistributedError`): a malformed address is refused before
any connection; a port that accepts connections but never answers as a Dask scheduler
is given up after the timeout (a probe bounded by its own clock: distributed's
``Client(timeout=...)`` alone does not bound the handshake); a scheduler that stops
answering mid-run ends the run with "the Dask scheduler at ... stopped answering; the
partial archive is kept; rerun to resume" (distributed's own error log of the lost
connection is silenced).
"""

from __future__ import annotations

import asyncio
import concurrent.futures
import ipaddress
import logging
import math
import re
import threading
from collections.abc import Iterator
from typing import Any

from rockscreen.pipeline import __version__
from rockscreen.pipeline.errors import DistributedError
from rockscreen.pipeline.execution.local import WorkFunction, run_with_single_threaded_blas
from rockscreen.pipeline.text import printable

#: Seconds to wait for the scheduler to answer, and for its first worker.
DEFAULT_TIMEOUT_S = 10.0
#: Address schemes a Dask scheduler listens on.
SCHEMES = ("tcp://", "tls://", "inproc://", "ucx://", "ws://", "wss://")
INSTALL_HINT = 'pip install "rockscreen[distributed]"'
# HOST:PORT after tcp:// or tls://: a bracketed IPv6 address or a host name / IPv4.
_HOST_PORT = re.compile(
    r"^(?:\[(?P<ip6>[0-9A-Fa-f:.]+)\]|(?P<host>[A-Za-z0-9._-]+))(?::(?P<port>\d+))?$"
)


def _import_distributed() -> Any:
    try:
        import distributed
    except ImportError as exc:
        raise DistributedError(
            f"--scheduler needs dask.distributed, which is not installed ({exc}); "
            f"install it with: {INSTALL_HINT}"
        ) from exc
    return distributed


def _malformed(address: Any, why: str) -> DistributedError:
    shown = printable(repr(address))[:80]
    return DistributedError(
        f"--scheduler={shown} is not a Dask scheduler address ({why}); "
        "expected tcp://HOST:PORT (e.g. tcp://10.0.0.5:8786)"
    )


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
        If the address is not a string of the form ``SCHEME://HOST[:PORT]``; for tcp
        and tls, if the host is not a host name, an IPv4 address or a bracketed IPv6
        address, or the port is not in 1..65535.
    """
    text = address.strip() if isinstance(address, str) else ""
    if not text.startswith(SCHEMES) or len(text.split("://", 1)[1]) == 0:
        raise _malformed(address, "no scheme://host")
    scheme, rest = text.split("://", 1)
    if scheme not in ("tcp", "tls"):
        return text
    match = _HOST_PORT.match(rest)
    if match is None:
        raise _malformed(address, "HOST:PORT expected after the scheme")
    if match["ip6"] is not None:
        try:
            ipaddress.IPv6Address(match["ip6"])
        except ValueError:
            raise _malformed(address, "not an IPv6 address in brackets") from None
    elif re.fullmatch(r"[0-9.]+", match["host"]):
        try:
            ipaddress.IPv4Address(match["host"])
        except ValueError:
            raise _malformed(address, "not an IPv4 address") from None
    if match["port"] is not None and not 1 <= int(match["port"]) <= 65535:
        raise _malformed(address, "the port must be in 1..65535")
    return text


async def _identity(distributed: Any, address: str, timeout: float) -> Any:
    comm = await distributed.comm.connect(address, timeout=timeout)
    try:
        await comm.write({"op": "identity", "reply": True})
        return await comm.read()
    finally:
        comm.abort()


def probe_scheduler(address: str, timeout: float) -> None:
    """Check within about ``timeout`` seconds that a Dask scheduler answers at ``address``.

    The probe runs on its own event loop in a daemon thread, bounded by its own clock,
    so a port that accepts connections and never answers cannot hold the run.

    Raises
    ------
    DistributedError
        One line: nothing answers, or the answer is not a Dask scheduler's.
    """
    distributed = _import_distributed()
    outcome: concurrent.futures.Future = concurrent.futures.Future()

    def probe() -> None:
        try:
            coro = _identity(distributed, address, timeout)
            # distributed's connect gives up on a refused port after ``timeout``; the
            # outer clock, one second later, on a port that accepts and stays silent.
            outcome.set_result(asyncio.run(asyncio.wait_for(coro, timeout + 1.0)))
        except BaseException as exc:  # noqa: BLE001 - reported to the caller below
            outcome.set_exception(exc)

    threading.Thread(target=probe, name="rockscreen-dask-probe", daemon=True).start()
    try:
        answer = outcome.result(timeout=timeout + 3.0)
    except (concurrent.futures.TimeoutError, asyncio.TimeoutError, TimeoutError) as exc:
        raise DistributedError(
            f"cannot reach the Dask scheduler at {address} within {timeout:g} s (the port "
            "accepts connections but does not answer as a Dask scheduler); is the address "
            "(tcp://HOST:PORT) the scheduler's?"
        ) from exc
    except Exception as exc:  # noqa: BLE001 - connection refused, reset, bad handshake...
        reason = str(exc).splitlines()[0][:200] if str(exc) else ""
        raise DistributedError(
            f"cannot reach the Dask scheduler at {address} within {timeout:g} s "
            f"({type(exc).__name__}: {reason}); is it running, and is the address "
            "(tcp://HOST:PORT) right?"
        ) from exc
    if not (isinstance(answer, dict) and str(answer.get("type", "")).endswith("Scheduler")):
        raise DistributedError(
            f"the service at {address} is not a Dask scheduler (it answered "
            f"{str(answer)[:60]!r}); is the address (tcp://HOST:PORT) the scheduler's?"
        )


def _silence_distributed_logs() -> None:
    """Stop distributed logging the lost scheduler connection (tracebacks on stderr)."""
    names = [name for name in logging.root.manager.loggerDict if name.startswith("distributed.")]
    for name in ("distributed", *names):
        logging.getLogger(name).setLevel(logging.CRITICAL + 1)


def _scheduler_lost(exc: BaseException) -> bool:
    text = str(exc)
    return "scheduler-connection-lost" in text or "lost the connection" in text


def _worker_version() -> str:
    """Return the rockscreen version importable on a worker (run there by the client)."""
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
        if self.address.startswith(("tcp://", "tls://")):
            probe_scheduler(self.address, self.timeout)
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
        lost = client.status not in ("running", "newly-created")
        if lost:
            _silence_distributed_logs()
        try:
            if self._futures and not lost:
                client.cancel(self._futures)
        except Exception:  # noqa: BLE001 - the scheduler went away meanwhile
            lost = True
        finally:
            self._futures = []
            self._shared = None
            try:
                client.close(timeout=self.timeout)
            except Exception:  # noqa: BLE001 - closing a client whose scheduler is gone
                if not lost:
                    raise

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
        try:
            [self._shared] = self._client.scatter([shared], broadcast=True, hash=False)
        except (concurrent.futures.CancelledError, OSError, TimeoutError) as exc:
            raise self._lost() from exc

    def _lost(self) -> DistributedError:
        """Return the one-line error of a scheduler that stopped answering."""
        _silence_distributed_logs()
        return DistributedError(
            f"the Dask scheduler at {self.address} stopped answering; the partial archive "
            "is kept; rerun to resume"
        )

    def _worker_lost(self, exc: BaseException) -> DistributedError:
        """Return the one-line error of a worker lost with data or tasks of the run."""
        _silence_distributed_logs()
        reason = " ".join(str(exc).split())
        reason = reason.split(" for reason: ", 1)[-1] if " for reason: " in reason else reason
        return DistributedError(
            f"a worker of the Dask cluster at {self.address} was lost during the run "
            f"({printable(reason[:160]) or type(exc).__name__}); the partial archive is kept; "
            "rerun to resume"
        )

    def submit(self, chunk: Any) -> None:
        """Submit one chunk as a task ``work(shared, chunk)`` (with a single-threaded BLAS)."""
        if self._work is None or self._client is None:
            raise RuntimeError("start() the executor before submitting chunks")
        # pure=False: two equal chunks are still two tasks (no key collision).
        self._futures.append(
            self._client.submit(
                run_with_single_threaded_blas, self._work, self._shared, chunk, pure=False
            )
        )

    def completed(self) -> Iterator[Any]:
        """Yield the results of the submitted chunks as they complete.

        A chunk that raised on a worker raises here with the worker's exception.

        Raises
        ------
        DistributedError
            When the scheduler stops answering mid-run, or a worker dies with data or tasks
            of the run (a task cancelled for lost dependencies, or one that killed its
            workers): one line; the caller keeps the partial archive, which a rerun resumes.
        """
        if not self._futures:
            return
        futures, self._futures = self._futures, []
        pending = set(futures)
        killed = getattr(self._distributed, "KilledWorker", ())
        try:
            for future in self._distributed.as_completed(futures, loop=self._client.loop):
                try:
                    result = future.result()
                except (concurrent.futures.CancelledError, OSError, TimeoutError) as exc:
                    client = self._client
                    if _scheduler_lost(exc) or (
                        client is not None and client.status not in ("running",)
                    ):
                        raise self._lost() from exc
                    if isinstance(exc, concurrent.futures.CancelledError):
                        raise self._worker_lost(exc) from exc
                    raise
                except killed as exc:
                    raise self._worker_lost(exc) from exc
                pending.discard(future)
                future.release()  # the result lives on the cluster until released
                yield result
        finally:
            # A consumer that stops early (error, kill) leaves the rest to close().
            self._futures = list(pending)
