"""Event-driven ``solve_ivp`` integration of :mod:`rockscreen.solver.paper_model`'s equations.

Regimes 0 rest, 1 tower rocking on the held building, 2 building sliding with the tower at
rest, 3 both, 4 tower locked upright by the sgn(theta) friction (sliding mode); every
transition is an event located by ``solve_ivp``'s root finder, never snapped to a sample.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.integrate import solve_ivp

from rockscreen.solver.constants import G
from rockscreen.solver.paper_model import BOTH, LOCKED, REST, ROCKING, SLIDING, PaperModel
from rockscreen.solver.response import Response

#: Integration tolerances of every ``solve_ivp`` call.
RTOL, ATOL = 1e-9, 1e-12
_MAX_EVENTS = 50_000


def _event(fun, direction=0.0, terminal=True):
    fun.terminal, fun.direction = terminal, direction
    return fun


class PaperRun:
    """Event-driven integration of one :class:`~rockscreen.solver.paper_model.PaperModel`."""

    def __init__(self, model: PaperModel, free_time: float):
        self.mod = model
        self.t, self.y = 0.0, np.zeros(4)
        self.regime, self.s, self.su = REST, 0, 0
        self.t_limit = model.t_exc + free_time
        self.theta_max, self.impacts = 0.0, []
        self.uplifted = self.slipped = False
        self.status, self.t_over, self.note, self.t_seg = "", math.nan, "", -1.0
        self.hist_t, self.hist_y, self.hist_r = [], [], []

    def _record(self, t, y, regime):
        self.hist_t.append(np.atleast_1d(t))
        self.hist_y.append(np.atleast_2d(y).reshape(4, -1))
        self.hist_r.append(np.full(np.size(t), regime, dtype=np.int8))

    def _grid(self, t0: float, t1: float) -> np.ndarray:
        dt = self.mod.dt
        k0 = math.floor(t0 / dt + 1e-9) + 1
        k1 = math.floor(t1 / dt + 1e-9)
        return np.arange(k0, k1 + 1) * dt

    def run(self) -> None:
        """Integrate until rest after the excitation, overturning or the time bound."""
        self._record(0.0, self.y, REST)
        for _ in range(_MAX_EVENTS):
            if self.status:
                return
            if self.t >= self.t_limit:
                self.status = "moving_at_end" if self.regime != REST else "came_to_rest"
                return
            if self.regime == REST:
                self._rest()
            else:
                self._move()
        self.status = "moving_at_end"

    def _rest(self) -> None:
        """Wait (exactly, on the piecewise-linear record) for uplift or slip."""
        mod, t0 = self.mod, self.t
        if t0 >= mod.t_exc:
            self.status = "came_to_rest" if (self.uplifted or self.slipped) else "no_motion"
            return
        mu = mod.mu_s if mod.form.regimes == "consistent" else mod.mu_k
        ratio = min(mod.tan_alpha, mu)
        k0 = int(t0 / mod.dt)
        a = np.abs(mod.acc[k0:]) - ratio * G
        a0 = abs(mod.ag(t0)) - ratio * G
        if a0 > 0.0:
            t_hit = t0
        else:
            hits = np.flatnonzero(a[1:] > 0.0)
            if hits.size == 0:
                self.t = mod.t_exc
                grid = self._grid(t0, self.t)
                self._record(grid, np.zeros((4, grid.size)), REST)
                return
            j = k0 + 1 + int(hits[0])
            f0, f1 = a[j - 1 - k0], a[j - k0]
            tj0 = max(t0, (j - 1) * mod.dt)
            f0 = abs(mod.ag(tj0)) - ratio * G
            t_hit = tj0 + (j * mod.dt - tj0) * (-f0) / (f1 - f0) if f1 != f0 else j * mod.dt
        grid = self._grid(t0, t_hit)
        self._record(grid, np.tile(self.y[:, None], grid.size), REST)
        self.t = t_hit
        ag = mod.ag(t_hit + 1e-9 * mod.dt)
        if mod.slides_from_rest(t_hit + 1e-9 * mod.dt):
            self.slipped, self.su = True, -int(np.sign(ag))
            self.regime = SLIDING
            self._check_uplift_while_sliding()
        else:
            self._uplift(-int(np.sign(ag)))

    def _uplift(self, s: int) -> None:
        if self.mod.form.regimes == "eq20":
            # eq. (20) from the first tilt on; with the sgn(theta) friction the base is pushed
            # at mu_k g towards the side the tower leans to: if that beats the overturning
            # moment on both sides, theta = 0 is a sliding mode (Filippov): the tower is locked
            self.slipped = True
            if self._is_locked():
                self._locked()
                return
            self.uplifted, self.s, self.su, self.regime = True, s, s, BOTH
            return
        if self.regime == SLIDING and self._is_locked():
            self._locked()
            return
        self.uplifted, self.s = True, s
        self.regime = BOTH if self.regime == SLIDING else ROCKING

    def _is_locked(self) -> bool:
        """Whether the sgn(theta) friction pushes the upright tower back from both sides."""
        if self.mod.form.friction_sign != "theta":
            return False
        y = np.array([0.0, 0.0, self.y[2], self.y[3]])
        tilt = [self.mod.both(y, side, 1, self.t)[1] * side for side in (1, -1)]
        return max(tilt) <= 0.0

    def _locked(self) -> None:
        """Tower held upright by the chattering sgn(theta) friction until the input ends.

        On the sliding mode the two friction directions average out (theta'' = 0 needs
        equal weights), so the building moves as if frictionless: u'' = -a_g.
        """
        mod, t0 = self.mod, self.t
        grid = np.concatenate(([t0], self._grid(t0, mod.t_exc)))
        ag = np.array([mod.ag(t) for t in grid])
        dv = np.concatenate(([0.0], np.cumsum(0.5 * (ag[1:] + ag[:-1]) * np.diff(grid))))
        v = self.y[3] - dv
        du = np.concatenate(([0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(grid))))
        u = self.y[2] + du
        stop = grid.size - 1
        if mod.form.regimes != "eq20" and v.size > 1:  # sliding ends when u' changes sign
            flips = np.flatnonzero(np.sign(v[1:]) != np.sign(v[1]))
            stop = int(flips[0]) + 1 if flips.size else stop
        zeros = np.zeros_like(grid)
        self._record(grid[1 : stop + 1], np.vstack((zeros, zeros, u, v))[:, 1 : stop + 1], LOCKED)
        self.t, self.y = float(grid[stop]), np.array([0.0, 0.0, u[stop], v[stop]])
        self.s = 0
        if stop < grid.size - 1:
            self.y[3], self.regime = 0.0, REST
            return
        self.status = "moving_at_end"
        self.note = (
            "the sgn(theta) friction of eq. (20) locks the tower upright (sliding mode at "
            "theta = 0); the building then moves as if frictionless: the outcome is undecided"
        )

    def _check_uplift_while_sliding(self) -> None:
        if self.mod.mu_k > self.mod.tan_alpha:  # base acceleration -mu_k su g lifts the tower
            self._uplift(self.su)

    def _events(self):
        mod, s, su, regime = self.mod, self.s, self.su, self.regime
        events = []
        if regime in (ROCKING, BOTH):
            events.append(_event(lambda t, y: y[0], -s))
            events.append(_event(lambda t, y: abs(y[0]) - 0.5 * math.pi, 1.0))
            events.append(_event(lambda t, y: y[1], 0.0, terminal=False))
        if regime == ROCKING:
            events.append(_event(lambda t, y: mod.slip_margin(y, s, t), 1.0))
        stops = regime == SLIDING or not (
            mod.form.regimes == "eq20" and mod.form.friction_sign == "theta"
        )
        if regime in (SLIDING, BOTH) and stops:
            events.append(_event(lambda t, y: y[3], -su))
        return events

    def _move(self) -> None:
        mod = self.mod
        t_end = mod.t_exc if self.t < mod.t_exc else self.t_limit
        kinds = self._event_kinds()
        self.t_seg = self.t
        grid = self._grid(self.t, t_end)
        on_grid = grid.size > 0 and abs(grid[-1] - t_end) <= 1e-9 * mod.dt
        t_eval = grid if on_grid else np.append(grid, t_end)
        sol = solve_ivp(
            mod.rhs(self.regime, self.s, self.su),
            (self.t, t_end),
            self.y,
            method="RK45",
            t_eval=t_eval,
            events=self._events(),
            rtol=RTOL,
            atol=ATOL,
            max_step=mod.dt,
        )
        if sol.status < 0:  # pragma: no cover - solve_ivp failure is not an outcome
            raise RuntimeError(f"solve_ivp failed at t = {self.t:.6g} s: {sol.message}")
        sol_t = np.asarray(sol.t, dtype=float)
        sol_y = np.asarray(sol.y, dtype=float).reshape(4, sol_t.size)
        n_grid = int(np.count_nonzero(sol_t <= grid[-1] + 1e-9 * mod.dt)) if grid.size else 0
        if n_grid:
            self._record(sol_t[:n_grid], sol_y[:, :n_grid], self.regime)
        if sol_t.size:
            self.theta_max = max(self.theta_max, float(np.max(np.abs(sol_y[0]))))
        fired = []
        for kind, te, ye in zip(kinds, sol.t_events, sol.y_events, strict=True):
            if kind == "peak" and ye.size:
                self.theta_max = max(self.theta_max, float(np.max(np.abs(ye[:, 0]))))
            elif te.size:
                fired.append((float(te[0]), kind, ye[0]))
        if not fired:
            self.t, self.y = float(t_end), np.array(sol_y[:, -1], dtype=float)
            return
        t_ev, kind, y_ev = min(fired, key=lambda item: item[0])
        self.t, self.y = t_ev, np.array(y_ev, dtype=float)
        self.theta_max = max(self.theta_max, abs(self.y[0]))
        getattr(self, f"_on_{kind}")()

    def _event_kinds(self) -> list[str]:
        kinds = []
        if self.regime in (ROCKING, BOTH):
            kinds += ["impact", "overturn", "peak"]
        if self.regime == ROCKING:
            kinds.append("slip")
        stops = self.regime == SLIDING or not (
            self.mod.form.regimes == "eq20" and self.mod.form.friction_sign == "theta"
        )
        if self.regime in (SLIDING, BOTH) and stops:
            kinds.append("stop")
        return kinds

    def _on_overturn(self) -> None:
        self.status, self.t_over = "overturned", self.t

    def _on_impact(self) -> None:
        mod = self.mod
        self.impacts.append(self.t)
        self.y[0] = 0.0
        self.y[1] *= mod.eta
        w = self.y[1]
        self.s = -self.s
        if self.regime == BOTH and self._is_locked():
            self._locked()
            return
        if abs(w) < mod.theta_dot_rest:
            self.y[:2] = 0.0
            self.s = 0
            if self.regime == BOTH and self.y[3] != 0.0:
                self.regime = SLIDING
                self._check_uplift_while_sliding()
            else:
                self.regime, self.y[3] = REST, 0.0
            return
        if self.regime == ROCKING and self.t >= mod.t_exc:
            # free motion on a held building: the energy barrier decides (impacts only dissipate)
            level = math.cos(mod.alpha) + w * w / (2.0 * mod.p_eff**2)
            if level >= 1.0:
                self.status, self.t_over = "overturned", self.t
            else:
                self.theta_max = max(self.theta_max, mod.alpha - math.acos(level))
                self.status = "came_to_rest"

    def _on_slip(self) -> None:
        mod = self.mod
        if mod.form.regimes == "consistent":
            force, _ = mod.hold_force(self.y, self.s, self.t)
        else:
            force = mod.ag(self.t)
        self.su = -int(np.sign(force)) or 1
        self.slipped, self.regime = True, BOTH

    def _on_stop(self) -> None:
        mod = self.mod
        self.y[3] = 0.0
        tiny = self.t + 1e-9 * mod.dt
        if mod.form.regimes == "eq20" and self.regime == BOTH:
            self.su = -self.su  # eq. (20) holds while the tower is tilted: keep sliding
            return
        if mod.form.regimes == "consistent":
            force, normal = mod.hold_force(self.y, self.s, tiny)
            holds = abs(force) <= mod.mu_s * normal
        else:
            force = mod.ag(tiny)
            holds = abs(force) <= mod.mu_k * G
        if holds or self.t <= self.t_seg + 1e-12 * mod.dt:
            # (a stop right where sliding restarted: the demand cannot drive it; hold it)
            self.regime = ROCKING if self.s != 0 else REST
        else:
            self.su = -int(np.sign(force)) or -self.su

    def response(self, history: bool) -> Response:
        """Collect the outcome as a :class:`rockscreen.solver.response.Response`."""
        mod = self.mod
        t = np.concatenate(self.hist_t)
        y = np.concatenate(self.hist_y, axis=1)
        regime = np.concatenate(self.hist_r)
        u = y[2]
        messages = {
            "overturned": f"overturned at t = {self.t_over:.4f} s",
            "came_to_rest": f"came to rest, or cannot overturn, by t = {self.t:.4f} s",
            "no_motion": "no uplift and no slip: the block never moved",
            "moving_at_end": f"still moving at t = {self.t:.4f} s: the outcome is undecided",
        }
        arrays = {}
        if history:
            arrays = dict(t=t, theta=y[0], theta_dot=y[1], u=u, u_dot=y[3], regime=regime)
        u_all = np.append(u, self.y[2])
        return Response(
            status=self.status,
            overturned=self.status == "overturned",
            uplifted=self.uplifted,
            slipped=self.slipped,
            theta_max=self.theta_max,
            theta_max_over_alpha=self.theta_max / mod.alpha,
            n_impacts=len(self.impacts),
            impact_times=np.asarray(self.impacts, dtype=float),
            t_overturn=self.t_over,
            slip_max=float(np.max(np.abs(u_all))),
            slip_residual=float(self.y[2]),
            friction_demand_max=math.nan,
            t_end=self.t,
            alpha=mod.alpha,
            p=mod.p_eff,
            eta=mod.eta,
            message=self.note or messages[self.status],
            **arrays,
        )
