"""Record sets centred in the NTC 2018 band: the selection of the embedded stochastic suite.

:func:`select_centred` picks, from a pool's spectra, a set whose mean spectrum over the
period range sits at the middle of the band of NTC 2018 §3.2.3.6 (mean/target within
0.90-1.30), each record amplitude-scaled and never matched; :func:`centred_set` returns it
as a :class:`~rockscreen.pipeline.hazard.selection.RecordSet`. The design, the margin and
the measured worst ratios are in ``docs/hazard.md`` (Selection, Compliance).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rockscreen.pipeline.errors import HazardError
from rockscreen.pipeline.hazard.selection import (
    SCALE_LIMITS,
    SELECTION_DOCS,
    RecordSet,
    check_options,
    set_message,
)
from rockscreen.solver.docstrings import fill_doc

__all__ = [
    "AIM_MARGIN",
    "COMMON_FACTOR_RANGE",
    "MAX_SWAPS",
    "SWAP_WINDOW",
    "centred_set",
    "select_centred",
]


#: Range of the common factor a centred set may need [-]: a record is a candidate of
#: :func:`select_centred` when its own least-squares factor, times any factor of this range,
#: stays within the scale limits (so the limits never distort the centring).
COMMON_FACTOR_RANGE = (0.8, 1.25)
#: How far inside the band :func:`select_centred` aims [-]: swaps continue while the set's
#: mean/target leaves ``[low + AIM_MARGIN, high - AIM_MARGIN]``.
AIM_MARGIN = 0.08
#: Most swaps of :func:`select_centred`'s search.
MAX_SWAPS = 60
#: Candidates (after the first ``n_records`` in the order) the swaps try first.
SWAP_WINDOW = 150


@dataclass(frozen=True)
class _Centring:
    """The log-ratio shapes of the candidates and what a centred set is judged on."""

    # (periods, candidates): ratio to the target of each record scaled by its own factor;
    # periods first, so that the maxima and minima over them run on contiguous rows
    shapes: np.ndarray
    log_factors: np.ndarray  # (candidates,) own least-squares factors, logs
    centre: float  # log of the band's geometric centre
    log_caps: tuple[float, float]

    def deviation(self, total: np.ndarray, n: int, low_f, high_f):
        """Worst |ln(ratio) - centre| of sets whose summed shapes are ``total`` (periods, ...).

        ``low_f``/``high_f`` are the logs of the sets' smallest and largest own factor; the
        common factor centres the ratio, limited so that every factor stays within the caps.
        Returns (deviation, log common factor), each of shape ``total.shape[1:]``.
        """
        top = np.log(total.max(axis=0) / n)
        bottom = np.log(total.min(axis=0) / n)
        common = np.clip(
            self.centre - 0.5 * (top + bottom), self.log_caps[0] - low_f, self.log_caps[1] - high_f
        )
        return np.maximum(top + common - self.centre, self.centre - bottom - common), common


def _centring(spectra, target, band, caps) -> _Centring:
    log_ratio = np.log(spectra) - np.log(target)
    log_factors = -log_ratio.mean(axis=1)
    shapes = np.ascontiguousarray(np.exp(log_ratio + log_factors[:, None]).T)
    centre = 0.5 * (math.log(band[0]) + math.log(band[1]))
    return _Centring(shapes, log_factors, centre, (math.log(caps[0]), math.log(caps[1])))


def _aim(band, margin: float, centre: float) -> float:
    """Largest deviation from the centre that keeps the ratio ``margin`` inside the band."""
    low, high = band[0] + margin, band[1] - margin
    if low >= high:
        return 0.0
    return min(centre - math.log(low), math.log(high) - centre)


def _swap_search(c: _Centring, chosen, unused, n, stop: float, max_swaps: int):
    """Swap one chosen record for an unused one, the best swap each time, while it helps."""
    chosen, unused = np.array(chosen), np.array(unused)
    f = c.log_factors
    total = c.shapes[:, chosen].sum(axis=1)
    current = float(c.deviation(total, n, f[chosen].min(), f[chosen].max())[0])
    others = ~np.eye(n, dtype=bool)
    for _ in range(max_swaps):
        if current <= stop or unused.size == 0:
            break
        # (periods, chosen k, unused j): the set with k swapped for j
        trial = (total[:, None] - c.shapes[:, chosen])[:, :, None] + c.shapes[:, None, unused]
        rest = np.broadcast_to(f[chosen], (n, n))
        low_f = np.minimum(np.where(others, rest, np.inf).min(axis=1)[:, None], f[unused])
        high_f = np.maximum(np.where(others, rest, -np.inf).max(axis=1)[:, None], f[unused])
        value, _ = c.deviation(trial, n, low_f, high_f)
        k, j = np.unravel_index(int(np.argmin(value)), value.shape)
        if value[k, j] >= current - 1e-12:
            break
        total = trial[:, k, j]
        chosen[k], unused[j] = unused[j], chosen[k]
        current = float(value[k, j])
    return list(chosen), current


def _greedy(c: _Centring, candidates: np.ndarray, n: int) -> list[int]:
    """Build a set one record at a time, each the one that keeps the deviation smallest."""
    chosen: list[int] = []
    total = np.zeros(c.shapes.shape[0])
    left = candidates.copy()
    f = c.log_factors
    for size in range(1, n + 1):
        trial = total[:, None] + c.shapes[:, left]
        low_f = np.minimum(f[chosen].min(initial=np.inf), f[left])
        high_f = np.maximum(f[chosen].max(initial=-np.inf), f[left])
        value, _ = c.deviation(trial, size, low_f, high_f)
        best = int(np.argmin(value))
        chosen.append(int(left[best]))
        total = trial[:, best]
        left = np.delete(left, best)
    return chosen


@fill_doc(SELECTION_DOCS)
def select_centred(
    spectra_g,
    target_g,
    *,
    n_records: int = 11,
    tolerance: tuple[float, float] = (-0.10, 0.30),
    scale_limits: tuple[float, float] = SCALE_LIMITS,
    aim_margin: float = AIM_MARGIN,
) -> tuple[np.ndarray, np.ndarray]:
    """Choose and scale a set from many candidates, its mean aimed at the band's centre.

    Vectorised for large pools (hundreds of candidates). Every candidate is scaled by its
    own least-squares factor (in logs over the periods) and the set by a common factor
    that puts the worst ratio mean/target as far inside the band as it can (its geometric
    centre, in log terms); only records whose own factor leaves room for a common factor in
    :data:`COMMON_FACTOR_RANGE` within ``scale_limits`` are candidates (all of them when
    fewer than ``n_records`` do). The set starts from the first ``n_records`` candidates in
    their index order (the embedded suite's pool order, the same at every site, so that
    sets share records; an order taken from the spectra would bias the set's scatter)
    and swaps a chosen record for an unused one, the best swap each time, while the
    mean/target lies outside the band narrowed by ``aim_margin`` on both sides; if that
    stalls, a set built greedily and improved by swaps until none helps is taken when it is
    better. Records are only amplitude-scaled, never matched.

    Parameters
    ----------
    spectra_g : numpy.ndarray
        Spectra of the candidates [g], shape (candidates, periods), positive.
    target_g : numpy.ndarray
        Target at the same periods [g].
    n_records : int
        Size of the set (the number of candidates if there are fewer).
    %(tolerance)s
    %(scale_limits)s
    aim_margin : float
        How far inside the band the search aims [-].

    Returns
    -------
    indices : numpy.ndarray
        The chosen candidates (int).
    scale_factors : numpy.ndarray
        Their factors [-], within ``scale_limits``.

    Raises
    ------
    HazardError
        For a non-positive spectral ordinate or invalid options.
    """
    spectra = np.asarray(spectra_g, float)
    target = np.asarray(target_g, float)
    check_options(n_records, (1.0, 2.0), tolerance, scale_limits)
    if spectra.ndim != 2 or spectra.shape[1] != target.size or not np.all(spectra > 0):
        raise HazardError("select_centred needs positive spectra of shape (records, periods)")
    band = (1.0 + tolerance[0], 1.0 + tolerance[1])
    caps = (float(scale_limits[0]), float(scale_limits[1]))
    c = _centring(spectra, target, band, caps)
    n_all = spectra.shape[0]
    n = min(int(n_records), n_all)
    room = (c.log_factors >= c.log_caps[0] - math.log(COMMON_FACTOR_RANGE[0])) & (
        c.log_factors <= c.log_caps[1] - math.log(COMMON_FACTOR_RANGE[1])
    )
    # in index order: the search starts from the first candidates (the docstring)
    candidates = np.flatnonzero(room) if np.count_nonzero(room) >= n else np.arange(n_all)
    aim = _aim(band, aim_margin, c.centre)
    # The next SWAP_WINDOW candidates first (cheap), then all of them.
    window = candidates[: n + SWAP_WINDOW]
    chosen, value = _swap_search(c, window[:n], window[n:], n, aim, MAX_SWAPS)
    if value > aim and candidates.size > window.size:
        rest = np.setdiff1d(candidates, chosen, assume_unique=True)  # sorted: index order
        chosen, value = _swap_search(c, chosen, rest, n, aim, MAX_SWAPS)
    if value > aim:
        greedy = _greedy(c, candidates, n)
        rest = np.setdiff1d(candidates, greedy, assume_unique=True)
        better, better_value = _swap_search(c, greedy, rest, n, -1.0, MAX_SWAPS)
        if better_value < value:
            chosen = better
    chosen = np.array(chosen, dtype=int)
    f = c.log_factors[chosen]
    _, common = c.deviation(c.shapes[:, chosen].sum(axis=1), n, f.min(), f.max())
    factors = np.clip(np.exp(f + float(common)), *caps)
    return chosen, factors


@fill_doc(SELECTION_DOCS)
def centred_set(
    records, spectra_g, periods_s, target_g, scale_factors, *, tolerance=(-0.10, 0.30), wanted=None
) -> RecordSet:
    """Return the :class:`RecordSet` of chosen records and their factors (mean, ratio, message).

    Parameters
    ----------
    records : sequence of SuiteRecord
        The chosen records, unscaled.
    spectra_g : numpy.ndarray
        Their spectra [g], shape (records, periods).
    periods_s, target_g : numpy.ndarray
        Matching periods [s] and target [g].
    scale_factors : numpy.ndarray
        Their factors [-].
    %(tolerance)s
    wanted : int, optional
        Size asked for (said in the message when larger than ``len(records)``).

    Returns
    -------
    RecordSet
    """
    scale = np.asarray(scale_factors, float)
    mean = (np.asarray(spectra_g, float) * scale[:, None]).mean(axis=0)
    ratio = mean / target_g
    low, high = 1.0 + tolerance[0], 1.0 + tolerance[1]
    meets = bool(ratio.min() >= low - 1e-12 and ratio.max() <= high + 1e-12)
    n = len(records)
    message = set_message(meets, ratio, periods_s, tolerance, n, wanted or n, n)
    return RecordSet(
        records=tuple(records),
        scale_factors=scale,
        periods_s=np.asarray(periods_s, float),
        mean_sa_g=mean,
        target_sa_g=np.asarray(target_g, float),
        ratio_min=float(ratio.min()),
        ratio_max=float(ratio.max()),
        meets_tolerance=meets,
        message=message,
    )
