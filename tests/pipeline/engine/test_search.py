"""The joint search of a record's components (issue 30: the adaptive IDA)."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from rockscreen.pipeline.engine.search import (
    Exceedance,
    first_exceedance_factors,
    geometric_grid,
    joint_first_exceedances,
)


def windowed(threshold: float, windows: list[tuple[float, float]]):
    """A level reached above ``threshold`` except inside the safe ``windows`` (not monotone)."""
    return lambda f: f > threshold and not any(a < f < b for a, b in windows)


class Counter:
    """Count the distinct factors a member's levels are asked at (one solve each)."""

    def __init__(self, levels):
        self.levels, self.asked = levels, set()

    def wrap(self):
        def ask(level):
            def reached(f: float) -> bool:
                self.asked.add(f)
                return level(f)

            return reached

        return [ask(level) for level in self.levels]


member = st.tuples(
    st.floats(0.3, 20.0),  # SLV threshold
    st.floats(1.0, 3.0),  # collapse / SLV threshold
    st.lists(st.tuples(st.floats(0.3, 30.0), st.floats(1.01, 1.5)), max_size=3),
    st.floats(0.05, 1.0),  # the member's floor (its own uplift-free factor)
)


@settings(max_examples=300, deadline=None)
@given(st.lists(member, min_size=1, max_size=3), st.sampled_from([0.01, 0.05]))
def test_the_group_minimum_is_the_full_searches(specs, tolerance):
    members, full, grids, floors = [], [], [], []
    for slv, ratio, windows, floor in specs:
        windows = [(a, a * w) for a, w in windows]
        levels = [windowed(slv * ratio, windows), windowed(slv, windows)]
        grid = geometric_grid(floor * 1.2, 1.2, 25.0)
        grids.append(grid)
        floors.append(floor)
        members.append(Counter(levels))
        full.append(Counter(levels))
    joint = joint_first_exceedances([m.wrap() for m in members], grids, tolerance, floors)
    alone = [
        first_exceedance_factors(m.wrap(), g, tolerance, fl)
        for m, g, fl in zip(full, grids, floors, strict=True)
    ]
    for level in range(2):
        smallest = min(a[level][0] for a in alone)
        assert min(j[level].factor for j in joint) == smallest
        for j, a in zip(joint, alone, strict=True):
            if j[level].settled:
                # Settled: its own factor lies above its lower end, which is not below the
                # group's smallest (so it never is the group's minimum).
                assert a[level][0] > j[level].lower >= smallest
            else:
                assert (j[level].factor, j[level].lower) == a[level]
    assert sum(len(m.asked) for m in members) <= sum(len(m.asked) for m in full)


def test_a_member_stops_once_another_reaches_the_level_lower():
    grid = geometric_grid(0.5, 1.2, 10.0)
    weak = Counter([lambda f: f > 1.0, lambda f: f > 0.8])
    strong = Counter([lambda f: f > 5.0, lambda f: f > 4.0])
    (w_fell, w_slv), (s_fell, s_slv) = joint_first_exceedances(
        [weak.wrap(), strong.wrap()], [grid, grid], 0.01, [0.4, 0.4]
    )
    assert not (w_fell.settled or w_slv.settled)
    assert w_fell.factor == first_exceedance_factors(weak.levels, grid, 0.01, 0.4)[0][0]
    assert s_fell == Exceedance(math.inf, s_fell.lower, settled=True)
    assert s_slv.settled and w_fell.factor <= s_fell.lower < 4.0
    # The strong member was not scanned beyond the first grid factor above the weak one's.
    assert max(strong.asked) <= 1.2 * 1.2
    # Never reached by either: both scan to the grid's end, censored there.
    never = joint_first_exceedances(
        [[lambda f: False] * 2, [lambda f: False] * 2], [grid, grid], 0.01, [0.4, 0.4]
    )
    assert all(e == Exceedance(math.inf, 10.0) for row in never for e in row)
    assert joint_first_exceedances([], [], 0.01, []) == []


def test_bisection_of_a_later_bracket_stops_above_the_smallest():
    # Both reach the level on the same grid factor; the second's bracket is bisected only
    # while it could still be below the first's factor.
    grid = np.array([1.0, 2.0])
    first = Counter([lambda f: f > 1.1])
    second = Counter([lambda f: f > 1.9])
    (a,), (b,) = joint_first_exceedances(
        [first.wrap(), second.wrap()], [grid, grid], 0.01, [0.5, 0.5]
    )
    assert a.factor == first_exceedance_factors(first.levels, grid, 0.01, 0.5)[0][0]
    assert b.settled and b.lower >= a.factor
    assert len(second.asked) < len(first.asked) + 3
