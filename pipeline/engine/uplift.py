"""The uplift pre-check: scale factors below which a block on a record provably rests.

Uplift of a rigid block from rest needs the horizontal base acceleration to exceed
``tan(alpha)`` times the apparent gravity (Housner 1963). Both bounds here are exact
consequences of that condition, so a case below them is motionless without a solve; the
case engine, the safety-factor search and the stripes use them (``docs/campaign.md``).
"""

from __future__ import annotations

import math

import numpy as np

from rockscreen.solver.constants import G
from rockscreen.solver.docstrings import fill_doc

__all__ = ["is_motionless", "sample_uplift_factor", "uplift_free_factor"]

#: Docstring blocks the uplift bounds share (:func:`rockscreen.solver.docstrings.fill_doc`).
_DOCS = {
    "acc_alpha": """
acc : numpy.ndarray
    Horizontal base acceleration [m/s²].
alpha : float
    Slenderness angle of the block [rad].
""",
}


@fill_doc(_DOCS)
def uplift_free_factor(acc: np.ndarray, alpha: float, acc_v: np.ndarray | None = None) -> float:
    """Return the largest scale factor at which a block on ``acc`` provably stays at rest.

    Uplift from rest needs ``|f a_h| > tan(alpha) (g + f a_v)`` at some sample; with
    ``A = max|a_h|`` and ``V = max|a_v|`` it cannot happen while
    ``f < g tan(alpha) / (A + tan(alpha) V)``.

    Parameters
    ----------
    %(acc_alpha)s
    acc_v : numpy.ndarray, optional
        Vertical acceleration [m/s²], positive up.

    Returns
    -------
    float
        The factor [-], ``inf`` for a motionless record.
    """
    tan_alpha = math.tan(alpha)
    peak = float(np.max(np.abs(acc))) if len(acc) else 0.0
    peak_v = float(np.max(np.abs(acc_v))) if acc_v is not None and len(acc_v) else 0.0
    denominator = peak + tan_alpha * peak_v
    return math.inf if denominator == 0.0 else G * tan_alpha / denominator


@fill_doc(_DOCS)
def sample_uplift_factor(acc: np.ndarray, alpha: float, acc_v: np.ndarray | None = None) -> float:
    """Return the scale factor below which no sample of ``acc`` reaches the uplift threshold.

    Uplift from rest at a sample needs ``f |a_h| > tan(alpha) (g + f a_v)``, i.e.
    ``f (|a_h| - tan(alpha) a_v) > g tan(alpha)``; the factor returned is
    ``g tan(alpha) / max(|a_h| - tan(alpha) a_v)`` over the samples. Between samples the
    records are linear, so ``|a_h| - tan(alpha) a_v`` is convex there and largest at a
    sample: below this factor the block never uplifts. It is never below
    :func:`uplift_free_factor` (which bounds the two peaks separately and fixes the scan
    grid); the search uses it only to skip solves whose verdict (safe) is certain.

    Parameters
    ----------
    %(acc_alpha)s
    acc_v : numpy.ndarray, optional
        Vertical acceleration [m/s²], positive up, same length as ``acc``.

    Returns
    -------
    float
        The factor [-], ``inf`` when no sample can ever reach the threshold.
    """
    tan_alpha = math.tan(alpha)
    demand = np.abs(acc)
    if acc_v is not None and len(acc_v):
        demand = demand - tan_alpha * np.asarray(acc_v)
    peak = float(np.max(demand)) if len(demand) else 0.0
    return math.inf if peak <= 0.0 else G * tan_alpha / peak


def is_motionless(acc: np.ndarray, alpha: float, acc_v: np.ndarray | None = None) -> bool:
    """Whether no sample of ``acc`` reaches the uplift threshold (the block stays at rest).

    The small margin (``1e-9``) keeps the kernel's own rounding of the threshold test out.

    Parameters
    ----------
    acc : numpy.ndarray
        Horizontal base acceleration [m/s²].
    alpha : float
        Slenderness angle of the block [rad].
    acc_v : numpy.ndarray, optional
        Vertical acceleration [m/s²], positive up, same length as ``acc``.
    """
    return sample_uplift_factor(acc, alpha, acc_v) * (1.0 - 1e-9) > 1.0
