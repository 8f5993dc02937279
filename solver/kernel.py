"""Compiled event-driven integrator shared by the rocking, sliding and double-block models.

One state machine covers all three models (docs/theory.md), in the regimes of
:class:`~rockscreen.solver.codes.Regime`:

- REST: everything at rest; the input is scanned sample by sample for the next uplift or
  slip threshold crossing, located exactly on the piecewise-linear input;
- ROCKING: tower rocking on a stuck base (the single Housner block);
- SLIDING: building sliding, tower at rest on it (the single sliding block when the
  tower is absent);
- BOTH: tower rocking on the sliding building.

Between events the state ``(theta, theta_dot, u, u_dot)`` is advanced with classical
RK4 on sub-steps inside each sample interval, where the input is linear and the
equations are smooth (:mod:`rockscreen.solver.dynamics`). Impacts, stick, slip and the overturning
angle are located by Illinois regula falsi on the RK4 step length, the state is
re-stepped to the event and the regime changes there (:mod:`rockscreen.solver.events`).

The per-step functions (:func:`_integrate`, :func:`_step`, :func:`rockscreen.solver.events.detect`)
are inlined by numba (``inline="always"``): as separate calls, each passing its named
tuples as some fifty flattened arguments, they made the kernel about a third slower.

Everything is compiled with ``numba.njit(cache=True)``; the signature of :func:`simulate`
is fixed (float64 arrays, float64 scalars, a :data:`Params` of floats and bools, a
boolean history flag), so a warm cache is reused by every later process. numba checks
the cache of :func:`simulate` against this file only, not the modules it calls: after
editing :mod:`solver.codes`, :mod:`solver.dynamics`, :mod:`solver.events` or
:mod:`solver.history` alone, touch this file (or empty
:func:`rockscreen.solver.cache.cache_dir`) so that it recompiles.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np
from numba import njit

from rockscreen.solver.codes import Event, Regime, Status
from rockscreen.solver.constants import G
from rockscreen.solver.dynamics import (
    Segment,
    State,
    advance,
    below_barrier,
    free_motion_overturns,
    free_motion_peak,
    friction_demand,
    hermite_peak,
    inputs,
    rocks,
    sign,
    slides,
)
from rockscreen.solver.events import (
    MAX_EVENTS_PER_SAMPLE,
    detect,
    event_table,
    onset_threshold,
    onset_time,
    transition,
)
from rockscreen.solver.history import append, record_rest, record_state

#: Model constants read by every compiled function (built by :func:`make_par`). The field
#: types are fixed (float, or bool for the flags), so the compiled signature never changes.
Params = namedtuple(
    "Params",
    [
        "k",  # p^2 / g [1/m]; p^2 R / g = m R^2 / I_O, so the inertia ratio needs no field
        "alpha",  # slenderness [rad]
        "radius",  # corner-to-centre-of-mass distance R [m]
        "mass_ratio",  # m / (M + m) [-]
        "mu_s",  # static friction coefficient of the base [-]
        "mu_k",  # kinetic friction coefficient of the base [-]
        "eta",  # coefficient of restitution of the angular velocity [-]
        "linearized",  # bool: small-angle rocking equations
        "tower",  # bool: a tower is present
        "can_slide",  # bool: the base (building) may slide on its foundation
        "c_up",  # uplift threshold |a_b| / g_e: tan(alpha), or alpha when linearized [-]
        "w_rest2",  # squared angular velocity below which an impact ends rocking [rad^2/s^2]
        "h_max",  # largest RK4 sub-step [s]
        "free_max",  # longest free motion integrated after the input ends [s]
        "p2",  # p^2 [rad^2/s^2]
        "scale",  # factor applied to both input records (the safety-factor search) [-]
        "friction_demand",  # bool: track |f_x/f_z| (NaN in the result otherwise)
        "stop_certain",  # bool: end the free motion once its outcome is certain (no settling)
    ],
)

#: What :func:`simulate` returns; the history arrays are empty unless it recorded them.
Result = namedtuple(
    "Result",
    [
        "status",  # Status code
        "t_end",  # end of the integration [s]
        "theta_max",  # largest |theta| [rad]
        "impact_times",  # [s]
        "t_overturn",  # NaN unless overturned [s]
        "slip_max",  # largest |u| [m]
        "u_end",  # final u [m]
        "demand_max",  # largest |f_x/f_z| [-], NaN unless tracked
        "uplifted",  # bool
        "slipped",  # bool
        "t",  # history: time [s]
        "theta",  # [rad]
        "theta_dot",  # [rad/s]
        "u",  # [m]
        "u_dot",  # [m/s]
        "regime",  # int8 Regime codes
    ],
)

#: Running results of :func:`simulate` between sample intervals.
Tally = namedtuple(
    "Tally",
    ["theta_max", "slip_max", "demand_max", "uplifted", "slipped", "impacts", "n_impacts"],
)

#: Default cap of the RK4 sub-step [s] (see :func:`make_par`).
MAX_SUBSTEP = 1.7e-3
#: The tower constants p, alpha, R and eta of the sliding block alone (no tower).
NO_TOWER = (0.0, 0.0, 0.0, 1.0)


@njit(cache=True)
def simulate(acc, acc_v, dt, par, theta0, theta_dot0, record_history):
    """Integrate the model described by ``par`` on a base acceleration record.

    Parameters
    ----------
    acc : ndarray of float64
        Horizontal base acceleration [m/s^2] at ``k*dt``, linear between samples, zero
        after the last one.
    acc_v : ndarray of float64
        Vertical base acceleration [m/s^2] on the same grid, or empty.
    dt : float
        Sampling step [s].
    par : Params
        Model constants from :func:`make_par`; both records are read multiplied by
        ``par.scale``.
    theta0, theta_dot0 : float
        Initial rotation [rad] and angular velocity [rad/s] of the tower.
    record_history : bool
        Record the state at every sample (and at the stopping event).

    Returns
    -------
    Result
        Named fields; the history arrays are empty unless ``record_history``;
        ``demand_max`` is NaN unless ``par.friction_demand``.
    """
    n = acc.size
    h_sub = dt / max(1, int(math.ceil(dt / par.h_max - 1e-9)))
    k_last = n - 1 + int(math.ceil(par.free_max / dt - 1e-9))  # end of the free motion
    # Where the input ends: the last sample, or with ``stop_certain`` the first of the
    # trailing zeros (zero-padded records); after it the base is still either way.
    n_in = input_end(acc, acc_v) if par.stop_certain else n
    table = event_table(par)
    s = sign(theta0) if theta0 != 0.0 else sign(theta_dot0)
    reg = Regime.ROCKING if s != 0.0 else Regime.REST
    st = State(0.0, theta0, theta_dot0, 0.0, 0.0, s, 0.0, reg)
    out = Tally(abs(theta0), 0.0, 0.0, rocks(reg), False, np.empty(64), 0)
    hist, n_h = record_state(np.empty((6, n + 16 if record_history else 1)), 0, st, record_history)
    status = Status.REST if reg == Regime.REST and n_in <= 1 else Status.MOVING
    t_over = np.nan
    k = 0
    while status == Status.MOVING and k < k_last:
        if st.reg == Regime.REST:  # skip the samples below the onset threshold (k < n_in - 1)
            j, out = _scan_rest(acc, acc_v, k, n_in, par, out)
            hist, n_h = record_rest(hist, n_h, k, j, dt, st.u, record_history)
            k, st = j, _at(st, j * dt)
            if k >= n_in - 1:
                status = Status.REST
                break
        seg = _segment(acc, acc_v, k, dt, par.scale)
        st, out, fell = _integrate(st, out, seg, h_sub, table, par)
        if fell:
            status, t_over = Status.OVERTURNED, st.t
        else:
            k += 1
            st = _at(st, k * dt)
        hist, n_h = record_state(hist, n_h, st, record_history)
        if status == Status.MOVING and k >= n_in - 1:  # the input has ended: free motion
            status = _free_motion_status(st, par)
            if status == Status.OVERTURNED:
                t_over = st.t
            elif status == Status.MOVING and par.stop_certain and _stop_certain(st, par):
                break  # below the barrier on a still base: no overturning (energy argument)
    theta_max = out.theta_max
    if status == Status.MOVING and k >= n_in - 1 and _rest_certain(st, par):
        # Below the barrier in free motion every impact dissipates: the Zeno sequence
        # ends at rest in finite time; report the largest amplitude still to come.
        status = Status.SAFE
        theta_max = max(theta_max, free_motion_peak(st.th, st.thd, st.s, par))
    return _result(status, st, out, theta_max, t_over, hist, n_h, par)


@njit(cache=True, inline="always")
def _integrate(st, out, seg, h_sub, table, par):
    """Advance through one sample interval; return (state, tally, overturned)."""
    theta_max, slip_max, demand, uplifted, slipped, imp, n_imp = out
    track = par.tower and par.friction_demand
    c_rest = onset_threshold(par)
    fell = False
    n_events = 0
    while st.t < seg.t_b:
        n_events += 1
        if n_events > MAX_EVENTS_PER_SAMPLE:
            # Chattering between events within one sample: settle at rest (documented).
            st = transition(_at(st, seg.t_b), Event.CHATTER, 0.0, 0.0, par)
            break
        if st.reg == Regime.REST:
            tc = onset_time(st.t, seg, c_rest)
            if tc < 0.0 or tc >= seg.t_b:  # no onset before the interval ends
                st = _at(st, seg.t_b)
                break
            ag, ge = inputs(tc, seg)
            st = transition(_at(st, tc), Event.ONSET, ag, ge, par)
        else:
            st0 = st
            st, event, h = _step(st0, seg, h_sub, table, par)
            if rocks(st0.reg) and st0.thd * st.thd <= 0.0:
                theta_max = max(theta_max, hermite_peak(st0.th, st0.thd, st.th, st.thd, h))
            theta_max = max(theta_max, abs(st.th))
            slip_max = max(slip_max, abs(st.u))
            if event == Event.OVERTURN:
                fell = True
                break
            if event == Event.IMPACT:
                imp, n_imp = append(imp, n_imp, st.t)
            ag, ge = inputs(st.t, seg)
            if event != Event.NONE:
                st = transition(st, event, ag, ge, par)
        uplifted = uplifted or rocks(st.reg)
        slipped = slipped or slides(st.reg)
        if track and st.reg != Regime.REST:
            demand = max(demand, friction_demand(st, ag, ge, par))
    return st, Tally(theta_max, slip_max, demand, uplifted, slipped, imp, n_imp), fell


@njit(cache=True, inline="always")
def _step(st, seg, h_sub, table, par):
    """One RK4 sub-step, cut at the earliest event; return (state, event, step length)."""
    h = min(h_sub, seg.t_b - st.t)
    if seg.t_b - (st.t + h) < 1e-9 * h_sub:
        h = seg.t_b - st.t
    end = advance(st, h, seg, par)
    event, h_event = detect(st, end, h, seg, table, par)
    if event != Event.NONE:
        return advance(st, h_event, seg, par), event, h_event
    if h == seg.t_b - st.t:
        end = _at(end, seg.t_b)  # land exactly on the sample
    return end, event, h


@njit(cache=True)
def _at(st, t):
    """Return the state ``st`` at time ``t`` (only the clock changes)."""
    return State(t, st.th, st.thd, st.u, st.ud, st.s, st.su, st.reg)


@njit(cache=True)
def _segment(acc, acc_v, k, dt, sc):
    """Return the input on interval k (zero after the last sample), scaled by ``sc``."""
    a0, a1, v0, v1 = 0.0, 0.0, 0.0, 0.0
    if k < acc.size - 1:
        # sc * x rounds exactly as a record multiplied by sc beforehand would.
        a0 = sc * acc[k]
        a1 = (sc * acc[k + 1] - a0) / dt
        if acc_v.size > 0:
            v0 = sc * acc_v[k]
            v1 = (sc * acc_v[k + 1] - v0) / dt
    return Segment(a0, a1, v0, v1, k * dt, (k + 1) * dt)


@njit(cache=True)
def input_end(acc, acc_v):
    """Return how many samples carry the input: trailing zeros of both records excluded.

    The input is linear between samples and zero after the last one, so a record cut after
    its first trailing zero (of ``acc`` and ``acc_v`` both) is the same input. Returns
    ``m + 2`` for the last nonzero sample ``m`` (at most ``acc.size``), 1 for records that
    are zero throughout.
    """
    n = acc.size
    has_v = acc_v.size > 0
    m = n - 1
    while m >= 0 and acc[m] == 0.0 and (not has_v or acc_v[m] == 0.0):
        m -= 1
    return min(n, m + 2) if m >= 0 else min(n, 1)


@njit(cache=True)
def _scan_rest(acc, acc_v, k, n, par, out):
    """Return the last sample j >= k up to which the input stays below the onset threshold.

    ``n`` is the number of input samples read (the input's end, at most ``acc.size``).
    Returns ``(j, tally)``; the tally's friction demand includes the samples passed.
    """
    sc = par.scale
    c_rest = onset_threshold(par)
    has_v = acc_v.size > 0
    demand_max = out.demand_max
    j = k
    ge_k = G + sc * acc_v[k] if has_v else G
    if abs(sc * acc[k]) > c_rest * ge_k:
        pass  # the threshold is exceeded now: the interval loop handles it
    elif par.tower and par.friction_demand:
        if has_v:
            while j < n - 1 and abs(sc * acc[j + 1]) <= c_rest * (G + sc * acc_v[j + 1]):
                j += 1
                dmd = abs(sc * acc[j]) / (G + sc * acc_v[j])
                if dmd > demand_max:
                    demand_max = dmd
        else:
            lim = c_rest * G
            amax = demand_max * G
            while j < n - 1 and abs(sc * acc[j + 1]) <= lim:
                j += 1
                a = abs(sc * acc[j])
                if a > amax:
                    amax = a
            demand_max = amax / G
    elif has_v:
        while j < n - 1 and abs(sc * acc[j + 1]) <= c_rest * (G + sc * acc_v[j + 1]):
            j += 1
    else:
        lim = c_rest * G
        while j < n - 1 and abs(sc * acc[j + 1]) <= lim:
            j += 1
    theta_max, slip_max, _, uplifted, slipped, imp, n_imp = out
    return j, Tally(theta_max, slip_max, demand_max, uplifted, slipped, imp, n_imp)


@njit(cache=True)
def _free_motion_status(st, par):
    """Return the status once the input has ended: REST, OVERTURNED or MOVING."""
    if st.reg == Regime.REST:
        return Status.REST
    if st.reg == Regime.ROCKING and par.tower and free_motion_overturns(st.th, st.thd, st.s, par):
        return Status.OVERTURNED
    return Status.MOVING


@njit(cache=True)
def _rest_certain(st, par):
    """Return whether rest is certain: rocking on a fixed base below the barrier, eta < 1."""
    if st.reg != Regime.ROCKING or not par.tower or not par.eta < 1.0:
        return False
    return not free_motion_overturns(st.th, st.thd, st.s, par)


@njit(cache=True)
def _stop_certain(st, par):
    """Return whether the free motion may end here (``stop_certain``; docs/theory.md).

    A single block (its base cannot slide) rocking on a still base with eta < 1, whose
    energy is below the overturning barrier whichever way it moves: energy is conserved
    between impacts and lost at each, so it never reaches alpha, and the largest swing
    still to come is :func:`rockscreen.solver.dynamics.free_motion_peak`. Not for a base
    that may slide (the double block): the tower may drag it loose, and the building's
    share of the energy makes the peak of later swings no closed form.
    """
    if st.reg != Regime.ROCKING or not par.tower or par.can_slide or not par.eta < 1.0:
        return False
    return below_barrier(st.th, st.thd, st.s, par)


@njit(cache=True)
def _result(status, st, out, theta_max, t_over, hist, n_h, par):
    """Return the :data:`Result`."""
    demand = out.demand_max if par.tower and par.friction_demand else np.nan
    return Result(
        status,
        st.t,
        theta_max,
        out.impacts[: out.n_impacts].copy(),
        t_over,
        out.slip_max,
        st.u,
        demand,
        out.uplifted,
        out.slipped,
        hist[0, :n_h].copy(),
        hist[1, :n_h].copy(),
        hist[2, :n_h].copy(),
        hist[3, :n_h].copy(),
        hist[4, :n_h].copy(),
        hist[5, :n_h].astype(np.int8),
    )


def make_par(block, run, *, linearized=False, can_slide=False, mass_ratio=0.0, mu_s=0.0, mu_k=0.0):
    """Pack a model into the :data:`Params` :func:`simulate` expects.

    Every field is converted to float or bool, so the compiled signature never changes.

    Parameters
    ----------
    block : RockingBlock or None
        The tower (its p, alpha, R and eta); None for the sliding block alone.
    run : rockscreen.solver.rocking.RunOptions
        The integration controls: ``rest_tolerance`` (Zeno cut-off [-]: after an impact, a
        tower that could still rise through less than this fraction of alpha is at rest),
        ``max_substep`` (largest RK4 sub-step [s]; None: ``min(0.02/p, MAX_SUBSTEP)`` with a
        tower), ``max_free_time`` [s], ``scale`` (factor applied to both input records
        inside the kernel, no scaled copy [-]), ``friction_demand`` (False skips the
        bookkeeping; the result is then NaN) and ``stop_when_certain`` (end the free motion
        as soon as its outcome is certain, see :class:`rockscreen.solver.rocking.RunOptions`).
    linearized : bool
        Small-angle rocking equations (uplift at alpha g).
    can_slide : bool
        Whether the base may slide on its foundation.
    mass_ratio : float
        Tower mass over total mass m / (M + m) [-].
    mu_s, mu_k : float
        Static and kinetic friction coefficients of the base [-].

    Returns
    -------
    Params
        The named model constants.
    """
    tower = block is not None
    p, alpha, radius, eta = (block.p, block.alpha, block.radius, block.eta) if tower else NO_TOWER
    p2 = float(p) * float(p)
    # After an impact, a tower whose kinetic energy could lift its centre of mass through
    # less than rest_tolerance * alpha of rotation is at rest (the Zeno cut-off).
    lever = alpha if linearized else math.sin(alpha)
    max_substep = run.max_substep
    if max_substep is None:
        # 1.7 ms cap: with 0.02/p alone, impact times on slender towers drifted by 3e-4 s and
        # theta_max by 20 % against the converged oracle (benchmarks/solver_bench.py). On the
        # 68 L'Aquila cases at 200 Hz the worst |d theta_max| is 1.9e-4 with 1 ms (5 sub-steps
        # per sample), 1.3e-3 with this cap (3 sub-steps, h = 1.67 ms; the error scales as
        # h^4), 6.1e-3 with 2.5 ms (2 sub-steps: above the 0.5 % target). 1.7 ms keeps every
        # record's sub-step at or below the 1.67 ms checked at 200 Hz, at 3/5 of the cost.
        max_substep = min(0.02 / p, MAX_SUBSTEP) if tower and p > 0.0 else np.inf
    return Params(
        k=float(p2 / G),
        alpha=float(alpha),
        radius=float(radius),
        mass_ratio=float(mass_ratio),
        mu_s=float(mu_s),
        mu_k=float(mu_k),
        eta=float(eta),
        linearized=bool(linearized),
        tower=bool(tower),
        can_slide=bool(can_slide),
        c_up=float((alpha if linearized else math.tan(alpha)) if tower else np.inf),
        w_rest2=float(2.0 * p2 * lever * run.rest_tolerance * alpha if tower else 0.0),
        h_max=float(max_substep),
        free_max=float(run.max_free_time),
        p2=float(p2),
        scale=float(run.scale),
        friction_demand=bool(run.friction_demand),
        stop_certain=bool(run.stop_when_certain),
    )
