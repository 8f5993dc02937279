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

from dataclasses import dataclass, fields, replace

from rockscreen.solver.block import RockingBlock
from rockscreen.solver.docstrings import fill_doc
from rockscreen.solver.double_block import DOUBLE_BLOCK_DOCS, check_building
from rockscreen.solver.errors import ParameterError
from rockscreen.solver.paper_integrator import PaperRun
from rockscreen.solver.paper_model import PaperModel
from rockscreen.solver.response import Response
from rockscreen.solver.validation import as_record, check_dt, check_positive

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
    run = PaperRun(PaperModel(block, form, acc, dt, **building), free_time)
    run.run()
    return run.response(history)
