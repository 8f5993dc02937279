"""The one shell of a long command (execution.job.Job): executor, work file, stops."""

from __future__ import annotations

import signal
from concurrent.futures.process import BrokenProcessPool
from pathlib import Path

import pytest

import rockscreen.pipeline.execution.job as job_module
from rockscreen.pipeline.archive.assess_part import AssessJournal
from rockscreen.pipeline.archive.campaign import ArchiveWriter
from rockscreen.pipeline.errors import Interrupted, RockscreenError
from rockscreen.pipeline.execution.job import Job
from rockscreen.stations.inventory import Tower
from rockscreen.stations.inventory_table import inventory_table


class FakeWork:
    """A work file in memory: what :class:`Job` asks of one (the ``WorkFile`` protocol)."""

    def __init__(self, n_done: int, *, resumed=False, discarded="", write_failed=False):
        self.part = Path("out.h5.part")
        self.n_done, self.resumed, self.discarded = n_done, resumed, discarded
        self.write_failed = write_failed
        self.removed = self.opened = self.closed = False

    def __enter__(self):
        self.opened = True
        return self

    def __exit__(self, *exc_info):
        self.closed = True

    def remove(self):
        self.removed = True


def _stopped(work: FakeWork, exc: BaseException, lines: list[str] | None = None, verb="computed"):
    """Run a job whose work raises ``exc``; return what the job raised."""
    with Job(lines.append if lines is not None else None, jobs=1, verb=verb) as job:
        job.keep(work, 5)
        with pytest.raises(BaseException) as info, job.running():
            raise exc
    return info.value


def test_a_stop_says_how_many_towers_the_work_file_keeps():
    work = FakeWork(2)
    raised = _stopped(work, KeyboardInterrupt(), verb="assessed")
    assert isinstance(raised, Interrupted) and raised.exit_code == 128 + signal.SIGINT
    assert raised.message == (
        "interrupted (SIGINT): the 2 tower(s) assessed so far are kept in out.h5.part; "
        "rerun the same command to resume"
    )
    assert work.opened and work.closed and not work.removed


def test_a_stop_before_the_first_tower_removes_the_work_file():
    work = FakeWork(0)
    raised = _stopped(work, KeyboardInterrupt())
    assert raised.message == "interrupted (SIGINT); no tower was finished, nothing was kept"
    assert work.removed


@pytest.mark.parametrize("n_done", [0, 3])
def test_a_lost_worker_is_one_line_saying_what_is_kept(n_done):
    work = FakeWork(n_done)
    raised = _stopped(work, BrokenProcessPool("a process terminated abruptly"))
    assert type(raised) is RockscreenError
    where = "kept in out.h5.part; rerun the same command to resume"
    assert str(raised) == (
        f"a worker process died (a process terminated abruptly); the {n_done} tower(s) "
        f"computed so far are {where if n_done else 'none was finished'}"
    )
    assert work.removed == (n_done == 0)


def test_another_error_passes_with_a_line_on_what_is_kept_unless_the_file_said_it():
    lines: list[str] = []
    work = FakeWork(1)
    assert isinstance(_stopped(work, ValueError("bad"), lines), ValueError)
    assert lines == [
        "the 1 tower(s) computed so far are kept in out.h5.part; rerun the same command to resume"
    ]
    lines.clear()
    failed = FakeWork(0, write_failed=True)  # its own error said what it keeps
    assert isinstance(_stopped(failed, OSError("disk"), lines), OSError)
    assert lines == [] and not failed.removed


def test_keep_says_what_was_discarded_and_resumed():
    lines, warnings = [], []
    with Job(lines.append, jobs=1, verb="assessed", warn=warnings.append) as job:
        job.keep(FakeWork(2, resumed=True, discarded="it is unreadable"), 7)
    assert warnings == ["discarded out.h5.part: it is unreadable; starting afresh"]
    assert lines == ["resuming out.h5.part: 2 of 7 tower(s) already assessed"]


def test_the_executor_is_closed_when_what_follows_its_choice_fails(monkeypatch):
    closed = []

    class Executor:
        def __exit__(self, *exc_info):
            closed.append(True)

    monkeypatch.setattr(job_module, "open_executor", lambda **options: (Executor(), 4))
    with pytest.raises(RockscreenError), Job(jobs=4) as job:
        assert job.workers == 4 and not closed
        raise RockscreenError("the work file cannot be created")
    assert closed == [True]


def test_both_work_files_are_the_jobs_own(tmp_path):
    """``run``'s archive writer and ``assess``'s journal: one stop, one line, one rule."""
    writer = ArchiveWriter(
        tmp_path / "run.h5",
        fingerprint="abc",
        metadata={},
        towers_table=inventory_table([Tower(id="T", width_m=2.0, height_m=10.0)]),
        motions={},
    )
    raised = _stopped(writer, KeyboardInterrupt())
    assert raised.message.endswith("no tower was finished, nothing was kept")
    assert not writer.part.exists()  # nothing to resume: removed, as assess does

    journal = AssessJournal(tmp_path / "assess.h5", {"v": 1})
    with journal:
        journal.append([{"index": 0, "row": {"id": "T0"}, "n_solves": 1}])
    raised = _stopped(journal, KeyboardInterrupt(), verb="assessed")
    assert raised.message.startswith("interrupted (SIGINT): the 1 tower(s) assessed so far")
    assert journal.part.is_file()
