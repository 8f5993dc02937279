"""Lognormal fragility fitted by maximum likelihood on multiple-stripe counts.

At stripe ``j`` (intensity ``a_j`` [g], here the site's ag on rock at one return period)
``k_j`` of ``n_j`` records overturn the tower. The fragility is
``P(C | a) = Phi(ln(a / theta) / beta)`` (median ``theta`` [g], dispersion ``beta`` [-]),
and its parameters maximise the binomial likelihood

    L = prod_j C(n_j, k_j) P_j^k_j (1 - P_j)^(n_j - k_j),      P_j = P(C | a_j)

(Baker 2015, Earthquake Spectra 31(1), 579-599, eq. 11; the stripes are those of the
multiple-stripe analysis of Jalayer & Cornell 2009). Fit quality: the log-likelihood, the
binomial deviance against the saturated model (``2 sum k ln(k / nP) + (n-k) ln((n-k) /
n(1-P))``; approximately chi-square with ``stripes - 2`` degrees of freedom when the
counts are large) and the largest Pearson residual ``|k - nP| / sqrt(nP(1-P))``. Standard
errors of ``ln theta`` and ``beta`` come from the observed Fisher information (the
numerical Hessian of ``-ln L`` at the optimum).

Degenerate data are reported, never invented:

- no record overturns at any stripe: ``median_g`` = the largest stripe ``a`` as a **lower
  bound** (``bound = "lower"``), ``beta`` NaN;
- every record overturns at every stripe: ``median_g`` = the smallest stripe ``a`` as an
  **upper bound** (``bound = "upper"``), ``beta`` NaN;
- counts that jump from none to all between two stripes (separable data) have no finite
  MLE of ``beta``; the fit stops at ``beta_min`` (default 0.05) and says so in ``note``.

The dispersion is record-to-record variability only (the records of a stripe); modelling
uncertainty is not included.

The same lognormal fitted to per-record collapse intensities with right-censoring is
:mod:`rockscreen.pipeline.risk.measures.censored_fit`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import minimize
from scipy.special import gammaln, log_ndtr, ndtr

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.verdict.messages import Message, message, render_all

__all__ = [
    "Fragility",
    "fit_fragility",
    "fragility_probability",
    "log_likelihood",
]

#: Bounds of the fitted dispersion beta [-].
BETA_MIN, BETA_MAX = 0.05, 3.0


@dataclass(frozen=True)
class Fragility:
    """A lognormal fragility and the quality of its fit."""

    #: Median capacity theta [g] (a bound when ``bound`` is set).
    median_g: float
    #: Logarithmic standard deviation [-]; NaN when ``bound`` is set.
    beta: float
    #: ``""`` (fitted), ``"lower"`` (never overturned: the median is above ``median_g``) or
    #: ``"upper"`` (always overturned: the median is below ``median_g``).
    bound: str = ""
    #: Log-likelihood at the optimum (binomial coefficients included) [-]; NaN for bounds.
    loglik: float = math.nan
    #: Binomial deviance against the saturated model [-]; NaN for bounds.
    deviance: float = math.nan
    #: Degrees of freedom of the deviance: stripes - 2 (>= 0).
    dof: int = 0
    #: Largest Pearson residual over the stripes [-]; NaN for bounds.
    max_residual: float = math.nan
    #: Standard errors of ``ln(median)`` and ``beta`` from the observed information [-]; NaN when
    #: the information matrix is singular or for bounds.
    se_ln_median: float = math.nan
    se_beta: float = math.nan
    #: Why a value is a bound or at a limit (codes of
    #: :mod:`rockscreen.pipeline.verdict.catalogue.fits`); empty otherwise.
    messages: tuple[Message, ...] = field(default=())

    @property
    def note(self) -> str:
        """Return :attr:`messages` in English, joined by ``"; "`` (``""`` for none)."""
        return render_all(self.messages)

    @property
    def is_fitted(self) -> bool:
        """Whether median and beta are an estimate (not a bound)."""
        return self.bound == ""

    def probability(self, ag_g: np.ndarray | float) -> np.ndarray | float:
        """Return ``P(overturning | ag)`` [-]; NaN for a bound (undefined)."""
        return fragility_probability(ag_g, self.median_g, self.beta)


def fragility_probability(
    ag_g: np.ndarray | float, median_g: float, beta: float
) -> np.ndarray | float:
    """Return the lognormal fragility ``Phi(ln(ag / median) / beta)`` [-].

    Parameters
    ----------
    ag_g : float or numpy.ndarray
        Intensity [g], > 0.
    median_g : float
        Median [g].
    beta : float
        Dispersion [-]; NaN gives NaN.
    """
    a = np.asarray(ag_g, dtype=float)
    with np.errstate(divide="ignore"):
        out = ndtr(np.log(a / median_g) / beta)
    return float(out) if np.ndim(out) == 0 else out


def _check(ag_g, n_records, n_failures) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    a = np.asarray(ag_g, dtype=float)
    n = np.asarray(n_records, dtype=float)
    k = np.asarray(n_failures, dtype=float)
    if not (a.ndim == n.ndim == k.ndim == 1 and len(a) == len(n) == len(k) and len(a) >= 1):
        raise RiskError(
            f"stripes: ag_g, n_records and n_failures must be 1-D of one length >= 1; got "
            f"lengths {a.size}, {n.size}, {k.size}"
        )
    if not np.all(np.isfinite(a) & (a > 0)):
        raise RiskError(f"stripes: every ag_g must be a finite number > 0 [g]; got {a.tolist()}")
    if not np.all((n >= 1) & (n == np.round(n))):
        raise RiskError(f"stripes: n_records must be integers >= 1; got {n.tolist()}")
    if not np.all((k >= 0) & (k <= n) & (k == np.round(k))):
        raise RiskError(
            f"stripes: n_failures must be integers in [0, n_records]; got {k.tolist()} "
            f"for n_records {n.tolist()}"
        )
    return a, n, k


def log_likelihood(
    ag_g: np.ndarray, n_records: np.ndarray, n_failures: np.ndarray, median_g: float, beta: float
) -> float:
    """Return the binomial log-likelihood of stripe counts (Baker 2015, eq. 11) [-].

    Parameters
    ----------
    ag_g : numpy.ndarray
        Stripe intensities [g].
    n_records, n_failures : numpy.ndarray
        Records per stripe and how many of them overturn the tower.
    median_g : float
        Fragility median [g].
    beta : float
        Fragility dispersion [-].
    """
    a, n, k = _check(ag_g, n_records, n_failures)
    return _loglik(math.log(median_g), beta, np.log(a), n, k)


def _loglik(ln_median: float, beta: float, ln_a, n, k) -> float:
    z = (ln_a - ln_median) / beta
    binomial = gammaln(n + 1) - gammaln(k + 1) - gammaln(n - k + 1)
    return float(np.sum(binomial + k * log_ndtr(z) + (n - k) * log_ndtr(-z)))


def _hessian(f, x: np.ndarray, h: float = 1e-4) -> np.ndarray:
    """Central-difference Hessian of ``f`` at ``x``."""
    d = len(x)
    out = np.zeros((d, d))
    for i in range(d):
        for j in range(i, d):
            e_i, e_j = np.eye(d)[i] * h, np.eye(d)[j] * h
            value = (f(x + e_i + e_j) - f(x + e_i - e_j) - f(x - e_i + e_j) + f(x - e_i - e_j)) / (
                4 * h * h
            )
            out[i, j] = out[j, i] = value
    return out


def _quality(ln_m: float, beta: float, ln_a, n, k) -> tuple[float, float]:
    p = np.clip(ndtr((ln_a - ln_m) / beta), 1e-300, 1 - 1e-16)
    expected = n * p
    with np.errstate(divide="ignore", invalid="ignore"):
        term = np.where(k > 0, k * np.log(k / expected), 0.0) + np.where(
            n - k > 0, (n - k) * np.log((n - k) / (n - expected)), 0.0
        )
        residual = np.abs(k - expected) / np.sqrt(expected * (1 - p))
    return float(2 * np.sum(term)), float(np.max(residual))


def fit_fragility(
    ag_g, n_records, n_failures, *, beta_min: float = BETA_MIN, beta_max: float = BETA_MAX
) -> Fragility:
    """Fit a lognormal fragility to multiple-stripe counts by maximum likelihood.

    Parameters
    ----------
    ag_g : array_like
        Stripe intensities [g], > 0.
    n_records : array_like
        Records per stripe, integers >= 1.
    n_failures : array_like
        Records that overturn the tower at each stripe, in [0, n_records].
    beta_min, beta_max : float
        Bounds of the dispersion [-] (module docstring: separable data stop at ``beta_min``).

    Returns
    -------
    Fragility
        Median, dispersion, bound flag, fit quality and standard errors.

    Raises
    ------
    RiskError
        For arrays of different lengths, non-positive intensities or counts out of range.
    """
    a, n, k = _check(ag_g, n_records, n_failures)
    dof = max(len(a) - 2, 0)
    none = k.sum() == 0
    if none or np.all(k == n):
        ag = float(a.max() if none else a.min())
        said = message("stripes.none_overturned" if none else "stripes.all_overturned", ag=ag)
        bound = "lower" if none else "upper"
        notes = (said, message("fit.beta_undetermined"))
        return Fragility(ag, math.nan, bound, dof=dof, messages=notes)
    ln_a = np.log(a)

    def negative(x: np.ndarray) -> float:
        return -_loglik(x[0], x[1], ln_a, n, k)

    fraction = k / n
    start_m = float(np.interp(0.5, *_monotone(fraction, ln_a)))
    best = None
    for start_beta in (0.2, 0.5, 1.0):
        result = minimize(
            negative,
            np.array([start_m, start_beta]),
            method="L-BFGS-B",
            bounds=[(ln_a.min() - 10.0, ln_a.max() + 10.0), (beta_min, beta_max)],
        )
        if best is None or result.fun < best.fun:
            best = result
    ln_m, beta = float(best.x[0]), float(best.x[1])
    deviance, max_residual = _quality(ln_m, beta, ln_a, n, k)
    notes = []
    se_m = se_b = math.nan
    if beta <= beta_min * (1 + 1e-6):
        notes.append(message("stripes.beta_min", beta=beta_min))
    elif beta >= beta_max * (1 - 1e-6):
        notes.append(message("stripes.beta_max", beta=beta_max))
    else:
        try:
            cov = np.linalg.inv(_hessian(negative, np.array([ln_m, beta])))
            if np.all(np.diag(cov) > 0):
                se_m, se_b = (float(math.sqrt(v)) for v in np.diag(cov))
        except np.linalg.LinAlgError:
            pass
    if ln_m > ln_a.max():
        notes.append(message("stripes.median_extrapolated"))
    return Fragility(
        math.exp(ln_m),
        beta,
        "",
        loglik=-float(best.fun),
        deviance=deviance,
        dof=dof,
        max_residual=max_residual,
        se_ln_median=se_m,
        se_beta=se_b,
        messages=tuple(notes),
    )


def _monotone(fraction: np.ndarray, ln_a: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return (fraction, ln a) made increasing for a starting guess of the median."""
    order = np.argsort(ln_a)
    f = np.maximum.accumulate(fraction[order]) + np.arange(len(order)) * 1e-9
    return f, ln_a[order]
