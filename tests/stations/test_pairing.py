"""Pairing towers with stations: explicit, nearest (geodesic), all, unpaired."""

from __future__ import annotations

import math

import pytest

from rockscreen.stations.errors import RockscreenError
from rockscreen.stations.inventory import Tower
from rockscreen.stations.pairing import (
    DEFAULT_MAX_DISTANCE_KM,
    StationSite,
    pair_towers,
    pair_towers_detailed,
)

# The four L'Aquila 2009 stations (coordinates from ITACA, see ../shared/data/SOURCES.md).
AQV = StationSite("IT.AQV", 42.37722, 13.34389)
AQG = StationSite("IT.AQG", 42.37347, 13.33703)
GSA = StationSite("IT.GSA", 42.42069, 13.51936)
AVZ = StationSite("IT.AVZ", 42.02746, 13.42593)
SITES = [AVZ, GSA, AQG, AQV]  # deliberately not sorted


def tower(tower_id, lat=None, lon=None, station=None):
    return Tower(tower_id, 2.0, 6.0, lat=lat, lon=lon, station=station)


def test_default_distance_is_documented():
    assert DEFAULT_MAX_DISTANCE_KM == 50.0
    import rockscreen.stations.pairing as module

    assert "DEFAULT_MAX_DISTANCE_KM = 50" in module.__doc__


def test_nearest_station_wins():
    towers = [
        tower("near-AQV", 42.380, 13.350),
        tower("near-AQG", 42.370, 13.330),
        tower("near-GSA", 42.43, 13.52),
        tower("near-AVZ", 42.03, 13.43),
    ]
    pairs = pair_towers(towers, SITES)
    assert pairs == {
        "near-AQV": ["IT.AQV"],
        "near-AQG": ["IT.AQG"],
        "near-GSA": ["IT.GSA"],
        "near-AVZ": ["IT.AVZ"],
    }
    detail = pair_towers_detailed(towers, SITES)["near-AVZ"]
    assert detail.rule == "nearest"
    assert detail.distance_km == pytest.approx(0.35, abs=0.1)
    assert "nearest station IT.AVZ at" in detail.reason


def test_distance_is_geodesic():
    # AQV-AVZ: 39.44 km on the WGS84 ellipsoid (a sphere of radius 6371 km gives 39.3 km).
    probe = tower("at-AQV", AQV.latitude, AQV.longitude)
    far = pair_towers_detailed([probe], [AVZ], max_distance_km=100)["at-AQV"]
    assert far.distance_km == pytest.approx(39.437, abs=0.005)


def test_too_far_is_unpaired_with_a_reason():
    lonely = tower("Bari", 41.12, 16.87)
    detail = pair_towers_detailed([lonely], SITES)["Bari"]
    assert detail.keys == () and detail.rule == "unpaired"
    assert "no station within 50 km" in detail.reason
    assert pair_towers([lonely], SITES) == {"Bari": []}
    # a larger limit pairs it with the nearest: AVZ is the southernmost of the four
    assert pair_towers([lonely], SITES, max_distance_km=500) == {"Bari": ["IT.AVZ"]}


def test_max_distance_boundary():
    probe = tower("p", AQV.latitude, AQV.longitude)
    assert pair_towers([probe], [AVZ], max_distance_km=39.5) == {"p": ["IT.AVZ"]}
    assert pair_towers([probe], [AVZ], max_distance_km=39.4) == {"p": []}


@pytest.mark.parametrize(
    ("station", "expected"), [("IT.AVZ", ["IT.AVZ"]), ("AVZ", ["IT.AVZ"]), ("it.avz", ["IT.AVZ"])]
)
def test_explicit_station_wins_over_nearest(station, expected):
    beside_aqv = tower("T", 42.378, 13.344, station=station)
    detail = pair_towers_detailed([beside_aqv], SITES)["T"]
    assert list(detail.keys) == expected
    assert detail.rule == "explicit"
    assert detail.distance_km == pytest.approx(39.4, abs=0.2)


def test_explicit_bare_station_code_matches_every_network():
    sites = [StationSite("IT.AQV", 42.0, 13.0), StationSite("XX.AQV", 42.1, 13.1)]
    assert pair_towers([tower("T", station="AQV")], sites) == {"T": ["IT.AQV", "XX.AQV"]}


def test_explicit_station_absent_gives_no_pair_and_a_reason():
    detail = pair_towers_detailed([tower("T", 42.37, 13.34, station="IT.XYZ")], SITES)["T"]
    assert detail.keys == () and detail.rule == "unpaired"
    assert "explicit station 'IT.XYZ' is not among the records' stations" in detail.reason
    assert "IT.AQV" in detail.reason


def test_tower_without_coordinates_gets_every_station():
    detail = pair_towers_detailed([tower("T")], SITES)["T"]
    assert detail.keys == ("IT.AQG", "IT.AQV", "IT.AVZ", "IT.GSA")  # sorted, order-free
    assert detail.rule == "all" and "the tower has no coordinates" in detail.reason


def test_no_site_coordinates_pairs_every_tower_with_every_station():
    sites = [StationSite("XX.B"), StationSite("XX.A", math.nan, 13.0)]
    pairs = pair_towers([tower("T1", 42.0, 13.0), tower("T2")], sites)
    assert pairs == {"T1": ["XX.A", "XX.B"], "T2": ["XX.A", "XX.B"]}


def test_unlocated_sites_join_the_nearest():
    sites = [AQV, StationSite("XX.UNK")]
    assert pair_towers([tower("T", 42.38, 13.35)], sites) == {"T": ["IT.AQV", "XX.UNK"]}
    far = pair_towers_detailed([tower("F", 45.0, 9.0)], sites)["F"]
    assert far.keys == ("XX.UNK",) and "without coordinates" in far.reason


def test_no_sites_at_all():
    detail = pair_towers_detailed([tower("T", 42.0, 13.0)], [])["T"]
    assert detail.keys == () and detail.rule == "unpaired"


def test_tie_goes_to_the_first_key():
    sites = [StationSite("XX.B", 42.0, 13.1), StationSite("XX.A", 42.0, 12.9)]
    assert pair_towers([tower("T", 42.0, 13.0)], sites) == {"T": ["XX.A"]}


def test_result_does_not_depend_on_site_order():
    towers = [tower(f"T{i}", 42.0 + 0.05 * i, 13.3 + 0.02 * i) for i in range(10)]
    assert pair_towers(towers, SITES) == pair_towers(towers, list(reversed(SITES)))


@pytest.mark.parametrize("bad", [0.0, -5.0, math.nan, math.inf])
def test_max_distance_must_be_positive(bad):
    with pytest.raises(RockscreenError, match="max_distance_km"):
        pair_towers([tower("T")], SITES, max_distance_km=bad)


def test_duplicate_site_keys_are_refused():
    with pytest.raises(RockscreenError, match="duplicate key"):
        pair_towers([tower("T")], [AQV, AQV])
