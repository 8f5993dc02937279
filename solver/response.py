"""The result object returned by every solver."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from rockscreen.solver.codes import Status


@dataclass(frozen=True)
class Outcome:
    """The outcome fields every solver reports: :class:`Response` and the oracle's result.

    :class:`solver.reference.ReferenceResult` extends it too, so that the compiled solvers
    and their independent oracle are compared field by field.
    """

    #: ``"no_motion"`` (never uplifted nor slipped), ``"came_to_rest"`` (at rest, or in free motion
    #: below the energy barrier with eta < 1 when the free-motion bound is reached, so rest is
    #: certain), ``"overturned"`` or ``"moving_at_end"`` (outcome undecided after the free-motion
    #: bound: eta = 1, or a building still sliding).
    status: str
    #: Whether the tower overturned, ever lifted off, and whether the base ever slid.
    overturned: bool
    uplifted: bool
    slipped: bool
    #: Largest |theta| [rad] (up to the overturning decision).
    theta_max: float
    #: ``theta_max / alpha`` [-] (NaN for the sliding block).
    theta_max_over_alpha: float
    #: Number of impacts.
    n_impacts: int
    #: Impact times [s].
    impact_times: np.ndarray
    #: Time at which overturning became certain [s]: |theta| = pi/2 while the base moves, or the
    #: energy-barrier verdict in free motion; NaN if it did not overturn.
    t_overturn: float
    #: Largest |u| and final u of the base slip relative to the ground [m].
    slip_max: float
    slip_residual: float


@dataclass(frozen=True)
class Response(Outcome):
    """Outcome of one simulation."""

    #: Largest |f_x / f_z| at the tower's base [-] (NaN without a tower).
    friction_demand_max: float
    #: End of the integration [s].
    t_end: float
    #: Block slenderness [rad], frequency parameter [rad/s], restitution [-] (NaN for the sliding
    #: block).
    alpha: float
    p: float
    eta: float
    #: A sentence describing the outcome.
    message: str
    #: Histories on the input grid ``k*dt`` extended to ``t_end`` [s, rad, rad/s, m, m/s, -];
    #: ``regime`` is int8 (0 rest, 1 tower rocking, 2 building sliding, 3 both). None when the
    #: solver ran with ``history=False``.
    t: np.ndarray | None = field(default=None, repr=False)
    theta: np.ndarray | None = field(default=None, repr=False)
    theta_dot: np.ndarray | None = field(default=None, repr=False)
    u: np.ndarray | None = field(default=None, repr=False)
    u_dot: np.ndarray | None = field(default=None, repr=False)
    regime: np.ndarray | None = field(default=None, repr=False)


def build_response(raw, block, *, history, max_free_time):
    """Turn the :class:`solver.kernel.Result` of :func:`solver.kernel.simulate` into a Response.

    Parameters
    ----------
    raw : rockscreen.solver.kernel.Result
        The kernel's named result.
    block : RockingBlock or None
        The tower (its slenderness, frequency parameter and restitution are quoted); None
        for the sliding block, whose rocking fields are then NaN.
    history : bool
        Whether the kernel recorded the histories (else they are None).
    max_free_time : float
        The free-motion bound [s] the kernel ran with (quoted in the message).

    Returns
    -------
    Response
        The outcome.
    """
    tower = block is not None
    alpha, p, eta = (block.alpha, block.p, block.eta) if tower else (math.nan,) * 3
    uplifted, slipped = bool(raw.uplifted), bool(raw.slipped)
    if raw.status == Status.OVERTURNED:
        status = "overturned"
        message = f"overturned; outcome certain at t = {raw.t_overturn:.4f} s"
    elif raw.status == Status.SAFE:
        status = "came_to_rest"
        message = (
            f"rocking below the overturning energy barrier at t = {raw.t_end:.4f} s, "
            f"after the input ended (free motion followed up to {max_free_time} s): it "
            "cannot overturn and comes to rest "
            "(impacts only dissipate); theta_max includes the largest swing still to come"
        )
    elif raw.status == Status.REST:
        if uplifted or slipped:
            status = "came_to_rest"
            message = f"moved and came to rest by t = {raw.t_end:.4f} s"
        else:
            status = "no_motion"
            message = "no uplift and no slip: the block never moved"
    else:
        status = "moving_at_end"
        message = (
            f"still moving at t = {raw.t_end:.4f} s, {max_free_time} s after the input ended; "
            "the outcome is undecided"
        )
    arrays = {}
    if history:
        names = ("t", "theta", "theta_dot", "u", "u_dot", "regime")
        arrays = {name: getattr(raw, name) for name in names}
    return Response(
        status=status,
        overturned=status == "overturned",
        uplifted=uplifted,
        slipped=slipped,
        theta_max=float(raw.theta_max) if tower else math.nan,
        theta_max_over_alpha=float(raw.theta_max) / alpha if tower else math.nan,
        n_impacts=int(raw.impact_times.size),
        impact_times=raw.impact_times,
        t_overturn=float(raw.t_overturn),
        slip_max=float(raw.slip_max),
        slip_residual=float(raw.u_end),
        friction_demand_max=float(raw.demand_max) if tower else math.nan,
        t_end=float(raw.t_end),
        alpha=float(alpha),
        p=float(p),
        eta=float(eta),
        message=message,
        **arrays,
    )
