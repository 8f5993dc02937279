"""Site-based stochastic ground motions: Rezaeian & Der Kiureghian (2010), with velocity pulses.

The model (Rezaeian & Der Kiureghian 2010, *Earthquake Engng Struct. Dyn.* 39:1155-1180;
"RDK" below) is a time-modulated, filtered white noise with a time-varying filter::

    a(t) = q(t) * sum_i h(t - tau_i; w_f(tau_i)) u_i / sqrt(sum_i h(t - tau_i; w_f(tau_i))^2)

over the samples tau_i <= t, with u_i independent standard normals, the impulse response of
a damped oscillator h(s; w) = w / sqrt(1 - zeta_f^2) exp(-zeta_f w s) sin(w sqrt(1 -
zeta_f^2) s) whose frequency is that at the time of the impulse, w_f(tau) = w_mid +
w' (tau - t_mid), and constant damping zeta_f. The normalisation makes the filtered
process unit-variance, so the gamma-type modulating function q(t) = alpha1 t^(alpha2 - 1)
exp(-alpha3 t) alone sets the intensity: alpha2, alpha3 give the significant duration
D5-95 and the time t_mid at which 45 % of the Arias intensity is reached, alpha1 the
expected Arias intensity I_a. A critically damped oscillator with corner
:data:`HIGH_PASS_HZ` removes the low-frequency drift (RDK's post-processing).

The six physical parameters ``(I_a, D_5-95, t_mid, omega_mid/2pi, omega'/2pi, zeta_f)`` are
drawn per record: correlated standard normals ``z_i = mu_i(M, R, V_s30, F) + e_i`` (total
error, between- and within-event variance added) are mapped to the parameters through
their marginal distributions (:data:`MARGINALS`). The coefficients, standard deviations,
correlations and marginals are the published ones as stored in the SCEC Broadband
Platform's module for these predictive equations (see ``docs/hazard.md`` for exactly what
was used and what was not checked against the paper).

The faulting indicator F of the predictive equations is 1 for every non-strike-slip
mechanism (reverse and normal), as in the SCEC Broadband Platform's module, which sets
F = 1 unless the rake is within 30 degrees of pure strike-slip.

A share of the records carries a **velocity pulse** (near-source directivity): a
Mavroeidis & Papageorgiou (2003, *BSSA* 93(3):1099-1131) wavelet added to the filtered
noise, with its period from the T_p(M) relation of Shahi & Baker (2011, *BSSA*
101(2):742-755) and the probability of a pulse from their logistic model for the
scenario's mechanism (strike-slip or non-strike-slip) at zero directivity length
(``docs/hazard.md``).

Everything is deterministic for a given :class:`numpy.random.Generator` state.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
from scipy import special, stats
from scipy.optimize import brentq
from scipy.signal import bilinear, lfilter

from rockscreen.solver.constants import G

__all__ = [
    "CORRELATION",
    "HIGH_PASS_HZ",
    "MARGINALS",
    "Scenario",
    "StochasticParameters",
    "Pulse",
    "gamma_modulation",
    "mavroeidis_papageorgiou_velocity",
    "pulse_probability",
    "rdk_accelerogram",
    "sample_parameters",
    "sample_pulse",
    "simulate_record",
]

#: Corner frequency of the critically damped high-pass oscillator [Hz].
HIGH_PASS_HZ = 0.2

#: Predictive equations of the six parameters in standard-normal space, one row each:
#: ``(const, M, F, R, V)`` coefficients; row 0 (Arias intensity) uses ``M/7``,
#: ``ln(R/25)`` and ``ln(V_s30/750)`` instead of ``M``, ``R`` [km], ``V_s30`` [m/s].
COEFFICIENTS = np.array(
    [
        [-2.2962, 2.9440, -0.0707, -1.3564, -0.2654],
        [-6.1946, 0.9703, -0.7034, 0.0087, -0.0007],
        [-5.0105, 0.6625, -0.3450, 0.0139, -0.0002],
        [2.2525, -0.2586, -0.0808, -0.0084, 0.0000],
        [-2.4886, 0.3440, 0.0441, 0.0026, -0.0001],
        [-0.2583, 0.1293, -0.4772, -0.0115, 0.0004],
    ]
)
#: Within-event (sigma) and between-event (tau) standard deviations in normal space.
SIGMA = np.array([0.5937, 0.5688, 0.4145, 0.7228, 0.9529, 0.7601])
TAU = np.array([0.2738, 0.4574, 0.5114, 0.6918, 0.1286, 0.6815])
#: Correlation of the total errors of the six parameters.
CORRELATION = np.array(
    [
        [1.0000, -0.3555, 0.0066, -0.1545, 0.1341, -0.0078],
        [-0.3555, 1.0000, 0.6729, -0.1303, -0.1576, -0.1958],
        [0.0066, 0.6729, 1.0000, -0.2761, -0.1977, -0.2188],
        [-0.1545, -0.1303, -0.2761, 1.0000, -0.2034, 0.2814],
        [0.1341, -0.1576, -0.1977, -0.2034, 1.0000, -0.0137],
        [-0.0078, -0.1958, -0.2188, 0.2814, -0.0137, 1.0000],
    ]
)
#: Marginal distributions (descriptive; :func:`_from_normal` applies them):
MARGINALS = {
    "arias_intensity": "lognormal, ln I_a [s·g] ~ N(-4.8255, 1.4318)",
    "d5_95_s": "beta(1.1314, 2.4474) on [5, 45] s",
    "t_mid_s": "beta(1.5792, 3.6405) on [0.5, 40] s",
    "f_mid_hz": "gamma(shape 4.0982, scale 1.4330) Hz",
    "f_slope_hz_s": "two-sided exponential (a=17.095, b=6.7729, c=4.8512) on [-2, 0.5] Hz/s",
    "zeta_f": "beta(1.4250, 5.7208) on [0.02, 1]",
}

#: Shahi & Baker (2011): ln T_p = PULSE_PERIOD[0] + PULSE_PERIOD[1] M, sigma PULSE_PERIOD[2].
PULSE_PERIOD = (-5.73, 0.99, 0.56)
#: Shahi & Baker (2011) at zero directivity length (s = 0 along strike, d = 0 along dip,
#: and angle 0): P(pulse) = 1 / (1 + exp(c0 + c1 R)), R [km]; ``PULSE_LOGIT[F]`` is
#: (c0, c1) for strike-slip (F = 0) and non-strike-slip (F = 1) ruptures.
PULSE_LOGIT = ((0.642, 0.167), (0.128, 0.055))
#: Ratio of the pulse's peak velocity to the noise's PGV: lognormal (median, sigma_ln).
PULSE_DOMINANCE = (2.0, 0.3)
#: Oscillatory character gamma of the wavelet: uniform range [-].
PULSE_GAMMA = (1.5, 3.0)
#: Smallest filter frequency [Hz] (the linear trend is held there).
MIN_FILTER_HZ = 0.3


@dataclass(frozen=True)
class Scenario:
    """An earthquake scenario at a site."""

    #: Moment magnitude [-].
    magnitude: float
    #: Rupture distance [km].
    distance_km: float
    #: Average shear-wave velocity of the top 30 m [m/s].
    vs30_m_s: float
    #: Faulting (RDK's F): 0 strike-slip, 1 any other mechanism (reverse or normal).
    non_strike_slip: int = 0


@dataclass(frozen=True)
class StochasticParameters:
    """The six physical parameters of one RDK record."""

    #: Arias intensity [s·g] (RDK's unit; times g·... only its ratio matters after scaling).
    arias_s_g: float
    #: Significant duration D5-95 [s].
    d5_95_s: float
    #: Time of 45 % of the Arias intensity [s].
    t_mid_s: float
    #: Filter frequency at t_mid [Hz].
    f_mid_hz: float
    #: Rate of change of the filter frequency [Hz/s].
    f_slope_hz_s: float
    #: Filter damping [-].
    zeta_f: float


@dataclass(frozen=True)
class Pulse:
    """A Mavroeidis-Papageorgiou velocity pulse."""

    #: Pulse period [s].
    period_s: float
    #: Oscillatory character gamma [-].
    gamma: float
    #: Phase nu [rad].
    phase_rad: float
    #: Peak velocity over the PGV of the noise part [-].
    dominance: float


def _means(scenario: Scenario) -> np.ndarray:
    """Means of the six parameters in standard-normal space."""
    m, r, v, f = (
        scenario.magnitude,
        scenario.distance_km,
        scenario.vs30_m_s,
        scenario.non_strike_slip,
    )
    first = COEFFICIENTS[0] @ [1.0, m / 7.0, f, math.log(r / 25.0), math.log(v / 750.0)]
    rest = COEFFICIENTS[1:] @ np.array([1.0, m, f, r, v])
    return np.concatenate([[first], rest])


def _slope_inverse(u: float, a=17.095, b=6.7729, c=4.8512, low=-2.0) -> float:
    """Inverse CDF of the two-sided exponential of omega'/2pi [Hz/s]."""
    at_zero = (c / b) * (1.0 - math.exp(b * low))
    if u < at_zero:
        return math.log(u * b / c + math.exp(b * low)) / b
    return -math.log(max(1.0 - (u - at_zero) * a / c, 1e-300)) / a


def _from_normal(z: np.ndarray) -> StochasticParameters:
    """Map six standard normals to the physical parameters (the marginals)."""
    u = np.clip(stats.norm.cdf(z), 1e-12, 1.0 - 1e-12)
    return StochasticParameters(
        arias_s_g=float(math.exp(stats.norm.ppf(u[0], -4.8255, 1.4318))),
        d5_95_s=float(5.0 + 40.0 * stats.beta.ppf(u[1], 1.1314, 2.4474)),
        t_mid_s=float(0.5 + 39.5 * stats.beta.ppf(u[2], 1.5792, 3.6405)),
        f_mid_hz=float(stats.gamma.ppf(u[3], 4.0982, scale=1.4330)),
        f_slope_hz_s=float(_slope_inverse(float(u[4]))),
        zeta_f=float(0.02 + 0.98 * stats.beta.ppf(u[5], 1.4250, 5.7208)),
    )


def sample_parameters(rng: np.random.Generator, scenario: Scenario) -> StochasticParameters:
    """Draw the six model parameters of one record for a scenario.

    Parameters
    ----------
    rng : numpy.random.Generator
        Consumed: six normal draws.
    scenario : Scenario

    Returns
    -------
    StochasticParameters
    """
    std = np.sqrt(SIGMA**2 + TAU**2)
    covariance = CORRELATION * np.outer(std, std)
    z = _means(scenario) + np.linalg.cholesky(covariance) @ rng.standard_normal(6)
    return _from_normal(z)


@lru_cache(maxsize=1024)
def gamma_modulation(arias_s_g: float, d5_95_s: float, t_mid_s: float) -> tuple[float, ...]:
    """Return (alpha1, alpha2, alpha3) of q(t) = alpha1 t^(alpha2-1) exp(-alpha3 t).

    The cumulative energy of q² is a gamma distribution of shape ``k = 2 alpha2 - 1`` and
    rate ``2 alpha3``: ``k`` follows from the ratio ``D5-95 / t_mid`` (scale-free), the rate
    from ``t_mid`` (its 45 % quantile), ``alpha1`` from ``I_a = pi/(2g) ∫ q² dt`` (the
    filtered process has unit variance). Cached: the three components of a record share
    their parameters.

    Parameters
    ----------
    arias_s_g : float
        Expected Arias intensity [s·g].
    d5_95_s : float
        Significant duration [s].
    t_mid_s : float
        Time of 45 % of the Arias intensity [s].

    Returns
    -------
    tuple of float
        alpha1 [m/s^(alpha2+1)], alpha2 [-], alpha3 [1/s].
    """

    def ratio(k: float) -> float:
        q = stats.gamma.ppf([0.05, 0.45, 0.95], k)
        return (q[2] - q[0]) / q[1]

    target = d5_95_s / t_mid_s
    low, high = 1.0001, 200.0
    target = min(max(target, ratio(high) * 1.0001), ratio(low) * 0.9999)
    k = brentq(lambda x: ratio(x) - target, low, high, xtol=1e-8)
    rate = stats.gamma.ppf(0.45, k) / t_mid_s
    arias = arias_s_g * G  # [m/s]
    alpha1_squared = arias * 2.0 * G / math.pi * rate**k / special.gamma(k)
    return math.sqrt(alpha1_squared), (k + 1.0) / 2.0, rate / 2.0


_KERNEL = None


def _filtered_noise_kernel():
    """Compile (once, on first use) the normalised time-varying filter of RDK."""
    global _KERNEL
    if _KERNEL is None:
        from numba import njit

        @njit(cache=False, fastmath=False)
        def kernel(u, omega, zeta, dt):  # pragma: no cover - compiled
            n = u.shape[0]
            out = np.zeros(n)
            damped = math.sqrt(1.0 - zeta * zeta)
            decay = np.empty(n, dtype=np.complex128)
            state = np.zeros(n, dtype=np.complex128)
            gain = np.empty(n)
            for i in range(n):
                decay[i] = np.exp(complex(-zeta * omega[i] * dt, omega[i] * damped * dt))
                gain[i] = omega[i] / damped
            for k in range(n):
                state[k] = 1.0 + 0.0j  # the impulse of sample k, at lag 0 (h = 0)
                total = 0.0
                power = 0.0
                for i in range(k + 1):
                    h = gain[i] * state[i].imag
                    total += h * u[i]
                    power += h * h
                    state[i] *= decay[i]
                if power > 0.0:
                    out[k] = total / math.sqrt(power)
            return out

        _KERNEL = kernel
    return _KERNEL


def _high_pass(acc: np.ndarray, dt: float, corner_hz: float) -> np.ndarray:
    """Acceleration after a critically damped oscillator of corner ``corner_hz``."""
    w = 2.0 * math.pi * corner_hz
    b, a = bilinear([1.0, 0.0, 0.0], [1.0, 2.0 * w, w * w], fs=1.0 / dt)
    return lfilter(b, a, acc)


def rdk_accelerogram(
    rng: np.random.Generator,
    parameters: StochasticParameters,
    dt: float,
    n_samples: int,
    *,
    frequency_factor: float = 1.0,
) -> np.ndarray:
    """Return one RDK accelerogram (modulated, filtered white noise, high-passed).

    Parameters
    ----------
    rng : numpy.random.Generator
        Consumed: ``n_samples`` normal draws.
    parameters : StochasticParameters
    dt : float
        Time step [s].
    n_samples : int
        Number of samples (time 0 is the start of the modulating function).
    frequency_factor : float
        Multiplies the filter frequency (1.5 for a vertical component).

    Returns
    -------
    numpy.ndarray
        Acceleration [m/s²].
    """
    p = parameters
    t = np.arange(n_samples) * dt
    f = frequency_factor * (p.f_mid_hz + p.f_slope_hz_s * (t - p.t_mid_s))
    omega = 2.0 * math.pi * np.maximum(f, MIN_FILTER_HZ)
    noise = _filtered_noise_kernel()(rng.standard_normal(n_samples), omega, p.zeta_f, dt)
    alpha1, alpha2, alpha3 = gamma_modulation(p.arias_s_g, p.d5_95_s, p.t_mid_s)
    with np.errstate(divide="ignore", invalid="ignore"):
        q = np.where(t > 0, alpha1 * t ** (alpha2 - 1.0) * np.exp(-alpha3 * t), 0.0)
    return _high_pass(q * noise, dt, HIGH_PASS_HZ)


def pulse_probability(distance_km: float, non_strike_slip: int = 0) -> float:
    """Return the probability that a record carries a velocity pulse [-].

    Shahi & Baker (2011) at zero directivity length: ``1 / (1 + exp(0.642 + 0.167 R))``
    for a strike-slip rupture, ``1 / (1 + exp(0.128 + 0.055 R))`` for any other
    (:data:`PULSE_LOGIT`).

    Parameters
    ----------
    distance_km : float
        Rupture distance R [km].
    non_strike_slip : int
        0 for a strike-slip rupture, 1 for a reverse or normal one.

    Returns
    -------
    float
    """
    c0, c1 = PULSE_LOGIT[int(bool(non_strike_slip))]
    return 1.0 / (1.0 + math.exp(c0 + c1 * distance_km))


def sample_pulse(rng: np.random.Generator, magnitude: float) -> Pulse:
    """Draw the parameters of a pulse (consumes four draws).

    Parameters
    ----------
    rng : numpy.random.Generator
    magnitude : float
        Moment magnitude [-].

    Returns
    -------
    Pulse
    """
    a, b, sigma = PULSE_PERIOD
    period = math.exp(a + b * magnitude + sigma * rng.standard_normal())
    gamma = rng.uniform(*PULSE_GAMMA)
    phase = rng.uniform(0.0, 2.0 * math.pi)
    dominance = PULSE_DOMINANCE[0] * math.exp(PULSE_DOMINANCE[1] * rng.standard_normal())
    return Pulse(period, gamma, phase, dominance)


def mavroeidis_papageorgiou_velocity(
    t: np.ndarray, peak: float, period_s: float, gamma: float, phase_rad: float, t0: float
) -> np.ndarray:
    """Return the Mavroeidis-Papageorgiou (2003) velocity pulse [m/s].

    ``v(t) = peak/2 [1 + cos(2 pi f_p (t - t0) / gamma)] cos(2 pi f_p (t - t0) + nu)`` for
    ``|t - t0| <= gamma / (2 f_p)``, zero elsewhere; it starts and ends at rest.

    Parameters
    ----------
    t : numpy.ndarray
        Times [s].
    peak : float
        Amplitude A [m/s].
    period_s : float
        Pulse period T_p = 1/f_p [s].
    gamma : float
        Oscillatory character [-].
    phase_rad : float
        Phase nu [rad].
    t0 : float
        Centre of the envelope [s].
    """
    fp = 1.0 / period_s
    x = t - t0
    inside = np.abs(x) <= gamma / (2.0 * fp)
    envelope = 0.5 * peak * (1.0 + np.cos(2.0 * math.pi * fp * x / gamma))
    return np.where(inside, envelope * np.cos(2.0 * math.pi * fp * x + phase_rad), 0.0)


def _with_pulse(acc: np.ndarray, dt: float, pulse: Pulse, t_centre: float) -> np.ndarray:
    """Add a pulse (peak ``dominance`` times the record's PGV) centred at ``t_centre``."""
    velocity = np.cumsum(acc) * dt
    pgv = float(np.max(np.abs(velocity - np.linspace(0, velocity[-1], len(velocity)))))
    t = np.arange(len(acc)) * dt
    v = mavroeidis_papageorgiou_velocity(
        t, pulse.dominance * pgv, pulse.period_s, pulse.gamma, pulse.phase_rad, t_centre
    )
    return acc + np.gradient(v, dt)


@dataclass(frozen=True)
class SimulatedRecord:
    """One simulated record: two horizontals and a vertical, and what made them."""

    x: np.ndarray
    y: np.ndarray
    z: np.ndarray
    dt_s: float
    scenario: Scenario
    parameters: StochasticParameters
    pulse: Pulse | None


def record_length_s(parameters: StochasticParameters, pulse: Pulse | None = None) -> float:
    """Return a duration that holds 99.5 % of the energy (and the pulse) plus 3 s [s]."""
    _, alpha2, alpha3 = gamma_modulation(1.0, parameters.d5_95_s, parameters.t_mid_s)
    end = float(stats.gamma.ppf(0.995, 2.0 * alpha2 - 1.0, scale=1.0 / (2.0 * alpha3)))
    if pulse is not None:
        end = max(end, max(parameters.t_mid_s, pulse.gamma * pulse.period_s / 2 + 0.5))
        end += pulse.gamma * pulse.period_s / 2.0
    return end + 3.0


def simulate_record(
    rng: np.random.Generator, scenario: Scenario, dt: float = 0.01, max_duration_s: float = 80.0
) -> SimulatedRecord:
    """Simulate one three-component record for a scenario.

    The parameters are drawn once (:func:`sample_parameters`); ``x`` and ``y`` are two
    independent realisations of the same process, ``z`` a third with the filter frequency
    times 1.5. With probability :func:`pulse_probability` the ``x`` component (taken as the
    fault-normal one) carries a Mavroeidis-Papageorgiou pulse centred at ``t_mid``.
    Amplitudes are the model's (expected Arias intensity); a suite rescales them.

    Parameters
    ----------
    rng : numpy.random.Generator
    scenario : Scenario
    dt : float
        Time step [s].
    max_duration_s : float
        Longest record [s].

    Returns
    -------
    SimulatedRecord
    """
    parameters = sample_parameters(rng, scenario)
    has_pulse = rng.uniform() < pulse_probability(scenario.distance_km, scenario.non_strike_slip)
    pulse = sample_pulse(rng, scenario.magnitude) if has_pulse else None
    n = round(min(record_length_s(parameters, pulse), max_duration_s) / dt)
    x = rdk_accelerogram(rng, parameters, dt, n)
    y = rdk_accelerogram(rng, parameters, dt, n)
    z = rdk_accelerogram(rng, parameters, dt, n, frequency_factor=1.5)
    if pulse is not None:
        half = pulse.gamma * pulse.period_s / 2.0
        x = _with_pulse(x, dt, pulse, max(parameters.t_mid_s, half + 0.5))
    return SimulatedRecord(x, y, z, dt, scenario, parameters, pulse)
