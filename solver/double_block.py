"""The double block: a tower rocking on a building that sticks or slides on its foundation."""

from __future__ import annotations

import math

from solver.block import RockingBlock
from solver.errors import ParameterError
from solver.response import Response
from solver.rocking import (
    MAX_FREE_TIME,
    REST_TOLERANCE,
    check_base_motion,
    check_initial,
    check_scale,
    check_solver_options,
    run_kernel,
)
from solver.validation import check_friction, check_positive


def check_coupling(block: RockingBlock, mass_ratio: float, mu_k: float) -> None:
    """Raise if the coupled sliding-rocking equations can lose their unique solution.

    The determinant of the regime-3 system is
    ``1 - r (m R^2/I_O) cos(phi) (cos(phi) + mu_k s_u sin(phi))`` with ``r = m/(M+m)``;
    its smallest value over all angles is ``1 - r (m R^2/I_O) (1 + sqrt(1 + mu_k^2))/2``.
    When that is not positive the Coulomb model is inconsistent (Painleve's paradox).
    """
    worst = 1.0 - mass_ratio * block.inertia_ratio * 0.5 * (1.0 + math.sqrt(1.0 + mu_k * mu_k))
    if not worst > 0.0:
        raise ParameterError(
            f"tower_mass/(tower_mass+building_mass)={mass_ratio!r} with mu_k={mu_k!r}: the "
            "rocking-sliding equations have no unique solution (Painleve paradox); the "
            "building must be heavier relative to the tower, or mu_k smaller"
        )


def solve_double_block(
    block: RockingBlock,
    acc,
    dt: float,
    *,
    tower_mass: float,
    building_mass: float,
    mu_s: float,
    mu_k: float,
    acc_v=None,
    history: bool = True,
    theta0: float = 0.0,
    theta_dot0: float = 0.0,
    max_free_time: float = MAX_FREE_TIME,
    rest_tolerance: float = REST_TOLERANCE,
    max_substep: float | None = None,
    scale: float = 1.0,
    friction_demand: bool = True,
) -> Response:
    """Integrate a tower rocking on a building that slides on its foundation (docs/theory.md).

    Parameters
    ----------
    block : RockingBlock
        The tower.
    acc : array_like, shape (n,), or BaseMotion
        Horizontal ground acceleration [m/s^2] at ``t_k = k*dt``, linear between
        samples, zero after the last sample; or a record checked once by
        :func:`solver.rocking.base_motion` (then ``acc_v`` is None and ``dt`` its step).
    dt : float
        Sampling step [s], > 0.
    tower_mass, building_mass : float
        Masses m and M [kg], > 0.
    mu_s, mu_k : float
        Static and kinetic friction of the building on its foundation [-],
        ``0 <= mu_k <= mu_s``.
    acc_v : array_like, shape (n,), optional
        Vertical ground acceleration [m/s^2], positive up; scaled, above -g.
    history : bool
        Return the histories.
    theta0, theta_dot0 : float
        Initial tower rotation [rad] and angular velocity [rad/s].
    max_free_time : float
        Longest free motion integrated after the input ends [s].
    rest_tolerance : float
        Zeno cut-off [-] (see :func:`solver.solve_rocking`).
    max_substep : float, optional
        Largest RK4 sub-step [s]; default ``min(0.02/p, 1.7 ms)``.
    scale : float
        Factor [-], > 0, applied to ``acc`` and ``acc_v`` inside the solver.
    friction_demand : bool
        Track the largest friction demand (``False``: NaN, a little faster).

    Returns
    -------
    Response
        Tower rotation, building slip ``u`` relative to the ground, regimes (0 rest,
        1 tower rocking, 2 building sliding, 3 both).
    """
    scale = check_scale(scale)
    motion = check_base_motion(block, acc, dt, acc_v, scale)
    check_positive("tower_mass", tower_mass, "kg")
    check_positive("building_mass", building_mass, "kg")
    check_friction(mu_s, mu_k)
    check_initial(theta0, theta_dot0)
    check_solver_options(max_free_time, rest_tolerance, max_substep)
    mass_ratio = tower_mass / (tower_mass + building_mass)
    check_coupling(block, mass_ratio, mu_k)
    return run_kernel(
        block,
        motion,
        theta0=theta0,
        theta_dot0=theta_dot0,
        history=history,
        max_free_time=max_free_time,
        rest_tolerance=rest_tolerance,
        max_substep=max_substep,
        scale=scale,
        friction_demand=bool(friction_demand),
        mass_ratio=mass_ratio,
        mu_s=mu_s,
        mu_k=mu_k,
        can_slide=True,
    )
