"""Equations of motion of the compiled kernel: accelerations, RK4 step, base forces, bounds.

The state between events is a :data:`State`; the input on one sample interval, where it
is linear in time, is a :data:`Segment`; the model constants are the
:class:`solver.kernel.Params` built by :func:`solver.kernel.make_par`. Everything here is
compiled with ``numba.njit(cache=True)``.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np
from numba import njit

from rockscreen.solver.codes import Regime
from rockscreen.solver.constants import G

#: State between events: time [s], tower rotation [rad] and its rate [rad/s], base slip
#: [m] and its rate [m/s], pivot sign s (+1 right corner, -1 left, 0 none), sliding sign
#: s_u of the base (0 when it sticks) and the :class:`~rockscreen.solver.codes.Regime`.
State = namedtuple("State", ["t", "th", "thd", "u", "ud", "s", "su", "reg"])

#: The input on one sample interval [t_a, t_b]: horizontal acceleration ``a0 + a1 (t - t_a)``
#: [m/s^2] and vertical ``v0 + v1 (t - t_a)`` [m/s^2], both already scaled.
Segment = namedtuple("Segment", ["a0", "a1", "v0", "v1", "t_a", "t_b"])


@njit(cache=True)
def sign(x):
    """Return the sign of ``x``: 1.0, -1.0 or 0.0."""
    return 1.0 if x > 0.0 else (-1.0 if x < 0.0 else 0.0)


@njit(cache=True)
def rocks(reg):
    """Return whether the tower rocks in regime ``reg`` (ROCKING or BOTH)."""
    return reg == Regime.ROCKING or reg == Regime.BOTH


@njit(cache=True)
def slides(reg):
    """Return whether the base slides in regime ``reg`` (SLIDING or BOTH)."""
    return reg == Regime.SLIDING or reg == Regime.BOTH


@njit(cache=True)
def _trig(phi, lin):
    if lin:
        return phi, 1.0
    return math.sin(phi), math.cos(phi)


@njit(cache=True)
def inputs(t, seg):
    """Return the input at time ``t`` on the segment ``seg``.

    Parameters
    ----------
    t : float
        Time [s], within the segment.
    seg : Segment
        The linear input on the current sample interval.

    Returns
    -------
    ag, ge : float
        Horizontal base acceleration and effective gravity ``g + a_v`` [m/s^2].
    """
    dtau = t - seg.t_a
    return seg.a0 + seg.a1 * dtau, G + seg.v0 + seg.v1 * dtau


@njit(cache=True)
def accelerations(reg, th, thd, s, su, ag, ge, par):
    """Return the accelerations of the state in regime ``reg``.

    Parameters
    ----------
    reg : Regime
        The regime.
    th, thd : float
        Tower rotation [rad] and angular velocity [rad/s].
    s, su : float
        Pivot sign and sliding sign of the base.
    ag, ge : float
        Horizontal base acceleration and effective gravity [m/s^2].
    par : Params
        Model constants.

    Returns
    -------
    thdd, udd : float
        Angular acceleration of the tower [rad/s^2] and acceleration of the base slip
        [m/s^2].
    """
    if reg == Regime.REST:
        return 0.0, 0.0
    mu_k = par.mu_k
    if reg == Regime.SLIDING:
        return 0.0, -ag - mu_k * su * ge
    k = par.k
    sphi, cphi = _trig(par.alpha * s - th, par.linearized)
    if reg == Regime.ROCKING:
        return -k * (ge * sphi + ag * cphi), 0.0
    # Both: building momentum (divided by M + m) and tower moment about its pivot.
    r = par.mass_ratio
    rr = r * par.radius
    w2 = thd * thd
    a12 = rr * (cphi + mu_k * su * sphi)
    b_a = -mu_k * su * (ge - rr * cphi * w2) - ag - rr * sphi * w2
    a21 = k * cphi
    b_b = -k * (ge * sphi + ag * cphi)
    det = 1.0 - a12 * a21
    udd = (b_a - a12 * b_b) / det
    thdd = (b_b - a21 * b_a) / det
    return thdd, udd


@njit(cache=True)
def advance(st, h, seg, par):
    """Advance the state by one classical RK4 step in its regime.

    Parameters
    ----------
    st : State
        State at the start of the step.
    h : float
        Step length [s]; ``st.t + h`` stays within the segment.
    seg : Segment
        The linear input on the current sample interval.
    par : Params
        Model constants.

    Returns
    -------
    State
        The state at ``st.t + h``, with the same regime and signs.
    """
    reg, s, su, t = st.reg, st.s, st.su, st.t
    th, thd, u, ud = st.th, st.thd, st.u, st.ud
    ag, ge = inputs(t, seg)
    k1a, k1u = accelerations(reg, th, thd, s, su, ag, ge, par)
    hh = 0.5 * h
    ag, ge = inputs(t + hh, seg)
    th2, thd2, ud2 = th + hh * thd, thd + hh * k1a, ud + hh * k1u
    k2a, k2u = accelerations(reg, th2, thd2, s, su, ag, ge, par)
    th3, thd3, ud3 = th + hh * thd2, thd + hh * k2a, ud + hh * k2u
    k3a, k3u = accelerations(reg, th3, thd3, s, su, ag, ge, par)
    ag, ge = inputs(t + h, seg)
    th4, thd4, ud4 = th + h * thd3, thd + h * k3a, ud + h * k3u
    k4a, k4u = accelerations(reg, th4, thd4, s, su, ag, ge, par)
    h6 = h / 6.0
    th_n = th + h6 * (thd + 2.0 * thd2 + 2.0 * thd3 + thd4)
    thd_n = thd + h6 * (k1a + 2.0 * k2a + 2.0 * k3a + k4a)
    u_n = u + h6 * (ud + 2.0 * ud2 + 2.0 * ud3 + ud4)
    ud_n = ud + h6 * (k1u + 2.0 * k2u + 2.0 * k3u + k4u)
    return State(t + h, th_n, thd_n, u_n, ud_n, s, su, reg)


@njit(cache=True)
def base_forces(th, thd, s, ag, ge, par):
    """Return the forces a stuck base needs while the tower rocks on it.

    ``F = ag + r x_G''`` and ``N = g_e + r z_G''``, per unit of the total mass M + m.

    Parameters
    ----------
    th, thd : float
        Tower rotation [rad] and angular velocity [rad/s].
    s : float
        Pivot sign.
    ag, ge : float
        Horizontal base acceleration and effective gravity [m/s^2].
    par : Params
        Model constants.

    Returns
    -------
    f, n : float
        Required friction and normal force on the base, per unit mass [m/s^2].
    """
    thdd, _ = accelerations(Regime.ROCKING, th, thd, s, 0.0, ag, ge, par)
    sphi, cphi = _trig(par.alpha * s - th, par.linearized)
    radius = par.radius
    w2 = thd * thd
    xdd = radius * (cphi * thdd + sphi * w2)
    zdd = radius * (sphi * thdd - cphi * w2)
    r = par.mass_ratio
    return ag + r * xdd, ge + r * zdd


@njit(cache=True)
def friction_demand(st, ag, ge, par):
    """Return the friction demand |f_x / f_z| at the tower's base (REFERENCES R8).

    Parameters
    ----------
    st : State
        The current state.
    ag, ge : float
        Horizontal base acceleration and effective gravity [m/s^2] at ``st.t``.
    par : Params
        Model constants.

    Returns
    -------
    float
        The demand [-]; inf when the tower's base is not pressed down.
    """
    reg, th, thd, s = st.reg, st.th, st.thd, st.s
    if reg == Regime.REST:
        return abs(ag) / ge
    if reg == Regime.SLIDING:
        return par.mu_k
    sphi, cphi = _trig(par.alpha * s - th, par.linearized)
    if reg == Regime.ROCKING:
        # Same expression as accelerations, without evaluating the sine and cosine twice.
        thdd, udd = -par.k * (ge * sphi + ag * cphi), 0.0
    else:
        thdd, udd = accelerations(reg, th, thd, s, st.su, ag, ge, par)
    radius = par.radius
    w2 = thd * thd
    fx = ag + udd + radius * (cphi * thdd + sphi * w2)
    fz = ge + radius * (sphi * thdd - cphi * w2)
    if fz <= 0.0:
        return np.inf
    return abs(fx) / fz


@njit(cache=True)
def hermite_peak(th0, thd0, th1, thd1, h):
    """Return the largest |theta| of the cubic Hermite interpolant on one step.

    Used on steps where theta_dot changes sign, so that the peak of each swing is not
    limited to the step ends.

    Parameters
    ----------
    th0, thd0 : float
        Rotation [rad] and angular velocity [rad/s] at the start of the step.
    th1, thd1 : float
        The same at its end.
    h : float
        Step length [s].

    Returns
    -------
    float
        The largest |theta| [rad] on the step.
    """
    # theta(x h) = th0 + h x thd0 + x^2 (3 d - h(2 thd0 + thd1)) + x^3 (h(thd0 + thd1) - 2 d)
    d = th1 - th0
    c2 = 3.0 * d - h * (2.0 * thd0 + thd1)
    c3 = h * (thd0 + thd1) - 2.0 * d
    # derivative: h thd0 + 2 c2 x + 3 c3 x^2 = 0
    qa, qb, qc = 3.0 * c3, 2.0 * c2, h * thd0
    best = max(abs(th0), abs(th1))
    if qa == 0.0:
        roots = (-qc / qb if qb != 0.0 else -1.0, -1.0)
    else:
        disc = qb * qb - 4.0 * qa * qc
        if disc < 0.0:
            return best
        sq = math.sqrt(disc)
        roots = ((-qb + sq) / (2.0 * qa), (-qb - sq) / (2.0 * qa))
    for x in roots:
        if 0.0 < x < 1.0:
            val = th0 + x * (h * thd0 + x * (c2 + x * c3))
            best = max(best, abs(val))
    return best


@njit(cache=True)
def barrier_speed2(ath, par):
    """Return the squared angular velocity [rad²/s²] that climbs from |theta| to alpha.

    ``theta_dot^2 + 2 p^2 cos(alpha - theta)`` is conserved in free motion (linearised:
    ``theta_dot^2 - p^2 (alpha - theta)^2``), so reaching ``theta = alpha`` from
    ``|theta| = ath`` takes ``2 p^2 (1 - cos(alpha - ath))`` (``p^2 (alpha - ath)^2``).
    """
    if par.linearized:
        return par.p2 * (par.alpha - ath) ** 2
    return 2.0 * par.p2 * (1.0 - math.cos(par.alpha - ath))


@njit(cache=True)
def free_motion_overturns(th, thd, s, par):
    """Return the energy-barrier verdict in free motion on a fixed base.

    See REFERENCES, 'Overturning'.

    Parameters
    ----------
    th, thd : float
        Tower rotation [rad] and angular velocity [rad/s].
    s : float
        Pivot sign.
    par : Params
        Model constants.

    Returns
    -------
    bool
        Whether the tower overturns without further input.
    """
    alpha = par.alpha
    ath = s * th
    outward = s * thd > 0.0
    excess = thd * thd - barrier_speed2(ath, par)
    if outward:
        return ath >= alpha or excess >= 0.0
    # Beyond alpha and moving inward too slowly to get back over the barrier: it falls out.
    return ath >= alpha and excess < 0.0


@njit(cache=True)
def below_barrier(th, thd, s, par):
    """Return whether the tower's energy is below the overturning barrier on a fixed base.

    Below it, ``|theta| < alpha`` and the kinetic energy is smaller than the potential still
    to climb to ``theta = alpha``, whichever way the tower moves; on a still base the
    energy only decreases (impacts dissipate), so it never overturns (docs/theory.md).

    Parameters
    ----------
    th, thd : float
        Tower rotation [rad] and angular velocity [rad/s].
    s : float
        Pivot sign.
    par : Params
        Model constants.

    Returns
    -------
    bool
    """
    ath = s * th
    if ath >= par.alpha:
        return False
    return thd * thd < barrier_speed2(ath, par)


@njit(cache=True)
def free_motion_peak(th, thd, s, par):
    """Return the largest |theta| still reachable in free motion below the barrier.

    Energy is conserved between impacts and only lost at impacts, so the peak of the
    current swing (moving outward) or of the swing after the next impact (moving inward)
    bounds every later amplitude.

    Parameters
    ----------
    th, thd : float
        Tower rotation [rad] and angular velocity [rad/s].
    s : float
        Pivot sign.
    par : Params
        Model constants.

    Returns
    -------
    float
        The bound [rad].
    """
    alpha = par.alpha
    p2 = par.p2
    ath = s * th
    lin = par.linearized
    if s * thd < 0.0:
        # Kinetic energy at theta = 0, reduced by eta^2 at the impact.
        if lin:
            w0 = thd * thd + p2 * (alpha * alpha - (alpha - ath) ** 2)
        else:
            w0 = thd * thd + 2.0 * p2 * (math.cos(alpha - ath) - math.cos(alpha))
        w0 *= par.eta**2
        ath = 0.0
        thd = math.sqrt(max(w0, 0.0))
    if lin:
        rest = (alpha - ath) ** 2 - thd * thd / p2
        return max(ath, alpha - math.sqrt(max(rest, 0.0)))
    # theta_dot^2 + 2 p^2 cos(alpha - theta) is conserved: at the peak theta_dot = 0.
    c = math.cos(alpha - ath) + thd * thd / (2.0 * p2)
    return max(ath, alpha - math.acos(min(max(c, -1.0), 1.0)))
