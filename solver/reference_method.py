"""The ``reference`` solver method: the ``solve_ivp`` oracle behind the compiled solvers' API.

:mod:`rockscreen.solver.reference` integrates the same equations independently, with its
own signatures (``p``, ``alpha``, ``eta`` instead of a block) and result
(:class:`~rockscreen.solver.reference.ReferenceResult`). The three functions here take the
arguments of :func:`rockscreen.solver.solve_rocking`, :func:`rockscreen.solver.solve_double_block`
and :func:`rockscreen.solver.solve_sliding` and return their
:class:`~rockscreen.solver.response.Response`, so the engine can run a whole case on the
oracle (:mod:`rockscreen.solver.methods`, method ``reference``). It is slow: for checks.

What the oracle does not compute is said, never filled in: ``friction_demand_max`` is NaN
(the oracle does not track the friction demand), and the message names the oracle. The
oracle's histories (at interval ends and events) are resampled to the input grid ``k*dt``
extended to ``t_end``, the compiled solvers' layout. ``stop_when_certain`` and
``friction_demand`` only skip work in the compiled solvers (same verdict and ``theta_max``),
so the oracle, which always runs in full, accepts and ignores them; the compiled solvers'
``rest_tolerance`` and ``max_substep`` have no counterpart and are refused unless default.
"""

from __future__ import annotations

import math

import numpy as np

from rockscreen.solver.reference import (
    T_FREE,
    reference_double_block,
    reference_rocking,
    reference_sliding,
)
from rockscreen.solver.response import Response
from rockscreen.solver.rocking import MAX_FREE_TIME, REST_TOLERANCE

__all__ = ["rocking", "double_block", "sliding"]


def _oracle_options(
    solver: str,
    *,
    acc_v=None,
    scale: float = 1.0,
    theta0: float = 0.0,
    theta_dot0: float = 0.0,
    max_free_time: float = MAX_FREE_TIME,
    rest_tolerance: float = REST_TOLERANCE,
    max_substep: float | None = None,
    history: bool = True,
    friction_demand: bool = True,
    stop_when_certain: bool = False,
) -> tuple[dict, float, bool, float]:
    """Return the oracle's keywords, the scale, ``history`` and ``max_free_time`` [s]."""
    del friction_demand, stop_when_certain  # work-savers of the compiled solvers only
    if rest_tolerance != REST_TOLERANCE or max_substep is not None:
        raise TypeError(
            f"{solver}() of the reference method has no rest_tolerance nor max_substep "
            "(the oracle's own controls are fixed)"
        )
    if not isinstance(scale, (int, float)) or not (scale > 0.0 and math.isfinite(scale)):
        raise ValueError(f"{solver}(): scale={scale!r} must be a finite number > 0")
    scaled_v = None if acc_v is None else np.asarray(acc_v, dtype=float) * scale
    options = {"acc_v": scaled_v, "theta0": theta0, "theta_dot0": theta_dot0,
               "t_free": max_free_time}  # fmt: skip
    return options, float(scale), bool(history), float(max_free_time)


def _on_grid(result, dt: float) -> dict[str, np.ndarray]:
    """Resample the oracle's histories on ``k*dt`` up to ``t_end`` (the compiled layout)."""
    n = int(math.floor(result.t_end / dt + 1e-9)) + 1
    t = np.arange(n) * dt
    out = {"t": t}
    for name in ("theta", "theta_dot", "u", "u_dot"):
        out[name] = np.interp(t, result.t, getattr(result, name))
    index = np.clip(np.searchsorted(result.t, t, side="right") - 1, 0, len(result.t) - 1)
    out["regime"] = np.asarray(result.regime, dtype=np.int8)[index]
    return out


def _response(result, block, dt: float, history: bool, max_free_time: float) -> Response:
    """Turn the oracle's result into the compiled solvers' :class:`Response`."""
    tower = block is not None
    alpha, p, eta = (block.alpha, block.p, block.eta) if tower else (math.nan,) * 3
    message = (
        f"{result.status} (reference solve_ivp integration, free motion followed up to "
        f"{max_free_time} s; friction demand not computed)"
    )
    arrays = _on_grid(result, dt) if history else {}
    return Response(
        status=result.status,
        overturned=bool(result.overturned),
        uplifted=bool(result.uplifted),
        slipped=bool(result.slipped),
        theta_max=float(result.theta_max),
        theta_max_over_alpha=float(result.theta_max_over_alpha),
        n_impacts=int(result.n_impacts),
        impact_times=np.asarray(result.impact_times, dtype=float),
        t_overturn=float(result.t_overturn),
        slip_max=float(result.slip_max),
        slip_residual=float(result.slip_residual),
        friction_demand_max=math.nan,
        t_end=float(result.t_end),
        alpha=alpha,
        p=p,
        eta=eta,
        message=message,
        **arrays,
    )


def rocking(block, acc, dt: float, *, linearized: bool = False, **options) -> Response:
    """Solve the single rocking block with the oracle (``solve_rocking``'s API).

    Parameters
    ----------
    block : rockscreen.solver.RockingBlock
    acc : array_like, shape (n,)
        Horizontal base acceleration [m/s^2] at ``t_k = k*dt``.
    dt : float
        Sampling step [s].
    linearized : bool
        Small-angle equations.
    **options
        :class:`rockscreen.solver.rocking.RunOptions`' keywords (module docstring).

    Returns
    -------
    Response
    """
    kwargs, scale, history, free = _oracle_options("rocking", **options)
    acc = np.asarray(acc, dtype=float) * scale
    result = reference_rocking(
        block.p, block.alpha, block.eta, acc, dt, linearized=linearized, **kwargs
    )
    return _response(result, block, dt, history, free)


def double_block(
    block, acc, dt: float, *, tower_mass: float, building_mass: float, mu_s: float, mu_k: float,
    **options,
) -> Response:  # fmt: skip
    """Solve the tower on the sliding building with the oracle (``solve_double_block``'s API).

    Parameters
    ----------
    block : rockscreen.solver.RockingBlock
    acc : array_like, shape (n,)
        Horizontal ground acceleration [m/s^2] at ``t_k = k*dt``.
    dt : float
        Sampling step [s].
    tower_mass, building_mass : float
        Masses of the tower and of the building [kg].
    mu_s, mu_k : float
        Static and kinetic friction of the building on its foundation [-].
    **options
        :class:`rockscreen.solver.rocking.RunOptions`' keywords (module docstring).

    Returns
    -------
    Response
    """
    kwargs, scale, history, free = _oracle_options("double_block", **options)
    acc = np.asarray(acc, dtype=float) * scale
    result = reference_double_block(
        block.p, block.alpha, block.eta, block.radius, acc, dt,
        tower_mass, building_mass, mu_s, mu_k, **kwargs,
    )  # fmt: skip
    return _response(result, block, dt, history, free)


def sliding(
    acc, dt: float, *, mu_s: float, mu_k: float, acc_v=None, history: bool = True,
    max_free_time: float = MAX_FREE_TIME,
) -> Response:  # fmt: skip
    """Solve the sliding block with the oracle (``solve_sliding``'s API).

    After the record the oracle follows the block until it sticks, up to its own bound
    (:data:`~rockscreen.solver.reference.T_FREE`, quoted in the message);
    ``max_free_time`` is taken for the API and not used.

    Parameters
    ----------
    acc : array_like, shape (n,)
        Horizontal ground acceleration [m/s^2] at ``t_k = k*dt``.
    dt : float
        Sampling step [s].
    mu_s, mu_k : float
        Static and kinetic friction coefficients [-].
    acc_v : array_like, shape (n,), optional
        Vertical ground acceleration [m/s^2], positive up.
    history : bool
        Return the histories on the input grid.
    max_free_time : float
        The compiled solver's free-motion bound [s]; not used.

    Returns
    -------
    Response
    """
    del max_free_time  # the oracle's own bound, T_FREE, applies
    result = reference_sliding(acc, dt, mu_s, mu_k, acc_v)
    return _response(result, None, dt, history, T_FREE)
