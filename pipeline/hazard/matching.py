"""Batched response spectra and frequency-domain spectral matching of many records at once.

:func:`batch_spectrum` is :func:`rockscreen.pipeline.motion.spectra.response_spectrum` (exact
piecewise-linear recurrence of Nigam & Jennings, linear upsampling below
``points_per_period`` samples per period, one period of free vibration after the record)
for a stack of records of one length: each period is one :func:`scipy.signal.lfilter` call
over the whole stack, and its step coefficients are computed once per (period, damping,
dt). It returns the total-acceleration spectrum SA only, equal to ``response_spectrum``'s
to rounding.

:func:`match_records` is the iterative frequency-domain scaling of
:mod:`rockscreen.pipeline.hazard.suite` applied to the whole stack at once.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from scipy.signal import lfilter

from rockscreen.pipeline.motion.spectra import POINTS_PER_PERIOD, recurrence
from rockscreen.solver.constants import G

__all__ = ["GAIN_LIMIT", "batch_spectrum", "match_records"]

#: Largest change of a Fourier amplitude in one pass, as |ln(gain)|.
GAIN_LIMIT = np.log(2.0)


@lru_cache(maxsize=4096)
def _filter(period: float, damping: float, dt: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return the recurrence as one filter from a_g to the total acceleration of the oscillator.

    With ``x = (u, u')`` and ``x[i+1] = phi x[i] + gamma0 a[i] + gamma1 a[i+1]``, the total
    acceleration ``-(2 zeta omega u' + omega^2 u)`` is ``B(z)/A(z)`` applied to ``a``, with
    ``A`` the characteristic polynomial of ``phi`` and a three-tap ``B``; starting from rest
    (``x[0] = 0``) removes the terms in ``a[0]`` at the first two samples, which is the
    filter ``correction`` applied to ``a[0] delta``.

    Returns
    -------
    numerator, denominator, correction : numpy.ndarray
        ``B``, ``A`` and the numerator of the start-from-rest correction.
    """
    c = recurrence(period, damping, dt)
    (p00, p01), (p10, p11) = c.phi
    omega = 2.0 * np.pi / period
    alpha, beta = -(omega**2), -2.0 * damping * omega
    # w[n] = h1[n-1] + h2[n-2], h1 = alpha g_u + beta g_v, h2 = the adjugate terms.
    u2, v2 = -alpha * p11 + beta * p10, alpha * p01 - beta * p00
    a0 = alpha * c.gamma0[0] + beta * c.gamma0[1]
    a1 = alpha * c.gamma1[0] + beta * c.gamma1[1]
    b0 = u2 * c.gamma0[0] + v2 * c.gamma0[1]
    b1 = u2 * c.gamma1[0] + v2 * c.gamma1[1]
    denominator = np.array([1.0, -(p00 + p11), p00 * p11 - p01 * p10])
    return np.array([a1, a0 + b1, b0]), denominator, np.array([a1, b1])


def _upsample(acc: np.ndarray, factor: int) -> np.ndarray:
    """Linear interpolation of every row by an integer factor (as ``response_spectrum``)."""
    if factor == 1:
        return acc
    fraction = np.arange(factor) / factor
    inner = acc[:, :-1, None] * (1.0 - fraction) + acc[:, 1:, None] * fraction
    return np.concatenate([inner.reshape(acc.shape[0], -1), acc[:, -1:]], axis=1)


def _total_peak(acc: np.ndarray, period: float, damping: float, dt: float) -> np.ndarray:
    """Peak total acceleration of one oscillator under every row of ``acc``, from rest."""
    numerator, denominator, correction = _filter(period, damping, dt)
    total = lfilter(numerator, denominator, acc, axis=1)
    first = acc[:, 0]
    if np.any(first != 0.0):
        impulse = np.zeros(acc.shape[1])
        impulse[0] = 1.0
        total -= first[:, None] * lfilter(correction, denominator, impulse)
    return np.max(np.abs(total), axis=1)


def batch_spectrum(
    acc: np.ndarray,
    dt: float,
    periods: np.ndarray,
    damping: float = 0.05,
    *,
    points_per_period: float = POINTS_PER_PERIOD,
) -> np.ndarray:
    """Return the total-acceleration spectra of a stack of records.

    Parameters
    ----------
    acc : numpy.ndarray
        Base accelerations [m/s²], shape (records, samples), linear between samples.
    dt : float
        Time step [s].
    periods : numpy.ndarray
        Oscillator periods [s], each > 0.
    damping : float
        Damping ratio [-].
    points_per_period : float
        Upsampling threshold, as in :func:`rockscreen.pipeline.motion.spectra.response_spectrum`.

    Returns
    -------
    numpy.ndarray
        SA [m/s²], shape (records, periods).
    """
    acc = np.atleast_2d(np.asarray(acc, float))
    periods = np.asarray(periods, float)
    sa = np.empty((acc.shape[0], periods.size))
    factors = np.maximum(1, np.ceil(points_per_period * dt / periods - 1e-9)).astype(int)
    for factor in np.unique(factors):
        group = np.flatnonzero(factors == factor)
        fine_dt = dt / factor
        fine = _upsample(acc, int(factor))
        n_free = int(np.ceil(periods[group].max() / fine_dt)) + 1
        padded = np.concatenate([fine, np.zeros((acc.shape[0], n_free))], axis=1)
        for index in group:
            sa[:, index] = _total_peak(padded, float(periods[index]), damping, fine_dt)
    return sa


def match_records(
    acc: np.ndarray,
    dt: float,
    periods: np.ndarray,
    target_g: np.ndarray,
    *,
    iterations: int,
    damping: float = 0.05,
) -> np.ndarray:
    """Scale the Fourier amplitudes of a stack of records until their spectra follow a target.

    Each pass compares every record's 5 % spectrum at ``periods`` with the target; the
    ratio target / SA, split into its geometric mean (applied whole, so the amplitude is
    right from the first pass) and the departure from it (interpolated in log period, held
    constant beyond the periods, limited to :data:`GAIN_LIMIT` per pass), multiplies the
    record's Fourier amplitudes at f = 1/T, phases unchanged; the record is transformed
    back (zero-padded, so nothing wraps around) and its last second tapered.

    Parameters
    ----------
    acc : numpy.ndarray
        Accelerations [m/s²], shape (records, samples).
    dt : float
        Time step [s].
    periods : numpy.ndarray
        Matching periods [s], increasing.
    target_g : numpy.ndarray
        Target SA [g] at ``periods``.
    iterations : int
        Passes.
    damping : float
        Damping ratio [-].

    Returns
    -------
    numpy.ndarray
        Matched accelerations [m/s²], same shape.
    """
    out = np.atleast_2d(np.asarray(acc, float)).copy()
    n = out.shape[1]
    n_fft = 1 << int(np.ceil(np.log2(2 * n)))
    frequency = np.fft.rfftfreq(n_fft, dt)
    log_t = np.log(periods)
    with np.errstate(divide="ignore"):
        log_period = np.log(1.0 / frequency)
    taper = np.ones(n)
    ramp = int(round(1.0 / dt))
    taper[n - ramp :] = 0.5 * (1 + np.cos(np.linspace(0.0, np.pi, ramp)))
    log_target = np.log(np.asarray(target_g, float) * G)
    for _ in range(iterations):
        log_ratio = log_target - np.log(batch_spectrum(out, dt, periods, damping))
        level = log_ratio.mean(axis=1, keepdims=True)
        shape = np.array([np.interp(log_period, log_t, row) for row in log_ratio - level])
        gain = np.exp(level + np.clip(shape, -GAIN_LIMIT, GAIN_LIMIT))
        spectrum = np.fft.rfft(out, n_fft, axis=1) * gain
        out = np.fft.irfft(spectrum, n_fft, axis=1)[:, :n] * taper
    return out
