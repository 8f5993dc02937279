"""The oracle's public functions: single block, sliding block, double block."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from rockscreen.solver.constants import G
from rockscreen.solver.docstrings import fill_doc
from rockscreen.solver.errors import ParameterError
from rockscreen.solver.reference.integrator import Integrator
from rockscreen.solver.reference.model import (
    REST_FRACTION,
    T_FREE,
    Excitation,
    ReferenceResult,
    System,
    check_block,
    check_friction,
    check_positive,
    check_record,
)

# --------------------------------------------------------------------------- public API

#: Parameter descriptions shared by the oracle's tower functions
#: (:func:`rockscreen.solver.docstrings.fill_doc`).
_DOCS = {
    "tower": """\
p : float
    Frequency parameter [rad/s].
alpha : float
    Slenderness angle [rad], in (0, pi/2).
eta : float
    Angular-velocity restitution theta'+/theta'- at an impact [-], in (0, 1].""",
    "options": """\
**options
    Optional keywords (another one raises TypeError): ``theta0`` and ``theta_dot0``, the
    initial tower rotation [rad] and angular velocity [rad/s] (free rocking, a building
    stuck), default 0; ``t_free``, the bound on the motion after the excitation [s],
    default :data:`~rockscreen.solver.reference.T_FREE`; ``rest_fraction`` [-], rest after an impact
    when ``|theta'+| < rest_fraction * p * alpha``, default
    :data:`~rockscreen.solver.reference.REST_FRACTION`.""",
}


@fill_doc(_DOCS)
def reference_rocking(
    p: float,
    alpha: float,
    eta: float,
    acc,
    dt: float,
    *,
    acc_v=None,
    linearized: bool = False,
    **options,
) -> ReferenceResult:
    """Integrate a rigid block rocking on a moving base (Housner), the reference way.

    Parameters
    ----------
    %(tower)s
    acc : array_like, shape (n,)
        Horizontal base acceleration [m/s^2] at ``t_k = k*dt``.
    dt : float
        Sampling step [s].
    acc_v : array_like, shape (n,), optional
        Vertical base acceleration [m/s^2], positive up.
    linearized : bool
        Small-angle equations (uplift at ``alpha g_e``).
    %(options)s

    Returns
    -------
    ReferenceResult
        Outcome and histories (``u`` stays zero).
    """
    p, alpha, eta = check_block(p, alpha, eta)
    system = System(p, alpha, eta, linearized=bool(linearized))
    return _integrate(system, acc, dt, acc_v, **options)


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
    mu_s, mu_k = check_friction(mu_s, mu_k)
    system = System(1.0, 0.1, 1.0, mass_ratio=1.0, mu_s=mu_s, mu_k=mu_k, has_tower=False)
    return _integrate(system, acc, dt, acc_v)


@fill_doc(_DOCS)
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
    **options,
) -> ReferenceResult:
    """Integrate a tower rocking on a building sliding on its foundation, the reference way.

    Parameters
    ----------
    %(tower)s
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
    %(options)s

    Returns
    -------
    ReferenceResult
        ``u`` is the building slip relative to the ground [m].
    """
    p, alpha, eta = check_block(p, alpha, eta)
    mu_s, mu_k = check_friction(mu_s, mu_k)
    m = check_positive("tower_mass", tower_mass)
    big_m = check_positive("building_mass", building_mass)
    system = System(p, alpha, eta, check_positive("R", R), (big_m + m) / m, mu_s, mu_k)
    return _integrate(system, acc, dt, acc_v, **options)


def _integrate(
    system: System,
    acc,
    dt,
    acc_v,
    *,
    theta0: float = 0.0,
    theta_dot0: float = 0.0,
    t_free: float = T_FREE,
    rest_fraction: float = REST_FRACTION,
) -> ReferenceResult:
    """Check the records, start from the initial rotation (if any) and run to the end.

    The keywords are the ``**options`` of the tower functions; ``rest_fraction`` sets the
    rest criterion of a tower.
    """
    if system.has_tower:
        rest = check_positive("rest_fraction", rest_fraction) * system.p * system.alpha
        system = replace(system, rest_velocity=rest)
    integ = _make_integrator(system, acc, dt, acc_v, t_free)
    integ.set_initial_rotation(theta0, theta_dot0)
    integ.run()
    return integ.result()


def _make_integrator(system: System, acc, dt, acc_v, t_free) -> Integrator:
    acc = check_record("acc", acc)
    acc_v = None if acc_v is None else check_record("acc_v", acc_v, acc.size)
    if acc_v is not None and np.min(acc_v) <= -G:
        # g + acc_v <= 0: the base falls away from the block, the contact model is void.
        raise ParameterError(
            f"acc_v reaches {np.min(acc_v)!r} m/s^2: it must stay above -g = {-G} m/s^2"
        )
    exc = Excitation(acc, check_positive("dt", dt), acc_v)
    t_free = float(t_free)
    if not math.isfinite(t_free) or t_free < 0.0:
        raise ParameterError(f"t_free={t_free!r} must be a finite number >= 0")
    return Integrator(system, exc, t_free)
