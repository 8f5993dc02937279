"""Shared pytest configuration: Hypothesis profiles, the shared-data fixture, Agg plots."""

from __future__ import annotations

import os
from pathlib import Path

import matplotlib
import pytest
from hypothesis import HealthCheck, settings

matplotlib.use("Agg")

# Derandomised in CI so a run is reproducible; random (and shorter) locally.
settings.register_profile(
    "ci", derandomize=True, deadline=None, suppress_health_check=[HealthCheck.too_slow]
)
settings.register_profile("dev", deadline=None, max_examples=50)
settings.load_profile("ci" if os.environ.get("CI") else "dev")

REPO_ROOT = Path(__file__).resolve().parents[1]


def shared_data_dir() -> Path:
    """Return ``../shared/data`` beside the checkout (or ``$ROCKSCREEN_SHARED_DATA``)."""
    env = os.environ.get("ROCKSCREEN_SHARED_DATA")
    return Path(env) if env else REPO_ROOT.parent / "shared" / "data"


@pytest.fixture(scope="session")
def shared_data() -> Path:
    """The real records of ``../shared/data``; skips the test when the folder is absent."""
    path = shared_data_dir()
    if not path.is_dir():
        pytest.skip(f"real records not available: {path} is absent (see README, 'Tests')")
    return path


def pytest_collection_modifyitems(config, items):
    """Mark every test that uses ``shared_data`` as ``data`` (so ``-m "not data"`` works)."""
    for item in items:
        if "shared_data" in getattr(item, "fixturenames", ()):
            item.add_marker(pytest.mark.data)
