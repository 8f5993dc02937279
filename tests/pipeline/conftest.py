"""Fixtures shared by the pipeline tests."""

from __future__ import annotations

import os

import pytest
from click.testing import CliRunner

from pipeline.cli import main


@pytest.fixture(scope="session")
def example_archive(tmp_path_factory):
    """The archive of ``rockscreen run --example`` (run once; tests only read it)."""
    folder = tmp_path_factory.mktemp("example-run")
    cwd = os.getcwd()
    os.chdir(folder)  # the run writes rockscreen-example.h5 into the current folder
    try:
        result = CliRunner().invoke(main, ["run", "--example", "--jobs", "1"])
    finally:
        os.chdir(cwd)
    assert result.exit_code == 0, result.output
    return folder / "rockscreen-example.h5"
