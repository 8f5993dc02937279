"""The first compile prints a line every 30 s, and the CLI and the README quote one figure."""

from __future__ import annotations

import time
from pathlib import Path

from rockscreen.pipeline.screening.batch import COMPILE_TIME_NOTE, compile_progress

README = Path(__file__).resolve().parents[2] / "README.md"


def test_a_line_every_interval_until_the_kernel_is_cached():
    lines: list[tuple[str, str]] = []
    state = {"cached": False}
    with compile_progress(
        lambda level, text: lines.append((level, text)),
        every_s=0.05,
        is_cached=lambda: state["cached"],
    ):
        time.sleep(0.4)
        state["cached"] = True
        time.sleep(0.2)
        count = len(lines)
    assert count >= 3
    assert all(level == "info" for level, _ in lines)
    assert lines[0][1].startswith("compiling the solver (first use) ... ")
    assert lines[0][1].endswith(" s")


def test_nothing_when_the_kernel_is_cached_or_inactive():
    lines: list[str] = []
    with compile_progress(
        lambda level, text: lines.append(text), every_s=0.02, is_cached=lambda: True
    ):
        time.sleep(0.2)
    with compile_progress(
        lambda level, text: lines.append(text), every_s=0.02, active=False, is_cached=lambda: False
    ):
        time.sleep(0.1)
    assert lines == []


def test_the_readme_quotes_the_figure_the_cli_prints():
    text = " ".join(README.read_text(encoding="utf-8").split())
    assert COMPILE_TIME_NOTE in text
    assert "about a minute" not in COMPILE_TIME_NOTE
