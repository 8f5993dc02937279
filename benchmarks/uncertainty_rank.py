"""The risk with its uncertainty, the rank and survey_first of the twelve towers.

docs/uncertainty.md.

::

    python benchmarks/uncertainty_rank.py [--n 1000] [--seed 0] [--seeds 5] [--top 3]
                                          [--rocking rocking.csv] [--inventory PATH]
                                          [--per-sample]

For every tower of ``examples/tower_population/towers_geometry.csv`` (geometry only: id,
lat, lon, width, depth, height, soil class; every other input from the default priors of
``risk.uncertainty.priors``): ``--n`` samples, the shaft's best-estimate capacity, the
kinematic capacities at F_C = 1, with ``--rocking`` the IDA's rocking median per tower (a
CSV ``id,rocking_median_g[,rocking_bound]``: the same for every sample), then the risk
(P in 50 years: best estimate, 90 % interval, mean; lambda; the governing mechanism and
its share), the rank and its band, ``survey_first`` with its index and expected narrowing,
and the time per tower. Then the best estimate over ``--seeds`` seeds (its range against
its median: the seed stability; the range of each tower's rank over the seeds), and which
survey changes the top ``--top`` list most.
Values flagged as bounds print with ``<=`` / ``>=``. ``--per-sample``: the shaft's sections
per sample (``shaft_capacity(batch=False)``, the reference) instead of all at once: the
speed before and after the vectorisation, same results.
"""

from __future__ import annotations

import argparse
import csv
import sys
import time
from pathlib import Path

import numpy as np

from rockscreen.pipeline.risk.assess.sites import tower_sites
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.uncertainty import TowerPriors, shaft_capacity
from rockscreen.pipeline.risk.uncertainty.kinematic import MechanismCapacity, kinematic_capacities
from rockscreen.pipeline.risk.uncertainty.rank import rank_towers, risk_rank
from rockscreen.pipeline.risk.uncertainty.risk import (
    DEFAULT_SAMPLES,
    site_hazard_curve,
    stratum_weights,
    tower_risk,
)
from rockscreen.pipeline.risk.uncertainty.sensitivity import sensitivity, top_n_changes
from rockscreen.stations.inventory import read_inventory

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "tower_population" / "towers_geometry.csv"
_MARK = {"": "  ", "at_most": "<=", "at_least": ">=", "both": "~?"}


def read_rocking(path: str | None) -> dict[str, tuple[float, str]]:
    """Return ``id -> (rocking median [g], bound)`` of a CSV, or an empty dict."""
    if not path:
        return {}
    with open(path, newline="") as fh:
        return {
            r["id"]: (float(r["rocking_median_g"]), r.get("rocking_bound", "") or "")
            for r in csv.DictReader(fh)
        }


def assess_tower(site, n: int, seed: int, rocking: dict, batch: bool = True) -> tuple:
    """Return (risk, samples, sensitivity, seconds) of one tower."""
    tower = site.tower
    start = time.perf_counter()
    cond = SiteConditions.of(site)
    priors = TowerPriors.from_tower(tower)
    samples = priors.sample(np.random.default_rng(seed), n)
    shaft = shaft_capacity(tower, cond, samples, batch=batch)
    mechanisms = [MechanismCapacity("shaft", shaft.ag_g, shaft.bound)]
    kinematic, _ = kinematic_capacities(tower, cond, samples)
    mechanisms += kinematic
    if tower.id in rocking:
        median, bound = rocking[tower.id]
        mechanisms.append(MechanismCapacity("rocking", np.full(n, median), bound))
    weights = stratum_weights(samples, priors)
    risk = tower_risk(mechanisms, site_hazard_curve(cond), weights=weights)
    sens = sensitivity(risk.probability, samples)
    return risk, samples, sens, time.perf_counter() - start


def main(argv: list[str] | None = None) -> int:
    """Run the benchmark (module docstring)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--inventory", default=str(EXAMPLE))
    parser.add_argument("--n", type=int, default=DEFAULT_SAMPLES)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--seeds", type=int, default=5)
    parser.add_argument("--top", type=int, default=3)
    parser.add_argument("--rocking", default=None)
    parser.add_argument("--per-sample", action="store_true", help="shaft sections per sample")
    args = parser.parse_args(argv)
    sites = tower_sites(read_inventory(args.inventory))
    rocking = read_rocking(args.rocking)
    print(f"{args.inventory}: n {args.n}, seed {args.seed}, {len(sites)} towers")
    if not rocking:
        print("rocking: not given (--rocking): the shaft and the kinematic mechanisms only")
    batch = not args.per_sample
    rows = [assess_tower(s, args.n, args.seed, rocking, batch) for s in sites]
    ids = [s.tower.id for s in sites]
    risks = [r[0] for r in rows]
    ranked = rank_towers(
        ids,
        [r.p50_best for r in risks],
        [r.p50_lo90 for r in risks],
        [r.p50_hi90 for r in risks],
    )
    print(
        "id   H m   P50 best   [5 %, 95 %]              mean      lambda best 1/y  "
        "governs (share)       rank band      survey_first (S1, narrowing)   ms"
    )
    for s, (risk, _, sens, sec), rk in zip(sites, rows, ranked, strict=True):
        best = f"{_MARK[risk.p50_best_bound]}{risk.p50_best:.4f}"
        lo = f"{_MARK[risk.p50_lo90_bound]}{risk.p50_lo90:.4f}"
        hi = f"{_MARK[risk.p50_hi90_bound]}{risk.p50_hi90:.4f}"
        mean = f"{_MARK[risk.p50_mean_bound]}{risk.p50_mean:.4f}"
        gov = f"{risk.governing_mechanism} ({risk.governing_share:.2f})"
        band = rk.band + ("?" if rk.band_uncertain else "")
        index, narrow = sens.survey_first_index, sens.survey_first_narrowing
        sf = f"{sens.survey_first} ({index:.2f}, {narrow:.2f})"
        print(
            f"{s.tower.id:4s} {s.tower.height_m:4.0f} {best} [{lo}, {hi}] {mean} "
            f"{risk.rate_best_per_y:.2e}         {gov:21s} {rk.rank:4d} {band:9s} {sf:30s} "
            f"{1e3 * sec:5.0f}"
        )
    print(
        f"time per tower: median {1e3 * np.median([r[3] for r in rows]):.0f} ms "
        f"(max {1e3 * max(r[3] for r in rows):.0f} ms) at n {args.n}"
    )
    print(f"\nseed stability: P50 best over seeds {args.seed}..{args.seed + args.seeds - 1}")
    worst = 0.0
    # seeds x towers: the best estimate and the upper end (the ranks of each seed)
    best = np.empty((args.seeds, len(sites)))
    upper = np.empty_like(best)
    for j, s in enumerate(sites):
        for k in range(args.seeds):
            risk = (
                rows[j][0] if k == 0 else assess_tower(s, args.n, args.seed + k, rocking, batch)[0]
            )
            best[k, j], upper[k, j] = risk.p50_best, risk.p50_hi90
    ranks = np.array([risk_rank(best[k], upper[k]) for k in range(args.seeds)])
    for j, s in enumerate(sites):
        values = best[:, j]
        med = float(np.median(values))
        spread = float(np.max(np.abs(values / med - 1.0)))
        worst = max(worst, spread)
        print(
            f"{s.tower.id:4s} median {med:.4f}  min {values.min():.4f}  max {values.max():.4f}  "
            f"largest deviation from the median {100 * spread:.1f} %  "
            f"rank {ranks[:, j].min()}-{ranks[:, j].max()}"
        )
    print(f"largest deviation over the towers: {100 * worst:.1f} %")
    changes = top_n_changes(
        ids,
        [r.p50_best for r in risks],
        [r.probability for r in risks],
        [r[1] for r in rows],
        [r[2].survey_first for r in rows],
        args.top,
        weights=[r.weights for r in risks],
    )
    print(f"\ntop {args.top}: which survey changes the list most")
    for c in changes:
        if c.probability > 0.0:
            where = "in" if c.in_top else "out"
            print(
                f"{c.tower_id:4s} ({where:3s}) measure {c.input:17s} P(crosses) {c.probability:.2f}"
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
