"""The screening risk of a whole assessment: the region's ranks and list, the long tables.

After all towers (:func:`assess_risk`, from every tower's record, so a resumed assessment
ranks as an uninterrupted one): each tower's record read back from the worker's result
(:func:`~rockscreen.pipeline.risk.assess.screening_risk.risk_item`) or computed without
rocking for a tower not assessed
(:func:`~rockscreen.pipeline.risk.assess.screening_risk.tower_screening_risk`), the
region's ranks, bands and top-N list (:func:`region_risk`), every tower's ``risk_*`` columns
and the ``/risk_fragility``, ``/risk_sensitivity`` and ``/risk_top_n`` rows.
``docs/risk.md``, "The screening risk in assess".
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from rockscreen.pipeline.risk.assess.row_table import RowTable
from rockscreen.pipeline.risk.assess.screening_risk import RiskOptions, tower_screening_risk
from rockscreen.pipeline.risk.uncertainty.rank import rank_towers
from rockscreen.pipeline.risk.uncertainty.sensitivity import top_n_changes_of_groups
from rockscreen.pipeline.verdict.messages import Message, loads, message
from rockscreen.pipeline.verdict.screening_risk import (
    FragilityCurve,
    RiskPlace,
    ScreeningRisk,
    risk_columns,
    risk_from_data,
)

__all__ = ["TOP_N", "AssessRisk", "RegionRisk", "assess_risk", "region_risk"]

#: The region's list length (fewer when the region has fewer towers).
TOP_N = 10


@dataclass(frozen=True)
class RegionRisk:
    """The region's list: every ranked tower's place and the top-N list's rows."""

    #: Tower id -> its place.
    places: dict[str, RiskPlace]
    #: ``/risk_top_n`` rows (tower_id, side, input, p_crosses), highest first.
    top_n_rows: tuple[dict[str, Any], ...]
    #: N.
    top_n: int


def region_risk(risks: Sequence[ScreeningRisk], top_n: int = TOP_N) -> RegionRisk:
    """Return the ranks, bands and top-N list of the towers that have a risk.

    Parameters
    ----------
    risks : sequence of ScreeningRisk
        Every tower with a risk (any order: the result does not depend on it).
    top_n : int
        N of the list (fewer when there are fewer towers).
    """
    if not risks:
        return RegionRisk({}, (), 0)
    ids = [r.tower_id for r in risks]
    ranked = rank_towers(
        ids, [r.p50_best for r in risks], [r.p50_lo90 for r in risks], [r.p50_hi90 for r in risks]
    )
    places = {t.tower_id: RiskPlace(t.rank, t.band, t.band_uncertain) for t in ranked}
    n_top = min(int(top_n), len(risks) - 1)
    if n_top < 1:  # one tower: no list to enter or leave
        return RegionRisk(places, (), 0)
    rows = tuple(
        {
            "tower_id": c.tower_id,
            "side": "in" if c.in_top else "out",
            "input": c.input,
            "p_crosses": float(c.probability),
        }
        for c in top_n_changes_of_groups(
            ids,
            [r.p50_best for r in risks],
            [(r.survey.weight, r.survey.p50_best) for r in risks],
            [r.survey_first for r in risks],
            n_top,
        )
    )
    return RegionRisk(places, rows, n_top)


@dataclass(frozen=True)
class AssessRisk:
    """The screening risk of a whole assessment: its long tables and the top-N list."""

    #: ``/risk_fragility`` and ``/risk_sensitivity`` rows, kept by column
    #: (:class:`~rockscreen.pipeline.risk.assess.row_table.RowTable`: 40 fragility rows a
    #: tower).
    fragility: Sequence[dict[str, Any]]
    sensitivity: Sequence[dict[str, Any]]
    #: ``/risk_top_n`` rows.
    top_n_rows: tuple[dict[str, Any], ...]
    #: N of the top-N list.
    top_n: int


#: Towers whose long-table rows are added to the tables as one block of columns.
_BLOCK_TOWERS = 256
#: What a tower's kept record holds of its fragility band once its rows are in the table.
_NO_BAND = FragilityCurve((), (), (), (), (), 0.0)


def _no_location(site: Any) -> Message:
    tower = site.tower
    if tower.lat is None or tower.lon is None:
        return message("risk.no_location", reason="lat, lon not given")
    return message("risk.no_location", reason="the NTC 2018 hazard has no value at its site")


def assess_risk(
    sites: Sequence[Any],
    summary: dict[int, dict[str, Any]],
    done: dict[int, dict[str, Any]],
    hazard_of: Callable[[Any], dict[str, Any] | None],
    seed: int,
    options: RiskOptions,
) -> AssessRisk:
    """Add every tower's ``risk_*`` columns to its summary row; return the long tables.

    Parameters
    ----------
    sites : sequence of TowerSite
        Every tower, in inventory order.
    summary : dict
        Inventory index -> the tower's summary row (updated in place).
    done : dict
        Inventory index -> the worker's result of an assessed tower
        (:func:`~rockscreen.pipeline.risk.assess.screening_risk.risk_item`'s ``risk`` and
        ``risk_notes``).
    hazard_of : callable
        A site -> its hazard (``curve``), or None when the tower has no site hazard.
    seed : int
        The run's seed.
    options : RiskOptions

    Returns
    -------
    AssessRisk
        The ranks are computed here, from every tower's record: a resumed assessment
        ranks as an uninterrupted one.
    """
    risks: dict[int, ScreeningRisk] = {}
    notes: dict[int, tuple[Message, ...]] = {}
    tables = _LongTables()
    for site in sites:
        item = done.get(site.index)
        if item is not None and "error" in item:  # the tower's work failed (/failures)
            notes[site.index] = (message("risk.failed", error=item["error"]),)
            continue
        if item is not None:
            data = item.get("risk")
            if data is not None:
                risks[site.index] = tables.add(risk_from_data(data))
            notes[site.index] = loads(item.get("risk_notes") or "[]")
            continue
        hazard = hazard_of(site)
        if hazard is None:
            notes[site.index] = (_no_location(site),)
            continue
        # not assessed (its record set failed or was refused): the risk without rocking
        risk, said = tower_screening_risk(site, None, hazard["curve"], seed, options)
        if risk is not None:
            risks[site.index] = tables.add(risk)
        notes[site.index] = said
    tables.flush()
    region = region_risk(list(risks.values()))
    for site in sites:
        risk = risks.get(site.index)
        place = region.places.get(risk.tower_id) if risk is not None else None
        summary[site.index].update(risk_columns(risk, place, notes.get(site.index, ())))
    return AssessRisk(
        fragility=tables.fragility,
        sensitivity=tables.sensitivity,
        top_n_rows=region.top_n_rows,
        top_n=region.top_n,
    )


class _LongTables:
    """``/risk_fragility`` and ``/risk_sensitivity`` filled tower by tower, kept by column.

    :meth:`add` takes a tower's rows and returns its record without them (its band and
    sensitivity are in the tables; the summary columns and the list need the rest): the
    main process does not keep 40 dict rows and the band's numbers twice per tower.
    """

    def __init__(self) -> None:
        self.fragility, self.sensitivity = RowTable(), RowTable()
        self._rows: tuple[list, list] = ([], [])

    def add(self, risk: ScreeningRisk) -> ScreeningRisk:
        self._rows[0].extend(_fragility_rows(risk))
        self._rows[1].extend(_sensitivity_rows(risk))
        if len(self._rows[0]) >= _BLOCK_TOWERS * len(risk.fragility.ag_g):
            self.flush()
        return dataclasses.replace(risk, fragility=_NO_BAND, sensitivity=())

    def flush(self) -> None:
        for table, rows in zip((self.fragility, self.sensitivity), self._rows, strict=True):
            table.extend(rows)
            rows.clear()


def _fragility_rows(risk: ScreeningRisk) -> list[dict[str, Any]]:
    f = risk.fragility
    return [
        {
            "tower_id": risk.tower_id,
            "ag_g": f.ag_g[j],
            "p_median": f.p_median[j],
            "p_lo90": f.p_lo90[j],
            "p_hi90": f.p_hi90[j],
            "p_mean": f.p_mean[j],
            "bounded_share": f.bounded_share,
        }
        for j in range(len(f.ag_g))
    ]


def _sensitivity_rows(risk: ScreeningRisk) -> list[dict[str, Any]]:
    return [
        {
            "tower_id": risk.tower_id,
            "input": s.input,
            "index": s.index,
            "narrowing": s.narrowing,
            "judgement": "yes" if s.judgement else "no",
        }
        for s in risk.sensitivity
    ]
