"""The oracle's engine: one ``solve_ivp`` call per sample interval, events by root finding."""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

from rockscreen.solver.constants import G
from rockscreen.solver.errors import ParameterError
from rockscreen.solver.reference.model import (
    ATOL,
    BOTH,
    MAX_EVENTS_AT_SAME_TIME,
    REST,
    ROCKING,
    RTOL,
    SLIDING,
    Excitation,
    ReferenceResult,
    System,
)

__all__ = ["Integrator"]

# --------------------------------------------------------------------------- engine


class Integrator:
    """Event-driven integration over the regimes of a :class:`~.model.System`.

    Parameters
    ----------
    system : System
        The model's parameters.
    exc : Excitation
        The ground motion.
    t_free : float
        Longest free motion integrated after the excitation [s], >= 0.
    """

    def __init__(self, system: System, exc: Excitation, t_free: float):
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

    def set_initial_rotation(self, theta0: float, theta_dot0: float) -> None:
        """Start the tower rocking from ``theta0`` [rad] with ``theta_dot0`` [rad/s].

        Parameters
        ----------
        theta0, theta_dot0 : float
            Initial rotation and angular velocity; both zero leave the tower at rest.

        Raises
        ------
        ParameterError
            When either is not finite.
        """
        theta0, theta_dot0 = float(theta0), float(theta_dot0)
        if not (math.isfinite(theta0) and math.isfinite(theta_dot0)):
            raise ParameterError(f"theta0={theta0!r}, theta_dot0={theta_dot0!r} must be finite")
        if theta0 != 0.0 or theta_dot0 != 0.0:
            self.y[:2] = theta0, theta_dot0
            self.s = int(np.sign(theta0)) if theta0 != 0.0 else int(np.sign(theta_dot0))
            self.uplifted = True
            self._set_regime()

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
        """Integrate to rest, overturning or the end of the free motion."""
        self._record(0.0, self.y)
        same_time, last_t = 0, -1.0
        while not self.status:
            same_time = same_time + 1 if self.t == last_t else 0
            last_t = self.t
            if same_time > MAX_EVENTS_AT_SAME_TIME:
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
