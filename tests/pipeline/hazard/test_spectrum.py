"""NTC 2018 elastic spectra and limit states against hand computations."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rockscreen.pipeline.errors import HazardError
from rockscreen.pipeline.hazard import (
    LIMIT_STATES,
    SiteHazard,
    elastic_spectrum,
    limit_state_return_period,
    reference_period,
    site_hazard,
    spectrum_parameters,
    vertical_spectrum,
)

SITE = SiteHazard(
    lon_deg=14.0, lat_deg=42.0, return_period_y=475.0, ag_g=0.25, F0=2.4, Tc_star_s=0.3
)


def test_rock_flat_five_percent_by_hand():
    # Soil A, T1: S = 1; xi = 5 % -> eta = sqrt(10/10) = 1.
    # T_C = 1.0 * 0.3 = 0.3 s, T_B = 0.1 s, T_D = 4 * 0.25 + 1.6 = 2.6 s;
    # plateau 0.25 * 2.4 = 0.6 g.
    p = spectrum_parameters(SITE)
    assert (p.S, p.S_S, p.S_T, p.C_C, p.eta) == (1.0, 1.0, 1.0, 1.0, 1.0)
    assert (p.TB_s, p.TC_s, p.TD_s) == pytest.approx((0.1, 0.3, 2.6))
    assert p.pga_g == pytest.approx(0.25)
    se = elastic_spectrum([0.0, 0.05, 0.2, 1.0, 3.0], SITE)
    expected = [
        0.25,  # T = 0: ag S
        0.25 * 2.4 * (0.05 / 0.1 + (1 - 0.05 / 0.1) / 2.4),  # = 0.3 + 0.125 = 0.425
        0.6,  # plateau
        0.6 * 0.3 / 1.0,  # = 0.18
        0.6 * 0.3 * 2.6 / 3.0**2,  # = 0.052
    ]
    assert se == pytest.approx(expected, rel=1e-12)
    assert se[1] == pytest.approx(0.425)


def test_soil_c_topography_t2_ten_percent_by_hand():
    # S_S = 1.70 - 0.60 * 2.4 * 0.25 = 1.70 - 0.36 = 1.34, inside [1.00, 1.50].
    # C_C = 1.05 * 0.3^-0.33 = 1.05 * exp(0.33 * 1.20397) = 1.05 * 1.48782 = 1.56221.
    # S_T = 1.2 -> S = 1.34 * 1.2 = 1.608; eta = sqrt(10/15) = 0.81650.
    # T_C = 1.56221 * 0.3 = 0.46866 s, T_B = 0.15622 s, T_D = 2.6 s.
    p = spectrum_parameters(SITE, "C", "T2", damping=0.10)
    assert p.S_S == pytest.approx(1.34)
    assert p.C_C == pytest.approx(1.56221, rel=1e-5)
    assert p.S == pytest.approx(1.608)
    assert p.eta == pytest.approx(0.81650, rel=1e-5)
    assert p.TC_s == pytest.approx(0.46866, rel=1e-4)
    assert p.TB_s == pytest.approx(0.15622, rel=1e-4)
    assert p.pga_g == pytest.approx(0.25 * 1.608)
    plateau = 0.25 * 1.608 * 0.81650 * 2.4  # = 0.78773 g
    se = elastic_spectrum([0.3, 1.0, 4.0], SITE, "C", "T2", 0.10)
    assert se[0] == pytest.approx(plateau, rel=1e-4)
    assert se[1] == pytest.approx(plateau * 0.46866 / 1.0, rel=1e-4)
    assert se[2] == pytest.approx(plateau * 0.46866 * 2.6 / 16.0, rel=1e-4)


def test_soil_factor_bounds_by_hand():
    strong = SiteHazard(14.0, 42.0, 2475.0, ag_g=0.5, F0=2.5, Tc_star_s=0.4)
    # D: 2.40 - 1.50 * 2.5 * 0.5 = 0.525 -> lower bound 0.90; C_C = 1.25 * 0.4^-0.5 = 1.97642.
    d = spectrum_parameters(strong, "D", "T4")
    assert d.S_S == 0.90
    assert d.C_C == pytest.approx(1.25 / math.sqrt(0.4))
    assert d.S == pytest.approx(0.90 * 1.4)
    weak = SiteHazard(14.0, 42.0, 30.0, ag_g=0.05, F0=2.4, Tc_star_s=0.25)
    # B: 1.40 - 0.40 * 2.4 * 0.05 = 1.352 -> upper bound 1.20; C_C = 1.10 * 0.25^-0.2 = 1.44768.
    b = spectrum_parameters(weak, "B", "T3")
    assert b.S_S == 1.20
    assert b.C_C == pytest.approx(1.10 * 0.25**-0.2)
    assert b.S == pytest.approx(1.44)
    # E: 2.00 - 1.10 * 2.4 * 0.05 = 1.868 -> 1.60; C_C = 1.15 * 0.25^-0.4.
    e = spectrum_parameters(weak, "E")
    assert e.S_S == 1.60
    assert e.C_C == pytest.approx(1.15 * 0.25**-0.4)


def test_damping_floor_eta():
    # xi = 30 %: sqrt(10/35) = 0.5345 < 0.55 -> 0.55.
    assert spectrum_parameters(SITE, damping=0.30).eta == 0.55
    # xi = 2 %: sqrt(10/7) = 1.19523.
    assert spectrum_parameters(SITE, damping=0.02).eta == pytest.approx(math.sqrt(10 / 7))


def test_vertical_by_hand():
    # F_v = 1.35 * 2.4 * 0.25^0.5 = 1.62; T4: S = 1.0 * 1.4; plateau 0.25 * 1.4 * 1.62 = 0.567 g.
    sve = vertical_spectrum([0.0, 0.025, 0.1, 0.5, 2.0], SITE, "C", "T4")
    expected = [
        0.25 * 1.4,  # = 0.35
        0.567 * (0.5 + 0.5 / 1.62),  # T/T_B = 0.5
        0.567,
        0.567 * 0.15 / 0.5,  # = 0.1701
        0.567 * 0.15 * 1.0 / 4.0,  # = 0.0212625
    ]
    assert sve == pytest.approx(expected, rel=1e-12)


def test_real_sites_by_hand():
    # L'Aquila at 475 years, soil B: S_S = 1.40 - 0.40 F0 ag, C_C = 1.10 T*C^-0.2.
    site = site_hazard(13.3995, 42.3498, 475)
    s_s = min(max(1.40 - 0.40 * site.F0 * site.ag_g, 1.0), 1.2)
    tc = 1.10 * site.Tc_star_s**-0.2 * site.Tc_star_s
    assert elastic_spectrum(0.2, site, "B") == pytest.approx(site.ag_g * s_s * site.F0)
    assert elastic_spectrum(1.0, site, "B") == pytest.approx(site.ag_g * s_s * site.F0 * tc)
    # Cervino at 975 years, rock, T1, 5 %: S = 1, T_C = T*C.
    cervino = site_hazard(14.42, 41.04, 975)
    td = 4.0 * cervino.ag_g + 1.6
    assert elastic_spectrum(td + 1.0, cervino) == pytest.approx(
        cervino.ag_g * cervino.F0 * cervino.Tc_star_s * td / (td + 1.0) ** 2
    )


def test_bad_classes_refused():
    with pytest.raises(HazardError, match="soil class 'F'"):
        spectrum_parameters(SITE, "F")
    with pytest.raises(HazardError, match="topography 'T5'"):
        elastic_spectrum(1.0, SITE, "A", "T5")
    with pytest.raises(HazardError, match="damping"):
        spectrum_parameters(SITE, damping=5.0)
    with pytest.raises(HazardError, match="periods"):
        elastic_spectrum([-1.0], SITE)


def test_limit_state_return_periods_by_hand():
    # V_N = 50, class II: V_R = 50 y; TR = -50 / ln(1 - P_VR).
    expected = {
        "SLO": -50 / math.log(0.19),  # 30.1 y
        "SLD": -50 / math.log(0.37),  # 50.3 y
        "SLV": -50 / math.log(0.90),  # 474.6 y
        "SLC": -50 / math.log(0.95),  # 974.8 y
    }
    for state in LIMIT_STATES:
        assert limit_state_return_period(state) == pytest.approx(expected[state])
    assert limit_state_return_period("SLV") == pytest.approx(474.56, abs=0.01)
    # Class III: V_R = 50 * 1.5 = 75 y -> SLV 711.8 y.
    assert limit_state_return_period("SLV", 50, "III") == pytest.approx(-75 / math.log(0.9))
    # Class I: V_R = 35 y -> SLO 21.1 y (below the table: site_hazard refuses it).
    assert limit_state_return_period("slo", 50, "I") == pytest.approx(-35 / math.log(0.19))
    # V_R never below 35 y (NTC 2018 §2.4.3): 10 * 2.0 = 20 -> 35.
    assert reference_period(10, "IV") == 35.0


def test_bad_limit_state_inputs():
    with pytest.raises(HazardError, match="limit state 'SLU'"):
        limit_state_return_period("SLU")
    with pytest.raises(HazardError, match="use class 'V'"):
        limit_state_return_period("SLV", 50, "V")
    with pytest.raises(HazardError, match="nominal life"):
        limit_state_return_period("SLV", -1.0)


def test_spectrum_shape_continuous_at_corners():
    p = spectrum_parameters(SITE, "E", "T3", 0.07)
    corners = np.array([p.TB_s, p.TC_s, p.TD_s])
    below = elastic_spectrum(corners * (1 - 1e-9), SITE, "E", "T3", 0.07)
    above = elastic_spectrum(corners * (1 + 1e-9), SITE, "E", "T3", 0.07)
    assert below == pytest.approx(above, rel=1e-6)
