"""Coulomb sliding block (Newmark 1965) and the rock-or-slide friction threshold."""

from __future__ import annotations

import math

import numpy as np

from rockscreen.solver.errors import ParameterError
from rockscreen.solver.response import Response
from rockscreen.solver.rocking import MAX_FREE_TIME, RunOptions, checked_motion, run_kernel
from rockscreen.solver.validation import check_alpha, check_friction, check_vertical_min


def solve_sliding(
    acc,
    dt: float,
    *,
    mu_s: float,
    mu_k: float,
    acc_v=None,
    history: bool = True,
    max_free_time: float = MAX_FREE_TIME,
) -> Response:
    """Integrate a rigid block sliding with Coulomb friction on a base moving with ``acc``.

    While sliding ``u'' = -acc - mu_k sgn(u') (g + acc_v)``; the block sticks when
    ``u'`` reaches zero and ``|acc| <= mu_s (g + acc_v)`` (Newmark 1965; seed eq. 17-18).

    Parameters
    ----------
    acc : array_like, shape (n,)
        Horizontal base acceleration [m/s^2] at ``t_k = k*dt``, linear between samples,
        zero after the last sample.
    dt : float
        Sampling step [s], > 0.
    mu_s, mu_k : float
        Static and kinetic friction coefficients [-], ``0 <= mu_k <= mu_s``.
    acc_v : array_like, shape (n,), optional
        Vertical base acceleration [m/s^2], positive up (changes the normal force).
    history : bool
        Return the histories (``u``, ``u_dot``, ``regime``).
    max_free_time : float
        Longest motion integrated after the input ends [s].

    Returns
    -------
    Response
        ``slip_max``, ``slip_residual`` [m] and ``slipped``; the rocking fields are NaN
        or zero.
    """
    motion = checked_motion(acc, dt, acc_v)
    check_vertical_min(motion.acc_v_min)
    check_friction(mu_s, mu_k)
    run = RunOptions(history=history, max_free_time=max_free_time)
    return run_kernel(None, motion, run, mu_s=mu_s, mu_k=mu_k, can_slide=True)


def critical_friction_for_rocking(accel_ratio, alpha):
    """Friction coefficient a rectangular block needs to rock without sliding at uplift.

    Shenton (1996); Zhang & Makris (2001), eq. 7::

        mu_cr(A) = [A - 3/4 sin(a) cos(a) (A/tan(a) - 1)] / [1 + 3/4 sin^2(a) (A/tan(a) - 1)]

    Parameters
    ----------
    accel_ratio : float or array_like
        Ground acceleration at uplift divided by g, A [-], ``A >= tan(alpha)``.
    alpha : float
        Slenderness [rad], 0 < alpha < pi/2.

    Returns
    -------
    float or ndarray
        mu_cr [-]; ``mu_cr(tan(alpha)) = tan(alpha)``.
    """
    check_alpha(alpha)
    a = np.asarray(accel_ratio, dtype=np.float64)
    tan_a = math.tan(alpha)
    if not np.all(np.isfinite(a)) or np.any(a < tan_a * (1.0 - 1e-12)):
        raise ParameterError(
            f"accel_ratio={accel_ratio!r} must be finite and >= tan(alpha)={tan_a!r} "
            "(the block uplifts only above that acceleration)"
        )
    excess = a / tan_a - 1.0
    sa, ca = math.sin(alpha), math.cos(alpha)
    mu = (a - 0.75 * sa * ca * excess) / (1.0 + 0.75 * sa * sa * excess)
    return float(mu) if mu.ndim == 0 else mu
