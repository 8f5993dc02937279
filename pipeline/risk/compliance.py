"""Code compliance of the record sets an assessment is built on (NTC 2018 §3.2.3.6, §7.3.5).

A fragility is only as good as the records behind it. NTC 2018 asks of a set of
accelerograms used for time-history analysis:

- **spectral compatibility** (§3.2.3.6; Circolare 2019 C3.2.3.6): the mean of the 5 %
  spectra departs from the code spectrum by no more than -10 % and +30 % over the period
  range of interest (0.15-2.0 s by default), i.e. ``0.90 <= mean / target <= 1.30``;
- **enough records for a mean** (§7.3.5): the effects are taken as the mean over at least
  :data:`MIN_RECORDS` = 7 records (with 3 to 6 the code takes the most unfavourable
  effect, which a fragility fit does not do).

:func:`set_compliance` measures one record set against both (and counts the scale factors
pinned at the scaling limits: records too weak or too strong for the target cannot be
scaled to it). :func:`noncompliance_message` writes the one refusal ``rockscreen assess``
gives before any solve; ``--allow-noncompliant`` runs anyway and every verdict built on
such a set is marked (:func:`rockscreen.pipeline.risk.classes.class_label`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from rockscreen.pipeline.hazard.selection import SCALE_LIMITS

__all__ = [
    "DEFAULT_TOLERANCE",
    "MIN_RECORDS",
    "SetCompliance",
    "noncompliance_message",
    "set_compliance",
]

#: Fewest records whose mean response the code accepts (NTC 2018 §7.3.5).
MIN_RECORDS = 7
#: Allowed departure of the mean spectrum below and above the target [-] (§3.2.3.6).
DEFAULT_TOLERANCE = (-0.10, 0.30)
#: Non-compliant sets named in full in the refusal (the rest are counted).
MAX_LISTED = 4


@dataclass(frozen=True)
class SetCompliance:
    """How one record set measures against NTC 2018 §3.2.3.6 and §7.3.5."""

    #: Records in the set [-].
    n_records: int
    #: Smallest and largest mean / target over the matching periods [-].
    ratio_min: float
    ratio_max: float
    #: Matching period range [s].
    period_range_s: tuple[float, float]
    #: Allowed mean / target (e.g. 0.90, 1.30) [-].
    band: tuple[float, float]
    #: Scale factors pinned at the scaling limits [-].
    n_capped: int
    #: Whether the set meets both requirements.
    compliant: bool
    #: ``""`` when compliant; otherwise the measured values against the requirements.
    reason: str


def set_compliance(
    record_set: Any,
    *,
    min_records: int = MIN_RECORDS,
    tolerance: tuple[float, float] = DEFAULT_TOLERANCE,
    scale_limits: tuple[float, float] = SCALE_LIMITS,
) -> SetCompliance:
    """Measure a record set against NTC 2018 §3.2.3.6 (spectrum) and §7.3.5 (count).

    Parameters
    ----------
    record_set : rockscreen.pipeline.hazard.RecordSet
        The selected set (``records``, ``scale_factors``, ``periods_s``, ``ratio_min``,
        ``ratio_max``).
    min_records : int
        Fewest records required [-].
    tolerance : (float, float)
        Allowed relative departure of the mean below and above the target [-].
    scale_limits : (float, float)
        Smallest and largest individual scale factor of the selection [-].

    Returns
    -------
    SetCompliance
    """
    n = len(record_set.records)
    low, high = 1.0 + tolerance[0], 1.0 + tolerance[1]
    r_min, r_max = float(record_set.ratio_min), float(record_set.ratio_max)
    periods = np.asarray(record_set.periods_s, dtype=float)
    span = (float(periods[0]), float(periods[-1]))
    factors = np.asarray(record_set.scale_factors, dtype=float)
    capped = int(
        np.sum(np.isclose(factors, scale_limits[0]) | np.isclose(factors, scale_limits[1]))
    )
    within = r_min >= low - 1e-9 and r_max <= high + 1e-9
    problems = []
    if n < min_records:
        problems.append(f"{n} records ({min_records} required, NTC 2018 §7.3.5)")
    if not within:
        problems.append(
            f"mean/target {r_min:.2f}-{r_max:.2f} over {span[0]:g}-{span[1]:g} s "
            f"(allowed {low:.2f}-{high:.2f}, NTC 2018 §3.2.3.6)"
        )
        if capped:
            problems.append(
                f"{capped} of {n} scale factors at the limits {scale_limits[0]:g}-"
                f"{scale_limits[1]:g} (records too weak or too strong for the target)"
            )
    return SetCompliance(
        n_records=n,
        ratio_min=r_min,
        ratio_max=r_max,
        period_range_s=span,
        band=(low, high),
        n_capped=capped,
        compliant=not problems,
        reason="; ".join(problems),
    )


def _site_text(key: Sequence[Any]) -> str:
    lon, lat, soil, topography = key
    return f"site lon={lon:g} lat={lat:g} (soil {soil}, {topography})"


def noncompliance_message(
    failing: Sequence[tuple[Sequence[Any], float, SetCompliance]],
    n_sets: int,
    options: Mapping[str, Any] | None = None,
) -> str:
    """Return the one refusal naming the non-compliant record sets and the ways out.

    Parameters
    ----------
    failing : sequence of (site key, return period [y], SetCompliance)
        The non-compliant sets; the key is (lon [deg], lat [deg], soil, topography).
    n_sets : int
        Record sets measured in all.
    options : mapping, optional
        The selection options (``n_records``, ``scale_limits``, ``period_range_s``).

    Returns
    -------
    str
    """
    options = options or {}
    listed = [f"{_site_text(key)} TR={tr:g} y: {c.reason}" for key, tr, c in failing[:MAX_LISTED]]
    more = len(failing) - len(listed)
    if more:
        listed.append(f"and {more} more")
    limits = options.get("scale_limits", SCALE_LIMITS)
    counts = sorted({c.n_records for _, _, c in failing})
    low = min(c.ratio_min for _, _, c in failing)
    high = max(c.ratio_max for _, _, c in failing)
    span = f"{counts[0]}-{counts[-1]}" if len(counts) > 1 else f"{counts[0]}"
    measured = f"measured: {span} records per set, mean/target {low:.2f}-{high:.2f}"
    return (
        f"{len(failing)} of {n_sets} record sets do not meet the code ({measured}; NTC 2018 "
        "§3.2.3.6: mean 5 % spectrum within -10 %/+30 % of the code spectrum over the period "
        "range, "
        f"Circolare 2019 C3.2.3.6; §7.3.5: the mean of at least {MIN_RECORDS} records): "
        + "; ".join(listed)
        + ". No tower was solved. Fix: a larger suite chosen for the site (--suite, "
        f"--records {MIN_RECORDS} or more), other scaling limits (--scale-limits, now "
        f"{limits[0]:g},{limits[1]:g}), or --allow-noncompliant to run anyway with every "
        "verdict marked 'basis not code-compliant'"
    )
