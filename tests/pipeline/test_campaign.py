"""Campaign orchestration: components, models, governing case, tasks, chunks, failures."""

from __future__ import annotations

import dataclasses
import math
from types import SimpleNamespace

import numpy as np
import pytest

from rockscreen.pipeline.config import CampaignConfig, config_from_mapping
from rockscreen.pipeline.engine.motion import GroundMotion, tower_components
from rockscreen.pipeline.engine.registry import tower_models
from rockscreen.pipeline.engine.solvers import Solvers
from rockscreen.pipeline.screening.campaign import chunk_tasks
from rockscreen.pipeline.screening.cases import CampaignShared, TowerTask
from rockscreen.pipeline.screening.evaluate import evaluate_tower, run_chunk
from rockscreen.pipeline.screening.histories import decimate
from rockscreen.pipeline.screening.inputs import make_tasks, pair
from rockscreen.solver.constants import G
from rockscreen.stations.inventory import Tower


def config(**sections):
    return config_from_mapping(sections) if sections else CampaignConfig()


@pytest.fixture
def evaluate(fake_solvers):
    """Screen one tower on ``motions`` with the stand-in solvers (or ``solvers``)."""

    def run(tower, motions, cfg=None, solvers=fake_solvers):
        shared = CampaignShared(motions, cfg or config(), solvers)
        return evaluate_tower(TowerTask(0, tower, tuple(motions)), shared)

    return run


def test_components_rotated_to_the_tower_axes_with_its_dimensions(make_motion):
    tower = Tower(id="T", width_m=2.0, height_m=6.0, depth_m=3.0, azimuth_deg=90.0)
    comps = tower_components(tower, make_motion(peak_n=2.0, peak_e=1.0))
    assert [(c, w, a) for c, _, w, a in comps] == [("X", 2.0, "x"), ("Y", 3.0, "y")]
    # x along east: the east component; y (90 deg clockwise from east = south): -north.
    m = make_motion(peak_n=2.0, peak_e=1.0)
    np.testing.assert_allclose(comps[0][1], m.horizontals[1], atol=1e-12)
    np.testing.assert_allclose(comps[1][1], -m.horizontals[0], atol=1e-12)


def test_components_unrotated_use_the_smaller_plan_dimension(make_motion):
    tower = Tower(id="T", width_m=2.0, height_m=6.0, depth_m=1.5)
    comps = tower_components(tower, make_motion(azimuths=(None, None)))
    # Along neither of the tower's axes: no axis (a part model takes its safe side).
    assert [(c, w, a) for c, _, w, a in comps] == [("N", 1.5, None), ("E", 1.5, None)]


# The data of the floor model (the building) and of the double block (masses, friction).
FLOOR_DATA = {"building_height_m": 10.0, "base_height_m": 8.0}
DOUBLE_DATA = {"tower_mass_kg": 3e4, "building_mass_kg": 1e6, "mu_s": 1.0, "mu_k": 0.7}
# A tower with the data of every model: ground, floor and double.
FULL = Tower(id="B", width_m=2.0, height_m=6.0, **DOUBLE_DATA, **FLOOR_DATA)


def test_models_follow_the_tower_data_and_the_configuration():
    bare = Tower(id="A", width_m=2.0, height_m=6.0)
    full = FULL
    assert tower_models(bare, ("ground", "floor", "double")) == ["ground"]
    floor_only, double_only = (dataclasses.replace(bare, **d) for d in (FLOOR_DATA, DOUBLE_DATA))
    assert tower_models(floor_only, ("ground", "floor", "double")) == ["ground", "floor"]
    assert tower_models(double_only, ("ground", "floor", "double")) == ["ground", "double"]
    assert tower_models(full, ("ground", "floor", "double")) == ["ground", "floor", "double"]
    assert tower_models(full, ("double",)) == ["double"]


def test_governing_case_is_the_overturned_one_then_the_largest_ratio(make_motion, evaluate):
    tower = Tower(id="T", width_m=2.0, height_m=6.0)  # uplift at g tan(alpha) = 3.27 m/s2
    motions = {
        "XX.A..HN": make_motion("XX.A..HN", peak_n=4.0, peak_e=5.0),  # rocks, no overturn
        "XX.B..HN": make_motion("XX.B..HN", peak_n=7.0, peak_e=1.0),  # N overturns (> 2x)
    }
    outcome = evaluate(tower, motions)
    assert len(outcome.rows) == 4
    s = outcome.summary
    assert s["governing_record"] == "XX.B..HNN"
    assert s["governing_model"] == "ground"
    assert s["governing_component"] == "N"
    assert s["overturned"] is True
    assert s["risk_class"] == "collapse"
    assert s["safety_factor"] <= 1.0
    # Fake overturns above 2 g tan(alpha): factor = 2 * 3.27 / 7 within the 1 % bracket.
    expected = 2 * G * (2.0 / 6.0) / 7.0
    assert s["safety_factor"] == pytest.approx(expected, rel=0.011)
    assert s["safety_factor"] >= expected


def test_safety_factor_of_a_safe_tower_and_its_class(make_motion, evaluate):
    tower = Tower(id="T", width_m=2.0, height_m=6.0)
    motions = {"XX.A..HN": make_motion("XX.A..HN", peak_n=4.0, peak_e=1.0)}
    outcome = evaluate(tower, motions)
    s = outcome.summary
    ratio = 4.0 / (G / 3.0) - 1.0
    assert s["theta_max_over_alpha"] == pytest.approx(ratio)
    expected_sf = 2 * G / 3.0 / 4.0
    assert s["safety_factor"] == pytest.approx(expected_sf, rel=0.011)
    # theta/alpha 0.22 >= 0.2 and SF 1.64 in [1.5, 2.5): "moderate".
    assert s["risk_class"] == "moderate"


def test_safety_factor_search_reuses_the_case_verdict_at_factor_one(
    make_motion, evaluate, fake_solvers
):
    # The scan grid holds 1; the governing case was solved at 1 already, so the search
    # must not solve it again, and safety_factor_solves counts real solver calls.
    factors = []

    def counting_rocking(block, acc, dt, **kwargs):
        factors.append(float(np.max(np.abs(acc))) / 4.0)  # the scale factor of this call
        return fake_solvers.rocking(block, acc, dt, **kwargs)

    solvers = dataclasses.replace(fake_solvers, rocking=counting_rocking)
    tower = Tower(id="T", width_m=2.0, height_m=6.0)
    motions = {"XX.A..HN": make_motion("XX.A..HN", peak_n=4.0, peak_e=1.0)}
    outcome = evaluate(tower, motions, config(output={"histories": "none"}), solvers)
    search = factors[2:]  # after the two component solves
    assert search and all(not math.isclose(f, 1.0, rel_tol=1e-12) for f in search)
    assert outcome.summary["safety_factor_solves"] == len(search)
    assert outcome.summary["safety_factor"] == pytest.approx(2 * G / 3.0 / 4.0, rel=0.011)


def test_floor_and_double_models_and_kept_histories(make_motion, evaluate):
    tower = dataclasses.replace(FULL, id="T", mu_k=0.3, base_height_m=10.0)
    motions = {"XX.A..HN": make_motion("XX.A..HN", peak_n=4.0, peak_e=2.0)}
    cfg = config(output={"histories": "decimated", "history_points": 50})
    outcome = evaluate(tower, motions, cfg)
    models = [r["model"] for r in outcome.rows]
    assert models == ["ground", "floor", "double"] * 2
    floor_row = outcome.rows[1]
    assert floor_row["pga_m_s2"] == pytest.approx(4.0 * 1.5)
    assert outcome.summary["governing_model"] == "floor"
    # One history per record-model pair (the worst component), decimated with its peak.
    assert [(h.model, h.component) for h in outcome.histories] == [
        ("ground", "N"),
        ("floor", "N"),
        ("double", "N"),
    ]
    for h in outcome.histories:
        assert len(h.t) <= 50
    assert np.max(np.abs(outcome.histories[0].theta)) == pytest.approx(4.0 / G, rel=1e-6)


def test_a_solver_error_is_a_failure_and_the_rest_goes_on(make_motion, evaluate, fake_solvers):
    def picky(block, acc, dt, **kwargs):
        if block.width < 2.0:
            raise ValueError("width too small for this test")
        return fake_solvers.rocking(block, acc, dt, **kwargs)

    solvers = dataclasses.replace(fake_solvers, rocking=picky)
    tower = Tower(id="T", width_m=1.0, height_m=6.0)
    outcome = evaluate(tower, {"XX.A..HN": make_motion("XX.A..HN")}, solvers=solvers)
    assert outcome.rows == []
    assert outcome.summary["risk_class"] == "unknown"
    assert {f.kind for f in outcome.failures} == {"solve"}
    assert "width too small" in outcome.failures[0].reason


def test_pairing_nearest_station_and_unpaired_towers_are_failures(make_motion):
    motions = {
        "XX.A..HN": make_motion("XX.A..HN"),
        "XX.B..HN": GroundMotion(
            **{**make_motion("XX.B..HN").__dict__, "latitude": 43.0, "longitude": 13.0}
        ),
    }
    towers = [
        Tower(id="near-A", width_m=2, height_m=6, lat=42.01, lon=13.0),
        Tower(id="near-B", width_m=2, height_m=6, lat=42.98, lon=13.0),
        Tower(id="far", width_m=2, height_m=6, lat=45.0, lon=13.0),
    ]
    tasks, failures = pair(towers, motions, max_distance_km=50.0)
    assert [(t.tower.id, t.record_ids) for t in tasks] == [
        ("near-A", ("XX.A..HN",)),
        ("near-B", ("XX.B..HN",)),
    ]
    assert [(f.kind, f.subject) for f in failures] == [("pair", "far")]
    assert "50 km" in failures[0].reason


def test_make_tasks_keeps_inventory_order_and_every_record_of_a_station(make_motion):
    motions = {
        "XX.A..HN": make_motion("XX.A..HN"),
        "XX.A..HN~2": make_motion("XX.A..HN", station="XX.A"),
    }
    towers = [Tower(id=f"T{i}", width_m=2, height_m=6) for i in range(3)]
    tasks, failures = make_tasks(towers, {t.id: ["XX.A"] for t in towers}, motions)
    assert [t.index for t in tasks] == [0, 1, 2]
    assert tasks[0].record_ids == ("XX.A..HN", "XX.A..HN~2")
    assert failures == []


@pytest.mark.parametrize(("n", "jobs", "size"), [(1, 2, 1), (100, 2, 7), (10_000, 2, 64)])
def test_chunks_cover_every_task_once(n, jobs, size):
    tasks = list(range(n))
    chunks = chunk_tasks(tasks, jobs)
    assert sum(chunks, []) == tasks
    assert max(len(c) for c in chunks) == size


def test_run_chunk_evaluates_every_tower(make_motion, fake_solvers):
    towers = [Tower(id=f"T{i}", width_m=2.0 + i, height_m=6.0) for i in range(3)]
    motions = {"XX.A..HN": make_motion("XX.A..HN", peak_n=4.0)}
    chunk = [TowerTask(i, t, ("XX.A..HN",)) for i, t in enumerate(towers)]
    outcomes = run_chunk(CampaignShared(motions, config(), fake_solvers), chunk)
    assert [o.tower_id for o in outcomes] == ["T0", "T1", "T2"]
    ratios = [o.summary["theta_max_over_alpha"] for o in outcomes]
    assert ratios == sorted(ratios, reverse=True)  # wider towers rock less


def test_decimated_history_spends_its_points_on_the_motion():
    n = 100_000
    t = np.arange(n) * 0.005
    theta = np.zeros(n)
    theta[20_000:22_000] = 0.01 * np.sin(np.linspace(0.0, 20.0, 2000))
    theta[21_234] = 0.05  # a sharp peak decimation must keep
    regime = (theta != 0.0).astype(np.int8)
    response = SimpleNamespace(t=t, theta=theta, u=None, regime=regime)
    t_kept, theta_kept, _, _ = decimate(response, 200)
    assert len(t_kept) <= 200
    assert t_kept[0] == 0.0 and t_kept[-1] == pytest.approx(t[-1])
    inside = (t_kept >= t[19_999]) & (t_kept <= t[22_000])
    assert inside.sum() >= 180  # ceil-sized bins: 2002 window samples in 182 bins
    assert np.max(theta_kept) == pytest.approx(0.05)


def test_real_solver_search_on_the_checked_record_equals_the_multiplied_record(
    monkeypatch, evaluate, fake_solvers
):
    # With the real solvers the search passes the checked record and the factor to the
    # solver and skips factors where no sample reaches uplift; stand-ins (wrappers of the
    # same solvers) get multiplied copies and every factor is solved: same result.
    import rockscreen.pipeline.screening.evaluate as campaign
    from rockscreen import solver

    t = np.arange(1200) * 0.01
    shape = np.sin(2 * np.pi * 0.6 * t) * np.exp(-(((t - 4.0) / 1.5) ** 2))
    record = GroundMotion(
        record_id="XX.A..HN",
        station="XX.A",
        dt=0.01,
        channels=("HNN", "HNE"),
        horizontals=(2.0 * shape, 1.0 * shape),
        azimuths=(0.0, 90.0),
        vertical=0.5 * np.cos(2 * np.pi * 1.1 * t) * np.exp(-(((t - 4.0) / 1.5) ** 2)),
        latitude=42.0,
        longitude=13.0,
    )
    tower = Tower(id="T", width_m=1.0, height_m=6.0)
    motions = {"XX.A..HN": record}
    cfg = config(output={"histories": "none"})
    fast = evaluate(tower, motions, cfg, Solvers().resolved())
    wrapped = Solvers(
        block=solver.RockingBlock.from_dimensions,
        rocking=lambda *a, **k: solver.solve_rocking(*a, **k),
        double=lambda *a, **k: solver.solve_double_block(*a, **k),
        floor=fake_solvers.floor,
    )
    monkeypatch.setattr(campaign, "sample_uplift_factor", lambda *a: 0.0)
    slow = evaluate(tower, motions, cfg, wrapped)
    for key in ("safety_factor", "safety_factor_lower", "theta_max_over_alpha"):
        assert fast.summary[key] == slow.summary[key]
    assert math.isfinite(fast.summary["safety_factor"])
    assert 0 < fast.summary["safety_factor_solves"] < slow.summary["safety_factor_solves"]
