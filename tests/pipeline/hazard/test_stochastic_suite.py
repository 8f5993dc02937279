"""The site-based stochastic suite (Rezaeian & Der Kiureghian 2010, pulses) and its dispersion."""

from __future__ import annotations

import math

import numpy as np
import pytest
from obspy import Stream
from scipy import optimize, stats

from rockscreen.pipeline.engine import registry
from rockscreen.pipeline.engine.cases import BlockCache, screen_case
from rockscreen.pipeline.hazard import RETURN_PERIODS_Y, limit_state_return_period
from rockscreen.pipeline.hazard.matching import batch_spectrum
from rockscreen.pipeline.hazard.selection import SuiteRecord, select_in_order
from rockscreen.pipeline.hazard.stochastic_suite import stochastic_suite, suite_scenario
from rockscreen.pipeline.hazard.suite import site_record_set
from rockscreen.pipeline.motion.stochastic import (
    Scenario,
    gamma_modulation,
    pulse_probability,
    simulate_record,
)
from rockscreen.pipeline.records.grouping import group_records
from rockscreen.pipeline.records.io import read_stream
from rockscreen.pipeline.risk.assess.run import AssessOptions, tower_sites
from rockscreen.solver.constants import G
from rockscreen.stations.inventory import Tower, example_inventory_path, read_inventory

LAQUILA = (13.3995, 42.3498)
CERVINO = (14.42, 41.04)


def test_gamma_modulation_gives_duration_and_midpoint():
    alpha1, alpha2, alpha3 = gamma_modulation(0.05, 12.0, 6.0)
    t = np.arange(1, 200_000) * 1e-3
    energy = np.cumsum((alpha1 * t ** (alpha2 - 1) * np.exp(-alpha3 * t)) ** 2) * 1e-3
    t5, t45, t95 = np.interp([0.05, 0.45, 0.95], energy / energy[-1], t)
    assert t95 - t5 == pytest.approx(12.0, rel=1e-3)
    assert t45 == pytest.approx(6.0, rel=1e-3)
    assert math.pi / (2 * G) * energy[-1] == pytest.approx(0.05 * G, rel=1e-3)


def test_pulse_probability_decreases_with_distance():
    assert pulse_probability(0.0) == pytest.approx(1 / (1 + math.exp(0.642)))
    assert pulse_probability(5.0) > pulse_probability(20.0) > pulse_probability(60.0)


def test_pulse_probability_of_non_strike_slip_ruptures_decays_slower():
    # Shahi & Baker (2011): 1 / (1 + exp(0.128 + 0.055 R)) for reverse and normal faults.
    assert pulse_probability(10.0, 1) == pytest.approx(1 / (1 + math.exp(0.128 + 0.55)))
    assert pulse_probability(10.0, 1) > 3 * pulse_probability(10.0, 0)
    assert pulse_probability(5.0, 1) > pulse_probability(20.0, 1) > pulse_probability(60.0, 1)


def test_suite_scenarios_are_non_strike_slip():
    scenario = suite_scenario(np.random.default_rng(0), "A")
    assert scenario.non_strike_slip == 1
    assert 5.0 <= scenario.magnitude <= 7.0 and 3.0 <= scenario.distance_km <= 100.0


def test_simulated_record_is_deterministic_and_ends_near_rest():
    scenario = Scenario(6.3, 10.0, 800.0)
    a = simulate_record(np.random.default_rng(3), scenario)
    b = simulate_record(np.random.default_rng(3), scenario)
    np.testing.assert_array_equal(a.x, b.x)
    assert not np.allclose(a.x, a.y)
    velocity = np.cumsum(a.x) * a.dt_s
    assert abs(velocity[-1]) < 0.05 * np.max(np.abs(velocity))


def test_stochastic_suite_is_deterministic_and_scaled_per_return_period():
    first = stochastic_suite(*LAQUILA, 475.0, n_records=3)
    again = stochastic_suite(*LAQUILA, 475.0, n_records=3)
    other = stochastic_suite(*LAQUILA, 975.0, n_records=3)
    assert len(first) == 3
    assert all(r.acc_y_m_s2 is not None and r.acc_z_m_s2 is not None for r in first)
    np.testing.assert_array_equal(first[0].acc_x_m_s2, again[0].acc_x_m_s2)
    assert first[0].acc_x_m_s2.shape != other[0].acc_x_m_s2.shape or not np.allclose(
        first[0].acc_x_m_s2, other[0].acc_x_m_s2
    )
    assert "Rezaeian & Der Kiureghian" in first[0].source


def test_site_record_set_stochastic_kind_has_eleven_records():
    result = site_record_set(*LAQUILA, 475.0, "A", "T1", kind="stochastic", seed=1)
    assert len(result.records) == 11
    assert np.all((result.scale_factors >= 0.25) & (result.scale_factors <= 4.0))


def test_site_record_set_scales_the_stochastic_records_once():
    # The suite's own scaling, not a second one on top (the 0.25-4 caps applied once).
    result = site_record_set(*CERVINO, 475.0, "A", "T1", seed=0)
    suite = {r.name: r for r in stochastic_suite(*CERVINO, 475.0, "A", "T1", seed=0)}
    assert result.meets_tolerance, result.message
    assert sorted(r.name for r in result.records) == sorted(suite)
    for i, record in enumerate(result.records):
        scaled = result.scaled(i)
        for component in ("acc_x_m_s2", "acc_y_m_s2", "acc_z_m_s2"):
            np.testing.assert_allclose(
                getattr(scaled, component), getattr(suite[record.name], component), rtol=1e-9
            )


@pytest.mark.slow
def test_default_suite_complies_at_every_return_period_of_an_example_site():
    sites = [s for s in tower_sites(read_inventory(example_inventory_path()), 0.01) if s.key]
    lon, lat, soil, topography = sites[0].key
    tr_slv = limit_state_return_period("SLV", sites[0].nominal_life_y, sites[0].use_class)
    for tr in sorted({*map(float, RETURN_PERIODS_Y), tr_slv}):
        result = site_record_set(lon, lat, tr, soil, topography)
        compliance = AssessOptions().set_compliance(result)
        assert compliance.compliant and len(result.records) == 11, (tr, compliance.reason)


def test_select_in_order_keeps_the_first_records_when_they_comply():
    periods = np.geomspace(0.15, 2.0, 5)
    target = np.ones(5)
    spectra = np.array([[1.0] * 5, [2.0] * 5, [0.5] * 5, [1.0, 1.0, 1.0, 1.0, 9.0]])
    suite = [SuiteRecord(f"R{i}", np.ones(4), None, None, 0.01, "") for i in range(4)]
    chosen = select_in_order(suite, spectra, periods, target, n_records=2)
    assert [r.name for r in chosen.records] == ["R0", "R1"] and chosen.meets_tolerance


# --- Dispersion acceptance (issue 20, item 3) ------------------------------------------

#: Reference block: 0.6 m x 4 m on rock, ground model.
TOWER = Tower(id="REF", width_m=0.6, height_m=4.0)
#: Geometric grid ratio, bisection steps, highest PGA tried [m/s²], free motion [s].
GRID_RATIO, BISECTIONS, PGA_CAP, FREE_S = 1.3, 4, 40.0, 10.0


def _collapse_pga(acc, dt, block):
    """PGA [m/s²] of first overturning (grid from the uplift PGA, then bisection)."""
    model = registry.get("ground")
    unit = np.asarray(acc, float) / np.max(np.abs(acc))

    def falls(pga):
        return screen_case(model, TOWER, block, unit * pga, None, dt, FREE_S).overturned

    safe = pga = G * math.tan(block.alpha)
    while pga <= PGA_CAP:
        if falls(pga):
            low, high = safe, pga
            for _ in range(BISECTIONS):
                mid = math.sqrt(low * high)
                low, high = (low, mid) if falls(mid) else (mid, high)
            return high, False
        safe, pga = pga, pga * GRID_RATIO
    return PGA_CAP, True


def _beta(values, censored):
    """Lognormal beta: sample std of ln, or the censored MLE when some never fell."""
    x, c = np.log(values), np.asarray(censored, bool)
    if not c.any():
        return float(np.std(x, ddof=1))

    def nll(p):
        b = math.exp(p[1])
        return -(stats.norm.logpdf(x[~c], p[0], b).sum() + stats.norm.logsf(x[c], p[0], b).sum())

    fit = optimize.minimize(nll, [x.mean(), math.log(x.std() + 1e-3)], method="Nelder-Mead")
    return math.exp(fit.x[1])


def _trimmed(acc, dt, margin_s=2.0):
    """The record between 0.1 % and 99.9 % of its Arias intensity, plus a margin."""
    energy = np.cumsum(np.asarray(acc, float) ** 2)
    energy /= energy[-1]
    pad = round(margin_s / dt)
    start = max(0, int(np.searchsorted(energy, 0.001)) - pad)
    return acc[start : int(np.searchsorted(energy, 0.999)) + pad]


#: NTC 2018 soil class (Tab. 3.2.II: B 360-800 m/s, C 180-360 m/s) of each real station,
#: from its V_s30 in ``../shared/data/SOURCES.md``: none is on soil A (> 800 m/s).
REAL_SOIL = {
    **dict.fromkeys(("AQV", "AQG", "GSA", "CSS", "STL"), "B"),
    **dict.fromkeys(("AVZ", "BOJ", "SNS", "CTL", "BBN", "FOR"), "C"),
}


def _real_horizontals(shared_data):
    """(soil class, horizontal [m/s²], dt [s]) of the 22 real components, trimmed."""
    out = []
    for name in ("laquila2009", "laquila2009_regional"):
        folder = shared_data / name
        if not (folder / "stations.xml").is_file():
            pytest.skip(f"{folder} is absent")
        stream = Stream()
        for path in sorted(folder.glob("*.mseed")):
            stream += read_stream(path, stations=folder / "stations.xml")
        for record in group_records(stream):
            soil = REAL_SOIL[record.station.split(".")[-1]]
            out += [(soil, _trimmed(h, record.dt), record.dt) for h in (record.h1, record.h2)]
    return out


def _own_factor(acc, dt, chosen):
    """Least-squares factor (in logs) of a real component's spectrum to a set's target."""
    sa = batch_spectrum(np.asarray(acc, float)[None, :], dt, chosen.periods_s)[0] / G
    return float(np.exp(np.mean(np.log(chosen.target_sa_g / sa))))


def _betas(components, block):
    """PGA-normalised and ag-scaled betas of (acceleration, dt, factor) components.

    The ag-scaled capacity is the PGA capacity over the scaled record's PGA (the multiple
    of the set at first overturning): the same search, the record's amplitude at its set's
    spectrum counted.
    """
    pga_cap, ag_cap, censored = [], [], []
    for acc, dt, factor in components:
        capacity, never = _collapse_pga(acc, dt, block)
        pga_cap.append(capacity)
        ag_cap.append(capacity / (factor * np.max(np.abs(acc))))
        censored.append(never)
    return _beta(pga_cap, censored), _beta(ag_cap, censored)


#: Seeds of the suite the acceptance is checked on (their sets pooled: 132 components).
SEEDS = (0, 1, 2)


@pytest.mark.slow
def test_stochastic_suite_dispersion_matches_real_records(shared_data):
    """The suite's betas (PGA-normalised, ag-scaled) within 25 % of the real records' ones.

    Like for like: the 22 real horizontals are on soils B (10) and C (12), none on A, so the
    suite is its L'Aquila sets for soils B and C at TR 475 y, both horizontals, of seeds 0,
    1 and 2 pooled (132 components: a beta of 44 components has a sampling error of about
    11 %, of 132 about 6 %). A real component's factor is its own least-squares factor to
    the target of its soil. Measured (docs/hazard.md, Dispersion): real 0.82 / 0.59, suite
    0.70 / 0.58 (seeds 0 / 1 / 2 alone: 0.65 / 0.73 / 0.72 and 0.46 / 0.60 / 0.64; 0.75 /
    0.55 when each set started from an order seeded by its site).
    """
    block = BlockCache(TOWER)(TOWER.width_m)
    sets = [
        {
            soil: site_record_set(*LAQUILA, 475.0, soil, "T1", kind="stochastic", seed=seed)
            for soil in "BC"
        }
        for seed in SEEDS
    ]
    real = [
        (acc, dt, _own_factor(acc, dt, sets[0][soil]))
        for soil, acc, dt in _real_horizontals(shared_data)
    ]
    beta_real = _betas(real, block)
    assert 0.6 < beta_real[0] < 1.1 and 0.3 < beta_real[1] < 0.8, beta_real
    suite = [
        (np.trim_zeros(getattr(record, component), "b"), record.dt_s, float(factor))
        for by_soil in sets
        for chosen in by_soil.values()
        for record, factor in zip(chosen.records, chosen.scale_factors, strict=True)
        for component in ("acc_x_m_s2", "acc_y_m_s2")
    ]
    assert len(real) == 22 and len(suite) == 132
    beta_suite = _betas(suite, block)
    ratios = [s / r for s, r in zip(beta_suite, beta_real, strict=True)]
    assert all(abs(r - 1.0) <= 0.25 for r in ratios), (beta_real, beta_suite)
