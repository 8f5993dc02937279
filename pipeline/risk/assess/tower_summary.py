"""One tower's ``/summary`` row of ``rockscreen assess``: what the worker computes per tower.

From a tower's stripes, its IDA intensities and its site hazard (computed by
:mod:`rockscreen.pipeline.risk.assess.run` in the worker), :func:`summarize_tower` builds the row:

1. the stripe fit, shown beside as a check (:data:`STRIPE_COLUMNS`);
2. the censored lognormal fits of collapse and SLV (:data:`CENSORED_COLUMNS`);
3. I_S and f_a from the SLV median divided by F_C (:data:`LV1_COLUMNS`);
4. the annual rate of overturning and P(overturning in 50 years) from the collapse
   fragility, with the share of the rate taken from the extrapolated hazard curve, and the
   risk class;
5. bootstrap intervals over the records (:data:`BOOTSTRAP_COLUMNS`);
6. the code's checks: part-model fragilities (the belfry), kinematic mechanisms, the
   governing mechanism.

:func:`base_summary_row` is the row of a tower not (yet) assessed: its identity and NaN results.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from typing import Any

from rockscreen.pipeline.risk.assess.ida import SLV_THETA_RATIO
from rockscreen.pipeline.risk.assess.sites import TowerSite
from rockscreen.pipeline.risk.assess.stripes import stripe_arrays
from rockscreen.pipeline.risk.assess.tower_ida import (
    DEFAULT_BOOTSTRAP_RESAMPLES,
    IDA_LEVELS,
    bootstrap_intervals,
    collapse_rate,
    fit_level,
    tower_seed,
)
from rockscreen.pipeline.risk.checks.confidence import confidence_factor
from rockscreen.pipeline.risk.checks.governing import (
    belfry_not_made,
    governing_columns,
    tower_check_results,
)
from rockscreen.pipeline.risk.checks.knowledge import tower_knowledge_level
from rockscreen.pipeline.risk.checks.registry import CheckContext
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.checks.tower_checks import (
    checks_nan_columns,
    part_block_notes,
    part_fragility_columns,
)
from rockscreen.pipeline.risk.checks.tower_code_checks import run_code_checks
from rockscreen.pipeline.risk.measures.censored_fit import REACHED_SLV, CensoredFit, with_event
from rockscreen.pipeline.risk.measures.classes import DEFAULT_LIMITS, risk_class
from rockscreen.pipeline.risk.measures.fragility import fit_fragility
from rockscreen.pipeline.risk.measures.hazard_integral import (
    EXTRAPOLATION_SHARE_LIMIT,
    HazardCurve,
    extrapolated_shares,
    probability_in,
)
from rockscreen.pipeline.risk.measures.lv1 import lv1_indices
from rockscreen.pipeline.verdict.messages import Message, message, note_columns
from rockscreen.pipeline.verdict.rules import disagreement

__all__ = [
    "BOOTSTRAP_COLUMNS",
    "CENSORED_COLUMNS",
    "LV1_COLUMNS",
    "STRIPE_COLUMNS",
    "base_summary_row",
    "disagreement_messages",
    "summarize_tower",
]


#: Summary columns of the stripe fit (the check shown beside the IDA fragility), from the
#: tower's :class:`~rockscreen.pipeline.risk.measures.fragility.Fragility` (column: attribute).
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
#: (suffix: :class:`~rockscreen.pipeline.risk.measures.censored_fit.CensoredFit` attribute).
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
#: Bootstrap columns (:func:`rockscreen.pipeline.risk.assess.tower_ida.bootstrap_intervals`).
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
#: Summary columns that are the tower's :class:`~pipeline.risk.measures.lv1.LV1` attributes of that
#: name.
LV1_COLUMNS = (
    "capacity_pga_g",
    "capacity_return_period_y",
    "tr_slv_y",
    "ag_slv_g",
    "safety_index",
    "acceleration_factor",
)


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
    fit_method: str = "newton",
    cpu_s: dict[str, float] | None = None,
) -> dict[str, Any]:
    """Return the summary row of one tower from its IDA intensities, stripes and site hazard.

    Parameters
    ----------
    site : TowerSite
    stripes : sequence of dict
        The tower's stripe rows (:func:`rockscreen.pipeline.risk.assess.stripes.evaluate_stripe`):
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
        The tower's ``/ida`` rows (:func:`rockscreen.pipeline.risk.assess.tower_ida.tower_ida`);
        empty: no fragility.
    knowledge_level : str, optional
        LC1, LC2 or LC3 of the run, for towers whose inventory row has none (the row's
        ``knowledge_level`` wins); None and none in the row takes
        :data:`~rockscreen.pipeline.risk.checks.knowledge.DEFAULT_KNOWLEDGE_LEVEL` as an assumption
        (noted).
    bootstrap_resamples : int
        Resamples of the record bootstrap (0: none).
    seed : int
        Seed of the bootstrap (mixed with the tower's id).
    parts : dict, optional
        Part model name -> its own IDA rows (the belfry alone): its fragility columns.
    fit_method : {'newton', 'trust-exact'}
        Optimiser of the tower's censored fits and their bootstrap
        (:func:`rockscreen.pipeline.risk.measures.censored_fit.fit_censored_lognormal`).
    cpu_s : dict, optional
        Receives the CPU time of this thread [s] of the fits (the stripe and IDA fits, the
        indices, the bootstrap: ``"fits"``) and of the code checks (``"checks"``), added to
        what it holds (the benchmark's CPU split).

    Returns
    -------
    dict
        The ``/summary`` row (units: :func:`rockscreen.pipeline.archive.risk_schema.assess_tables`).
    """
    clock = time.thread_time()
    level, source = tower_knowledge_level(site.tower, knowledge_level)
    fc = confidence_factor(level)
    row = base_summary_row(site)
    notes: list[Message] = _stripe_fit_columns(row, stripes)
    row.update(
        knowledge_level=level,
        confidence_factor=fc,
        n_stripes=len(stripes),
        models=stripes[0]["models"] if stripes else "",
        tr_slv_y=float(tr_slv_y),
        ag_slv_g=float(ag_slv_g),
    )
    if not ida:
        row.update(note_columns([*notes, message("assess.no_ida")]))
        return row
    notes += _ida_columns(
        row,
        ida,
        curve,
        (tr_slv_y, ag_slv_g, fc),
        class_limits,
        (bootstrap_resamples, tower_seed(seed, site.tower.id)),
        fit_method,
    )
    fitted = time.thread_time()
    notes.extend(
        _code_checks(row, site, curve, tr_slv_y, ag_slv_g, (level, fc), class_limits, parts)
    )
    if cpu_s is not None:
        cpu_s["fits"] = cpu_s.get("fits", 0.0) + fitted - clock
        cpu_s["checks"] = cpu_s.get("checks", 0.0) + time.thread_time() - fitted
    notes += _assumption_notes(site, level, fc, source=source)
    row.update(note_columns(notes))
    return row


def _ida_columns(
    row: dict[str, Any],
    ida: Sequence[dict[str, Any]],
    curve: HazardCurve,
    slv: tuple[float, float, float],
    class_limits: Sequence[float],
    bootstrap: tuple[int, int],
    fit_method: str,
) -> list[Message]:
    """Fill a row's columns of the tower's IDA; return the notes.

    The censored fits of both levels, the LV1 indices from the SLV fit divided by F_C, the
    overturning rate and probability from the collapse fit, the risk class and the record
    bootstrap's intervals.

    Parameters
    ----------
    row : dict
        The summary row (updated in place).
    ida : sequence of dict
        The tower's ``/ida`` rows, not empty.
    curve : HazardCurve
        The site's hazard curve.
    slv : tuple of float
        ``(tr_slv_y, ag_slv_g, confidence_factor)``: T_R of the SLV action [y], the site's
        ag at it [g] and F_C [-].
    class_limits : sequence of float
        I_S limits of the classes.
    bootstrap : tuple of int
        ``(resamples, seed)`` of the record bootstrap (the seed already the tower's).
    fit_method : {'newton', 'trust-exact'}
        Optimiser of the censored fits.

    Returns
    -------
    list of Message
    """
    tr_slv_y, ag_slv_g, fc = slv
    fits = {name: fit_level(ida, name, fit_method) for name in IDA_LEVELS}
    notes = _ida_fit_columns(row, fits)
    row["models"] = row["models"] or str(ida[0]["models"])
    lv1 = lv1_indices(fits["slv"], curve, tr_slv_y, ag_slv_g, fc)
    if lv1.messages:
        notes.append(message("indices.from_slv", notes=lv1.messages))
    row.update({name: getattr(lv1, name) for name in LV1_COLUMNS})
    notes += _overturning_columns(row, curve, fits["collapse"])
    row["risk_class"] = risk_class(lv1.safety_index, class_limits)
    resamples, seed = bootstrap
    row.update(bootstrap_intervals(ida, curve, tr_slv_y, fc, resamples, seed, fit_method))
    return notes


def _stripe_fit_columns(row: dict[str, Any], stripes: Sequence[dict[str, Any]]) -> list[Message]:
    """Fill the stripe fit's columns of a row (the check beside the IDA); return the notes."""
    arrays = stripe_arrays(stripes)
    if not len(arrays[0]):
        return [message("stripes.vertical_limit")]
    stripe_fit = fit_fragility(*arrays)
    row.update({column: getattr(stripe_fit, name) for column, name in STRIPE_COLUMNS.items()})
    return []


def _ida_fit_columns(row: dict[str, Any], fits: dict[str, CensoredFit]) -> list[Message]:
    """Fill the collapse and SLV fragility columns of a row from their fits; return the notes."""
    notes: list[Message] = []
    for name, fit in fits.items():
        row.update({f"{name}_{suffix}": getattr(fit, a) for suffix, a in CENSORED_COLUMNS.items()})
        if fit.messages and name == "collapse":
            notes.append(message("fit.collapse", notes=fit.messages))
        elif fit.messages:
            said = with_event(fit.messages, REACHED_SLV)
            notes.append(message("fit.slv", ratio=SLV_THETA_RATIO, notes=said))
    return notes


def _overturning_columns(
    row: dict[str, Any], curve: HazardCurve, collapse: CensoredFit
) -> list[Message]:
    """Fill the annual rate of overturning, P50 and the extrapolated shares; return the notes."""
    notes: list[Message] = []
    rate = collapse_rate(curve, collapse)
    share_above = share_below = math.nan
    if math.isfinite(rate) and collapse.beta > 0:
        share_above, share_below = extrapolated_shares(curve, collapse.median_g, collapse.beta)
        if share_above + share_below > EXTRAPOLATION_SHARE_LIMIT:
            notes.append(
                message(
                    "rate.extrapolated",
                    share=100 * (share_above + share_below),
                    tr_high=1 / curve.rate_per_y[-1],
                    over=100 * share_above,
                    tr_low=1 / curve.rate_per_y[0],
                    under=100 * share_below,
                )
            )
    elif not math.isfinite(rate):
        notes.append(message("rate.undefined"))
    row.update(
        annual_rate_overturning_per_y=rate,
        p_overturning_50y=probability_in(rate, 50.0) if math.isfinite(rate) else math.nan,
        rate_share_tr_over_2475=share_above,
        rate_share_tr_under_30=share_below,
        rate_extrapolated=bool(share_above + share_below > EXTRAPOLATION_SHARE_LIMIT),
    )
    return notes


def _assumption_notes(site: TowerSite, level: str, fc: float, *, source: str) -> list[Message]:
    """Return the notes of the knowledge level and of the site's assumed values.

    ``source``: ``"inventory"`` (the row's), ``"run"`` (``--knowledge-level``) or
    ``"assumed"`` (neither).
    """
    code = {"inventory": "knowledge.inventory", "run": "knowledge.run"}.get(
        source, "knowledge.assumed"
    )
    notes = [message(code, level=level, fc=fc)]
    if site.defaults:
        defaults = [message("site.default", name=n, value=v) for n, v in site.defaults]
        notes.append(message("site.assumed", defaults=defaults))
    return notes


def _code_checks(
    row: dict[str, Any],
    site: TowerSite,
    curve: HazardCurve,
    tr_slv_y: float,
    ag_slv_g: float,
    knowledge: tuple[str, float],
    class_limits: Sequence[float],
    parts: dict[str, Sequence[dict[str, Any]]] | None,
) -> list[Message]:
    """Fill the part-model, code checks' and governing columns of a row; return the notes.

    ``knowledge``: the tower's knowledge level and its F_C. The code checks are every
    registered one (:func:`rockscreen.pipeline.risk.checks.tower_code_checks.
    run_code_checks`: the kinematic checks, LV1, a check added as a module).
    """
    level, fc = knowledge
    notes: list[Message] = []
    for name, rows in (parts or {}).items():
        columns, more = part_fragility_columns(name, rows, curve, tr_slv_y, ag_slv_g, fc)
        row.update(columns)
        notes += more
    notes += part_block_notes(site.tower, list(parts or {}))
    # A tower whose bells hang in a bell gable instead of a belfry has its bell-carrying
    # part checked (the gable's kinematic check and rocking): no belfry is missing.
    bells_part = site.tower.has_belfry or site.tower.has_gable
    not_made = [] if bells_part else [belfry_not_made()]
    # every registered code check (the kinematic checks, LV1, a check added as a module)
    context = CheckContext(site, SiteConditions.of(site), level, fc)
    columns, more, missing = run_code_checks(context)
    row.update(columns)
    notes += more
    not_made += missing
    row.update(governing_columns(row, class_limits, not_made))
    notes += disagreement_messages(row, class_limits)
    return notes


def disagreement_messages(row: dict[str, Any], class_limits: Sequence[float]) -> list[Message]:
    """Return the note's clauses where rocking and the code's checks differ in class.

    :func:`rockscreen.pipeline.verdict.rules.disagreement` over the row's check results
    (:func:`rockscreen.pipeline.risk.checks.governing.tower_check_results`): the messages the row's
    ``checks_disagree`` is rendered from.
    """
    return list(disagreement(tower_check_results(row), class_limits))


def _fit_nan(level: str) -> dict[str, Any]:
    """NaN columns of an IDA fit of ``level``."""
    out: dict[str, Any] = {f"{level}_{suffix}": math.nan for suffix in CENSORED_COLUMNS}
    out.update({f"{level}_bound": "", f"{level}_n_records": 0, f"{level}_n_censored": 0})
    return out


def base_summary_row(site: TowerSite, note: Sequence[Message] = ()) -> dict[str, Any]:
    """Return a summary row with the tower's identity and NaN results (filled when assessed).

    ``note``: why it was not assessed (its ``note`` and ``note_codes``,
    :func:`rockscreen.pipeline.verdict.messages.note_columns`).
    """
    tower = site.tower
    nan = math.nan
    return {
        "id": tower.id,
        "name": tower.name,
        "comune": tower.comune,
        "provincia": tower.provincia,
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
        **note_columns(note),
    }
