"""Response spectra: exact recurrence, closed forms, and the ITACA / ESM reference spectra."""

from __future__ import annotations

import numpy as np
import pytest
from obspy import read
from scipy.linalg import expm

from rockscreen.pipeline.motion.spectra import (
    recurrence,
    recurrence_closed_form,
    recurrence_series,
    response_spectrum,
    sdof_response,
)
from rockscreen.solver.errors import ParameterError

LAQUILA = [f"IT.{sta}..HN{cha}" for sta in ("AQV", "AQG", "GSA", "AVZ") for cha in "ENZ"]
ESM_STEM = "TK.4612..HN{}.D.20230206.102449.C"
ESM_HEADER_LINES = 64  # "DYNA 1.2" header; one value per line follows


def _foh_oracle(period, damping, dt):
    """Exact discretisation with a first-order hold, through a matrix exponential."""
    omega = 2.0 * np.pi / period
    system = np.zeros((4, 4))
    system[0, 1] = 1.0
    system[1, 0] = -(omega**2)
    system[1, 1] = -2.0 * damping * omega
    system[1, 2] = -1.0  # load -a_g
    system[2, 3] = 1.0  # a_g grows linearly within the step
    block = expm(system * dt)
    phi, hold, ramp = block[:2, :2], block[:2, 2], block[:2, 3]
    return phi, hold - ramp / dt, ramp / dt


# omega*dt from 0.25 to 12.6 (closed form) and 0.0003 to 0.13 (series); the oracle's own
# subtraction hold - ramp/dt loses digits as omega*dt -> 0, hence the looser rtol there.
@pytest.mark.parametrize(
    ("period", "damping", "dt", "rtol"),
    [
        (0.5, 0.05, 0.02, 1e-9),
        (0.05, 0.0, 0.005, 1e-9),
        (0.005, 0.2, 0.01, 1e-9),
        (1.0, 0.95, 0.02, 1e-9),
        (0.3, 0.05, 0.005, 1e-8),
        (10.0, 0.3, 0.0005, 1e-5),
    ],
)
def test_recurrence_matches_matrix_exponential(period, damping, dt, rtol):
    coefficients = recurrence(period, damping, dt)
    phi, gamma0, gamma1 = _foh_oracle(period, damping, dt)
    np.testing.assert_allclose(coefficients.phi, phi, rtol=1e-9, atol=1e-12 * np.abs(phi).max())
    np.testing.assert_allclose(coefficients.gamma0, gamma0, rtol=rtol, atol=1e-20)
    np.testing.assert_allclose(coefficients.gamma1, gamma1, rtol=rtol, atol=1e-20)


@pytest.mark.parametrize("damping", [0.0, 0.05, 0.3, 0.95])
@pytest.mark.parametrize("omega_dt", [0.05, 0.1, 0.19])
def test_closed_form_and_series_agree_where_both_are_accurate(damping, omega_dt):
    period, dt = 1.0, omega_dt / (2 * np.pi)
    closed = recurrence_closed_form(period, damping, dt)
    series = recurrence_series(period, damping, dt)
    np.testing.assert_allclose(series.phi, closed.phi, rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(series.gamma0, closed.gamma0, rtol=1e-10)
    np.testing.assert_allclose(series.gamma1, closed.gamma1, rtol=1e-10)


def test_filter_form_equals_the_step_by_step_recurrence():
    rng = np.random.default_rng(1)
    acc = rng.normal(size=2000)
    dt, period, damping = 0.01, 0.3, 0.05
    coefficients = recurrence(period, damping, dt)
    state = np.zeros(2)
    expected = [state.copy()]
    for i in range(acc.size - 1):
        state = (
            coefficients.phi @ state
            + coefficients.gamma0 * acc[i]
            + coefficients.gamma1 * acc[i + 1]
        )
        expected.append(state.copy())
    expected = np.array(expected)
    u, u_dot, total = sdof_response(acc, dt, period, damping)
    scale = np.abs(expected).max(axis=0)
    np.testing.assert_allclose(u, expected[:, 0], atol=1e-12 * scale[0])
    np.testing.assert_allclose(u_dot, expected[:, 1], atol=1e-12 * scale[1])
    omega = 2.0 * np.pi / period
    np.testing.assert_allclose(total, -(omega**2) * u - 2 * damping * omega * u_dot)


def test_undamped_oscillator_under_a_harmonic_matches_the_closed_form():
    # u'' + w^2 u = -A sin(W t) from rest: u = -A/(w^2 - W^2) (sin W t - (W/w) sin w t).
    amplitude, forcing, period, dt = 2.0, 2 * np.pi * 1.3, 0.4, 1e-3
    omega = 2 * np.pi / period
    t = np.arange(0, 5.0, dt)
    acc = amplitude * np.sin(forcing * t)
    exact = (
        -amplitude
        / (omega**2 - forcing**2)
        * (np.sin(forcing * t) - forcing / omega * np.sin(omega * t))
    )
    u, _, _ = sdof_response(acc, dt, period, damping=0.0)
    # Only error: the sine is linear between samples, O((W dt)^2 / 12) ~ 1e-7.
    np.testing.assert_allclose(u, exact, atol=1e-5 * np.abs(exact).max())


def test_rigid_oscillator_gives_the_pga():
    t = np.arange(0, 4.0, 0.002)
    acc = 3.0 * np.sin(2 * np.pi * 1.0 * t) * np.exp(-0.3 * t)
    pga = np.abs(acc).max()
    sa, psa = response_spectrum(acc, 0.002, [0.0, 1e-3], damping=0.05)
    assert sa[0] == psa[0] == pga
    # A 1 ms oscillator follows a 1 Hz motion: SA/PGA - 1 ~ (T/T_motion)^2 ~ 1e-6.
    assert sa[1] == pytest.approx(pga, rel=1e-4)
    assert psa[1] == pytest.approx(pga, rel=1e-4)


def test_sa_equals_psa_without_damping():
    rng = np.random.default_rng(2)
    acc = rng.normal(size=3000)
    periods = np.array([0.05, 0.2, 1.0, 3.0])
    sa, psa = response_spectrum(acc, 0.01, periods, damping=0.0)
    np.testing.assert_allclose(sa, psa, rtol=1e-12)
    sa5, psa5 = response_spectrum(acc, 0.01, periods, damping=0.05)
    assert not np.allclose(sa5, psa5, rtol=1e-6)


def test_upsampling_equals_running_on_a_linearly_interpolated_record():
    rng = np.random.default_rng(3)
    acc = rng.normal(size=400)
    dt, period = 0.02, 0.1  # 5 samples per period -> factor 4 at 20 points per period
    fine_t = np.arange(0, (acc.size - 1) * dt + 1e-12, dt / 4)
    fine = np.interp(fine_t, np.arange(acc.size) * dt, acc)
    expected = response_spectrum(fine, dt / 4, [period], points_per_period=1)
    np.testing.assert_allclose(response_spectrum(acc, dt, [period]), expected, rtol=1e-10)


def test_free_vibration_after_the_record_is_counted():
    # A short ramp then nothing: the long oscillator peaks after the record has ended.
    acc = np.array([0.0, 1.0, 0.0])
    dt, period = 0.01, 2.0
    _, psa = response_spectrum(acc, dt, [period], damping=0.0)
    u, _, _ = sdof_response(np.concatenate([acc, np.zeros(300)]), dt, period, damping=0.0)
    omega = 2 * np.pi / period
    assert psa[0] == pytest.approx(omega**2 * np.abs(u).max(), rel=1e-12)
    assert psa[0] > 10 * omega**2 * np.abs(u[:3]).max()


def test_output_has_the_shape_of_periods():
    acc = np.sin(np.linspace(0, 20, 500))
    sa, psa = response_spectrum(acc, 0.01, 0.5)
    assert sa.shape == psa.shape == ()
    sa, psa = response_spectrum(acc, 0.01, [[0.1, 0.2], [0.3, 0.4]])
    assert sa.shape == (2, 2)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"periods": [0.1, -0.2]}, "periods"),
        ({"periods": [np.nan]}, "periods"),
        ({"damping": 1.0}, "damping=1.0"),
        ({"damping": -0.01}, "damping"),
        ({"dt": 0.0}, "dt=0.0"),
        ({"acc": np.array([0.0, np.inf])}, r"acc\[1\]"),
        ({"acc": np.array([])}, "non-empty"),
        ({"acc": np.zeros((2, 2))}, "1-D"),
    ],
)
def test_invalid_inputs_are_refused(kwargs, message):
    args = {"acc": np.ones(10), "dt": 0.01, "periods": [0.1], "damping": 0.05} | kwargs
    with pytest.raises(ParameterError, match=message):
        response_spectrum(**args)


def test_sdof_response_refuses_a_zero_period():
    with pytest.raises(ParameterError, match="period=0"):
        sdof_response(np.ones(10), 0.01, 0.0)


# --- real references -------------------------------------------------------------------------
# Tolerance 2 % (the acceptance) from 0.05 to 4 s. Measured with the default
# 20 points per period: <= 1.05 % against ITACA's PSA (GSA HNN, 0.10 s).


def _itaca(shared_data, stem):
    trace = read(str(shared_data / "laquila2009" / f"{stem}.mseed"))[0]
    table = np.loadtxt(shared_data / "laquila2009" / f"{stem}.rs.txt", skiprows=1)
    table = table[table[:, 0] >= 0.0]  # the last row (period -1) is the PGV
    return trace, table


@pytest.mark.data
@pytest.mark.parametrize("stem", LAQUILA)
def test_psa_matches_itaca_at_5_percent(shared_data, stem):
    trace, table = _itaca(shared_data, stem)
    periods = table[:, 0]
    _, psa = response_spectrum(trace.data, trace.stats.delta, periods, damping=0.05)
    assert psa[0] == pytest.approx(table[0, 2], rel=1e-6)  # period 0 = PGA
    band = (periods >= 0.05) & (periods <= 4.0)
    np.testing.assert_allclose(psa[band], table[band, 2], rtol=0.02)


@pytest.mark.data
@pytest.mark.parametrize(("column", "damping"), [(3, 0.07), (4, 0.10), (5, 0.20), (6, 0.30)])
def test_psa_matches_itaca_at_other_dampings(shared_data, column, damping):
    # ITACA's 2 % column is left out: for every NS component it departs from any
    # oscillator (e.g. +129 % at 0.19 s for AQV HNN) while the other five columns agree.
    trace, table = _itaca(shared_data, "IT.AVZ..HNE")
    periods = table[:, 0]
    band = (periods >= 0.05) & (periods <= 4.0)
    _, psa = response_spectrum(trace.data, trace.stats.delta, periods[band], damping=damping)
    np.testing.assert_allclose(psa, table[band, column], rtol=0.02)


def _esm(shared_data, component):
    folder = shared_data / "formats" / "esm"
    stem = ESM_STEM.format(component)
    acc = np.loadtxt(folder / f"{stem}.ACC.ASC", skiprows=ESM_HEADER_LINES) / 100.0  # cm/s2
    reference = np.loadtxt(folder / f"{stem}.SA.ASC", skiprows=ESM_HEADER_LINES)
    return acc, reference[:, 0], reference[:, 1] / 100.0


ESM_DT = 0.005  # SAMPLING_INTERVAL_S in the header


@pytest.mark.data
@pytest.mark.parametrize("component", "EN")
def test_sa_matches_esm_horizontals(shared_data, component):
    acc, periods, reference = _esm(shared_data, component)
    band = (periods >= 0.05) & (periods <= 4.0)
    sa, _ = response_spectrum(acc, ESM_DT, periods[band], damping=0.05)
    np.testing.assert_allclose(sa, reference[band], rtol=0.02)  # measured <= 0.45 %


@pytest.mark.data
@pytest.mark.parametrize("component", "ENZ")
def test_esm_method_is_reproduced_with_10_points_per_period(shared_data, component):
    # ESM searches the peak on a record linearly upsampled to 10 points per period:
    # with the same setting the recurrence reproduces its SA within 6e-4 (measured) from
    # 0.01 to 4 s; beyond 4 s the two differ by up to 0.4 %, with both signs.
    acc, periods, reference = _esm(shared_data, component)
    band = periods <= 4.0
    sa, _ = response_spectrum(acc, ESM_DT, periods[band], damping=0.05, points_per_period=10)
    np.testing.assert_allclose(sa, reference[band], rtol=1e-3)


@pytest.mark.data
def test_sa_esm_vertical_differs_only_by_its_peak_sampling(shared_data):
    # The vertical has energy near 0.06 s where 10 points per period miss up to 2.5 % of
    # the peak; the default (20) stays within its bound 1 - cos(pi/20) = 1.2 % of the
    # converged value (200 points; measured 0.74 %).
    acc, periods, reference = _esm(shared_data, "Z")
    band = (periods >= 0.05) & (periods <= 4.0)
    sa, _ = response_spectrum(acc, ESM_DT, periods[band], damping=0.05)
    converged, _ = response_spectrum(
        acc, ESM_DT, periods[band], damping=0.05, points_per_period=200
    )
    np.testing.assert_allclose(sa, converged, rtol=0.0123)
    assert np.all(converged >= reference[band] * (1 - 1e-4))  # ESM only under-estimates
    np.testing.assert_allclose(sa, reference[band], rtol=0.03)
