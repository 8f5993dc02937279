"""What commands print on stderr, and how much: ``--quiet`` and ``--verbose``.

Results (tables, JSON) go to stdout; everything else (progress, warnings, notes) to
stderr, prefixed ``rockscreen:``, through :class:`Output`, so that every command honours
the same two options. Warnings are printed even with ``--quiet``: they change how a
result is to be read.
"""

from __future__ import annotations

import functools
from collections.abc import Callable
from typing import Any

import click

from rockscreen.pipeline.text import printable


class Output:
    """Print messages to stderr by level: 0 quiet, 1 normal, 2 verbose."""

    def __init__(self, level: int = 1) -> None:
        self.level = level

    def _echo(self, message: str) -> None:
        click.echo(f"rockscreen: {printable(message)}", err=True)

    def info(self, message: str) -> None:
        """Progress and notes (hidden by ``--quiet``)."""
        if self.level >= 1:
            self._echo(message)

    def detail(self, message: str) -> None:
        """Details shown with ``--verbose`` only."""
        if self.level >= 2:
            self._echo(message)

    def warning(self, message: str) -> None:
        """Something that changes how the result reads: always printed."""
        self._echo(message)

    def result(self, message: str) -> None:
        """Print the closing line of a command (unless ``--quiet``)."""
        self.info(message)

    def notify(self, level: str, message: str) -> None:
        """Dispatch a library message (``"info"``, ``"warning"`` or ``"detail"``)."""
        {"warning": self.warning, "detail": self.detail}.get(level, self.info)(message)


def output_options(command: Callable[..., Any]) -> Callable[..., Any]:
    """Add ``--quiet`` and ``--verbose`` to a command; it receives ``out_level`` (0, 1, 2)."""

    @click.option("--quiet", "-q", is_flag=True, help="Print only warnings and results.")
    @click.option("--verbose", "-v", is_flag=True, help="Print more detail on stderr.")
    @functools.wraps(command)
    def wrapper(*args: Any, quiet: bool, verbose: bool, **kwargs: Any) -> Any:
        if quiet and verbose:
            raise click.UsageError("give --quiet or --verbose, not both")
        return command(*args, out_level=0 if quiet else (2 if verbose else 1), **kwargs)

    return wrapper
