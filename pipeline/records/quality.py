"""Quality checks of an accelerogram, each failure with its reason.

The checks follow the spirit of USGS gmprocess's screening (minimum sampling rate,
minimum duration, clipping) plus the basic sanity checks any integrator needs (finite
samples, a signal that is not flat). Each returns a :class:`Finding`; processing refuses a
trace with findings by raising :class:`QualityError`, which carries them.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass

import numpy as np

from pipeline.errors import ProcessingError


@dataclass(frozen=True)
class QualityLimits:
    """Thresholds of the quality checks.

    Attributes
    ----------
    min_sampling_rate_hz : float
        Lowest acceptable sampling rate [Hz] (gmprocess's default minimum, 20 Hz).
    min_duration_s : float
        Shortest acceptable record, ``npts * dt`` [s].
    flat_tolerance : float
        A record whose peak-to-peak amplitude is at most this is flat [m/s^2]
        (far below the least significant bit of any strong-motion digitiser).
    clip_run : int
        A record is clipped when at least this many consecutive samples sit at its
        positive or negative extreme (a saturated sensor or digitiser plateaus there).
    clip_tolerance : float
        Relative distance from the extreme that counts as "at" it [-].
    """

    min_sampling_rate_hz: float = 20.0
    min_duration_s: float = 5.0
    flat_tolerance: float = 1e-9
    clip_run: int = 5
    clip_tolerance: float = 1e-6

    def __post_init__(self) -> None:
        for name in ("min_sampling_rate_hz", "min_duration_s", "flat_tolerance", "clip_tolerance"):
            value = getattr(self, name)
            if not (np.isfinite(value) and value >= 0):
                raise ProcessingError(f"{name}={value!r} must be a finite number >= 0")
        if int(self.clip_run) != self.clip_run or self.clip_run < 2:
            raise ProcessingError(f"clip_run={self.clip_run!r} must be an integer >= 2")

    def to_dict(self) -> dict:
        """Return the limits as a plain dict (for provenance and archives)."""
        return asdict(self)


@dataclass(frozen=True)
class Finding:
    """One failed quality check.

    Attributes
    ----------
    check : str
        ``sampling_rate``, ``non_finite``, ``too_short``, ``flat`` or ``clipped``.
    reason : str
        A sentence with the measured value and the limit.
    """

    check: str
    reason: str

    def __str__(self) -> str:
        return f"{self.check}: {self.reason}"


class QualityError(ProcessingError):
    """A trace failed quality checks; ``findings`` lists why."""

    def __init__(self, message: str, findings: list[Finding]):
        super().__init__(message)
        self.findings = list(findings)


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


def check_array(acc, dt: float, limits: QualityLimits | None = None) -> list[Finding]:
    """Run every quality check on an acceleration array.

    Parameters
    ----------
    acc : array_like, shape (n,)
        Acceleration [m/s^2].
    dt : float
        Sampling interval [s].
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
    if values.size == 0 or np.ptp(values) <= limits.flat_tolerance:
        ptp = float(np.ptp(values)) if values.size else 0.0
        findings.append(
            Finding(
                "flat",
                f"flat signal: peak-to-peak {ptp:.3g} m/s^2 is at most {limits.flat_tolerance:g}",
            )
        )
    elif values.size == acc.size:
        clipped = _clipped(values - np.median(values), limits)
        if clipped is not None:
            findings.append(clipped)
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
    "Finding",
    "QualityError",
    "QualityLimits",
    "check_array",
    "check_trace",
    "require_quality",
]
