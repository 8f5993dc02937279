"""The sites of an assessment: their hazard, their towers, their record sets' rows.

Steps 1 and 2 of :mod:`rockscreen.pipeline.risk.assess.run` seen from the main process: each
located tower's site hazard (:func:`locate_sites`, towers without coordinates or without a
site hazard reported, not assessed), the archive id of a selected record
(:func:`record_id`), a set's ``/selection`` row (:func:`selection_row`) and the towers
resting on a set that fails NTC 2018 §3.2.3.6/§7.3.5 (:func:`noncompliant_towers`, and
:func:`refused_towers`: those not assessed for it).
"""

from __future__ import annotations

import dataclasses
import hashlib
import math
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.hazard import hazard_curve, limit_state_return_period, site_hazard
from rockscreen.pipeline.risk.assess.compliance import SetCompliance, noncompliance_message
from rockscreen.pipeline.risk.assess.pool_samples import float32_record
from rockscreen.pipeline.risk.assess.sites import TowerSite
from rockscreen.pipeline.risk.assess.tower_summary import base_summary_row
from rockscreen.pipeline.risk.measures.hazard_integral import HazardCurve
from rockscreen.pipeline.verdict.messages import message
from rockscreen.stations.errors import RockscreenError

__all__ = [
    "KeptRecords",
    "LocatedSites",
    "References",
    "hazard_of",
    "locate_sites",
    "noncompliant_towers",
    "record_id",
    "refused_towers",
    "selection_row",
    "set_references",
    "tower_site_hazard",
]


@dataclass
class LocatedSites:
    """The towers of an inventory by site, and those that have no site hazard."""

    #: Site hazard by (lon, lat, nominal life, use class) (:func:`tower_site_hazard`).
    hazards: dict[tuple, dict[str, Any]] = field(default_factory=dict)
    #: The located towers by site key (lon, lat, soil class, topography).
    groups: dict[tuple, list[TowerSite]] = field(default_factory=dict)
    #: Summary rows of the towers not assessed, by inventory index.
    summary: dict[int, dict[str, Any]] = field(default_factory=dict)
    #: ``/failures`` rows of those towers (kind ``site`` or ``hazard``).
    failures: list[dict[str, Any]] = field(default_factory=list)

    def hazard_or_none(self, site: TowerSite) -> dict[str, Any] | None:
        """Return the hazard of a tower's site (:func:`hazard_of`), None if it has none."""
        key = (site.lon_deg, site.lat_deg, site.nominal_life_y, site.use_class)
        return self.hazards.get(key) if site.key in self.groups else None


def locate_sites(sites: Sequence[TowerSite], trs: Sequence[float]) -> LocatedSites:
    """Return each tower's site hazard and its site group; report those that have none.

    Parameters
    ----------
    sites : sequence of TowerSite
        The inventory's towers with their sites
        (:func:`rockscreen.pipeline.risk.assess.sites.tower_sites`).
    trs : sequence of float
        The stripes' return periods [y].

    Returns
    -------
    LocatedSites
        A tower without coordinates (message ``site.no_coordinates``) or whose site hazard
        failed (``site.hazard_failed``, a :class:`RockscreenError`) has a base summary row
        and a ``/failures`` row, and no group.
    """
    out = LocatedSites()
    for site in sites:
        if math.isnan(site.lon_deg):
            said = message("site.no_coordinates")
            out.summary[site.index] = base_summary_row(site, [said])
            out.failures.append({"kind": "site", "subject": site.tower.id, "reason": said.render()})
            continue
        hazard_key = (site.lon_deg, site.lat_deg, site.nominal_life_y, site.use_class)
        try:
            if hazard_key not in out.hazards:
                out.hazards[hazard_key] = tower_site_hazard(site, trs)
        except Exception as exc:  # noqa: BLE001 - HazardError and the like, per tower
            if not isinstance(exc, RockscreenError):
                raise
            said = message("site.hazard_failed", error=str(exc))
            out.summary[site.index] = base_summary_row(site, [said])
            out.failures.append({"kind": "hazard", "subject": site.tower.id, "reason": str(exc)})
            continue
        out.groups.setdefault(site.key, []).append(site)
    return out


def tower_site_hazard(site: TowerSite, trs: Sequence[float]) -> dict[str, Any]:
    """Hazard of a site: curve, stripe ag, T_R,SLV and ag_SLV (HazardError propagates)."""
    periods, ag = hazard_curve(site.lon_deg, site.lat_deg)
    tr_slv = limit_state_return_period("SLV", site.nominal_life_y, site.use_class)
    return {
        "curve": HazardCurve.from_return_periods(periods, ag),
        "ags": {tr: site_hazard(site.lon_deg, site.lat_deg, tr).ag_g for tr in trs},
        "tr_slv": tr_slv,
        "ag_slv": site_hazard(site.lon_deg, site.lat_deg, tr_slv).ag_g,
    }


def record_id(record: Any) -> str:
    """Return the archive id of a suite record: its name and a digest of its samples.

    Records of the embedded suites share names across sites and return periods (their
    samples differ); the digest tells them apart and lets an identical record of several
    sets be stored once.

    Parameters
    ----------
    record : rockscreen.pipeline.hazard.selection.SuiteRecord

    Returns
    -------
    str
        ``"<name>-<10 hex digits>"``, with ``/`` in the name replaced by ``_``.
    """
    digest = hashlib.sha1(repr(float(record.dt_s)).encode())
    for acc in (record.acc_x_m_s2, record.acc_y_m_s2, record.acc_z_m_s2):
        data = b"-" if acc is None else np.ascontiguousarray(acc, dtype="<f8").tobytes()
        digest.update(data)
    name = str(record.name).replace("/", "_").strip() or "record"
    return f"{name}-{digest.hexdigest()[:10]}"


def selection_row(
    key: tuple, tr: float, record_set: Any, compliance: SetCompliance
) -> dict[str, Any]:
    """Return the ``/selection`` row of a site's record set at ``tr`` and its compliance.

    The set's records and factors themselves are stored as references (``/set_records``,
    :func:`set_references`).
    """
    return {
        "site_lon_deg": key[0],
        "site_lat_deg": key[1],
        "soil_class": key[2],
        "topography": key[3],
        "return_period_y": tr,
        "ratio_min": float(record_set.ratio_min),
        "ratio_max": float(record_set.ratio_max),
        "meets_tolerance": bool(record_set.meets_tolerance),
        "message": record_set.message,
        "n_records": compliance.n_records,
        "compliant": compliance.compliant,
        "compliance_note": compliance.reason,
        "period_from_s": float(compliance.period_range_s[0]),
        "period_to_s": float(compliance.period_range_s[1]),
    }


def set_references(
    row: int, record_set: Any, id_of: Callable[[Any], str] = record_id
) -> list[tuple[int, str, float]]:
    """Return a set's references: (its ``/selection`` row, record id, exact factor) per record.

    Parameters
    ----------
    row : int
        The set's row in ``/selection``.
    record_set : rockscreen.pipeline.hazard.RecordSet
    id_of : callable
        A record -> its id (:func:`record_id`, or :meth:`KeptRecords.id_of`: computed once).

    Returns
    -------
    list of (int, str, float)
        In the set's order; the ids of :func:`record_id`.
    """
    return [
        (row, id_of(record), float(factor))
        for record, factor in zip(record_set.records, record_set.scale_factors, strict=True)
    ]


class KeptRecords:
    """The records of an assessment's sets in the main process: one object per record.

    A set arrives from a worker with its pool records as their places in the pool
    (:class:`~rockscreen.pipeline.hazard.stochastic_suite.PoolRecord`), each taken again
    from the pool here; :meth:`kept` gives every set the first object of each record, so
    the main process holds each record's samples once, whatever the number of sets (110
    references a tower at one site per tower), a pool record's as views of its pool's
    float32 samples (:func:`~rockscreen.pipeline.risk.assess.pool_samples.float32_record`:
    no float64 copy of 44 kB a record), and :meth:`id_of` digests each record once
    (:func:`record_id`).
    """

    def __init__(self) -> None:
        self._records: dict[Any, Any] = {}
        self._ids: dict[int, str] = {}

    @staticmethod
    def _key(record: Any) -> Any:
        pool_key = getattr(record, "pool_key", None)
        return ("pool", *pool_key) if pool_key else ("id", id(record))

    def kept(self, record_set: Any) -> Any:
        """Return ``record_set`` with each of its records as the object kept for it."""
        records = record_set.records
        same = tuple(self._keep(r) for r in records)
        if all(a is b for a, b in zip(same, records, strict=True)):
            return record_set
        return dataclasses.replace(record_set, records=same)

    def _keep(self, record: Any) -> Any:
        """Return the object kept for ``record``: the first one met (a pool record's float32)."""
        key = self._key(record)
        kept = self._records.get(key)
        if kept is None:
            kept = self._records[key] = float32_record(record)
        return kept

    def id_of(self, record: Any) -> str:
        """Return :func:`record_id` of a record, computed once per kept record."""
        rid = self._ids.get(id(record))
        if rid is None:
            rid = self._ids[id(record)] = record_id(record)
            self._records.setdefault(("id", id(record)), record)  # its id() stays its own
        return rid


class References(Sequence[tuple[int, str, float]]):
    """The sets' references (``/set_records``) kept by column: about 20 bytes each.

    Reads as the sequence of (``/selection`` row, record id, exact factor) tuples of
    :func:`set_references`; 110 references a tower at one site per tower cost about 90
    bytes each as tuples.
    """

    def __init__(self) -> None:
        self._rows: list[np.ndarray] = []
        self._ids: list[str] = []
        self._factors: list[np.ndarray] = []

    def extend(self, references: Sequence[tuple[int, str, float]]) -> None:
        """Append references (:func:`set_references`'s tuples)."""
        if not references:
            return
        self._rows.append(np.asarray([r for r, _, _ in references], dtype=np.int64))
        self._ids.extend(i for _, i, _ in references)
        self._factors.append(np.asarray([f for _, _, f in references], dtype=np.float64))

    def __len__(self) -> int:
        return len(self._ids)

    def __iter__(self) -> Iterator[tuple[int, str, float]]:
        ids = iter(self._ids)
        for rows, factors in zip(self._rows, self._factors, strict=True):
            for row, factor in zip(rows.tolist(), factors.tolist(), strict=True):
                yield (row, next(ids), factor)

    def __getitem__(self, index):  # type: ignore[override]
        return list(self)[index]

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Sequence):
            return NotImplemented
        return list(self) == list(other)

    __hash__ = None  # type: ignore[assignment]


def noncompliant_towers(
    sites: Sequence[TowerSite], trs: Sequence[float], hazards: dict, sets: dict, basis: dict
) -> dict[int, list[tuple[float, SetCompliance, Any]]]:
    """Return the towers resting on a non-compliant set: index -> [(TR, compliance, set)].

    A tower rests on its site's sets at the stripes' return periods ``trs`` and at its own
    T_R,SLV (the IDA's); a set that could not be made is a selection failure, not here.
    """
    out: dict[int, list[tuple[float, SetCompliance, Any]]] = {}
    for site in sites:
        if site.key not in basis:  # not located, or no site hazard
            continue
        own = sorted({*trs, hazard_of(hazards, site)["tr_slv"]})
        bad = [
            (tr, basis[site.key][tr], sets[site.key][tr])
            for tr in own
            if tr in basis[site.key] and not basis[site.key][tr].compliant
        ]
        if bad:
            out[site.index] = bad
    return out


def hazard_of(hazards: dict, site: TowerSite) -> dict[str, Any]:
    """Return the hazard of a located site (curve, stripe ags, T_R,SLV, ag_SLV)."""
    return hazards[(site.lon_deg, site.lat_deg, site.nominal_life_y, site.use_class)]


def refused_towers(
    sites: Sequence[TowerSite],
    trs: Sequence[float],
    located: LocatedSites,
    sets: dict,
    basis: dict,
    allow_noncompliant: bool,
    selection: dict[str, Any],
) -> dict[int, list[tuple[float, SetCompliance, Any]]]:
    """Return the towers not assessed for resting on a non-compliant set (none if allowed).

    A tower resting on a non-compliant set is not assessed (listed in ``/failures``), unless
    ``allow_noncompliant``; the other towers are, whatever their neighbours' sets.
    ``selection`` is the record selection's options (named in the message).

    Raises
    ------
    RiskError
        When every located tower is refused (nothing left to assess): the failing sets
        named (:func:`rockscreen.pipeline.risk.assess.compliance.noncompliance_message`).
    """
    if allow_noncompliant:
        return {}
    refused = noncompliant_towers(sites, trs, located.hazards, sets, basis)
    groups = located.groups
    if refused and all(m.index in refused for members in groups.values() for m in members):
        failing = [
            (key, tr, c) for key in groups for tr, c in basis[key].items() if not c.compliant
        ]
        n_sets = sum(len(v) for v in basis.values())
        raise RiskError(noncompliance_message(failing, n_sets, selection))
    return refused
