"""The seed paper's double block (solver.paper_formulation) and its one-at-a-time switches."""

from __future__ import annotations

import numpy as np
import pytest

from rockscreen.solver import ParameterError, RockingBlock, solve_double_block
from rockscreen.solver.constants import G
from rockscreen.solver.paper_formulation import (
    NAMED,
    Formulation,
    formulation_name,
    parse_formulation,
    solve_paper_double_block,
)

BLOCK = RockingBlock.from_dimensions(2.06, 5.80, eta=0.9)
MASSES = {"tower_mass": 339e3 / G, "building_mass": 96840.67e3 / G}


def _harmonic(a_g: float, f: float, duration: float, dt: float = 1e-3):
    t = np.arange(int(round(duration / dt)) + 1) * dt
    return a_g * G * np.cos(2 * np.pi * f * t), dt


def _paper(acc, dt, form, mu=(1.0, 0.7)):
    return solve_paper_double_block(
        BLOCK, acc, dt, mu_s=mu[0], mu_k=mu[1], formulation=form, **MASSES
    )


def test_names_and_switches_parse_and_round_trip():
    assert parse_formulation("consistent") == Formulation()
    paper = parse_formulation("di-gennaro-2023")
    assert (paper.friction_sign, paper.normal_force, paper.tangential_sign, paper.regimes) == (
        "theta",
        "paper",
        "paper",
        "paper",
    )
    one = parse_formulation("consistent+normal_force=paper")
    assert one == Formulation(normal_force="paper")
    assert formulation_name(one) == "consistent+normal_force=paper"
    for name, form in NAMED.items():
        assert formulation_name(form) == name


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("bogus", "is not one of"),
        ("consistent+friction_sign=up", "is not allowed"),
        ("consistent+regimes=eq20", "needs friction_sign=theta"),
    ],
)
def test_bad_formulations_are_one_line_errors(text, match):
    with pytest.raises(ParameterError, match=match):
        parse_formulation(text)


def test_section_2_3_mass_labels_make_the_system_singular():
    acc, dt = _harmonic(0.4, 3.0, 0.5)
    with pytest.raises(ParameterError, match="singular"):
        _paper(acc, dt, "consistent+mass_labels=labels")


def test_consistent_switches_off_reproduce_the_compiled_kernel():
    acc, dt = _harmonic(0.4, 3.0, 2.0)
    ref = solve_double_block(BLOCK, acc, dt, mu_s=1.0, mu_k=0.7, **MASSES)
    res = _paper(acc, dt, "consistent")
    assert res.status == ref.status == "came_to_rest"
    assert res.theta_max == pytest.approx(ref.theta_max, rel=1e-3)
    assert res.slip_max == 0.0 and not res.slipped


def test_consistent_while_the_building_slides_matches_the_kernel():
    acc, dt = _harmonic(1.2, 3.0, 2.0)
    ref = solve_double_block(BLOCK, acc, dt, mu_s=1.0, mu_k=0.7, **MASSES)
    res = _paper(acc, dt, "consistent")
    assert res.slipped and ref.slipped
    assert res.theta_max == pytest.approx(ref.theta_max, rel=2e-3)
    assert res.slip_max == pytest.approx(ref.slip_max, rel=2e-2)


def test_each_switch_changes_a_sliding_run_in_the_documented_direction():
    acc, dt = _harmonic(1.2, 3.0, 2.0)
    base = _paper(acc, dt, "consistent")
    # N = M g without the tower's vertical inertia: a little less friction, more slip
    normal = _paper(acc, dt, "consistent+normal_force=paper")
    assert normal.slip_max > base.slip_max
    assert normal.theta_max == pytest.approx(base.theta_max, rel=1e-3)
    # sgn(theta) on the tangential term: the tower's reaction pushes the building, more slip
    tangential = _paper(acc, dt, "consistent+tangential_sign=paper")
    assert tangential.slip_max > 1.1 * base.slip_max
    # friction signed by theta: the base is pushed at mu_k g towards the leaning side,
    # which holds the tower upright (sliding mode): no rotation at all
    theta = _paper(acc, dt, "consistent+friction_sign=theta")
    assert base.theta_max > 0.02 and theta.theta_max == 0.0
    assert theta.n_impacts == 0 and "locks the tower" in theta.message


@pytest.mark.parametrize("mu", [(1.0, 0.7), (3.6, 2.2)])
def test_paper_at_table_2_amplitudes_is_the_single_block_for_every_friction_pair(mu):
    """Eqs. (21)-(23): the building moves only if |a_g| > mu_k g, never at 0.4 g."""
    acc, dt = _harmonic(0.4, 5.0, 1.0)
    ref = solve_double_block(BLOCK, acc, dt, mu_s=mu[0], mu_k=mu[1], **MASSES)
    res = _paper(acc, dt, "di-gennaro-2023", mu)
    assert not res.slipped and res.theta_max == pytest.approx(ref.theta_max, rel=1e-3)


@pytest.mark.parametrize("mu", [(1.0, 0.7), (3.6, 2.2)])
def test_eq20_reading_locks_the_tower_for_every_friction_pair(mu):
    acc, dt = _harmonic(0.5, 3.0, 1.0)
    res = _paper(acc, dt, "di-gennaro-2023-eq20", mu)
    assert res.theta_max == 0.0 and res.slipped and res.status == "moving_at_end"
    assert res.regime is not None and set(np.unique(res.regime)) <= {0, 4}
