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
gives before any solve (:func:`check_record_basis` measures every set of an assessment and
refuses); ``--allow-noncompliant`` runs anyway and every verdict built on such a set is
marked (:func:`mark_noncompliant_row`, :func:`rockscreen.pipeline.risk.classes.class_label`).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.hazard.selection import SCALE_LIMITS
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


def check_record_basis(
    groups: Mapping[tuple, Any],
    sets: Mapping[tuple, Mapping[float, Any]],
    set_trs: Mapping[tuple, Sequence[float]],
    options: Any,
    say: Callable[[str], None],
) -> dict[tuple, dict[float, SetCompliance]]:
    """Measure every record set (NTC 2018 §3.2.3.6, §7.3.5); refuse a non-compliant basis.

    Parameters
    ----------
    groups : mapping
        The sites' keys (each a group of towers).
    sets : mapping
        Site key -> return period [y] -> record set (a ``str`` when it could not be made).
    set_trs : mapping
        Site key -> its return periods [y].
    options : rockscreen.pipeline.risk.assess.AssessOptions
        ``set_compliance``, ``allow_noncompliant`` and ``selection``.
    say : callable
        Where the warning goes under ``allow_noncompliant``.

    Returns
    -------
    dict
        Site key -> return period [y] -> :class:`SetCompliance`.

    Raises
    ------
    RiskError
        When a set is not compliant and ``options.allow_noncompliant`` is False: one
        message naming the sites, return periods, measured counts and ratios, and the fixes.
    """
    basis: dict[tuple, dict[float, SetCompliance]] = {}
    failing = []
    for key in groups:
        basis[key] = {}
        for tr in set_trs[key]:
            if isinstance(sets[key][tr], str):
                continue
            compliance = options.set_compliance(sets[key][tr])
            basis[key][tr] = compliance
            if not compliance.compliant:
                failing.append((key, tr, compliance))
    if failing:
        message = noncompliance_message(
            failing, sum(len(v) for v in basis.values()), options.selection
        )
        if not options.allow_noncompliant:
            raise RiskError(message)
        say(f"warning (--allow-noncompliant): {message}")
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
