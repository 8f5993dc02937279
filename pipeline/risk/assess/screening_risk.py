"""The screening risk of ``assess``: the uncertainty library wired per tower and per region.

Per tower, in the worker after its IDA (:func:`tower_screening_risk`): the tower's priors
(:meth:`~rockscreen.pipeline.risk.uncertainty.priors.TowerPriors.from_tower`, the region's
from ``--priors``), ``n`` samples from a generator of the run's seed and the tower's id
(:func:`risk_rng`: a tower's result does not depend on its place in the inventory), the
best-estimate capacities of the shaft (:func:`~rockscreen.pipeline.risk.uncertainty.shaft.
shaft_capacity`) and of the kinematic mechanisms (:func:`~rockscreen.pipeline.risk.
uncertainty.kinematic.kinematic_capacities`) on the tower's site and support, the rocking
capacities of the IDA the worker ran (the whole tower's and each part model's fit median,
**the same in every sample**: rocking is taken at the row's inputs, a documented limit), the
post-stratification weights, the risk on the site's hazard curve (beta the IDA fit's where
rocking governs, else :data:`~rockscreen.pipeline.risk.uncertainty.risk.DEFAULT_ALEATORY_BETA`,
a judgement) and the sensitivity. The result is a
:class:`~rockscreen.pipeline.verdict.screening_risk.ScreeningRisk`.

The worker's result carries it as plain data (:func:`risk_item`). After all towers, the
region's ranks, bands and top-N list and the long tables:
:mod:`rockscreen.pipeline.risk.assess.screening_region`.
``docs/risk.md``, "The screening risk in assess".
"""

from __future__ import annotations

import zlib
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.checks.tower_mechanisms import tower_support
from rockscreen.pipeline.risk.measures.hazard_integral import HazardCurve
from rockscreen.pipeline.risk.uncertainty.belfry import belfry_for_row
from rockscreen.pipeline.risk.uncertainty.kinematic import MechanismCapacity, kinematic_capacities
from rockscreen.pipeline.risk.uncertainty.priors import RegionPriors, TowerPriors, masonry_prior
from rockscreen.pipeline.risk.uncertainty.risk import (
    DEFAULT_ALEATORY_BETA,
    DEFAULT_SAMPLES,
    TowerRisk,
    stratum_weights,
    tower_risk,
)
from rockscreen.pipeline.risk.uncertainty.sensitivity import (
    conditional_best,
    epistemic_inputs,
    sensitivity,
)
from rockscreen.pipeline.risk.uncertainty.shaft import shaft_capacity
from rockscreen.pipeline.verdict.messages import Message, dumps, message
from rockscreen.pipeline.verdict.screening_risk import (
    FragilityCurve,
    InputSensitivity,
    RiskBound,
    ScreeningRisk,
    SurveyGroups,
    risk_to_data,
)
from rockscreen.stations.errors import RockscreenError

__all__ = [
    "FRAGILITY_AG_G",
    "MIN_RISK_SAMPLES",
    "RISK_METHODS",
    "RiskOptions",
    "risk_item",
    "risk_rng",
    "survey_groups",
    "tower_screening_risk",
]

#: Fewest epistemic samples ``--risk-samples`` accepts (the 5 % and 95 % ends need them).
MIN_RISK_SAMPLES = 100
#: The ag [g] of a tower's fragility band (``/risk_fragility``): 40 log-spaced points.
FRAGILITY_AG_G = tuple(float(a) for a in np.geomspace(0.01, 2.0, 40))
#: What the screening risk computes (the archive's ``risk_methods``).
RISK_METHODS = ("shaft_lv1_mean", "kinematic_mean", "rocking_ida", "hazard_integral")
#: A stream of the seed sequence apart from the bootstrap's (tower_ida.tower_seed).
_RISK_STREAM = 31
#: The kinematic mechanisms' names of the library -> the archive's mechanism ids.
_KINEMATIC_IDS = {"whole tower": "tower_kinematic"}


@dataclass(frozen=True)
class RiskOptions:
    """Options of the screening risk of ``assess``."""

    #: Epistemic samples per tower (>= :data:`MIN_RISK_SAMPLES`).
    samples: int = DEFAULT_SAMPLES
    #: The region's priors (``--priors``); None: the defaults (TURRIS, judgement).
    region: RegionPriors | None = None
    #: The priors file's name, or ``"default"`` (the archive's ``risk_priors_source``).
    priors_source: str = "default"
    #: False: not computed (a benchmark's reference run; every row says so).
    enabled: bool = True

    def __post_init__(self):
        if self.enabled and int(self.samples) < MIN_RISK_SAMPLES:
            raise RiskError(
                f"--risk-samples {self.samples}: too few for a 90 % interval; allowed: an "
                f"integer >= {MIN_RISK_SAMPLES} (default {DEFAULT_SAMPLES})"
            )


def risk_rng(seed: int, tower_id: str) -> np.random.Generator:
    """Return the generator of a tower's samples: the run's seed and the tower's id."""
    crc = zlib.crc32(str(tower_id).encode("utf-8"))
    return np.random.default_rng(np.random.SeedSequence([int(seed) % 2**32, crc, _RISK_STREAM]))


def _rocking(
    row: dict[str, Any] | None, n: int, parts: Sequence[str]
) -> tuple[list[MechanismCapacity], dict[str, float], list[Message]]:
    """Return the IDA's rocking capacities (constant arrays), their fit betas and notes."""
    if row is None:
        left_out = message(
            "risk.rocking_left_out", mechanism="rocking", reason=message("risk.no_ida_run")
        )
        return [], {}, [left_out]
    # (mechanism, median, bound, beta columns, whether a missing fit is said: the whole
    # tower's always; a part model's columns are NaN when the row has no such part)
    slots = [("rocking", "collapse_median_g", "collapse_bound", "collapse_beta", True)]
    slots += [
        (
            f"{p}_rocking",
            f"{p}_fragility_median_g",
            f"{p}_fragility_bound",
            f"{p}_fragility_beta",
            False,
        )
        for p in parts
        if f"{p}_fragility_median_g" in row
    ]
    out, betas, notes = [], {}, []
    for name, median, bound, beta, say_missing in slots:
        ag = float(row.get(median, np.nan))
        if not np.isfinite(ag) or ag <= 0.0:
            if say_missing:
                reason = message("risk.no_ida_fit")
                notes.append(message("risk.rocking_left_out", mechanism=name, reason=reason))
            continue
        out.append(MechanismCapacity(name, np.full(n, ag), str(row.get(bound) or "")))
        betas[name] = float(row.get(beta, np.nan))
        # the printed precision: a fit's last digits (1e-9 between optimisers) are no news
        notes.append(message("risk.rocking_at_row", mechanism=name, ag=round(ag, 4)))
    return out, betas, notes


def _risk_over_samples(
    mechanisms: list[MechanismCapacity], curve: HazardCurve, weights: np.ndarray, betas: dict
) -> tuple[TowerRisk, str]:
    """Return the risk (beta the governing rocking fit's, else the judgement) and its source."""
    risk = tower_risk(mechanisms, curve, weights=weights)
    fit = betas.get(risk.governing_mechanism, np.nan)
    if np.isfinite(fit) and fit > 0.0:
        return tower_risk(mechanisms, curve, beta=fit, beta_source="ida_fit", weights=weights), (
            "ida_fit"
        )
    return risk, "judgement_fema_p695"


def tower_screening_risk(
    site: Any,
    row: dict[str, Any] | None,
    curve: HazardCurve,
    seed: int,
    options: RiskOptions,
    parts: Sequence[str] = (),
) -> tuple[ScreeningRisk | None, tuple[Message, ...]]:
    """Return a tower's screening risk, or None with the messages saying why.

    Parameters
    ----------
    site : rockscreen.pipeline.risk.assess.sites.TowerSite
        The tower and its site (located).
    row : dict or None
        Its summary row after the IDA (the rocking fits); None: no IDA was run.
    curve : HazardCurve
        The site's hazard curve (``assess``'s).
    seed : int
        The run's seed (mixed with the tower's id: :func:`risk_rng`).
    options : RiskOptions
    parts : sequence of str
        The part models whose IDA columns the row may hold.

    Returns
    -------
    risk : ScreeningRisk or None
    notes : tuple of Message
        Why there is no risk (empty with a risk: its notes are in it).
    """
    if not options.enabled:
        return None, (message("risk.not_computed"),)
    try:
        return _compute(site, row, curve, seed, options, parts), ()
    except (RockscreenError, ValueError, ArithmeticError) as exc:
        return None, (message("risk.failed", error=str(exc)),)


def _compute(
    site: Any,
    row: dict[str, Any] | None,
    curve: HazardCurve,
    seed: int,
    options: RiskOptions,
    parts: Sequence[str],
) -> ScreeningRisk:
    tower = site.tower
    n = int(options.samples)
    priors = TowerPriors.from_tower(tower, options.region)
    region = RegionPriors() if options.region is None else options.region
    belfry, belfry_judged, belfry_notes = belfry_for_row(tower, region.belfry)
    samples = priors.sample(risk_rng(seed, tower.id), n, belfry=belfry)
    conditions = SiteConditions.of(site)
    support, _ = tower_support(tower)
    shaft = shaft_capacity(tower, conditions, samples, support=support)
    kinematic, kin_notes = kinematic_capacities(tower, conditions, samples)
    rocking, betas, notes = _rocking(row, n, parts)
    mechanisms = [
        MechanismCapacity("shaft", shaft.ag_g, shaft.bound, shaft.extrapolated),
        *(
            MechanismCapacity(
                _KINEMATIC_IDS.get(m.name, f"{m.name}_kinematic"), m.ag_g, m.bound, m.extrapolated
            )
            for m in kinematic
        ),
        *rocking,
    ]
    weights = stratum_weights(samples, priors)
    risk, beta_source = _risk_over_samples(mechanisms, curve, weights, betas)
    sens = sensitivity(risk.probability, samples)
    judged = {*priors.judgements, *belfry_judged}
    judgement = [*priors.judgements, *belfry_judged]
    prior_of = priors.priors()
    notes = [
        *(
            message("risk.judgement_prior", input=k, source=_source(prior_of[k].source))
            for k in priors.judgements
        ),
        *belfry_notes,
        *notes,
    ]
    if beta_source == "ida_fit":
        notes.append(message("risk.beta_ida", beta=risk.beta, mechanism=risk.governing_mechanism))
    else:
        judgement.append("beta")
        notes.append(message("risk.beta_judgement", beta=DEFAULT_ALEATORY_BETA))
    k_bounded = int(np.sum(risk.capacity_bound != ""))
    if k_bounded:
        notes.append(message("risk.bounded_samples", k=k_bounded, n=n))
    k_beyond = int(np.sum(risk.capacity_extrapolated))
    if k_beyond:
        share = round(100.0 * risk.rate_extrapolated_share)
        notes.append(message("risk.extrapolated_samples", k=k_beyond, n=n, share=share))
    notes.extend(kin_notes)
    notes.append(message("risk.sampled_inputs", inputs=", ".join(sens.first_order) or "-"))
    return _record(tower.id, risk, beta_source, sens, judged, judgement, notes, samples)


def _source(text: str) -> Message | str:
    """Return a prior's source for its message.

    The default masonry prior's as a catalogue code (an Italian page reads it in Italian); a
    region file's text as its author wrote it.
    """
    return message("risk.source_masonry_uniform") if text == masonry_prior().source else text


def survey_groups(
    probability: np.ndarray, weights: np.ndarray, samples: dict[str, np.ndarray], name: str
) -> SurveyGroups:
    """Return a tower's samples grouped by its ``survey_first`` input (the top-N list's need).

    Parameters
    ----------
    probability : ndarray
        P in 50 years per sample [-].
    weights : ndarray
        Each sample's weight [-].
    samples : dict
        The epistemic samples (the taper from ``wall_m`` and ``wall_top_m``).
    name : str
        The tower's ``survey_first`` input (``""``: nothing varies, no group).

    Returns
    -------
    SurveyGroups
        Each group's share of the weight and its weighted median of P, as
        :func:`rockscreen.pipeline.risk.uncertainty.sensitivity.top_n_changes` computes them
        from every sample: the region's list from these is the same list
        (:func:`rockscreen.pipeline.risk.assess.screening_region.region_risk`).
    """
    inputs = epistemic_inputs(samples)
    if not name or name not in inputs:
        return SurveyGroups()
    p = np.asarray(probability, dtype=float)
    shares, best = conditional_best(p, inputs[name], np.asarray(weights, dtype=float))
    return SurveyGroups(tuple(shares.tolist()), tuple(best.tolist()))


def _record(
    tower_id: str,
    risk: TowerRisk,
    beta_source: str,
    sens: Any,
    judged: set[str],
    judgement: list[str],
    notes: list[Message],
    samples: dict[str, np.ndarray],
) -> ScreeningRisk:
    band = risk.fragility_band(np.asarray(FRAGILITY_AG_G))
    return ScreeningRisk(
        tower_id=str(tower_id),
        p50_best=risk.p50_best,
        p50_lo90=risk.p50_lo90,
        p50_hi90=risk.p50_hi90,
        p50_mean=risk.p50_mean,
        p50_best_bound=RiskBound.parse(risk.p50_best_bound),
        p50_lo90_bound=RiskBound.parse(risk.p50_lo90_bound),
        p50_hi90_bound=RiskBound.parse(risk.p50_hi90_bound),
        p50_mean_bound=RiskBound.parse(risk.p50_mean_bound),
        rate_best_per_y=risk.rate_best_per_y,
        rate_lo90_per_y=risk.rate_lo90_per_y,
        rate_hi90_per_y=risk.rate_hi90_per_y,
        governing_mechanism=risk.governing_mechanism,
        governing_share=min(risk.governing_share, 1.0),  # a sum of weights: round-off
        extrapolated_share=risk.extrapolated_share,
        rate_extrapolated_share=risk.rate_extrapolated_share,
        survey_first=sens.survey_first,
        survey_first_index=sens.survey_first_index,
        survey_first_narrowing=sens.survey_first_narrowing,
        beta=risk.beta,
        beta_source=beta_source,
        samples=risk.n,
        judgement_inputs=tuple(judgement),
        notes=tuple(dict.fromkeys(notes)),
        sensitivity=tuple(
            InputSensitivity(k, float(v), float(sens.narrowing[k]), k in judged)
            for k, v in sens.first_order.items()
        ),
        fragility=FragilityCurve(
            ag_g=tuple(band.ag_g.tolist()),
            p_median=tuple(band.median.tolist()),
            p_lo90=tuple(band.lo90.tolist()),
            p_hi90=tuple(band.hi90.tolist()),
            p_mean=tuple(band.mean.tolist()),
            bounded_share=band.bounded_share,
        ),
        survey=survey_groups(risk.probability, risk.weights, samples, sens.survey_first),
    )


def risk_item(
    site: Any,
    row: dict[str, Any],
    curve: HazardCurve,
    seed: int,
    options: RiskOptions,
    parts: Sequence[str],
) -> dict[str, Any]:
    """Return a tower's screening risk as the worker's result carries it (plain data).

    ``{"risk": risk_to_data(...) or None, "risk_notes": stored messages}``: the work file
    keeps it, and
    :func:`~rockscreen.pipeline.risk.assess.screening_region.assess_risk` reads it back after
    all towers.
    """
    risk, notes = tower_screening_risk(site, row, curve, seed, options, parts)
    return {"risk": None if risk is None else risk_to_data(risk), "risk_notes": dumps(notes)}
