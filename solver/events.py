"""Events of the compiled kernel: which are active, where they happen, what they change.

Laid out like SciPy's ``integrate/_ivp/ivp.py``: an event function per event
(:func:`event_value`, > 0 before the event and <= 0 once it has happened), one table of the
events active in each regime (:func:`event_table`), one detect-and-locate path for a step
(:func:`detect`, calling :func:`locate` for each event whose function changed sign, as
``find_active_events`` and ``solve_event_equation`` do), and every regime change in one
place (:func:`transition`). At rest nothing is integrated: the onset of motion is found on
the piecewise-linear input directly (:func:`onset_threshold`, :func:`onset_time`).
"""

from __future__ import annotations

import math

from numba import njit

from rockscreen.solver.codes import Event, Regime
from rockscreen.solver.dynamics import State, advance, base_forces, inputs, sign, slides

HALF_PI = 0.5 * math.pi

#: Most events handled within one sample interval before the kernel settles at rest.
MAX_EVENTS_PER_SAMPLE = 100000


@njit(cache=True)
def event_table(par):
    """Return which events are located by integration in which regime.

    Parameters
    ----------
    par : Params
        Model constants (``can_slide`` enables the slip of a rocking tower's base).

    Returns
    -------
    tuple of int
        One bit mask per regime (indexed by its code): bit ``e`` is set when the event
        with code ``e`` is active. Nothing is located at rest: the onset of motion is
        solved on the input.
    """
    impact, overturn = _bit(Event.IMPACT), _bit(Event.OVERTURN)
    stick, slip = _bit(Event.STICK), _bit(Event.SLIP)
    return (
        0,  # REST
        impact | overturn | (slip if par.can_slide else 0),  # ROCKING
        stick,  # SLIDING
        impact | overturn | stick,  # BOTH
    )


@njit(cache=True)
def _bit(event):
    return 1 << event.value


@njit(cache=True)
def event_value(event, st, seg, par):
    """Evaluate the event function of ``event``: > 0 before the event, <= 0 once it happened.

    Parameters
    ----------
    event : Event
        IMPACT (s theta), OVERTURN (pi/2 - s theta), STICK (s_u u_dot) or SLIP
        (mu_s N - |F| of the stuck base under the rocking tower).
    st : State
        The state.
    seg : Segment
        The linear input on the current sample interval.
    par : Params
        Model constants.

    Returns
    -------
    float
        The event function's value.
    """
    if event == Event.IMPACT:
        return st.s * st.th
    if event == Event.OVERTURN:
        return HALF_PI - st.s * st.th
    if event == Event.STICK:
        return st.su * st.ud
    ag, ge = inputs(st.t, seg)
    f, n = base_forces(st.th, st.thd, st.s, ag, ge, par)
    return par.mu_s * n - abs(f)


@njit(cache=True)
def locate(event, st, h, f_a, f_b, seg, par):
    """Return the step length from ``st`` to ``event`` (Illinois regula falsi).

    Each trial re-integrates one RK4 step from ``st``, so the located state is an RK4
    state, not an interpolant.

    Parameters
    ----------
    event : Event
        The event whose function changes sign within the step.
    st : State
        State at the start of the step.
    h : float
        Step length [s] at whose end the event has happened.
    f_a, f_b : float
        Event function at the start (>= 0) and at the end (<= 0) of the step.
    seg : Segment
        The linear input on the current sample interval.
    par : Params
        Model constants.

    Returns
    -------
    float
        The smallest bracketed step length [s] at which the event has happened.
    """
    lo, hi = 0.0, h
    side = 0
    tol = 1e-13 + 1e-12 * h
    for _ in range(100):
        if hi - lo <= tol:
            break
        c = (lo * f_b - hi * f_a) / (f_b - f_a) if f_a != f_b else 0.5 * (lo + hi)
        if not (lo < c < hi) or f_a == 0.0:
            c = 0.5 * (lo + hi)
        f_c = event_value(event, advance(st, c, seg, par), seg, par)
        if f_c > 0.0:
            lo, f_a = c, f_c
            if side == 1:
                f_b *= 0.5
            side = 1
        else:
            hi, f_b = c, f_c
            if side == -1:
                f_a *= 0.5
            side = -1
    return hi


@njit(cache=True, inline="always")
def detect(st0, st1, h, seg, table, par):
    """Return the earliest active event within one RK4 step, and the step length to it.

    Parameters
    ----------
    st0, st1 : State
        States at the start and at the end of the step.
    h : float
        Step length [s].
    seg : Segment
        The linear input on the current sample interval.
    table : tuple of int
        The :func:`event_table`.
    par : Params
        Model constants.

    Returns
    -------
    event : Event
        The earliest event (the first in the order below on a tie), or NONE.
    h_event : float
        The step length to it [s] (``h + 1`` when there is none).
    """
    # One call per event, not a loop: in a loop LLVM would hoist the (speculatable)
    # trigonometry of the slip test out of it and evaluate it on every step.
    active = table[st0.reg.value]
    found, h_event = Event.NONE, h + 1.0
    found, h_event = _check(Event.IMPACT, active, found, h_event, st0, st1, h, seg, par)
    found, h_event = _check(Event.OVERTURN, active, found, h_event, st0, st1, h, seg, par)
    found, h_event = _check(Event.STICK, active, found, h_event, st0, st1, h, seg, par)
    found, h_event = _check(Event.SLIP, active, found, h_event, st0, st1, h, seg, par)
    return found, h_event


@njit(cache=True, inline="always")
def _check(event, active, found, h_event, st0, st1, h, seg, par):
    """Locate ``event`` if it is active and happened in the step before ``found``."""
    if not active & _bit(event):
        return found, h_event
    f1 = event_value(event, st1, seg, par)
    # Overturning counts at |theta| = pi/2 exactly; the others once past zero.
    if f1 < 0.0 or (event == Event.OVERTURN and f1 == 0.0):
        f0 = event_value(event, st0, seg, par)
        h_e = locate(event, st0, h, max(f0, 0.0), f1, seg, par)
        if h_e < h_event:
            return event, h_e
    return found, h_event


@njit(cache=True)
def onset_threshold(par):
    """Return the threshold |a| / g_e at which motion starts from rest.

    Parameters
    ----------
    par : Params
        Model constants.

    Returns
    -------
    float
        The lower of the uplift (tower) and slip (sliding base) thresholds [-].
    """
    if par.tower and par.can_slide:
        return min(par.c_up, par.mu_s)
    if par.tower:
        return par.c_up
    return par.mu_s


@njit(cache=True)
def onset_time(t, seg, c):
    """Return the earliest time in [t, t_b] at which |a| > c g_e on the linear input.

    Parameters
    ----------
    t : float
        Start of the search [s], within the segment.
    seg : Segment
        The linear input on the current sample interval (ending at ``seg.t_b``).
    c : float
        The :func:`onset_threshold` [-].

    Returns
    -------
    float
        The onset time [s], or -1 if there is none.
    """
    t_b = seg.t_b
    ag_t, ge_t = inputs(t, seg)
    ag_b, ge_b = inputs(t_b, seg)
    best = -1.0
    for sig in (1.0, -1.0):
        f_a = sig * ag_t - c * ge_t
        f_b = sig * ag_b - c * ge_b
        if f_a > 0.0:
            return t
        if f_b > 0.0:
            tc = t + (t_b - t) * (-f_a) / (f_b - f_a)
            if best < 0.0 or tc < best:
                best = tc
    return best


@njit(cache=True)
def transition(st, event, ag, ge, par):
    """Return the state just after ``event``: every regime change of the kernel is here.

    Parameters
    ----------
    st : State
        The state at the event (for OVERTURN, the state is returned unchanged: it ends
        the simulation).
    event : Event
        ONSET (from rest), CHATTER (settle at rest), IMPACT, STICK or SLIP.
    ag, ge : float
        Horizontal base acceleration and effective gravity [m/s^2] at ``st.t``.
    par : Params
        Model constants.

    Returns
    -------
    State
        The state after the event, in its new regime.
    """
    th, thd, ud, s, su, reg = st.th, st.thd, st.ud, st.s, st.su, st.reg
    if event == Event.ONSET:
        if par.tower and (not par.can_slide or par.c_up <= par.mu_s):
            reg, s, th, thd = Regime.ROCKING, -sign(ag), 0.0, 0.0
        else:
            reg, su, ud = Regime.SLIDING, -sign(ag), 0.0
    elif event == Event.CHATTER:
        reg, th, thd, ud = Regime.REST, 0.0, 0.0, 0.0
    elif event == Event.IMPACT:
        th = 0.0
        ud_new = ud
        if reg == Regime.BOTH:
            # Momentum-consistent impact: the system's horizontal momentum is kept.
            cos_alpha = 1.0 if par.linearized else math.cos(par.alpha)
            ud_new = ud + par.mass_ratio * par.radius * cos_alpha * (1.0 - par.eta) * thd
        thd = par.eta * thd
        s = -s
        if thd * thd < par.w_rest2:  # the Zeno cut-off: the tower is at rest on its base
            thd = 0.0
            reg = Regime.REST if reg == Regime.ROCKING else Regime.SLIDING
        if slides(reg) and su * ud_new <= 0.0:
            event = Event.STICK  # the impulse stopped the base: the stick test below
        else:
            ud = ud_new
    elif event == Event.SLIP:
        f, _ = base_forces(th, thd, s, ag, ge, par)
        reg, su, ud = Regime.BOTH, -sign(f), 0.0
    if event == Event.STICK:
        ud = 0.0
        if reg == Regime.BOTH:
            f, n = base_forces(th, thd, s, ag, ge, par)
            if abs(f) <= par.mu_s * n:
                reg, su = Regime.ROCKING, 0.0
            else:
                su = -sign(f)
        elif reg == Regime.SLIDING:
            if abs(ag) <= par.mu_s * ge:
                reg, su = Regime.REST, 0.0
            else:
                su = -sign(ag)
    if reg == Regime.SLIDING and par.tower and par.mu_k > par.c_up:
        # Kinetic friction above the uplift threshold: the sliding base lifts the tower.
        reg, s, th, thd = Regime.BOTH, su, 0.0, 0.0
    return State(st.t, th, thd, st.u, ud, s, su, reg)
