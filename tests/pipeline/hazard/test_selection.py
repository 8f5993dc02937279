"""Spectrum-compatible record sets (NTC 2018 §3.2.3.6): selection and the synthetic suite."""

from __future__ import annotations

import numpy as np
import pytest

from rockscreen.pipeline.errors import HazardError
from rockscreen.pipeline.hazard import (
    LIMIT_STATES,
    SuiteRecord,
    elastic_spectrum,
    limit_state_return_period,
    load_suite,
    select_records,
    site_hazard,
    site_record_set,
    synthetic_suite,
)
from rockscreen.pipeline.hazard.selection import N_MATCH_PERIODS
from rockscreen.pipeline.motion.spectra import response_spectrum
from rockscreen.solver.constants import G

LAQUILA = (13.3995, 42.3498)
CERVINO = (14.42, 41.04)  # S. Anna in Cervino (CE)
VENEZIA = (12.33, 45.44)  # low hazard
TARGET_T = np.geomspace(0.02, 5.0, 100)


def _harmonic(name: str, amplitude: float, frequency: float) -> SuiteRecord:
    t = np.arange(0, 20, 0.01)
    acc = amplitude * np.sin(2 * np.pi * frequency * t) * np.sin(np.pi * t / 20) ** 2
    return SuiteRecord(name, acc, None, None, 0.01, "test")


def test_selection_scales_to_a_target_made_of_the_records():
    # Seven copies of one shape at different amplitudes: the target is that shape, so the
    # least-squares factors bring every copy onto it and the ratio is flat at the centre.
    base = _harmonic("base", 1.0, 1.0)
    suite = [
        SuiteRecord(f"r{k}", base.acc_x_m_s2 * a, None, None, 0.01, "test")
        for k, a in enumerate([0.5, 0.8, 1.0, 1.3, 2.0, 2.5, 3.0])
    ]
    periods = np.geomspace(0.15, 2.0, N_MATCH_PERIODS)  # the matching periods themselves
    sa, _ = response_spectrum(base.acc_x_m_s2, 0.01, periods)
    result = select_records(suite, periods, sa / G)
    assert result.meets_tolerance
    assert result.message.startswith("meets the tolerance")
    # The common factor centres the ratio at sqrt(0.9 * 1.3) = 1.0817.
    assert result.ratio_min == pytest.approx(np.sqrt(0.9 * 1.3), rel=1e-6)
    assert result.ratio_max == pytest.approx(np.sqrt(0.9 * 1.3), rel=1e-6)
    amplitude = {r.name: a for r, a in zip(suite, [0.5, 0.8, 1.0, 1.3, 2.0, 2.5, 3.0], strict=True)}
    for record, factor in zip(result.records, result.scale_factors, strict=True):
        assert factor * amplitude[record.name] == pytest.approx(np.sqrt(0.9 * 1.3), rel=1e-6)
    scaled = result.scaled(0)
    assert np.allclose(scaled.acc_x_m_s2, result.records[0].acc_x_m_s2 * result.scale_factors[0])


def test_selection_reports_failure_and_keeps_best():
    # Narrow-band records at 5 Hz cannot follow a broad code spectrum out to 2 s.
    suite = [_harmonic(f"h{k}", 1.0 + k, 5.0) for k in range(8)]
    site = site_hazard(*LAQUILA, 475)
    result = select_records(suite, TARGET_T, elastic_spectrum(TARGET_T, site))
    assert not result.meets_tolerance
    assert result.message.startswith("does not meet the tolerance")
    assert "worst at T=" in result.message
    assert len(result.records) == 7
    assert result.ratio_min < 0.9 or result.ratio_max > 1.3


def test_selection_options_checked():
    suite = [_harmonic("a", 1.0, 1.0)]
    with pytest.raises(HazardError, match="empty"):
        select_records([], TARGET_T, np.ones_like(TARGET_T))
    with pytest.raises(HazardError, match="period_range_s"):
        select_records(suite, TARGET_T, np.ones_like(TARGET_T), period_range_s=(2.0, 0.1))
    with pytest.raises(HazardError, match="cover the matching range"):
        select_records(suite, [0.5, 1.0], [1.0, 1.0])
    result = select_records(suite, TARGET_T, np.ones_like(TARGET_T), n_records=3)
    assert "only 1 records in the suite, 3 wanted" in result.message


@pytest.mark.parametrize("site", [LAQUILA, CERVINO, VENEZIA], ids=["laquila", "cervino", "venezia"])
def test_synthetic_suite_meets_tolerance_at_every_limit_state(site):
    ag = []
    for state in LIMIT_STATES:
        tr = limit_state_return_period(state, 50.0, "III")
        result = site_record_set(*site, tr, "B", "T1", kind="matched")
        assert result.meets_tolerance, result.message
        assert 0.9 <= result.ratio_min <= result.ratio_max <= 1.3
        assert len(result.records) == 7
        assert np.all((result.scale_factors >= 0.25) & (result.scale_factors <= 4.0))
        ag.append(site_hazard(*site, tr).ag_g)
    assert ag == sorted(ag)


def test_synthetic_suite_is_seeded_cached_and_three_component():
    first = synthetic_suite(*CERVINO, 475.0, "C", n_records=7, seed=3)
    again = synthetic_suite(*CERVINO, 475.0, "C", n_records=7, seed=3)
    assert [r.name for r in first] == [r.name for r in again]
    assert first[0].acc_x_m_s2 is again[0].acc_x_m_s2  # cached, read-only arrays
    assert not first[0].acc_x_m_s2.flags.writeable
    for record in first:
        assert record.acc_y_m_s2.shape == record.acc_x_m_s2.shape == record.acc_z_m_s2.shape
        assert record.dt_s == 0.01
        assert "seed=(3," in record.source
    other = synthetic_suite(*CERVINO, 475.0, "C", n_records=7, seed=4)
    assert not np.array_equal(other[0].acc_x_m_s2, first[0].acc_x_m_s2)


def test_laquila_records_selection(shared_data):
    folders = [shared_data / "laquila2009", shared_data / "laquila2009_regional"]
    for folder in folders:
        if not (folder / "stations.xml").is_file():
            pytest.skip(f"{folder} is absent")
    suite = [record for folder in folders for record in load_suite(folder)]
    assert len(suite) == 11
    assert all(r.acc_z_m_s2 is not None and r.acc_y_m_s2 is not None for r in suite)
    aqv = next(r for r in suite if r.name == "IT.AQV..HN")
    # PGA of the first horizontal (HNN, ITACA): 5.366 m/s².
    assert np.max(np.abs(aqv.acc_x_m_s2)) == pytest.approx(5.366, rel=0.01)
    tr = limit_state_return_period("SLV", 50.0, "III")
    result = site_record_set(*LAQUILA, tr, "B", suite=suite)
    assert len(result.records) == 7
    if result.meets_tolerance:
        assert 0.9 <= result.ratio_min <= result.ratio_max <= 1.3
    else:
        # Eleven records, most of them weak and far: the message must say why.
        assert result.message.startswith("does not meet the tolerance")
        assert "worst at T=" in result.message
    # The set is the best the search found: no single swap with an unused record gets the
    # mean closer to the band.
    chosen = {r.name for r in result.records}
    assert len(chosen) == 7
