"""The shell of a long command: its executor, its work file, its stop signals, what it keeps.

``rockscreen run``, ``assess`` and ``sweep`` compute in workers; around the computation
each needs the same shell, and :class:`Job` is that shell, written once:

- the executor, chosen by :func:`rockscreen.pipeline.execution.choose.open_executor`
  when the job is made, and closed when the job ends however it ends (the local
  workers stopped, a Dask client closed), also when what follows its choice fails (a work
  file that cannot be created, a refused one);
- the work file ``OUT.part`` that keeps finished towers (:class:`WorkFile`: ``run``'s
  :class:`~rockscreen.pipeline.archive.campaign.ArchiveWriter`, ``assess``'s
  :class:`~rockscreen.pipeline.archive.assess_part.AssessJournal`): :meth:`Job.keep` says
  what was discarded or resumed;
- while the work runs (:meth:`Job.running`), SIGTERM and SIGHUP stop it like Ctrl-C
  (:class:`~rockscreen.pipeline.signals.StopSignals`), and a stop, a lost worker process or
  any other error ends with one line saying what the work file keeps; a work file that
  holds no finished tower is removed (nothing to resume).

The output itself is claimed before any work by
:func:`rockscreen.pipeline.archive.lock.claimed_output` (never an input, never an existing
file without ``--overwrite``, one command per ``--out``), the first step of every command
that writes an archive, ``scenario`` included (it computes in this process, without a
work file). This module imports no stage: the work file is a protocol.

Usage (``run``)::

    with claimed_output(out, inputs, "run", overwrite=None):
        ...  # read the inputs
        with Job(say, jobs=jobs, scheduler=scheduler, n_tasks=n, verb="computed") as job:
            writer = job.keep(ArchiveWriter(out, ...), n)
            with job.running():
                ...  # job.executor computes, the writer keeps each chunk
"""

from __future__ import annotations

import contextlib
from collections.abc import Callable, Iterator
from concurrent.futures.process import BrokenProcessPool
from pathlib import Path
from typing import Any, Protocol

from rockscreen.pipeline.errors import Interrupted, RockscreenError
from rockscreen.pipeline.execution.choose import open_executor
from rockscreen.pipeline.signals import StopSignals

__all__ = ["Job", "WorkFile"]


class WorkFile(Protocol):
    """A work file ``OUT.part`` keeping finished towers, open for writing in a ``with`` block.

    :class:`rockscreen.pipeline.archive.resume.PartFile`'s subclasses (``run``'s archive
    writer, ``assess``'s journal) are the two.
    """

    #: The work file.
    part: Path
    #: Whether an earlier work file of the same inputs was resumed.
    resumed: bool
    #: Why an earlier work file was discarded (``""`` when none was).
    discarded: str
    #: Whether a write failed; its error already said what the file keeps.
    write_failed: bool
    #: Towers committed to the work file (resumed ones included).
    n_done: int

    def remove(self) -> None:
        """Delete the work file."""

    def __enter__(self) -> Any:
        """Open the work file for writing."""

    def __exit__(self, *exc_info: object) -> None:
        """Close it."""


class Job:
    """The shell of one long command (module docstring): executor, work file, stops.

    Parameters
    ----------
    notify : callable, optional
        ``notify(line)`` receives the executor's notes and what was resumed (default:
        dropped).
    jobs, scheduler, n_tasks : optional
        The executor's choice (:func:`rockscreen.pipeline.execution.choose.open_executor`,
        made here: with ``scheduler`` the cluster is connected at once, so an unreachable
        one stops the command before its work file is created).
    verb : str
        What the command does to a tower, in its messages: ``"computed"``, ``"assessed"``.
    warn : callable, optional
        ``warn(line)`` receives what changes how a result reads (a work file discarded);
        default ``notify``.

    Attributes
    ----------
    executor : executor
        The executor (not started), closed when the job's ``with`` block ends.
    workers : int
        Its worker count (local processes, or the cluster's threads): sizes the chunks.
    """

    def __init__(
        self,
        notify: Callable[[str], None] | None = None,
        *,
        jobs: int | None = None,
        scheduler: str | None = None,
        n_tasks: int | None = None,
        verb: str = "computed",
        warn: Callable[[str], None] | None = None,
    ) -> None:
        self.notify = notify or (lambda line: None)
        self.warn = warn or self.notify
        self.verb = verb
        self.work: WorkFile | None = None
        self.executor, self.workers = open_executor(
            jobs=jobs, scheduler=scheduler, n_tasks=n_tasks, notify=self.notify
        )

    def __enter__(self) -> Job:
        return self

    def __exit__(self, *exc_info: object) -> None:
        self.executor.__exit__(None, None, None)  # idempotent: the work may have left it

    def keep(self, work: WorkFile, total: int) -> Any:
        """Take the job's work file, saying what was discarded or resumed; return it.

        Parameters
        ----------
        work : WorkFile
            The work file, opened (created or resumed).
        total : int
            Towers the job computes, resumed ones included (named beside those resumed).
        """
        if work.discarded:
            self.warn(f"discarded {work.part}: {work.discarded}; starting afresh")
        if work.resumed:
            self.notify(
                f"resuming {work.part}: {work.n_done} of {total} tower(s) already {self.verb}"
            )
        self.work = work
        return work

    def _so_far(self) -> str:
        """Return ``the N tower(s) <verb> so far are``, the subject of a stop's line."""
        return f"the {self.work.n_done} tower(s) {self.verb} so far are"

    def _drop_if_empty(self) -> None:
        """Remove a work file that keeps no tower (unless its own error said it is kept)."""
        if self.work.n_done == 0 and not self.work.write_failed:
            self.work.remove()

    @contextlib.contextmanager
    def running(self) -> Iterator[None]:
        """Run the block with the work file open; on a stop say what it keeps.

        Raises
        ------
        Interrupted
            On Ctrl-C, SIGTERM or SIGHUP: ``interrupted (SIGTERM): the N tower(s) computed
            so far are kept in OUT.part; rerun the same command to resume`` (``no tower was
            finished, nothing was kept`` when none was), exit code 128 + the signal.
        RockscreenError
            When a worker process died: ``a worker process died (...); the N tower(s) ...
            so far are kept in OUT.part; ...`` (``none was finished``).
        """
        work = self.work
        kept = f"kept in {work.part}; rerun the same command to resume"
        with StopSignals() as stop:
            try:
                with work:
                    yield
            except KeyboardInterrupt:
                self._drop_if_empty()
                said = f"interrupted ({stop.signal.name})"
                if work.n_done == 0:
                    said += "; no tower was finished, nothing was kept"
                else:
                    said += f": {self._so_far()} {kept}"
                raise Interrupted(said, stop.exit_code) from None
            except BrokenProcessPool as exc:
                self._drop_if_empty()
                where = kept if work.n_done else "none was finished"
                raise RockscreenError(
                    f"a worker process died ({exc or 'killed'}); {self._so_far()} {where}"
                ) from None
            except BaseException:
                self._drop_if_empty()
                if work.n_done and not work.write_failed:
                    self.notify(f"{self._so_far()} {kept}")
                raise
