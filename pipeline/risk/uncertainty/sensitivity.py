"""What to survey first: the sensitivity of a tower's risk to each epistemic input.

**First-order Sobol' indices** of ``Y = ln P_i`` (the sample's probability in 50 years,
:class:`~rockscreen.pipeline.risk.uncertainty.risk.TowerRisk`) over the epistemic inputs
(base wall, taper, masonry type, strength, unit weight, period; an input the inventory
gives is a point and has none): ``S_k = Var(E[Y | X_k]) / Var(Y)``, the expected share of
``Var(Y)`` removed when ``X_k`` is known exactly (Saltelli et al., *Global Sensitivity
Analysis: The Primer*, Wiley 2008, ch. 1). Estimated by **binning on the samples already
computed** (the correlation ratio; Saltelli et al. 2008 §1.2.5): no extra model run, where
the pick-freeze estimator (Saltelli 2002) would need ``n (k + 2)`` runs of the shaft's,
the kinematic and the rocking capacities. ``X_k`` is cut into :func:`_bins` equal-count
bins (one per category for the masonry type) and the between-bin variance is corrected
for the bins' finite size (epsilon-squared, Kelley 1935: ``(SS_b - (B - 1) SS_w / (n -
B)) / SS_tot``, clipped to [0, 1]). Read with dependent inputs (``f_m`` and ``w`` are
drawn given the type), ``S_k`` is still what knowing ``X_k`` removes: a measured strength
also says something of the type.

**survey_first**: the input of the largest ``S_k``, with the **expected narrowing** of the
90 % interval of P when it is fixed, computed by conditioning: the samples cut into groups
of :data:`NARROWING_GROUP` or more by that input (its categories for the type), the
interval's width in each, averaged with the groups' weights, against the same average over
random groups of the same sizes (:data:`NULL_PERMUTATIONS` permutations: a group of 40
samples has a narrower empirical 90 % interval than 200, whatever the input);
``narrowing = 1 - E[width | X_k] / E[width | random]``, in [0, 1].

**A region's list**: :func:`top_n_changes` gives, for every tower, the probability that its
membership of the top N changes once its ``survey_first`` input is measured (the
conditional best estimate of each group against the N-th best estimate of the other
towers).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.uncertainty.belfry import BELFRY_KEYS
from rockscreen.pipeline.risk.uncertainty.risk import INTERVAL, QUANTILE_METHOD

__all__ = [
    "conditional_best",
    "INPUTS",
    "NARROWING_GROUP",
    "NULL_PERMUTATIONS",
    "Sensitivity",
    "TopNChange",
    "epistemic_inputs",
    "expected_narrowing",
    "first_order_indices",
    "mean_group_width",
    "sensitivity",
    "top_n_changes",
    "top_n_changes_of_groups",
]

#: The epistemic inputs (names of the samples' arrays; ``taper`` = wall_top_m / wall_m).
INPUTS = ("wall_m", "taper", "masonry_type", "fm_pa", "unit_weight_n_m3", "period_s")
#: Smallest group of the conditional interval (samples).
NARROWING_GROUP = 40
#: Random groupings of the reference width.
NULL_PERMUTATIONS = 20


def epistemic_inputs(samples: dict[str, np.ndarray]) -> dict[str, np.ndarray]:
    """Return the inputs of the samples that vary (``INPUTS``; points left out).

    A sampled belfry (:data:`~rockscreen.pipeline.risk.uncertainty.belfry.BELFRY_KEYS`, the
    region's default) adds its inputs: its presence (a category), the height share, the opening
    ratio, the bells' mass and height share (each a few scenarios' values: its bins).

    Parameters
    ----------
    samples : dict
        :meth:`~rockscreen.pipeline.risk.uncertainty.priors.TowerPriors.sample`'s arrays.

    Returns
    -------
    dict
        Name to array; ``masonry_type`` an array of str.
    """
    out = {}
    for name in (*INPUTS, *(k for k in BELFRY_KEYS if k in samples)):
        if name == "taper":
            if "wall_m" not in samples or "wall_top_m" not in samples:
                continue
            x = np.asarray(samples["wall_top_m"], float) / np.asarray(samples["wall_m"], float)
        elif name not in samples:
            continue
        elif name in ("masonry_type", "belfry_present"):
            x = np.asarray(samples[name]).astype(str)
        else:
            x = np.asarray(samples[name], dtype=float)
        if np.unique(x).size > 1:
            out[name] = x
    return out


def _is_categorical(x: np.ndarray) -> bool:
    return x.dtype.kind in "OUS"


def _bins(x: np.ndarray, size: int) -> np.ndarray:
    """Return a group label per sample: categories, or equal-count bins of ``size`` or more.

    Continuous: ``max(2, min(n // size, ceil(sqrt(n))))`` bins between the samples'
    quantiles; equal values share a bin (the taper's prismatic share is one value), so a
    bin may hold more than its share.
    """
    if _is_categorical(x):
        return np.unique(x, return_inverse=True)[1]
    n = x.size
    n_bins = max(2, min(n // size, math.ceil(math.sqrt(n))))
    ordered = np.sort(x)
    edges = ordered[(np.arange(1, n_bins) * n) // n_bins]
    return np.searchsorted(np.unique(edges), x, side="right")


def _epsilon_squared(y: np.ndarray, labels: np.ndarray) -> float:
    """Return the bias-corrected correlation ratio of ``y`` on the groups (module docstring)."""
    n = y.size
    groups = np.unique(labels)
    b = groups.size
    total = float(np.sum((y - y.mean()) ** 2))
    if total <= 0.0 or b < 2 or n <= b:
        return 0.0
    between = sum(np.sum(labels == g) * (y[labels == g].mean() - y.mean()) ** 2 for g in groups)
    within = total - between
    value = (between - (b - 1) * within / (n - b)) / total
    return float(min(max(value, 0.0), 1.0))


def first_order_indices(
    y: np.ndarray, inputs: dict[str, np.ndarray], *, bin_size: int = 20
) -> dict[str, float]:
    """Return the first-order Sobol' index of ``y`` for each input (module docstring).

    Parameters
    ----------
    y : ndarray
        The output per sample.
    inputs : dict
        Name to the input's samples (str arrays are categorical).
    bin_size : int
        Smallest bin of a continuous input (samples); the bins are also at most
        ``ceil(sqrt(n))``.

    Returns
    -------
    dict
        Name to ``S_k`` in [0, 1].
    """
    y = np.asarray(y, dtype=float)
    if not np.all(np.isfinite(y)):
        raise RiskError("sensitivity: the output must be finite")
    out = {}
    for name, x in inputs.items():
        if np.shape(x) != y.shape:
            raise RiskError(f"sensitivity: input {name!r} has {np.size(x)} samples, not {y.size}")
        out[name] = _epsilon_squared(y, _bins(np.asarray(x), bin_size))
    return out


def _width(p: np.ndarray) -> float:
    lo, hi = np.quantile(p, [0.5 - 0.5 * INTERVAL, 0.5 + 0.5 * INTERVAL], method=QUANTILE_METHOD)
    return float(hi - lo)


def mean_group_width(p: np.ndarray, labels: np.ndarray) -> float:
    """Return the groups' 90 % interval widths of ``p`` averaged with the groups' sizes.

    All groups at once: the samples sorted by group then value, each group's two order
    statistics picked as :func:`numpy.quantile`'s ``inverted_cdf`` picks them (its index
    ``n q - 1``, up where it has a fraction), so each width is that of
    :func:`numpy.quantile` on the group bit for bit, summed in the groups' order (a test
    checks); with a NaN in ``p``, :func:`numpy.quantile` per group.

    Parameters
    ----------
    p : ndarray
        P per sample [-].
    labels : ndarray of int
        The group of each sample.

    Returns
    -------
    float
        ``sum(n_g width_g) / n`` [-].
    """
    return _mean_group_widths(p, np.asarray(labels)[None, :])[0]


def _mean_group_widths(p: np.ndarray, labellings: np.ndarray) -> list[float]:
    """Return :func:`mean_group_width` of each row of ``labellings`` (the same group sizes).

    The rows are permutations of one labelling (:func:`expected_narrowing`'s random
    groupings): their groups and sizes are the first row's.
    """
    groups, counts = np.unique(labellings[0], return_counts=True)
    if QUANTILE_METHOD != "inverted_cdf" or not np.all(np.isfinite(p)):
        rows = [[_width(p[row == g]) for g in groups] for row in labellings]
    else:
        order = np.argsort(p, kind="stable")
        # Each row's samples by group, by value inside a group (a stable sort of the
        # value-sorted samples by their group).
        ordered = p[order][np.argsort(labellings[:, order], axis=1, kind="stable")]
        starts = np.cumsum(counts) - counts
        picks = []
        for q in (0.5 - 0.5 * INTERVAL, 0.5 + 0.5 * INTERVAL):
            index = counts * q - 1.0
            below = np.floor(index)
            k = np.where(index - below == 0.0, below, below + 1.0).astype(np.intp)
            picks.append(ordered[:, starts + np.maximum(k, 0)])
        rows = (picks[1] - picks[0]).tolist()
    return [
        float(sum(c * w for c, w in zip(counts, widths, strict=True)) / p.size) for widths in rows
    ]


def expected_narrowing(
    probability: np.ndarray, x: np.ndarray, *, seed: int = 0
) -> tuple[float, float]:
    """Return the expected narrowing of the 90 % interval of P when ``x`` is fixed.

    Parameters
    ----------
    probability : ndarray
        P per sample [-].
    x : ndarray
        The input per sample.
    seed : int
        Seed of the random groupings (the reference width).

    Returns
    -------
    narrowing : float
        ``1 - E[width | x] / E[width | random groups]`` in [0, 1] (module docstring).
    width_after : float
        The expected width once ``x`` is known [-]: today's width times ``1 - narrowing``.
    """
    p = np.asarray(probability, dtype=float)
    labels = _bins(np.asarray(x), NARROWING_GROUP)
    conditional = mean_group_width(p, labels)
    rng = np.random.default_rng(seed)
    groupings = np.array([rng.permutation(labels) for _ in range(NULL_PERMUTATIONS)])
    null = np.mean(_mean_group_widths(p, groupings))
    if null <= 0.0:
        return 0.0, _width(p)
    narrowing = float(min(max(1.0 - conditional / null, 0.0), 1.0))
    return narrowing, _width(p) * (1.0 - narrowing)


@dataclass(frozen=True)
class Sensitivity:
    """A tower's sensitivity to its epistemic inputs (module docstring)."""

    #: First-order Sobol' index of ln P per varying input [-].
    first_order: dict
    #: Expected narrowing of the 90 % interval of P per input [-].
    narrowing: dict
    #: The input to survey first ("" when no input varies) and its index and narrowing.
    survey_first: str
    survey_first_index: float
    survey_first_narrowing: float
    #: The 90 % interval's width today and expected once ``survey_first`` is known [-].
    width90: float
    width90_after: float


def sensitivity(probability: np.ndarray, samples: dict[str, np.ndarray]) -> Sensitivity:
    """Return a tower's first-order indices of ln P and its ``survey_first``.

    Parameters
    ----------
    probability : ndarray
        P in 50 years per sample (``TowerRisk.probability``) [-].
    samples : dict
        The epistemic samples it was computed from.

    Returns
    -------
    Sensitivity
    """
    p = np.asarray(probability, dtype=float)
    y = np.log(np.clip(p, 1e-300, None))
    inputs = epistemic_inputs(samples)
    indices = first_order_indices(y, inputs)
    narrowing = {name: expected_narrowing(p, x)[0] for name, x in inputs.items()}
    width = _width(p)
    if not indices:
        return Sensitivity(indices, narrowing, "", 0.0, 0.0, width, width)
    top = max(indices, key=lambda k: (indices[k], narrowing[k]))
    return Sensitivity(
        first_order=indices,
        narrowing=narrowing,
        survey_first=top,
        survey_first_index=indices[top],
        survey_first_narrowing=narrowing[top],
        width90=width,
        width90_after=width * (1.0 - narrowing[top]),
    )


@dataclass(frozen=True)
class TopNChange:
    """How likely measuring one input moves a tower across the top-N line."""

    tower_id: str
    #: Whether it is in the top N today.
    in_top: bool
    #: The input measured (the tower's ``survey_first``).
    input: str
    #: Probability over the input's value that the tower enters or leaves the top N [-].
    probability: float


def conditional_best(p: np.ndarray, x: np.ndarray, w: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Return each group's share of the weight and its best estimate (weighted median of P).

    Parameters
    ----------
    p : numpy.ndarray
        P in 50 years per sample [-].
    x : numpy.ndarray
        The input the samples are grouped by (categories, or equal-count bins of
        :data:`NARROWING_GROUP` samples or more).
    w : numpy.ndarray
        Each sample's weight [-].

    Returns
    -------
    shares, best : numpy.ndarray
        Per group, in the groups' order.
    """
    labels = _bins(x, NARROWING_GROUP)
    groups = np.unique(labels)
    weights = np.array([w[labels == g].sum() for g in groups])
    best = np.array(
        [
            float(np.quantile(p[labels == g], 0.5, method=QUANTILE_METHOD, weights=w[labels == g]))
            for g in groups
        ]
    )
    return weights / weights.sum(), best


def top_n_changes(
    tower_ids: Sequence[str],
    best: Sequence[float],
    probabilities: Sequence[np.ndarray],
    samples: Sequence[dict[str, np.ndarray]],
    survey_first: Sequence[str],
    n_top: int,
    weights: Sequence[np.ndarray] | None = None,
) -> list[TopNChange]:
    """Return, per tower, the probability its top-N membership changes once surveyed.

    Tower ``i`` is in the top N while its best estimate exceeds ``t_i``, the N-th highest
    best estimate of the other towers. Its ``survey_first`` input measured, its best
    estimate becomes the median of P among the samples of that input's group
    (:func:`_bins`; weighted as the best estimate); the probability of a change is the
    weight of the groups whose median is on the other side of ``t_i``. The other towers
    are held at their best estimates.

    Parameters
    ----------
    tower_ids : sequence of str
    best : sequence of float
        ``p50_best`` of each tower [-].
    probabilities : sequence of ndarray
        ``TowerRisk.probability`` of each tower.
    samples : sequence of dict
        The epistemic samples of each tower.
    survey_first : sequence of str
        Each tower's ``survey_first`` ("" : nothing varies, no change).
    n_top : int
        N, in [1, number of towers - 1].
    weights : sequence of ndarray, optional
        Each tower's sample weights (``TowerRisk.weights``, as its best estimate); None:
        equal.

    Returns
    -------
    list of TopNChange
        Sorted by probability, highest first (then by id).
    """
    b = np.asarray(best, dtype=float)
    n = b.size
    if not (len(tower_ids) == len(probabilities) == len(samples) == len(survey_first) == n):
        raise RiskError("top-N changes: the towers' lists differ in length")
    groups = []
    for i in range(n):
        name = survey_first[i]
        inputs = epistemic_inputs(samples[i])
        if not name or name not in inputs:
            groups.append((np.empty(0), np.empty(0)))
            continue
        p = np.asarray(probabilities[i], dtype=float)
        w = np.full(p.size, 1.0 / p.size) if weights is None else np.asarray(weights[i], float)
        if w.shape != p.shape:
            raise RiskError(f"top-N changes: tower {tower_ids[i]!r} has {w.size} weights")
        groups.append(conditional_best(p, inputs[name], w))
    return top_n_changes_of_groups(tower_ids, b, groups, survey_first, n_top)


def top_n_changes_of_groups(
    tower_ids: Sequence[str],
    best: Sequence[float],
    groups: Sequence[tuple[np.ndarray, np.ndarray]],
    survey_first: Sequence[str],
    n_top: int,
) -> list[TopNChange]:
    """Return :func:`top_n_changes` from each tower's groups instead of its samples.

    What a region needs of a tower's samples is its ``survey_first`` input's groups: each
    group's share of the weight and its best estimate (:func:`conditional_best`), so a
    region's list is made without keeping every tower's samples.

    Parameters
    ----------
    tower_ids : sequence of str
    best : sequence of float
        ``p50_best`` of each tower [-] (NaN: above every number, as a sort puts it).
    groups : sequence of (ndarray, ndarray)
        Each tower's groups: shares of the weight and best estimates (empty: nothing varies).
    survey_first : sequence of str
    n_top : int
        N, in [1, number of towers - 1].

    Returns
    -------
    list of TopNChange
        Sorted by probability, highest first (then by id).
    """
    b = np.asarray(best, dtype=float)
    n = b.size
    if not (len(tower_ids) == len(groups) == len(survey_first) == n):
        raise RiskError("top-N changes: the towers' lists differ in length")
    if not 1 <= int(n_top) < n:
        raise RiskError(f"top-N changes: n_top={n_top!r}; allowed: 1 to {n - 1}")
    ordered = np.sort(b)[::-1]  # NaN first
    n_nan = int(np.isnan(b).sum())
    ascending = np.sort(b[~np.isnan(b)])
    out = []
    for i in range(n):
        # The others' N-th highest: ``ordered`` without one occurrence of b[i], which sits
        # at ``first`` (after the NaNs and the higher values).
        if np.isnan(b[i]):
            first = 0
        else:
            first = n_nan + ascending.size - int(np.searchsorted(ascending, b[i], side="right"))
        threshold = ordered[int(n_top) - 1] if int(n_top) - 1 < first else ordered[int(n_top)]
        in_top = bool(b[i] > threshold)
        shares, cond = (np.asarray(g, dtype=float) for g in groups[i])
        crossing = float(np.sum(shares[(cond > threshold) != in_top])) if shares.size else 0.0
        out.append(TopNChange(str(tower_ids[i]), in_top, survey_first[i], crossing))
    return sorted(out, key=lambda c: (-c.probability, c.tower_id))
