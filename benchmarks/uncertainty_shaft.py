"""Measure the best-estimate shaft capacity against the code's LV1 (docs/uncertainty.md).

::

    python benchmarks/uncertainty_shaft.py [--turris /path/to/turris.csv] [--n 200] [--seed 0]

1. The twelve towers of ``examples/tower_population/towers_shaft_lc1.csv``: the code's LV1
   (``assess``'s ``lv1_capacity_ag_g`` and ``lv1_compression_ratio``, computed by
   ``tower_lv1_checks.lv1_columns`` at the row's knowledge level), the deterministic best
   estimate with the row's walls and masonry type (the type's mean f_m, the middle of Table
   C8.5.I's range; no gamma_M, no F_C), and the geometry-only best estimate (the row
   stripped to id, lat, lon, width, depth, height; every other input from the priors):
   median and 90 % interval of the capacity over ``--n`` samples, with the time per tower.
2. The stability of the 90 % interval across seeds (five seeds, one geometry-only tower).
3. With ``--turris``: the Italian TURRIS towers with a base wall thickness (the thicker
   wall at the base, the thinner at the top), as solid brick and as rubble:
   ``sigma_0 / (0.85 f)`` at the base at the code's LC1 (``f_d = f_min / (2 x 1.35)``) and
   at the mean strength with no factor, counted at or above 1 and their medians (issue 31).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

from rockscreen.pipeline.risk.assess.sites import tower_sites
from rockscreen.pipeline.risk.checks.confidence import (
    MASONRY_TYPES,
    confidence_factor,
    masonry_strength,
)
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.checks.tower_lv1 import tower_period_guidelines
from rockscreen.pipeline.risk.checks.tower_lv1_checks import lv1_columns
from rockscreen.pipeline.risk.uncertainty import TowerPriors, best_estimate_lv1, shaft_capacity
from rockscreen.stations.inventory import Tower, read_inventory

ROOT = Path(__file__).resolve().parent.parent
EXAMPLE = ROOT / "examples" / "tower_population" / "towers_shaft_lc1.csv"
GEOMETRY = ("id", "lat", "lon", "width_m", "depth_m", "height_m", "soil_class")


def mean_strength(masonry_type: str) -> float:
    """Return the middle of Table C8.5.I's range of f [Pa] (LC2's value)."""
    return masonry_strength(masonry_type, "LC2")


def twelve_towers(n: int, seed: int) -> None:
    """Print part 1 (module docstring)."""
    towers = read_inventory(EXAMPLE)
    print(f"1. {EXAMPLE.relative_to(ROOT)}: code's LV1 vs best estimate (n {n}, seed {seed})")
    print(
        "id   type          H m  code: ratio  ag g  | best, given type: ratio  ag g  | "
        "geometry only: ag median [5 %, 95 %]  ratio median  ms"
    )
    for site in tower_sites(towers):
        t = site.tower
        level = t.knowledge_level
        code, _, _ = lv1_columns(site, confidence_factor(level), level)
        cond = SiteConditions.of(site)
        best = best_estimate_lv1(
            t,
            cond,
            wall_m=t.wall_thickness_m,
            wall_top_m=t.wall_thickness_top_m or t.wall_thickness_m,
            unit_weight_n_m3=MASONRY_TYPES[t.masonry_type].unit_weight_n_m3,
            fm_pa=mean_strength(t.masonry_type),
            period_s=t.shaft_period_s or tower_period_guidelines(t.height_m),
        )
        bare = Tower(**{k: getattr(t, k) for k in GEOMETRY})
        start = time.perf_counter()
        samples = TowerPriors.from_tower(bare).sample(np.random.default_rng(seed), n)
        # the table's bounds, as measured in docs/uncertainty.md (not continued beyond it)
        cap = shaft_capacity(bare, cond, samples, extrapolate=False)
        ms = 1e3 * (time.perf_counter() - start)
        lo, hi = cap.interval_g(0.9)
        print(
            f"{t.id}  {t.masonry_type:13s} {t.height_m:4.0f}  "
            f"{code['lv1_compression_ratio']:5.2f}  {code['lv1_capacity_ag_g']:6.3f}"
            f"{'*' if code['lv1_bound'] else ' '}| "
            f"{best.critical.compression_ratio:5.2f}  {best.capacity.ag_g:6.3f}"
            f"{'*' if best.capacity.bound else ' '}| "
            f"{cap.median_g:6.3f} [{lo:5.3f}, {hi:5.3f}]  "
            f"{np.median(cap.compression_ratio):5.2f}  {ms:5.0f}"
        )
    print("(* a bound: the check holds at 2475 y or fails at 30 y)")


def seeds(n: int) -> None:
    """Print part 2 (module docstring)."""
    t = read_inventory(EXAMPLE)[5]
    bare = Tower(**{k: getattr(t, k) for k in GEOMETRY})
    cond = SiteConditions.of(tower_sites([bare])[0])
    priors = TowerPriors.from_tower(bare)
    print(f"2. {t.id} geometry only, n {n}: 90 % interval of the capacity across seeds")
    rows = []
    for seed in range(5):
        cap = shaft_capacity(
            bare, cond, priors.sample(np.random.default_rng(seed), n), extrapolate=False
        )
        rows.append((cap.median_g, *cap.interval_g(0.9)))
        print(f"   seed {seed}: median {rows[-1][0]:.3f} g, [{rows[-1][1]:.3f}, {rows[-1][2]:.3f}]")
    a = np.array(rows)
    spread = (a.max(axis=0) - a.min(axis=0)) / np.median(a, axis=0)
    print(
        f"   range across seeds / median: median {spread[0]:.1%}, 5 % end {spread[1]:.1%}, "
        f"95 % end {spread[2]:.1%}"
    )


def turris(path: Path) -> None:
    """Print part 3 (module docstring)."""
    sys.path.insert(0, str(Path(__file__).resolve().parent))
    from turris_priors import italian_towers  # noqa: PLC0415 (a sibling script)

    rows = [
        t
        for t in italian_towers(path)
        if t["max_wall"] > 0 and t["H"] > 0 and t["width"] > 0 and t["length"] > 0
    ]
    print(f"3. TURRIS: {len(rows)} unique Italian towers with a base wall thickness")
    for kind in ("solid_brick", "rubble"):
        row = MASONRY_TYPES[kind]
        code_fd = masonry_strength(kind, "LC1")
        out = {"code LC1": [], "mean, no factor": [], "critical, mean": []}
        for k, t in enumerate(rows):
            tower = Tower(
                id=f"TU{k}",
                width_m=t["width"],
                depth_m=t["length"],
                height_m=t["H"],
                lat=t["lat"],
                lon=t["lon"],
            )
            top = t["min_wall"] if t["min_wall"] > 0 else t["max_wall"]
            site = SiteConditions.of(tower_sites([tower])[0])
            args = dict(
                wall_m=t["max_wall"],
                wall_top_m=top,
                unit_weight_n_m3=row.unit_weight_n_m3,
                period_s=tower_period_guidelines(t["H"]),
            )
            code = best_estimate_lv1(
                tower, site, fm_pa=code_fd, gamma_m=2.0, fc=confidence_factor("LC1"), **args
            )
            best = best_estimate_lv1(tower, site, fm_pa=mean_strength(kind), **args)
            out["code LC1"].append(code.sections[0].compression_ratio)
            out["mean, no factor"].append(best.sections[0].compression_ratio)
            out["critical, mean"].append(best.critical.compression_ratio)
        for name, values in out.items():
            v = np.array(values)
            where = "critical section" if name.startswith("critical") else "base"
            print(
                f"   {kind:11s} {name:16s} ({where}): sigma_0/(0.85 f) >= 1 for "
                f"{int(np.sum(v >= 1.0))} of {v.size}, median {np.median(v):.2f}, "
                f"max {v.max():.2f}"
            )


def main(argv: list[str] | None = None) -> int:
    """Run the three parts (module docstring)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--turris", type=Path, help="CSV export of TURRIS.xlsx")
    parser.add_argument("--n", type=int, default=200, help="samples per tower (200)")
    parser.add_argument("--seed", type=int, default=0, help="random seed (0)")
    args = parser.parse_args(argv)
    twelve_towers(args.n, args.seed)
    seeds(args.n)
    if args.turris is not None:
        if not args.turris.is_file():
            print(f"uncertainty_shaft: no file {args.turris}", file=sys.stderr)
            return 1
        turris(args.turris)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
