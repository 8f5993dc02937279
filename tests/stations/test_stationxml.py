"""Station coordinates, orientations and sensitivities from StationXML."""

from __future__ import annotations

import math

import pytest
from obspy import UTCDateTime

from rockscreen.stations.errors import StationMetadataError
from rockscreen.stations.stationxml import read_station_metadata, station_coordinates


@pytest.fixture
def xml_path(tmp_path, make_inventory):
    path = tmp_path / "stations.xml"
    make_inventory().write(str(path), format="STATIONXML")
    return path


def test_coordinates_from_file(xml_path):
    meta = read_station_metadata(xml_path)
    assert meta.station_codes() == ["XX.ABC"]
    assert meta.coordinates("XX.ABC") == {"latitude": 42.5, "longitude": 13.25, "elevation": 700.0}
    assert station_coordinates(xml_path, "XX.ABC..HNZ")["latitude"] == 42.5


def test_inventory_in_memory_is_accepted(make_inventory):
    meta = read_station_metadata(make_inventory())
    assert read_station_metadata(meta) is meta
    assert meta.coordinates("XX.ABC")["longitude"] == 13.25


def test_orientation_and_sensitivity(xml_path):
    meta = read_station_metadata(xml_path)
    time = UTCDateTime(2020, 1, 1)
    assert meta.orientation("XX.ABC..HNE", time) == {"azimuth": 90.0, "dip": 0.0}
    sens = meta.sensitivity("XX.ABC..HNN", time)
    assert sens.value == pytest.approx(2.0e5)
    assert sens.input_units == "M/S**2"
    assert math.isclose(sens.frequency, 1.0)
    assert meta.has_channel("XX.ABC..HNN", time)
    assert not meta.has_channel("XX.ABC..HNN", UTCDateTime(1990, 1, 1))


def test_unknown_station_lists_known_ones(xml_path):
    meta = read_station_metadata(xml_path)
    with pytest.raises(StationMetadataError, match=r"no station 'XX.ZZZ'.*XX\.ABC"):
        meta.coordinates("XX.ZZZ")
    with pytest.raises(StationMetadataError, match="NET.STA"):
        meta.coordinates("ABC")
    with pytest.raises(StationMetadataError, match="no channel"):
        meta.sensitivity("XX.ABC..BHZ")
    with pytest.raises(StationMetadataError, match="NET.STA.LOC.CHA"):
        meta.sensitivity("XX.ABC")


def test_missing_and_invalid_files(tmp_path):
    with pytest.raises(StationMetadataError, match="no such file"):
        read_station_metadata(tmp_path / "absent.xml")
    bad = tmp_path / "bad.xml"
    bad.write_text("<not station xml")
    with pytest.raises(StationMetadataError, match="not readable StationXML") as info:
        read_station_metadata(bad)
    assert str(bad) in str(info.value)


@pytest.mark.data
def test_laquila_coordinates_match_sources_table(shared_data):
    meta = read_station_metadata(shared_data / "laquila2009" / "stations.xml")
    expected = {  # SOURCES.md, rounded to 5 decimals there
        "IT.AQV": (42.37722, 13.34389),
        "IT.AQG": (42.37347, 13.33703),
        "IT.GSA": (42.42069, 13.51936),
        "IT.AVZ": (42.02746, 13.42593),
    }
    for code, (lat, lon) in expected.items():
        coords = meta.coordinates(code)
        assert coords["latitude"] == pytest.approx(lat, abs=1e-5)
        assert coords["longitude"] == pytest.approx(lon, abs=1e-5)


@pytest.mark.data
def test_petrolia_sensitivity(shared_data):
    meta = read_station_metadata(shared_data / "formats" / "mseed_response" / "CE.79435.xml")
    sens = meta.sensitivity("CE.79435.10.HNE", UTCDateTime(2021, 12, 20, 20, 13))
    assert sens.input_units == "M/S**2"
    assert sens.value == pytest.approx(214580.74612)
    assert meta.orientation("CE.79435.10.HNE", UTCDateTime(2021, 12, 20))["azimuth"] == 270.0
