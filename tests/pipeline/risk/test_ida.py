"""Collapse intensity per record (IDA): the search, its censoring and the SLV level."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from rockscreen.pipeline.engine.cases import BlockCache, screen_case
from rockscreen.pipeline.engine.motion import GroundMotion
from rockscreen.pipeline.engine.registry import get
from rockscreen.pipeline.engine.search import first_exceedance_factors, geometric_grid
from rockscreen.pipeline.engine.solvers import Solvers, use_solvers
from rockscreen.pipeline.engine.uplift import uplift_free_factor
from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.motion.excitations import pulse
from rockscreen.pipeline.risk.assess.ida import (
    SLV_THETA_RATIO,
    CollapseIntensity,
    IdaOptions,
    ida_fragility,
    motion_pga_g,
    record_collapse,
    record_collapse_intensities,
)
from rockscreen.solver import solve_rocking
from rockscreen.solver.constants import G
from rockscreen.solver.errors import ParameterError
from rockscreen.stations.tower import Tower

GROUND = IdaOptions(models=("ground",))
FREE_S = GROUND.free_motion_s


@pytest.fixture(scope="module")
def tower():
    """A slender block, 0.6 m x 4 m (tan(alpha) = 0.15)."""
    return Tower(id="T", width_m=0.6, height_m=4.0)


def one_sine(frequency_hz: float = 1.0, amplitude_m_s2: float = 1.0, vertical=None):
    acc, dt = pulse("one-sine", amplitude_m_s2, frequency_hz, dt=0.005, duration=4.0)
    z = None if vertical is None else vertical * np.abs(acc)
    return GroundMotion.along_tower_axes(f"sine{frequency_hz:g}", acc, None, z, dt)


def verdict(tower, motion, factor):
    """The engine's verdict of the motion's first component scaled by ``factor``."""
    block = BlockCache(tower)(tower.width_m)
    vertical = None if motion.vertical is None else motion.vertical * factor
    acc = motion.horizontals[0] * factor
    return screen_case(get("ground"), tower, block, acc, vertical, motion.dt, FREE_S)


def test_collapse_scale_overturns_and_the_scan_below_it_is_safe(tower):
    motion = one_sine()
    (result,) = record_collapse_intensities(tower, motion, GROUND)
    assert isinstance(result, CollapseIntensity)
    assert (result.record, result.component, result.models) == ("sine1", "X", "ground")
    assert not result.censored and result.censor_reason == ""
    assert result.pga_g == pytest.approx(1.0 / G)
    assert result.collapse_pga_g == pytest.approx(result.collapse_scale * result.pga_g)
    # The scale found overturns; the bisection's lower end does not, within the tolerance.
    assert verdict(tower, motion, result.collapse_scale).overturned
    assert not verdict(tower, motion, result.collapse_lower_scale).overturned
    gap = result.collapse_scale - result.collapse_lower_scale
    assert 0 < gap <= GROUND.tolerance * result.collapse_scale
    # Every factor of the scan grid below the one found is safe.
    alpha = BlockCache(tower)(tower.width_m).alpha
    start = uplift_free_factor(motion.horizontals[0], alpha)
    grid = geometric_grid(start, GROUND.ratio, GROUND.cap_pga_g / result.pga_g)
    below = grid[grid < result.collapse_lower_scale]
    assert len(below) >= 2
    assert not any(verdict(tower, motion, f).overturned for f in below)
    # The grid factor above the bracket overturns (it started the bisection).
    assert verdict(tower, motion, grid[len(below)]).overturned


def test_slv_scale_reaches_the_level_and_is_not_above_collapse(tower):
    (result,) = record_collapse_intensities(tower, one_sine(), GROUND)
    assert not result.slv_censored
    assert result.slv_scale <= result.collapse_scale
    assert result.slv_pga_g == pytest.approx(result.slv_scale * result.pga_g)
    reached = verdict(tower, one_sine(), result.slv_scale)
    assert reached.overturned or reached.theta_max_over_alpha >= SLV_THETA_RATIO
    assert SLV_THETA_RATIO == 0.4


def test_a_block_that_cannot_overturn_under_the_cap_is_censored_cap(tower):
    motion = one_sine(frequency_hz=20.0)  # far too short a pulse for this block
    (result,) = record_collapse_intensities(tower, motion, GROUND)
    assert result.censored and result.slv_censored and result.censor_reason == "cap"
    assert result.collapse_pga_g == pytest.approx(GROUND.cap_pga_g)
    assert result.collapse_scale == pytest.approx(GROUND.cap_pga_g / motion_pga_g(motion))
    assert not verdict(tower, motion, result.collapse_scale).overturned
    options = IdaOptions(models=("ground",), cap_pga_g=1.0)
    (lower,) = record_collapse_intensities(tower, motion, options)
    assert lower.censored and lower.collapse_pga_g == pytest.approx(1.0)


def test_a_large_vertical_is_censored_at_the_vertical_limit(tower):
    # Vertical three times the horizontal, downward: it reaches -g at a factor of about
    # 3.4, long before a 20 Hz pulse could overturn the block.
    motion = one_sine(frequency_hz=20.0, vertical=-3.0)
    limit = -G / float(np.min(motion.vertical))
    assert limit < GROUND.cap_pga_g / motion_pga_g(motion)
    (result,) = record_collapse_intensities(tower, motion, GROUND)
    assert result.censored and result.slv_censored
    assert result.censor_reason == "vertical_limit"
    assert result.collapse_scale == pytest.approx(limit, rel=1e-6)
    assert result.collapse_scale < limit  # just below, where the model still holds
    assert result.collapse_pga_g < GROUND.cap_pga_g


def test_a_vertical_that_does_not_bind_leaves_the_overturning(tower):
    (result,) = record_collapse_intensities(tower, one_sine(vertical=-0.3), GROUND)
    assert not result.censored
    assert result.collapse_scale < G / 0.3


def test_a_solver_limit_during_the_search_censors_where_the_model_last_held(tower):
    # A stand-in that refuses (the model's limit) every excitation above 2 m/s².
    def refusing(block, acc, dt, **options):
        if np.max(np.abs(acc)) > 2.0:
            raise ParameterError("beyond the model's limit")
        return solve_rocking(block, acc, dt, **options)

    with use_solvers(Solvers(rocking=refusing)):
        (result,) = record_collapse_intensities(tower, one_sine(), GROUND)
    assert result.censored and result.censor_reason == "vertical_limit"
    assert result.collapse_scale <= 2.0
    assert not verdict(tower, one_sine(), result.collapse_scale).overturned


def test_solves_are_counted_honestly(tower):
    calls = []

    def counting(block, acc, dt, **options):
        calls.append(float(np.max(np.abs(acc))))
        return solve_rocking(block, acc, dt, **options)

    with use_solvers(Solvers(rocking=counting)):
        (result,) = record_collapse_intensities(tower, one_sine(), GROUND)
    assert result.n_solves == len(calls) > 0
    assert len(set(calls)) == len(calls)  # each factor solved once (SLV reuses verdicts)
    # Nothing is solved at or below the uplift threshold g tan(alpha) (motionless).
    assert min(calls) > G * 0.15 * 1.01


def test_every_enabled_model_counts():
    church = Tower(id="C", width_m=0.6, height_m=4.0, building_height_m=12.0, base_height_m=12.0)
    motion = one_sine()
    (both,) = record_collapse_intensities(church, motion, IdaOptions(models=("ground", "floor")))
    assert both.models == "ground,floor" and not both.censored
    # The tower falls at that scale under one of the models, and its SLV scale is not above.
    block = BlockCache(church)(church.width_m)
    acc = motion.horizontals[0] * both.collapse_scale
    fell = [
        screen_case(get(name), church, block, get(name).excitation(church, acc, motion.dt),
                    None, motion.dt, FREE_S).overturned
        for name in ("ground", "floor")
    ]  # fmt: skip
    assert any(fell)
    assert both.slv_scale <= both.collapse_scale
    with pytest.raises(RiskError, match="runs none"):
        record_collapse_intensities(church, motion, IdaOptions(models=("double",)))


def test_components_of_a_record_share_its_pga_and_combine_to_the_smaller(tower):
    acc, dt = pulse("one-sine", 1.0, 1.0, dt=0.005, duration=4.0)
    motion = GroundMotion.along_tower_axes("two", acc, 0.5 * acc, None, dt)
    full = replace(GROUND, adaptive=False)
    x, y = record_collapse_intensities(tower, motion, full)
    assert (x.component, y.component) == ("X", "Y")
    assert x.pga_g == y.pga_g == pytest.approx(motion_pga_g(motion))
    # The weaker component needs about twice the scale.
    assert y.collapse_scale == pytest.approx(2 * x.collapse_scale, rel=0.03)
    combined = record_collapse([x, y])
    assert combined == {"two": (x.collapse_pga_g, False, "")}
    # The adaptive search stops Y once X overturns below it: the record is the same, Y is
    # only a lower bound (censored, its reason said), and fewer solves.
    ax, ay = record_collapse_intensities(tower, motion, GROUND)
    assert ax == x
    assert ay.censored and ay.slv_censored and ay.censor_reason == "other_component"
    assert x.collapse_scale <= ay.collapse_scale < y.collapse_scale
    assert x.slv_scale <= ay.slv_scale < y.slv_scale
    assert record_collapse([ax, ay]) == combined
    assert record_collapse([ax, ay], "slv") == record_collapse([x, y], "slv")
    assert ax.n_solves + ay.n_solves < x.n_solves + y.n_solves


def test_adaptive_search_finds_the_full_search_records_on_stochastic_records():
    """Issue 30: on a few three-component stochastic records (a tower with its own plan
    depth, so both components matter, and a vertical), the adaptive search gives each
    record the full search's collapse and SLV intensity, censoring and reason, with fewer
    solves; a component it settles is a lower bound not below the record's."""
    from rockscreen.pipeline.motion.synthetic import stochastic_accelerogram

    tower = Tower(id="S", width_m=0.8, height_m=4.0, depth_m=1.0)
    motions = []
    for i in range(4):
        rng = np.random.default_rng(30 + i)
        x, y, z = (
            stochastic_accelerogram(
                rng,
                n_samples=1200,
                dt=0.01,
                pga=2.0,
                ground_frequency=1.0 + 0.6 * i,
                ground_damping=0.5,
                envelope_duration=6.0,
                onset=1.0,
            )  # fmt: skip
            for _ in range(3)
        )
        y_share = 0.8 if i % 2 else 1.6  # either component the weaker
        motions.append(GroundMotion.along_tower_axes(f"S{i}", x, y_share * y, 0.3 * z, 0.01))
    full = replace(GROUND, adaptive=False)
    n_full = n_adaptive = 0
    settled = set()
    for motion in motions:
        exact = record_collapse_intensities(tower, motion, full)
        fast = record_collapse_intensities(tower, motion, GROUND)
        n_full += sum(r.n_solves for r in exact)
        n_adaptive += sum(r.n_solves for r in fast)
        for level in ("collapse", "slv"):
            assert record_collapse(fast, level) == record_collapse(exact, level)
        for mine, theirs in zip(fast, exact, strict=True):
            if mine.censor_reason == "other_component":
                settled.add(mine.component)
                record = record_collapse(exact)[motion.record_id][0]
                assert mine.censored and mine.collapse_pga_g >= record
            elif mine.censor_reason == "":
                assert mine == replace(theirs, n_solves=mine.n_solves)
    assert n_adaptive < n_full
    assert settled == {"X", "Y"}


def test_record_collapse_keeps_a_censoring_below_the_other_component():
    def result(component, value, censored):
        return CollapseIntensity(
            "r", component, "ground", 0.1, value / 0.1, value, value / 0.1, value,
            censored, censored, "vertical_limit" if censored else "", value / 0.1, 3,
        )  # fmt: skip

    combined = record_collapse([result("X", 0.5, False), result("Y", 0.4, True)])
    assert combined == {"r": (0.4, True, "vertical_limit")}
    combined = record_collapse([result("X", 0.4, True), result("Y", 0.4, False)])
    assert combined == {"r": (0.4, False, "")}
    with pytest.raises(RiskError, match="level"):
        record_collapse([], "dls")


def test_ida_fragility_fits_the_records(tower):
    motions = [one_sine(f) for f in (0.8, 1.0, 1.5, 2.0, 20.0)]
    results = [r for m in motions for r in record_collapse_intensities(tower, m, GROUND)]
    fit = ida_fragility(results)
    assert fit.n == 5 and fit.n_censored == 1  # the 20 Hz pulse: censored at the cap
    assert fit.is_fitted and 0 < fit.beta < 3
    slv = ida_fragility(results, "slv")
    assert slv.median_g <= fit.median_g


def test_search_helpers():
    grid = geometric_grid(0.5, 1.2, 2.0)
    assert grid[0] == 0.5 and grid[-1] == 2.0
    assert np.all(np.diff(grid) > 0) and np.all(grid[1:-1] / grid[:-2] == pytest.approx(1.2))
    assert geometric_grid(1.0, 1.2, 1.0).tolist() == [1.0]
    with pytest.raises(ValueError, match="grid needs"):
        geometric_grid(0.0, 1.2, 2.0)
    # A level reached on (1.3, inf) except in a safe window (2, 3): found at 1.3, to 1 %.
    (first,) = first_exceedance_factors(
        [lambda f: f > 1.3 and not 2.0 < f < 3.0], geometric_grid(1.0, 1.2, 10.0), 0.01
    )
    assert first[0] == pytest.approx(1.3, rel=0.01) and first[0] > 1.3 >= first[1]
    (never,) = first_exceedance_factors([lambda f: False], np.array([1.0, 2.0]), 0.01)
    assert never == (math.inf, 2.0)


def test_options_are_checked():
    for bad in ({"ratio": 1.0}, {"tolerance": 0.0}, {"cap_pga_g": -1.0}, {"slv_theta_ratio": 2}):
        with pytest.raises(RiskError):
            IdaOptions(**bad)


@pytest.mark.data
def test_real_records_fragility_of_a_slender_block(shared_data, tower, capsys):
    """IDA of the 0.6 x 4 m block on the L'Aquila 2009 horizontals (ground model)."""
    from obspy import Stream

    from rockscreen.pipeline.records.grouping import group_records
    from rockscreen.pipeline.records.io import read_stream

    folder = shared_data / "laquila2009"
    stream = Stream()
    for path in sorted(folder.glob("*.mseed")):
        stream += read_stream(path, stations=folder / "stations.xml")
    results = []
    for record in group_records(stream):
        for name, h in (("h1", record.h1), ("h2", record.h2)):
            # Each horizontal normalised to PGA 1 m/s², then scaled by the search.
            acc = h / np.max(np.abs(h))
            motion = GroundMotion.along_tower_axes(f"{record.id}{name}", acc, None, None, record.dt)
            results += record_collapse_intensities(tower, motion, GROUND)
    assert len(results) == 8
    assert all(r.pga_g == pytest.approx(1.0 / G) for r in results)
    fit = ida_fragility(results)
    slv = ida_fragility(results, "slv")
    with capsys.disabled():
        print(
            f"\nL'Aquila 2009, 8 horizontals, 0.6 x 4 m block: collapse median "
            f"{fit.median_g:.3f} g, beta {fit.beta:.3f} (SE {fit.se_beta:.3f}), "
            f"{fit.n_censored} censored; SLV median {slv.median_g:.3f} g, beta {slv.beta:.3f}"
        )
    assert fit.is_fitted and math.isfinite(fit.beta) and 0.5 <= fit.beta <= 1.6
    assert slv.median_g <= fit.median_g
