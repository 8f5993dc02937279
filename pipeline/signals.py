"""Signals that stop a command the way Ctrl-C does.

SIGTERM (a scheduler or ``kill``) and SIGHUP (the terminal closed) raise
:class:`KeyboardInterrupt` while a command runs, so that it stops at once, keeps what its
archive already holds (a ``.part`` of ``rockscreen run``), prints one line and exits with
128 + the signal number. A signal the process inherited as ignored (``nohup``) stays
ignored.

Worker processes leave Ctrl-C to their parent: :func:`blocked_in_children` blocks
SIGINT in the thread that starts them (a child inherits the mask through ``exec``, so
one that is still importing when Ctrl-C reaches the whole process group does not print a
traceback); the signal stays pending in the parent and is handled there.
"""

from __future__ import annotations

import contextlib
import signal
from collections.abc import Iterator
from typing import Any

__all__ = ["STOP_SIGNALS", "StopSignals", "blocked_in_children", "ignore_interrupts"]

#: Signals that stop a command like Ctrl-C, where the platform has them.
STOP_SIGNALS = tuple(
    getattr(signal, name) for name in ("SIGTERM", "SIGHUP") if hasattr(signal, name)
)


class StopSignals:
    """Turn the :data:`STOP_SIGNALS` into :class:`KeyboardInterrupt` within a ``with`` block.

    The previous handlers are restored on exit. Outside the main thread (a test runner's
    thread) nothing is installed: Python only lets the main thread set handlers.

    Attributes
    ----------
    signal : signal.Signals
        The signal that stopped the block; SIGINT (Ctrl-C) unless a stop signal came.
    """

    def __enter__(self) -> StopSignals:
        self.signal = signal.SIGINT
        self._previous: dict[int, Any] = {}
        for signum in STOP_SIGNALS:
            try:
                if signal.getsignal(signum) is signal.SIG_IGN:
                    continue
                self._previous[signum] = signal.signal(signum, self._handler)
            except ValueError:  # not the main thread
                break
        return self

    def _handler(self, signum: int, frame: Any) -> None:
        self.signal = signal.Signals(signum)
        raise KeyboardInterrupt

    def __exit__(self, *exc: Any) -> None:
        for signum, previous in self._previous.items():
            signal.signal(signum, previous)

    @property
    def exit_code(self) -> int:
        """Return the exit code of a command stopped by :attr:`signal` (128 + its number)."""
        return 128 + int(self.signal)


@contextlib.contextmanager
def blocked_in_children(signums: tuple[int, ...] = (signal.SIGINT,)) -> Iterator[None]:
    """Block ``signums`` in the calling thread while the block starts child processes.

    A child started (``fork`` and ``exec``) inside the block inherits the mask, so it
    never receives the signals (until it unblocks them); in this process a signal that
    arrives meanwhile is pending and delivered when the block ends, so none is lost.
    Without ``pthread_sigmask`` (Windows) nothing is blocked.

    Parameters
    ----------
    signums : tuple of int
        The signals to block (default SIGINT: Ctrl-C is the parent's to handle).
    """
    if not hasattr(signal, "pthread_sigmask"):
        yield
        return
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, signums)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


def ignore_interrupts() -> None:
    """Make a worker process ignore SIGINT and receive SIGTERM by its default action.

    Called first in a worker: Ctrl-C reaches the whole process group, and the parent
    handles it (it stops the workers); a worker dies quietly with its parent, never
    with a traceback of its own.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if hasattr(signal, "SIGTERM"):
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
