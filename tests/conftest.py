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
        pytest.skip(f"real records not available: {path} is absent (see docs/development.md)")
    return path


def pytest_collection_modifyitems(config, items):
    """Mark every test that uses ``shared_data`` as ``data`` (so ``-m "not data"`` works)."""
    for item in items:
        if "shared_data" in getattr(item, "fixturenames", ()):
            item.add_marker(pytest.mark.data)


@pytest.fixture(scope="session")
def make_inventory():
    """``make_inventory(station, ...)``: an ObsPy inventory of one XX station.

    Its HNN, HNE (azimuth 90) and HNZ channels read acceleration (``input_units``) with
    ``sensitivity`` counts per unit.
    """
    from obspy import UTCDateTime
    from obspy.core.inventory import (
        Channel,
        InstrumentSensitivity,
        Inventory,
        Network,
        Response,
        Station,
    )

    year_2000 = UTCDateTime(2000, 1, 1)

    def make(
        station="ABC",
        *,
        location="",
        latitude=42.5,
        longitude=13.25,
        elevation=700.0,
        sensitivity=2.0e5,
        input_units="M/S**2",
        start_date=year_2000,
    ) -> Inventory:
        sens = InstrumentSensitivity(
            value=sensitivity, frequency=1.0, input_units=input_units, output_units="COUNTS"
        )
        place = {"latitude": latitude, "longitude": longitude, "elevation": elevation}
        channels = [
            Channel(
                code=code,
                location_code=location,
                **place,
                depth=0.0,
                azimuth=azimuth,
                dip=dip,
                sample_rate=100.0,
                start_date=start_date,
                response=Response(instrument_sensitivity=sens),
            )
            for code, azimuth, dip in (("HNN", 0.0, 0.0), ("HNE", 90.0, 0.0), ("HNZ", 0.0, -90.0))
        ]
        stations = [Station(station, **place, channels=channels)]
        return Inventory(networks=[Network("XX", stations=stations)], source="rockscreen tests")

    return make
