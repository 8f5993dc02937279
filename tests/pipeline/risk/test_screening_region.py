"""The region's top-N list from each tower's groups equals the list from every sample.

``assess`` keeps of each tower, until the list is made, only its ``survey_first`` input's
groups (:func:`~rockscreen.pipeline.risk.assess.screening_risk.survey_groups`: each group's
weight and weighted median of P) instead of its samples' probabilities, weights and inputs
(issue 30: memory). :func:`~rockscreen.pipeline.risk.assess.screening_region.region_risk`
must then give exactly the rows that
:func:`~rockscreen.pipeline.risk.uncertainty.sensitivity.top_n_changes` gives from every
sample: the same towers, sides, inputs and probabilities to the bit, ties of best estimates
included, for a continuous input, the taper, the masonry type and a tower where nothing varies.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from rockscreen.pipeline.risk.assess.screening_region import region_risk
from rockscreen.pipeline.risk.assess.screening_risk import survey_groups
from rockscreen.pipeline.risk.uncertainty.risk import QUANTILE_METHOD
from rockscreen.pipeline.risk.uncertainty.sensitivity import top_n_changes
from rockscreen.pipeline.verdict.screening_risk import (
    FragilityCurve,
    RiskBound,
    ScreeningRisk,
    SurveyGroups,
    risk_from_data,
    risk_to_data,
)

#: survey_first of the region's towers in turn ("" : nothing varies).
INPUTS = ("fm_pa", "taper", "masonry_type", "wall_m", "period_s", "")


def _template(tower_id: str) -> ScreeningRisk:
    none = RiskBound.NONE
    return ScreeningRisk(
        tower_id=tower_id,
        **dict.fromkeys(("p50_best", "p50_lo90", "p50_hi90", "p50_mean"), 0.0),
        **dict.fromkeys(("p50_best_bound", "p50_lo90_bound", "p50_hi90_bound"), none),
        p50_mean_bound=none,
        **dict.fromkeys(("rate_best_per_y", "rate_lo90_per_y", "rate_hi90_per_y"), 0.0),
        governing_mechanism="shaft",
        governing_share=1.0,
        survey_first="",
        survey_first_index=0.0,
        survey_first_narrowing=0.0,
        beta=0.4,
        beta_source="judgement_fema_p695",
        samples=0,
        judgement_inputs=(),
        notes=(),
        sensitivity=(),
        fragility=FragilityCurve((0.1,), (0.1,), (0.0,), (0.2,), (0.1,), 0.0),
        survey=SurveyGroups(),
    )


def _region(n_towers: int, n_samples: int, seed: int, tied: bool):
    """Return (ScreeningRisk per tower, and each tower's samples for top_n_changes)."""
    rng = np.random.default_rng(seed)
    risks, full = [], []
    for i in range(n_towers):
        wall = rng.uniform(0.8, 2.0, n_samples)
        samples = {
            "wall_m": wall,
            # a prismatic share: equal values share a bin
            "wall_top_m": np.where(rng.random(n_samples) < 0.4, wall, 0.7 * wall),
            "masonry_type": rng.choice(["rubble", "cut_stone", "solid_brick"], n_samples),
            "fm_pa": rng.lognormal(np.log(2e6), 0.4, n_samples),
            "period_s": np.full(n_samples, 0.8) if i % 7 == 4 else rng.uniform(0.5, 1.5, n_samples),
        }
        p = np.clip(rng.lognormal(np.log(0.02 * (1 + i % 5)), 1.0, n_samples), 0.0, 1.0)
        w = rng.uniform(0.5, 1.5, n_samples)
        w /= w.sum()
        best = float(np.quantile(p, 0.5, method=QUANTILE_METHOD, weights=w))
        if tied:
            best = round(best, 2)  # many equal best estimates
        name = INPUTS[i % len(INPUTS)]
        risks.append(
            dataclasses.replace(
                _template(f"T{i:02d}"),
                p50_best=best,
                p50_lo90=min(best, float(np.min(p))),
                p50_hi90=max(best, float(np.max(p))),
                survey_first=name,
                survey=survey_groups(p, w, samples, name),
            )
        )
        full.append((p, w, samples))
    return risks, full


@pytest.mark.parametrize(("n_towers", "n_samples", "seed", "tied", "top_n"), [
    (30, 1000, 1, False, 10),
    (30, 1000, 2, True, 10),
    (12, 300, 3, True, 10),
    (5, 200, 4, False, 10),
    (40, 400, 5, True, 3),
])  # fmt: skip
def test_the_list_from_the_groups_is_the_list_from_every_sample(
    n_towers, n_samples, seed, tied, top_n
):
    risks, full = _region(n_towers, n_samples, seed, tied)
    region = region_risk(risks, top_n=top_n)
    n = min(top_n, n_towers - 1)
    expected = top_n_changes(
        [r.tower_id for r in risks],
        [r.p50_best for r in risks],
        [p for p, _, _ in full],
        [samples for _, _, samples in full],
        [r.survey_first for r in risks],
        n,
        weights=[w for _, w, _ in full],
    )
    rows = [
        {"tower_id": c.tower_id, "side": "in" if c.in_top else "out", "input": c.input}
        | {"p_crosses": float(c.probability)}
        for c in expected
    ]
    assert region.top_n == n
    assert list(region.top_n_rows) == rows
    if n_towers >= 12:  # the lists say something: towers cross both ways
        assert any(row["p_crosses"] > 0.0 for row in rows)
    assert any(row["side"] == "in" for row in rows) and any(row["side"] == "out" for row in rows)


def test_a_tower_whose_input_does_not_vary_has_no_groups():
    p = np.linspace(0.01, 0.1, 200)
    w = np.full(200, 1 / 200)
    assert survey_groups(p, w, {"period_s": np.full(200, 0.8)}, "period_s") == SurveyGroups()
    assert survey_groups(p, w, {"period_s": np.linspace(0.5, 1, 200)}, "") == SurveyGroups()


def test_the_groups_travel_through_the_work_file_codec_exactly():
    risks, _ = _region(6, 300, 7, False)
    for risk in risks:
        assert risk_from_data(risk_to_data(risk)) == risk
    groups = risks[0].survey
    assert len(groups.weight) == len(groups.p50_best) > 1
    assert sum(groups.weight) == pytest.approx(1.0, abs=1e-12)
