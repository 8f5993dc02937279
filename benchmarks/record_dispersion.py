"""Record-to-record dispersion of a rigid block: real L'Aquila records against the suite.

::

    python benchmarks/record_dispersion.py [--data ../shared/data] [--seeds 0,1,2] [--pool 150]

The reference block of issue 30 (0.6 m x 4 m, ground model, ``engine.cases.screen_case``
with the real solver, 10 s of free motion) is pushed to its first overturning by each
horizontal component, scaled up in 15 % steps from the uplift PGA (g tan alpha) to a cap
of 40 m/s² (censored above). Two lognormal betas of the capacities (sample standard
deviation of the logs; the censored maximum-likelihood one when a record never topples):

- **PGA-normalised**: each component normalised to PGA 1 (the capacity is the PGA of the
  first overturning);
- **ag-scaled**: each component first scaled to the code spectrum of L'Aquila (13.3995 E,
  42.3498 N, TR 475 y) of its soil -- the suite's records by their own set's factor, a real
  record by its least-squares factor (in logs, the set's 0.15-2 s) to the target of its
  station's soil (B or C by V_s30, :data:`REAL_SOIL`) -- and the capacity is the multiple
  of that scaling at the first overturning, i.e. in ag (so the spread of the records' PGA
  at a given spectrum counts).

It prints, per group of records, n, both betas and what a rocking block sees of each
record: PGV/PGA (velocity baseline-corrected by a linear trend), D5-95 (Arias), the mean
period T_m (Rathje et al. 1998, Fourier amplitudes 0.25-20 Hz), the share of pulses (suite
and pool records) and the mean of ln(capacity / uplift PGA). Groups: the 22 real
horizontals (both folders), the issue's 10 (the four near stations and BOJ), the real near
firm-ground ones (AQV, AQG, GSA: R <= 18 km, Vs30 474-685 m/s); per seed, the suite's
L'Aquila sets of soils B and C at TR 475 y, both horizontals (like for like: the real
stations are on soils B and C), and the seeds pooled; the sets the acceptance used before
(soil A, TR 475 and 975 y, ``x`` only); ``--pool`` random records of the soil-A pool and
those of them within 20 km. Real records are read from ``--data`` (``../shared/data``;
exit 1 when absent). Takes about 3-5 minutes (the pools of other seeds are generated once).
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np
from obspy import Stream
from scipy import optimize, stats

from rockscreen.pipeline.engine import registry
from rockscreen.pipeline.engine.cases import BlockCache, screen_case
from rockscreen.pipeline.hazard.matching import batch_spectrum
from rockscreen.pipeline.hazard.record_pool import record_pool
from rockscreen.pipeline.hazard.suite import site_record_set
from rockscreen.pipeline.records.grouping import group_records
from rockscreen.pipeline.records.io import read_stream
from rockscreen.solver.constants import G
from rockscreen.stations.inventory import Tower

#: Reference block, site, IDA step, cap [m/s²], free motion [s].
TOWER = Tower(id="REF", width_m=0.6, height_m=4.0)
LAQUILA = (13.3995, 42.3498)
STEP, PGA_CAP, FREE_S = 1.15, 40.0, 10.0
#: NTC 2018 soil class of each real station by its V_s30 (``../shared/data/SOURCES.md``;
#: Tab. 3.2.II: B 360-800 m/s, C 180-360 m/s).
REAL_SOIL = {
    **dict.fromkeys(("AQV", "AQG", "GSA", "CSS", "STL"), "B"),
    **dict.fromkeys(("AVZ", "BOJ", "SNS", "CTL", "BBN", "FOR"), "C"),
}
NEAR_FIRM = ("AQV", "AQG", "GSA")
ISSUE_TEN = ("AQV", "AQG", "GSA", "AVZ", "BOJ")


def capacity_pga(acc: np.ndarray, dt: float, block) -> tuple[float, bool]:
    """Return (PGA of first overturning [m/s²], censored) in 15 % steps from the uplift PGA."""
    model = registry.get("ground")
    unit = np.asarray(acc, float) / np.max(np.abs(acc))
    pga = G * math.tan(block.alpha)
    while pga <= PGA_CAP:
        if screen_case(model, TOWER, block, unit * pga, None, dt, FREE_S).overturned:
            return pga, False
        pga *= STEP
    return PGA_CAP, True


def lognormal_beta(values, censored) -> float:
    """Sample std of the logs, or the censored maximum-likelihood beta."""
    x, c = np.log(values), np.asarray(censored, bool)
    if not c.any():
        return float(np.std(x, ddof=1))

    def nll(p):
        b = math.exp(p[1])
        return -(stats.norm.logpdf(x[~c], p[0], b).sum() + stats.norm.logsf(x[c], p[0], b).sum())

    fit = optimize.minimize(nll, [x.mean(), math.log(x.std() + 1e-3)], method="Nelder-Mead")
    return math.exp(fit.x[1])


def features(acc: np.ndarray, dt: float) -> dict:
    """PGV/PGA [s], D5-95 [s] and mean period T_m [s] of one component."""
    acc = np.asarray(acc, float)
    velocity = np.cumsum(acc) * dt
    velocity -= np.linspace(0.0, velocity[-1], len(velocity))
    energy = np.cumsum(acc**2)
    energy /= energy[-1]
    t5, t95 = np.searchsorted(energy, [0.05, 0.95]) * dt
    f = np.fft.rfftfreq(len(acc), dt)
    amplitude = np.abs(np.fft.rfft(acc))
    band = (f >= 0.25) & (f <= 20.0)
    tm = np.sum(amplitude[band] ** 2 / f[band]) / np.sum(amplitude[band] ** 2)
    return {"pgv_pga": np.max(np.abs(velocity)) / np.max(np.abs(acc)), "d595": t95 - t5, "tm": tm}


def trimmed(acc: np.ndarray, dt: float, margin_s: float = 2.0) -> np.ndarray:
    """Return the record between 0.1 % and 99.9 % of its Arias intensity, plus a margin."""
    energy = np.cumsum(np.asarray(acc, float) ** 2)
    energy /= energy[-1]
    pad = round(margin_s / dt)
    start = max(0, int(np.searchsorted(energy, 0.001)) - pad)
    return acc[start : int(np.searchsorted(energy, 0.999)) + pad]


def own_factor(acc: np.ndarray, dt: float, chosen) -> float:
    """Least-squares factor (in logs) of a component's spectrum to a record set's target."""
    sa = batch_spectrum(np.asarray(acc, float)[None, :], dt, chosen.periods_s)[0] / G
    return float(np.exp(np.mean(np.log(chosen.target_sa_g / sa))))


def measure(name: str, items: list, block) -> None:
    """Print one group: ``items`` are (acceleration [m/s²], dt [s], factor, pulse or None)."""
    rows = []
    for acc, dt, factor, pulse in items:
        cap, censored = capacity_pga(acc, dt, block)
        # the multiple of the record's scaling to its set's spectrum at first overturning
        ag_cap = cap / (factor * np.max(np.abs(acc)))
        rows.append((cap, ag_cap, censored, pulse, features(acc, dt)))
    cap, ag_cap, cens = (np.array([r[i] for r in rows]) for i in range(3))
    pulses = [r[3] for r in rows if r[3] is not None]
    f = {k: np.array([r[4][k] for r in rows]) for k in ("pgv_pga", "d595", "tm")}
    uplift = G * math.tan(block.alpha)
    pulse = f"{np.mean(pulses):.2f}" if pulses else "-"
    print(
        f"{name:<46} n={len(rows):>3}  beta PGA {lognormal_beta(cap, cens):.2f}  "
        f"ag {lognormal_beta(ag_cap, cens):.2f}  PGV/PGA {np.median(f['pgv_pga']):.3f} s "
        f"(>0.14 s: {np.mean(f['pgv_pga'] > 0.14):.2f})  D5-95 {np.median(f['d595']):.1f} s  "
        f"T_m {np.median(f['tm']):.2f} s  pulse {pulse}  "
        f"ln(cap/uplift) {np.mean(np.log(cap / uplift)):.2f}",
        flush=True,
    )


def real_components(data: Path) -> list[tuple[str, np.ndarray, float]]:
    """(station, horizontal [m/s²], dt [s]) of both L'Aquila folders, trimmed."""
    out = []
    for folder in (data / "laquila2009", data / "laquila2009_regional"):
        stream = Stream()
        for path in sorted(folder.glob("*.mseed")):
            stream += read_stream(path, stations=folder / "stations.xml")
        for record in group_records(stream):
            station = record.station.split(".")[-1]
            out += [(station, trimmed(h, record.dt), record.dt) for h in (record.h1, record.h2)]
    return out


def suite_items(chosen, components) -> list:
    """(component, dt, factor, pulse) of a record set's records."""
    return [
        (np.trim_zeros(getattr(r, c), "b"), r.dt_s, float(f), "no pulse" not in r.source)
        for r, f in zip(chosen.records, chosen.scale_factors, strict=True)
        for c in components
    ]


def main(argv: list[str] | None = None) -> int:
    """Run the measurement and print one line per group."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    default_data = Path(__file__).resolve().parents[2] / "shared" / "data"
    parser.add_argument("--data", type=Path, default=default_data)
    parser.add_argument("--seeds", default="0,1,2")
    parser.add_argument("--pool", type=int, default=150)
    args = parser.parse_args(argv)
    if not (args.data / "laquila2009" / "stations.xml").is_file():
        print(f"record_dispersion: no L'Aquila records under {args.data}", file=sys.stderr)
        return 1
    block = BlockCache(TOWER)(TOWER.width_m)
    seeds = [int(s) for s in args.seeds.split(",")]
    horizontals = ("acc_x_m_s2", "acc_y_m_s2")
    sets = {
        (seed, soil): site_record_set(*LAQUILA, 475.0, soil, "T1", kind="stochastic", seed=seed)
        for seed in seeds
        for soil in "BC"
    }
    real = [
        (station, acc, dt, own_factor(acc, dt, sets[seeds[0], REAL_SOIL[station]]))
        for station, acc, dt in real_components(args.data)
    ]
    groups = (
        ("real, 11 stations", REAL_SOIL),
        ("real, issue's 10 (4 near + BOJ)", ISSUE_TEN),
        ("real, near firm (AQV AQG GSA)", NEAR_FIRM),
    )
    for label, keep in groups:
        measure(label, [(a, dt, f, None) for s, a, dt, f in real if s in keep], block)
    pooled = []
    for seed in seeds:
        items = [it for soil in "BC" for it in suite_items(sets[seed, soil], horizontals)]
        pooled += items
        measure(f"suite seed {seed}, soils B+C, 475 y, x+y", items, block)
    measure(f"suite seeds {args.seeds} pooled", pooled, block)
    for seed in seeds:
        items = []
        for tr in (475.0, 975.0):
            chosen = site_record_set(*LAQUILA, tr, "A", "T1", kind="stochastic", seed=seed)
            items += suite_items(chosen, ("acc_x_m_s2",))
        measure(f"before: suite seed {seed}, soil A, 475+975 y, x", items, block)
    pool = record_pool("A", 0)
    reference = sets[seeds[0], "B"]
    chosen = np.random.default_rng(123).choice(len(pool.offsets) - 1, args.pool, replace=False)
    items = []
    for i in chosen:
        x = pool.record(int(i))[0]
        items.append((x, 0.01, own_factor(x, 0.01, reference), not math.isnan(pool.pulse[i, 0])))
    measure(f"pool A seed 0, {args.pool} random records", items, block)
    near = [it for it, i in zip(items, chosen, strict=True) if pool.scenario[i, 1] <= 20.0]
    measure("  of which R <= 20 km", near, block)
    return 0


if __name__ == "__main__":
    sys.exit(main())
