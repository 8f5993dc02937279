"""Lognormal fragility fitted by maximum likelihood on right-censored collapse intensities.

:func:`fit_censored_lognormal` fits the lognormal fragility of
:mod:`rockscreen.pipeline.risk.fragility`, ``P(C | a) = Phi(ln(a / theta) / beta)``, to
the collapse intensities of single records (incremental dynamic analysis,
:mod:`rockscreen.pipeline.risk.ida`; Baker 2015 §"IDA"), some right-censored (the record
never overturned the tower up to the intensity given). With ``x = ln a``,
``z = (x - ln theta) / beta``, the log-likelihood is

    ln L = sum_observed [-ln(beta a) - ln(2 pi)/2 - z^2/2] + sum_censored ln(1 - Phi(z))

(the lognormal density for an overturning record, the survival for a censored one).
It is maximised in ``(ln theta, s = ln beta)`` (beta stays positive) by a trust-region
Newton method with the analytic gradient and Hessian, from the mean and standard
deviation of the observed logs. Standard errors come from the observed information (the
inverse Hessian of ``-ln L``; ``se_beta = beta se_s``, delta method). There is **no beta
floor**: observed intensities nearly equal give the small beta they imply, with its SE.
What the data cannot give is not invented:

- every record censored: no fit, ``median_g`` = the smallest censoring intensity as a
  **lower bound**;
- one overturning record: no dispersion; the median is a bound read from the counts (a
  lower bound at the smallest censoring intensity when fewer than half the records are
  known to have overturned there, else an upper bound at the overturning intensity);
- two or more overturning records all at one intensity: the likelihood grows without
  limit as beta -> 0; ``beta = 0`` is reported as that degenerate limit, SEs NaN, and the
  note says so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize
from scipy.special import log_ndtr

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.fragility import fragility_probability

__all__ = ["CensoredFit", "censored_log_likelihood", "fit_censored_lognormal"]


@dataclass(frozen=True)
class CensoredFit:
    """A lognormal fragility fitted to right-censored collapse intensities, or its bound."""

    #: Median capacity theta [g] (a bound when ``bound`` is set).
    median_g: float
    #: Logarithmic standard deviation [-]; NaN when ``bound`` is set (no dispersion can be
    #: estimated); 0 for the degenerate fit of equal observed intensities.
    beta: float
    #: Standard errors of ``ln(median)`` and ``beta`` from the observed information [-];
    #: NaN for bounds, a degenerate fit or a singular information matrix.
    se_ln_median: float = math.nan
    se_beta: float = math.nan
    #: Log-likelihood at the optimum [-] (densities in 1/g); NaN for bounds.
    loglik: float = math.nan
    #: Records fitted, and how many of them are censored.
    n: int = 0
    n_censored: int = 0
    #: ``""`` (fitted), ``"lower"`` (the median is above ``median_g``) or ``"upper"`` (below).
    bound: str = ""
    #: Why a value is a bound or degenerate; ``""`` for a regular fit.
    note: str = ""

    @property
    def is_fitted(self) -> bool:
        """Whether median and beta are an estimate (not a bound)."""
        return self.bound == ""

    def probability(self, ag_g: np.ndarray | float) -> np.ndarray | float:
        """Return ``P(overturning | a)`` [-]; NaN for a bound or a degenerate beta."""
        if not (self.is_fitted and self.beta > 0):
            return math.nan if np.ndim(ag_g) == 0 else np.full(np.shape(ag_g), math.nan)
        return fragility_probability(ag_g, self.median_g, self.beta)


_LN_SQRT_2PI = 0.5 * math.log(2.0 * math.pi)


def _check_censored(intensities, censored) -> tuple[np.ndarray, np.ndarray]:
    a = np.asarray(intensities, dtype=float)
    c = np.asarray(censored)
    if not (a.ndim == 1 and c.shape == a.shape and a.size >= 1):
        raise RiskError(
            f"censored fit: intensities and censored must be 1-D of one length >= 1; got "
            f"shapes {a.shape} and {c.shape}"
        )
    if c.dtype != bool and not np.all((c == 0) | (c == 1)):
        raise RiskError(f"censored fit: censored must be booleans; got {c.tolist()}")
    if not np.all(np.isfinite(a) & (a > 0)):
        raise RiskError(
            f"censored fit: every intensity must be a finite number > 0 [g]; got {a.tolist()}"
        )
    return a, c.astype(bool)


def _censored_terms(ln_m: float, s: float, x: np.ndarray, cens: np.ndarray):
    """Return -ln L, its gradient and Hessian in ``(ln theta, s = ln beta)``."""
    inv = math.exp(-s)
    z = (x - ln_m) * inv
    zo, zc = z[~cens], z[cens]
    # Observed: l = -s - x - ln(2 pi)/2 - z^2/2.
    loglik = float(np.sum(-s - x[~cens] - _LN_SQRT_2PI - 0.5 * zo**2))
    g_m = float(np.sum(zo)) * inv
    g_s = float(np.sum(zo**2 - 1.0))
    h_mm = -len(zo) * inv * inv
    h_ms = -2.0 * float(np.sum(zo)) * inv
    h_ss = -2.0 * float(np.sum(zo**2))
    if zc.size:
        # Censored: l = ln Phi(-z); dl/dz = -h, h = phi(z) / Phi(-z), h' = h (h - z).
        tail = log_ndtr(-zc)
        h = np.exp(-0.5 * zc**2 - _LN_SQRT_2PI - tail)
        dh = h * (h - zc)
        loglik += float(np.sum(tail))
        g_m += float(np.sum(h)) * inv
        g_s += float(np.sum(h * zc))
        h_mm += -float(np.sum(dh)) * inv * inv
        h_ms += -float(np.sum(zc * dh + h)) * inv
        h_ss += -float(np.sum(zc * (zc * dh + h)))
    gradient = -np.array([g_m, g_s])
    hessian = -np.array([[h_mm, h_ms], [h_ms, h_ss]])
    return -loglik, gradient, hessian


def censored_log_likelihood(intensities, censored, median_g: float, beta: float) -> float:
    """Return the log-likelihood of right-censored collapse intensities [-].

    Parameters
    ----------
    intensities : array_like
        Collapse intensity of each record [g], > 0; for a censored record the intensity up
        to which it did not overturn the tower.
    censored : array_like of bool
        Whether each record is right-censored.
    median_g : float
        Fragility median [g].
    beta : float
        Fragility dispersion [-], > 0.
    """
    a, c = _check_censored(intensities, censored)
    return -_censored_terms(math.log(median_g), math.log(beta), np.log(a), c)[0]


def _count_bound(a: np.ndarray, c: np.ndarray) -> tuple[float, str, str]:
    """Return (median bound [g], bound, note) for fewer than two overturning records."""
    n, observed = len(a), a[~c]
    if c.any():
        lowest = float(a[c].min())
        known = int(np.sum(observed <= lowest))
        if known < 0.5 * n:
            what = "no record overturned" if not observed.size else "one record overturned"
            return (
                lowest,
                "lower",
                f"{what} the tower; {n - known} of {n} records stand at {lowest:.4g} g, the "
                "smallest censoring intensity: the median is above it (lower bound); beta "
                "undetermined",
            )
    value = float(observed.min())
    return (
        value,
        "upper",
        f"one record overturned the tower, at {value:.4g} g, and at least half of the {n} "
        "records have overturned there: the median is below it (upper bound); beta "
        "undetermined",
    )


def fit_censored_lognormal(intensities, censored) -> CensoredFit:
    """Fit a lognormal fragility to right-censored collapse intensities by maximum likelihood.

    Parameters
    ----------
    intensities : array_like
        Collapse intensity of each record [g], > 0; for a censored record, the intensity up
        to which it did not overturn the tower (the censoring intensity).
    censored : array_like of bool
        Whether each record is right-censored (never overturned up to its intensity).

    Returns
    -------
    CensoredFit
        Median, dispersion, their standard errors and the log-likelihood; a bound with a
        note when the data cannot give a dispersion (module docstring).

    Raises
    ------
    RiskError
        For arrays of different shapes, empty ones, or intensities not finite and > 0.
    """
    a, c = _check_censored(intensities, censored)
    n, n_cens = len(a), int(c.sum())
    if n - n_cens < 2:
        median, bound, note = _count_bound(a, c)
        return CensoredFit(median, math.nan, n=n, n_censored=n_cens, bound=bound, note=note)
    x = np.log(a)
    observed = x[~c]
    ln_m0, spread = float(observed.mean()), float(observed.std())
    if spread <= 1e-12 * max(1.0, abs(ln_m0)):
        return CensoredFit(
            float(np.exp(ln_m0)),
            0.0,
            n=n,
            n_censored=n_cens,
            note=(
                f"the {n - n_cens} overturning records share one intensity: the likelihood "
                "grows without limit as beta -> 0 (degenerate fit, beta = 0, no standard errors)"
            ),
        )

    def objective(p):
        return _censored_terms(p[0], p[1], x, c)[0]

    def jacobian(p):
        return _censored_terms(p[0], p[1], x, c)[1]

    def hessian(p):
        return _censored_terms(p[0], p[1], x, c)[2]

    # From the moments of the observed logs; with censored records that start can be far
    # off (observed intensities nearly equal, censorings well above them), so the moments of
    # every log and a unit beta are tried too, and the best optimum is kept.
    starts = [(ln_m0, math.log(spread)), (float(x.mean()), math.log(max(float(x.std()), spread)))]
    starts.append((ln_m0, 0.0))
    result = None
    with np.errstate(over="ignore", under="ignore"):
        for start in starts:
            trial = minimize(
                objective,
                np.array(start),
                jac=jacobian,
                hess=hessian,
                method="trust-exact",
                options={"gtol": 1e-10, "maxiter": 500},
            )
            if np.isfinite(trial.fun) and (result is None or trial.fun < result.fun):
                result = trial
        ln_m, s = float(result.x[0]), float(result.x[1])
        neg, gradient, info = _censored_terms(ln_m, s, x, c)
    notes = []
    if not (result.success or np.max(np.abs(gradient)) < 1e-6):
        notes.append(f"the optimiser did not converge ({result.message})")
    se_m = se_b = math.nan
    try:
        cov = np.linalg.inv(info)
        if np.all(np.diag(cov) > 0) and np.all(np.isfinite(cov)):
            se_m = float(math.sqrt(cov[0, 0]))
            se_b = float(math.exp(s) * math.sqrt(cov[1, 1]))
    except np.linalg.LinAlgError:
        pass
    if not math.isfinite(se_m):
        notes.append("the information matrix is singular: no standard errors")
    if ln_m > float(x.max()):
        notes.append("median extrapolated above every intensity of the data")
    return CensoredFit(
        math.exp(ln_m),
        math.exp(s),
        se_ln_median=se_m,
        se_beta=se_b,
        loglik=-neg,
        n=n,
        n_censored=n_cens,
        note="; ".join(notes),
    )
