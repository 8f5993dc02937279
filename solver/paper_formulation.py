"""The double block as Di Gennaro, Guadagnuolo & Monaco (Buildings 2023, 13, 762) print it.

A non-default option next to rockscreen's own ("consistent") double block: the paper's
eqs. (5), (20) and (21)-(24), integrated with :func:`scipy.integrate.solve_ivp` and events
(it is not the hot path; the compiled kernel stays rockscreen's model). Each departure
of the paper from the consistent model is a *switch* (:class:`Formulation`) so that it can
be applied alone on top of the consistent model; the paper's formulation is every switch
at its paper value. ``docs/theory.md`` section 5 derives them; in short, in rockscreen's
sign convention (theta > 0 tilts the tower about its right corner, x to the right) the
paper's eq. (20) reads, with ``s = sgn(theta)``, ``phi = s alpha - theta``, building slip
``u`` and total mass ``M_t = m + M``::

    M_t (a_g + u'') + m R [c cos(phi) theta'' + sin(phi) theta'^2] = F
    m R cos(phi) (a_g + u'') + I_O theta'' = -m R g sin(phi)

Eq. (20a) of the paper has the opposite sign of the base-acceleration term to eq. (5);
with x mirrored, both (20a) and the centripetal term of (20b) agree with the consistent
model, which fixes the convention ("minimum interpretation" 1). The switches:

``friction_sign``
    ``"velocity"``: ``F = -mu_k sgn(u') N`` (Coulomb). ``"theta"``: eq. (20b) signs the
    friction with ``sgn(theta)``: ``F = +mu_k s N`` in our convention (the friction then
    pushes the building towards the side the tower leans to, whatever the building does).
``normal_force``
    ``"consistent"``: ``N = M_t g + m z_G''`` (the tower's vertical inertia).
    ``"paper"``: ``N = M_t g`` (eq. (20b): ``M mu_k g``).
``tangential_sign``
    ``"consistent"``: ``c = 1``. ``"paper"``: ``c = sgn(theta)`` (eq. (20b) multiplies the
    whole brace, the ``cos(alpha - |theta|) theta''`` term included, by ``sgn(theta)``).
``regimes``
    When the building slides. ``"consistent"``: it slips when the force needed to hold it
    exceeds ``mu_s N`` and sticks again when ``u' = 0`` and the holding force is below
    ``mu_s N``. ``"paper"``: eqs. (21)-(23) read as magnitudes ("``sgn(x_g')``" taken as
    "in the direction of motion"): it slides when ``|a_g| > mu_k g`` and stops when
    ``u' = 0`` ("Lower building sliding stops when x_g'(t) = 0", read as the sliding
    velocity) unless ``|a_g| > mu_k g`` still; the tower's reaction and ``mu_s`` of eq. (24)
    play no part. ``"eq20"``: the other reading of section 3.2 ("the only sliding motion
    of the lower structure was considered according to Equation (20)"): eq. (20) governs
    whenever the tower is tilted (``theta != 0``), the building is never held while the
    tower rocks.
``mass_labels``
    ``"values"``: the symbols of eq. (20) take the values listed in section 4
    (``m2 = 339 kN``, the tower: the consistent model). ``"labels"``: the labels of
    section 2.3 (``m2`` "the mass of the monumental complex") with the same physical
    masses: the tower terms of eq. (20) then carry the complex's mass. With the paper's
    masses the regime-3 system is then singular (its determinant is negative at theta =
    alpha): refused.

Other choices, the same for every formulation: impact ``theta'+ = r theta'-`` with the
building's velocity unchanged (the paper states no rule for it); a rest cut-off after an
impact as :data:`rockscreen.solver.rocking.REST_TOLERANCE`; overturning at ``|theta| = pi/2`` while
the base moves, or by the energy barrier in free motion on a held building; no vertical
ground motion. The consistent formulation here is an independent check of the compiled
kernel (``tests/solver/test_paper_formulation.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace

from rockscreen.solver.block import RockingBlock
from rockscreen.solver.constants import G
from rockscreen.solver.docstrings import fill_doc
from rockscreen.solver.double_block import DOUBLE_BLOCK_DOCS, check_building
from rockscreen.solver.errors import ParameterError
from rockscreen.solver.response import Response
from rockscreen.solver.rocking import REST_TOLERANCE
from rockscreen.solver.validation import as_record, check_dt, check_positive

REST, ROCKING, SLIDING, BOTH = 0, 1, 2, 3
#: Regime code of the tower held upright by the sgn(theta) friction (eq20 reading).
LOCKED = 4
#: Integration tolerances of every ``solve_ivp`` call.
RTOL, ATOL = 1e-9, 1e-12
#: Default bound on the motion integrated after the excitation ends [s].
FREE_TIME = 20.0


@dataclass(frozen=True)
class Formulation:
    """Which of the paper's departures apply (defaults: the consistent model)."""

    friction_sign: str = "velocity"
    normal_force: str = "consistent"
    tangential_sign: str = "consistent"
    regimes: str = "consistent"
    mass_labels: str = "values"


#: Allowed values of each switch, the consistent value first.
SWITCHES = {
    "friction_sign": ("velocity", "theta"),
    "normal_force": ("consistent", "paper"),
    "tangential_sign": ("consistent", "paper"),
    "regimes": ("consistent", "paper", "eq20"),
    "mass_labels": ("values", "labels"),
}
#: Named formulations.
NAMED = {
    "consistent": Formulation(),
    "di-gennaro-2023": Formulation("theta", "paper", "paper", "paper", "values"),
    "di-gennaro-2023-eq20": Formulation("theta", "paper", "paper", "eq20", "values"),
}


def parse_formulation(text: str) -> Formulation:
    """Parse ``NAME[+switch=value...]``, e.g. ``"consistent+friction_sign=theta"``.

    Raises
    ------
    ParameterError
        Naming the bad part and what is allowed.
    """
    if not isinstance(text, str):
        raise ParameterError(f"formulation={text!r} must be a string")
    name, *mods = text.split("+")
    if name not in NAMED:
        raise ParameterError(
            f"formulation {text!r}: {name!r} is not one of {', '.join(NAMED)} "
            "(optionally followed by +switch=value)"
        )
    form = NAMED[name]
    for mod in mods:
        key, _, value = mod.partition("=")
        if key not in SWITCHES or value not in SWITCHES[key]:
            allowed = "; ".join(f"{k}={'|'.join(v)}" for k, v in SWITCHES.items())
            raise ParameterError(f"formulation {text!r}: {mod!r} is not allowed ({allowed})")
        form = replace(form, **{key: value})
    if form.regimes == "eq20" and form.friction_sign != "theta":
        raise ParameterError(
            f"formulation {text!r}: regimes=eq20 needs friction_sign=theta (with Coulomb "
            "friction a building that is never held while the tower tilts is ill-posed at u' = 0)"
        )
    return form


def formulation_name(form: Formulation) -> str:
    """Return the shortest text that :func:`parse_formulation` maps back to ``form``."""
    for name, named in NAMED.items():
        if named == form:
            return name
    mods = [
        f"{f.name}={getattr(form, f.name)}"
        for f in fields(form)
        if getattr(form, f.name) != SWITCHES[f.name][0]
    ]
    return "+".join(["consistent", *mods])


class _Model:
    """Equations of the double block under one :class:`Formulation` (SI, our convention)."""

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


@fill_doc(DOUBLE_BLOCK_DOCS)
def solve_paper_double_block(
    block: RockingBlock,
    acc,
    dt: float,
    *,
    tower_mass: float,
    building_mass: float,
    mu_s: float,
    mu_k: float,
    formulation: Formulation | str = "di-gennaro-2023",
    history: bool = True,
    free_time: float = FREE_TIME,
) -> Response:
    """Integrate the double block in the paper's formulation, or with some of its switches.

    Parameters
    ----------
    block : RockingBlock
        The tower (2b, 2h, eta = the paper's r; the paper's m2 and m1 of section 4 are the
        tower's and the building's mass).
    acc : array_like, shape (n,)
        Horizontal ground acceleration [m/s^2] at ``k*dt``, linear between samples, zero
        after the last sample.
    dt : float
        Sampling step [s], > 0.
    %(building)s
    formulation : Formulation or str
        A :class:`Formulation` or a text for :func:`parse_formulation`; default the
        paper's eqs. (20)-(24) as printed.
    history : bool
        Return the histories on the sample grid.
    free_time : float
        Longest motion integrated after the excitation ends [s], > 0.

    Returns
    -------
    Response
        As :func:`rockscreen.solver.solve_double_block` (``friction_demand_max`` NaN; ``p`` the
        frequency parameter of the tower equation).
    """
    form = parse_formulation(formulation) if isinstance(formulation, str) else formulation
    if not isinstance(form, Formulation):
        raise ParameterError(f"formulation={formulation!r} must be a Formulation or a name")
    acc = as_record("acc", acc)
    dt = check_dt(dt)
    building = dict(tower_mass=tower_mass, building_mass=building_mass, mu_s=mu_s, mu_k=mu_k)
    check_building(**building)
    check_positive("free_time", free_time, "s")
    from rockscreen.solver.paper_integrator import PaperRun

    run = PaperRun(_Model(block, form, acc, dt, **building), free_time)
    run.run()
    return run.response(history)
