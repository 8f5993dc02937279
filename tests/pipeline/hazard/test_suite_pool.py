"""The embedded suite's shared pools: batched spectra, reuse across return periods, determinism."""

from __future__ import annotations

import numpy as np
import pytest

from rockscreen.pipeline.hazard import RETURN_PERIODS_Y, SuiteRecord, select_records, site_hazard
from rockscreen.pipeline.hazard import suite as suite_module
from rockscreen.pipeline.hazard.matching import batch_spectrum
from rockscreen.pipeline.hazard.selection import (
    N_MATCH_PERIODS,
    record_spectrum,
    select_from_spectra,
)
from rockscreen.pipeline.hazard.suite import site_record_set, synthetic_suite
from rockscreen.pipeline.motion.spectra import response_spectrum

CERVINO = (14.42, 41.04)


def _clear_caches():
    suite_module._cached_suite.cache_clear()
    suite_module._matched_pool.cache_clear()


def _return_periods_sharing_a_shape(lon, lat, soil):
    by_shape = {}
    for tr in RETURN_PERIODS_Y:
        site = site_hazard(lon, lat, float(tr))
        shape = suite_module._rounded(suite_module._shape_of(site, soil, "T1"))
        by_shape.setdefault(shape, []).append(float(tr))
    return next(trs[:2] for trs in by_shape.values() if len(trs) >= 2)


def test_batch_spectrum_equals_response_spectrum():
    rng = np.random.default_rng(1)
    envelope = np.sin(np.linspace(0.0, np.pi, 1500)) ** 2
    acc = rng.normal(size=(3, 1500)) * envelope
    acc[1] += 0.3  # a record that does not start from zero
    periods = np.geomspace(0.03, 4.0, 25)  # upsampled and plain periods
    batch = batch_spectrum(acc, 0.01, periods, 0.05)
    for row, sa in zip(acc, batch, strict=True):
        reference, _ = response_spectrum(row, 0.01, periods, 0.05)
        np.testing.assert_allclose(sa, reference, rtol=1e-9)


def test_select_from_spectra_is_select_records():
    rng = np.random.default_rng(2)
    t = np.arange(0.0, 15.0, 0.01)
    suite = [
        SuiteRecord(f"r{k}", rng.normal(size=t.size) * np.sin(np.pi * t / 15), None, None, 0.01, "")
        for k in range(9)
    ]
    target_t = np.geomspace(0.02, 5.0, 100)
    target = 0.3 * np.minimum(1.0, 0.5 / target_t)
    direct = select_records(suite, target_t, target, n_records=5)
    periods = np.geomspace(0.15, 2.0, N_MATCH_PERIODS)
    spectra = np.array([record_spectrum(r, periods) for r in suite])
    on_target = np.exp(np.interp(np.log(periods), np.log(target_t), np.log(target)))
    split = select_from_spectra(suite, spectra, periods, on_target, n_records=5)
    assert [r.name for r in split.records] == [r.name for r in direct.records]
    np.testing.assert_allclose(split.scale_factors, direct.scale_factors, rtol=1e-9)


def test_return_periods_of_a_site_reuse_one_matched_pool():
    lon, lat = CERVINO
    first, second = _return_periods_sharing_a_shape(lon, lat, "B")
    _clear_caches()
    sets = [
        site_record_set(lon, lat, tr, "B", "T1", seed=5, kind="matched") for tr in (first, second)
    ]
    info = suite_module._matched_pool.cache_info()
    assert (info.misses, info.hits) == (1, 1)  # matched once, reused for the second TR
    for result in sets:
        assert result.meets_tolerance, result.message
        assert np.all((result.scale_factors > 0.8) & (result.scale_factors < 1.25))
    # Same pool, scaled linearly: a record chosen at both TR differs by one factor only.
    a = {r.name: r for r in synthetic_suite(lon, lat, first, "B", seed=5)}
    b = {r.name: r for r in synthetic_suite(lon, lat, second, "B", seed=5)}
    name = sorted(set(a) & set(b))[0]
    ratio = b[name].acc_x_m_s2 / np.where(a[name].acc_x_m_s2 == 0, np.nan, a[name].acc_x_m_s2)
    assert np.nanmax(ratio) == pytest.approx(np.nanmin(ratio), rel=1e-9)
    assert site_hazard(lon, lat, second).ag_g > site_hazard(lon, lat, first).ag_g
    assert np.nanmax(ratio) > 1.0


def test_nine_return_periods_need_fewer_pools_than_return_periods():
    _clear_caches()
    for tr in RETURN_PERIODS_Y:
        assert site_record_set(
            *CERVINO, float(tr), "A", "T1", seed=6, kind="matched"
        ).meets_tolerance
    assert suite_module._matched_pool.cache_info().misses < len(RETURN_PERIODS_Y)


def test_suite_does_not_depend_on_the_order_of_calls():
    lon, lat = CERVINO
    trs = (50.0, 475.0, 2475.0)
    runs = []
    for order in (trs, trs[::-1]):
        _clear_caches()
        got = {tr: synthetic_suite(lon, lat, tr, "C", "T2", seed=7) for tr in order}
        runs.append(got)
    for tr in trs:
        for one, other in zip(runs[0][tr], runs[1][tr], strict=True):
            assert one.name == other.name and one.source == other.source
            for component in ("acc_x_m_s2", "acc_y_m_s2", "acc_z_m_s2"):
                np.testing.assert_array_equal(getattr(one, component), getattr(other, component))
