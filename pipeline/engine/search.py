"""The one search of a scale factor: an upward geometric scan, then bisection.

Rocking is **not monotone** in amplitude: a block that overturns at ``f`` may survive at
``1.1 f`` (the "safe regions" of Zhang & Makris 2001 and Makris & Konstantinidis 2003). A
plain bisection on ``[0, cap]`` could therefore land above the smallest factor that reaches
a level (overturning, a damage level). The search instead

1. scans upward on a geometric grid of factors, stopping at the first factor that reaches
   every level asked;
2. bisects each level between the last grid factor below it and the first reaching it until
   the bracket is narrower than ``tolerance`` of its upper end, and reports the upper end
   (a factor that reaches the level, so the value is never optimistic by more than the
   bracket).

A window narrower than one grid step below the first grid factor reaching a level can be
missed: the grid step is the documented resolution. Two products use it: ``run``'s safety
factor of the governing case (:func:`safety_factor` on the :func:`scan_factors` grid, with
1 on it) and ``assess``'s collapse and SLV intensities of every record
(:mod:`rockscreen.pipeline.risk.assess.ida`, on :func:`geometric_grid`). The scaled vertical
reaching -g ends a search (:func:`vertical_limit_factor`): beyond it the rigid-block model
no longer holds.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from rockscreen.solver.constants import G

__all__ = [
    "Exceedance",
    "SafetyFactorResult",
    "first_exceedance_factors",
    "geometric_grid",
    "joint_first_exceedances",
    "safety_factor",
    "scan_factors",
    "vertical_limit_factor",
]


@dataclass(frozen=True)
class SafetyFactorResult:
    """Outcome of :func:`safety_factor`."""

    #: Smallest overturning scale factor found [-], ``inf`` when none up to the cap.
    factor: float
    #: Largest factor known safe below ``factor`` [-] (0 when the scan's first factor overturned).
    lower: float
    #: Number of evaluations of the overturning predicate.
    n_solves: int


def scan_factors(start: float, ratio: float, cap: float) -> np.ndarray:
    """Return the upward scan grid ``start * ratio**k`` up to ``cap``, with 1 and cap added.

    Parameters
    ----------
    start : float
        First factor, > 0 [-].
    ratio : float
        Geometric step, > 1 [-].
    cap : float
        Last factor [-].

    Returns
    -------
    numpy.ndarray
        Increasing factors, ``start <= f <= cap``.
    """
    if not (start > 0 and ratio > 1 and cap >= start):
        raise ValueError(
            f"scan needs start > 0, ratio > 1, cap >= start; got {start}, {ratio}, {cap}"
        )
    n = int(math.floor(math.log(cap / start) / math.log(ratio) + 1e-9)) + 1
    grid = start * ratio ** np.arange(n)
    extra = [cap] + ([1.0] if start < 1.0 < cap else [])
    grid = np.unique(np.concatenate([grid[grid < cap], extra]))
    return grid


def geometric_grid(start: float, ratio: float, stop: float) -> np.ndarray:
    """Return ``start * ratio**k`` for the ``k`` that stay below ``stop``, then ``stop``.

    Parameters
    ----------
    start : float
        First factor, > 0 [-].
    ratio : float
        Step, > 1 [-].
    stop : float
        Last factor, >= ``start`` [-].

    Returns
    -------
    numpy.ndarray
        Increasing factors from ``start`` to ``stop`` inclusive.
    """
    if not (start > 0.0 and ratio > 1.0 and stop >= start and math.isfinite(stop)):
        raise ValueError(
            f"grid needs 0 < start <= stop < inf, ratio > 1; got {start}, {ratio}, {stop}"
        )
    steps = math.ceil(math.log(stop / start) / math.log(ratio) - 1e-9)
    factors = start * ratio ** np.arange(max(steps, 0))
    return np.append(factors[factors < stop * (1.0 - 1e-12)], stop)


def first_exceedance_factors(
    levels: Sequence[Callable[[float], bool]],
    grid: np.ndarray,
    tolerance: float,
    floor: float = 0.0,
) -> list[tuple[float, float]]:
    """Find, for each level, the smallest factor of ``grid`` reaching it, refined by bisection.

    The scan walks up ``grid`` until every level is reached (or the grid ends); each level
    is then bisected between the last grid factor below it and the first reaching it,
    until ``hi - lo <= tolerance * hi``. Rocking is not monotone in amplitude: a level
    reached in a window narrower than one grid step below the first grid factor reaching
    it can be missed (the grid step is the resolution).

    Parameters
    ----------
    levels : sequence of callable
        ``reached(factor) -> bool`` per level (callers cache shared work).
    grid : numpy.ndarray
        Increasing scale factors [-] (:func:`geometric_grid`).
    tolerance : float
        Relative width of the final bracket, > 0 [-].
    floor : float
        A factor known not to reach any level [-], the bracket's lower end when the first
        grid factor already reaches one.

    Returns
    -------
    list of (float, float)
        Per level ``(factor, lower)``: the smallest factor found reaching the level and
        the largest known below it; ``(inf, last grid factor)`` when the grid never
        reaches it.
    """
    brackets: list[tuple[float, float] | None] = [None] * len(levels)
    below = floor
    for factor in map(float, grid):
        for i, reached in enumerate(levels):
            if brackets[i] is None and reached(factor):
                brackets[i] = (below, factor)
        if all(b is not None for b in brackets):
            break
        below = factor
    found = []
    for reached, bracket in zip(levels, brackets, strict=True):
        if bracket is None:
            found.append((math.inf, float(grid[-1])))
            continue
        lo, hi = bracket
        while hi - lo > tolerance * hi:
            mid = 0.5 * (lo + hi)
            lo, hi = (lo, mid) if reached(mid) else (mid, hi)
        found.append((hi, lo))
    return found


@dataclass(frozen=True)
class Exceedance:
    """One member's level in :func:`joint_first_exceedances`."""

    #: Smallest factor found reaching the level [-]; ``inf`` when not reached up to the
    #: member's grid end, or when ``settled``.
    factor: float
    #: Largest factor known below the level [-]: the bisection's lower end; the grid's last
    #: factor when never reached; where the search of the member stopped when ``settled``.
    lower: float
    #: The level was not searched beyond ``lower``: another member reaches it at or below
    #: ``lower``, so this member cannot give the smallest factor of the group.
    settled: bool = False


def joint_first_exceedances(
    members: Sequence[Sequence[Callable[[float], bool]]],
    grids: Sequence[np.ndarray],
    tolerance: float,
    floors: Sequence[float],
) -> list[list[Exceedance]]:
    """Search several members for the smallest factor of the group reaching each level.

    The group's value of a level is the smallest over its members (the components of a
    record: the tower is lost when either component overturns). Each member runs
    :func:`first_exceedance_factors` on its own grid, with the same scan and the same
    bisection, but the members are scanned together in increasing factor, and a member's
    level is left **settled** (not searched further) once the member is known not to reach
    it up to a factor at which another member already reaches it: its own first exceedance
    then lies above the group's, whatever it is. The bisections run in increasing order of
    their brackets' upper ends and stop as soon as their lower end passes the smallest
    factor found. For every level, the smallest factor over the members (and which member
    gives it) is therefore the one the separate searches give, with fewer evaluations; a
    settled member's own factor is only known to exceed its ``lower``.

    Parameters
    ----------
    members : sequence of sequence of callable
        Per member, ``reached(factor) -> bool`` per level (the same levels for every
        member; callers cache shared work).
    grids : sequence of numpy.ndarray
        Per member, increasing scale factors [-] (:func:`geometric_grid`).
    tolerance : float
        Relative width of the final bracket, > 0 [-].
    floors : sequence of float
        Per member, a factor known not to reach any level [-].

    Returns
    -------
    list of list of Exceedance
        Per member, per level. A member's level that is not settled holds what
        :func:`first_exceedance_factors` gives.
    """
    n_levels = len(members[0]) if members else 0
    brackets = [[None] * n_levels for _ in members]
    below = [float(f) for f in floors]
    position = [0] * len(members)
    active = [len(g) > 0 for g in grids]
    ended = [len(g) == 0 for g in grids]  # the scan reached the grid's end
    best = [math.inf] * n_levels  # smallest first-reaching grid factor of each level so far
    while any(active):
        i = min((k for k, a in enumerate(active) if a), key=lambda k: grids[k][position[k]])
        open_levels = [lv for lv in range(n_levels) if brackets[i][lv] is None]
        if all(below[i] >= best[lv] for lv in open_levels):
            active[i] = False  # every level it lacks is reached lower by another member
            continue
        factor = float(grids[i][position[i]])
        for lv in open_levels:
            if members[i][lv](factor):
                brackets[i][lv] = (below[i], factor)
                best[lv] = min(best[lv], factor)
        position[i] += 1
        ended[i] = position[i] == len(grids[i])
        if ended[i] or all(b is not None for b in brackets[i]):
            active[i] = False
        else:
            below[i] = factor
    found: list[list[Exceedance | None]] = [[None] * n_levels for _ in members]
    for lv in range(n_levels):
        smallest = math.inf
        order = sorted(
            (k for k in range(len(members)) if brackets[k][lv] is not None),
            key=lambda k: brackets[k][lv][1],
        )
        for k in order:
            lo, hi = brackets[k][lv]
            reached = members[k][lv]
            while hi - lo > tolerance * hi and lo < smallest:
                mid = 0.5 * (lo + hi)
                lo, hi = (lo, mid) if reached(mid) else (mid, hi)
            if hi - lo > tolerance * hi:  # left above the smallest found: settled
                found[k][lv] = Exceedance(math.inf, lo, settled=True)
            else:
                found[k][lv] = Exceedance(hi, lo)
                smallest = min(smallest, hi)
        for k in range(len(members)):
            if found[k][lv] is None:
                found[k][lv] = (
                    Exceedance(math.inf, float(grids[k][-1]) if len(grids[k]) else floors[k])
                    if ended[k]
                    else Exceedance(math.inf, below[k], settled=True)
                )
    return found  # type: ignore[return-value]


def safety_factor(
    overturns: Callable[[float], bool],
    *,
    start: float = 0.05,
    ratio: float = 1.2,
    cap: float = 10.0,
    tolerance: float = 0.01,
) -> SafetyFactorResult:
    """Find the smallest scale factor for which ``overturns(factor)`` is True.

    Upward geometric scan, then bisection between the last safe and the first
    overturning factor (see the module docstring for why not a plain bisection).

    Parameters
    ----------
    overturns : callable
        ``overturns(factor) -> bool``: does the governing case scaled by ``factor``
        overturn the tower?
    start : float
        First factor of the scan, > 0 [-].
    ratio : float
        Geometric step of the scan, > 1 [-].
    cap : float
        Largest factor tried [-].
    tolerance : float
        The bisection stops when ``(hi - lo) <= tolerance * hi`` [-].

    Returns
    -------
    SafetyFactorResult
        ``factor = inf`` when nothing up to ``cap`` overturns.
    """
    calls = 0

    def counted(factor: float) -> bool:
        nonlocal calls
        calls += 1
        return overturns(factor)

    grid = scan_factors(start, ratio, cap)
    ((factor, lower),) = first_exceedance_factors([counted], grid, tolerance)
    return SafetyFactorResult(factor, lower, calls)


def vertical_limit_factor(acc_v: np.ndarray | None) -> float:
    """Return the scale factor at which the scaled vertical record first reaches -g [-].

    The search scales the vertical with the horizontals (the same earthquake, larger;
    ``docs/campaign.md``). Beyond this factor the base would fall away from the tower
    (downward acceleration beyond gravity): the rigid-block model no longer applies, so
    the search stops there. ``inf`` without a vertical record or a downward sample.
    """
    lowest = float(np.min(acc_v)) if acc_v is not None and len(acc_v) else 0.0
    return -G / lowest if lowest < 0.0 else math.inf
