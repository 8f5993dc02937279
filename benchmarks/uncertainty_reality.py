"""Reality checks of the screening risk: where the best-estimate capacities sit (issue 31).

docs/risk.md, "Reality checks of the screening risk".

::

    python benchmarks/uncertainty_reality.py [--turris PATH] [--n 1000] [--seed 0]

For the twelve towers of ``examples/tower_population/towers_geometry.csv`` (L'Aquila, soil
B) and, with ``--turris``, the Italian towers of TURRIS with a wall thickness at their own
location on soil B (geometry only, as ``uncertainty_calibration.py``; the Emilia subset:
latitude 44.3-44.95, longitude 10.5-12.3, the plain of the 2012 sequence and Bologna), the
library's best estimate per tower (default priors, n samples, seed): the **median capacity**
(the weighted median over the samples of the weakest mechanism's ag on rock [g], as
``tower_risk`` reads it, with the share of samples whose capacity is a bound of the hazard
table), P in 50 years, and two readings made for comparing with what earthquakes did:

- the shaft's capacity **without the table's ceiling**: a sample that holds at 2475 y gets
  the ag at which its S_e,SLV is reached on the site's 2475-y spectral shape (F0, T*C kept,
  ag raised; ``elastic_spectrum`` of NTC 2018 §3.2.3.2.1), so the median is a value, not a
  bound; then the whole tower's ground PGA ``S ag`` (soil B's S at that ag);
- the expected **share of towers that fail** at a ground PGA of 0.25, 0.49 and 0.86 g: the
  mean over towers of each tower's fragility (the samples' lognormal curves, beta 0.40,
  mixed with their weights) on the shaft's ceiling-free capacity, the PGA on rock being the
  ground PGA over soil B's S.

The figures to compare with (issue 31): ordinary masonry houses in Central Italy 2016
collapsed with median PGA 0.49 g (Saretta et al. 2023); bell towers in Finale Emilia 2012
fell at about 0.2-0.3 g; Sant'Agostino's tower at Amatrice stood about 0.86 g; 8 of 33
damaged towers of the Modena-Nonantola archdiocese collapsed in 2012.
"""

from __future__ import annotations

import argparse
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
from scipy.special import ndtr

from rockscreen.pipeline.hazard import elastic_spectrum, spectrum_parameters
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.uncertainty import TowerPriors, shaft_capacity
from rockscreen.pipeline.risk.uncertainty.kinematic import MechanismCapacity, kinematic_capacities
from rockscreen.pipeline.risk.uncertainty.risk import (
    DEFAULT_ALEATORY_BETA,
    DEFAULT_SAMPLES,
    site_hazard_curve,
    stratum_weights,
    tower_risk,
)
from rockscreen.solver.constants import G
from rockscreen.stations.inventory import read_inventory
from rockscreen.stations.tower import Tower

sys.path.insert(0, str(Path(__file__).resolve().parent))
from uncertainty_calibration import geometry_only, turris_rows, turris_towers  # noqa: E402

EXAMPLE = Path(__file__).resolve().parents[1] / "examples/tower_population/towers_geometry.csv"
#: The Emilia subset of TURRIS (module docstring) [deg].
EMILIA = ((44.3, 44.95), (10.5, 12.3))
#: Ground PGAs of the comparison [g].
GROUND_PGA_G = (0.25, 0.49, 0.86)
#: The ag grid [g] of the ceiling-free inversion.
_AG = np.geomspace(0.01, 5.0, 400)


def _weighted_median(x: np.ndarray, w: np.ndarray) -> float:
    return float(np.quantile(x, 0.5, method="inverted_cdf", weights=w))


def ceiling_free(site: SiteConditions, se_slv: np.ndarray, period: np.ndarray, ag, bound):
    """Return the shaft's ag [g] with the 2475-y ceiling lifted (module docstring)."""
    out = np.asarray(ag, dtype=float).copy()
    held = np.asarray(bound) == "lower"
    if not held.any():
        return out
    top = site.hazard(2475.0)
    se = np.array(
        [
            elastic_spectrum(period[held], replace(top, ag_g=float(a)), site.soil_class) * G
            for a in _AG
        ]
    )  # ag grid x held samples [m/s2]
    crossed = se >= se_slv[held][None, :]
    j = np.where(crossed.any(axis=0), np.argmax(crossed, axis=0), len(_AG) - 1)
    out[held] = _AG[j]
    return out


def soil_factor(site: SiteConditions, ag_g: float) -> float:
    """Return soil B's S at the site's 2475-y shape scaled to ag [-] (NTC 2018 §3.2.3.2.1)."""
    top = site.hazard(2475.0)
    return spectrum_parameters(replace(top, ag_g=float(ag_g)), site.soil_class).S


def one_tower(tower: Tower, n: int, seed: int) -> dict:
    """Return one tower's best-estimate numbers (module docstring)."""
    site = SiteConditions(lon_deg=tower.lon, lat_deg=tower.lat, soil_class=tower.soil_class)
    priors = TowerPriors.from_tower(tower)
    samples = priors.sample(np.random.default_rng(seed), n)
    shaft = shaft_capacity(tower, site, samples)
    kinematic, _ = kinematic_capacities(tower, site, samples)
    w = stratum_weights(samples, priors)
    risk = tower_risk(
        [MechanismCapacity("shaft", shaft.ag_g, shaft.bound), *kinematic],
        site_hazard_curve(site),
        weights=w,
    )
    free = ceiling_free(site, shaft.se_slv_m_s2, shaft.period_s, shaft.ag_g, shaft.bound)
    free_median = _weighted_median(free, w)
    fail = {}
    for pga in GROUND_PGA_G:
        # ag on rock whose ground PGA S ag is pga (S depends on ag: a fixed point).
        a = pga / 1.2
        for _ in range(20):
            a = pga / soil_factor(site, a)
        fail[pga] = float(w @ ndtr(np.log(a / free) / DEFAULT_ALEATORY_BETA))
    return {
        "capacity_g": _weighted_median(risk.capacity_g, w),
        "bounded": float(w @ (risk.capacity_bound != "")),
        "p50": risk.p50_best,
        "free_g": free_median,
        "free_pga_g": free_median * soil_factor(site, free_median),
        "fail": fail,
        "ag2475_g": site.hazard(2475.0).ag_g,
    }


def report(label: str, towers: list[Tower], n: int, seed: int) -> None:
    """Print a population's numbers."""
    rows = [one_tower(t, n, seed) for t in towers]
    if not rows:
        print(f"{label}: none")
        return

    def q(key):
        x = np.array([r[key] for r in rows])
        return f"{np.quantile(x, 0.1):.3f} / {np.median(x):.3f} / {np.quantile(x, 0.9):.3f}"

    print(f"\n{label}: {len(rows)} towers, n {n}, seed {seed} (10 / 50 / 90 % over the towers)")
    print(f"  median capacity at the site, ag on rock [g]   {q('capacity_g')}")
    print(f"  share of its samples bounded by the table      {q('bounded')}")
    print(f"  ag at 2475 y on rock at the site [g]           {q('ag2475_g')}")
    print(f"  shaft, ceiling lifted: ag on rock [g]          {q('free_g')}")
    print(f"  shaft, ceiling lifted: ground PGA S ag [g]     {q('free_pga_g')}")
    print(f"  P in 50 years, best estimate                   {q('p50')}")
    for pga in GROUND_PGA_G:
        share = np.mean([r["fail"][pga] for r in rows])
        print(f"  expected share failing at ground PGA {pga:.2f} g: {share:.2f}")


def main(argv: list[str] | None = None) -> int:
    """Run the checks (module docstring)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--turris", type=Path, default=None)
    parser.add_argument("--n", type=int, default=DEFAULT_SAMPLES)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    report("twelve-tower example (L'Aquila, soil B)", read_inventory(EXAMPLE), args.n, args.seed)
    if args.turris is not None:
        towers = [geometry_only(t) for t in turris_towers(turris_rows(args.turris), "B")]
        (la0, la1), (lo0, lo1) = EMILIA
        emilia = [t for t in towers if la0 <= t.lat <= la1 and lo0 <= t.lon <= lo1]
        report("TURRIS, Emilia, each at its location (soil B)", emilia, args.n, args.seed)
        report("TURRIS, all Italian with a wall (soil B)", towers, args.n, args.seed)
    return 0


if __name__ == "__main__":
    sys.exit(main())
