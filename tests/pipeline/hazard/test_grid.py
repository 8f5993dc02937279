"""Site hazard from the shipped NTC 2018 grid (Allegato A interpolation rules)."""

from __future__ import annotations

import csv
import gzip
import io
import math
from importlib import resources

import numpy as np
import pytest

from rockscreen.pipeline.errors import HazardError, RockscreenError
from rockscreen.pipeline.hazard import RETURN_PERIODS_Y, hazard_curve, site_hazard
from rockscreen.pipeline.hazard.grid import (
    MAX_NODE_DISTANCE_KM,
    great_circle_km,
    hazard_grid,
    site_hazards,
)

LAQUILA = (13.3995, 42.3498)


@pytest.fixture(scope="module")
def table():
    """The shipped table, read independently with the csv module (rows of floats)."""
    raw = (
        resources.files("rockscreen.pipeline.hazard") / "data" / "ntc2018_grid.csv.gz"
    ).read_bytes()
    reader = csv.reader(io.StringIO(gzip.decompress(raw).decode("ascii")))
    header = [name.strip() for name in next(reader)]
    rows = [[float(cell) for cell in row] for row in reader]
    return header, np.array(rows)


def test_shipped_table_is_package_data(table):
    header, rows = table
    assert rows.shape == (10751, 29)
    assert header[:5] == ["lon_deg", "lat_deg", "ag_30_g10", "F0_30", "Tc_30_s"]
    assert list(RETURN_PERIODS_Y) == [30, 50, 72, 101, 140, 201, 475, 975, 2475]


def test_shipped_table_matches_shared_copy(shared_data):
    source = shared_data / "hazard" / "ntc2018_grid.csv"
    if not source.is_file():
        pytest.skip(f"{source} is absent")
    raw = (
        resources.files("rockscreen.pipeline.hazard") / "data" / "ntc2018_grid.csv.gz"
    ).read_bytes()
    assert gzip.decompress(raw) == source.read_bytes()


def test_laquila_475_within_one_percent():
    site = site_hazard(*LAQUILA, 475)
    assert site.ag_g == pytest.approx(0.261, rel=0.01)
    assert site.F0 == pytest.approx(2.364, rel=0.01)
    assert site.Tc_star_s == pytest.approx(0.347, rel=0.01)


@pytest.mark.parametrize("row", [0, 4321, 10750])
def test_node_returns_its_own_values_exactly(table, row):
    header, rows = table
    lon, lat = rows[row, 0], rows[row, 1]
    for k, tr in enumerate(RETURN_PERIODS_Y):
        site = site_hazard(lon, lat, tr)
        assert site.ag_g == rows[row, 2 + 3 * k] / 10.0
        assert site.F0 == rows[row, 3 + 3 * k]
        assert site.Tc_star_s == rows[row, 4 + 3 * k]


def test_inverse_distance_of_four_nearest_nodes(table):
    _, rows = table
    lon, lat = 14.4213, 41.0417  # between nodes near Cervino
    d = great_circle_km(lon, lat, rows[:, 0], rows[:, 1])
    nearest = np.argsort(d)[:4]
    w = 1.0 / d[nearest]
    # ag at 475 years is column 2 + 3*6 = 20 (in g/10); F0 column 21; T*C column 22.
    ag = np.sum(w * rows[nearest, 20] / 10.0) / np.sum(w)
    f0 = np.sum(w * rows[nearest, 21]) / np.sum(w)
    site = site_hazard(lon, lat, 475)
    assert site.ag_g == pytest.approx(ag, rel=1e-12)
    assert site.F0 == pytest.approx(f0, rel=1e-12)
    assert hazard_curve(lon, lat)[1][6] == pytest.approx(ag, rel=1e-12)


def test_between_tabulated_return_periods_log_log(table):
    _, rows = table
    lon, lat = rows[100, 0], rows[100, 1]
    # TR = 300 y lies between 201 (index 5) and 475 (index 6).
    p1, p2 = rows[100, 2 + 3 * 5] / 10.0, rows[100, 2 + 3 * 6] / 10.0
    expected = math.exp(
        math.log(p1) + math.log(p2 / p1) * math.log(300 / 201) / math.log(475 / 201)
    )
    assert site_hazard(lon, lat, 300).ag_g == pytest.approx(expected, rel=1e-12)
    # Monotone between the two tabulated values and not the linear interpolation.
    linear = p1 + (p2 - p1) * (300 - 201) / (475 - 201)
    assert min(p1, p2) < expected < max(p1, p2)
    assert expected != pytest.approx(linear, rel=1e-6)


@pytest.mark.parametrize("tr", [10.0, 29.9, 2500.0, 0.0, -5.0, float("nan")])
def test_return_period_outside_table_refused(tr):
    with pytest.raises(HazardError, match="TR="):
        site_hazard(*LAQUILA, tr)


def test_clamp_on_request():
    low = site_hazard(*LAQUILA, 21.0, out_of_range="clamp")
    assert low.return_period_y == 30.0
    assert low.ag_g == site_hazard(*LAQUILA, 30.0).ag_g


@pytest.mark.parametrize(
    ("lon", "lat"),
    [(10.0, 39.0), (12.0, 40.0), (12.6, 35.5), (-20.0, 10.0)],
)
def test_site_off_grid_refused(lon, lat):
    with pytest.raises(HazardError, match="outside the NTC 2018 hazard grid") as info:
        site_hazard(lon, lat, 475)
    assert isinstance(info.value, RockscreenError)
    assert "\n" not in str(info.value)


def test_grid_spacing_measured():
    spacing = hazard_grid().spacing_km
    assert 5.0 < spacing < 6.0
    assert spacing <= MAX_NODE_DISTANCE_KM < 1.1 * spacing


def test_bad_coordinates_refused():
    with pytest.raises(HazardError, match="lat_deg"):
        site_hazard(13.0, 95.0, 475)
    with pytest.raises(HazardError, match="lon_deg"):
        site_hazard("x", 42.0, 475)


def test_many_return_periods_at_once_are_site_hazard_bit_for_bit():
    """site_hazards: each element site_hazard's (tabulated TR, between them, both ends)."""
    rng = np.random.default_rng(4)
    for lon, lat in (LAQUILA, (14.42, 41.04), (15.65, 38.10), (11.25, 43.77)):
        periods = [*np.exp(rng.uniform(math.log(30.0), math.log(2475.0), 500)), 30, 2475.0]
        periods += RETURN_PERIODS_Y.tolist()
        many = site_hazards(lon, lat, periods)
        assert many == [site_hazard(lon, lat, tr) for tr in periods]
    assert site_hazards(*LAQUILA, [10.0, 5000.0], out_of_range="clamp") == [
        site_hazard(*LAQUILA, tr, out_of_range="clamp") for tr in (10.0, 5000.0)
    ]
    with pytest.raises(HazardError, match="outside the tabulated"):
        site_hazards(*LAQUILA, [100.0, 3000.0])
    with pytest.raises(HazardError, match="outside the NTC 2018 hazard grid"):
        site_hazards(0.0, 0.0, [100.0])
