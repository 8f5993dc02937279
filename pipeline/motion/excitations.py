"""Synthetic base excitations: harmonic motion and single pulses.

Every function returns the acceleration sampled on a uniform grid ``t_k = k*dt``
[s], in m/s^2, as a 1-D ``float64`` array starting at ``t = 0``. The solvers treat
the samples as a piecewise-linear signal and continue with zero base motion after
the last sample, so a pulse array only needs to cover the pulse itself.

Conventions (Zhang & Makris 2001; Makris & Konstantinidis 2003):

- one-sine ``A sin(2 pi f t)`` and one-cosine ``A cos(2 pi f t)`` for ``0 <= t <= 1/f``;
- half-sine ``A sin(2 pi f t)`` and rectangular ``A`` for ``0 <= t <= 1/(2 f)``;
- harmonic ``A cos(2 pi f t)`` for ``0 <= t <= duration``.
"""

from __future__ import annotations

import numpy as np

from rockscreen.pipeline.vocabulary import PULSE_SHAPES
from rockscreen.solver.docstrings import fill_doc
from rockscreen.solver.errors import ParameterError

#: Names accepted by :func:`pulse`.

#: The sampling option and the Returns section every excitation shares (``fill_doc``).
_DOCS = {
    "dt": """
dt : float, optional
    Sampling step [s]; default :func:`default_dt`.
""",
    "returns": """
Returns
-------
acc : ndarray, shape (n,)
    Base acceleration [m/s^2].
dt : float
    Sampling step [s].
""",
}


def default_dt(frequency: float) -> float:
    """Return a sampling step [s] fine enough for a signal of ``frequency`` [Hz].

    At least 400 samples per period and never coarser than 1 ms, so that the
    piecewise-linear interpolation error on the peak is below 3e-5 of the amplitude.
    """
    _check_positive("frequency", frequency)
    return min(1e-3, 1.0 / (400.0 * frequency))


def _check_positive(name: str, value: float) -> None:
    if not np.isfinite(value) or value <= 0.0:
        raise ParameterError(f"{name}={value!r} must be a finite number > 0")


def pulse_duration(shape: str, frequency: float) -> float:
    """Return the length [s] of a pulse: ``1/f`` for one-sine and one-cosine, else ``1/(2f)``."""
    return (1.0 if shape in ("one-sine", "one-cosine") else 0.5) / frequency


def _sampling_step(dt: float | None, frequency: float) -> float:
    """Return ``dt`` [s], or :func:`default_dt` for ``frequency`` when None, checked > 0."""
    dt = default_dt(frequency) if dt is None else dt
    _check_positive("dt", dt)
    return dt


def _grid(duration: float, dt: float) -> np.ndarray:
    n = int(np.floor(duration / dt + 1e-9)) + 1
    return np.arange(n) * dt


@fill_doc(_DOCS)
def harmonic(
    amplitude: float, frequency: float, duration: float, dt: float | None = None
) -> tuple[np.ndarray, float]:
    """Sample ``A cos(2 pi f t)`` for ``0 <= t <= duration``.

    Parameters
    ----------
    amplitude : float
        Peak acceleration A [m/s^2] (may be negative to flip the sign).
    frequency : float
        Frequency f [Hz], > 0.
    duration : float
        Length of the excitation [s], > 0.
    %(dt)s

    %(returns)s
    """
    _check_positive("duration", duration)
    dt = _sampling_step(dt, frequency)
    t = _grid(duration, dt)
    return amplitude * np.cos(2.0 * np.pi * frequency * t), dt


@fill_doc(_DOCS)
def pulse(
    shape: str,
    amplitude: float,
    frequency: float,
    dt: float | None = None,
    duration: float | None = None,
) -> tuple[np.ndarray, float]:
    """Sample a single pulse of the given shape.

    Parameters
    ----------
    shape : {'one-sine', 'one-cosine', 'half-sine', 'rectangular'}
        Pulse shape (see the module docstring for the formulas).
    amplitude : float
        Peak acceleration A [m/s^2].
    frequency : float
        Pulse frequency f [Hz] (f = 1 / T_p for the full-cycle pulses; the half-sine
        and the rectangular pulse last 1/(2f)).
    %(dt)s
    duration : float, optional
        Total length of the returned signal [s], zero-padded after the pulse.
        Default: the pulse length.

    %(returns)s
    """
    if shape not in PULSE_SHAPES:
        raise ParameterError(f"pulse shape {shape!r} is not one of {', '.join(PULSE_SHAPES)}")
    _check_positive("frequency", frequency)
    dt = _sampling_step(dt, frequency)
    t_pulse = pulse_duration(shape, frequency)
    total = t_pulse if duration is None else max(duration, t_pulse)
    t = _grid(total, dt)
    inside = t <= t_pulse + 1e-12
    w = 2.0 * np.pi * frequency
    if shape == "one-sine" or shape == "half-sine":
        acc = amplitude * np.sin(w * t)
    elif shape == "one-cosine":
        acc = amplitude * np.cos(w * t)
    else:
        acc = np.full_like(t, float(amplitude))
    acc[~inside] = 0.0
    return acc, dt
