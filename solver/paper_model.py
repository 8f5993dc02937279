"""The equations of :mod:`rockscreen.solver.paper_formulation`'s double block, regime by regime.

One :class:`PaperModel` holds the tower, the building, the ground motion and the switches of
one formulation; :class:`rockscreen.solver.paper_integrator.PaperRun` integrates it over its
regimes and :func:`rockscreen.solver.paper_formulation.solve_paper_double_block` is the
entry point. ``docs/theory.md`` section 5 derives the equations.
"""

from __future__ import annotations

import math

from rockscreen.solver.constants import G
from rockscreen.solver.errors import ParameterError
from rockscreen.solver.rocking import REST_TOLERANCE

__all__ = ["BOTH", "LOCKED", "REST", "ROCKING", "SLIDING", "PaperModel"]

#: Regime codes: at rest, tower rocking on the held building, building sliding with the
#: tower at rest, both moving.
REST, ROCKING, SLIDING, BOTH = 0, 1, 2, 3
#: Regime code of the tower held upright by the sgn(theta) friction (eq20 reading).
LOCKED = 4


class PaperModel:
    """Equations of the double block under one formulation (SI, rockscreen's convention).

    Parameters
    ----------
    block : RockingBlock
        The tower.
    form : Formulation
        The switches (:class:`rockscreen.solver.paper_formulation.Formulation`).
    acc : numpy.ndarray, shape (n,)
        Checked horizontal ground acceleration [m/s^2] at ``k*dt``.
    dt : float
        Checked sampling step [s].
    tower_mass, building_mass : float
        Masses of the tower and of the building [kg].
    mu_s, mu_k : float
        Static and kinetic friction coefficients of the building foundation [-].

    Raises
    ------
    ParameterError
        When the regime-3 system is singular (``mass_labels="labels"`` with the paper's
        masses).
    """

    def __init__(self, block, form, acc, dt, *, tower_mass, building_mass, mu_s, mu_k):
        m, big_m = tower_mass, building_mass
        self.alpha, self.eta, self.radius = block.alpha, block.eta, block.radius
        self.inertia = m * block.inertia_per_mass  # I_O [kg m^2]
        coupling = m if form.mass_labels == "values" else big_m
        self.mc = coupling  # mass of the tower terms of eq. (20) [kg]
        self.mt = m + big_m
        self.mu_s, self.mu_k, self.form = mu_s, mu_k, form
        self.p_eff = math.sqrt(coupling * G * block.radius / self.inertia)
        self.acc, self.dt, self.t_exc = acc, dt, (acc.size - 1) * dt
        self.tan_alpha = math.tan(block.alpha)
        # The kernel's cut-off (solver.kernel.make_par, w_rest2): after an impact the tower
        # rests when it could rise by less than REST_TOLERANCE * alpha.
        self.theta_dot_rest = block.p * math.sqrt(
            2.0 * math.sin(block.alpha) * REST_TOLERANCE * block.alpha
        )
        # Regime 3 solves for theta'' and u'' with the matrix [[I_O, mc R cos phi],
        # [mc R cos phi, M + m]]; its determinant is smallest at phi = 0 (theta = +-alpha).
        det = self.mt * self.inertia - (coupling * block.radius) ** 2
        if det <= 0.0:
            raise ParameterError(
                f"mass_labels={form.mass_labels!r}: the regime-3 system is singular "
                f"(determinant {det:.3e} kg^2 m^2 <= 0 at theta = alpha; with section 2.3's "
                "labels the complex's mass sits in the tower terms of eq. (20))"
            )

    def ag(self, t: float) -> float:
        """Ground acceleration [m/s^2], linear between samples, zero after the last one."""
        if t >= self.t_exc or t < 0.0:
            return 0.0
        x = t / self.dt
        k = int(x)
        a0 = self.acc[k]
        return a0 + (self.acc[k + 1] - a0) * (x - k)

    def normal(self, phi: float, w: float, theta_dd: float) -> float:
        """Return the normal force N [N] of the foundation on the building."""
        if self.form.normal_force == "paper":
            return self.mt * G
        r = self.radius
        return self.mt * G + self.mc * (r * math.sin(phi) * theta_dd - r * math.cos(phi) * w * w)

    def rocking(self, theta: float, s: int, a_b: float) -> float:
        """Return theta'' [rad/s^2] of the tower on a base accelerating by ``a_b``."""
        phi = self.alpha * s - theta
        return -self.mc * self.radius * (G * math.sin(phi) + a_b * math.cos(phi)) / self.inertia

    def hold_force(self, y, s: int, t: float) -> tuple[float, float]:
        """Force F [N] holding the building, and N [N], in regime 0 or 1."""
        ag = self.ag(t)
        if s == 0:
            return self.mt * ag, self.mt * G
        theta, w = y[0], y[1]
        phi = self.alpha * s - theta
        acc = self.rocking(theta, s, ag)
        c = s if self.form.tangential_sign == "paper" else 1.0
        r = self.radius
        force = self.mt * ag + self.mc * r * (c * math.cos(phi) * acc + math.sin(phi) * w * w)
        return force, self.normal(phi, w, acc)

    def both(self, y, s: int, su: int, t: float) -> tuple[float, float]:
        """Return ``(u'', theta'')`` of regime 3 from the 2x2 linear system."""
        theta, w = y[0], y[1]
        phi = self.alpha * s - theta
        cp, sp = math.cos(phi), math.sin(phi)
        r, mc, mu, ag = self.radius, self.mc, self.mu_k, self.ag(t)
        sigma = su if self.form.friction_sign == "velocity" else -s
        c = s if self.form.tangential_sign == "paper" else 1.0
        # F = -mu sigma N, N = Mt g + kn mc r (sp theta'' - cp w^2)
        kn = 0.0 if self.form.normal_force == "paper" else 1.0
        a11 = self.mt
        a12 = mc * r * (c * cp + kn * mu * sigma * sp)
        b1 = -mu * sigma * (self.mt * G - kn * mc * r * cp * w * w) - self.mt * ag
        b1 -= mc * r * sp * w * w
        a21, a22 = mc * r * cp, self.inertia
        b2 = -mc * r * (G * sp + ag * cp)
        det = a11 * a22 - a12 * a21
        return (b1 * a22 - a12 * b2) / det, (a11 * b2 - a21 * b1) / det

    def slides_from_rest(self, t: float) -> bool:
        """Whether the held building slips at ``t`` (tower at rest)."""
        mu = self.mu_s if self.form.regimes == "consistent" else self.mu_k
        return abs(self.ag(t)) > mu * G

    def slip_margin(self, y, s: int, t: float) -> float:
        """Positive when the held building slips (regime 1)."""
        if self.form.regimes == "consistent":
            force, normal = self.hold_force(y, s, t)
            return abs(force) - self.mu_s * normal
        return abs(self.ag(t)) - self.mu_k * G

    def rhs(self, regime: int, s: int, su: int):
        """Right-hand side ``f(t, y)`` of ``y = (theta, theta', u, u')`` in a regime."""
        if regime == ROCKING:
            return lambda t, y: (y[1], self.rocking(y[0], s, self.ag(t)), 0.0, 0.0)
        if regime == SLIDING:
            return lambda t, y: (0.0, 0.0, y[3], -self.ag(t) - self.mu_k * su * G)
        if regime == BOTH:

            def f(t, y):
                udd, tdd = self.both(y, s, su, t)
                return (y[1], tdd, y[3], udd)

            return f
        return lambda t, y: (0.0, 0.0, 0.0, 0.0)
