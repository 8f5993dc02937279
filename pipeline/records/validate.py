"""Checks of every trace read from a file: codes, sampling, sample type, length, place.

Used by :func:`pipeline.records.io.read_stream` before units are converted; each failure is
a :class:`~pipeline.errors.RecordFormatError` naming the file, the field, the bad value and
what is allowed.
"""

from __future__ import annotations

import math
import re

import numpy as np
from obspy import Trace

from rockscreen.pipeline.errors import RecordFormatError
from rockscreen.pipeline.text import printable

#: Sampling rates a record may have [Hz]: accelerographs sample at 50-1000 Hz and
#: digitised analogue records at 25-200 Hz; outside this range a header is corrupt (below
#: 20 Hz processing refuses a record anyway: QualityLimits.min_sampling_rate_hz).
SAMPLING_RATE_RANGE_HZ = (1.0, 10_000.0)

#: Characters and length of a network, station, location or channel code. A '.' would split
#: the id NET.STA.LOC.CHA, a '/' names an HDF5 group, a control character reaches the
#: terminal: codes holding anything else are refused.
CODE_PATTERN = re.compile(r"[A-Za-z0-9_-]{0,64}")


def validate_trace(trace: Trace, name: str) -> None:
    """Refuse codes, sampling, sample types and lengths no accelerogram has."""
    stats = trace.stats
    fmt = str(stats._format)
    for key in ("network", "station", "location", "channel"):
        code = str(stats[key])
        if not CODE_PATTERN.fullmatch(code):
            raise RecordFormatError(
                f"{name}: {fmt} {key} code {printable(code[:40])!r}"
                f"{'...' if len(code) > 40 else ''} is not a code (allowed: letters, digits, "
                "'_' and '-', at most 64)"
            )
    rate = float(stats.sampling_rate)
    low, high = SAMPLING_RATE_RANGE_HZ
    if not (math.isfinite(rate) and low <= rate <= high):
        raise RecordFormatError(
            f"{name}: {trace.id}: sampling rate {rate!r} Hz from the {fmt} header is not "
            f"plausible (allowed: {low:g} to {high:g} Hz)"
        )
    kind = np.asarray(trace.data).dtype.kind
    if kind not in "iuf":
        raise RecordFormatError(
            f"{name}: {trace.id}: the {fmt} data are {np.asarray(trace.data).dtype} "
            "(text, e.g. miniSEED ASCII encoding), not samples"
        )
    if stats.npts < 1:
        raise RecordFormatError(f"{name}: {trace.id}: no samples")
    if fmt == "KNET":
        check_knet_length(trace, name)


def check_knet_length(trace: Trace, name: str) -> None:
    """Refuse a K-NET file whose samples do not match its header's duration x rate.

    Fewer samples: a truncated file. More than one second of samples beyond it: a sampling
    frequency or duration the header does not state as plain numbers (ObsPy reads the
    digits before the first non-digit, so ``1e2Hz`` becomes 1 Hz, which would stretch the
    record a hundredfold).
    """
    stats = trace.stats
    duration = float(stats.knet.get("duration", math.nan))
    if not math.isfinite(duration):
        return
    rate = float(stats.sampling_rate)
    expected = round(duration * rate)
    if stats.npts < expected:
        raise RecordFormatError(
            f"{name}: truncated K-NET file: {stats.npts} samples but the header's "
            f"Duration Time {duration:g} s x {rate:g} Hz = {expected}"
        )
    most = expected + math.ceil(rate)
    if stats.npts > most:
        raise RecordFormatError(
            f"{name}: K-NET header inconsistent with its data: {stats.npts} samples, but "
            f"Duration Time {duration:g} s x Sampling Freq {rate:g} Hz = {expected} (allowed: "
            f"{expected} to {most}); the header's sampling frequency or duration is corrupt"
        )


def check_coordinates(trace: Trace, coordinates: dict, source: str, name: str) -> None:
    """Refuse a latitude outside [-90, 90] or a longitude outside [-180, 360] [deg].

    NaN means unknown (the station is then paired as one without coordinates); a value out
    of range is a corrupt header that would pair the record with the wrong towers.
    """
    for key, limit in (("latitude", (-90.0, 90.0)), ("longitude", (-180.0, 360.0))):
        value = float(coordinates[key])
        if math.isfinite(value) and limit[0] <= value <= limit[1] or math.isnan(value):
            continue
        raise RecordFormatError(
            f"{name}: {trace.id}: station {key} {value!r} deg from the {source} is impossible "
            f"(allowed: {limit[0]:g} to {limit[1]:g}, or absent)"
        )


__all__ = [
    "CODE_PATTERN",
    "SAMPLING_RATE_RANGE_HZ",
    "check_coordinates",
    "check_knet_length",
    "validate_trace",
]
