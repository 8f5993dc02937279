"""The ``rockscreen`` command line.

Each subcommand lives in its own module ``rockscreen.pipeline.cli.<name>`` exposing a click
command named ``cli``; modules are imported only when their command runs, so
``rockscreen --help`` stays fast (no numba, ObsPy or h5py import). Commands hold no
physics and no file-format logic: they parse options, call the library, print or save.
"""

from __future__ import annotations

import difflib
import importlib
import importlib.util
import os
import sys
from typing import Any

import click

from rockscreen.pipeline import __version__

#: Subcommand name -> module under ``rockscreen.pipeline.cli`` (in the order ``--help`` lists them).
COMMANDS = {
    "run": "run",
    "simulate": "simulate",
    "sweep": "sweep",
    "info": "info",
    "spectrum": "spectrum",
    "inspect": "inspect",
    "plot": "plot",
    "export": "export",
    "hazard": "hazard",
    "assess": "assess",
    "scenario": "scenario",
    "report": "report",
}


def _user_errors() -> tuple[type[BaseException], ...]:
    """Exception types that are the user's to fix: reported as one line, no traceback."""
    from rockscreen.solver.errors import ParameterError
    from rockscreen.stations.errors import RockscreenError

    return (RockscreenError, ParameterError, OSError)


class RockscreenGroup(click.Group):
    """A click group with lazily imported subcommands and one-line error reports."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        """Return the subcommands whose module is present, in declaration order."""
        return [
            name
            for name, module in COMMANDS.items()
            if importlib.util.find_spec(f"{__name__}.{module}") is not None
        ]

    def resolve_command(
        self, ctx: click.Context, args: list[str]
    ) -> tuple[str | None, click.Command | None, list[str]]:
        """Resolve the subcommand; an unknown one is a usage error naming the closest ones."""
        name = args[0] if args else ""
        if name and not name.startswith("-") and self.get_command(ctx, name) is None:
            close = difflib.get_close_matches(name, self.list_commands(ctx), n=2, cutoff=0.5)
            hint = f" (did you mean {' or '.join(repr(c) for c in close)}?)" if close else ""
            commands = ", ".join(self.list_commands(ctx))
            ctx.fail(f"no such command {name!r}{hint}; the commands are: {commands}")
        return super().resolve_command(ctx, args)

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        """Import ``rockscreen.pipeline.cli.<module>`` and return its ``cli`` command."""
        module = COMMANDS.get(cmd_name)
        if module is None or importlib.util.find_spec(f"{__name__}.{module}") is None:
            return None
        return importlib.import_module(f"{__name__}.{module}").cli

    def invoke(self, ctx: click.Context):
        """Run the subcommand; turn user errors into one line on stderr and exit code 1.

        SIGTERM and SIGHUP stop it like Ctrl-C (:class:`rockscreen.pipeline.signals.StopSignals`).
        """
        from rockscreen.pipeline.signals import StopSignals

        with StopSignals() as stop:
            return self._invoke_reporting(ctx, stop)

    def _invoke_reporting(self, ctx: click.Context, stop: Any) -> Any:
        """Run the subcommand and report how it ended (inside :meth:`invoke`'s handlers)."""
        from rockscreen.pipeline.errors import Interrupted
        from rockscreen.pipeline.text import printable

        try:
            return super().invoke(ctx)
        except Interrupted as exc:
            click.echo(f"rockscreen: {exc.message}", err=True)
            ctx.exit(exc.exit_code)
        except KeyboardInterrupt:
            message = f"rockscreen: interrupted ({stop.signal.name}); nothing was written"
            click.echo(message, err=True)
            ctx.exit(stop.exit_code)
        except BrokenPipeError:
            # The reader of stdout went away (``rockscreen inspect ... | head -1``): it has what
            # it wanted, so stop quietly with 0 as Unix filters do, and keep Python from
            # complaining again when it flushes stdout at exit.
            os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
            ctx.exit(0)
        except _user_errors() as exc:
            if ctx.obj and ctx.obj.get("debug"):
                raise
            click.echo(f"rockscreen: error: {printable(str(exc))}", err=True)
            ctx.exit(1)


@click.group(cls=RockscreenGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, "--version", prog_name="rockscreen")
@click.option("--debug", is_flag=True, help="Show full tracebacks instead of one-line errors.")
@click.pass_context
def main(ctx: click.Context, debug: bool) -> None:
    """Screen masonry bell towers for seismic rocking and overturning.

    Single block (Housner rocking) on the ground or floor motion, and the
    double block (tower rocking on a building sliding on its foundation), after
    Di Gennaro, Guadagnuolo & Monaco (Buildings 2023, 13, 762).
    All quantities are SI: m, s, kg, rad, m/s^2.
    """
    ctx.ensure_object(dict)
    ctx.obj["debug"] = debug


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
