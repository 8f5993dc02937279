"""Quality checks of an accelerogram, each failure with its reason.

The checks follow the spirit of USGS gmprocess's screening (minimum sampling rate,
minimum duration, clipping) plus the basic sanity checks any integrator needs (finite
samples, a signal that is not flat) and physical plausibility: one bad sample must not
decide a verdict. Each returns a :class:`Finding`; processing refuses a trace with findings
by raising :class:`rockscreen.pipeline.errors.QualityError`, which carries them.

Plausibility (also applied when a file is read, :func:`plausibility_findings`):

* **peak**: ``max |a - median(a)|`` above :data:`MAX_PGA_M_S2` (5 g) is refused. The largest
  accelerations ever recorded are about 4 g: 4.36 g (three-component vector; 3.9 g
  vertical) at KiK-net IWTH25 in the 2008 Iwate-Miyagi Nairiku earthquake (Aoi, Kunugi &
  Fujiwara 2008, *Science* 322:727-730, "Trampoline effect in extreme ground motion").
  Values beyond are raw counts, cm/s^2 read as m/s^2 or a corrupt sample.
* **spike**: a sample of at least ``spike_floor`` times the record's peak that exceeds
  ``spike_ratio`` times the largest of its ``spike_half_window`` neighbours on each side
  is refused as an isolated corrupt sample (a flipped bit). Ground acceleration is
  band-limited: at strong-motion sampling rates (50-200 Hz) a real peak has neighbours of
  comparable size. On all real records of the project's test data (miniSEED, SAC, K-NET,
  ESM, AT2; 50-200 Hz) the largest ratio is 2.4 (a 50 Hz SAC vertical), far below the
  default 8.
* **vertical/horizontal** (:func:`vertical_ratio_flag`, a flag, not a refusal): a vertical
  peak above ``max_vertical_ratio`` (2) times the larger horizontal peak. Near-source
  verticals can exceed the horizontals, rarely by twice; a larger ratio usually means a
  gain or channel mix-up (the ITACA record of station AQA for L'Aquila 2009 has
  horizontals a third of its vertical, a known defect). Flags go to
  ``trace.stats.rockscreen["quality_flags"]`` and
  :attr:`rockscreen.pipeline.records.grouping.Record.quality_flags`.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from rockscreen.pipeline.errors import ProcessingError, QualityError
from rockscreen.solver.constants import G
from rockscreen.solver.docstrings import fill_doc

#: Largest plausible peak ground acceleration [m/s^2] (5 g; see the module docstring).
MAX_PGA_M_S2 = 5.0 * G

#: The opening of the Parameters section of the functions that take a record as an array,
#: for :func:`solver.docstrings.fill_doc` (also used by :mod:`pipeline.processing.steps`).
RECORD_DOCS = {
    "record_parameters": """
Parameters
----------
acc : array_like, shape (n,)
    Acceleration [m/s^2].
dt : float
    Sampling interval [s].
""",
}


@dataclass(frozen=True)
class QualityLimits:
    """Thresholds of the quality checks."""

    #: Lowest acceptable sampling rate [Hz] (gmprocess's default minimum, 20 Hz).
    min_sampling_rate_hz: float = 20.0
    #: Shortest acceptable record, ``npts * dt`` [s].
    min_duration_s: float = 5.0
    #: A record whose peak-to-peak amplitude is at most this is flat [m/s^2] (far below the least
    #: significant bit of any strong-motion digitiser).
    flat_tolerance: float = 1e-9
    #: A record is clipped when at least this many consecutive samples sit at its positive or
    #: negative extreme (a saturated sensor or digitiser plateaus there).
    clip_run: int = 5
    #: Relative distance from the extreme that counts as "at" it [-].
    clip_tolerance: float = 1e-6
    #: Largest plausible ``max |a - median(a)|`` [m/s^2] (default 5 g).
    max_peak_m_s2: float = MAX_PGA_M_S2
    #: A sample above this many times its neighbours' envelope is a spike [-].
    spike_ratio: float = 8.0
    #: Neighbours on each side that form the envelope [samples].
    spike_half_window: int = 3
    #: Only samples of at least this fraction of the record's peak can be spikes [-].
    spike_floor: float = 0.25
    #: Vertical peak over the larger horizontal peak above which a record is flagged [-].
    max_vertical_ratio: float = 2.0

    def __post_init__(self) -> None:
        for name in ("min_sampling_rate_hz", "min_duration_s", "flat_tolerance", "clip_tolerance"):
            value = getattr(self, name)
            if not (np.isfinite(value) and value >= 0):
                raise ProcessingError(f"{name}={value!r} must be a finite number >= 0")
        for name in ("max_peak_m_s2", "spike_ratio", "max_vertical_ratio"):
            value = getattr(self, name)
            if not (np.isfinite(value) and value > 0):
                raise ProcessingError(f"{name}={value!r} must be a finite number > 0")
        if not (np.isfinite(self.spike_floor) and 0 <= self.spike_floor <= 1):
            raise ProcessingError(f"spike_floor={self.spike_floor!r} must be in [0, 1]")
        if int(self.clip_run) != self.clip_run or self.clip_run < 2:
            raise ProcessingError(f"clip_run={self.clip_run!r} must be an integer >= 2")
        half = self.spike_half_window
        if int(half) != half or half < 1:
            raise ProcessingError(f"spike_half_window={half!r} must be an integer >= 1")

    def to_dict(self) -> dict:
        """Return the limits as a plain dict (for provenance and archives)."""
        return asdict(self)


@dataclass(frozen=True)
class Finding:
    """One failed quality check."""

    #: ``sampling_rate``, ``non_finite``, ``too_short``, ``flat``, ``clipped``, ``implausible_peak``
    #: or ``spike``.
    check: str
    #: A sentence with the measured value and the limit.
    reason: str

    def __str__(self) -> str:
        return f"{self.check}: {self.reason}"


def _longest_run(mask: np.ndarray) -> int:
    """Length of the longest run of True in a boolean array."""
    if not mask.any():
        return 0
    padded = np.concatenate(([0], mask.view(np.int8), [0]))
    edges = np.flatnonzero(np.diff(padded))
    return int((edges[1::2] - edges[::2]).max())


def _clipped(acc: np.ndarray, limits: QualityLimits) -> Finding | None:
    for sign, name in ((1.0, "positive"), (-1.0, "negative")):
        extreme = float((sign * acc).max())
        if extreme <= 0:
            continue
        at_extreme = sign * acc >= extreme * (1.0 - limits.clip_tolerance)
        run = _longest_run(at_extreme)
        if run >= limits.clip_run:
            return Finding(
                "clipped",
                f"{run} consecutive samples sit at the {name} extreme {sign * extreme:.6g} "
                f"(limit: fewer than {limits.clip_run}); the sensor or digitiser saturated",
            )
    return None


def peak_finding(acc: np.ndarray, limits: QualityLimits) -> Finding | None:
    """``implausible_peak`` when ``max |a - median(a)|`` exceeds ``limits.max_peak_m_s2``.

    ``acc`` [m/s^2] must be finite.
    """
    if acc.size == 0:
        return None
    peak = float(np.abs(acc - np.median(acc)).max())
    if peak <= limits.max_peak_m_s2:
        return None
    return Finding(
        "implausible_peak",
        f"peak {peak:.5g} m/s^2 ({peak / G:.3g} g) is not a plausible ground acceleration "
        f"(limit {limits.max_peak_m_s2:.4g} m/s^2 = {limits.max_peak_m_s2 / G:.3g} g; "
        "the largest ever recorded is about 4 g)",
    )


def _neighbour_envelope(amplitude: np.ndarray, half: int) -> np.ndarray:
    """Largest amplitude among the ``half`` samples on each side of every sample."""
    envelope = np.zeros_like(amplitude)
    for k in range(1, half + 1):
        np.maximum(envelope[k:], amplitude[:-k], out=envelope[k:])
        np.maximum(envelope[:-k], amplitude[k:], out=envelope[:-k])
    return envelope


def spike_finding(acc: np.ndarray, dt: float, limits: QualityLimits) -> Finding | None:
    """``spike`` when an isolated sample towers over its neighbours (see the module docstring).

    ``acc`` [m/s^2] must be finite; ``dt`` [s] only dates the spike in the reason.
    """
    if acc.size < 2:
        return None
    amplitude = np.abs(acc - np.median(acc))
    peak = float(amplitude.max())
    if peak == 0.0:
        return None
    envelope = _neighbour_envelope(amplitude, int(limits.spike_half_window))
    spikes = np.flatnonzero(
        (amplitude >= limits.spike_floor * peak) & (amplitude > limits.spike_ratio * envelope)
    )
    if spikes.size == 0:
        return None
    worst = int(spikes[np.argmax(amplitude[spikes])])
    return Finding(
        "spike",
        f"{spikes.size} isolated spike(s); sample {worst} (t = {worst * dt:.6g} s) is "
        f"{acc[worst]:.5g} m/s^2, more than {limits.spike_ratio:g} times the largest of its "
        f"{limits.spike_half_window} neighbours on each side ({envelope[worst]:.3g} m/s^2): "
        "a corrupt sample (flipped bit?)",
    )


@fill_doc(RECORD_DOCS)
def plausibility_findings(acc, dt: float, limits: QualityLimits | None = None) -> list[Finding]:
    """Check that a file's samples can be ground acceleration at all (applied on reading).

    %(record_parameters)s
    limits : QualityLimits, optional
        Thresholds (``max_peak_m_s2``, ``spike_*``).

    Returns
    -------
    list of Finding
        ``non_finite``, else ``implausible_peak`` and/or ``spike``; empty when plausible.
    """
    limits = limits or QualityLimits()
    acc = np.asarray(acc, dtype=np.float64)
    finite = np.isfinite(acc)
    if not finite.all():
        first = int(np.flatnonzero(~finite)[0])
        return [
            Finding(
                "non_finite",
                f"{int((~finite).sum())} of {acc.size} samples are NaN or inf "
                f"(first: sample {first}, {float(acc[first])!r})",
            )
        ]
    with np.errstate(over="ignore", invalid="ignore"):  # 1e308 samples: inf compares right
        found = [peak_finding(acc, limits), spike_finding(acc, dt, limits)]
    return [finding for finding in found if finding is not None]


def vertical_ratio_flag(
    horizontal_peaks, vertical_peak: float, limits: QualityLimits | None = None
) -> str | None:
    """Flag a vertical peak implausibly larger than the horizontals (not a refusal).

    Parameters
    ----------
    horizontal_peaks : iterable of float
        Peak |a| of each horizontal component [m/s^2].
    vertical_peak : float
        Peak |a| of the vertical component [m/s^2].
    limits : QualityLimits, optional
        ``max_vertical_ratio``.

    Returns
    -------
    str or None
        ``"vertical_ratio: ..."`` with both peaks and the ratio, or None.
    """
    limits = limits or QualityLimits()
    horizontal = max((float(p) for p in horizontal_peaks), default=0.0)
    if not (np.isfinite(vertical_peak) and vertical_peak > 0):
        return None
    if horizontal > 0 and vertical_peak <= limits.max_vertical_ratio * horizontal:
        return None
    ratio = vertical_peak / horizontal if horizontal > 0 else float("inf")
    return (
        f"vertical_ratio: vertical peak {vertical_peak:.4g} m/s^2 is {ratio:.3g} times the "
        f"larger horizontal peak {horizontal:.4g} m/s^2 (flag above "
        f"{limits.max_vertical_ratio:g}); check the horizontals' gain and channel codes"
    )


@fill_doc(RECORD_DOCS)
def check_array(acc, dt: float, limits: QualityLimits | None = None) -> list[Finding]:
    """Run every quality check on an acceleration array.

    %(record_parameters)s
    limits : QualityLimits, optional
        Thresholds; the defaults of :class:`QualityLimits` when omitted.

    Returns
    -------
    list of Finding
        Empty when the record passes.
    """
    limits = limits or QualityLimits()
    acc = np.asarray(acc, dtype=np.float64)
    if not (np.isfinite(dt) and dt > 0):
        raise ProcessingError(f"dt={dt!r} must be a finite number > 0 [s]")
    findings = []
    rate = 1.0 / dt
    if rate < limits.min_sampling_rate_hz:
        findings.append(
            Finding(
                "sampling_rate",
                f"sampling rate {rate:.6g} Hz is below the minimum "
                f"{limits.min_sampling_rate_hz:g} Hz",
            )
        )
    finite = np.isfinite(acc)
    if not finite.all():
        findings.append(
            Finding("non_finite", f"{int((~finite).sum())} of {acc.size} samples are NaN or inf")
        )
    duration = acc.size * dt
    if duration < limits.min_duration_s:
        findings.append(
            Finding(
                "too_short",
                f"duration {duration:.6g} s ({acc.size} samples) is shorter than the minimum "
                f"{limits.min_duration_s:g} s",
            )
        )
    values = acc[finite]
    with np.errstate(over="ignore"):  # the span of +-1e308 samples is inf: not flat
        span = float(np.ptp(values)) if values.size else 0.0
    if values.size == 0 or span <= limits.flat_tolerance:
        findings.append(
            Finding(
                "flat",
                f"flat signal: peak-to-peak {span:.3g} m/s^2 is at most {limits.flat_tolerance:g}",
            )
        )
    elif values.size == acc.size:
        clipped = _clipped(values - np.median(values), limits)
        if clipped is not None:
            findings.append(clipped)
        findings.extend(plausibility_findings(values, dt, limits))
    return findings


def check_trace(trace, limits: QualityLimits | None = None) -> list[Finding]:
    """Run :func:`check_array` on an ObsPy trace (data [m/s^2], ``stats.delta`` [s])."""
    return check_array(trace.data, float(trace.stats.delta), limits)


def require_quality(trace, limits: QualityLimits | None = None) -> None:
    """Raise :class:`QualityError` naming the trace and every reason when a check fails."""
    findings = check_trace(trace, limits)
    if findings:
        reasons = "; ".join(str(finding) for finding in findings)
        raise QualityError(f"{trace.id}: refused by quality checks: {reasons}", findings)


__all__ = [
    "MAX_PGA_M_S2",
    "Finding",
    "QualityLimits",
    "RECORD_DOCS",
    "check_array",
    "check_trace",
    "peak_finding",
    "plausibility_findings",
    "require_quality",
    "spike_finding",
    "vertical_ratio_flag",
]
