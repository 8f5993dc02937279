"""Housner's rigid block rocking on a moving base (nonlinear, or linearized on request)."""

from __future__ import annotations

import math

from solver.block import RockingBlock
from solver.errors import ParameterError
from solver.kernel import make_par, simulate
from solver.response import Response, build_response
from solver.validation import as_record, as_vertical, check_dt, check_positive

#: Longest free motion integrated after the input ends before giving up [s].
MAX_FREE_TIME = 60.0
#: Zeno cut-off: an impact after which the tower could rise by less than this fraction
#: of alpha ends the rocking (the tower is at rest and waits for a new uplift test).
#: Rocking on real records is chaotic: a coarser cut-off (1e-5) changed theta_max by up to
#: 98 % against the converged solve_ivp oracle (benchmarks/solver_bench.py); 1e-9 agrees
#: within 0.08 % on all 68 benchmark cases.
REST_TOLERANCE = 1e-9


def check_block(block) -> None:
    """Raise unless ``block`` is a :class:`RockingBlock`."""
    if not isinstance(block, RockingBlock):
        raise ParameterError(
            f"block must be a RockingBlock (use RockingBlock.from_dimensions), got {block!r}"
        )


def check_initial(theta0: float, theta_dot0: float) -> None:
    """Raise unless the initial rotation is within (-pi/2, pi/2) and both are finite."""
    if not (math.isfinite(theta0) and abs(theta0) < 0.5 * math.pi):
        raise ParameterError(f"theta0={theta0!r} rad must be finite with |theta0| < pi/2")
    if not math.isfinite(theta_dot0):
        raise ParameterError(f"theta_dot0={theta_dot0!r} rad/s must be finite")


def check_solver_options(max_free_time: float, rest_tolerance: float, max_substep) -> None:
    """Validate the integration controls shared by all solvers."""
    check_positive("max_free_time", max_free_time, "s")
    check_positive("rest_tolerance", rest_tolerance)
    if max_substep is not None:
        check_positive("max_substep", max_substep, "s")


def check_base_motion(block, acc, dt: float, acc_v):
    """Validate a tower and its base motion; return them as the kernel takes them.

    Returns
    -------
    acc : ndarray, shape (n,)
        Horizontal base acceleration [m/s^2], float64.
    dt : float
        Sampling step [s].
    acc_v : ndarray, shape (n,)
        Vertical base acceleration [m/s^2] (zeros when none was given).
    """
    check_block(block)
    arr = as_record("acc", acc)
    dt = check_dt(dt)
    return arr, dt, as_vertical(acc_v, arr.size)


def run_tower(
    block: RockingBlock,
    acc,
    acc_v,
    dt: float,
    *,
    theta0: float,
    theta_dot0: float,
    history: bool,
    max_free_time: float,
    rest_tolerance: float,
    max_substep: float | None,
    **model,
) -> Response:
    """Integrate a checked tower with the compiled kernel and build its :class:`Response`.

    ``acc``, ``acc_v`` [m/s^2] and ``dt`` [s] come from :func:`check_base_motion`;
    ``model`` holds the :func:`solver.kernel.make_par` keywords that tell the models
    apart (``linearized``, ``can_slide``, ``mass_ratio``, ``mu_s``, ``mu_k``).
    """
    par = make_par(
        p=block.p,
        alpha=block.alpha,
        inertia_ratio=block.inertia_ratio,
        radius=block.radius,
        eta=block.eta,
        tower=True,
        rest_tolerance=rest_tolerance,
        max_substep=max_substep,
        max_free_time=max_free_time,
        **model,
    )
    raw = simulate(acc, acc_v, dt, par, float(theta0), float(theta_dot0), bool(history))
    return build_response(
        raw,
        alpha=block.alpha,
        p=block.p,
        eta=block.eta,
        tower=True,
        history=history,
        max_free_time=max_free_time,
    )


def solve_rocking(
    block: RockingBlock,
    acc,
    dt: float,
    *,
    acc_v=None,
    linearized: bool = False,
    theta0: float = 0.0,
    theta_dot0: float = 0.0,
    history: bool = True,
    max_free_time: float = MAX_FREE_TIME,
    rest_tolerance: float = REST_TOLERANCE,
    max_substep: float | None = None,
) -> Response:
    """Integrate the rocking of a rigid block on a base moving with ``acc``.

    Parameters
    ----------
    block : RockingBlock
        The block (alpha, p, eta, R, I_O/m).
    acc : array_like, shape (n,)
        Horizontal base acceleration [m/s^2] at ``t_k = k*dt``, linear between samples,
        zero after the last sample.
    dt : float
        Sampling step [s], > 0.
    acc_v : array_like, shape (n,), optional
        Vertical base acceleration [m/s^2], positive up; must stay above -g.
    linearized : bool
        Use the small-angle equations (uplift at alpha*g); only for comparison with
        classic closed forms.
    theta0, theta_dot0 : float
        Initial rotation [rad] and angular velocity [rad/s]; positive = rocking about
        the right corner.
    history : bool
        Return the histories; ``False`` allocates no arrays (fast screening path).
    max_free_time : float
        Longest free motion integrated after the input ends [s] while the outcome is
        undecided (then the status is ``"moving_at_end"``).
    rest_tolerance : float
        Zeno cut-off [-]: the fraction of alpha the tower could still rise after an
        impact below which it is at rest.
    max_substep : float, optional
        Largest RK4 sub-step [s]; default ``min(0.02/p, 1 ms)``.

    Returns
    -------
    Response
        The outcome; ``slip_max`` and ``slip_residual`` are 0 (the base does not slide).
    """
    arr, dt, arr_v = check_base_motion(block, acc, dt, acc_v)
    check_initial(theta0, theta_dot0)
    check_solver_options(max_free_time, rest_tolerance, max_substep)
    return run_tower(
        block,
        arr,
        arr_v,
        dt,
        theta0=theta0,
        theta_dot0=theta_dot0,
        history=history,
        max_free_time=max_free_time,
        rest_tolerance=rest_tolerance,
        max_substep=max_substep,
        linearized=bool(linearized),
        can_slide=False,
    )
