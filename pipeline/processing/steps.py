"""Strong-motion processing with provenance: demean, detrend, taper, band-pass, resample.

Three layers, as in ObsPy: pure functions on arrays (``demean``, ``detrend_linear``,
``taper``, ``bandpass``, ``resample``, ``baseline_polynomial``); :func:`process_trace`,
which applies them to a copy of a trace and records every step with its parameters in
``stats.rockscreen["provenance"]``; :func:`process_stream`, the loop that reports and
skips failing traces.

Defaults (:class:`ProcessingConfig`) follow USGS gmprocess and ITACA practice: remove the
mean and a linear trend, a 5 % cosine (Tukey) taper at each end, then a zero-phase
(acausal: forward and backward) Butterworth band-pass, 0.1-20 Hz, order 4 per pass.
No silent fallbacks: a corner at or above Nyquist is a :class:`ProcessingError`, never
a quiet switch to a high-pass.
"""

from __future__ import annotations

import copy
from dataclasses import asdict, dataclass, field
from fractions import Fraction

import numpy as np
from obspy import Stream, Trace
from obspy.core.util import AttribDict
from scipy import signal
from scipy.integrate import cumulative_trapezoid

from rockscreen.pipeline.errors import ProcessingError, RockscreenError
from rockscreen.pipeline.records.quality import RECORD_DOCS, QualityLimits, require_quality
from rockscreen.solver.docstrings import fill_doc

DETREND_TYPES = ("linear", "constant")


@dataclass(frozen=True)
class ProcessingConfig:
    """How records are processed (every field is recorded in the provenance)."""

    #: Remove the mean first (default True).
    demean: bool = True
    #: ({"linear", "constant"} or None) Remove a least-squares line (default ``"linear"``) or the
    #: mean again.
    detrend: str | None = "linear"
    #: Length of the cosine (Tukey) taper at *each* end, as a fraction of the record [-] (default
    #: 0.05, gmprocess's 5 %); 0 disables it.
    taper_fraction: float = 0.05
    #: Band-pass low corner [Hz] (default 0.1 Hz). None: low-pass only -- an explicit choice, never
    #: a fallback.
    freqmin_hz: float | None = 0.1
    #: Band-pass high corner [Hz] (default 20 Hz: below the 25 Hz Nyquist of the classic 50 Hz
    #: records such as El Centro 1940). None: high-pass only. A corner at or above the record's
    #: Nyquist frequency is a :class:`ProcessingError`.
    freqmax_hz: float | None = 20.0
    #: Butterworth order of each pass (default 4). Zero-phase filtering runs it forward and
    #: backward: the amplitude response is the order-4 response squared.
    filter_order: int = 4
    #: Acausal (forward-backward, no phase shift; ITACA and gmprocess practice) when True (default),
    #: causal otherwise.
    zerophase: bool = True
    #: New sampling rate [Hz] after filtering (polyphase, with its anti-alias filter); None
    #: (default) keeps the record's rate. Down-sampling so that ``freqmax_hz`` reaches the new
    #: Nyquist is an error.
    resample_hz: float | None = None
    #: Fit a polynomial (no constant or linear term) to the displacement and remove its second
    #: derivative from the acceleration (gmprocess's baseline correction); default False.
    baseline_correction: bool = False
    #: Degree of that polynomial (default 6, as gmprocess).
    baseline_order: int = 6
    #: Refuse traces failing :mod:`rockscreen.pipeline.records.quality` (default True).
    check_quality: bool = True
    #: Thresholds of the quality checks.
    quality: QualityLimits = field(default_factory=QualityLimits)

    def __post_init__(self) -> None:
        if self.detrend not in (*DETREND_TYPES, None):
            raise ProcessingError(
                f"detrend={self.detrend!r} is not allowed; use 'linear', 'constant' or None"
            )
        if not (0.0 <= self.taper_fraction <= 0.5):
            raise ProcessingError(
                f"taper_fraction={self.taper_fraction!r} must lie in [0, 0.5] (per end)"
            )
        for name in ("freqmin_hz", "freqmax_hz", "resample_hz"):
            value = getattr(self, name)
            if value is not None and not (np.isfinite(value) and value > 0):
                raise ProcessingError(f"{name}={value!r} must be a number > 0 [Hz] or None")
        if (
            self.freqmin_hz is not None
            and self.freqmax_hz is not None
            and self.freqmin_hz >= self.freqmax_hz
        ):
            raise ProcessingError(
                f"freqmin_hz={self.freqmin_hz} must be below freqmax_hz={self.freqmax_hz}"
            )
        if int(self.filter_order) != self.filter_order or not 1 <= self.filter_order <= 10:
            raise ProcessingError(
                f"filter_order={self.filter_order!r} must be an integer from 1 to 10"
            )
        if int(self.baseline_order) != self.baseline_order or not 2 <= self.baseline_order <= 10:
            raise ProcessingError(
                f"baseline_order={self.baseline_order!r} must be an integer from 2 to 10"
            )

    def to_dict(self) -> dict:
        """Return the configuration as a plain, JSON-ready dict."""
        return asdict(self)


# --- array layer -------------------------------------------------------------------------


def demean(acc) -> np.ndarray:
    """Return ``acc`` minus its mean (array of shape (n,), any units)."""
    acc = np.asarray(acc, dtype=np.float64)
    return acc - acc.mean()


def detrend_linear(acc) -> np.ndarray:
    """Return ``acc`` minus its least-squares straight line (shape (n,))."""
    return signal.detrend(np.asarray(acc, dtype=np.float64), type="linear")


def taper(acc, fraction: float = 0.05) -> np.ndarray:
    """Apply a cosine (Tukey) taper of ``fraction`` of the length at each end.

    Parameters
    ----------
    acc : array_like, shape (n,)
        Signal.
    fraction : float
        Taper length at each end as a fraction of ``n`` (0 to 0.5) [-].

    Returns
    -------
    numpy.ndarray, shape (n,)
        The tapered signal (first and last samples zero when ``fraction > 0``).
    """
    acc = np.asarray(acc, dtype=np.float64)
    if not 0.0 <= fraction <= 0.5:
        raise ProcessingError(f"taper fraction={fraction!r} must lie in [0, 0.5] (per end)")
    return acc * signal.windows.tukey(acc.size, alpha=2.0 * fraction)


def bandpass(
    acc,
    dt: float,
    freqmin: float | None,
    freqmax: float | None,
    *,
    order: int = 4,
    zerophase: bool = True,
) -> np.ndarray:
    """Butterworth band-pass (or an explicitly requested high- or low-pass).

    Parameters
    ----------
    acc : array_like, shape (n,)
        Signal sampled every ``dt``.
    dt : float
        Sampling interval [s].
    freqmin, freqmax : float or None
        Corners [Hz]; None drops that side (``freqmin=None``: low-pass;
        ``freqmax=None``: high-pass). Both None returns the signal unchanged.
    order : int
        Butterworth order of each pass.
    zerophase : bool
        Filter forward then backward (no phase shift, squared amplitude response).

    Returns
    -------
    numpy.ndarray, shape (n,)

    Raises
    ------
    ProcessingError
        If a corner is at or above the Nyquist frequency ``0.5/dt`` (no silent change of
        filter type), not positive, or ``freqmin >= freqmax``.
    """
    acc = np.asarray(acc, dtype=np.float64)
    nyquist = 0.5 / dt
    for name, corner in (("freqmin", freqmin), ("freqmax", freqmax)):
        if corner is None:
            continue
        if not corner > 0:
            raise ProcessingError(f"{name}={corner!r} must be > 0 Hz")
        if corner >= nyquist:
            raise ProcessingError(
                f"{name}={corner:g} Hz is at or above the Nyquist frequency {nyquist:g} Hz "
                f"(dt={dt:g} s); lower it below {nyquist:g} Hz or resample the record "
                "(rockscreen never turns a band-pass into a high-pass silently)"
            )
    if freqmin is not None and freqmax is not None and freqmin >= freqmax:
        raise ProcessingError(f"freqmin={freqmin:g} Hz must be below freqmax={freqmax:g} Hz")
    if freqmin is None and freqmax is None:
        return acc.copy()
    if freqmax is None:
        sos = signal.butter(order, freqmin / nyquist, btype="highpass", output="sos")
    elif freqmin is None:
        sos = signal.butter(order, freqmax / nyquist, btype="lowpass", output="sos")
    else:
        sos = signal.butter(order, [freqmin / nyquist, freqmax / nyquist], "bandpass", output="sos")
    filtered = signal.sosfilt(sos, acc)
    if zerophase:
        # As ObsPy's zerophase: the same causal filter run again on the reversed output.
        filtered = signal.sosfilt(sos, filtered[::-1])[::-1]
    return filtered


def resample(acc, dt: float, rate_hz: float) -> tuple[np.ndarray, float]:
    """Resample to ``rate_hz`` with a polyphase filter (anti-aliasing included).

    Parameters
    ----------
    acc : array_like, shape (n,)
        Signal sampled every ``dt`` [s].
    dt : float
        Sampling interval [s].
    rate_hz : float
        New sampling rate [Hz]; its ratio to ``1/dt`` must be a fraction with a
        denominator of at most 1000 (e.g. 200 -> 100, 100 -> 250 Hz).

    Returns
    -------
    acc : numpy.ndarray
        Resampled signal.
    dt : float
        New sampling interval ``1/rate_hz`` [s].
    """
    acc = np.asarray(acc, dtype=np.float64)
    ratio = Fraction(rate_hz * dt).limit_denominator(1000)
    if ratio <= 0 or abs(float(ratio) - rate_hz * dt) > 1e-9 * rate_hz * dt:
        raise ProcessingError(
            f"resample_hz={rate_hz:g} Hz: its ratio to the record's {1 / dt:g} Hz is not a "
            "simple fraction (denominator <= 1000)"
        )
    if ratio == 1:
        return acc.copy(), dt
    out = signal.resample_poly(acc, ratio.numerator, ratio.denominator)
    return out, 1.0 / rate_hz


@fill_doc(RECORD_DOCS)
def baseline_polynomial(acc, dt: float, order: int = 6) -> np.ndarray:
    """Remove the second derivative of a polynomial fitted to the displacement.

    The displacement (trapezoidal double integral of ``acc``, starting at rest) is fitted
    in least squares by ``sum_{k=2..order} c_k t^k`` -- no constant or linear term, so the
    initial displacement and velocity stay zero -- and ``sum k (k-1) c_k t^(k-2)`` is
    subtracted from ``acc`` (gmprocess's ``correct_baseline``).

    %(record_parameters)s
    order : int
        Polynomial degree (>= 2).

    Returns
    -------
    numpy.ndarray, shape (n,)
        Corrected acceleration [m/s^2].
    """
    acc = np.asarray(acc, dtype=np.float64)
    t = np.arange(acc.size) * dt
    velocity = cumulative_trapezoid(acc, dx=dt, initial=0.0)
    displacement = cumulative_trapezoid(velocity, dx=dt, initial=0.0)
    # Scale time to [0, 1] so the Vandermonde columns stay well conditioned.
    span = t[-1] if t[-1] > 0 else 1.0
    tau = t / span
    powers = np.arange(2, order + 1)
    design = tau[:, None] ** powers[None, :]
    coef, *_ = np.linalg.lstsq(design, displacement, rcond=None)
    second = (powers * (powers - 1) * coef)[None, :] * tau[:, None] ** (powers - 2)[None, :]
    return acc - second.sum(axis=1) / span**2


# --- trace layer -------------------------------------------------------------------------


def _provenance(trace: Trace) -> list:
    stats = trace.stats
    if "rockscreen" not in stats:
        stats.rockscreen = AttribDict(provenance=[])
    stats.rockscreen.setdefault("provenance", [])
    return stats.rockscreen["provenance"]


def process_trace(trace: Trace, config: ProcessingConfig | None = None) -> Trace:
    """Return a processed copy of ``trace``; every step is appended to its provenance.

    Steps, in order (each only when enabled): quality checks (recorded with their
    limits), demean, detrend, taper, band-pass, resample, baseline correction.

    Parameters
    ----------
    trace : obspy.Trace
        Acceleration [m/s^2], as returned by :func:`rockscreen.pipeline.records.io.read_stream`.
    config : ProcessingConfig, optional
        Defaults of :class:`ProcessingConfig` when omitted.

    Returns
    -------
    obspy.Trace
        The processed copy (``trace`` itself is untouched); its
        ``stats.rockscreen["provenance"]`` ends with one dict per step
        (``{"step": "bandpass", "freqmin_hz": 0.1, ...}``).

    Raises
    ------
    ProcessingError
        If the trace fails quality checks (:class:`~rockscreen.pipeline.errors.QualityError`, with
        ``findings``) or a step cannot be applied (e.g. a corner at or above Nyquist).
    """
    config = config or ProcessingConfig()
    if config.check_quality:
        require_quality(trace, config.quality)
    out = trace.copy()
    provenance = _provenance(out)
    dt = float(out.stats.delta)
    data = np.asarray(out.data, dtype=np.float64)

    def record(step: str, **params) -> None:
        provenance.append({"step": step, **params})

    if config.check_quality:
        record("quality_checks", passed=True, **config.quality.to_dict())
    try:
        if config.demean:
            data = demean(data)
            record("demean")
        if config.detrend == "linear":
            data = detrend_linear(data)
            record("detrend", type="linear")
        elif config.detrend == "constant":
            data = demean(data)
            record("detrend", type="constant")
        if config.taper_fraction > 0:
            data = taper(data, config.taper_fraction)
            record("taper", type="tukey (cosine)", fraction_per_end=config.taper_fraction)
        if config.freqmin_hz is not None or config.freqmax_hz is not None:
            data = bandpass(
                data,
                dt,
                config.freqmin_hz,
                config.freqmax_hz,
                order=config.filter_order,
                zerophase=config.zerophase,
            )
            kind = {
                (True, True): "bandpass",
                (True, False): "highpass",
                (False, True): "lowpass",
            }[(config.freqmin_hz is not None, config.freqmax_hz is not None)]
            record(
                "filter",
                type=f"butterworth {kind}",
                freqmin_hz=config.freqmin_hz,
                freqmax_hz=config.freqmax_hz,
                order=config.filter_order,
                zerophase=config.zerophase,
            )
        if config.resample_hz is not None:
            new_nyquist = 0.5 * config.resample_hz
            if config.freqmax_hz is not None and config.freqmax_hz >= new_nyquist:
                raise ProcessingError(
                    f"resample_hz={config.resample_hz:g} Hz puts the Nyquist frequency "
                    f"({new_nyquist:g} Hz) at or below freqmax_hz={config.freqmax_hz:g} Hz"
                )
            old_rate = 1.0 / dt
            data, dt = resample(data, dt, config.resample_hz)
            record("resample", from_hz=old_rate, to_hz=config.resample_hz, method="polyphase")
        if config.baseline_correction:
            data = baseline_polynomial(data, dt, config.baseline_order)
            record("baseline_correction", type="polynomial", order=config.baseline_order)
    except ProcessingError as exc:
        raise ProcessingError(f"{trace.id}: {exc}") from exc
    out.data = data
    out.stats.delta = dt
    return out


def process_stream(
    stream: Stream, config: ProcessingConfig | None = None
) -> tuple[Stream, list[tuple[str, str]]]:
    """Process every trace; report, rather than stop at, the traces that fail.

    Parameters
    ----------
    stream : obspy.Stream
        Traces in m/s^2.
    config : ProcessingConfig, optional
        Processing configuration.

    Returns
    -------
    processed : obspy.Stream
        Processed copies of the traces that passed.
    failures : list of tuple(str, str)
        ``(trace id, reason)`` of the traces refused.
    """
    processed, failures = Stream(), []
    for trace in stream:
        try:
            processed.append(process_trace(trace, config))
        except RockscreenError as exc:
            failures.append((trace.id, str(exc)))
    return processed, failures


def provenance_of(trace: Trace) -> list[dict]:
    """Return a deep copy of a trace's provenance list (empty when it has none)."""
    if "rockscreen" not in trace.stats:
        return []
    return copy.deepcopy(list(trace.stats.rockscreen.get("provenance", [])))


__all__ = [
    "ProcessingConfig",
    "bandpass",
    "baseline_polynomial",
    "demean",
    "detrend_linear",
    "process_stream",
    "process_trace",
    "provenance_of",
    "resample",
    "taper",
]
