"""Issue 31's acceptance tests of the uncertainty library on a known tower.

(a) A known tower (T06 of the twelve-tower example, 34 m of rubble at L'Aquila) with every
input given (wall, taper, masonry type, mean strength, period: every prior collapsed to a
point) gets, as its best estimate, the deterministic P in 50 years: the shaft's
``best_estimate_lv1`` at the mean strength, the whole tower's kinematic check at F_C = 1,
the weaker of the two through the risk integral. With near-point priors (each input known
to about 1 %) the same P is recovered within the Monte-Carlo error of the sample median.

(b) The 90 % interval of P widens when a prior widens: the period ratio's log-std (and,
separately, the wall ratio's) through a region's priors file at three widths, the interval
monotone in the width (common random numbers: the same seed for each width; the other
priors of the file fixed, so that only the widened one varies).
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from rockscreen.pipeline.risk.checks.kinematic import kinematic_check
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.checks.tower_mechanisms import tower_kinematic_mechanism
from rockscreen.pipeline.risk.measures.hazard_integral import (
    annual_rate_of_overturning,
    probability_in,
)
from rockscreen.pipeline.risk.uncertainty import (
    TowerPriors,
    best_estimate_lv1,
    read_region_priors,
    shaft_capacity,
)
from rockscreen.pipeline.risk.uncertainty.distributions import LogNormal, Point, Uniform
from rockscreen.pipeline.risk.uncertainty.kinematic import MechanismCapacity, kinematic_capacities
from rockscreen.pipeline.risk.uncertainty.risk import (
    DEFAULT_ALEATORY_BETA,
    site_hazard_curve,
    stratum_weights,
    tower_risk,
)
from rockscreen.stations.inventory import read_inventory

EXAMPLES = Path(__file__).resolve().parents[4] / "examples" / "tower_population"
#: T06 of the example: 34 x 5.5 m, rubble, walls 1.1 m (towers_shaft_lc1.csv).
T06 = next(t for t in read_inventory(EXAMPLES / "towers_shaft_lc1.csv") if t.id == "T06")
#: Every input given: the taper, the mean strength of rubble (the middle of Table C8.5.I's
#: 1.0-2.0 MPa) and the period of the code's law.
EXACT = replace(
    T06,
    wall_thickness_top_m=0.7,
    masonry_strength_mpa=1.5,
    knowledge_level="LC3",  # a measured f_m is read at LC3 only (the inventory's rule)
    shaft_period_s=0.0187 * T06.height_m,
)
SITE = SiteConditions(lon_deg=EXACT.lon, lat_deg=EXACT.lat, soil_class=EXACT.soil_class)
CURVE = site_hazard_curve(SITE)


def _risk(tower, priors: TowerPriors, n: int, seed: int = 0):
    samples = priors.sample(np.random.default_rng(seed), n)
    shaft = shaft_capacity(tower, SITE, samples)
    kinematic, _ = kinematic_capacities(tower, SITE, samples)
    mechanisms = [MechanismCapacity("shaft", shaft.ag_g, shaft.bound), *kinematic]
    return tower_risk(mechanisms, CURVE, weights=stratum_weights(samples, priors))


def _deterministic_p50() -> float:
    """Return P in 50 y of EXACT computed directly, without the library's sampling."""
    w = 19.0e3  # rubble's unit weight, Table C8.5.I [N/m3]
    shaft = best_estimate_lv1(
        EXACT,
        SITE,
        wall_m=EXACT.wall_thickness_m,
        wall_top_m=EXACT.wall_thickness_top_m,
        unit_weight_n_m3=w,
        fm_pa=1.5e6,
        period_s=EXACT.shaft_period_s,
    ).capacity
    mechanism, _ = tower_kinematic_mechanism(EXACT)
    whole = kinematic_check(mechanism, SITE, fc=1.0).nonlinear
    assert shaft.bound == "" and shaft.ag_g < whole.ag_g  # the shaft governs, a value
    rate = annual_rate_of_overturning(CURVE, shaft.ag_g, DEFAULT_ALEATORY_BETA)
    return probability_in(rate)


def test_exact_inputs_recover_the_deterministic_p50():
    """Priors collapsed to points: the best estimate is the deterministic P50.

    No Monte-Carlo error is left (every sample is the same tower): the tolerance, 1e-6
    relative, is the capacity's inversion on the hazard (RTOL_LN_TR = 1e-7 in ln T_R,
    times d ln P / d ln T_R of order 1-10).
    """
    priors = TowerPriors.from_tower(EXACT)
    assert all(isinstance(p, Point) for p in priors.priors().values())
    risk = _risk(EXACT, priors, 50)
    expected = _deterministic_p50()
    assert 0.0 < expected < 1.0
    assert risk.p50_best == pytest.approx(expected, rel=1e-6)
    assert risk.p50_lo90 == risk.p50_best == risk.p50_hi90
    assert risk.governing_mechanism == "shaft" and risk.governing_share == 1.0


def test_near_exact_inputs_recover_the_deterministic_p50_within_the_mc_error():
    """Each input known to about 1 %: the best estimate within 3 standard errors.

    The wall, the taper's top wall, f_m and the period each carry a 1 % prior (log-std
    0.01, or uniform +-1.7 %: the same standard deviation) centred on the exact value, so
    the deterministic P50 is the median of P over the inputs to first order. The best
    estimate is the sample median of P_i over n = 400 samples: its standard error is
    estimated by a bootstrap of the samples' P (200 resamples with the samples' weights),
    and the tolerance is 3 standard errors plus the first-order bias bound, 1e-3 relative
    (the second-order term of a 1 % input spread).
    """
    exact = TowerPriors.from_tower(EXACT)
    wall, top = EXACT.wall_thickness_m, EXACT.wall_thickness_top_m
    priors = replace(
        exact,
        wall=LogNormal(wall, 0.01, "test: 1 %"),
        period=LogNormal(EXACT.shaft_period_s, 0.01, "test: 1 %"),
        fm_given_pa=None,
        masonry=Point("rubble", "test"),
    )
    # f_m: uniform +-1.7 % about 1.5 MPa (std 1 %), through the strength prior's hook.
    fm = Uniform(1.5e6 * (1 - 0.0173), 1.5e6 * (1 + 0.0173), "test: 1 %")
    priors = _with_strength(replace(priors, taper=LogNormal(top / wall, 0.01, "test: 1 %")), fm)
    n = 400
    risk = _risk(EXACT, priors, n, seed=3)
    p = risk.probability
    assert np.ptp(p) > 0.0  # the inputs do vary: a real Monte-Carlo estimate
    rng = np.random.default_rng(0)
    boot = [
        np.quantile(p[idx], 0.5, method="inverted_cdf", weights=risk.weights[idx])
        for idx in (rng.integers(0, n, n) for _ in range(200))
    ]
    se = float(np.std(boot))
    expected = _deterministic_p50()
    assert abs(risk.p50_best - expected) <= 3.0 * se + 1e-3 * expected
    assert risk.p50_lo90 < expected < risk.p50_hi90


def _with_strength(priors: TowerPriors, fm: Uniform) -> TowerPriors:
    """Return ``priors`` whose f_m prior is ``fm`` whatever the type (a test-only subclass)."""

    class _Priors(TowerPriors):
        def strength(self, masonry_type: str):
            return fm

    return _Priors(**{k: getattr(priors, k) for k in priors.__dataclass_fields__})


GEOMETRY_ONLY = replace(
    T06,
    wall_thickness_m=None,
    masonry_type="solid_brick",  # the type fixed: the interval is the prior's alone
    knowledge_level=None,
)


#: The other priors fixed in the region's file, so that only the widened one varies (the
#: wall matters only through the taper: a prismatic shaft's base stress is w H whatever
#: its wall, so the wall's test tapers the walls to half).
FIXED = {
    "period_ratio": '[taper]\nvalue = 0.5\nsource = "test"\n',
    "wall_ratio": '[taper]\nvalue = 0.5\nsource = "test"\n'
    '[period_ratio]\nvalue = 0.95\nsource = "test"\n',
}


def _region(tmp_path: Path, table: str, median: float, log_std: float) -> Path:
    path = tmp_path / f"{table}_{log_std}.toml"
    path.write_text(
        f'region = "test"\n[{table}]\nmedian = {median}\nlog_std = {log_std}\n'
        f'source = "test: a prior widened"\n{FIXED[table]}'
    )
    return path


@pytest.mark.parametrize(
    ("table", "median", "widths"),
    [("period_ratio", 0.9501, (0.15, 0.3, 0.6)), ("wall_ratio", 0.2271, (0.1, 0.2, 0.4))],
)
def test_the_interval_widens_monotonically_with_a_prior(tmp_path, table, median, widths):
    """A region's prior at three log-stds (each the double of the last): wider each time."""
    out = []
    for log_std in widths:
        region = read_region_priors(_region(tmp_path, table, median, log_std))
        priors = TowerPriors.from_tower(GEOMETRY_ONLY, region)
        risk = _risk(GEOMETRY_ONLY, priors, 300, seed=1)
        assert risk.p50_lo90 <= risk.p50_best <= risk.p50_hi90
        out.append(risk.p50_hi90 - risk.p50_lo90)
    assert 0.0 < out[0] < out[1] < out[2], out
