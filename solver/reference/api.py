"""The oracle's public functions: single block, sliding block, double block."""

from __future__ import annotations

import math

import numpy as np

from solver.constants import G
from solver.errors import ParameterError
from solver.reference.integrator import _Integrator
from solver.reference.model import (
    REST_FRACTION,
    T_FREE,
    ReferenceResult,
    _check_block,
    _check_friction,
    _check_positive,
    _check_record,
    _Excitation,
    _System,
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
    return _integrate(system, acc, dt, acc_v, t_free, theta0, theta_dot0)


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
    return _integrate(system, acc, dt, acc_v, T_FREE)


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
    return _integrate(system, acc, dt, acc_v, t_free, theta0, theta_dot0)


def _set_initial_rotation(integ: _Integrator, theta0: float, theta_dot0: float) -> None:
    theta0, theta_dot0 = float(theta0), float(theta_dot0)
    if not (math.isfinite(theta0) and math.isfinite(theta_dot0)):
        raise ParameterError(f"theta0={theta0!r}, theta_dot0={theta_dot0!r} must be finite")
    if theta0 != 0.0 or theta_dot0 != 0.0:
        integ.y[:2] = theta0, theta_dot0
        integ.s = int(np.sign(theta0)) if theta0 != 0.0 else int(np.sign(theta_dot0))
        integ.uplifted = True
        integ._set_regime()


def _integrate(
    system: _System, acc, dt, acc_v, t_free, theta0: float = 0.0, theta_dot0: float = 0.0
) -> ReferenceResult:
    """Check the records, start from the initial rotation (if any) and run to the end."""
    integ = _make_integrator(system, acc, dt, acc_v, t_free)
    _set_initial_rotation(integ, theta0, theta_dot0)
    integ.run()
    return integ.result()


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
