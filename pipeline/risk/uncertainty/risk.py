"""A tower's risk with its epistemic uncertainty: P in 50 years, lambda, the fragility band.

Per sample ``i`` of the epistemic inputs (:mod:`.priors`) the tower's capacity is its
weakest mechanism's, ``theta_i = min_m a_m,i`` [g] (the shaft, :mod:`.shaft`; the kinematic
mechanisms, :mod:`.kinematic`; the rocking medians of the IDA, given), read as the median
of a lognormal fragility with the aleatory (record-to-record) dispersion ``beta``:
``P(C | a, i) = Phi(ln(a / theta_i) / beta)``. Its mean annual frequency ``lambda_i``
comes from the site's hazard curve by the risk integral and its probability in ``years``
by Poisson (:mod:`rockscreen.pipeline.risk.measures.hazard_integral`:
``annual_rate_of_overturning``, ``probability_in``). The two uncertainties stay apart: ``beta``
inside each sample's fragility, the inputs across the samples.

**Best estimate** (``p50_best``): the median over the epistemic samples of ``P_i``. With
one ``beta`` for the tower, ``P`` decreases with ``theta``, so this is the probability of
the tower at its median capacity: "the P50 of the median tower", defined even where an
input is categorical (the masonry type), and a central value of the same distribution as
its 90 % interval (``p50_lo90``, ``p50_hi90``: the 5 % and 95 % quantiles over the
samples), so always inside it. The mean over the samples (``p50_mean``: ``1 - exp(-years x
mean lambda)``, the probability of the tower whose fragility mixes both uncertainties,
Cornell et al. 2002's "mean estimate") is given beside: the expected value a decision
over many towers adds up, more sensitive to a few weak samples. Quantiles are sample
order statistics (``numpy.quantile``, ``method="inverted_cdf"``), weighted.

**Post-stratification on the masonry type and the period** (:func:`stratum_weights`): P
clusters by type (rubble against brick) and follows the period (its first-order index is
0.5-0.8 on the example), so the best estimate sits where few samples fall and the
binomial scatter of the samples' shares moves it. Each sample is weighted by its stratum's
prior probability (type x one of :data:`PERIOD_STRATA` equal-probability bands of the
period) over the stratum's share of the samples (Cochran, *Sampling Techniques*, 3rd ed.,
Wiley 1977, §5A.9): the shares are then exactly the prior's. Measured on the twelve towers
at n = 1000 it brings the largest seed-to-seed deviation of the best estimate from 10.5 %
to 5 % (docs/uncertainty.md).

**Bounds**: a capacity that holds at the table's longest return period (``"lower"``) or
fails at its shortest (``"upper"``) is a bound, not a value; so is any statistic it can
move. A sample whose capacity is at least ``theta_i`` has a probability at most ``P_i``:
a quantile ``q`` is flagged ``"at_most"`` when such a sample has ``P_i >= q`` (it could
fall below ``q`` and lower it); ``"at_least"`` likewise for capacities that are at most
``theta_i``; ``"both"`` when both apply. The mean is flagged by any such sample. A flagged
value must be printed as a bound (``<=``, ``>=``) or not at all.

**Beyond the table**: a capacity continued beyond the table
(:mod:`~rockscreen.pipeline.risk.uncertainty.extrapolation`, the screening risk's
default) is a value, not a bound: its ``P_i`` and ``lambda_i`` are integrated on the hazard
curve's extrapolation, as ``assess``'s ``lambda_C`` is
(:func:`~rockscreen.pipeline.risk.measures.hazard_integral.extrapolated_shares`). The tower carries
the (weighted) share of samples whose governing capacity is extrapolated
(``extrapolated_share``) and the share of the best estimate's ``lambda`` read on the
extrapolated hazard curve (``rate_extrapolated_share``).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.special import ndtr

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.hazard import hazard_curve
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.measures.hazard_integral import (
    HazardCurve,
    annual_rate_of_overturning,
    extrapolated_shares,
    probability_in,
)
from rockscreen.pipeline.risk.uncertainty.kinematic import MechanismCapacity

__all__ = [
    "DEFAULT_ALEATORY_BETA",
    "DEFAULT_ALEATORY_BETA_SOURCE",
    "DEFAULT_SAMPLES",
    "INTERVAL",
    "PERIOD_STRATA",
    "QUANTILE_METHOD",
    "RATE_NODES",
    "FragilityBand",
    "TowerRisk",
    "quantile_bound",
    "rates_of_capacities",
    "site_hazard_curve",
    "stratum_weights",
    "tower_risk",
]

#: Record-to-record (aleatory) dispersion of a mechanism's collapse intensity [-] when the
#: IDA's fit gives none (the shaft's and the kinematic capacities are single values).
DEFAULT_ALEATORY_BETA = 0.40
DEFAULT_ALEATORY_BETA_SOURCE = (
    "FEMA P-695 (2009) §7.3.1: record-to-record beta_RTR = 0.40 (judgement for masonry towers)"
)
#: Epistemic samples per tower (the best estimate within about 10 % across seeds: measured,
#: docs/uncertainty.md).
DEFAULT_SAMPLES = 1000
#: Capacities whose lambda is integrated before the rest is a spline (rates_of_capacities).
RATE_NODES = 65
#: Equal-probability bands of the period prior in the post-stratification.
PERIOD_STRATA = 10
#: The central interval over the epistemic samples [-].
INTERVAL = 0.90
#: Quantiles are order statistics of the samples (they commute with the monotone P(theta)).
QUANTILE_METHOD = "inverted_cdf"
#: P's bound flags from the capacity's: a capacity at least theta gives P at most P_i.
_P_BOUND = {"lower": "at_most", "upper": "at_least"}


def site_hazard_curve(site: SiteConditions) -> HazardCurve:
    """Return the site's hazard curve of ag on rock (NTC 2018 Allegato B, as ``assess``)."""
    periods, ag = hazard_curve(site.lon_deg, site.lat_deg)
    return HazardCurve.from_return_periods(periods, ag)


def stratum_weights(
    samples: dict[str, np.ndarray], priors: Any, *, period_strata: int = PERIOD_STRATA
) -> np.ndarray:
    """Return the post-stratification weights on the masonry type and the period.

    The strata are the type's categories crossed with ``period_strata`` equal-probability
    bands of the period's lognormal prior (``Phi(ln(T / median) / log_std)``); each sample
    is weighted by its stratum's prior probability over the stratum's share of the samples
    (Cochran 1977, §5A.9), the prior renormalised over the strata that have samples. A
    point prior makes one stratum of it.

    Parameters
    ----------
    samples : dict
        ``masonry_type`` and ``period_s`` arrays.
    priors : TowerPriors
        The tower's priors (``masonry``, ``period``).
    period_strata : int
        Bands of the period, >= 1.

    Returns
    -------
    ndarray
        Weights summing to 1.
    """
    kinds = np.asarray(samples["masonry_type"]).astype(str)
    period = np.asarray(samples["period_s"], dtype=float)
    if kinds.shape != period.shape or kinds.size == 0:
        raise RiskError("stratum weights: masonry_type and period_s differ in length or are empty")
    if int(period_strata) < 1:
        raise RiskError(f"stratum weights: period_strata={period_strata!r}; allowed: >= 1")
    type_pi = dict(getattr(priors.masonry, "weights", ())) or {k: 1.0 for k in set(kinds)}
    missing = sorted(set(kinds) - set(type_pi))
    if missing:
        raise RiskError(f"stratum weights: sampled types {missing} are not in the prior")
    prior = priors.period
    k = int(period_strata) if hasattr(prior, "log_std") else 1
    if k > 1:
        u = ndtr(np.log(period / prior.median_value) / prior.log_std)
        band = np.minimum((u * k).astype(int), k - 1)
    else:
        band = np.zeros(period.size, dtype=int)
    keys = np.array([f"{a}|{b}" for a, b in zip(kinds, band, strict=True)])
    names, inverse, counts = np.unique(keys, return_inverse=True, return_counts=True)
    pi = np.array([type_pi[name.split("|")[0]] / k for name in names])
    w = (pi / counts)[inverse]
    return w / w.sum()


def quantile_bound(values: np.ndarray, flags: np.ndarray, q: float) -> str:
    """Return the bound flag of a quantile ``q`` of ``values`` (module docstring).

    Parameters
    ----------
    values : ndarray
        The samples' values (a probability or a rate).
    flags : ndarray of str
        Each sample's ``""``, ``"at_most"`` or ``"at_least"``.
    q : float
        The quantile's value.

    Returns
    -------
    str
        ``""``, ``"at_most"``, ``"at_least"`` or ``"both"``.
    """
    down = bool(np.any((flags == "at_most") & (values >= q)))
    up = bool(np.any((flags == "at_least") & (values <= q)))
    return "both" if down and up else "at_most" if down else "at_least" if up else ""


def _quantile(values: np.ndarray, weights: np.ndarray, q: float) -> float:
    """Return the weighted ``q`` quantile: the smallest value whose weight below reaches q."""
    return float(np.quantile(values, q, method=QUANTILE_METHOD, weights=weights))


def _mean_bound(flags: np.ndarray) -> str:
    down, up = bool(np.any(flags == "at_most")), bool(np.any(flags == "at_least"))
    return "both" if down and up else "at_most" if down else "at_least" if up else ""


@dataclass(frozen=True)
class FragilityBand:
    """The fragility over the epistemic samples: median curve, band, mixture."""

    #: ag on rock [g].
    ag_g: np.ndarray
    #: Median over the samples of P(C | ag), the 5 % and 95 % curves [-].
    median: np.ndarray
    lo90: np.ndarray
    hi90: np.ndarray
    #: Mean over the samples: the fragility with both uncertainties mixed [-].
    mean: np.ndarray
    #: Share of samples whose capacity is a bound [-] (their curves are bounds).
    bounded_share: float


@dataclass(frozen=True)
class TowerRisk:
    """A tower's risk over its epistemic samples (module docstring)."""

    #: Per sample: the weakest capacity [g], its bound, the mechanism it comes from.
    capacity_g: np.ndarray
    capacity_bound: np.ndarray
    governing: np.ndarray
    #: Per sample: the weight (sums to 1; :func:`stratum_weights`).
    weights: np.ndarray
    #: Per sample: lambda [1/y], P in ``years`` [-] and the bound of both.
    rate_per_y: np.ndarray
    probability: np.ndarray
    probability_bound: np.ndarray
    #: Aleatory dispersion [-] and where it comes from; the exposure [y].
    beta: float
    beta_source: str
    years: float
    #: P in ``years``: best estimate (median over samples), 90 % interval, mean [-].
    p50_best: float
    p50_lo90: float
    p50_hi90: float
    p50_mean: float
    #: Their bound flags: ``""``, ``"at_most"``, ``"at_least"``, ``"both"``.
    p50_best_bound: str
    p50_lo90_bound: str
    p50_hi90_bound: str
    p50_mean_bound: str
    #: lambda [1/y] likewise (the same flags: P is monotone in lambda).
    rate_best_per_y: float
    rate_lo90_per_y: float
    rate_hi90_per_y: float
    rate_mean_per_y: float
    #: The mechanism that governs most often and the share of samples it governs [-].
    governing_mechanism: str
    governing_share: float
    #: Each mechanism's share of governed samples [-].
    governing_shares: dict
    #: Per sample: whether the governing capacity is continued beyond the table (a value).
    capacity_extrapolated: np.ndarray | None = None
    #: Weighted share of samples whose governing capacity is extrapolated [-].
    extrapolated_share: float = 0.0
    #: Share of the best estimate's lambda from the extrapolated hazard curve (beyond its
    #: last or below its first tabulated point) [-].
    rate_extrapolated_share: float = 0.0

    @property
    def n(self) -> int:
        """Return the number of epistemic samples."""
        return int(self.capacity_g.size)

    def fragility_band(self, ag_g: Sequence[float] | np.ndarray) -> FragilityBand:
        """Return the fragility's median curve, 90 % band and mixture at ``ag_g`` [g]."""
        a = np.asarray(ag_g, dtype=float)
        if a.ndim != 1 or not np.all(a > 0.0):
            raise RiskError("fragility band: ag [g] must be a 1-d array of values > 0")
        p = ndtr(np.log(a[None, :] / self.capacity_g[:, None]) / self.beta)
        levels = [0.5 - 0.5 * INTERVAL, 0.5, 0.5 + 0.5 * INTERVAL]
        lo, med, hi = (
            np.array([_quantile(p[:, j], self.weights, q) for j in range(a.size)]) for q in levels
        )
        return FragilityBand(
            ag_g=a,
            median=med,
            lo90=lo,
            hi90=hi,
            mean=self.weights @ p,
            bounded_share=float(np.mean(self.capacity_bound != "")),
        )


def _weakest(
    mechanisms: Sequence[MechanismCapacity],
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Return per sample the weakest capacity [g], its bound, the governing name, extrapolated.

    The minimum of bounds (module docstring): with a capacity at most a value (``"upper"``)
    anywhere at or below the minimum, the minimum is at most that; a minimum that is a
    lower bound stays one unless an exact capacity is at or below it.
    """
    if not mechanisms:
        raise RiskError("tower risk: no mechanism's capacity")
    ag = np.vstack([m.ag_g for m in mechanisms])
    if len({a.size for a in ag}) != 1:
        raise RiskError("tower risk: the mechanisms' capacities differ in length")
    bound = np.vstack([m.bound for m in mechanisms])
    names = np.array([m.name for m in mechanisms], dtype=object)
    k = np.argmin(ag, axis=0)
    cols = np.arange(ag.shape[1])
    theta = ag[k, cols]
    out = bound[k, cols].astype(object)
    upper = np.any((bound == "upper"), axis=0)
    out[upper] = "upper"
    beyond = np.vstack([m.extrapolated for m in mechanisms])[k, cols] & (out == "")
    return theta, out, names[k], beyond


def rates_of_capacities(
    curve: HazardCurve, capacity_g: np.ndarray, beta: float, *, nodes: int | None = RATE_NODES
) -> np.ndarray:
    """Return lambda [1/y] of a lognormal fragility at each of many medians ``capacity_g``.

    ``annual_rate_of_overturning`` (the risk integral, 4001 points) of each capacity when
    there are at most ``nodes`` of them; else of ``nodes`` log-spaced capacities over their
    range, ``ln lambda`` then a cubic spline in ``ln theta`` (lambda is the hazard curve
    convolved with the fragility: smooth in ``ln theta``). Measured at L'Aquila from 0.02
    to 2 g (beta 0.4): within 3.1e-4 of integrating each capacity, whose own discretisation
    error is 1.8e-4 (against 40001 points), the spline's 1.8e-4: as accurate, far below the
    Monte-Carlo error (docs/uncertainty.md "Speed"; the test holds it within 5e-4).

    Parameters
    ----------
    curve : HazardCurve
        The site's hazard curve.
    capacity_g : ndarray
        Fragility medians [g], > 0.
    beta : float
        Dispersion [-], > 0.
    nodes : int or None
        Spline nodes, >= 4; None: every capacity integrated.

    Returns
    -------
    ndarray
        lambda [1/y] of each capacity.
    """
    theta = np.asarray(capacity_g, dtype=float)
    if nodes is not None and int(nodes) < 4:
        raise RiskError(f"risk rates: nodes={nodes!r}; allowed: an integer >= 4, or None")
    unique = np.unique(theta)
    if nodes is None or unique.size <= int(nodes):
        rates = np.array([annual_rate_of_overturning(curve, float(t), beta) for t in unique])
        return rates[np.searchsorted(unique, theta)]
    grid = np.geomspace(unique[0], unique[-1], int(nodes))
    at_grid = np.array([annual_rate_of_overturning(curve, float(t), beta) for t in grid])
    if not np.all(at_grid > 0.0):  # ln lambda undefined: integrate every capacity
        return rates_of_capacities(curve, theta, beta, nodes=None)
    spline = CubicSpline(np.log(grid), np.log(at_grid))
    return np.exp(spline(np.log(theta)))


def tower_risk(
    mechanisms: Sequence[MechanismCapacity],
    curve: HazardCurve,
    *,
    beta: float = DEFAULT_ALEATORY_BETA,
    beta_source: str = DEFAULT_ALEATORY_BETA_SOURCE,
    years: float = 50.0,
    weights: np.ndarray | None = None,
    rate_nodes: int | None = RATE_NODES,
) -> TowerRisk:
    """Return a tower's risk over its epistemic samples (module docstring).

    Parameters
    ----------
    mechanisms : sequence of MechanismCapacity
        Each mechanism's capacity per sample, one length (the shaft's:
        ``MechanismCapacity("shaft", cap.ag_g, cap.bound)`` of a
        :class:`~rockscreen.pipeline.risk.uncertainty.shaft.ShaftCapacity`; the kinematic
        ones of :func:`~rockscreen.pipeline.risk.uncertainty.kinematic.kinematic_capacities`;
        the rocking medians of the IDA per sample, a scalar broadcast by the caller).
    curve : HazardCurve
        The site's hazard curve (:func:`site_hazard_curve`).
    beta : float
        Aleatory dispersion [-], > 0 (default :data:`DEFAULT_ALEATORY_BETA`; the IDA fit's
        when it has one).
    beta_source : str
        Where ``beta`` comes from (shown with the result).
    years : float
        Exposure [y], > 0.
    weights : ndarray, optional
        The samples' weights (:func:`stratum_weights`); None: equal.
    rate_nodes : int or None
        :func:`rates_of_capacities`' ``nodes`` (None: every distinct capacity integrated).

    Returns
    -------
    TowerRisk
    """
    if not (math.isfinite(beta) and beta > 0.0):
        raise RiskError(f"tower risk: beta={beta!r}; allowed: a finite number > 0")
    if not (math.isfinite(years) and years > 0.0):
        raise RiskError(f"tower risk: years={years!r}; allowed: a finite number > 0")
    theta, bound, governing, beyond = _weakest(mechanisms)
    if weights is None:
        w = np.full(theta.size, 1.0 / theta.size)
    else:
        w = np.asarray(weights, dtype=float)
        if w.shape != theta.shape or not np.all(np.isfinite(w) & (w >= 0.0)) or w.sum() <= 0:
            raise RiskError(
                f"tower risk: {w.size} weights for {theta.size} samples; allowed: finite, "
                ">= 0, not all 0"
            )
        w = w / w.sum()
    unique, inverse = np.unique(theta, return_inverse=True)
    rate = rates_of_capacities(curve, unique, beta, nodes=rate_nodes)[inverse]
    prob = -np.expm1(-years * rate)
    flags = np.array([_P_BOUND.get(b, "") for b in bound], dtype=object)
    levels = [0.5, 0.5 - 0.5 * INTERVAL, 0.5 + 0.5 * INTERVAL]
    p_q = [_quantile(prob, w, q) for q in levels]
    r_q = [_quantile(rate, w, q) for q in levels]
    p_flags = [quantile_bound(prob, flags, float(q)) for q in p_q]
    names = governing.astype(str)
    shares = {str(k): float(w[names == k].sum()) for k in np.unique(names)}
    top = max(shares, key=lambda k: (shares[k], k))
    mean_rate = float(w @ rate)
    # the best estimate's sample: the capacity whose P is the median (P decreases with theta)
    best = int(np.argmin(np.abs(prob - p_q[0])))
    above, below = extrapolated_shares(curve, float(theta[best]), beta)
    return TowerRisk(
        capacity_g=theta,
        capacity_bound=bound,
        governing=governing,
        weights=w,
        rate_per_y=rate,
        probability=prob,
        probability_bound=flags,
        beta=float(beta),
        beta_source=beta_source,
        years=float(years),
        p50_best=float(p_q[0]),
        p50_lo90=float(p_q[1]),
        p50_hi90=float(p_q[2]),
        p50_mean=probability_in(mean_rate, years),
        p50_best_bound=p_flags[0],
        p50_lo90_bound=p_flags[1],
        p50_hi90_bound=p_flags[2],
        p50_mean_bound=_mean_bound(flags),
        rate_best_per_y=float(r_q[0]),
        rate_lo90_per_y=float(r_q[1]),
        rate_hi90_per_y=float(r_q[2]),
        rate_mean_per_y=mean_rate,
        governing_mechanism=top,
        governing_share=shares[top],
        governing_shares=shares,
        capacity_extrapolated=beyond,
        extrapolated_share=min(float(w[beyond].sum()), 1.0),
        rate_extrapolated_share=min(above + below, 1.0),
    )
