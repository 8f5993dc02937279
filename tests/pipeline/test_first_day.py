"""A screening office's first day (issue 24): small things that erode trust, one test each."""

from __future__ import annotations

import subprocess
import sys

import pytest
from click.testing import CliRunner

from rockscreen.pipeline.cli import main
from rockscreen.pipeline.text import printable


@pytest.mark.parametrize(
    ("typed", "meant"),
    [("rn", "'run'"), ("asess", "'assess'"), ("inspekt", "'inspect' or 'spectrum'")],
)
def test_a_mistyped_command_names_the_closest_one(typed, meant):
    result = CliRunner().invoke(main, [typed])
    assert result.exit_code == 2
    assert f"no such command '{typed}' (did you mean {meant}?)" in result.output
    assert "the commands are: run, simulate" in result.output


def test_an_unknown_command_without_a_close_one_lists_the_commands():
    result = CliRunner().invoke(main, ["zzzzzz"])
    assert result.exit_code == 2
    assert "did you mean" not in result.output
    assert "the commands are:" in result.output


@pytest.mark.parametrize(
    "control", ["\u202e", "\u202d", "\u2066", "\u2067", "\u2068", "\u2069", "\u200e", "\u061c"]
)
def test_bidirectional_controls_are_escaped(control):
    shown = printable(f"AQ{control}GIUS")
    assert control not in shown
    assert shown == f"AQ\\u{ord(control):04x}GIUS"
    assert printable("città di L'Aquila") == "città di L'Aquila"  # letters stay as they are


def test_a_closed_pipe_ends_quietly_with_exit_0(example_archive):
    """``rockscreen inspect X.h5 | head -1``: the reader leaves, rockscreen exits 0, silently."""
    code = (
        "import subprocess, sys\n"
        "p = subprocess.Popen([sys.executable, '-m', 'rockscreen.pipeline', 'inspect', "
        f"{str(example_archive)!r}], stdout=subprocess.PIPE, stderr=subprocess.PIPE)\n"
        "p.stdout.readline(); p.stdout.close()\n"
        "err = p.stderr.read(); print(p.wait()); print(repr(err))\n"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=120
    ).stdout.splitlines()
    assert out == ["0", "b''"]
