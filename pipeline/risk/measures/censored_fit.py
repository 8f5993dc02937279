"""Lognormal fragility fitted by maximum likelihood on right-censored collapse intensities.

:func:`fit_censored_lognormal` fits the lognormal fragility of
:mod:`rockscreen.pipeline.risk.measures.fragility`, ``P(C | a) = Phi(ln(a / theta) / beta)``, to
the collapse intensities of single records (incremental dynamic analysis,
:mod:`rockscreen.pipeline.risk.assess.ida`; Baker 2015 §"IDA"), some right-censored (the record
never overturned the tower up to the intensity given). With ``x = ln a``,
``z = (x - ln theta) / beta``, the log-likelihood is

    ln L = sum_observed [-ln(beta a) - ln(2 pi)/2 - z^2/2] + sum_censored ln(1 - Phi(z))

(the lognormal density for an overturning record, the survival for a censored one).
It is maximised by Newton's method in Olsen's parameters ``g = 1/beta``,
``d = ln(theta)/beta``, in which the log-likelihood is globally concave (``z = g x - d``;
the observed terms ``ln g - z^2/2`` and the censored ``ln Phi(-z)`` are concave: the Tobit
likelihood, Olsen 1978, Econometrica 46(5), 1211-1215), so the maximum is unique and
Newton's steps with a backtracking line search reach it from the moments of the observed
logs (:func:`censored_mle`, which fits many weighted samples at once, e.g. the bootstrap's
resamples; without censoring the maximum is the closed form, mean and standard deviation
of the logs). ``method="trust-exact"`` is the reference: a trust-region Newton method in
``(ln theta, s = ln beta)`` (scipy) from three starts, keeping the best optimum; both reach
the same optimum (to about 1e-8 relative). Standard errors come from the observed
information (the inverse Hessian of ``-ln L``; ``se_beta = beta se_s``, delta method).
There is **no beta floor**: observed intensities nearly equal give the small beta they
imply, with its SE. What the data cannot give is not invented:

- every record censored: no fit, ``median_g`` = the smallest censoring intensity as a
  **lower bound**;
- one overturning record: when a record is censored above its intensity, the likelihood
  still has one interior maximum (beta -> 0 would put zero survival at that censoring,
  beta -> infinity zero density at the observed one; concave in Olsen's parameters), so
  the fit is made, its wide standard errors shown and the note saying that it rests on one
  overturning record; otherwise (every censoring below it) no dispersion can be had and
  the median is a bound read from the counts (a lower bound at the smallest censoring
  intensity when fewer than half the records are known to have overturned there, else an
  upper bound at the overturning intensity);
- two or more overturning records all at one intensity: the likelihood grows without
  limit as beta -> 0; ``beta = 0`` is reported as that degenerate limit, SEs NaN, and the
  note says so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import minimize
from scipy.special import log_ndtr

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.measures.fragility import fragility_probability
from rockscreen.pipeline.verdict.messages import Message, message, render_all

__all__ = [
    "FIT_METHODS",
    "OVERTURNED",
    "REACHED_SLV",
    "CensoredFit",
    "censored_log_likelihood",
    "censored_mle",
    "fit_censored_lognormal",
    "with_event",
]

#: What the records did, in a fit's messages (``{event}``): the fit of the collapse, and
#: of the SLV level (:func:`with_event`).
OVERTURNED = message("fit.event_overturned")
REACHED_SLV = message("fit.event_slv")

#: Optimisers of :func:`fit_censored_lognormal`: Newton in the concave parameters (default)
#: and scipy's trust-region method (the reference).
FIT_METHODS = ("newton", "trust-exact")
#: Newton iterations of :func:`censored_mle` before a sample counts as not converged.
MAX_NEWTON_ITERATIONS = 100
#: Relative step at which :func:`censored_mle` stops [-].
NEWTON_STEP_TOLERANCE = 1e-13


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
    #: Why a value is a bound or degenerate (:mod:`rockscreen.pipeline.verdict.catalogue.fits`,
    #: the records' ``{event}`` is :data:`OVERTURNED`); empty for a regular fit.
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


def _count_bound(a: np.ndarray, c: np.ndarray) -> tuple[float, str, tuple[Message, ...]]:
    """Return (median bound [g], bound, messages) for fewer than two overturning records."""
    n, observed = len(a), a[~c]
    undetermined = message("fit.beta_undetermined")
    if c.any():
        lowest = float(a[c].min())
        known = int(np.sum(observed <= lowest))
        if known < 0.5 * n:
            what = "fit.none" if not observed.size else "fit.one"
            return (
                lowest,
                "lower",
                (
                    message(what, event=OVERTURNED),
                    message("fit.censored_all", k=n - known, n=n, ag=lowest),
                    undetermined,
                ),
            )
    value = float(observed.min())
    return (
        value,
        "upper",
        (message("fit.one_upper", event=OVERTURNED, ag=value, n=n), undetermined),
    )


def with_event(messages: tuple[Message, ...], event: Message) -> tuple[Message, ...]:
    """Return a fit's messages with what the records did (``{event}``) replaced by ``event``.

    A fit of the SLV level (records that reached it, not overturned) says so
    (:data:`REACHED_SLV`).
    """
    return tuple(
        Message(m.code, tuple(sorted({**m.kwargs, "event": event}.items())))
        if "event" in m.kwargs
        else m
        for m in messages
    )


def _olsen_terms(d, g, x, obs, weights):
    """Return ln L, gradient and Hessian in ``(d, g)`` of each weighted sample (rows)."""
    z = g[:, None] * x[None, :] - d[:, None]
    wo, wc = weights * obs, weights * ~obs
    with np.errstate(over="ignore", under="ignore", divide="ignore", invalid="ignore"):
        tail = log_ndtr(-z)
        h = np.exp(-0.5 * z * z - _LN_SQRT_2PI - tail)
        k = h * (h - z)
        loglik = (wo * (-0.5 * z * z - x - _LN_SQRT_2PI)).sum(1) + (wc * tail).sum(1)
        loglik += wo.sum(1) * np.log(g)
    grad_g = wo.sum(1) / g - (wo * z * x).sum(1) - (wc * h * x).sum(1)
    grad_d = (wo * z).sum(1) + (wc * h).sum(1)
    h_gg = -wo.sum(1) / (g * g) - (wo * x * x).sum(1) - (wc * k * x * x).sum(1)
    h_gd = (wo * x).sum(1) + (wc * k * x).sum(1)
    h_dd = -wo.sum(1) - (wc * k).sum(1)
    return loglik, (grad_d, grad_g), (h_dd, h_gd, h_gg)


def censored_mle(x, censored, weights, start) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Maximise the censored normal likelihood of many weighted samples of one data set.

    Newton's method in Olsen's parameters ``d = mu/sigma``, ``g = 1/sigma`` (module
    docstring: the log-likelihood is concave there), the step halved until ``ln L`` does
    not decrease and ``g`` stays positive; a sample stops when its relative step is below
    :data:`NEWTON_STEP_TOLERANCE`.

    Parameters
    ----------
    x : numpy.ndarray
        Logs of the intensities, shape (n,) [-].
    censored : numpy.ndarray of bool
        Whether each is right-censored, shape (n,).
    weights : numpy.ndarray
        How many times each intensity enters each sample, shape (r, n) (ones: the data;
        counts: bootstrap resamples). Each sample needs two observed entries of different
        value (else its likelihood has no maximum).
    start : numpy.ndarray
        ``(mu, ln sigma)`` of each sample to start from, shape (r, 2).

    Returns
    -------
    mu, ln_sigma : numpy.ndarray
        The maximum of each sample, shape (r,) (``mu = ln theta``, ``ln sigma = ln beta``).
    converged : numpy.ndarray of bool
        Whether each sample's Newton iteration converged (else its values are the last
        iterate).
    """
    x = np.asarray(x, dtype=float)
    obs = ~np.asarray(censored, dtype=bool)
    weights = np.asarray(weights, dtype=float)
    g = np.exp(-np.asarray(start[:, 1], dtype=float))
    d = np.asarray(start[:, 0], dtype=float) * g
    done = np.zeros(len(d), dtype=bool)
    for _ in range(MAX_NEWTON_ITERATIONS):
        active = ~done
        if not active.any():
            break
        w, da, ga = weights[active], d[active], g[active]
        loglik, (gd, gg), (hdd, hgd, hgg) = _olsen_terms(da, ga, x, obs, w)
        det = hdd * hgg - hgd * hgd
        with np.errstate(divide="ignore", invalid="ignore"):
            step_d = -(hgg * gd - hgd * gg) / det
            step_g = -(hdd * gg - hgd * gd) / det
        bad = ~(np.isfinite(step_d) & np.isfinite(step_g) & (det > 0) & (hdd < 0))
        step_d[bad], step_g[bad] = gd[bad], gg[bad]  # not concave here: gradient ascent
        t = np.ones(len(da))
        accepted = np.zeros(len(da), dtype=bool)
        for _ in range(60):
            trial_g = ga + t * step_g
            trial_d = da + t * step_d
            positive = trial_g > 0
            trial_ll = np.full(len(da), -np.inf)
            if positive.any():
                trial_ll[positive] = _olsen_terms(
                    trial_d[positive], trial_g[positive], x, obs, w[positive]
                )[0]
            ok = ~accepted & positive & (trial_ll >= loglik - 1e-12 * (1.0 + np.abs(loglik)))
            accepted |= ok
            if accepted.all():
                break
            t = np.where(accepted, t, 0.5 * t)
        t = np.where(accepted, t, 0.0)
        new_d, new_g = da + t * step_d, ga + t * step_g
        size = np.maximum(np.abs(new_d - da) / (1.0 + np.abs(da)), np.abs(new_g - ga) / ga)
        d[active], g[active] = new_d, new_g
        done[np.flatnonzero(active)[size <= NEWTON_STEP_TOLERANCE]] = True
    return d / g, -np.log(g), done


def _newton_fit(x: np.ndarray, c: np.ndarray, ln_m0: float, spread: float):
    """Return ``(ln theta, ln beta)`` by :func:`censored_mle`, or None if it did not converge."""
    if not c.any():  # no censoring: the normal MLE in closed form (mean, population std)
        return ln_m0, math.log(spread)
    mu, ln_sigma, converged = censored_mle(
        x, c, np.ones((1, len(x))), np.array([[ln_m0, math.log(spread)]])
    )
    if not (converged[0] and math.isfinite(mu[0]) and math.isfinite(ln_sigma[0])):
        return None
    return float(mu[0]), float(ln_sigma[0])


def fit_censored_lognormal(intensities, censored, *, method: str = "newton") -> CensoredFit:
    """Fit a lognormal fragility to right-censored collapse intensities by maximum likelihood.

    Parameters
    ----------
    intensities : array_like
        Collapse intensity of each record [g], > 0; for a censored record, the intensity up
        to which it did not overturn the tower (the censoring intensity).
    censored : array_like of bool
        Whether each record is right-censored (never overturned up to its intensity).
    method : {'newton', 'trust-exact'}
        The optimiser (:data:`FIT_METHODS`, module docstring): Newton in the concave
        parameters (closed form without censoring); ``"trust-exact"`` is the reference
        (scipy), also used when Newton does not converge.

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
    if method not in FIT_METHODS:
        raise RiskError(f"censored fit: method {method!r} is not one of {FIT_METHODS}")
    a, c = _check_censored(intensities, censored)
    n, n_cens = len(a), int(c.sum())
    if n - n_cens == 1 and float(a[c].max(initial=0.0)) > float(a[~c][0]):
        single = _single_observation_fit(a, c)
        if single is not None:
            return single
    if n - n_cens < 2:
        median, bound, notes = _count_bound(a, c)
        return CensoredFit(median, math.nan, n=n, n_censored=n_cens, bound=bound, messages=notes)
    x = np.log(a)
    observed = x[~c]
    ln_m0, spread = float(observed.mean()), float(observed.std())
    if spread <= 1e-12 * max(1.0, abs(ln_m0)):
        return CensoredFit(
            float(np.exp(ln_m0)),
            0.0,
            n=n,
            n_censored=n_cens,
            messages=(message("fit.degenerate", k=n - n_cens),),
        )

    fast = _newton_fit(x, c, ln_m0, spread) if method == "newton" else None
    if fast is not None:
        ln_m, s = fast
        with np.errstate(over="ignore", under="ignore"):
            neg, _, info = _censored_terms(ln_m, s, x, c)
        return _fitted(ln_m, s, neg, info, float(x.max()), n, n_cens, [])

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
        notes.append(message("fit.not_converged", reason=str(result.message)))
    return _fitted(ln_m, s, neg, info, float(x.max()), n, n_cens, notes)


def _single_observation_fit(a: np.ndarray, c: np.ndarray) -> CensoredFit | None:
    """Fit one overturning record with censorings above it (module docstring), or None.

    None when Newton does not converge or the information matrix gives no standard errors
    (the caller then reads a bound from the counts).
    """
    x = np.log(a)
    n, n_cens = len(a), int(c.sum())
    start = float(x[~c][0]), math.log(max(float(x.std()), 0.1))
    fit = _newton_fit(x, c, *start[:1], math.exp(start[1]))
    if fit is None:
        return None
    ln_m, s = fit
    with np.errstate(over="ignore", under="ignore"):
        neg, _, info = _censored_terms(ln_m, s, x, c)
    note = message("fit.single", n=n, event=OVERTURNED, k=n_cens)
    out = _fitted(ln_m, s, neg, info, float(x.max()), n, n_cens, [note])
    if not (math.isfinite(out.se_ln_median) and math.isfinite(out.se_beta)):
        return None
    return out


def _fitted(ln_m, s, neg, info, x_max, n, n_cens, notes) -> CensoredFit:
    """Return the regular fit at the optimum ``(ln_m, s)`` with SEs from ``info``."""
    se_m = se_b = math.nan
    try:
        cov = np.linalg.inv(info)
        if np.all(np.diag(cov) > 0) and np.all(np.isfinite(cov)):
            se_m = float(math.sqrt(cov[0, 0]))
            se_b = float(math.exp(s) * math.sqrt(cov[1, 1]))
    except np.linalg.LinAlgError:
        pass
    if not math.isfinite(se_m):
        notes.append(message("fit.singular"))
    if ln_m > x_max:
        notes.append(message("fit.median_extrapolated"))
    return CensoredFit(
        math.exp(ln_m),
        math.exp(s),
        se_ln_median=se_m,
        se_beta=se_b,
        loglik=-neg,
        n=n,
        n_censored=n_cens,
        messages=tuple(notes),
    )
