"""The ranking of towers by risk and its bands (``risk.uncertainty.rank``, issue 31)."""

from __future__ import annotations

import numpy as np
import pytest

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.uncertainty.rank import rank_band, rank_towers, risk_rank


def test_rank_by_best_estimate_ties_by_upper_bound_then_shared():
    best = [0.10, 0.30, 0.30, 0.05, 0.30, 0.20]
    upper = [0.20, 0.40, 0.50, 0.10, 0.40, 0.30]
    # 0.30/0.50 first; the two 0.30/0.40 share rank 2; then 0.20 (4), 0.10 (5), 0.05 (6).
    np.testing.assert_array_equal(risk_rank(best, upper), [5, 2, 1, 6, 2, 4])


def test_rank_refuses_bad_input():
    with pytest.raises(RiskError):
        risk_rank([0.1, 0.2], [0.1])
    with pytest.raises(RiskError):
        risk_rank([0.1, np.nan], [0.1, 0.2])


def test_bands_by_share_of_the_towers():
    assert [rank_band(r, 20) for r in (1, 2, 3, 5, 6, 10, 11, 20)] == [
        "top_10",
        "top_10",
        "top_25",
        "top_25",
        "top_50",
        "top_50",
        "rest",
        "rest",
    ]
    with pytest.raises(RiskError):
        rank_band(0, 20)


def test_a_band_is_uncertain_when_the_interval_reaches_another():
    ids = [f"T{i}" for i in range(10)]
    best = np.linspace(0.5, 0.05, 10)
    lo = best * 0.99
    hi = best * 1.01
    hi[5] = 0.6  # its upper end would rank it first: top_10
    ranked = rank_towers(ids, best, lo, hi)
    assert [r.rank for r in ranked] == list(range(1, 11))
    assert ranked[0].band == "top_10" and not ranked[0].band_uncertain
    assert ranked[5].band == "rest" and ranked[5].band_uncertain
    assert ranked[5].rank_if_hi90 == 1
    with pytest.raises(RiskError, match="inside its interval"):
        rank_towers(ids, best, hi, lo)
