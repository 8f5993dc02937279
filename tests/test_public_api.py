"""The curated public API of pipeline resolves, and importing pipeline stays light."""

from __future__ import annotations

import subprocess
import sys

import pytest

from rockscreen import pipeline


@pytest.mark.parametrize("name", sorted(set(pipeline.__all__) - {"__version__"}))
def test_every_public_name_resolves(name):
    assert callable(getattr(pipeline, name))


def test_unknown_name_is_an_attribute_error():
    with pytest.raises(AttributeError, match="no_such"):
        pipeline.no_such  # noqa: B018


def test_import_pipeline_loads_no_heavy_dependency():
    # Every command module too: ``rockscreen --help`` imports them all for their summaries.
    code = (
        "import sys, importlib, rockscreen.pipeline, rockscreen.pipeline.cli as cli; "
        "[importlib.import_module('rockscreen.pipeline.cli.' + m) for m in cli.COMMANDS.values()]; "
        "print(sorted(m for m in ('numba', 'obspy', 'h5py', 'matplotlib') if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
