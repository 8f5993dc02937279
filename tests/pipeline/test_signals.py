"""SIGTERM and SIGHUP stop a command like Ctrl-C: one line, exit 128 + the signal."""

from __future__ import annotations

import os
import signal
import sys

import pytest
from click.testing import CliRunner

import rockscreen.pipeline.records.io
from rockscreen.pipeline.cli import main
from rockscreen.pipeline.signals import STOP_SIGNALS, StopSignals

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="POSIX signals")


@pytest.mark.parametrize("name", ["SIGTERM", "SIGHUP"])
def test_a_stop_signal_interrupts_the_block_and_the_handlers_come_back(name):
    signum = getattr(signal, name)
    before = signal.getsignal(signum)
    with pytest.raises(KeyboardInterrupt), StopSignals() as stop:
        os.kill(os.getpid(), signum)
    assert stop.signal == signum and stop.exit_code == 128 + signum
    assert signal.getsignal(signum) == before


def test_a_signal_ignored_on_entry_stays_ignored():
    signum = STOP_SIGNALS[-1]
    previous = signal.signal(signum, signal.SIG_IGN)
    try:
        with StopSignals() as stop:
            os.kill(os.getpid(), signum)
        assert stop.signal == signal.SIGINT and stop.exit_code == 130
    finally:
        signal.signal(signum, previous)


def test_sigterm_during_a_command_is_one_line_and_exit_143(tmp_path, monkeypatch):
    def terminated(*args, **kwargs):
        os.kill(os.getpid(), signal.SIGTERM)
        raise AssertionError("SIGTERM was not turned into an interrupt")

    monkeypatch.setattr(rockscreen.pipeline.records.io, "read_stream", terminated)
    record = tmp_path / "a.mseed"
    record.write_bytes(b"")
    result = CliRunner().invoke(main, ["info", str(record)])
    assert result.exit_code == 128 + signal.SIGTERM, result.output
    assert result.stderr.strip() == "rockscreen: interrupted (SIGTERM); nothing was written"
