"""The screening risk of one tower as a typed record, and its summary columns (issue 31).

The code's verdict (``safety_class``, LV1 at the code's strengths, F_C, gamma_M) and the
screening risk (best estimates at mean strengths, no partial factor, the epistemic
uncertainty as a 90 % interval) answer two questions and stay apart: this module holds the
second's record, :class:`ScreeningRisk`, produced by
:mod:`rockscreen.pipeline.risk.assess.screening_risk` and flattened to the ``risk_*`` columns of the
assess archive (:data:`rockscreen.pipeline.archive.risk_schema.RISK_SUMMARY_UNITS`) by
:func:`risk_columns` at the archive's door. ``docs/risk.md``, "The screening risk in assess".
"""

from __future__ import annotations

import enum
import math
from dataclasses import dataclass, fields
from typing import Any

from rockscreen.pipeline.verdict.messages import Message, dumps, loads

__all__ = [
    "BETA_SOURCES",
    "FragilityCurve",
    "InputSensitivity",
    "RiskBound",
    "RiskPlace",
    "ScreeningRisk",
    "SurveyGroups",
    "risk_columns",
    "risk_from_data",
    "risk_to_data",
]

#: Where the aleatory beta comes from (``risk_beta_source``).
BETA_SOURCES = ("ida_fit", "judgement_fema_p695")


class RiskBound(enum.Enum):
    """Whether a statistic over the epistemic samples is a value or a bound.

    A sample whose capacity is a bound (holds at 2475 y, fails at 30 y) makes a probability
    a bound, and so every statistic it can move (``docs/uncertainty.md``, "The risk").
    """

    #: A value.
    NONE = ""
    #: At most this (printed ``<=``).
    AT_MOST = "at_most"
    #: At least this (printed ``>=``).
    AT_LEAST = "at_least"
    #: Bounded both ways: not a value (printed ``~?``).
    BOTH = "both"

    @property
    def sign(self) -> str:
        """Return the sign printed before the number: ``""``, ``"<="``, ``">="``, ``"~?"``."""
        return {"": "", "at_most": "<=", "at_least": ">=", "both": "~?"}[self.value]

    @classmethod
    def parse(cls, value: object) -> RiskBound:
        """Return the bound of a stored spelling (str, bytes, None or a :class:`RiskBound`)."""
        if isinstance(value, RiskBound):
            return value
        if isinstance(value, bytes):
            value = value.decode("utf-8")
        return cls("" if value is None else str(value))


@dataclass(frozen=True)
class InputSensitivity:
    """What knowing one epistemic input exactly would do to the tower's interval."""

    #: The input (``period_s``, ``masonry_type``, ``fm_pa``, ``wall_m``, ``taper``, ...).
    input: str
    #: First-order Sobol' index of ln P [-].
    index: float
    #: Expected relative narrowing of the 90 % interval of P [-].
    narrowing: float
    #: Whether the input's prior is a judgement (not a fit of data).
    judgement: bool


@dataclass(frozen=True)
class FragilityCurve:
    """The fragility over the epistemic samples at a few ag: median, 90 % band, mixture."""

    #: ag on rock [g].
    ag_g: tuple[float, ...]
    #: P(collapse | ag): median over the samples, 5 % and 95 % curves, mean [-].
    p_median: tuple[float, ...]
    p_lo90: tuple[float, ...]
    p_hi90: tuple[float, ...]
    p_mean: tuple[float, ...]
    #: Share of samples whose capacity is a bound [-].
    bounded_share: float


@dataclass(frozen=True)
class SurveyGroups:
    """What the region's top-N list needs of a tower once every tower is done.

    The tower's samples cut into groups by its ``survey_first`` input as the list cuts them
    (:func:`rockscreen.pipeline.risk.uncertainty.sensitivity.top_n_changes`: the categories
    of the masonry type, else equal-count bins of at least ``NARROWING_GROUP`` samples):
    each group's share of the samples' weight and its best estimate (the weighted median of
    P within), in the groups' order. About 25 numbers a side for 1000 samples, where the
    samples' probabilities, weights and inputs took 4000 (issue 30: the main process keeps
    one of these per tower until the list is made). No group when nothing varies.
    """

    #: Each group's share of the weight (post-stratification), summing to 1 [-].
    weight: tuple[float, ...] = ()
    #: Each group's best estimate: the weighted median of P in 50 years within [-].
    p50_best: tuple[float, ...] = ()


@dataclass(frozen=True)
class ScreeningRisk:
    """A tower's screening risk: P in 50 years, lambda, mechanism, what to survey first."""

    tower_id: str
    #: P(collapse in 50 years): best estimate (median over the samples), 5 %, 95 %, mean [-].
    p50_best: float
    p50_lo90: float
    p50_hi90: float
    p50_mean: float
    #: Their bounds.
    p50_best_bound: RiskBound
    p50_lo90_bound: RiskBound
    p50_hi90_bound: RiskBound
    p50_mean_bound: RiskBound
    #: lambda [1/y] likewise (the bounds of P hold for lambda).
    rate_best_per_y: float
    rate_lo90_per_y: float
    rate_hi90_per_y: float
    #: The mechanism governing the largest (weighted) share of samples, and the share [-].
    governing_mechanism: str
    governing_share: float
    #: The input whose exact value narrows the interval most ("" when nothing varies), its
    #: first-order index and expected narrowing [-].
    survey_first: str
    survey_first_index: float
    survey_first_narrowing: float
    #: Aleatory dispersion [-] and its source (:data:`BETA_SOURCES`).
    beta: float
    beta_source: str
    #: Epistemic samples.
    samples: int
    #: Inputs whose prior is a judgement (``beta`` when the dispersion is one).
    judgement_inputs: tuple[str, ...]
    #: The risk side's messages: judgement priors, bounds, model limits.
    notes: tuple[Message, ...]
    #: Every varying input's index and narrowing.
    sensitivity: tuple[InputSensitivity, ...]
    #: The fragility band (``/risk_fragility``).
    fragility: FragilityCurve
    #: What the top-N list needs: the ``survey_first`` input's groups.
    survey: SurveyGroups
    #: Weighted share of samples whose capacity is continued beyond the NTC 2018 table
    #: (a value, not a bound) [-], and the share of the best estimate's lambda read on the
    #: hazard curve extrapolated beyond the table [-] (a record written before: 0).
    extrapolated_share: float = 0.0
    rate_extrapolated_share: float = 0.0


@dataclass(frozen=True)
class RiskPlace:
    """A tower's place in the region's list (after all towers)."""

    #: 1 = riskiest by the best estimate (ties by the higher hi90; competition ranking).
    rank: int
    #: ``top_10``, ``top_25``, ``top_50``, ``rest``.
    band: str
    #: The 90 % interval reaches another band.
    band_uncertain: bool


def risk_columns(
    risk: ScreeningRisk | None, place: RiskPlace | None, notes: tuple[Message, ...] = ()
) -> dict[str, Any]:
    """Return a tower's ``risk_*`` summary columns (the archive's contract).

    Parameters
    ----------
    risk : ScreeningRisk or None
        None: the tower has no risk (NaN and ``""``; ``notes`` say why).
    place : RiskPlace or None
        Its rank (None: no rank, ``risk_rank`` 0).
    notes : tuple of Message
        Messages of a tower without a risk.
    """
    if risk is None:
        out: dict[str, Any] = {
            name: math.nan
            for name in (
                "risk_p50_best",
                "risk_p50_lo90",
                "risk_p50_hi90",
                "risk_p50_mean",
                "risk_rate_best_per_y",
                "risk_rate_lo90_per_y",
                "risk_rate_hi90_per_y",
            )
        }
        for name in ("best", "lo90", "hi90", "mean"):
            out[f"risk_p50_{name}_bound"] = ""
        out.update(
            risk_rank=0,
            risk_band="",
            risk_band_uncertain="",
            risk_governing_mechanism="",
            risk_governing_share=math.nan,
            risk_extrapolated_share=math.nan,
            risk_survey_first="",
            risk_survey_first_index=math.nan,
            risk_survey_first_narrowing=math.nan,
            risk_beta=math.nan,
            risk_beta_source="",
            risk_samples=0,
            risk_judgement_inputs="",
            risk_note_codes=dumps(notes),
        )
        return _ordered(out)
    out = {
        "risk_p50_best": risk.p50_best,
        "risk_p50_best_bound": risk.p50_best_bound.value,
        "risk_p50_lo90": risk.p50_lo90,
        "risk_p50_lo90_bound": risk.p50_lo90_bound.value,
        "risk_p50_hi90": risk.p50_hi90,
        "risk_p50_hi90_bound": risk.p50_hi90_bound.value,
        "risk_p50_mean": risk.p50_mean,
        "risk_p50_mean_bound": risk.p50_mean_bound.value,
        "risk_rate_best_per_y": risk.rate_best_per_y,
        "risk_rate_lo90_per_y": risk.rate_lo90_per_y,
        "risk_rate_hi90_per_y": risk.rate_hi90_per_y,
        "risk_rank": place.rank if place else 0,
        "risk_band": place.band if place else "",
        "risk_band_uncertain": ("yes" if place.band_uncertain else "no") if place else "",
        "risk_governing_mechanism": risk.governing_mechanism,
        "risk_governing_share": risk.governing_share,
        "risk_extrapolated_share": risk.extrapolated_share,
        "risk_survey_first": risk.survey_first,
        "risk_survey_first_index": risk.survey_first_index,
        "risk_survey_first_narrowing": risk.survey_first_narrowing,
        "risk_beta": risk.beta,
        "risk_beta_source": risk.beta_source,
        "risk_samples": risk.samples,
        "risk_judgement_inputs": ";".join(risk.judgement_inputs),
        "risk_note_codes": dumps(risk.notes),
    }
    return out


#: The columns in the contract's order (:func:`risk_columns`).
_ORDER = (
    "risk_p50_best",
    "risk_p50_best_bound",
    "risk_p50_lo90",
    "risk_p50_lo90_bound",
    "risk_p50_hi90",
    "risk_p50_hi90_bound",
    "risk_p50_mean",
    "risk_p50_mean_bound",
    "risk_rate_best_per_y",
    "risk_rate_lo90_per_y",
    "risk_rate_hi90_per_y",
    "risk_rank",
    "risk_band",
    "risk_band_uncertain",
    "risk_governing_mechanism",
    "risk_governing_share",
    "risk_extrapolated_share",
    "risk_survey_first",
    "risk_survey_first_index",
    "risk_survey_first_narrowing",
    "risk_beta",
    "risk_beta_source",
    "risk_samples",
    "risk_judgement_inputs",
    "risk_note_codes",
)


def _ordered(columns: dict[str, Any]) -> dict[str, Any]:
    return {name: columns[name] for name in _ORDER}


# ------------------------------------------------------------------------ work-file codec


def risk_to_data(risk: ScreeningRisk) -> dict[str, Any]:
    """Return a :class:`ScreeningRisk` as plain data (the assess work file keeps it so).

    Enums as their values, messages as their stored text, the nested records as dicts;
    :func:`risk_from_data` restores it exactly.
    """
    out: dict[str, Any] = {}
    for f in fields(ScreeningRisk):
        value = getattr(risk, f.name)
        if isinstance(value, RiskBound):
            value = value.value
        elif f.name == "notes":
            value = dumps(value)
        elif f.name == "sensitivity":
            value = [[s.input, s.index, s.narrowing, s.judgement] for s in value]
        elif f.name in ("fragility", "survey"):
            value = {g.name: getattr(value, g.name) for g in fields(value)}
        out[f.name] = value
    return out


def risk_from_data(data: dict[str, Any]) -> ScreeningRisk:
    """Return the :class:`ScreeningRisk` of :func:`risk_to_data`'s plain data."""
    values = dict(data)
    for name in ("p50_best_bound", "p50_lo90_bound", "p50_hi90_bound", "p50_mean_bound"):
        values[name] = RiskBound.parse(values[name])
    values["notes"] = loads(values["notes"])
    values["judgement_inputs"] = tuple(values["judgement_inputs"])
    values["sensitivity"] = tuple(
        InputSensitivity(str(a), float(b), float(c), bool(d))
        for a, b, c, d in values["sensitivity"]
    )
    frag = values["fragility"]
    values["fragility"] = FragilityCurve(
        **{k: (tuple(v) if k != "bounded_share" else float(v)) for k, v in frag.items()}
    )
    survey = values["survey"]
    values["survey"] = SurveyGroups(
        tuple(float(w) for w in survey["weight"]), tuple(float(p) for p in survey["p50_best"])
    )
    return ScreeningRisk(**values)
