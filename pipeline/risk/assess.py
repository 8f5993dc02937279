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
4. **Per tower, in the worker** (:func:`rockscreen.pipeline.risk.tower_ida.tower_ida`): the
   collapse and SLV intensity of every record of the site's set at the tower's T_R,SLV
   (incremental dynamic analysis, in the site's ag on rock); then :func:`summarize_tower`:
   the censored lognormal fits of collapse and SLV, I_S and f_a from the SLV median
   divided by F_C, the annual rate of overturning and P(overturning in 50 years) from the
   collapse fragility, bootstrap intervals over the records, the stripe fit beside as a
   check, and the risk class.

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
from rockscreen.pipeline.risk.code_checks.confidence import confidence_factor
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
    extrapolated_shares,
    probability_in,
)
from rockscreen.pipeline.risk.ida import IdaOptions
from rockscreen.pipeline.risk.lv1 import lv1_indices
from rockscreen.pipeline.risk.sites import TowerSite, tower_defaults, tower_sites
from rockscreen.pipeline.risk.stripes import StripeOptions, evaluate_stripe, stripe_arrays
from rockscreen.pipeline.risk.tower_checks import (
    BELFRY_MISSING,
    LV1_MISSING,
    checks_nan_columns,
    governing_columns,
    kinematic_columns,
    part_fragility_columns,
    part_models,
)
from rockscreen.pipeline.risk.tower_ida import (
    DEFAULT_BOOTSTRAP_RESAMPLES,
    IDA_LEVELS,
    bootstrap_intervals,
    collapse_rate,
    fit_level,
    tower_ida,
    tower_seed,
)
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
#: Knowledge level taken when none is given (an assumption, written in every row's note).
DEFAULT_KNOWLEDGE_LEVEL = "LC1"
#: Summary columns of the stripe fit (the check shown beside the IDA fragility), from the
#: tower's :class:`~rockscreen.pipeline.risk.fragility.Fragility` (column: attribute).
STRIPE_COLUMNS = {
    "stripe_median_g": "median_g",
    "stripe_beta": "beta",
    "stripe_bound": "bound",
    "stripe_loglik": "loglik",
    "stripe_deviance": "deviance",
    "stripe_dof": "dof",
    "stripe_max_residual": "max_residual",
    "stripe_se_ln_median": "se_ln_median",
    "stripe_se_beta": "se_beta",
}
#: Summary columns of each IDA fit, ``<level>_<suffix>`` for level ``collapse`` and ``slv``
#: (suffix: :class:`~rockscreen.pipeline.risk.fragility.CensoredFit` attribute).
CENSORED_COLUMNS = {
    "median_g": "median_g",
    "beta": "beta",
    "bound": "bound",
    "se_ln_median": "se_ln_median",
    "se_beta": "se_beta",
    "loglik": "loglik",
    "n_records": "n",
    "n_censored": "n_censored",
}
#: Bootstrap columns (:func:`rockscreen.pipeline.risk.tower_ida.bootstrap_intervals`).
BOOTSTRAP_COLUMNS = (
    "collapse_median_lo90_g",
    "collapse_median_hi90_g",
    "annual_rate_lo90_per_y",
    "annual_rate_hi90_per_y",
    "safety_index_lo90",
    "safety_index_hi90",
    "bootstrap_resamples",
    "bootstrap_fitted_collapse",
    "bootstrap_fitted_slv",
)
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
    #: Knowledge level of every tower (LC1, LC2, LC3; Circolare 2019 §C8.5.4); its F_C divides
    #: the SLV capacity. None: :data:`DEFAULT_KNOWLEDGE_LEVEL`, an assumption said in the note.
    knowledge_level: str | None = None
    #: Resamples of the record bootstrap (0: no intervals).
    bootstrap_resamples: int = DEFAULT_BOOTSTRAP_RESAMPLES
    #: Seed of the bootstrap (mixed per tower with its id).
    seed: int = 0

    def ida_options(self, models: Sequence[str] | None = None) -> IdaOptions:
        """Return the IDA search options (the stripes' models, or ``models``, and free motion)."""
        enabled = self.stripe.models if models is None else tuple(models)
        return IdaOptions(models=enabled, free_motion_s=self.stripe.free_motion_s)

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
    _, sets, members = chunk
    return ("towers", [_tower_work(shared, site, sets, hazard) for site, hazard in members])


def _record_set(shared: _Shared, key: tuple, tr: float) -> Any:
    lon, lat, soil, topography = key
    options = dict(shared.options.selection)
    try:
        return site_record_set(lon, lat, tr, soil, topography, suite=shared.suite, **options)
    except Exception as exc:  # noqa: BLE001 - reported per site, the run goes on
        if isinstance(exc, (RockscreenError, ValueError, ArithmeticError)):
            return f"record set at lon={lon:g} lat={lat:g} TR={tr:g} y: {exc}"
        raise


def _tower_work(shared: _Shared, site: TowerSite, sets: dict, hazard: dict) -> dict[str, Any]:
    """Stripes, IDA and the summary row of one tower (in the worker)."""
    options = shared.options
    stripes, outcomes, n_solves = [], [], 0
    blocks = BlockCache(site.tower, Solvers())
    for tr in options.resolved_return_periods():
        stripe, rows, solves = evaluate_stripe(
            site.tower, sets[tr], tr, hazard["ags"][tr], options.stripe, blocks
        )
        stripes.append(stripe)
        outcomes.extend(rows)
        n_solves += solves
    tr_slv = hazard["tr_slv"]
    ida, ida_solves = tower_ida(
        site.tower, sets[tr_slv], tr_slv, hazard["ag_slv"], options.ida_options(), blocks
    )
    # Each part model (the belfry) alone: its own fragility, beside the tower's.
    parts = {}
    for model in part_models(site.tower, options.stripe.models):
        rows, solves = tower_ida(
            site.tower,
            sets[tr_slv],
            tr_slv,
            hazard["ag_slv"],
            options.ida_options(models=(model.name,)),
            blocks,
        )
        parts[model.name] = rows
        n_solves += solves
    row = summarize_tower(
        site,
        stripes,
        hazard["curve"],
        tr_slv,
        hazard["ag_slv"],
        options.class_limits,
        ida=ida,
        knowledge_level=options.knowledge_level,
        bootstrap_resamples=options.bootstrap_resamples,
        seed=options.seed,
        parts=parts,
    )
    row["n_solves"] = n_solves + ida_solves
    row["ida_n_solves"] = ida_solves
    return {
        "index": site.index,
        "stripes": stripes,
        "outcomes": outcomes,
        "ida": ida,
        "row": row,
        "n_solves": n_solves + ida_solves,
    }


# ------------------------------------------------------------------------ per tower


def summarize_tower(
    site: TowerSite,
    stripes: Sequence[dict[str, Any]],
    curve: HazardCurve,
    tr_slv_y: float,
    ag_slv_g: float,
    class_limits: Sequence[float] = DEFAULT_LIMITS,
    *,
    ida: Sequence[dict[str, Any]] = (),
    knowledge_level: str | None = None,
    bootstrap_resamples: int = DEFAULT_BOOTSTRAP_RESAMPLES,
    seed: int = 0,
    parts: dict[str, Sequence[dict[str, Any]]] | None = None,
) -> dict[str, Any]:
    """Return the summary row of one tower from its IDA intensities, stripes and site hazard.

    Parameters
    ----------
    site : TowerSite
    stripes : sequence of dict
        The tower's stripe rows (:func:`rockscreen.pipeline.risk.stripes.evaluate_stripe`):
        the stripe fit, shown beside as a check.
    curve : HazardCurve
        The site's hazard curve (tabulated points).
    tr_slv_y : float
        Return period of the SLV action [y].
    ag_slv_g : float
        Site's ag at ``tr_slv_y`` [g].
    class_limits : sequence of float
        I_S limits of the classes.
    ida : sequence of dict
        The tower's ``/ida`` rows (:func:`rockscreen.pipeline.risk.tower_ida.tower_ida`);
        empty: no fragility.
    knowledge_level : str, optional
        LC1, LC2 or LC3; None takes :data:`DEFAULT_KNOWLEDGE_LEVEL` as an assumption (noted).
    bootstrap_resamples : int
        Resamples of the record bootstrap (0: none).
    seed : int
        Seed of the bootstrap (mixed with the tower's id).
    parts : dict, optional
        Part model name -> its own IDA rows (the belfry alone): its fragility columns.

    Returns
    -------
    dict
        The ``/summary`` row (units: :data:`rockscreen.pipeline.archive.schema.ASSESS_TABLES`).
    """
    level = knowledge_level or DEFAULT_KNOWLEDGE_LEVEL
    fc = confidence_factor(level)
    row = base_summary_row(site)
    notes: list[str] = []
    arrays = stripe_arrays(stripes)
    if len(arrays[0]):
        stripe_fit = fit_fragility(*arrays)
        row.update({column: getattr(stripe_fit, name) for column, name in STRIPE_COLUMNS.items()})
    else:
        notes.append(
            "every record of every stripe reaches the vertical limit of the rigid-block model "
            "(scaled vertical <= -g): no stripe fit"
        )
    row.update(
        knowledge_level=level,
        confidence_factor=fc,
        n_stripes=len(stripes),
        models=stripes[0]["models"] if stripes else "",
        tr_slv_y=float(tr_slv_y),
        ag_slv_g=float(ag_slv_g),
    )
    if not ida:
        row["note"] = "; ".join([*notes, "no IDA intensities: no fragility"])
        return row
    fits = {name: fit_level(ida, name) for name in IDA_LEVELS}
    for name, fit in fits.items():
        row.update({f"{name}_{suffix}": getattr(fit, a) for suffix, a in CENSORED_COLUMNS.items()})
        if fit.note and name == "collapse":
            notes.append(f"collapse fit: {fit.note}")
        elif fit.note:
            text = fit.note.replace("overturned the tower", "reached the SLV level")
            notes.append(f"SLV fit (theta_max/alpha >= 0.4): {text}")
    row["models"] = row["models"] or str(ida[0]["models"])
    collapse, slv = fits["collapse"], fits["slv"]
    lv1 = lv1_indices(slv, curve, tr_slv_y, ag_slv_g, fc)
    if lv1.note:
        notes.append(f"I_S and f_a from the SLV fragility: {lv1.note}")
    row.update({name: getattr(lv1, name) for name in LV1_COLUMNS})
    rate = collapse_rate(curve, collapse)
    share_above = share_below = math.nan
    if math.isfinite(rate) and collapse.beta > 0:
        share_above, share_below = extrapolated_shares(curve, collapse.median_g, collapse.beta)
        if share_above + share_below > EXTRAPOLATION_SHARE_LIMIT:
            notes.append(
                f"{100 * (share_above + share_below):.0f} % of lambda_C comes from the hazard "
                f"curve extrapolated beyond TR = {1 / curve.rate_per_y[-1]:.0f} y "
                f"({100 * share_above:.0f} %) or below TR = {1 / curve.rate_per_y[0]:.0f} y "
                f"({100 * share_below:.0f} %), where the code defines no hazard: lambda_C and "
                "P50 rest mostly on that extrapolation"
            )
    elif not math.isfinite(rate):
        notes.append(
            "annual rate of overturning undefined: the collapse fragility median is only a bound"
        )
    row.update(
        annual_rate_overturning_per_y=rate,
        p_overturning_50y=probability_in(rate, 50.0) if math.isfinite(rate) else math.nan,
        rate_share_tr_over_2475=share_above,
        rate_share_tr_under_30=share_below,
        rate_extrapolated=bool(share_above + share_below > EXTRAPOLATION_SHARE_LIMIT),
        risk_class=risk_class(lv1.safety_index, class_limits),
    )
    row.update(
        bootstrap_intervals(
            ida, curve, tr_slv_y, fc, bootstrap_resamples, tower_seed(seed, site.tower.id)
        )
    )
    notes.extend(_code_checks(row, site, curve, tr_slv_y, ag_slv_g, fc, class_limits, parts))
    assumed = "" if knowledge_level else " assumed: not in the inventory (--knowledge-level)"
    notes.append(f"knowledge level {level} (F_C = {fc:.2f} divides the SLV capacity){assumed}")
    if site.assumptions:
        notes.append("assumed " + ", ".join(site.assumptions))
    row["note"] = "; ".join(notes)
    return row


def _code_checks(
    row: dict[str, Any],
    site: TowerSite,
    curve: HazardCurve,
    tr_slv_y: float,
    ag_slv_g: float,
    fc: float,
    class_limits: Sequence[float],
    parts: dict[str, Sequence[dict[str, Any]]] | None,
) -> list[str]:
    """Fill the kinematic, part-model and governing columns of a row; return the notes."""
    notes: list[str] = []
    for name, rows in (parts or {}).items():
        columns, more = part_fragility_columns(name, rows, curve, tr_slv_y, ag_slv_g, fc)
        row.update(columns)
        notes += more
    try:
        columns, more = kinematic_columns(site, fc)
    except RockscreenError as exc:  # off the NTC grid, a bad geometry: said, not fatal
        columns, more = {}, [f"kinematic checks not made: {exc}"]
    row.update(columns)
    notes += more
    missing = [] if site.tower.has_belfry else [BELFRY_MISSING]
    missing.append(LV1_MISSING)
    row.update(governing_columns(row, class_limits, missing))
    if row.get("checks_disagree"):
        notes.append(row["checks_disagree"])
    return notes


def _fit_nan(level: str) -> dict[str, Any]:
    """NaN columns of an IDA fit of ``level``."""
    out: dict[str, Any] = {f"{level}_{suffix}": math.nan for suffix in CENSORED_COLUMNS}
    out.update({f"{level}_bound": "", f"{level}_n_records": 0, f"{level}_n_censored": 0})
    return out


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
        **_fit_nan("collapse"),
        "collapse_median_lo90_g": nan,
        "collapse_median_hi90_g": nan,
        **_fit_nan("slv"),
        "stripe_median_g": nan,
        "stripe_beta": nan,
        "stripe_bound": "",
        "stripe_loglik": nan,
        "stripe_deviance": nan,
        "stripe_dof": 0,
        "stripe_max_residual": nan,
        "stripe_se_ln_median": nan,
        "stripe_se_beta": nan,
        "knowledge_level": "",
        "confidence_factor": nan,
        "annual_rate_overturning_per_y": nan,
        "annual_rate_lo90_per_y": nan,
        "annual_rate_hi90_per_y": nan,
        "p_overturning_50y": nan,
        "rate_share_tr_over_2475": nan,
        "rate_share_tr_under_30": nan,
        "rate_extrapolated": False,
        "capacity_pga_g": nan,
        "capacity_return_period_y": nan,
        "tr_slv_y": nan,
        "ag_slv_g": nan,
        "safety_index": nan,
        "safety_index_lo90": nan,
        "safety_index_hi90": nan,
        "acceleration_factor": nan,
        "bootstrap_resamples": 0,
        "bootstrap_fitted_collapse": 0,
        "bootstrap_fitted_slv": 0,
        "risk_class": "undefined",
        "basis_compliant": True,
        "n_stripes": 0,
        "n_solves": 0,
        "ida_n_solves": 0,
        "models": "",
        **checks_nan_columns(),
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
    #: Rows of ``/ida`` (tower x record x component of the set at T_R,SLV).
    ida: list[dict[str, Any]] = field(default_factory=list)
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
    # The stripes' return periods and, per site, the T_R,SLV of its towers (the IDA's set).
    set_trs = {
        key: sorted(set(trs) | {_hazard_of(hazards, site)["tr_slv"] for site in members})
        for key, members in groups.items()
    }
    shared = _Shared(suite, options)
    result = AssessResult([], [], [], [], failures, n_sites=len(groups))
    with executor as ex:
        ex.start(_work, shared)
        sets = _compute_sets(ex, groups, set_trs, say)
        basis = _check_basis(groups, sets, set_trs, options, say)
        done_by_index = _compute_towers(ex, groups, sets, hazards, set_trs, jobs, say, result)
    for key in groups:
        for tr in set_trs[key]:
            if not isinstance(sets[key][tr], str):
                result.selection.append(_selection_row(key, tr, sets[key][tr], basis[key][tr]))
    for site in sites:
        if site.index in summary:
            continue
        own = (*trs, _hazard_of(hazards, site)["tr_slv"])
        failed = [sets[site.key][tr] for tr in own if isinstance(sets[site.key][tr], str)]
        if failed:
            summary[site.index] = base_summary_row(site, failed[0])
            failures.append({"kind": "selection", "subject": site.tower.id, "reason": failed[0]})
            continue
        done = done_by_index[site.index]
        row = done["row"]
        _mark_basis(row, {tr: basis[site.key][tr] for tr in own})
        summary[site.index] = row
        result.stripes.extend(done["stripes"])
        result.outcomes.extend(done["outcomes"])
        result.ida.extend(done["ida"])
    result.summary = [summary[i] for i in sorted(summary)]
    return result


def _hazard_of(hazards: dict, site: TowerSite) -> dict[str, Any]:
    """Return the hazard of a located site (curve, stripe ags, T_R,SLV, ag_SLV)."""
    return hazards[(site.lon_deg, site.lat_deg, site.nominal_life_y, site.use_class)]


def _check_basis(
    groups: dict, sets: dict, set_trs: dict, options: AssessOptions, say: Callable
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


def _mark_basis(row: dict[str, Any], basis: dict[float, SetCompliance]) -> None:
    """Mark a tower's row built on non-compliant record sets (``basis_compliant``, note)."""
    bad = [(tr, c) for tr, c in basis.items() if not c.compliant]
    if not bad:
        return
    row["basis_compliant"] = False
    text = "; ".join(f"TR={tr:g} y: {c.reason}" for tr, c in bad)
    mark = f"{NONCOMPLIANT_MARK} (run with --allow-noncompliant): {text}"
    row["note"] = f"{row['note']}; {mark}" if row["note"] else mark


def _compute_sets(ex: Any, groups: dict, set_trs: dict, say: Callable) -> dict:
    sets: dict[tuple, dict[float, Any]] = {key: {} for key in groups}
    for key in groups:
        for tr in set_trs[key]:
            ex.submit(("set", key, tr))
    total, done = sum(len(set_trs[key]) for key in groups), 0
    for _, key, tr, record_set in ex.completed():
        sets[key][tr] = record_set
        done += 1
        if done == total or done % max(1, total // 10) == 0:
            say(f"record sets: {done}/{total} (sites x return periods)")
    return sets


def _compute_towers(ex, groups, sets, hazards, set_trs, jobs, say, result) -> dict[int, Any]:
    """Submit the towers in chunks of one site; return each tower's stripes, IDA and row."""
    n_towers = sum(len(v) for v in groups.values())
    size = int(np.clip(math.ceil(n_towers / (8 * max(jobs, 1))), 1, MAX_CHUNK_TOWERS))
    for key, members in groups.items():
        if any(isinstance(sets[key][tr], str) for tr in set_trs[key]):
            n_towers -= len(members)
            continue
        for start in range(0, len(members), size):
            chunk = [(m, _hazard_of(hazards, m)) for m in members[start : start + size]]
            ex.submit(("towers", sets[key], chunk))
    out: dict[int, Any] = {}
    for _, towers in ex.completed():
        for item in towers:
            out[item["index"]] = item
            result.n_solves += item["n_solves"]
        if len(out) == n_towers or len(out) % max(1, n_towers // 10) < len(towers):
            say(f"towers: {len(out)}/{n_towers} assessed")
    return out
