"""Signals that stop a command the way Ctrl-C does.

SIGTERM (a scheduler or ``kill``) and SIGHUP (the terminal closed) raise
:class:`KeyboardInterrupt` while a command runs, so that it stops at once, keeps what its
archive already holds (a ``.part`` of ``rockscreen run``), prints one line and exits with
128 + the signal number. A signal the process inherited as ignored (``nohup``) stays
ignored.
"""

from __future__ import annotations

import signal
from typing import Any

__all__ = ["STOP_SIGNALS", "StopSignals"]

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
