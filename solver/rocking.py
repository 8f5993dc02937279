"""Housner's rigid block rocking on a moving base (nonlinear, or linearized on request)."""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from rockscreen.solver.block import RockingBlock
from rockscreen.solver.docstrings import fill_doc
from rockscreen.solver.errors import ParameterError
from rockscreen.solver.kernel import make_par, simulate
from rockscreen.solver.response import Response, build_response
from rockscreen.solver.validation import (
    as_record,
    as_vertical,
    check_dt,
    check_positive,
    check_vertical_min,
)

#: Longest free motion integrated after the input ends before giving up [s].
MAX_FREE_TIME = 60.0
#: Zeno cut-off: an impact after which the tower could rise by less than this fraction
#: of alpha ends the rocking (the tower is at rest and waits for a new uplift test).
#: Rocking on real records is chaotic: a coarser cut-off (1e-5) changed theta_max by up to
#: 98 % against the converged solve_ivp oracle (benchmarks/solver_bench.py); 1e-9 agrees
#: within 0.13 % on all 68 benchmark cases with the default sub-step (1e-8: the same
#: theta_max, not measurably faster).
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


def check_scale(scale: float) -> float:
    """Return the record scale factor as float after checking it is finite and > 0."""
    check_positive("scale", scale)
    return float(scale)


def check_solver_options(max_free_time: float, rest_tolerance: float, max_substep) -> None:
    """Validate the integration controls of the tower solvers (rocking and double block)."""
    check_positive("max_free_time", max_free_time, "s")
    check_positive("rest_tolerance", rest_tolerance)
    if max_substep is not None:
        check_positive("max_substep", max_substep, "s")


@dataclass(frozen=True)
class RunOptions:
    """The keywords the tower solvers share: vertical record, initial state, integration controls.

    :func:`solve_rocking` and :func:`solver.solve_double_block` take each field as a keyword
    of the same name and default (``**options``; another keyword raises TypeError);
    :func:`solver.solve_sliding` runs with its ``history`` and ``max_free_time``. The values
    are checked on construction (:class:`~rockscreen.solver.errors.ParameterError`); the vertical
    record is checked with the horizontal one (:func:`check_base_motion`).
    """

    #: (array_like, shape (n,), optional) Vertical base acceleration [m/s^2], positive up; scaled,
    #: it must stay above -g. None with a :class:`BaseMotion` as ``acc`` (it holds its own).
    acc_v: object = None
    #: Initial rotation [rad] and angular velocity [rad/s]; positive = rocking about the right
    #: corner.
    theta0: float = 0.0
    theta_dot0: float = 0.0
    #: Return the histories; False allocates no arrays (fast screening path).
    history: bool = True
    #: Longest free motion integrated after the input ends [s] while the outcome is undecided
    #: (then the status is ``"moving_at_end"``).
    max_free_time: float = MAX_FREE_TIME
    #: Zeno cut-off [-]: the fraction of alpha the tower could still rise after an impact below
    #: which it is at rest.
    rest_tolerance: float = REST_TOLERANCE
    #: Largest RK4 sub-step [s]; None: ``min(0.02/p, 1.7 ms)``.
    max_substep: float | None = None
    #: Factor [-], > 0, applied to ``acc`` and ``acc_v`` (the same result as solving the
    #: multiplied records, without making them).
    scale: float = 1.0
    #: Track the largest friction demand; False skips it (a little faster) and
    #: ``friction_demand_max`` is NaN.
    friction_demand: bool = True
    #: End the free motion as soon as its outcome is certain (verdict-only screening):
    #: trailing zeros of the records are free motion too; once the base is still, a tower
    #: rocking on it below the overturning energy barrier (eta < 1) can never overturn
    #: (impacts and friction only dissipate; docs/theory.md, "Early stop"), so the solve
    #: stops with status ``came_to_rest`` and ``theta_max`` including the largest swing still
    #: to come, instead of following the decay to rest. The verdict and ``theta_max`` are
    #: those of the full solve (to the integration's accuracy); ``t_end``, ``n_impacts``,
    #: ``impact_times``, ``slip_residual`` and the histories stop at the early end.
    stop_when_certain: bool = False

    def __post_init__(self) -> None:
        # Frozen: the scale is stored as the float it is checked and quoted as.
        object.__setattr__(self, "scale", check_scale(self.scale))
        check_initial(self.theta0, self.theta_dot0)
        check_solver_options(self.max_free_time, self.rest_tolerance, self.max_substep)

    @classmethod
    def from_keywords(cls, solver: str, options: dict) -> RunOptions:
        """Return the options of a call of ``rockscreen.solver`` (its ``**options``), checked.

        Raises
        ------
        TypeError
            For a keyword that is not a field, naming it, the solver and the allowed ones.
        ParameterError
            For a value out of its range.
        """
        try:
            return cls(**options)
        except TypeError:
            # Named only on the way out: a valid call pays nothing for the message.
            allowed = [field.name for field in fields(cls)]
            unknown = sorted(set(options) - set(allowed))
            if not unknown:
                raise
            raise TypeError(
                f"{solver}() got an unexpected keyword argument {unknown[0]!r}; "
                f"its options are {', '.join(allowed)}"
            ) from None


#: Parameter descriptions the tower solvers share (:func:`rockscreen.solver.docstrings.fill_doc`).
TOWER_DOCS = {
    "motion": """\
acc : array_like, shape (n,), or BaseMotion
    Horizontal base acceleration [m/s^2] (of the ground, under the building of the double
    block) at ``t_k = k*dt``, linear between samples, zero after the last sample; or a
    record checked once by :func:`rockscreen.solver.rocking.base_motion` (then ``acc_v`` is None and
    ``dt`` its step).
dt : float
    Sampling step [s], > 0.""",
    "options": """\
**options
    The keywords of :class:`rockscreen.solver.rocking.RunOptions`, with its defaults and checks:
    ``acc_v`` (vertical base acceleration [m/s^2]), ``theta0`` and ``theta_dot0`` (initial
    rotation [rad] and angular velocity [rad/s]), ``history``, ``max_free_time`` [s],
    ``rest_tolerance`` [-], ``max_substep`` [s], ``scale`` [-], ``friction_demand`` and
    ``stop_when_certain``.""",
}


@dataclass(frozen=True)
class BaseMotion:
    """A base motion checked once, for many solves of the same record.

    Build it with :func:`base_motion` and pass it as ``acc`` to :func:`solve_rocking` or
    :func:`rockscreen.solver.solve_double_block` (with ``acc_v=None`` and the same ``dt``): the
    record is then not converted and scanned for NaN again on every call, which matters
    for repeated solves of a long record with different ``scale`` (a safety-factor
    search).
    """

    #: (ndarray, shape (n,)) Horizontal base acceleration [m/s^2], float64, read-only.
    acc: np.ndarray
    #: (ndarray, shape (n,) or (0,)) Vertical base acceleration [m/s^2], float64, read-only; empty
    #: when none.
    acc_v: np.ndarray
    #: Sampling step [s].
    dt: float
    #: Smallest vertical acceleration [m/s^2] (0 when none).
    acc_v_min: float


def base_motion(acc, dt: float, acc_v=None) -> BaseMotion:
    """Check a base motion once and return it as a read-only :class:`BaseMotion`.

    Parameters
    ----------
    acc : array_like, shape (n,)
        Horizontal base acceleration [m/s^2], finite.
    dt : float
        Sampling step [s], > 0.
    acc_v : array_like, shape (n,), optional
        Vertical base acceleration [m/s^2], finite, positive up. Whether it stays above
        -g is checked per solve, on the scaled record.

    Returns
    -------
    BaseMotion
        Private read-only copies of the records.
    """
    return checked_motion(acc, dt, acc_v, copy=True)


def checked_motion(acc, dt, acc_v, *, copy: bool = False) -> BaseMotion:
    """Check a base motion (the records, ``dt``) and return it as a :class:`BaseMotion`.

    ``copy=True`` makes private read-only copies; whether the vertical record stays above
    -g is left to :func:`rockscreen.solver.validation.check_vertical_min` on ``acc_v_min``.
    """
    arr = as_record("acc", acc)
    dt = check_dt(dt)
    arr_v = as_vertical(acc_v, arr.size)
    if copy:
        # Private copies: a caller changing its arrays later cannot bypass the checks.
        arr, arr_v = arr.copy(), arr_v.copy()
        arr.flags.writeable = False
        arr_v.flags.writeable = False
    low = float(arr_v.min()) if arr_v.size else 0.0
    return BaseMotion(arr, arr_v, dt, low)


def check_base_motion(block, acc, dt: float, acc_v, scale: float = 1.0) -> BaseMotion:
    """Validate a tower and its base motion; return the motion as the kernel takes it.

    ``acc`` is an array or a :class:`BaseMotion` (then ``acc_v`` must be None and
    ``dt`` its step). The vertical acceleration scaled by ``scale`` must stay above -g.

    Returns
    -------
    BaseMotion
        The records as contiguous float64 arrays (``acc_v`` empty when none was given).
    """
    check_block(block)
    if isinstance(acc, BaseMotion):
        if acc_v is not None:
            raise ParameterError(
                "acc_v must be None when acc is a BaseMotion (it holds its vertical record)"
            )
        if not dt == acc.dt:
            raise ParameterError(f"dt={dt!r} s differs from the BaseMotion's dt={acc.dt!r} s")
        motion = acc
    else:
        motion = checked_motion(acc, dt, acc_v)
    check_vertical_min(motion.acc_v_min, scale)
    return motion


def run_kernel(
    block: RockingBlock | None, motion: BaseMotion, run: RunOptions, **model
) -> Response:
    """Integrate checked inputs with the compiled kernel and build their :class:`Response`.

    Parameters
    ----------
    block : RockingBlock or None
        The tower; None for the sliding block alone.
    motion : BaseMotion
        The checked records [m/s^2] and step [s] (:func:`check_base_motion`,
        :func:`checked_motion`).
    run : RunOptions
        The initial state and the integration controls.
    **model
        The other :func:`rockscreen.solver.kernel.make_par` keywords (``linearized``, ``can_slide``,
        ``mass_ratio``, ``mu_s``, ``mu_k``).

    Returns
    -------
    Response
        The outcome.
    """
    par = make_par(block, run, **model)
    raw = simulate(
        motion.acc,
        motion.acc_v,
        motion.dt,
        par,
        float(run.theta0),
        float(run.theta_dot0),
        bool(run.history),
    )
    return build_response(raw, block, history=run.history, max_free_time=run.max_free_time)


@fill_doc(TOWER_DOCS)
def solve_rocking(
    block: RockingBlock, acc, dt: float, *, linearized: bool = False, **options
) -> Response:
    """Integrate the rocking of a rigid block on a base moving with ``acc``.

    Parameters
    ----------
    block : RockingBlock
        The block (alpha, p, eta, R, I_O/m).
    %(motion)s
    linearized : bool
        Use the small-angle equations (uplift at alpha*g); only for comparison with
        classic closed forms.
    %(options)s

    Returns
    -------
    Response
        The outcome; ``slip_max`` and ``slip_residual`` are 0 (the base does not slide).
    """
    run = RunOptions.from_keywords("solve_rocking", options)
    motion = check_base_motion(block, acc, dt, run.acc_v, run.scale)
    return run_kernel(block, motion, run, linearized=bool(linearized), can_slide=False)
