"""Options that several commands share: one definition each, the help text per command.

Each function returns a click decorator, used as ``@jobs_option()`` above a command.
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import click

Decorator = Callable[[Callable[..., Any]], Callable[..., Any]]


def path_option(
    name: str,
    dest: str | None = None,
    *,
    help: str,
    metavar: str | None = None,
    as_path: bool = False,
) -> Decorator:
    """Return an option naming one file to write or read.

    Parameters
    ----------
    name : str
        The option, e.g. ``"--out"``.
    dest : str, optional
        The parameter name of the command (default from ``name``).
    help : str
        The help text.
    metavar : str, optional
        The value's name in the help.
    as_path : bool
        Pass a :class:`pathlib.Path` (default a str).

    Returns
    -------
    callable
        The click decorator; the value defaults to None.
    """
    kind = click.Path(dir_okay=False, path_type=Path if as_path else None)
    names = (name,) if dest is None else (name, dest)
    return click.option(*names, metavar=metavar, type=kind, default=None, help=help)


def folder_option(name: str, *, help: str) -> Decorator:
    """Return an option naming one folder to write into (a :class:`pathlib.Path`, or None)."""
    kind = click.Path(file_okay=False, dir_okay=True, path_type=Path)
    return click.option(name, type=kind, default=None, help=help)


def out_option(help: str) -> Decorator:
    """Return ``--out FILE``: the file a command writes (help says the default)."""
    return path_option("--out", help=help)


def towers_option() -> Decorator:
    """Return ``--towers CSV``: the tower inventory."""
    return path_option("--towers", help="Tower inventory CSV.")


def example_option(help: str) -> Decorator:
    """Return ``--example``: run on the embedded example data (help says which)."""
    return click.option("--example", is_flag=True, help=help)


def jobs_option(
    default: int | None = None, help: str = "Worker processes (default: the number of CPUs)."
) -> Decorator:
    """Return ``--jobs N``: the number of local worker processes, at least 1.

    Parameters
    ----------
    default : int, optional
        The default (shown in the help); None lets the library choose.
    help : str
        The help text.

    Returns
    -------
    callable
        The click decorator.
    """
    shown = {} if default is None else {"show_default": True}
    return click.option("--jobs", type=click.IntRange(min=1), default=default, help=help, **shown)


def scheduler_option(help: str) -> Decorator:
    """Return ``--scheduler TCP://HOST:PORT``: compute on a running Dask scheduler."""
    return click.option("--scheduler", metavar="TCP://HOST:PORT", help=help)
