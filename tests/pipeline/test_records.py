"""Grouping traces into records, pairing horizontals, rotating to a tower's axes."""

from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from obspy import Stream, Trace, UTCDateTime
from obspy.core.util import AttribDict

from rockscreen.pipeline.errors import ProcessingError
from rockscreen.pipeline.records.grouping import classify, group_records, rotate_horizontals

START = UTCDateTime(2020, 5, 1, 10)


def trace(channel, data=None, station="ABC", start=START, dt=0.01, orientation=None):
    data = np.arange(100, dtype=np.float64) if data is None else np.asarray(data, dtype=float)
    tr = Trace(data, header={"network": "XX", "station": station, "channel": channel})
    tr.stats.delta = dt
    tr.stats.starttime = start
    tr.stats.coordinates = AttribDict(latitude=1.0, longitude=2.0, elevation=3.0)
    tr.stats.rockscreen = AttribDict(units="m/s2", provenance=[{"step": "read"}])
    if orientation is not None:
        tr.stats.orientation = AttribDict(azimuth=orientation[0], dip=orientation[1])
    return tr


def test_groups_by_station_and_time_window():
    later = START + 3600
    stream = Stream(
        [
            trace("HNZ"),
            trace("HNE"),
            trace("HNN"),
            trace("HNN", station="DEF"),
            trace("HNN", start=later),
            trace("HNE", start=later),
        ]
    )
    records = group_records(stream)
    assert [(r.id, r.starttime) for r in records] == [
        ("XX.ABC..HN", START),
        ("XX.ABC..HN", later),
        ("XX.DEF..HN", START),
    ]
    first = records[0]
    assert first.channels == {"h1": "XX.ABC..HNN", "h2": "XX.ABC..HNE", "z": "XX.ABC..HNZ"}
    assert (first.h1_azimuth, first.h2_azimuth) == (0.0, 90.0)
    assert first.coordinates == {"latitude": 1.0, "longitude": 2.0, "elevation": 3.0}
    assert first.station == "XX.ABC" and first.npts == 100 and first.dt == 0.01
    assert first.provenance["h1"] == [{"step": "read"}]
    assert first.provenance["record"][0]["step"] == "common_grid"
    assert records[1].z is None


@pytest.mark.parametrize(
    ("channel", "vertical", "azimuth"),
    [
        ("HNN", False, 0.0),
        ("HNE", False, 90.0),
        ("HNZ", True, None),
        ("HN1", False, None),
        ("HN3", True, None),
        ("NS", False, 0.0),
        ("EW", False, 90.0),
        ("UD", True, None),
        ("067", False, 67.0),
        ("360", False, 0.0),
        ("UP", True, None),
        ("DWN", True, None),
        ("H2", False, None),
    ],
)
def test_classify(channel, vertical, azimuth):
    component = classify(trace(channel))
    assert (component.vertical, component.azimuth) == (vertical, azimuth)


def test_stationxml_orientation_wins():
    assert classify(trace("HNE", orientation=(270.0, 0.0))).azimuth == 270.0
    assert classify(trace("HN1", orientation=(0.0, -90.0))).vertical


def test_unknown_channel_is_an_error():
    with pytest.raises(ProcessingError, match="horizontal or vertical"):
        classify(trace("XYZQ"))


def test_duplicate_components_are_an_error():
    with pytest.raises(ProcessingError, match="more than two horizontals"):
        group_records(Stream([trace("HNN"), trace("HNE"), trace("HN1", start=START + 0.2)]))


def test_common_grid_trims_and_interpolates():
    h1 = trace("HNN", np.arange(200.0), start=START)
    h2 = trace("HNE", np.arange(50.0) * 2.0, start=START + 0.5, dt=0.02)
    (record,) = group_records(Stream([h1, h2]))
    assert record.starttime == START + 0.5
    assert record.dt == 0.01
    np.testing.assert_allclose(record.h1[:3], [50.0, 51.0, 52.0])
    # h2 = 2 * sample index at 0.02 s = 100 * time since its start: linear, so exact.
    np.testing.assert_allclose(record.h2, 100.0 * record.times)
    step = record.provenance["record"][0]
    assert step["interpolated_linear"] == ["XX.ABC..HNE"] and step["trimmed"] == ["XX.ABC..HNN"]


def test_no_common_window():
    from rockscreen.pipeline.records.grouping import common_grid

    with pytest.raises(ProcessingError, match="share no time window"):
        common_grid([trace("HNN"), trace("HNE", start=START + 10)], "XX.ABC..HN")


def test_rotation_by_90_swaps_with_a_sign():
    north, east = np.array([1.0, 2.0, -3.0]), np.array([0.5, -1.0, 4.0])
    (record,) = group_records(Stream([trace("HNN", north), trace("HNE", east)]))
    along, across = record.rotate(90.0)
    np.testing.assert_allclose(along, east, atol=1e-12)
    np.testing.assert_allclose(across, -north, atol=1e-12)
    along0, across0 = record.rotate(0.0)
    np.testing.assert_allclose(along0, north, atol=1e-12)
    np.testing.assert_allclose(across0, east, atol=1e-12)


def test_rotation_with_a_west_pointing_channel():
    # The Petrolia station's HNE points to 270 deg: its positive values are westward.
    north, west = np.array([1.0, 0.0]), np.array([0.0, 2.0])
    along, across = rotate_horizontals(north, west, 0.0, 270.0, 90.0)
    np.testing.assert_allclose(along, [0.0, -2.0], atol=1e-12)
    np.testing.assert_allclose(across, [-1.0, 0.0], atol=1e-12)


@given(
    azimuth=st.floats(-720.0, 720.0, allow_nan=False),
    h1_azimuth=st.sampled_from([0.0, 67.0, 90.0, 337.0]),
    handed=st.sampled_from([90.0, -90.0]),
)
def test_rotation_preserves_energy(azimuth, h1_azimuth, handed):
    rng = np.random.default_rng(7)
    h1, h2 = rng.standard_normal(50), rng.standard_normal(50)
    along, across = rotate_horizontals(h1, h2, h1_azimuth, h1_azimuth + handed, azimuth)
    np.testing.assert_allclose(along**2 + across**2, h1**2 + h2**2, rtol=1e-9, atol=1e-12)


def test_rotation_errors():
    (single,) = group_records(Stream([trace("HNN")]))
    with pytest.raises(ProcessingError, match="two horizontal"):
        single.rotate(10.0)
    (unknown,) = group_records(Stream([trace("HN1"), trace("HN2")]))
    with pytest.raises(ProcessingError, match="azimuths .* unknown"):
        unknown.rotate(10.0)
    (skew,) = group_records(Stream([trace("067"), trace("100")]))
    with pytest.raises(ProcessingError, match="not orthogonal"):
        skew.rotate(10.0)
    with pytest.raises(ProcessingError, match="azimuth_deg"):
        skew.rotate(float("nan"))


@pytest.mark.data
def test_real_records_group(shared_data):
    from rockscreen.pipeline.records.io import read_streams

    folder = shared_data / "laquila2009"
    stream, failures = read_streams(
        sorted(folder.glob("*.mseed")), stations=folder / "stations.xml"
    )
    assert failures == []
    records = group_records(stream)
    assert [r.id for r in records] == ["IT.AQG..HN", "IT.AQV..HN", "IT.AVZ..HN", "IT.GSA..HN"]
    aqv = records[1]
    assert aqv.npts == 112600 and aqv.z is not None
    along, across = aqv.rotate(30.0)
    assert np.sum(along**2 + across**2) == pytest.approx(np.sum(aqv.h1**2 + aqv.h2**2))
    at2, _ = read_streams(sorted((shared_data / "formats" / "at2").glob("RSN763*.AT2")))
    (loma,) = group_records(at2)
    assert (loma.h1_azimuth, loma.h2_azimuth) == (67.0, 337.0)
