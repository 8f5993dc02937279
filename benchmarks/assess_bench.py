"""Benchmark of ``rockscreen assess``: N towers x 9 stripes x 7 records x 2 components.

Not part of the test suite. Towers: slender blocks (alpha 0.08-0.30 rad, R 1-6 m) spread
over ``--sites`` sites of the NTC grid; records: ``--suite synthetic`` (the embedded
spectrum-matched suite, about 9 s per site and return period to generate) or
``--suite stochastic`` (a generated suite of 20 stochastic records given as a user suite:
selection only, the cost of a user suite). Prints the wall time of the whole assessment,
the solver calls and solves per second. Other users of the machine share the CPU: say so
when quoting figures.

    python benchmarks/assess_bench.py --towers 1000 --sites 2 --jobs 2 --suite stochastic
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

SITES = [(41.04, 14.42), (38.10, 15.65), (42.35, 13.40), (43.77, 11.25), (40.85, 14.27)]


def _suite(n: int = 20):
    from rockscreen.pipeline.hazard.selection import SuiteRecord
    from rockscreen.pipeline.motion.synthetic import stochastic_accelerogram

    out = []
    for i in range(n):
        rng = np.random.default_rng(i)
        acc = [
            stochastic_accelerogram(
                rng,
                n_samples=2000,
                dt=0.01,
                pga=2.0,
                ground_frequency=1.5 + 0.2 * i,
                ground_damping=0.6,
                envelope_duration=6.0 + 0.5 * i,
                onset=1.0,
            )
            for _ in range(3)
        ]
        out.append(SuiteRecord(f"B-{i:02d}", acc[0], acc[1], 0.5 * acc[2], 0.01, "benchmark"))
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--towers", type=int, default=1000)
    parser.add_argument("--sites", type=int, default=2)
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--suite", choices=("synthetic", "stochastic"), default="stochastic")
    args = parser.parse_args()

    from rockscreen.pipeline.execution.choose import open_executor
    from rockscreen.pipeline.risk.assess import AssessOptions, run_assess
    from rockscreen.stations.inventory import Tower

    rng = np.random.default_rng(0)
    towers = []
    for i in range(args.towers):
        alpha, radius = rng.uniform(0.08, 0.30), rng.uniform(1.0, 6.0)
        lat, lon = SITES[i % args.sites]
        towers.append(
            Tower(
                id=f"B{i:04d}",
                width_m=2 * radius * math.sin(alpha),
                height_m=2 * radius * math.cos(alpha),
                lat=lat,
                lon=lon,
            )
        )
    suite = _suite() if args.suite == "stochastic" else None
    start = time.perf_counter()
    executor, jobs = open_executor(jobs=args.jobs, notify=print)
    result = run_assess(
        towers,
        AssessOptions(),
        executor,
        suite=suite,
        jobs=jobs,
        progress=lambda text: print(f"  {text}", flush=True),
    )
    elapsed = time.perf_counter() - start
    cases = len(result.outcomes)
    fitted = sum(1 for r in result.summary if r["collapse_bound"] == "")
    print(f"towers {args.towers}, sites {result.n_sites}, jobs {args.jobs}, suite {args.suite}")
    ida = sum(int(r.get("ida_n_solves", 0) or 0) for r in result.summary)
    stripe_solves = result.n_solves - ida
    print(
        f"stripe cases {cases} (record x component x model): {stripe_solves} solved, "
        f"{cases - stripe_solves} motionless skipped; IDA solves {ida} "
        f"({ida / max(len(result.summary), 1):.0f} per tower); solver calls {result.n_solves} "
        f"({result.n_solves / max(len(result.summary), 1):.0f} per tower)"
    )
    print(
        f"wall {elapsed:.1f} s, {result.n_solves / elapsed:.0f} solves/s, "
        f"{cases / elapsed:.0f} cases/s; fitted fragilities {fitted}/{args.towers}"
    )


if __name__ == "__main__":
    main()
