"""Spectrum-compatible record sets (NTC 2018 §3.2.3.6) from a suite of accelerograms.

NTC 2018 §3.2.3.6 admits natural or synthetic accelerograms for time-history analysis when
the mean of their 5 %-damped elastic spectra departs from the code spectrum by no more
than -10 % and +30 % over the period range of interest (0.15-2.0 s by default, or up to
2 T for a structure of period T). :func:`select_records` chooses and linearly scales
``n_records`` records of a suite so that their mean meets that tolerance:

1. each record's spectrum SA (total acceleration, of the ``x`` component, which is the one
   a tower is excited with along its width) is computed at ``N_MATCH_PERIODS`` periods
   spaced logarithmically over the range, and its least-squares scale factor in log terms
   is ``f_i = exp(mean(ln(target / SA_i)))``, capped to ``scale_limits`` (0.25-4 by
   default: beyond a factor of 4 a record's amplitude, and with it the duration and pulse
   that go with its magnitude and distance, no longer represent the target earthquake);
2. the set is built greedily, each time adding the record that keeps the spread
   ``max(r) / min(r)`` of the ratio ``r(T) = mean / target`` smallest, then improved by
   swapping a chosen record with an unused one while the spread decreases;
3. a common factor ``c = sqrt(0.9 / min r * 1.3 / max r)`` (for the default tolerance)
   centres the mean inside the band in log terms; every factor becomes ``c f_i``, still
   within the caps.

The tolerance is met when ``1 - 0.10 <= r(T) <= 1 + 0.30`` at every period; otherwise the
best set is kept and :attr:`RecordSet.message` says what is wrong. Only the spectral shape
is matched: magnitude, distance, duration and the velocity pulse of near-source records,
which govern rocking, are not checked (``docs/hazard.md``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rockscreen.pipeline.errors import HazardError
from rockscreen.pipeline.hazard.matching import batch_spectrum
from rockscreen.pipeline.motion.spectra import response_spectrum
from rockscreen.solver.constants import G
from rockscreen.solver.docstrings import fill_doc

__all__ = [
    "N_MATCH_PERIODS",
    "SELECTION_DOCS",
    "RecordSet",
    "SuiteRecord",
    "check_options",
    "record_spectrum",
    "select_from_spectra",
    "select_in_order",
    "select_records",
    "set_message",
]

#: Number of log-spaced periods at which a set is matched.
N_MATCH_PERIODS = 30
#: Default smallest and largest individual scale factor [-].
SCALE_LIMITS = (0.25, 4.0)
#: Most swap passes of the local search.
MAX_SWAP_PASSES = 10

#: Options and result shared by :func:`select_records`, :func:`select_from_spectra` and
#: :func:`select_in_order`.
SELECTION_DOCS = {
    "suite": """
suite : sequence of SuiteRecord
    Candidate records.
""",
    "tolerance": """
tolerance : (float, float)
    Allowed relative departure of the mean below and above the target [-].
""",
    "scale_limits": """
scale_limits : (float, float)
    Smallest and largest individual factor [-].
""",
    "spectra": """
spectra_g : numpy.ndarray
    Their 5 % spectra [g], shape (records, periods).
periods_s : numpy.ndarray
    Matching periods [s].
target_g : numpy.ndarray
    Target [g] at ``periods_s``.
n_records : int
    Size of the set.
""",
    "returns": """
Returns
-------
RecordSet
    The best set found, whether or not it meets the tolerance.
""",
}


@dataclass(frozen=True)
class SuiteRecord:
    """One accelerogram of a suite (SI units)."""

    #: Identifier (``NET.STA.LOC.PREFIX`` for real records, ``SYN-...`` for synthetics).
    name: str
    #: First horizontal acceleration [m/s²]: the component the selection matches.
    acc_x_m_s2: np.ndarray
    #: Second horizontal and vertical acceleration [m/s²].
    acc_y_m_s2: np.ndarray | None
    acc_z_m_s2: np.ndarray | None
    #: Time step [s].
    dt_s: float
    #: Where the record comes from (file, or the generator and its seed).
    source: str


@dataclass(frozen=True)
class RecordSet:
    """A spectrum-compatible set of scaled records."""

    #: The chosen records, unscaled.
    records: tuple[SuiteRecord, ...]
    #: Factor applied to every component of each record [-].
    scale_factors: np.ndarray
    #: Matching periods [s].
    periods_s: np.ndarray
    #: Mean 5 % spectrum of the scaled ``x`` components and target, at ``periods_s`` [g].
    mean_sa_g: np.ndarray
    target_sa_g: np.ndarray
    #: Smallest and largest mean / target over ``periods_s`` [-].
    ratio_min: float
    ratio_max: float
    #: Whether ``1 + tolerance[0] <= ratio <= 1 + tolerance[1]`` everywhere.
    meets_tolerance: bool
    #: One line: the match, or why the tolerance is not met.
    message: str

    def scaled(self, index: int) -> SuiteRecord:
        """Return record ``index`` with every component multiplied by its factor."""
        record, factor = self.records[index], float(self.scale_factors[index])

        def scale(acc):
            return None if acc is None else acc * factor

        return SuiteRecord(
            name=record.name,
            acc_x_m_s2=record.acc_x_m_s2 * factor,
            acc_y_m_s2=scale(record.acc_y_m_s2),
            acc_z_m_s2=scale(record.acc_z_m_s2),
            dt_s=record.dt_s,
            source=f"{record.source} x {factor:.4g}",
        )


def record_spectrum(record: SuiteRecord, periods_s: np.ndarray, damping: float = 0.05):
    """Return the total-acceleration spectrum of a record's ``x`` component [g].

    Parameters
    ----------
    record : SuiteRecord
        The record.
    periods_s : numpy.ndarray
        Periods [s].
    damping : float
        Damping ratio [-].

    Returns
    -------
    numpy.ndarray
        SA [g] (:func:`rockscreen.pipeline.motion.spectra.response_spectrum`, divided by g).
    """
    sa, _ = response_spectrum(record.acc_x_m_s2, record.dt_s, periods_s, damping)
    return sa / G


def _target_on(periods: np.ndarray, target_periods: np.ndarray, target_sa: np.ndarray):
    """Interpolate the target linearly in log-log coordinates at ``periods``."""
    positive = (target_periods > 0) & (target_sa > 0)
    tp, ts = target_periods[positive], target_sa[positive]
    if tp.size < 2 or periods[0] < tp[0] * (1 - 1e-9) or periods[-1] > tp[-1] * (1 + 1e-9):
        raise HazardError(
            f"the target spectrum ({tp.size} positive ordinates, "
            f"{tp.min(initial=np.nan):g}-{tp.max(initial=np.nan):g} s) must cover the "
            f"matching range {periods[0]:g}-{periods[-1]:g} s"
        )
    order = np.argsort(tp)
    return np.exp(np.interp(np.log(periods), np.log(tp[order]), np.log(ts[order])))


@fill_doc(SELECTION_DOCS)
def check_options(n_records, period_range_s, tolerance, scale_limits) -> None:
    """Refuse invalid selection options with a :class:`HazardError` naming the option.

    Parameters
    ----------
    n_records : int
        Size of the set, >= 1.
    period_range_s : (float, float)
        Matching range [s], 0 < low < high.
    %(tolerance)s
    %(scale_limits)s
    """
    low, high = period_range_s
    if not (0 < low < high and math.isfinite(high)):
        raise HazardError(
            f"period_range_s={period_range_s!r} must be (low, high) s, 0 < low < high"
        )
    if not (-1 < tolerance[0] <= 0 <= tolerance[1]):
        raise HazardError(
            f"tolerance={tolerance!r} must be (below <= 0, above >= 0), e.g. (-0.1, 0.3)"
        )
    if not (0 < scale_limits[0] <= 1 <= scale_limits[1]):
        raise HazardError(f"scale_limits={scale_limits!r} must satisfy 0 < low <= 1 <= high")
    if int(n_records) != n_records or n_records < 1:
        raise HazardError(f"n_records={n_records!r} must be an integer >= 1")


@dataclass(frozen=True)
class _Problem:
    """What a candidate set is judged on: capped individual factors and the band."""

    spectra: np.ndarray  # (records, periods) [g]
    factors: np.ndarray  # individual least-squares factors, capped [-]
    target: np.ndarray  # [g]
    band: tuple[float, float]  # allowed mean/target, e.g. (0.9, 1.3)
    caps: tuple[float, float]  # smallest and largest factor [-]

    def common_factor(self, chosen: list[int]) -> float:
        """Factor centring mean/target in the band (log terms), limited by the caps."""
        ratio = self.ratio(chosen, 1.0)
        common = math.sqrt(self.band[0] / ratio.min() * self.band[1] / ratio.max())
        f = self.factors[chosen]
        return min(max(common, self.caps[0] / f.min()), self.caps[1] / f.max())

    def ratio(self, chosen: list[int], common: float) -> np.ndarray:
        """Mean of the scaled spectra over the target."""
        scaled = self.spectra[chosen] * self.factors[chosen, None] * common
        return scaled.mean(axis=0) / self.target

    def cost(self, chosen: list[int]) -> tuple[float, float]:
        """(log-distance outside the band after the common factor, log spread)."""
        ratio = self.ratio(chosen, self.common_factor(chosen))
        outside = max(0.0, math.log(self.band[0] / ratio.min()))
        outside += max(0.0, math.log(ratio.max() / self.band[1]))
        return outside, float(math.log(ratio.max() / ratio.min()))


def _choose(problem: _Problem, n: int) -> list[int]:
    """Greedy build, then swap improvements, minimising :meth:`_Problem.cost`."""
    chosen: list[int] = []
    pool = list(range(len(problem.spectra)))
    while len(chosen) < n:
        best = min(pool, key=lambda i: (problem.cost([*chosen, i]), i))
        chosen.append(best)
        pool.remove(best)
    current = problem.cost(chosen)
    for _ in range(MAX_SWAP_PASSES):
        improved = False
        for k in range(n):
            for j in list(pool):
                trial = chosen.copy()
                trial[k] = j
                value = problem.cost(trial)
                if value < current:
                    pool.append(chosen[k])
                    pool.remove(j)
                    chosen, current, improved = trial, value, True
        if not improved:
            break
    return chosen


@fill_doc(SELECTION_DOCS)
def select_records(
    suite,
    target_periods_s,
    target_sa_g,
    *,
    n_records: int = 7,
    period_range_s: tuple[float, float] = (0.15, 2.0),
    tolerance: tuple[float, float] = (-0.10, 0.30),
    damping: float = 0.05,
    scale_limits: tuple[float, float] = SCALE_LIMITS,
) -> RecordSet:
    """Select and scale a spectrum-compatible set of records (NTC 2018 §3.2.3.6).

    Parameters
    ----------
    %(suite)s
    target_periods_s, target_sa_g : array_like
        Target spectrum: periods [s] and ordinates [g]; it must cover ``period_range_s``.
    n_records : int
        Size of the set (7 by default: NTC 2018 §7.3.5 takes the mean response of at
        least 7 records); the whole suite when it is smaller (said in ``message``).
    period_range_s : (float, float)
        Matching range [s].
    %(tolerance)s
    damping : float
        Damping ratio of the spectra [-].
    %(scale_limits)s

    %(returns)s

    Raises
    ------
    HazardError
        For an empty suite, a target not covering the range or invalid options.
    """
    suite = _candidates(suite)
    check_options(n_records, period_range_s, tolerance, scale_limits)
    periods = np.geomspace(period_range_s[0], period_range_s[1], N_MATCH_PERIODS)
    target = _target_on(
        periods, np.atleast_1d(np.asarray(target_periods_s, float)), np.asarray(target_sa_g, float)
    )
    return select_from_spectra(
        suite,
        _spectra(suite, periods, damping),
        periods,
        target,
        n_records=n_records,
        tolerance=tolerance,
        scale_limits=scale_limits,
    )


def _candidates(suite) -> list:
    """Return the suite as a list, refusing an empty one."""
    suite = list(suite)
    if not suite:
        raise HazardError("the record suite is empty: no record to select")
    return suite


def _spectra(suite, periods: np.ndarray, damping: float) -> np.ndarray:
    """Spectra of the ``x`` components [g]: in one batch when the records are alike."""
    first = suite[0].acc_x_m_s2
    alike = all(
        r.dt_s == suite[0].dt_s and np.shape(r.acc_x_m_s2) == np.shape(first) for r in suite
    )
    if alike and np.ndim(first) == 1 and np.size(first) > 1 and 0.0 <= damping < 1.0:
        stack = np.array([r.acc_x_m_s2 for r in suite], dtype=float)
        if np.all(np.isfinite(stack)) and math.isfinite(suite[0].dt_s) and suite[0].dt_s > 0:
            return batch_spectrum(stack, suite[0].dt_s, periods, damping) / G
    return np.array([record_spectrum(r, periods, damping) for r in suite])


@fill_doc(SELECTION_DOCS)
def select_from_spectra(
    suite,
    spectra_g,
    periods_s,
    target_g,
    *,
    n_records: int = 7,
    tolerance: tuple[float, float] = (-0.10, 0.30),
    scale_limits: tuple[float, float] = SCALE_LIMITS,
) -> RecordSet:
    """Select and scale a set as :func:`select_records` does, from spectra already computed.

    Parameters
    ----------
    %(suite)s
    %(spectra)s
    %(tolerance)s
    %(scale_limits)s

    %(returns)s

    Raises
    ------
    HazardError
        For a zero spectral ordinate or invalid options.
    """
    suite = _candidates(suite)
    problem = _problem(suite, spectra_g, periods_s, target_g, n_records, tolerance, scale_limits)
    chosen = _choose(problem, min(int(n_records), len(suite)))
    return _scaled_set(suite, problem, chosen, periods_s, tolerance, n_records, note_caps=True)


@fill_doc(SELECTION_DOCS)
def select_in_order(
    suite,
    spectra_g,
    periods_s,
    target_g,
    *,
    n_records: int = 11,
    tolerance: tuple[float, float] = (-0.10, 0.30),
    scale_limits: tuple[float, float] = SCALE_LIMITS,
) -> RecordSet:
    """Select a set that keeps the suite's record-to-record variability, then scale it.

    Unlike :func:`select_from_spectra`, which builds the set that fits the target best (and
    so favours records alike), this takes the first ``n_records`` candidates in their
    order (for a random pool: a random sample) and swaps a chosen record for a later one
    only while the scaled mean lies outside the band, each swap the one that brings it
    closest; the scaling rule is the same (individual least-squares factors within the
    caps, times a common factor centring mean/target in the band).

    Parameters
    ----------
    %(suite)s
    %(spectra)s
    %(tolerance)s
    %(scale_limits)s

    %(returns)s
    """
    suite = _candidates(suite)
    problem = _problem(suite, spectra_g, periods_s, target_g, n_records, tolerance, scale_limits)
    n = min(int(n_records), len(suite))
    chosen = list(range(n))
    unused = list(range(n, len(suite)))
    outside = problem.cost(chosen)[0]
    while outside > 0.0 and unused:
        trials = [
            (problem.cost([*chosen[:k], j, *chosen[k + 1 :]])[0], k, j)
            for k in range(n)
            for j in unused
        ]
        value, k, j = min(trials)
        if value >= outside:
            break
        unused.remove(j)
        unused.append(chosen[k])
        chosen[k], outside = j, value
    return _scaled_set(suite, problem, chosen, periods_s, tolerance, n_records, note_caps=False)


def _problem(suite, spectra_g, periods_s, target_g, n_records, tolerance, scale_limits):
    """Check the options and spectra; return what a set of ``suite`` is judged on."""
    check_options(n_records, (periods_s[0], periods_s[-1]), tolerance, scale_limits)
    spectra = np.asarray(spectra_g, float)
    if np.any(spectra <= 0):
        bad = suite[int(np.nonzero(np.any(spectra <= 0, axis=1))[0][0])].name
        raise HazardError(f"record {bad!r} has a zero spectral ordinate in the range")
    caps = (float(scale_limits[0]), float(scale_limits[1]))
    factors = np.clip(np.exp(np.mean(np.log(target_g / spectra), axis=1)), *caps)
    low, high = 1.0 + tolerance[0], 1.0 + tolerance[1]
    return _Problem(spectra, factors, target_g, (low, high), caps)


def _scaled_set(suite, problem, chosen, periods_s, tolerance, n_records, *, note_caps):
    """Scale the chosen records (their factors times the common one) into a RecordSet."""
    n, (low, high), caps = len(chosen), problem.band, problem.caps
    scale = problem.factors[chosen] * problem.common_factor(chosen)
    mean = (problem.spectra[chosen] * scale[:, None]).mean(axis=0)
    ratio = mean / problem.target
    meets = bool(ratio.min() >= low - 1e-12 and ratio.max() <= high + 1e-12)
    message = set_message(meets, ratio, periods_s, tolerance, n, n_records, len(suite))
    capped = int(np.sum(np.isclose(scale, caps[0]) | np.isclose(scale, caps[1])))
    if note_caps and not meets and capped:
        message += (
            f"; {capped} of {n} factors at the limits {caps[0]:g}-{caps[1]:g} (the suite's "
            "records are too weak or too strong for this target)"
        )
    return RecordSet(
        records=tuple(suite[i] for i in chosen),
        scale_factors=scale,
        periods_s=periods_s,
        mean_sa_g=mean,
        target_sa_g=problem.target,
        ratio_min=float(ratio.min()),
        ratio_max=float(ratio.max()),
        meets_tolerance=meets,
        message=message,
    )


def set_message(meets, ratio, periods, tolerance, n, wanted, available) -> str:
    """Return what a set's check says: its count, mean/target range and whether it meets the band.

    Parameters
    ----------
    meets : bool
        Whether the mean/target ratio lies in the band at every period.
    ratio : numpy.ndarray
        Mean/target at ``periods`` [-].
    periods : numpy.ndarray
        Periods of the check [s].
    tolerance : (float, float)
        Allowed relative departure below and above the target [-].
    n, wanted, available : int
        Records in the set, asked for, and in the suite.

    Returns
    -------
    str
    """
    band = f"{1 + tolerance[0]:.2f}-{1 + tolerance[1]:.2f}"
    text = (
        f"{n} records, mean/target {ratio.min():.3f}-{ratio.max():.3f} over "
        f"{periods[0]:g}-{periods[-1]:g} s (allowed {band}, NTC 2018 §3.2.3.6)"
    )
    if n < wanted:
        text += f"; only {available} records in the suite, {wanted} wanted"
    if meets:
        return "meets the tolerance: " + text
    worst = int(np.argmax(np.maximum(1 + tolerance[0] - ratio, ratio - 1 - tolerance[1])))
    return (
        f"does not meet the tolerance (worst at T={periods[worst]:.3g} s, ratio "
        f"{ratio[worst]:.3f}); best set kept: " + text
    )
