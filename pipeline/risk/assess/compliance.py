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
scaled to it). :func:`check_record_basis` measures every set of an assessment. A failing
set stops only the towers that rest on it: each is listed in ``/failures`` with the measured
values and the fixes (:func:`noncompliance_reason`) and every other tower is assessed;
``--allow-noncompliant`` assesses those towers too and marks each verdict built on such a
set (:func:`mark_noncompliant_row`, :func:`rockscreen.pipeline.risk.measures.classes.class_label`).
When no tower is left to assess, :func:`noncompliance_message` writes the one refusal
``rockscreen assess`` gives before any solve.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rockscreen.pipeline.hazard.selection import SCALE_LIMITS
from rockscreen.pipeline.risk.assess.record_sets import is_failed
from rockscreen.pipeline.risk.measures.classes import NONCOMPLIANT_MARK
from rockscreen.pipeline.verdict.messages import (
    Message,
    message,
    note_columns,
    note_messages,
    render_all,
)

__all__ = [
    "DEFAULT_TOLERANCE",
    "MIN_RECORDS",
    "SetCompliance",
    "check_record_basis",
    "mark_noncompliant_row",
    "noncompliance_message",
    "noncompliance_reason",
    "ratio_digits",
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
    #: Empty when compliant; otherwise the measured values against the requirements
    #: (``records.*`` codes of :mod:`rockscreen.pipeline.verdict.catalogue.records`).
    problems: tuple[Message, ...] = field(default=())

    @property
    def reason(self) -> str:
        """``""`` when compliant; otherwise :attr:`problems` in English, joined by ``"; "``."""
        return render_all(self.problems)


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
        problems.append(message("records.too_few", n=n, required=min_records))
    if not within:
        problems.append(
            message(
                "records.mean_off",
                ratio_min=r_min,
                ratio_max=r_max,
                min_digits=ratio_digits(r_min, low, high),
                max_digits=ratio_digits(r_max, low, high),
                t_from_s=span[0],
                t_to_s=span[1],
                low=low,
                high=high,
            )
        )
        if capped:
            problems.append(
                message(
                    "records.capped",
                    capped=capped,
                    n=n,
                    low=float(scale_limits[0]),
                    high=float(scale_limits[1]),
                )
            )
    return SetCompliance(
        n_records=n,
        ratio_min=r_min,
        ratio_max=r_max,
        period_range_s=span,
        band=(low, high),
        n_capped=capped,
        compliant=not problems,
        problems=tuple(problems),
    )


def ratio_digits(value: float, low: float, high: float) -> int:
    """Return the decimals a mean/target ratio is printed with: two, or as many as show a miss.

    0.8996 is outside 0.90-1.30 but prints as 0.90 with two decimals (0.89996 as 0.9000
    with four): a missed bound is never printed as a met one.
    """
    outside = value < low - 1e-9 or value > high + 1e-9
    for digits in range(2, 12):
        if not outside or not low - 1e-9 <= round(value, digits) <= high + 1e-9:
            return digits
    return 12


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
    band = failing[0][2].band
    ratios = f"{low:.{ratio_digits(low, *band)}f}-{high:.{ratio_digits(high, *band)}f}"
    measured = f"measured: {span} records per set, mean/target {ratios}"
    return (
        f"{len(failing)} of {n_sets} record sets do not meet the code ({measured}; NTC 2018 "
        "§3.2.3.6: mean 5 % spectrum within -10 %/+30 % of the code spectrum over the period "
        "range, "
        f"Circolare 2019 C3.2.3.6; §7.3.5: the mean of at least {MIN_RECORDS} records): "
        + "; ".join(listed)
        + f". No tower was solved. Fix: {_fixes(limits)}"
    )


def _fixes(limits: Sequence[float]) -> str:
    return (
        f"a larger suite chosen for the site (--suite, --records {MIN_RECORDS} or more), "
        f"other scaling limits (--scale-limits, now {limits[0]:g},{limits[1]:g}), or "
        "--allow-noncompliant to run anyway with each verdict built on such a set marked "
        f"'{NONCOMPLIANT_MARK}'"
    )


def noncompliance_reason(
    key: Sequence[Any],
    failing: Sequence[tuple[float, SetCompliance, Any]],
    options: Mapping[str, Any] | None = None,
) -> str:
    """Return why a tower resting on non-compliant record sets is not assessed, and the fix.

    Parameters
    ----------
    key : sequence
        The site's key: (lon [deg], lat [deg], soil, topography).
    failing : sequence of (return period [y], SetCompliance, record set)
        The tower's non-compliant sets (the set's ``records`` and ``scale_factors``).
    options : mapping, optional
        The selection options (``scale_limits``).

    Returns
    -------
    str
        One line: the site, then per return period the measured count, mean/target range
        and capped factors (:class:`SetCompliance`'s reason) and the set (record x scale
        factor), then the fixes.
    """
    limits = (options or {}).get("scale_limits", SCALE_LIMITS)
    parts = []
    for tr, compliance, record_set in failing:
        members = ", ".join(
            f"{record.name} x{factor:.3g}"
            for record, factor in zip(record_set.records, record_set.scale_factors, strict=True)
        )
        parts.append(f"TR={tr:g} y: {compliance.reason}; set: {members}")
    return (
        f"record set not code-compliant at {_site_text(key)}: "
        + "; ".join(parts)
        + f". Fix: {_fixes(limits)}"
    )


def check_record_basis(
    groups: Mapping[tuple, Any],
    sets: Mapping[tuple, Mapping[float, Any]],
    set_trs: Mapping[tuple, Sequence[float]],
    options: Any,
    say: Callable[[str], None],
) -> dict[tuple, dict[float, SetCompliance]]:
    """Measure every record set (NTC 2018 §3.2.3.6, §7.3.5); say which fail.

    A failing set refuses nothing here: the assessment lists the towers resting on it in
    ``/failures`` (:func:`noncompliance_reason`), or, under ``allow_noncompliant``, assesses
    and marks them (:func:`mark_noncompliant_row`).

    Parameters
    ----------
    groups : mapping
        The sites' keys (each a group of towers).
    sets : mapping
        Site key -> return period [y] -> record set (a ``str`` when it could not be made).
    set_trs : mapping
        Site key -> its return periods [y].
    options : rockscreen.pipeline.risk.assess.run.AssessOptions
        ``set_compliance``, ``allow_noncompliant`` and ``selection``.
    say : callable
        Receives one line when a set fails: how many, at how many sites, and what becomes
        of their towers.

    Returns
    -------
    dict
        Site key -> return period [y] -> :class:`SetCompliance`.
    """
    basis: dict[tuple, dict[float, SetCompliance]] = {}
    failing = []
    for key in groups:
        basis[key] = {}
        for tr in set_trs[key]:
            if is_failed(sets[key][tr]):
                continue
            compliance = options.set_compliance(sets[key][tr])
            basis[key][tr] = compliance
            if not compliance.compliant:
                failing.append((key, tr, compliance))
    if failing:
        n_sets = sum(len(v) for v in basis.values())
        n_sites = len({key for key, _, _ in failing})
        what = (
            "warning (--allow-noncompliant): their towers are assessed, each verdict marked "
            f"'{NONCOMPLIANT_MARK}'"
            if options.allow_noncompliant
            else "their towers are not assessed (listed in /failures with the measured values "
            "and the fix); every other tower is"
        )
        say(
            f"{len(failing)} of {n_sets} record sets at {n_sites} site(s) do not meet NTC "
            f"2018 §3.2.3.6/§7.3.5: {what}"
        )
    return basis


def mark_noncompliant_row(row: dict[str, Any], basis: Mapping[float, SetCompliance]) -> None:
    """Mark a tower's row built on non-compliant record sets (``basis_compliant``, note).

    Parameters
    ----------
    row : dict
        The tower's summary row, changed in place.
    basis : mapping
        Return period [y] -> :class:`SetCompliance` of the sets the row rests on.
    """
    bad = [(tr, c) for tr, c in basis.items() if not c.compliant]
    if not bad:
        return
    row["basis_compliant"] = False
    detail = [message("records.set_problems", tr=tr, problems=c.problems) for tr, c in bad]
    mark = message("basis.noncompliant", detail=detail)
    row.update(note_columns([*(note_messages(row) or ()), mark]))
