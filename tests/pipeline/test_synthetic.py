"""Example records: stochastic model pieces, determinism, files ObsPy reads back."""

from __future__ import annotations

import numpy as np
import obspy
import pytest

from rockscreen.pipeline.motion.synthetic import (
    DURATION_S,
    EXAMPLE_STATIONS,
    SAMPLING_RATE_HZ,
    clough_penzien_gain,
    example_station_sites,
    filter_coefficients,
    kanai_tajimi_gain,
    saragoni_hart_envelope,
    stochastic_accelerogram,
    write_example_records,
)
from rockscreen.solver.constants import G
from rockscreen.stations.inventory import example_inventory_path, read_inventory
from rockscreen.stations.pairing import pair_towers


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    return write_example_records(tmp_path_factory.mktemp("example"))


def test_envelope_peak_and_decay():
    t_n = 20.0
    t = np.linspace(-1.0, 2 * t_n, 40001)
    env = saragoni_hart_envelope(t, t_n)
    assert env[t <= 0].max() == 0.0
    assert env.max() == pytest.approx(1.0, abs=1e-6)
    assert t[np.argmax(env)] == pytest.approx(0.2 * t_n, abs=2e-3)
    assert saragoni_hart_envelope(np.array([t_n]), t_n)[0] == pytest.approx(0.05, rel=1e-12)


def test_filter_gains():
    f = np.array([0.0, 2.5, 1000.0])
    kt = np.abs(kanai_tajimi_gain(f, 2.5, 0.6))
    assert kt[0] == pytest.approx(1.0)
    # at the ground frequency |H| = sqrt(1 + 4 zeta^2) / (2 zeta)
    assert kt[1] == pytest.approx(np.sqrt(1 + 4 * 0.36) / 1.2)
    assert kt[2] < 0.01
    cp = np.abs(clough_penzien_gain(f, 0.25, 0.6))
    assert cp[0] == 0.0 and cp[2] == pytest.approx(1.0, abs=1e-6)


def test_digital_filter_matches_the_analog_gains():
    from scipy.signal import freqz

    f = np.array([0.1, 0.25, 1.0, 2.5, 4.0])
    b, a = filter_coefficients(2.5, 0.6, 0.01)
    _, digital = freqz(b, a, worN=f, fs=100.0)
    analog = kanai_tajimi_gain(f, 2.5, 0.6) * clough_penzien_gain(f, 0.25, 0.6)
    # bilinear warping: below 0.5 % in frequency up to 4 Hz at 100 Hz
    np.testing.assert_allclose(np.abs(digital), np.abs(analog), rtol=0.01)


def test_accelerogram_peak_and_no_drift():
    dt = 0.01
    acc = stochastic_accelerogram(
        np.random.default_rng(1),
        n_samples=4000,
        dt=dt,
        pga=3.0,
        ground_frequency=2.5,
        ground_damping=0.6,
        envelope_duration=20.0,
        onset=2.0,
    )
    assert np.abs(acc).max() == pytest.approx(3.0)
    assert np.all(acc[: round(2.0 / dt)] == 0.0)  # nothing before the onset
    assert acc[-1] == pytest.approx(0.0, abs=1e-12)  # ends at rest
    velocity = np.cumsum(acc) * dt
    displacement = np.cumsum(velocity) * dt
    # Clough-Penzien high-pass: final velocity and displacement small against the peaks
    assert abs(velocity[-1]) < 0.02 * np.abs(velocity).max()
    assert abs(displacement[-1]) < 0.05 * np.abs(displacement).max()


def test_files_and_stationxml(written):
    records, stationxml = written
    assert len(records) == 3 * len(EXAMPLE_STATIONS) == 9
    inventory = obspy.read_inventory(str(stationxml))
    for path in records:
        stream = obspy.read(str(path))
        assert len(stream) == 1
        trace = stream[0]
        assert trace.data.dtype == np.float64
        assert trace.stats.mseed.encoding == "FLOAT64"
        assert trace.stats.sampling_rate == SAMPLING_RATE_HZ
        assert trace.stats.npts == round(DURATION_S * SAMPLING_RATE_HZ)
        assert path.name == f"{trace.id}.mseed"
        response = inventory.get_response(trace.id, trace.stats.starttime)
        assert response.instrument_sensitivity.input_units == "M/S**2"
        assert response.instrument_sensitivity.value == 1.0
        coordinates = inventory.get_coordinates(trace.id, trace.stats.starttime)
        site = next(s for s in EXAMPLE_STATIONS if s.code == trace.stats.station)
        assert coordinates["latitude"] == site.latitude


def test_pga_decreases_with_distance_and_vertical_is_smaller(written):
    records, _ = written
    stream = obspy.Stream()
    for path in records:
        stream += obspy.read(str(path))
    pga = {tr.id: np.abs(tr.data).max() / G for tr in stream}
    near, mid, far = (s.code for s in EXAMPLE_STATIONS)
    horizontal = {
        code: max(pga[f"XX.{code}..HNE"], pga[f"XX.{code}..HNN"]) for code in (near, mid, far)
    }
    assert horizontal[near] == pytest.approx(0.40)
    assert horizontal[mid] == pytest.approx(0.20)
    assert horizontal[far] == pytest.approx(0.05)
    for code in (near, mid, far):
        assert pga[f"XX.{code}..HNZ"] < pga[f"XX.{code}..HNN"] < pga[f"XX.{code}..HNE"]


def test_deterministic_bytes(written, tmp_path):
    records, stationxml = written
    again, again_xml = write_example_records(tmp_path)
    assert [p.name for p in again] == [p.name for p in records]
    for first, second in zip(records, again, strict=True):
        assert first.read_bytes() == second.read_bytes()
    assert stationxml.read_bytes() == again_xml.read_bytes()


def test_example_inventory_pairs_with_example_stations():
    towers = read_inventory(example_inventory_path())
    pairs = pair_towers(towers, example_station_sites())
    assert all(pairs.values()), pairs  # every example tower gets a record
    assert pairs["CE-SANNA"] == ["XX.SYN1"]
    assert pairs["ARC-07"] == ["XX.SYN2"]  # explicit station, no coordinates
    used = {key for keys in pairs.values() for key in keys}
    assert used == {site.key for site in example_station_sites()}
