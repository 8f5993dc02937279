"""``rockscreen assess``: per-tower fragility, annual rate of overturning and LV1 indices.

Flow (``docs/risk.md``):

1. **Sites** (:func:`tower_sites`): each tower's site is its location rounded to
   ``site_resolution_deg`` (default 0.01 deg, about 1 km; 0 keeps it exact) with its soil
   class and topography (inventory columns ``soil_class``/``topography`` when present,
   else the tower defaults of :data:`rockscreen.pipeline.hazard.TOWER_DEFAULTS`, recorded as an
   assumption). Towers sharing a site share its record sets. A tower without coordinates
   has no site hazard and is reported, not assessed.
2. **Record sets** (one task per site and return period, in parallel): the site's
   spectrum-compatible set (:func:`pipeline.hazard.site_record_set`) from the user suite or
   the embedded synthetic one.
3. **Stripes** (chunks of towers of one site, in parallel, each chunk carrying its site's
   record sets): :func:`rockscreen.pipeline.risk.stripes.evaluate_stripe` at every return period.
4. **Per tower** (:func:`summarize_tower`): maximum-likelihood fragility in the site's ag,
   the annual rate of overturning on the site hazard curve, P(overturning in 50 years),
   the LV1 quantities and the risk class.

The executor is chosen as for ``rockscreen run``
(:func:`rockscreen.pipeline.execution.choose.open_executor`: local processes, or Dask): the
main process alone collects results and writes the archive.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rockscreen.pipeline.engine.cases import BlockCache, Solvers
from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.hazard import (
    RETURN_PERIODS_Y,
    hazard_curve,
    limit_state_return_period,
    site_hazard,
)
from rockscreen.pipeline.hazard.selection import SCALE_LIMITS
from rockscreen.pipeline.hazard.suite import site_record_set
from rockscreen.pipeline.risk.classes import DEFAULT_LIMITS, NONCOMPLIANT_MARK, risk_class
from rockscreen.pipeline.risk.compliance import (
    DEFAULT_TOLERANCE,
    SetCompliance,
    noncompliance_message,
    set_compliance,
)
from rockscreen.pipeline.risk.fragility import fit_fragility
from rockscreen.pipeline.risk.hazard_integral import (
    EXTRAPOLATION_SHARE_LIMIT,
    HazardCurve,
    annual_rate_of_overturning,
    extrapolated_shares,
    probability_in,
)
from rockscreen.pipeline.risk.lv1 import lv1_indices
from rockscreen.pipeline.risk.sites import TowerSite, tower_defaults, tower_sites
from rockscreen.pipeline.risk.stripes import StripeOptions, evaluate_stripe, stripe_arrays
from rockscreen.stations.errors import RockscreenError

__all__ = [
    "AssessOptions",
    "AssessResult",
    "TowerSite",
    "run_assess",
    "summarize_tower",
    "tower_defaults",
    "tower_sites",
]

#: Towers per chunk of the stripe phase (a chunk carries its site's record sets).
MAX_CHUNK_TOWERS = 32
#: Summary columns taken from the tower's :class:`~rockscreen.pipeline.risk.fragility.Fragility`
#: (column: attribute).
FRAGILITY_COLUMNS = {
    "fragility_median_g": "median_g",
    "fragility_beta": "beta",
    "median_is_bound": "bound",
    "fit_loglik": "loglik",
    "fit_deviance": "deviance",
    "fit_dof": "dof",
    "fit_max_residual": "max_residual",
    "se_ln_median": "se_ln_median",
    "se_beta": "se_beta",
}
#: Summary columns that are the tower's :class:`~pipeline.risk.lv1.LV1` attributes of that name.
LV1_COLUMNS = (
    "capacity_pga_g",
    "capacity_return_period_y",
    "tr_slv_y",
    "ag_slv_g",
    "safety_index",
    "acceleration_factor",
)


@dataclass(frozen=True)
class AssessOptions:
    """Options of an assessment."""

    #: Stripes [y] (default the nine tabulated return periods of NTC 2018).
    return_periods_y: tuple[float, ...] = ()
    #: Models, damage levels, free motion.
    stripe: StripeOptions = field(default_factory=StripeOptions)
    #: Keyword arguments of :func:`pipeline.hazard.select_records` (``n_records``, ...); ``seed``
    #: seeds the embedded synthetic suite.
    selection: dict[str, Any] = field(default_factory=dict)
    #: Rounding of tower locations into shared sites [deg]; 0 = exact.
    site_resolution_deg: float = 0.01
    #: Lower I_S limits of the classes (:mod:`rockscreen.pipeline.risk.classes`).
    class_limits: tuple[float, ...] = DEFAULT_LIMITS
    #: Run on record sets that fail NTC 2018 §3.2.3.6 / §7.3.5 (every verdict built on them
    #: is marked); False refuses them before any solve (:mod:`rockscreen.pipeline.risk.compliance`).
    allow_noncompliant: bool = False

    def set_compliance(self, record_set: Any) -> SetCompliance:
        """Return the compliance of a record set under these options' tolerance and limits."""
        selection = self.selection
        return set_compliance(
            record_set,
            tolerance=tuple(selection.get("tolerance", DEFAULT_TOLERANCE)),
            scale_limits=tuple(selection.get("scale_limits", SCALE_LIMITS)),
        )

    def resolved_return_periods(self) -> tuple[float, ...]:
        """Return the stripes' return periods [y], the nine tabulated ones by default."""
        if self.return_periods_y:
            return tuple(sorted(float(tr) for tr in self.return_periods_y))

        return tuple(float(tr) for tr in RETURN_PERIODS_Y)


# ------------------------------------------------------------------------ worker side


@dataclass(frozen=True)
class _Shared:
    suite: Any
    options: AssessOptions


def _work(shared: _Shared, chunk: tuple) -> Any:
    """Executor work function: a record-set task or a chunk of towers of one site."""
    kind = chunk[0]
    if kind == "set":
        _, key, tr = chunk
        return ("set", key, tr, _record_set(shared, key, tr))
    _, sets, ags, sites = chunk
    return ("towers", [_tower_stripes(shared, site, sets, ags) for site in sites])


def _record_set(shared: _Shared, key: tuple, tr: float) -> Any:
    lon, lat, soil, topography = key
    options = dict(shared.options.selection)
    try:
        return site_record_set(lon, lat, tr, soil, topography, suite=shared.suite, **options)
    except Exception as exc:  # noqa: BLE001 - reported per site, the run goes on
        if isinstance(exc, (RockscreenError, ValueError, ArithmeticError)):
            return f"record set at lon={lon:g} lat={lat:g} TR={tr:g} y: {exc}"
        raise


def _tower_stripes(shared: _Shared, site: TowerSite, sets: dict, ags: dict) -> dict[str, Any]:
    stripes, outcomes, n_solves = [], [], 0
    blocks = BlockCache(site.tower, Solvers())
    for tr in shared.options.resolved_return_periods():
        stripe, rows, solves = evaluate_stripe(
            site.tower, sets[tr], tr, ags[tr], shared.options.stripe, blocks
        )
        stripes.append(stripe)
        outcomes.extend(rows)
        n_solves += solves
    return {"index": site.index, "stripes": stripes, "outcomes": outcomes, "n_solves": n_solves}


# ------------------------------------------------------------------------ per tower


def summarize_tower(
    site: TowerSite,
    stripes: Sequence[dict[str, Any]],
    curve: HazardCurve,
    tr_slv_y: float,
    ag_slv_g: float,
    class_limits: Sequence[float] = DEFAULT_LIMITS,
) -> dict[str, Any]:
    """Return the summary row of one tower from its stripes and its site hazard.

    Parameters
    ----------
    site : TowerSite
    stripes : sequence of dict
        The tower's stripe rows (:func:`rockscreen.pipeline.risk.stripes.evaluate_stripe`).
    curve : HazardCurve
        The site's hazard curve (tabulated points).
    tr_slv_y : float
        Return period of the SLV action [y].
    ag_slv_g : float
        Site's ag at ``tr_slv_y`` [g].
    class_limits : sequence of float
        I_S limits of the classes.

    Returns
    -------
    dict
        The ``/summary`` row (units follow the column names:
        :func:`rockscreen.pipeline.archive.risk_archive.units_of`).
    """
    arrays = stripe_arrays(stripes)
    if not len(arrays[0]):
        return base_summary_row(
            site,
            "every record of every stripe reaches the vertical limit of the rigid-block model "
            "(scaled vertical <= -g): no fragility",
        )
    fragility = fit_fragility(*arrays)
    lv1 = lv1_indices(fragility, curve, tr_slv_y, ag_slv_g)
    notes = [n for n in (fragility.note, lv1.note) if n]
    share_above = share_below = math.nan
    if fragility.is_fitted:
        rate = annual_rate_of_overturning(curve, fragility.median_g, fragility.beta)
        p50 = probability_in(rate, 50.0)
        share_above, share_below = extrapolated_shares(curve, fragility.median_g, fragility.beta)
        if share_above + share_below > EXTRAPOLATION_SHARE_LIMIT:
            notes.append(
                f"{100 * (share_above + share_below):.0f} % of lambda_C comes from the hazard "
                f"curve extrapolated beyond TR = {1 / curve.rate_per_y[-1]:.0f} y "
                f"({100 * share_above:.0f} %) or below TR = {1 / curve.rate_per_y[0]:.0f} y "
                f"({100 * share_below:.0f} %), where the code defines no hazard: lambda_C and "
                "P50 rest mostly on that extrapolation"
            )
    else:
        rate = p50 = math.nan
        notes.append("annual rate of overturning undefined: the fragility median is only a bound")
    if site.assumptions:
        notes.append("assumed " + ", ".join(site.assumptions))
    row = base_summary_row(site)
    row.update({column: getattr(fragility, name) for column, name in FRAGILITY_COLUMNS.items()})
    row.update({name: getattr(lv1, name) for name in LV1_COLUMNS})
    row.update(
        annual_rate_overturning_per_y=rate,
        p_overturning_50y=p50,
        rate_share_tr_over_2475=share_above,
        rate_share_tr_under_30=share_below,
        rate_extrapolated=bool(share_above + share_below > EXTRAPOLATION_SHARE_LIMIT),
        risk_class=risk_class(lv1.safety_index, class_limits),
        n_stripes=len(stripes),
        models=stripes[0]["models"] if stripes else "",
        note="; ".join(notes),
    )
    return row


def base_summary_row(site: TowerSite, note: str = "") -> dict[str, Any]:
    """Return a summary row with the tower's identity and NaN results (filled when assessed)."""
    tower = site.tower
    nan = math.nan
    return {
        "id": tower.id,
        "name": tower.name,
        "lat_deg": nan if tower.lat is None else float(tower.lat),
        "lon_deg": nan if tower.lon is None else float(tower.lon),
        "site_lat_deg": site.lat_deg,
        "site_lon_deg": site.lon_deg,
        "soil_class": site.soil_class,
        "soil_class_source": site.soil_class_source,
        "topography": site.topography,
        "use_class": site.use_class,
        "nominal_life_y": site.nominal_life_y,
        "fragility_median_g": nan,
        "fragility_beta": nan,
        "median_is_bound": "",
        "fit_loglik": nan,
        "fit_deviance": nan,
        "fit_dof": 0,
        "fit_max_residual": nan,
        "se_ln_median": nan,
        "se_beta": nan,
        "annual_rate_overturning_per_y": nan,
        "p_overturning_50y": nan,
        "rate_share_tr_over_2475": nan,
        "rate_share_tr_under_30": nan,
        "rate_extrapolated": False,
        "capacity_pga_g": nan,
        "capacity_return_period_y": nan,
        "tr_slv_y": nan,
        "ag_slv_g": nan,
        "safety_index": nan,
        "acceleration_factor": nan,
        "risk_class": "undefined",
        "basis_compliant": True,
        "n_stripes": 0,
        "n_solves": 0,
        "models": "",
        "note": note,
    }


# ------------------------------------------------------------------------ orchestration


@dataclass
class AssessResult:
    """Tables of an assessment, in inventory order (stripes by return period)."""

    #: Rows of ``/summary``, ``/stripes``, ``/outcomes``, ``/selection``, ``/failures``.
    summary: list[dict[str, Any]]
    stripes: list[dict[str, Any]]
    outcomes: list[dict[str, Any]]
    selection: list[dict[str, Any]]
    failures: list[dict[str, Any]]
    #: Solver calls made.
    n_solves: int = 0
    #: Distinct sites (record-set keys).
    n_sites: int = 0


def _site_hazard(site: TowerSite, trs: Sequence[float]) -> dict[str, Any]:
    """Hazard of a site: curve, stripe ag, T_R,SLV and ag_SLV (HazardError propagates)."""
    periods, ag = hazard_curve(site.lon_deg, site.lat_deg)
    tr_slv = limit_state_return_period("SLV", site.nominal_life_y, site.use_class)
    return {
        "curve": HazardCurve.from_return_periods(periods, ag),
        "ags": {tr: site_hazard(site.lon_deg, site.lat_deg, tr).ag_g for tr in trs},
        "tr_slv": tr_slv,
        "ag_slv": site_hazard(site.lon_deg, site.lat_deg, tr_slv).ag_g,
    }


def _selection_row(
    key: tuple, tr: float, record_set: Any, compliance: SetCompliance
) -> dict[str, Any]:
    return {
        "site_lon_deg": key[0],
        "site_lat_deg": key[1],
        "soil_class": key[2],
        "topography": key[3],
        "return_period_y": tr,
        "records": ",".join(r.name for r in record_set.records),
        "scale_factors": ",".join(f"{f:.6g}" for f in record_set.scale_factors),
        "ratio_min": float(record_set.ratio_min),
        "ratio_max": float(record_set.ratio_max),
        "meets_tolerance": bool(record_set.meets_tolerance),
        "message": record_set.message,
        "n_records": compliance.n_records,
        "compliant": compliance.compliant,
        "compliance_note": compliance.reason,
    }


def run_assess(
    towers: Sequence[Any],
    options: AssessOptions,
    executor: Any,
    *,
    suite: Any = None,
    jobs: int = 1,
    progress: Callable[[str], None] | None = None,
) -> AssessResult:
    """Assess every tower of an inventory (module docstring).

    Parameters
    ----------
    towers : sequence of rockscreen.stations.inventory.Tower
    options : AssessOptions
    executor : executor
        :func:`rockscreen.pipeline.execution.choose.open_executor`'s executor (not started).
    suite : sequence of SuiteRecord, optional
        Candidate records; None = the embedded synthetic suite.
    jobs : int
        Workers (sizes the chunks).
    progress : callable, optional
        Receives one line of progress text at a time.

    Returns
    -------
    AssessResult
    """
    say = progress or (lambda text: None)
    trs = options.resolved_return_periods()
    sites = tower_sites(towers, options.site_resolution_deg)
    summary: dict[int, dict[str, Any]] = {}
    failures: list[dict[str, Any]] = []
    hazards: dict[tuple, dict[str, Any]] = {}
    groups: dict[tuple, list[TowerSite]] = {}
    for site in sites:
        if math.isnan(site.lon_deg):
            reason = "no coordinates: the site hazard is unknown, the tower is not assessed"
            summary[site.index] = base_summary_row(site, reason)
            failures.append({"kind": "site", "subject": site.tower.id, "reason": reason})
            continue
        hazard_key = (site.lon_deg, site.lat_deg, site.nominal_life_y, site.use_class)
        try:
            if hazard_key not in hazards:
                hazards[hazard_key] = _site_hazard(site, trs)
        except Exception as exc:  # noqa: BLE001 - HazardError and the like, per tower
            if not isinstance(exc, RockscreenError):
                raise
            summary[site.index] = base_summary_row(site, f"site hazard: {exc}")
            failures.append({"kind": "hazard", "subject": site.tower.id, "reason": str(exc)})
            continue
        groups.setdefault(site.key, []).append(site)
    shared = _Shared(suite, options)
    result = AssessResult([], [], [], [], failures, n_sites=len(groups))
    with executor as ex:
        ex.start(_work, shared)
        sets = _compute_sets(ex, groups, trs, say)
        basis = _check_basis(groups, sets, trs, options, say)
        stripes_by_index = _compute_stripes(ex, groups, sets, hazards, trs, jobs, say, result)
    for key in groups:
        for tr in trs:
            if not isinstance(sets[key][tr], str):
                result.selection.append(_selection_row(key, tr, sets[key][tr], basis[key][tr]))
    for site in sites:
        if site.index in summary:
            continue
        hazard = hazards[(site.lon_deg, site.lat_deg, site.nominal_life_y, site.use_class)]
        failed = [sets[site.key][tr] for tr in trs if isinstance(sets[site.key][tr], str)]
        if failed:
            summary[site.index] = base_summary_row(site, failed[0])
            failures.append({"kind": "selection", "subject": site.tower.id, "reason": failed[0]})
            continue
        done = stripes_by_index[site.index]
        row = summarize_tower(
            site,
            done["stripes"],
            hazard["curve"],
            hazard["tr_slv"],
            hazard["ag_slv"],
            options.class_limits,
        )
        row["n_solves"] = done["n_solves"]
        _mark_basis(row, basis[site.key])
        summary[site.index] = row
        result.stripes.extend(done["stripes"])
        result.outcomes.extend(done["outcomes"])
    result.summary = [summary[i] for i in sorted(summary)]
    return result


def _check_basis(
    groups: dict, sets: dict, trs: Sequence[float], options: AssessOptions, say: Callable
) -> dict[tuple, dict[float, SetCompliance]]:
    """Measure every record set (NTC 2018 §3.2.3.6, §7.3.5); refuse a non-compliant basis.

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
        for tr in trs:
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


def _mark_basis(row: dict[str, Any], basis: dict[float, SetCompliance]) -> None:
    """Mark a tower's row built on non-compliant record sets (``basis_compliant``, note)."""
    bad = [(tr, c) for tr, c in basis.items() if not c.compliant]
    if not bad:
        return
    row["basis_compliant"] = False
    text = "; ".join(f"TR={tr:g} y: {c.reason}" for tr, c in bad)
    mark = f"{NONCOMPLIANT_MARK} (run with --allow-noncompliant): {text}"
    row["note"] = f"{row['note']}; {mark}" if row["note"] else mark


def _compute_sets(ex: Any, groups: dict, trs: Sequence[float], say: Callable) -> dict:
    sets: dict[tuple, dict[float, Any]] = {key: {} for key in groups}
    for key in groups:
        for tr in trs:
            ex.submit(("set", key, tr))
    total, done = len(groups) * len(trs), 0
    for _, key, tr, record_set in ex.completed():
        sets[key][tr] = record_set
        done += 1
        if done == total or done % max(1, total // 10) == 0:
            say(f"record sets: {done}/{total} (sites x return periods)")
    return sets


def _compute_stripes(ex, groups, sets, hazards, trs, jobs, say, result) -> dict[int, Any]:
    n_towers = sum(len(v) for v in groups.values())
    size = int(np.clip(math.ceil(n_towers / (8 * max(jobs, 1))), 1, MAX_CHUNK_TOWERS))
    for key, members in groups.items():
        if any(isinstance(sets[key][tr], str) for tr in trs):
            continue
        first = members[0]
        hazard = hazards[(first.lon_deg, first.lat_deg, first.nominal_life_y, first.use_class)]
        for start in range(0, len(members), size):
            ex.submit(("towers", sets[key], hazard["ags"], members[start : start + size]))
    out: dict[int, Any] = {}
    for _, towers in ex.completed():
        for item in towers:
            out[item["index"]] = item
            result.n_solves += item["n_solves"]
        if len(out) == n_towers or len(out) % max(1, n_towers // 10) < len(towers):
            say(f"towers: {len(out)}/{n_towers} assessed")
    return out
