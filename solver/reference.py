"""Reference (oracle) integration of the rocking, sliding and double-block equations.

An independent, plain-Python implementation of the equations agreed for rockscreen
(``docs/theory.md``) with :func:`scipy.integrate.solve_ivp` and events. It is slow on
purpose-built terms: every sample interval of the record is integrated by its own
``solve_ivp`` call (DOP853, ``rtol=1e-10``, ``atol=1e-12``) so that the piecewise-linear
base acceleration is smooth inside every call, and every event (uplift, impact, rest,
stick/slip, overturning) is located by the integrator's root finder, never snapped to a
sample. Rest phases are not integrated: the next onset of motion is found exactly on
the piecewise-linear record.

It serves two purposes: the accuracy oracle for the compiled solver (``tests/solver``)
and the speed baseline of ``benchmarks/solver_bench.py``. It shares no code with the
compiled solver (only :mod:`solver.constants` and :mod:`solver.errors`).

Conventions
-----------
- ``acc``, ``acc_v``: base acceleration [m/s^2] at ``t_k = k*dt``, linear between
  samples, **zero from the last sample on** (the excitation ends at ``(n-1)*dt``).
- theta > 0: tower tilted about its right corner; ``s = sgn(theta)``,
  ``phi = alpha*s - theta``; ``g_e = g + acc_v``.
- Rocking: ``theta'' = -(p^2/g) [g_e sin(phi) + a_b cos(phi)]``; linearized
  ``theta'' = p^2 [(g_e/g)(theta - alpha s) - a_b/g]``. Uplift from rest when
  ``|a_b| > g_e tan(alpha)`` (linearized ``g_e alpha``); ``a_b > 0`` starts ``theta < 0``.
- Impact at ``theta = 0``: ``theta'+ = eta theta'-`` (``eta`` is the angular-velocity
  ratio), building velocity unchanged. **Rest (Zeno)**: after an impact with
  ``|theta'+| < rest_fraction * p * alpha`` the tower is at rest (theta = theta' = 0)
  and waits for a new uplift test; with the default ``rest_fraction = 1e-4`` the next
  swing would reach less than about 1e-8 alpha.
- Overturning: during the excitation only when ``|theta| >= pi/2``. In free motion
  (excitation over, building stuck) the energy barrier decides: a swing moving outward
  (or leaving an impact) with ``theta'^2 >= 2 p^2 (1 - cos(alpha - |theta|))``
  (linearized ``theta'^2 >= p^2 (alpha - |theta|)^2``), or ``|theta| > alpha`` while
  moving outward, overturns. After the excitation the integration goes on until rest,
  overturning, or ``t_free`` seconds, whichever comes first.
- Double block: building mass ``M``, tower mass ``m``, corner inertia
  ``I_O = m g R / p^2``; regimes 0 rest, 1 tower rocking on the stuck building,
  2 building sliding with the tower at rest, 3 both. Equations as in ``docs/theory.md``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.integrate import solve_ivp

from solver.constants import G
from solver.errors import ParameterError

#: Integration tolerances of every ``solve_ivp`` call.
RTOL = 1e-10
ATOL = 1e-12
#: Default rest criterion: ``|theta'+| < REST_FRACTION * p * alpha`` after an impact.
REST_FRACTION = 1e-4
#: Default bound on the free motion after the excitation [s].
T_FREE = 300.0
#: Guard against an event loop that does not advance in time.
_MAX_EVENTS_AT_SAME_TIME = 10_000

REST, ROCKING, SLIDING, BOTH = 0, 1, 2, 3


@dataclass
class ReferenceResult:
    """Outcome and time histories of a reference integration.

    Attributes
    ----------
    status : str
        ``"no_motion"``, ``"came_to_rest"``, ``"overturned"`` or ``"moving_at_end"``.
    overturned, uplifted, slipped : bool
        Outcome flags.
    theta_max : float
        Largest ``|theta|`` [rad] (peaks located by events, not only at samples).
    theta_max_over_alpha : float
        ``theta_max / alpha`` [-] (NaN for the sliding block).
    n_impacts : int
        Number of impacts.
    impact_times : ndarray
        Impact times [s].
    t_overturn : float
        Time [s] overturning was decided (NaN if not overturned).
    slip_max, slip_residual : float
        Largest ``|u|`` and final ``u`` of the building slip [m].
    t_end : float
        Time [s] the integration stopped.
    t, theta, theta_dot, u, u_dot, regime : ndarray
        Histories at interval ends and events (non-uniform ``t`` [s]).
    """

    status: str
    overturned: bool
    uplifted: bool
    slipped: bool
    theta_max: float
    theta_max_over_alpha: float
    n_impacts: int
    impact_times: np.ndarray
    t_overturn: float
    slip_max: float
    slip_residual: float
    t_end: float
    t: np.ndarray = field(repr=False)
    theta: np.ndarray = field(repr=False)
    theta_dot: np.ndarray = field(repr=False)
    u: np.ndarray = field(repr=False)
    u_dot: np.ndarray = field(repr=False)
    regime: np.ndarray = field(repr=False)


# --------------------------------------------------------------------------- inputs


def _check_positive(name: str, value: float) -> float:
    value = float(value)
    if not math.isfinite(value) or value <= 0.0:
        raise ParameterError(f"{name}={value!r} must be a finite number > 0")
    return value


def _check_record(name: str, values, n: int | None = None) -> np.ndarray:
    arr = np.asarray(values, dtype=float)
    if arr.ndim != 1 or arr.size == 0:
        raise ParameterError(f"{name} must be a non-empty 1-D array, got shape {arr.shape}")
    if n is not None and arr.size != n:
        raise ParameterError(f"{name} has {arr.size} samples, acc has {n}: they must match")
    if not np.all(np.isfinite(arr)):
        bad = int(np.flatnonzero(~np.isfinite(arr))[0])
        raise ParameterError(f"{name}[{bad}]={arr[bad]!r}: every sample must be finite")
    return arr


def _check_block(p: float, alpha: float, eta: float) -> tuple[float, float, float]:
    p = _check_positive("p", p)
    alpha = float(alpha)
    if not 0.0 < alpha < math.pi / 2:
        raise ParameterError(f"alpha={alpha!r} must lie in (0, pi/2) rad")
    eta = float(eta)
    if not 0.0 < eta <= 1.0:
        raise ParameterError(f"eta={eta!r} (angular-velocity restitution) must lie in (0, 1]")
    return p, alpha, eta


def _check_friction(mu_s: float, mu_k: float) -> tuple[float, float]:
    mu_s = _check_positive("mu_s", mu_s)
    mu_k = _check_positive("mu_k", mu_k)
    if mu_k > mu_s:
        raise ParameterError(f"mu_k={mu_k!r} must not exceed mu_s={mu_s!r}")
    return mu_s, mu_k


class _Excitation:
    """Piecewise-linear ground motion, zero from the last sample on."""

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
class _System:
    """Parameters of the coupled tower-building model (single cases are its limits)."""

    p: float
    alpha: float
    eta: float
    radius: float  # R [m]; only the coupled regimes use it
    mass_ratio: float  # (M + m) / m [-]; inf for a fixed base
    mu_s: float  # inf: the building never slides
    mu_k: float
    has_tower: bool
    linearized: bool
    rest_velocity: float  # [rad/s]

    @property
    def uplift_ratio(self) -> float:
        """``|a_b| / g_e`` above which a tower at rest uplifts."""
        return self.alpha if self.linearized else math.tan(self.alpha)

    @property
    def can_slide(self) -> bool:
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


# --------------------------------------------------------------------------- engine


class _Integrator:
    """Event-driven integration over the regimes of :class:`_System`."""

    def __init__(self, system: _System, exc: _Excitation, t_free: float):
        self.sys = system
        self.exc = exc
        self.t_limit = exc.t_end + t_free
        self.t = 0.0
        self.y = np.zeros(4)  # theta, theta', u, u'
        self.s = 0  # rocking side, 0 at rest
        self.su = 0  # sliding direction, 0 when stuck
        self.regime = REST
        self.uplifted = False
        self.slipped = False
        self.impacts: list[float] = []
        self.theta_max = 0.0
        self.slip_max = 0.0
        self.status = ""
        self.t_overturn = math.nan
        self.free_safe = False
        self.hist_t: list[float] = []
        self.hist_y: list[np.ndarray] = []
        self.hist_regime: list[int] = []

    # ---- bookkeeping
    def _record(self, t: float, y: np.ndarray) -> None:
        self.hist_t.append(t)
        self.hist_y.append(np.array(y, dtype=float))
        self.hist_regime.append(self.regime)
        self.theta_max = max(self.theta_max, abs(y[0]))
        self.slip_max = max(self.slip_max, abs(y[2]))

    def _set_regime(self) -> None:
        rocking, sliding = self.s != 0, self.su != 0
        self.regime = {
            (False, False): REST,
            (True, False): ROCKING,
            (False, True): SLIDING,
            (True, True): BOTH,
        }[(rocking, sliding)]

    # ---- right-hand side and events for the current regime on one input line
    def _rhs(self, line):
        tk, a0, da, v0, dv = line
        sys_, s, su, regime = self.sys, self.s, self.su, self.regime

        def rhs(t, y):
            ag = a0 + da * (t - tk)
            g_e = G + v0 + dv * (t - tk)
            if regime == ROCKING:
                return (y[1], sys_.theta_ddot(y[0], s, ag, g_e), y[3], 0.0)
            if regime == SLIDING:
                return (0.0, 0.0, y[3], -ag - sys_.mu_k * su * g_e)
            u_dd, th_dd = sys_.coupled_accelerations(y, s, su, ag, g_e)
            return (y[1], th_dd, y[3], u_dd)

        return rhs

    def _events(self, line):
        tk, a0, da, v0, dv = line
        sys_, s, su, regime = self.sys, self.s, self.su, self.regime
        events = []
        if s != 0:
            # s*theta decreases through 0; it starts at exactly 0 after uplift or an
            # impact and grows, which direction=-1 does not mistake for a crossing.
            def impact(t, y):
                return s * y[0]

            def lying(t, y):
                return s * y[0] - math.pi / 2

            def peak(t, y):
                return y[1]

            impact.terminal, impact.direction = True, -1
            lying.terminal, lying.direction = True, 1
            peak.terminal, peak.direction = False, 0
            events += [("impact", impact), ("overturn", lying), ("peak", peak)]
        if su != 0:

            def stop(t, y):
                return su * y[3]

            stop.terminal, stop.direction = True, -1
            events.append(("stop", stop))
        elif regime == ROCKING and sys_.can_slide:

            def slip(t, y):
                ag = a0 + da * (t - tk)
                force, normal = sys_.stuck_force(y, s, ag, G + v0 + dv * (t - tk))
                return sys_.mu_s * normal - abs(force)

            slip.terminal, slip.direction = True, -1
            events.append(("slip", slip))
        return events

    # ---- one integration call
    def _advance(self, t_stop: float, line, t_eval=None) -> str | None:
        """Integrate from ``self.t`` to ``t_stop`` on ``line``; return the terminal event."""
        named = self._events(line)
        names = [name for name, _ in named]
        sol = solve_ivp(
            self._rhs(line),
            (self.t, t_stop),
            self.y,
            method="DOP853",
            rtol=RTOL,
            atol=ATOL,
            events=[fn for _, fn in named] or None,
            t_eval=t_eval,
        )
        if sol.status < 0:
            raise RuntimeError(f"reference integration failed at t={self.t:.6f} s: {sol.message}")
        # With t_eval and an early terminal event, solve_ivp may return no column at all.
        ys = np.asarray(sol.y, dtype=float).reshape(self.y.size, -1)
        points = [(ti, yi) for ti, yi in zip(sol.t, ys.T, strict=False) if ti > self.t]
        # Turning points (peak events) go into the history so that it holds every peak.
        for name, t_ev, y_ev in zip(names, sol.t_events or [], sol.y_events or [], strict=False):
            if name == "peak":
                points += [(ti, yi) for ti, yi in zip(t_ev, y_ev, strict=False) if ti > self.t]
        for ti, yi in sorted(points, key=lambda point: point[0]):
            self._record(ti, yi)
        if sol.status == 1:
            for name, t_ev, y_ev in zip(names, sol.t_events, sol.y_events, strict=False):
                if name != "peak" and t_ev.size:
                    self.t, self.y = float(t_ev[-1]), np.array(y_ev[-1], dtype=float)
                    return name
        self.t = t_stop
        self.y = ys[:, -1].copy()
        return None

    # ---- event handling
    def _on_event(self, name: str) -> None:
        y = self.y
        if name == "impact":
            self.impacts.append(self.t)
            y[0] = 0.0
            y[1] *= self.sys.eta
            self.s = -self.s
            if abs(y[1]) < self.sys.rest_velocity:
                y[1] = 0.0
                self.s = 0
        elif name == "overturn":
            self._overturn()
        elif name == "stop":
            y[3] = 0.0
            self._stick_or_reverse()
        elif name == "slip":
            ag, av = self.exc.at(self.t)
            force, _ = self.sys.stuck_force(y, self.s, ag, G + av)
            self.su = -1 if force > 0.0 else 1
            self.slipped = True
        self._set_regime()
        self._record(self.t, y)

    def _slip_required(self) -> bool:
        ag, av = self.exc.at(self.t)
        force, normal = self.sys.stuck_force(self.y, self.s, ag, G + av)
        return abs(force) > self.sys.mu_s * normal

    def _stick_or_reverse(self) -> None:
        ag, av = self.exc.at(self.t)
        force, normal = self.sys.stuck_force(self.y, self.s, ag, G + av)
        if abs(force) <= self.sys.mu_s * normal:
            self.su = 0
        else:
            # Static friction cannot hold: slide on, opposite to the required force.
            self.su = -1 if force > 0.0 else 1

    def _overturn(self) -> None:
        self.status = "overturned"
        self.t_overturn = self.t

    def _leave_rest(self) -> bool:
        """Find the next onset of motion from rest; return False if there is none."""
        sys_ = self.sys
        rock = self.exc.first_exceedance(self.t, sys_.uplift_ratio) if sys_.has_tower else None
        slide = self.exc.first_exceedance(self.t, sys_.mu_s) if sys_.can_slide else None
        if rock is None and slide is None:
            return False
        if slide is not None and (rock is None or slide[0] <= rock[0]):
            self.t = slide[0]
            self.su = -slide[1]
            self.slipped = True
        else:
            self.t = rock[0]
            self.s = -rock[1]
            self.uplifted = True
        self._set_regime()
        self._record(self.t, self.y)
        return True

    def _uplift_while_sliding(self) -> None:
        """Uplift at once in regime 2 if ``|a_b| = mu_k g_e`` exceeds the tower's threshold."""
        if self.sys.has_tower and self.sys.mu_k > self.sys.uplift_ratio:
            self.s = self.su  # a_b = -mu_k su g_e
            self.uplifted = True
            self._set_regime()

    # ---- main loop
    def run(self) -> None:
        self._record(0.0, self.y)
        same_time, last_t = 0, -1.0
        while not self.status:
            same_time = same_time + 1 if self.t == last_t else 0
            last_t = self.t
            if same_time > _MAX_EVENTS_AT_SAME_TIME:
                raise RuntimeError(f"reference integration stuck at t={self.t:.9f} s")
            if self.regime == SLIDING:
                self._uplift_while_sliding()
            if self.regime == ROCKING and self.sys.can_slide and self._slip_required():
                # Only an initial rotation can start regime 1 beyond static friction.
                self._on_event("slip")
            if self.regime == REST:
                if not self._leave_rest():
                    self.status = "came_to_rest" if self._moved else "no_motion"
                    self.t = max(self.t, self.exc.t_end)
                    self._record(self.t, self.y)
                continue
            if self.t >= self.exc.t_end - 1e-12 * self.exc.dt:
                self._free_step()
                continue
            k = self.exc.interval(self.t)
            t_stop = min((k + 1) * self.exc.dt, self.exc.t_end)
            if t_stop - self.t <= 1e-12 * self.exc.dt:
                self.t = t_stop
                continue
            name = self._advance(t_stop, self.exc.line(k))
            if name is not None:
                self._on_event(name)

    @property
    def _moved(self) -> bool:
        return self.uplifted or self.slipped

    def _free_step(self) -> None:
        """One segment of motion after the excitation (zero ground motion)."""
        if self.regime == ROCKING and not self.free_safe:
            verdict = self.sys.energy_verdict(self.y[0], self.y[1])
            if verdict == "overturned":
                self._overturn()
                return
            self.free_safe = verdict == "safe"
        if self.t >= self.t_limit:
            self.status = "moving_at_end"
            return
        grid = np.arange(
            math.floor(self.t / self.exc.dt) + 1, math.ceil(self.t_limit / self.exc.dt)
        )
        t_eval = np.append(grid * self.exc.dt, self.t_limit)
        # t_eval always ends at t_limit, so the last column is the final state.
        t_eval = t_eval[(t_eval > self.t) & (t_eval <= self.t_limit)]
        name = self._advance(self.t_limit, (0.0, 0.0, 0.0, 0.0, 0.0), t_eval=t_eval)
        if name is not None:
            self._on_event(name)

    def result(self) -> ReferenceResult:
        """Collect the outcome."""
        y = np.array(self.hist_y)
        overturned = self.status == "overturned"
        alpha = self.sys.alpha if self.sys.has_tower else math.nan
        return ReferenceResult(
            status=self.status,
            overturned=overturned,
            uplifted=self.uplifted,
            slipped=self.slipped,
            theta_max=self.theta_max,
            theta_max_over_alpha=self.theta_max / alpha,
            n_impacts=len(self.impacts),
            impact_times=np.array(self.impacts),
            t_overturn=self.t_overturn,
            slip_max=self.slip_max,
            slip_residual=float(self.y[2]),
            t_end=self.t,
            t=np.array(self.hist_t),
            theta=y[:, 0],
            theta_dot=y[:, 1],
            u=y[:, 2],
            u_dot=y[:, 3],
            regime=np.array(self.hist_regime),
        )


# --------------------------------------------------------------------------- public API


def reference_rocking(
    p: float,
    alpha: float,
    eta: float,
    acc,
    dt: float,
    *,
    acc_v=None,
    linearized: bool = False,
    theta0: float = 0.0,
    theta_dot0: float = 0.0,
    t_free: float = T_FREE,
    rest_fraction: float = REST_FRACTION,
) -> ReferenceResult:
    """Integrate a rigid block rocking on a moving base (Housner), the reference way.

    Parameters
    ----------
    p : float
        Frequency parameter [rad/s].
    alpha : float
        Slenderness angle [rad], in (0, pi/2).
    eta : float
        Angular-velocity restitution theta'+/theta'- at an impact [-], in (0, 1].
    acc : array_like, shape (n,)
        Horizontal base acceleration [m/s^2] at ``t_k = k*dt``.
    dt : float
        Sampling step [s].
    acc_v : array_like, shape (n,), optional
        Vertical base acceleration [m/s^2], positive up.
    linearized : bool
        Small-angle equations (uplift at ``alpha g_e``).
    theta0, theta_dot0 : float
        Initial rotation [rad] and angular velocity [rad/s] (free rocking).
    t_free : float
        Bound on the motion after the excitation [s].
    rest_fraction : float
        Rest after an impact when ``|theta'+| < rest_fraction * p * alpha`` [-].

    Returns
    -------
    ReferenceResult
        Outcome and histories (``u`` stays zero).
    """
    p, alpha, eta = _check_block(p, alpha, eta)
    system = _System(
        p, alpha, eta, math.nan, math.inf, math.inf, math.inf, True, bool(linearized),
        _check_positive("rest_fraction", rest_fraction) * p * alpha,
    )  # fmt: skip
    integ = _make_integrator(system, acc, dt, acc_v, t_free)
    _set_initial_rotation(integ, theta0, theta_dot0)
    integ.run()
    return integ.result()


def reference_sliding(acc, dt: float, mu_s: float, mu_k: float, acc_v=None) -> ReferenceResult:
    """Integrate a Coulomb block sliding on a moving base (Newmark), the reference way.

    Parameters
    ----------
    acc : array_like, shape (n,)
        Horizontal ground acceleration [m/s^2] at ``t_k = k*dt``.
    dt : float
        Sampling step [s].
    mu_s, mu_k : float
        Static and kinetic friction coefficients [-], ``mu_s >= mu_k > 0``.
    acc_v : array_like, shape (n,), optional
        Vertical ground acceleration [m/s^2], positive up (enters the normal force).

    Returns
    -------
    ReferenceResult
        ``u`` is the slip relative to the ground [m].
    """
    mu_s, mu_k = _check_friction(mu_s, mu_k)
    system = _System(1.0, 0.1, 1.0, math.nan, 1.0, mu_s, mu_k, False, False, 0.0)
    integ = _make_integrator(system, acc, dt, acc_v, T_FREE)
    integ.run()
    return integ.result()


def reference_double_block(
    p: float,
    alpha: float,
    eta: float,
    R: float,
    acc,
    dt: float,
    tower_mass: float,
    building_mass: float,
    mu_s: float,
    mu_k: float,
    acc_v=None,
    *,
    theta0: float = 0.0,
    theta_dot0: float = 0.0,
    t_free: float = T_FREE,
    rest_fraction: float = REST_FRACTION,
) -> ReferenceResult:
    """Integrate a tower rocking on a building sliding on its foundation, the reference way.

    Parameters
    ----------
    p, alpha, eta : float
        Tower frequency parameter [rad/s], slenderness [rad], restitution [-].
    R : float
        Distance from a base corner to the tower's centre of mass [m]; the corner
        inertia is ``I_O = m g R / p^2``.
    acc : array_like, shape (n,)
        Horizontal ground acceleration [m/s^2] at ``t_k = k*dt``.
    dt : float
        Sampling step [s].
    tower_mass, building_mass : float
        Masses m and M [kg].
    mu_s, mu_k : float
        Static and kinetic friction of the building on its foundation [-].
    acc_v : array_like, shape (n,), optional
        Vertical ground acceleration [m/s^2], positive up.
    theta0, theta_dot0 : float
        Initial tower rotation [rad] and angular velocity [rad/s], building stuck.
    t_free : float
        Bound on the motion after the excitation [s].
    rest_fraction : float
        Tower rest criterion, as in :func:`reference_rocking`.

    Returns
    -------
    ReferenceResult
        ``u`` is the building slip relative to the ground [m].
    """
    p, alpha, eta = _check_block(p, alpha, eta)
    mu_s, mu_k = _check_friction(mu_s, mu_k)
    m = _check_positive("tower_mass", tower_mass)
    big_m = _check_positive("building_mass", building_mass)
    system = _System(
        p, alpha, eta, _check_positive("R", R), (big_m + m) / m, mu_s, mu_k, True, False,
        _check_positive("rest_fraction", rest_fraction) * p * alpha,
    )  # fmt: skip
    integ = _make_integrator(system, acc, dt, acc_v, t_free)
    _set_initial_rotation(integ, theta0, theta_dot0)
    integ.run()
    return integ.result()


def _set_initial_rotation(integ: _Integrator, theta0: float, theta_dot0: float) -> None:
    theta0, theta_dot0 = float(theta0), float(theta_dot0)
    if not (math.isfinite(theta0) and math.isfinite(theta_dot0)):
        raise ParameterError(f"theta0={theta0!r}, theta_dot0={theta_dot0!r} must be finite")
    if theta0 != 0.0 or theta_dot0 != 0.0:
        integ.y[:2] = theta0, theta_dot0
        integ.s = int(np.sign(theta0)) if theta0 != 0.0 else int(np.sign(theta_dot0))
        integ.uplifted = True
        integ._set_regime()


def _make_integrator(system: _System, acc, dt, acc_v, t_free) -> _Integrator:
    acc = _check_record("acc", acc)
    acc_v = None if acc_v is None else _check_record("acc_v", acc_v, acc.size)
    if acc_v is not None and np.min(acc_v) <= -G:
        # g + acc_v <= 0: the base falls away from the block, the contact model is void.
        raise ParameterError(
            f"acc_v reaches {np.min(acc_v)!r} m/s^2: it must stay above -g = {-G} m/s^2"
        )
    exc = _Excitation(acc, _check_positive("dt", dt), acc_v)
    t_free = float(t_free)
    if not math.isfinite(t_free) or t_free < 0.0:
        raise ParameterError(f"t_free={t_free!r} must be a finite number >= 0")
    return _Integrator(system, exc, t_free)
