"""The oracle's model: tolerances, result type, input checks, excitation and equations."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from rockscreen.solver.constants import G
from rockscreen.solver.errors import ParameterError
from rockscreen.solver.response import Outcome

__all__ = [
    "ATOL",
    "BOTH",
    "MAX_EVENTS_AT_SAME_TIME",
    "REST",
    "REST_FRACTION",
    "ROCKING",
    "RTOL",
    "SLIDING",
    "T_FREE",
    "Excitation",
    "ReferenceResult",
    "System",
    "check_block",
    "check_friction",
    "check_positive",
    "check_record",
]

#: Integration tolerances of every ``solve_ivp`` call.
RTOL = 1e-10
ATOL = 1e-12
#: Default rest criterion: ``|theta'+| < REST_FRACTION * p * alpha`` after an impact.
REST_FRACTION = 1e-4
#: Default bound on the free motion after the excitation [s].
T_FREE = 300.0
#: Guard against an event loop that does not advance in time.
MAX_EVENTS_AT_SAME_TIME = 10_000

#: Regime codes: at rest, tower rocking on the stuck building, building sliding with the
#: tower at rest, both moving.
REST, ROCKING, SLIDING, BOTH = 0, 1, 2, 3


@dataclass(frozen=True)
class ReferenceResult(Outcome):
    """Outcome and time histories of a reference integration.

    The outcome fields are those of :class:`rockscreen.solver.response.Outcome`; ``theta_max`` takes
    the peaks located by events, not only at samples.
    """

    #: Time [s] the integration stopped.
    t_end: float
    #: Histories at interval ends and events (non-uniform ``t`` [s]).
    t: np.ndarray = field(repr=False)
    theta: np.ndarray = field(repr=False)
    theta_dot: np.ndarray = field(repr=False)
    u: np.ndarray = field(repr=False)
    u_dot: np.ndarray = field(repr=False)
    regime: np.ndarray = field(repr=False)


# --------------------------------------------------------------------------- inputs


def check_positive(name: str, value: float) -> float:
    """Return ``value`` as a float after checking it is finite and > 0.

    Parameters
    ----------
    name : str
        The parameter's name, for the message.
    value : float
        The value.

    Returns
    -------
    float
        The value.

    Raises
    ------
    ParameterError
        When it is not finite or not > 0.
    """
    value = float(value)
    if not math.isfinite(value) or value <= 0.0:
        raise ParameterError(f"{name}={value!r} must be a finite number > 0")
    return value


def check_record(name: str, values, n: int | None = None) -> np.ndarray:
    """Return a record as a 1-D float array after checking its shape and samples.

    Parameters
    ----------
    name : str
        The record's name (``"acc"``, ``"acc_v"``), for the message.
    values : array_like
        The samples [m/s^2], every one finite.
    n : int, optional
        The number of samples it must have (that of ``acc``).

    Returns
    -------
    numpy.ndarray
        The record.

    Raises
    ------
    ParameterError
        Naming the shape, the length or the first bad sample.
    """
    arr = np.asarray(values, dtype=float)
    if arr.ndim != 1 or arr.size == 0:
        raise ParameterError(f"{name} must be a non-empty 1-D array, got shape {arr.shape}")
    if n is not None and arr.size != n:
        raise ParameterError(f"{name} has {arr.size} samples, acc has {n}: they must match")
    if not np.all(np.isfinite(arr)):
        bad = int(np.flatnonzero(~np.isfinite(arr))[0])
        raise ParameterError(f"{name}[{bad}]={arr[bad]!r}: every sample must be finite")
    return arr


def check_block(p: float, alpha: float, eta: float) -> tuple[float, float, float]:
    """Return the block's ``(p, alpha, eta)`` as floats after checking their ranges.

    Parameters
    ----------
    p : float
        Frequency parameter [rad/s], > 0.
    alpha : float
        Slenderness angle [rad], in (0, pi/2).
    eta : float
        Angular-velocity restitution [-], in (0, 1].

    Returns
    -------
    (float, float, float)
        ``(p, alpha, eta)``.

    Raises
    ------
    ParameterError
        Naming the value out of range.
    """
    p = check_positive("p", p)
    alpha = float(alpha)
    if not 0.0 < alpha < math.pi / 2:
        raise ParameterError(f"alpha={alpha!r} must lie in (0, pi/2) rad")
    eta = float(eta)
    if not 0.0 < eta <= 1.0:
        raise ParameterError(f"eta={eta!r} (angular-velocity restitution) must lie in (0, 1]")
    return p, alpha, eta


def check_friction(mu_s: float, mu_k: float) -> tuple[float, float]:
    """Return ``(mu_s, mu_k)`` as floats after checking ``0 < mu_k <= mu_s``.

    Parameters
    ----------
    mu_s, mu_k : float
        Static and kinetic friction coefficients [-].

    Returns
    -------
    (float, float)
        ``(mu_s, mu_k)``.

    Raises
    ------
    ParameterError
        When either is not > 0 or ``mu_k > mu_s``.
    """
    mu_s = check_positive("mu_s", mu_s)
    mu_k = check_positive("mu_k", mu_k)
    if mu_k > mu_s:
        raise ParameterError(f"mu_k={mu_k!r} must not exceed mu_s={mu_s!r}")
    return mu_s, mu_k


class Excitation:
    """Piecewise-linear ground motion, zero from the last sample on.

    Parameters
    ----------
    acc : numpy.ndarray, shape (n,)
        Checked horizontal base acceleration [m/s^2] at ``k*dt``.
    dt : float
        Checked sampling step [s].
    acc_v : numpy.ndarray or None
        Checked vertical base acceleration [m/s^2], same length; None: none.
    """

    def __init__(self, acc: np.ndarray, dt: float, acc_v: np.ndarray | None):
        self.acc = acc
        self.acc_v = np.zeros_like(acc) if acc_v is None else acc_v
        self.dt = dt
        self.n = acc.size
        self.t_end = (self.n - 1) * dt

    def interval(self, t: float) -> int:
        """Index k of the sample interval [t_k, t_k+1] that the motion after ``t`` uses."""
        k = int(math.floor(t / self.dt))
        # t may sit a rounding error below a knot: then the next interval applies.
        if (k + 1) * self.dt - t <= 1e-9 * self.dt:
            k += 1
        return k

    def line(self, k: int) -> tuple[float, float, float, float, float]:
        """Return ``(t_k, a_k, slope_a, v_k, slope_v)`` of interval k."""
        if k >= self.n - 1:
            return k * self.dt, 0.0, 0.0, 0.0, 0.0
        a0, a1 = self.acc[k], self.acc[k + 1]
        v0, v1 = self.acc_v[k], self.acc_v[k + 1]
        return k * self.dt, a0, (a1 - a0) / self.dt, v0, (v1 - v0) / self.dt

    def at(self, t: float) -> tuple[float, float]:
        """Return ``(ag, av)`` [m/s^2] at time ``t``."""
        if t >= self.t_end:
            return 0.0, 0.0
        tk, a0, da, v0, dv = self.line(int(math.floor(t / self.dt)))
        return a0 + da * (t - tk), v0 + dv * (t - tk)

    def first_exceedance(self, t0: float, ratio: float) -> tuple[float, int] | None:
        """Return the first time >= t0 with ``|ag| > ratio * (g + av)`` and ``sgn(ag)``.

        Both ``ag - ratio*g_e`` and ``-ag - ratio*g_e`` are piecewise linear, so the
        crossing inside an interval is the exact root of a line.
        """
        if t0 >= self.t_end:
            return None
        best = None
        a0, v0 = self.at(t0)
        k0 = int(math.floor(t0 / self.dt)) + 1
        for sign in (1, -1):
            f0 = sign * a0 - ratio * (G + v0)
            if f0 > 0.0:
                return t0, sign
            f = sign * self.acc[k0:] - ratio * (G + self.acc_v[k0:])
            hits = np.flatnonzero(f > 0.0)
            if hits.size == 0:
                continue
            j = int(hits[0])
            f_prev, t_prev = (f0, t0) if j == 0 else (f[j - 1], (k0 + j - 1) * self.dt)
            t_hit = t_prev + ((k0 + j) * self.dt - t_prev) * (-f_prev) / (f[j] - f_prev)
            if best is None or t_hit < best[0]:
                best = (t_hit, sign)
        return best


# --------------------------------------------------------------------------- model


@dataclass(frozen=True)
class System:
    """Parameters of the coupled tower-building model (single cases are its limits)."""

    p: float
    alpha: float
    eta: float
    # The defaults are the single block on a fixed base, without a rest criterion.
    radius: float = math.nan  # R [m]; only the coupled regimes use it
    mass_ratio: float = math.inf  # (M + m) / m [-]; inf for a fixed base
    mu_s: float = math.inf  # inf: the building never slides
    mu_k: float = math.inf
    has_tower: bool = True
    linearized: bool = False
    rest_velocity: float = 0.0  # [rad/s]

    @property
    def uplift_ratio(self) -> float:
        """``|a_b| / g_e`` above which a tower at rest uplifts."""
        return self.alpha if self.linearized else math.tan(self.alpha)

    @property
    def can_slide(self) -> bool:
        """Whether the building may slide (finite static friction)."""
        return math.isfinite(self.mu_s)

    def theta_ddot(self, theta: float, s: int, a_b: float, g_e: float) -> float:
        """Angular acceleration [rad/s^2] of the tower on a base accelerating by ``a_b``."""
        if self.linearized:
            return self.p**2 * ((g_e / G) * (theta - self.alpha * s) - a_b / G)
        phi = self.alpha * s - theta
        return -(self.p**2 / G) * (g_e * math.sin(phi) + a_b * math.cos(phi))

    def stuck_force(self, y, s: int, ag: float, g_e: float) -> tuple[float, float]:
        """Friction force and normal force per tower mass [m/s^2] keeping the building stuck.

        ``F = (M+m) ag + m x_G''`` and ``N = (M+m) g_e + m z_G''``, divided by m; with no
        tower (or the tower at rest) the tower terms vanish.
        """
        force, normal = self.mass_ratio * ag, self.mass_ratio * g_e
        if self.has_tower and s != 0:
            theta, omega = y[0], y[1]
            phi = self.alpha * s - theta
            acc = self.theta_ddot(theta, s, ag, g_e)
            r = self.radius
            force += r * math.cos(phi) * acc + r * math.sin(phi) * omega**2
            normal += r * math.sin(phi) * acc - r * math.cos(phi) * omega**2
        return force, normal

    def coupled_accelerations(
        self, y, s: int, su: int, ag: float, g_e: float
    ) -> tuple[float, float]:
        """Return ``(u'', theta'')`` of regime 3 from the 2x2 system (divided by m)."""
        theta, omega = y[0], y[1]
        phi = self.alpha * s - theta
        r, mr, mu = self.radius, self.mass_ratio, self.mu_k
        a11 = mr
        a12 = r * (math.cos(phi) + mu * su * math.sin(phi))
        b1 = -mu * su * (mr * g_e - r * math.cos(phi) * omega**2) - mr * ag
        b1 -= r * math.sin(phi) * omega**2
        a21 = r * math.cos(phi)
        a22 = G * r / self.p**2  # I_O / m
        b2 = -r * (g_e * math.sin(phi) + ag * math.cos(phi))
        det = a11 * a22 - a12 * a21
        return (b1 * a22 - a12 * b2) / det, (a11 * b2 - a21 * b1) / det

    def energy_verdict(self, theta: float, omega: float) -> str:
        """Free-motion verdict: ``"overturned"``, ``"safe"`` or ``"undecided"``.

        ``safe`` means the current outward swing stays below the barrier; energy only
        drops at later impacts, so the tower can no longer overturn in free motion.
        """
        a = abs(theta)
        outward = theta * omega > 0.0 or (theta == 0.0 and omega != 0.0)
        if self.linearized:
            margin = self.p**2 * (self.alpha - a) ** 2 - omega**2
        else:
            margin = 2.0 * self.p**2 * (1.0 - math.cos(self.alpha - a)) - omega**2
        if a > self.alpha:
            # Beyond the corner: outward motion falls over, inward motion falls over too
            # unless it carries enough energy to climb back over the barrier.
            return "overturned" if outward or margin > 0.0 else "undecided"
        if outward:
            return "safe" if margin > 0.0 else "overturned"
        return "undecided"
