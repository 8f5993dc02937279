"""The ranking of a region's towers by their risk, and its bands for the report and QGIS.

``risk_rank``: 1 = the riskiest tower by the best estimate of P in 50 years
(:class:`~rockscreen.pipeline.risk.uncertainty.risk.TowerRisk` ``p50_best``); towers with
the same best estimate are ordered by the upper end of their 90 % interval (``p50_hi90``,
the higher first); towers equal in both share a rank ("competition" ranking, 1, 2, 2, 4:
the next rank counts the towers above it). A best estimate flagged as a bound is ranked
by its value and keeps its flag (a tower whose best estimate is "at most" ranks no
higher than shown).

Bands (:data:`RANK_BANDS`), by the rank's share of the region's towers, ``rank / N``:
``top_10`` (the riskiest 10 %), ``top_25`` (10-25 %), ``top_50`` (25-50 %) and ``rest``.
A tower's band is **uncertain** when its 90 % interval reaches another band: ranked by its
``p50_hi90`` (or ``p50_lo90``) among the others' best estimates it would fall in a
different band.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from rockscreen.pipeline.errors import RiskError

__all__ = ["RANK_BANDS", "RankedTower", "rank_band", "risk_rank", "rank_towers"]

#: (upper share of rank / N, band): the first band whose share is >= rank / N.
RANK_BANDS: tuple[tuple[float, str], ...] = (
    (0.10, "top_10"),
    (0.25, "top_25"),
    (0.50, "top_50"),
    (1.00, "rest"),
)


def risk_rank(best: Sequence[float], upper: Sequence[float]) -> np.ndarray:
    """Return each tower's rank: 1 = the highest ``best``, ties by the higher ``upper``.

    Parameters
    ----------
    best : sequence of float
        The towers' best estimates (``p50_best``) [-].
    upper : sequence of float
        The upper ends of their intervals (``p50_hi90``) [-].

    Returns
    -------
    ndarray of int
        Ranks from 1; towers equal in both share the lowest rank of their group.
    """
    b = np.asarray(best, dtype=float)
    u = np.asarray(upper, dtype=float)
    if b.shape != u.shape or b.ndim != 1:
        raise RiskError(f"risk rank: {b.size} best estimates for {u.size} upper bounds")
    if not np.all(np.isfinite(b) & np.isfinite(u)):
        raise RiskError("risk rank: best estimates and upper bounds must be finite")
    order = np.lexsort((-u, -b))
    ranks = np.empty(b.size, dtype=int)
    previous = None
    for position, i in enumerate(order, start=1):
        key = (b[i], u[i])
        if key != previous:
            current, previous = position, key
        ranks[i] = current
    return ranks


def rank_band(rank: int, n_towers: int) -> str:
    """Return the band of a rank among ``n_towers`` (:data:`RANK_BANDS`)."""
    if n_towers < 1 or not 1 <= rank <= n_towers:
        raise RiskError(f"rank band: rank {rank!r} of {n_towers!r} towers")
    share = rank / n_towers
    for limit, name in RANK_BANDS:
        if share <= limit + 1e-12:
            return name
    return RANK_BANDS[-1][1]


@dataclass(frozen=True)
class RankedTower:
    """A tower's place in the region's list."""

    tower_id: str
    rank: int
    band: str
    #: Whether its 90 % interval reaches another band (module docstring).
    band_uncertain: bool
    #: The ranks its interval's ends would take among the others' best estimates.
    rank_if_hi90: int
    rank_if_lo90: int


def _rank_among(value: float, others: np.ndarray) -> int:
    """Return the rank a value would take among the other towers' best estimates."""
    return int(np.sum(others > value)) + 1


def rank_towers(
    tower_ids: Sequence[str],
    best: Sequence[float],
    lo90: Sequence[float],
    hi90: Sequence[float],
) -> list[RankedTower]:
    """Return every tower's rank, band and whether its band is uncertain.

    Parameters
    ----------
    tower_ids : sequence of str
    best, lo90, hi90 : sequence of float
        ``p50_best``, ``p50_lo90``, ``p50_hi90`` of each tower [-].

    Returns
    -------
    list of RankedTower
        In the order of ``tower_ids``.
    """
    b = np.asarray(best, dtype=float)
    lo = np.asarray(lo90, dtype=float)
    hi = np.asarray(hi90, dtype=float)
    if not (len(tower_ids) == b.size == lo.size == hi.size):
        raise RiskError("rank towers: ids, best, lo90 and hi90 differ in length")
    if np.any(lo > b) or np.any(b > hi):
        raise RiskError("rank towers: each best estimate must lie inside its interval")
    ranks = risk_rank(b, hi)
    n = b.size
    out = []
    for i, tower_id in enumerate(tower_ids):
        others = np.delete(b, i)
        r_hi, r_lo = _rank_among(hi[i], others), _rank_among(lo[i], others)
        band = rank_band(int(ranks[i]), n)
        uncertain = rank_band(r_hi, n) != band or rank_band(r_lo, n) != band
        out.append(RankedTower(str(tower_id), int(ranks[i]), band, uncertain, r_hi, r_lo))
    return out
