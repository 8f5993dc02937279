"""Floor motion: code floor spectra, period laws and the modal floor accelerogram."""

from __future__ import annotations

import numpy as np
import pytest

from rockscreen.pipeline.motion.floor import (
    building_period_from_height,
    ec8_floor_acceleration,
    floor_amplitude,
    linear_mode_participation,
    modal_floor_accelerogram,
    ntc_floor_acceleration,
    ntc_floor_parameters,
)
from rockscreen.pipeline.motion.spectra import response_spectrum, sdof_response
from rockscreen.solver.constants import G
from rockscreen.solver.errors import ParameterError

ALPHA, SOIL = 0.25, 1.2  # alpha S = 0.3
ALPHA_S = ALPHA * SOIL


# --- Eurocode 8 eq. 4.25 -----------------------------------------------------------------------


@pytest.mark.parametrize(("z", "expected"), [(0.0, 1.0), (5.0, 1.75), (10.0, 2.5)])
def test_ec8_rigid_element(z, expected):
    # T_a = 0: 3(1 + z/H)/2 - 0.5, i.e. 1.0 alpha S at the base and 2.5 alpha S at the top.
    value = ec8_floor_acceleration(ALPHA, SOIL, z, 10.0, 0.0, 0.4)
    assert value == pytest.approx(expected * ALPHA_S, rel=1e-12)


def test_ec8_resonance_and_lower_bound():
    assert ec8_floor_acceleration(ALPHA, SOIL, 10.0, 10.0, 0.4, 0.4) == pytest.approx(5.5 * ALPHA_S)
    # A long-period element: 3(1+z/H)/(1+(1-Ta/T1)^2) - 0.5 < 1, the bound alpha S rules.
    assert ec8_floor_acceleration(ALPHA, SOIL, 0.0, 10.0, 4.0, 0.4) == pytest.approx(ALPHA_S)


# --- Circolare 2019 eq. C7.2.11 ----------------------------------------------------------------


@pytest.mark.parametrize(
    ("T1", "row"),
    [
        (0.2, (0.8, 1.4, 5.0)),
        (0.5, (0.8, 1.4, 5.0)),
        (0.7, (0.3, 1.2, 4.0)),
        (1.0, (0.3, 1.2, 4.0)),
        (1.6, (0.3, 1.0, 2.5)),
    ],
)
def test_ntc_table(T1, row):
    assert ntc_floor_parameters(T1) == row


@pytest.mark.parametrize("T1", [0.3, 0.8, 1.5])
def test_ntc_branches_meet_at_a_T1_and_b_T1(T1):
    a, b, a_p = ntc_floor_parameters(T1)
    z, height = 6.0, 10.0
    plateau = ALPHA_S * (1 + z / height) * a_p
    for corner in (a * T1, b * T1):
        below = ntc_floor_acceleration(ALPHA, SOIL, z, height, corner * (1 - 1e-9), T1)
        above = ntc_floor_acceleration(ALPHA, SOIL, z, height, corner * (1 + 1e-9), T1)
        assert below == pytest.approx(plateau, rel=1e-7)
        assert above == pytest.approx(plateau, rel=1e-7)
    middle = 0.5 * (a + b) * T1
    assert ntc_floor_acceleration(ALPHA, SOIL, z, height, middle, T1) == pytest.approx(plateau)


def test_ntc_rigid_element_and_long_period_decay():
    # T_a = 0: a_p / (1 + (a_p - 1)) = 1, the floor PGA alpha S (1 + z/H).
    assert ntc_floor_acceleration(ALPHA, SOIL, 10.0, 10.0, 0.0, 0.3) == pytest.approx(2.0 * ALPHA_S)
    # Past b T1 the spectrum falls: T_a = 2 b T_1 gives a_p / (1 + (a_p - 1)) of the plateau.
    a, b, a_p = ntc_floor_parameters(0.3)
    value = ntc_floor_acceleration(ALPHA, SOIL, 10.0, 10.0, 2 * b * 0.3, 0.3)
    assert value == pytest.approx(2.0 * ALPHA_S * a_p / (1 + (a_p - 1)))


def test_floor_amplitude_is_in_m_s2():
    expected = G * ec8_floor_acceleration(ALPHA, SOIL, 10.0, 10.0, 0.2, 0.4)
    amplitude = floor_amplitude(
        "ec8", ag_over_g=ALPHA, soil_factor=SOIL, z=10.0, H=10.0, Ta=0.2, T1=0.4
    )
    assert amplitude == pytest.approx(expected)
    with pytest.raises(ParameterError, match="code='asce'"):
        floor_amplitude("asce", ag_over_g=ALPHA, soil_factor=SOIL, z=1.0, H=10.0, Ta=0.2, T1=0.4)


@pytest.mark.parametrize("formula", [ec8_floor_acceleration, ntc_floor_acceleration])
@pytest.mark.parametrize(
    ("args", "message"),
    [
        ((-0.1, 1.0, 0.0, 10.0, 0.0, 0.4), "ag_over_g"),
        ((0.2, 0.0, 0.0, 10.0, 0.0, 0.4), "soil_factor"),
        ((0.2, 1.0, 11.0, 10.0, 0.0, 0.4), r"z=11.0 must lie in \[0, H\]"),
        ((0.2, 1.0, 1.0, 0.0, 0.0, 0.4), "H=0.0"),
        ((0.2, 1.0, 1.0, 10.0, -0.1, 0.4), "Ta=-0.1"),
        ((0.2, 1.0, 1.0, 10.0, 0.1, 0.0), "T1=0.0"),
    ],
)
def test_floor_spectra_refuse_bad_input(formula, args, message):
    with pytest.raises(ParameterError, match=message):
        formula(*args)


# --- period laws ------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("law", "expected"),
    [
        ("faccio2010", 0.0187 * 30),  # 0.561 s
        ("ec8", 0.640931),  # 0.05 * 30**0.75
        ("rainieri-fabbrocino", 0.545412),  # 0.01137 * 30**1.138
        ("shakya", 0.594659),  # 0.0151 * 30**1.08
    ],
)
def test_period_laws_at_30_m(law, expected):
    assert building_period_from_height(30.0, law) == pytest.approx(expected, rel=1e-5)


def test_period_law_default_and_errors():
    assert building_period_from_height(10.0) == pytest.approx(0.187)
    with pytest.raises(ParameterError, match="law='nope'.*faccio2010"):
        building_period_from_height(10.0, "nope")
    with pytest.raises(ParameterError, match="H=-1"):
        building_period_from_height(-1.0)


@pytest.mark.parametrize(("n", "expected"), [(1, 1.0), (2, 1.2), (5, 15 / 11), (None, 1.5)])
def test_linear_mode_participation(n, expected):
    assert linear_mode_participation(n) == pytest.approx(expected)


def test_linear_mode_participation_tends_to_the_continuous_limit():
    assert linear_mode_participation(10_000) == pytest.approx(1.5, abs=1e-4)
    with pytest.raises(ParameterError, match="n_storeys=0"):
        linear_mode_participation(0)


# --- modal floor accelerogram ----------------------------------------------------------------


def _ground(dt=0.002, duration=8.0):
    t = np.arange(0.0, duration, dt)
    return 2.0 * np.sin(2 * np.pi * 1.5 * t) * np.exp(-0.4 * t) * (1 - np.exp(-5 * t)), dt


def test_stiff_building_transmits_the_ground_motion():
    ground, dt = _ground()
    floor = modal_floor_accelerogram(ground, dt, building_period=0.01)
    # Relative modal acceleration ~ (T1/T_ground)^2 ~ 2e-4 of the ground, times Gamma phi = 1.5.
    assert np.abs(floor - ground).max() < 1e-3 * np.abs(ground).max()


def test_resonant_building_amplifies():
    dt, period = 0.002, 0.25
    t = np.arange(0.0, 10 * period, dt)
    ground = np.sin(2 * np.pi * t / period)
    floor = modal_floor_accelerogram(ground, dt, building_period=period, damping=0.05)
    # Ten cycles at resonance: the modal response grows toward 1/(2 zeta) = 10 times the input.
    assert np.abs(floor).max() > 5.0 * np.abs(ground).max()


def test_unit_participation_gives_the_oscillator_total_acceleration():
    ground, dt = _ground()
    floor = modal_floor_accelerogram(
        ground, dt, building_period=0.3, participation=1.0, mode_shape_at_base=1.0
    )
    sa, _ = response_spectrum(ground, dt, [0.3], damping=0.05, points_per_period=1)
    # The spectrum pads one period of free vibration; this record has decayed by then.
    assert np.abs(floor).max() == pytest.approx(sa[0], rel=1e-9)


@pytest.mark.parametrize("period", [0.02, 0.3, 3.0])
def test_one_filter_floor_equals_the_oscillator_recurrence(period):
    # The campaign's fast path (one filter on the record) against sdof_response, on a
    # record that does not start at zero: the first samples test the initial state.
    ground, dt = _ground(dt=0.005)
    ground = ground + 0.7 + 0.3 * np.cos(np.arange(ground.size) * 0.37)
    _, _, total = sdof_response(ground, dt, period, 0.05)
    floor = modal_floor_accelerogram(ground, dt, building_period=period, participation=1.0)
    np.testing.assert_allclose(floor, total, rtol=0, atol=1e-12 * np.abs(total).max())


def test_floor_at_the_foundation_is_the_ground():
    ground, dt = _ground()
    floor = modal_floor_accelerogram(ground, dt, building_period=0.3, mode_shape_at_base=0.0)
    np.testing.assert_array_equal(floor, ground)


def test_floor_motion_scales_with_gamma_phi():
    ground, dt = _ground()
    one = modal_floor_accelerogram(ground, dt, building_period=0.3, participation=1.0)
    default = modal_floor_accelerogram(ground, dt, building_period=0.3)
    np.testing.assert_allclose(default - ground, 1.5 * (one - ground), rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"building_period": 0.0}, "building_period=0.0"),
        ({"building_period": 0.3, "participation": -1.0}, "participation=-1.0"),
        ({"building_period": 0.3, "mode_shape_at_base": -0.5}, "mode_shape_at_base=-0.5"),
        ({"building_period": 0.3, "damping": 1.2}, "damping=1.2"),
    ],
)
def test_modal_floor_refuses_bad_input(kwargs, message):
    with pytest.raises(ParameterError, match=message):
        modal_floor_accelerogram(np.ones(50), 0.01, **kwargs)
