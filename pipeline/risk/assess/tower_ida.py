"""Collapse and SLV fragilities of one tower from its records' IDA intensities (``assess``).

For one tower, every record of the site's spectrum-compatible set at the tower's
``T_R,SLV`` (each record scaled by its set factor, so that scale 1 is the set's target:
the site's ag on rock at ``T_R,SLV``) is searched for the scale at which the tower first
overturns and first reaches the SLV level ``theta_max/alpha >= 0.4``
(:func:`rockscreen.pipeline.risk.assess.ida.record_collapse_intensities`, both components, every
enabled model). The intensities are expressed in the code's IM, the site's ag on rock:

    collapse_ag_g = collapse_scale * ag(T_R of the set),   slv_ag_g = slv_scale * ag(T_R)

A record's intensity is the smaller of its components' (:func:`record_intensities`),
censored when that smaller one is. Two censored lognormal fits follow
(:func:`rockscreen.pipeline.risk.measures.censored_fit.fit_censored_lognormal`, no beta floor):
**collapse** (overturning) and **SLV**. The limit states read them as follows
(:func:`limit_state_values`):

- ``a_SLV = slv_median / F_C`` (capacity divided by the confidence factor), its return
  period on the site curve, ``I_S = T_R(a_SLV) / T_R,SLV``, ``f_a = a_SLV / ag_SLV``;
- ``lambda_C`` over the site hazard curve from the **collapse** fragility (best estimate,
  no F_C), ``P50 = 1 - exp(-50 lambda_C)``.

:func:`bootstrap_intervals` resamples the records with replacement (seeded) and refits
both levels: 90 % percentile intervals of the collapse median, ``lambda_C`` and ``I_S``.
"""

from __future__ import annotations

import math
import zlib
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from rockscreen.pipeline.risk.assess.ida import (
    IdaOptions,
    motion_pga_g,
    record_collapse_intensities,
)
from rockscreen.pipeline.risk.assess.stripes import suite_motion
from rockscreen.pipeline.risk.measures.censored_fit import (
    CensoredFit,
    censored_mle,
    fit_censored_lognormal,
)
from rockscreen.pipeline.risk.measures.hazard_integral import (
    HazardCurve,
    annual_rate_of_overturning,
)
from rockscreen.stations.tower import Tower

__all__ = [
    "BOOTSTRAP_LEVEL",
    "DEFAULT_BOOTSTRAP_RESAMPLES",
    "IDA_LEVELS",
    "RecordIntensities",
    "bootstrap_intervals",
    "collapse_rate",
    "fit_level",
    "limit_state_values",
    "record_intensities",
    "resample_fits",
    "tower_ida",
    "tower_seed",
]

#: Resamples of the record bootstrap (seeded per tower).
DEFAULT_BOOTSTRAP_RESAMPLES = 200
#: Coverage of the bootstrap percentile intervals [-] (5 % and 95 % percentiles).
BOOTSTRAP_LEVEL = 0.90
#: The two fitted levels: overturning, and the SLV level theta_max/alpha >= 0.4.
IDA_LEVELS = ("collapse", "slv")


def tower_ida(
    tower: Tower,
    record_set: Any,
    return_period_y: float,
    ag_g: float,
    options: IdaOptions,
    blocks: Any = None,
) -> tuple[list[dict[str, Any]], int]:
    """Search the collapse and SLV intensities of a tower under every record of a set.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
    record_set : rockscreen.pipeline.hazard.RecordSet
        The site's record set (records and their scale factors to the set's target).
    return_period_y : float
        The set's return period [y].
    ag_g : float
        The set's target, the site's ag on rock at ``return_period_y`` [g]: scale 1.
    options : IdaOptions
    blocks : rockscreen.pipeline.engine.cases.BlockCache, optional

    Returns
    -------
    rows : list of dict
        One ``/ida`` row per record x component: ``tower_id``, ``return_period_y`` [y],
        ``set_ag_g`` [g], ``record``, ``set_scale_factor`` [1], ``component``, ``models``,
        ``collapse_scale`` [1], ``collapse_ag_g`` [g], ``slv_scale`` [1], ``slv_ag_g`` [g],
        ``censored``, ``slv_censored``, ``censor_reason``, ``n_solves``.
    n_solves : int
        Solver calls made.
    """
    rows: list[dict[str, Any]] = []
    n_solves = 0
    for record, factor in zip(record_set.records, record_set.scale_factors, strict=True):
        motion = suite_motion(record, float(factor))
        pga = motion_pga_g(motion)
        for r in record_collapse_intensities(tower, motion, options, blocks):
            n_solves += r.n_solves
            rows.append(
                {
                    "tower_id": tower.id,
                    "return_period_y": float(return_period_y),
                    "set_ag_g": float(ag_g),
                    "record": r.record,
                    "set_scale_factor": float(factor),
                    "component": r.component,
                    "models": r.models,
                    "collapse_scale": _finite_scale(r.collapse_scale, pga, options),
                    "collapse_ag_g": _finite_scale(r.collapse_scale, pga, options) * ag_g,
                    "slv_scale": _finite_scale(r.slv_scale, pga, options),
                    "slv_ag_g": _finite_scale(r.slv_scale, pga, options) * ag_g,
                    "censored": bool(r.censored),
                    "slv_censored": bool(r.slv_censored),
                    "censor_reason": r.censor_reason,
                    "n_solves": int(r.n_solves),
                }
            )
    return rows, n_solves


def _finite_scale(scale: float, pga_g: float, options: IdaOptions) -> float:
    """Return ``scale``, or the cap's factor for a motionless component (scale ``inf``)."""
    if math.isfinite(scale):
        return float(scale)
    return options.cap_pga_g / pga_g if pga_g > 0 else options.cap_pga_g


@dataclass(frozen=True)
class RecordIntensities:
    """Per-record intensities of one level (components combined)."""

    #: Record names, in first-seen order.
    records: tuple[str, ...]
    #: Intensity of each record [g] (the censoring intensity when censored).
    ag_g: np.ndarray
    #: Whether each record is right-censored.
    censored: np.ndarray


def record_intensities(
    rows: Sequence[dict[str, Any]], level: str = "collapse"
) -> RecordIntensities:
    """Combine the ``/ida`` rows of one tower per record: the smaller component governs.

    A record is censored when its smallest component intensity is (ties: an observed level
    beats a censoring at the same intensity), as in
    :func:`rockscreen.pipeline.risk.assess.ida.record_collapse`.

    Parameters
    ----------
    rows : sequence of dict
        ``/ida`` rows of one tower (:func:`tower_ida`).
    level : {'collapse', 'slv'}

    Returns
    -------
    RecordIntensities
    """
    value_key, flag_key = (
        ("collapse_ag_g", "censored")
        if level == "collapse"
        else (
            "slv_ag_g",
            "slv_censored",
        )
    )
    best: dict[str, tuple[float, bool]] = {}
    for row in rows:
        item = (float(row[value_key]), bool(row[flag_key]))
        name = str(row["record"])
        if name not in best or item < best[name]:
            best[name] = item
    return RecordIntensities(
        tuple(best),
        np.array([v for v, _ in best.values()], dtype=float),
        np.array([c for _, c in best.values()], dtype=bool),
    )


def fit_level(
    rows: Sequence[dict[str, Any]], level: str = "collapse", method: str = "newton"
) -> CensoredFit:
    """Return the censored lognormal fit in ag [g] of one level of a tower's ``/ida`` rows.

    ``method`` is :func:`rockscreen.pipeline.risk.measures.censored_fit.fit_censored_lognormal`'s.
    """
    data = record_intensities(rows, level)
    return fit_censored_lognormal(data.ag_g, data.censored, method=method)


def collapse_rate(curve: HazardCurve, fit: CensoredFit) -> float:
    """Return ``lambda_C`` [1/y] of a fitted collapse fragility over the site curve.

    A degenerate fit (``beta = 0``: every overturning record at one intensity) is the step
    fragility at its median, whose rate is the curve's rate at the median. NaN for a bound.
    """
    if not fit.is_fitted or not math.isfinite(fit.beta):
        return math.nan
    if fit.beta == 0.0:
        return float(curve.rate(fit.median_g))
    return annual_rate_of_overturning(curve, fit.median_g, fit.beta)


def limit_state_values(
    slv: CensoredFit, curve: HazardCurve, tr_slv_y: float, confidence_factor: float
) -> tuple[float, float]:
    """Return ``(a_SLV [g], I_S [-])``: ``a_SLV = median / F_C``, ``I_S = T_R(a_SLV) / T_R,SLV``."""
    a_slv = slv.median_g / confidence_factor
    return a_slv, curve.return_period(a_slv) / tr_slv_y


def _usable(fit: CensoredFit) -> bool:
    """Whether a resample's fit enters the percentiles (a regular fit, beta > 0)."""
    return fit.is_fitted and fit.beta > 0


def resample_fits(
    data: RecordIntensities, picks: np.ndarray, method: str = "newton"
) -> list[tuple[float, float]]:
    """Return ``(median [g], beta [-])`` of every resample with a regular fit, in order.

    A resample is ``data`` at the record indices of one row of ``picks``; it has a regular
    fit when it holds two or more overturning records of different intensity, or one with a
    censoring above it
    (:func:`rockscreen.pipeline.risk.measures.censored_fit.fit_censored_lognormal`; else the fit is
    a bound, or the degenerate beta = 0, and the resample is left out). ``"newton"`` fits all
    resamples at once as weighted samples
    (:func:`rockscreen.pipeline.risk.measures.censored_fit.censored_mle`; without a censored record,
    the closed form), a resample that does not converge by the reference; ``"trust-exact"`` calls
    :func:`rockscreen.pipeline.risk.measures.censored_fit.fit_censored_lognormal` on each resample
    with the reference optimiser.

    Parameters
    ----------
    data : RecordIntensities
        One level's record intensities.
    picks : numpy.ndarray of int
        Record indices of each resample, shape (r, n).
    method : {'newton', 'trust-exact'}

    Returns
    -------
    list of (float, float)
    """
    if method == "trust-exact":
        fits = [
            fit_censored_lognormal(data.ag_g[pick], data.censored[pick], method=method)
            for pick in picks
        ]
        return [(fit.median_g, fit.beta) for fit in fits if _usable(fit)]
    n_res, n = picks.shape
    counts = np.zeros((n_res, n))
    np.add.at(counts, (np.repeat(np.arange(n_res), n), picks.ravel()), 1.0)
    x = np.log(data.ag_g)
    cens = np.asarray(data.censored, dtype=bool)
    w_obs = counts * ~cens
    n_obs = w_obs.sum(1)
    with np.errstate(divide="ignore", invalid="ignore"):
        mean = (w_obs * x).sum(1) / n_obs
        spread = np.sqrt((w_obs * (x[None, :] - mean[:, None]) ** 2).sum(1) / n_obs)
    regular = (n_obs >= 2) & (spread > 1e-12 * np.maximum(1.0, np.abs(mean)))
    mu = np.where(regular, mean, np.nan)
    ln_beta = np.full(n_res, np.nan)
    ln_beta[regular] = np.log(spread[regular])  # no censored pick: the closed form
    mixed = regular & ((counts * cens).sum(1) > 0)
    if mixed.any():
        start = np.column_stack([mean[mixed], np.log(spread[mixed])])
        m_mu, m_ln_beta, converged = censored_mle(x, cens, counts[mixed], start)
        mu[mixed], ln_beta[mixed] = m_mu, m_ln_beta
        for row, ok in zip(np.flatnonzero(mixed), converged, strict=True):
            if not ok:
                fit = fit_censored_lognormal(
                    data.ag_g[picks[row]], data.censored[picks[row]], method="trust-exact"
                )
                mu[row], ln_beta[row] = math.log(fit.median_g), math.log(fit.beta)
    # One overturning record with a censoring above it: fitted as the point estimate is
    # (fit_censored_lognormal, its interior maximum), so both methods keep the same resamples.
    single = n_obs == 1
    for row in np.flatnonzero(single):
        fit = fit_censored_lognormal(data.ag_g[picks[row]], data.censored[picks[row]])
        if _usable(fit):
            regular[row] = True
            mu[row], ln_beta[row] = math.log(fit.median_g), math.log(fit.beta)
    return [(math.exp(mu[i]), math.exp(ln_beta[i])) for i in np.flatnonzero(regular)]


def tower_seed(seed: int, tower_id: str) -> int:
    """Return the bootstrap seed of a tower: the run's seed mixed with a hash of its id."""
    return (int(seed) * 1_000_003 + zlib.crc32(str(tower_id).encode("utf-8"))) % 2**32


def bootstrap_intervals(
    rows: Sequence[dict[str, Any]],
    curve: HazardCurve,
    tr_slv_y: float,
    confidence_factor: float,
    n_resamples: int = DEFAULT_BOOTSTRAP_RESAMPLES,
    seed: int = 0,
    method: str = "newton",
) -> dict[str, Any]:
    """Return 90 % bootstrap intervals of the collapse median, ``lambda_C`` and ``I_S``.

    The records (not the components) are resampled with replacement, ``n_resamples``
    times, and both levels are refitted on each resample (the same records for both).
    Percentiles 5 and 95 are taken over the resamples that give a regular fit (not a bound:
    fewer than two overturning records; not the degenerate beta = 0 of one record drawn
    several times); how many did is reported. A level whose fit on all the records is only
    a bound has no interval (NaN).

    Parameters
    ----------
    rows : sequence of dict
        ``/ida`` rows of one tower.
    curve : HazardCurve
        The site's hazard curve.
    tr_slv_y : float
        ``T_R,SLV`` [y].
    confidence_factor : float
        F_C [-] dividing the SLV capacity.
    n_resamples : int
        Resamples (0: no intervals).
    seed : int
        Seed of the resampling.
    method : {'newton', 'trust-exact'}
        The optimiser of the fits (:func:`resample_fits`).

    Returns
    -------
    dict
        ``collapse_median_lo90_g``, ``collapse_median_hi90_g`` [g],
        ``annual_rate_lo90_per_y``, ``annual_rate_hi90_per_y`` [1/y],
        ``safety_index_lo90``, ``safety_index_hi90`` [-], ``bootstrap_resamples``,
        ``bootstrap_fitted_collapse``, ``bootstrap_fitted_slv``.
    """
    collapse, slv = record_intensities(rows, "collapse"), record_intensities(rows, "slv")
    n = len(collapse.records)
    # A level whose point estimate is only a bound has no interval.
    point = {
        name: fit_censored_lognormal(data.ag_g, data.censored, method=method).is_fitted
        if n
        else False
        for name, data in (("collapse", collapse), ("slv", slv))
    }
    rng = np.random.default_rng(seed)
    picks = rng.integers(0, n, (n_resamples, n)) if n and n_resamples else np.zeros((0, n), int)
    medians, rates, indices = [], [], []
    if point["collapse"]:
        fits = resample_fits(collapse, picks, method)
        medians = [median for median, _ in fits]
        rates = [collapse_rate(curve, CensoredFit(median, beta)) for median, beta in fits]
    if point["slv"]:
        for median, beta in resample_fits(slv, picks, method):
            fit = CensoredFit(median, beta)
            indices.append(limit_state_values(fit, curve, tr_slv_y, confidence_factor)[1])
    tail = 100.0 * (1.0 - BOOTSTRAP_LEVEL) / 2.0

    def band(values: list[float]) -> tuple[float, float]:
        if not values:
            return math.nan, math.nan
        lo, hi = np.percentile(np.asarray(values, dtype=float), [tail, 100.0 - tail])
        return float(lo), float(hi)

    (m_lo, m_hi), (r_lo, r_hi), (i_lo, i_hi) = band(medians), band(rates), band(indices)
    return {
        "collapse_median_lo90_g": m_lo,
        "collapse_median_hi90_g": m_hi,
        "annual_rate_lo90_per_y": r_lo,
        "annual_rate_hi90_per_y": r_hi,
        "safety_index_lo90": i_lo,
        "safety_index_hi90": i_hi,
        "bootstrap_resamples": int(n_resamples if n else 0),
        "bootstrap_fitted_collapse": len(medians),
        "bootstrap_fitted_slv": len(indices),
    }
