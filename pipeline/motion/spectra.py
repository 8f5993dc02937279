"""Elastic response of a linear oscillator and response spectra of a record.

A single-degree-of-freedom oscillator of natural period ``T`` [s] and damping
ratio ``zeta`` [-] on a base with acceleration ``a_g(t)`` [m/s^2] obeys, for its
displacement relative to the base ``u`` [m],

    u'' + 2 zeta omega u' + omega^2 u = -a_g(t),        omega = 2 pi / T.

Its *total* (absolute) acceleration is ``u'' + a_g = -(2 zeta omega u' + omega^2 u)``.
The elastic spectra are

- SA(T) = max_t |u''(t) + a_g(t)|   (total-acceleration spectrum, ESM's ``SA``);
- PSA(T) = omega^2 max_t |u(t)|     (pseudo-spectral acceleration, ITACA's ``PSA``).

Both are equal when ``zeta = 0``; at ``T = 0`` (a rigid oscillator) both are the PGA.

Integration is exact for a base acceleration that is linear between samples
(Nigam & Jennings 1969, BSSA 59(2):909-922; the coefficients below are those of
Chopra, *Dynamics of Structures*, §5.2, with ``m = 1``, ``k = omega^2`` and
``p = -a_g``). The state ``x = (u, u')`` advances as

    x[i+1] = Phi x[i] + Gamma0 a_g[i] + Gamma1 a_g[i+1].

This is the same piecewise-linear convention the solver uses for base motion, so
a spectrum describes exactly the signal the solver integrates. Because the
recurrence is a linear time-invariant filter with two poles, each period is run
through :func:`scipy.signal.lfilter` (compiled, O(n)), which needs no JIT and is
about as fast as a numba loop for the tens to hundreds of periods of a spectrum.

Upsampling: the recurrence is exact at the samples, but a peak of the response
between two samples is missed; with ``n`` samples per oscillator period the peak
of a near-harmonic response can be underestimated by up to ``1 - cos(pi/n)``
(5 % at ``n = 10``, 1.2 % at ``n = 20``). When ``dt > T / points_per_period`` the
record is therefore resampled by an integer factor with *linear* interpolation,
for the periods that need it only. Linear interpolation adds no new content: it
is the very signal the recurrence already assumes, so upsampling changes only
how densely the response is inspected for its peak, never the input (an FFT/sinc
interpolation would instead change the input into a band-limited one, which
differs from what the solver integrates).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.signal import lfilter

from rockscreen.solver.errors import ParameterError

#: Default number of samples per oscillator period below which the record is upsampled.
POINTS_PER_PERIOD = 20

#: Below this omega*dt the step coefficients are summed as a series (no cancellation).
SERIES_LIMIT = 0.2


@dataclass(frozen=True)
class Recurrence:
    """Exact one-step recurrence of a linear oscillator under piecewise-linear base motion.

    ``x[i+1] = phi @ x[i] + gamma0 * a_g[i] + gamma1 * a_g[i+1]`` with ``x = (u, u')``.
    """

    #: Transition matrix, shape (2, 2) [-, s; 1/s, -].
    phi: np.ndarray
    #: Load vectors for the acceleration at the start and the end of the step, shape (2,) [s^2, s].
    gamma0: np.ndarray
    gamma1: np.ndarray

    @property
    def denominator(self) -> list[float]:
        """Characteristic polynomial ``det(zI - Phi)``: the denominator of the recurrence's filter.

        Returns
        -------
        list of float
            ``[1, -trace(Phi), det(Phi)]``, the coefficients :func:`scipy.signal.lfilter`
            takes as ``a`` (its roots are the filter's poles).
        """
        phi = self.phi
        return [1.0, -(phi[0, 0] + phi[1, 1]), phi[0, 0] * phi[1, 1] - phi[0, 1] * phi[1, 0]]


def recurrence(period: float, damping: float, dt: float) -> Recurrence:
    """Return the exact step coefficients for an oscillator (Nigam & Jennings 1969).

    Parameters
    ----------
    period : float
        Natural period T [s], > 0.
    damping : float
        Damping ratio zeta [-], 0 <= zeta < 1.
    dt : float
        Time step [s], > 0.

    Returns
    -------
    Recurrence
        Coefficients of ``x[i+1] = phi x[i] + gamma0 a_g[i] + gamma1 a_g[i+1]``.

    Notes
    -----
    The closed form (Nigam & Jennings 1969; Chopra Table 5.2.1) loses digits to
    cancellation when ``omega dt`` is small (relative error ~ 1e-16/(omega dt)^3,
    2e-6 at T = 10 s, dt = 0.5 ms). Below ``omega dt = SERIES_LIMIT`` the same exact
    coefficients are summed as a power series, whose terms are all of one sign.
    """
    if 2.0 * np.pi / period * dt < SERIES_LIMIT:
        return recurrence_series(period, damping, dt)
    return recurrence_closed_form(period, damping, dt)


def recurrence_closed_form(period: float, damping: float, dt: float) -> Recurrence:
    """Return the Nigam & Jennings coefficients in closed form (Chopra, Table 5.2.1).

    Parameters are those of :func:`recurrence`, which picks this form for
    ``omega dt >= SERIES_LIMIT`` (it loses digits to cancellation below).

    Returns
    -------
    Recurrence
        The exact step coefficients.
    """
    omega = 2.0 * np.pi / period
    root = np.sqrt(1.0 - damping**2)
    omega_d = omega * root
    ratio = damping / root
    decay = np.exp(-damping * omega * dt)
    sin = np.sin(omega_d * dt)
    cos = np.cos(omega_d * dt)
    stiffness = omega**2
    two_zeta_over = 2.0 * damping / (omega * dt)

    # Chopra (2012), Table 5.2.1, for m = 1 and load p = -a_g (hence the minus signs below).
    a11 = decay * (ratio * sin + cos)
    a12 = decay * sin / omega_d
    a21 = -decay * omega / root * sin
    a22 = decay * (cos - ratio * sin)
    c = (
        two_zeta_over
        + decay
        * (((1.0 - 2.0 * damping**2) / (omega_d * dt) - ratio) * sin - (1.0 + two_zeta_over) * cos)
    ) / stiffness
    d = (
        1.0
        - two_zeta_over
        + decay * ((2.0 * damping**2 - 1.0) / (omega_d * dt) * sin + two_zeta_over * cos)
    ) / stiffness
    c_dot = (-1.0 / dt + decay * ((omega / root + ratio / dt) * sin + cos / dt)) / stiffness
    d_dot = (1.0 - decay * (ratio * sin + cos)) / (stiffness * dt)
    return Recurrence(
        phi=np.array([[a11, a12], [a21, a22]]),
        gamma0=-np.array([c, c_dot]),
        gamma1=-np.array([d, d_dot]),
    )


def recurrence_series(period: float, damping: float, dt: float, terms: int = 30) -> Recurrence:
    """Return the same coefficients summed as power series in ``dt`` (for small omega dt).

    With ``x' = A x + b a_g`` and ``a_g`` linear in the step (Beta integrals of the
    convolution): ``phi = sum (A dt)^k / k!``, ``gamma1 = sum A^k b dt^(k+1) / (k+2)!``,
    ``gamma0 = sum A^k b dt^(k+1) (k+1) / (k+2)!``.

    Parameters
    ----------
    period, damping, dt : float
        As :func:`recurrence`, which picks this form for ``omega dt < SERIES_LIMIT``.
    terms : int
        Number of terms summed.

    Returns
    -------
    Recurrence
        The exact step coefficients (to the truncation of the series).
    """
    omega = 2.0 * np.pi / period
    system = np.array([[0.0, 1.0], [-(omega**2), -2.0 * damping * omega]])
    load = np.array([0.0, -1.0])
    phi = np.zeros((2, 2))
    gamma0 = np.zeros(2)
    gamma1 = np.zeros(2)
    term = np.eye(2)  # (A dt)^k / k!
    for k in range(terms):
        phi += term
        forced = term @ load * dt / ((k + 1) * (k + 2))  # A^k b dt^(k+1) / (k+2)!
        gamma1 += forced
        gamma0 += forced * (k + 1)
        term = term @ system * dt / (k + 1)
    return Recurrence(phi=phi, gamma0=gamma0, gamma1=gamma1)


def _relative_response(acc: np.ndarray, coefficients: Recurrence) -> tuple[np.ndarray, np.ndarray]:
    """Run the recurrence over a whole record from rest; return u [m] and u' [m/s].

    The two-state recurrence is the filter ``X(z) = (zI - Phi)^-1 G(z)`` with
    ``g[i] = gamma0 a_g[i] + gamma1 a_g[i+1]``; expanding the adjugate gives one
    all-pole second-order filter per state, which :func:`scipy.signal.lfilter` runs
    in compiled code. ``u[0] = u'[0] = 0`` exactly (the oscillator starts at rest).
    """
    phi, g0, g1 = coefficients.phi, coefficients.gamma0, coefficients.gamma1
    following = np.append(acc[1:], 0.0)  # zero base motion after the last sample
    g_u = g0[0] * acc + g1[0] * following
    g_v = g0[1] * acc + g1[1] * following
    # w[n] = g[n-1] (delayed once) and the adjugate terms delayed twice.
    w_u = np.zeros_like(acc)
    w_v = np.zeros_like(acc)
    w_u[1:] += g_u[:-1]
    w_v[1:] += g_v[:-1]
    w_u[2:] += -phi[1, 1] * g_u[:-2] + phi[0, 1] * g_v[:-2]
    w_v[2:] += -phi[0, 0] * g_v[:-2] + phi[1, 0] * g_u[:-2]
    denominator = coefficients.denominator
    return lfilter([1.0], denominator, w_u), lfilter([1.0], denominator, w_v)


def sdof_response(
    acc: np.ndarray, dt: float, period: float, damping: float = 0.05
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Response histories of a linear oscillator to a base acceleration, from rest.

    Parameters
    ----------
    acc : numpy.ndarray
        Base acceleration a_g [m/s^2] at ``t_k = k*dt``, shape (n,), linear between samples.
    dt : float
        Sampling step [s], > 0.
    period : float
        Natural period T [s], > 0.
    damping : float
        Damping ratio zeta [-], 0 <= zeta < 1.

    Returns
    -------
    u : numpy.ndarray
        Displacement relative to the base [m], shape (n,).
    u_dot : numpy.ndarray
        Velocity relative to the base [m/s], shape (n,).
    total_acc : numpy.ndarray
        Total (absolute) acceleration ``u'' + a_g`` [m/s^2], shape (n,).

    Raises
    ------
    ParameterError
        If an input is outside the allowed range.
    """
    acc = check_record(acc, dt)
    check_damping(damping)
    if not np.isfinite(period) or period <= 0.0:
        raise ParameterError(f"period={period!r} must be a finite number > 0 [s]")
    u, u_dot = _relative_response(acc, recurrence(period, damping, dt))
    omega = 2.0 * np.pi / period
    return u, u_dot, -(2.0 * damping * omega * u_dot + omega**2 * u)


def response_spectrum(
    acc: np.ndarray,
    dt: float,
    periods: np.ndarray,
    damping: float = 0.05,
    *,
    points_per_period: float = POINTS_PER_PERIOD,
) -> tuple[np.ndarray, np.ndarray]:
    """Elastic acceleration spectra SA (total) and PSA (pseudo) of a record.

    Parameters
    ----------
    acc : numpy.ndarray
        Base acceleration [m/s^2] at ``t_k = k*dt``, shape (n,), linear between samples.
    dt : float
        Sampling step [s], > 0.
    periods : array_like
        Oscillator periods T [s], shape (m,) (or a scalar); each > 0, or exactly 0
        for the PGA.
    damping : float
        Damping ratio zeta [-], 0 <= zeta < 1 (default 0.05).
    points_per_period : float
        Upsample (linear interpolation, integer factor) for every period with
        fewer than this many samples per period; default 20, i.e. a peak-sampling
        error below 1.2 %.

    Returns
    -------
    sa : numpy.ndarray
        Total-acceleration spectrum max|u'' + a_g| [m/s^2], shape of ``periods``.
    psa : numpy.ndarray
        Pseudo-acceleration spectrum omega^2 max|u| [m/s^2], shape of ``periods``.

    Raises
    ------
    ParameterError
        If ``acc`` is empty or not finite, ``dt <= 0``, a period is negative or not
        finite, or ``damping`` is outside [0, 1).

    Notes
    -----
    The oscillator starts at rest and the record is followed by zero base motion
    for one period of the longest oscillator in each group, so that the first peak
    of the free vibration after the record is counted too.
    """
    acc = check_record(acc, dt)
    check_damping(damping)
    if not np.isfinite(points_per_period) or points_per_period < 1.0:
        raise ParameterError(f"points_per_period={points_per_period!r} must be >= 1")
    periods_in = np.asarray(periods, dtype=float)
    flat = np.atleast_1d(periods_in).ravel()
    bad = flat[~np.isfinite(flat) | (flat < 0.0)]
    if bad.size:
        raise ParameterError(
            f"periods contain {bad[0]!r}; each period must be finite and > 0 [s] (0 for the PGA)"
        )

    sa = np.empty_like(flat)
    psa = np.empty_like(flat)
    pga = float(np.max(np.abs(acc)))
    sa[flat == 0.0] = pga
    psa[flat == 0.0] = pga

    positive = np.flatnonzero(flat > 0.0)
    factors = np.maximum(1, np.ceil(points_per_period * dt / flat[positive] - 1e-9)).astype(int)
    for factor in np.unique(factors):
        group = positive[factors == factor]
        fine_dt = dt / factor
        fine = _upsample_linear(acc, factor)
        n_free = int(np.ceil(flat[group].max() / fine_dt)) + 1
        padded = np.concatenate([fine, np.zeros(n_free)])
        for index in group:
            period = flat[index]
            u, u_dot = _relative_response(padded, recurrence(period, damping, fine_dt))
            omega = 2.0 * np.pi / period
            sa[index] = np.max(np.abs(2.0 * damping * omega * u_dot + omega**2 * u))
            psa[index] = omega**2 * np.max(np.abs(u))
    return sa.reshape(periods_in.shape), psa.reshape(periods_in.shape)


def _upsample_linear(acc: np.ndarray, factor: int) -> np.ndarray:
    """Insert ``factor - 1`` linearly interpolated samples between each pair of samples."""
    if factor == 1:
        return acc
    fraction = np.arange(factor) / factor
    inner = acc[:-1, None] * (1.0 - fraction) + acc[1:, None] * fraction
    return np.append(inner.ravel(), acc[-1])


def check_record(acc: np.ndarray, dt: float) -> np.ndarray:
    """Return a base-acceleration record as a float array after checking it and its step.

    Parameters
    ----------
    acc : array_like, shape (n,)
        Base acceleration [m/s^2], non-empty, every sample finite.
    dt : float
        Sampling step [s], finite and > 0.

    Returns
    -------
    numpy.ndarray
        ``acc`` as a 1-D float array.

    Raises
    ------
    ParameterError
        Naming the first bad sample, the shape or the step.
    """
    array = np.asarray(acc, dtype=float)
    if array.ndim != 1 or array.size == 0:
        raise ParameterError(
            f"acc must be a non-empty 1-D array of accelerations [m/s^2], got shape {array.shape}"
        )
    if not np.all(np.isfinite(array)):
        first = int(np.flatnonzero(~np.isfinite(array))[0])
        raise ParameterError(f"acc[{first}]={array[first]!r}: every sample must be finite")
    if not np.isfinite(dt) or dt <= 0.0:
        raise ParameterError(f"dt={dt!r} must be a finite number > 0 [s]")
    return array


def check_damping(damping: float) -> None:
    """Check an oscillator's damping ratio.

    Parameters
    ----------
    damping : float
        Damping ratio zeta [-], in [0, 1).

    Raises
    ------
    ParameterError
        When it is outside [0, 1) or not finite.
    """
    if not np.isfinite(damping) or not 0.0 <= damping < 1.0:
        raise ParameterError(f"damping={damping!r} must be in [0, 1) (a ratio, 0.05 = 5 %)")
