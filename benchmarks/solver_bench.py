"""Compiled solver versus the solve_ivp oracle on the L'Aquila 2009 records.

Run from the repository root::

    python benchmarks/solver_bench.py [--data DIR] [--quick]

For every case (record component x tower, plus double-block cases) the script solves
the same input with the event-driven ``solve_ivp`` oracle (:mod:`rockscreen.solver.reference`) and
with the project's compiled solver, and prints theta_max from both, their relative
difference, the verdicts, the run times and the speed ratio. The summary line gives the
total-time speed ratio and whether the issue's targets hold: ratio >= 100x,
|d theta_max| <= 0.5 % whenever the tower does not overturn, same overturning verdict.

Not part of the test suite. Exit status: 0 when every target holds, 1 when the data are
missing, 2 when a target is missed.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from rockscreen.solver.constants import G
from rockscreen.solver.reference import reference_double_block, reference_rocking

DEFAULT_DATA = Path(__file__).resolve().parents[1] / ".." / "shared" / "data" / "laquila2009"
STATIONS = ("AQV", "AQG", "GSA", "AVZ")  # nearest to farthest
TOWERS = ((1.0, 8.0), (2.0, 8.0), (2.06, 5.8), (3.0, 6.0), (4.0, 6.0))  # full 2b x 2h [m]
# Seed paper (Di Gennaro et al. 2023): tower 339 kN on a 96,840.67 kN church, 2.06 m x 5.80 m.
SEED_TOWER = (2.06, 5.8)
TOWER_MASS = 339e3 / G
BUILDING_MASS = 96_840.67e3 / G
FRICTION_PAIRS = ((0.5, 0.4), (1.0, 0.7))  # (mu_s, mu_k): the first slides under AQV
SCALES = (5.0, 3.0, 2.0)  # factors applied to AQV.HNE (x5 topples the slender towers)
THETA_RTOL = 5e-3
SPEED_TARGET = 100.0
COMPILED_REPEATS = 3


@dataclass(frozen=True)
class Record:
    """One horizontal component with the station's vertical [m/s^2]."""

    name: str
    acc: np.ndarray
    acc_v: np.ndarray
    dt: float


@dataclass(frozen=True)
class Case:
    """One benchmark case: a record, a tower and optionally a building."""

    record: Record
    width: float
    height: float
    vertical: bool = False
    friction: tuple[float, float] | None = None

    @property
    def label(self) -> str:
        """Tower size, building friction and vertical motion in a few characters."""
        tower = f"{self.width:g}x{self.height:g}"
        if self.friction:
            tower += f" on building mu={self.friction[0]:g}/{self.friction[1]:g}"
        if self.vertical:
            tower += " +vertical"
        return tower


@dataclass
class Row:
    """The measured outcome of one case."""

    case: Case
    theta_oracle: float
    theta_compiled: float
    over_oracle: bool
    over_compiled: bool
    slip_oracle: float
    slip_compiled: float
    t_oracle: float
    t_compiled: float
    error: str = ""

    @property
    def rel_diff(self) -> float:
        """Relative difference of the compiled theta_max from the oracle's [-]."""
        if self.theta_oracle == 0.0:
            return 0.0 if self.theta_compiled == 0.0 else math.inf
        return abs(self.theta_compiled - self.theta_oracle) / self.theta_oracle

    @property
    def ok(self) -> bool:
        """Same verdict, and theta_max within tolerance unless the tower overturned."""
        if self.error or self.over_oracle != self.over_compiled:
            return False
        return self.over_oracle or self.rel_diff <= THETA_RTOL


def rectangle(width: float, height: float) -> tuple[float, float, float, float]:
    """Return (p [rad/s], alpha [rad], eta [-], R [m]) of a solid rectangle 2b x 2h."""
    radius = 0.5 * math.hypot(width, height)
    alpha = math.atan(width / height)
    return math.sqrt(3.0 * G / (4.0 * radius)), alpha, 1.0 - 1.5 * math.sin(alpha) ** 2, radius


def load_records(data_dir: Path, quick: bool) -> list[Record]:
    """Read the horizontals (and the vertical) of each station; values are m/s^2."""
    import obspy  # only the benchmark needs ObsPy; solver must not import it

    stations = ("AQV", "GSA") if quick else STATIONS
    channels = ("HNE",) if quick else ("HNE", "HNN")
    records = []
    for station in stations:
        vertical = obspy.read(str(data_dir / f"IT.{station}..HNZ.mseed"))[0]
        for channel in channels:
            trace = obspy.read(str(data_dir / f"IT.{station}..{channel}.mseed"))[0]
            if trace.stats.delta != vertical.stats.delta or trace.stats.npts != vertical.stats.npts:
                raise SystemExit(f"{station}: {channel} and HNZ differ in sampling or length")
            records.append(
                Record(
                    f"{station}.{channel}",
                    np.asarray(trace.data, dtype=float),
                    np.asarray(vertical.data, dtype=float),
                    float(trace.stats.delta),
                )
            )
    # Scaled copies of the strongest component make stocky towers rock and slender ones
    # overturn, so that the verdicts are compared too (PGA 0.66 g alone topples none).
    strongest = records[0]
    for factor in SCALES[:1] if quick else SCALES:
        records.append(
            Record(
                f"{strongest.name}x{factor:g}",
                factor * strongest.acc,
                factor * strongest.acc_v,
                strongest.dt,
            )
        )
    return records


def build_cases(records: list[Record], quick: bool) -> list[Case]:
    """Every record with every tower; the seed tower also with vertical motion and on a building."""
    towers = (TOWERS[0], TOWERS[2], TOWERS[4]) if quick else TOWERS
    cases = [Case(rec, w, h) for rec in records for (w, h) in towers]
    strong = [rec for rec in records if rec.name.startswith(("AQV.HNE", "AQG.HNE"))]
    # With the vertical component: unscaled and x2 only (x3 lifts the base off: g + av < 0).
    with_vertical = [rec for rec in strong if not rec.name.endswith(("x3", "x5"))]
    cases += [Case(rec, *SEED_TOWER, vertical=True) for rec in with_vertical]
    pairs = FRICTION_PAIRS[:1] if quick else FRICTION_PAIRS
    cases += [Case(rec, *SEED_TOWER, friction=pair) for rec in strong for pair in pairs]
    return cases


def solve_oracle(case: Case):
    p, alpha, eta, radius = rectangle(case.width, case.height)
    rec = case.record
    acc_v = rec.acc_v if case.vertical else None
    if case.friction:
        mu_s, mu_k = case.friction
        return reference_double_block(
            p, alpha, eta, radius, rec.acc, rec.dt, TOWER_MASS, BUILDING_MASS, mu_s, mu_k, acc_v
        )
    return reference_rocking(p, alpha, eta, rec.acc, rec.dt, acc_v=acc_v)


def solve_compiled(case: Case, options: dict):
    from rockscreen.solver import RockingBlock, solve_rocking

    block = RockingBlock.from_dimensions(case.width, case.height)
    rec = case.record
    acc_v = rec.acc_v if case.vertical else None
    if case.friction:
        from rockscreen.solver import solve_double_block

        mu_s, mu_k = case.friction
        return solve_double_block(
            block, rec.acc, rec.dt, tower_mass=TOWER_MASS, building_mass=BUILDING_MASS,
            mu_s=mu_s, mu_k=mu_k, acc_v=acc_v, **options,
        )  # fmt: skip
    return solve_rocking(block, rec.acc, rec.dt, acc_v=acc_v, **options)


def warm_up() -> float:
    """Call every compiled entry point once; return the time [s] (compile or cache load)."""
    from rockscreen.solver import RockingBlock, solve_double_block, solve_rocking, solve_sliding

    start = time.perf_counter()
    acc = 0.5 * G * np.sin(np.linspace(0.0, 2.0 * np.pi, 201))
    block = RockingBlock.from_dimensions(2.0, 6.0)
    solve_rocking(block, acc, 0.005)
    solve_rocking(block, acc, 0.005, acc_v=0.1 * acc)
    solve_rocking(block, acc, 0.005, linearized=True)
    solve_sliding(acc, 0.005, mu_s=0.3, mu_k=0.2)
    solve_double_block(block, acc, 0.005, tower_mass=1.0, building_mass=3.0, mu_s=0.3, mu_k=0.2)
    return time.perf_counter() - start


def check_parameters(case: Case, response) -> str:
    """Compare the compiled solver's p, alpha, eta with the oracle's own derivation."""
    p, alpha, eta, _ = rectangle(case.width, case.height)
    ours = {"p": p, "alpha": alpha, "eta": eta}
    bad = [
        f"{name} {getattr(response, name):.6g} vs {value:.6g}"
        for name, value in ours.items()
        if not math.isclose(getattr(response, name), value, rel_tol=1e-9)
    ]
    return "; ".join(bad)


def run_case(case: Case, options: dict) -> Row:
    start = time.perf_counter()
    ref = solve_oracle(case)
    t_oracle = time.perf_counter() - start
    error, res, t_compiled = "", None, math.nan
    try:
        times = []
        for _ in range(COMPILED_REPEATS):
            start = time.perf_counter()
            res = solve_compiled(case, options)
            times.append(time.perf_counter() - start)
        t_compiled = min(times)
        error = check_parameters(case, res)
    except Exception as exc:  # report and go on with the next case
        error = f"{type(exc).__name__}: {exc}"
    return Row(
        case,
        ref.theta_max,
        res.theta_max if res is not None else math.nan,
        ref.overturned,
        bool(res.overturned) if res is not None else False,
        ref.slip_max,
        res.slip_max if res is not None else math.nan,
        t_oracle,
        t_compiled,
        error,
    )


HEADER = (
    f"{'record':<9} {'tower':<30} {'th_max oracle':>13} {'th_max compiled':>15} "
    f"{'rel diff':>9} {'verdict o/c':>11} {'slip o/c [m]':>17} "
    f"{'t oracle':>9} {'t comp.':>9} {'ratio':>7}  ok"
)


def format_row(row: Row) -> str:
    verdict = f"{'OT' if row.over_oracle else 'ok'}/{'OT' if row.over_compiled else 'ok'}"
    slip = f"{row.slip_oracle:.4f}/{row.slip_compiled:.4f}" if row.case.friction else "-"
    ratio = row.t_oracle / row.t_compiled if row.t_compiled > 0 else math.nan
    line = (
        f"{row.case.record.name:<9} {row.case.label:<30} {row.theta_oracle:13.6e} "
        f"{row.theta_compiled:15.6e} {row.rel_diff:9.2e} {verdict:>11} {slip:>17} "
        f"{row.t_oracle:8.3f}s {row.t_compiled * 1e3:7.2f}ms {ratio:6.0f}x  "
        f"{'yes' if row.ok else 'NO'}"
    )
    return line + (f"  [{row.error}]" if row.error else "")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--data", type=Path, default=DEFAULT_DATA, help="folder with IT.<STA>..HN?.mseed"
    )
    parser.add_argument(
        "--quick",
        action="store_true",
        help="AQV and GSA east-west and AQV x3 only, 3 towers, 1 building",
    )
    parser.add_argument(
        "--rest-tolerance", type=float, help="passed to the compiled solver (Zeno cut-off)"
    )
    parser.add_argument(
        "--max-substep", type=float, help="passed to the compiled solver (RK4 sub-step [s])"
    )
    args = parser.parse_args(argv)
    options = {
        name: value
        for name, value in (
            ("rest_tolerance", args.rest_tolerance),
            ("max_substep", args.max_substep),
        )
        if value is not None
    }
    data_dir = args.data.resolve()
    if not (data_dir / "IT.AQV..HNE.mseed").is_file():
        print(
            f"error: L'Aquila records not found in {data_dir} (expected IT.AQV..HNE.mseed ...); "
            "pass --data DIR",
            file=sys.stderr,
        )
        return 1

    records = load_records(data_dir, args.quick)
    cases = build_cases(records, args.quick)
    print(f"rockscreen solver benchmark: {len(cases)} cases, records from {data_dir}")
    print(
        "full records, no trimming (AQV.HNExK: that record times K); oracle = solve_ivp "
        "DOP853 per sample interval, rtol 1e-10, atol 1e-12;"
    )
    print(
        f"compiled time = best of {COMPILED_REPEATS} runs with history; "
        f"eta = 1 - 1.5 sin^2(alpha); compiled options: {options or 'defaults'}"
    )
    print(f"first call of the compiled solver (compile or cache load): {warm_up():.2f} s")
    print(HEADER)
    rows = []
    for case in cases:
        rows.append(run_case(case, options))
        print(format_row(rows[-1]), flush=True)

    total_oracle = sum(row.t_oracle for row in rows)
    total_compiled = sum(row.t_compiled for row in rows if math.isfinite(row.t_compiled))
    ratio = total_oracle / total_compiled if total_compiled > 0 else math.nan
    worst = max((row.rel_diff for row in rows if not row.over_oracle), default=0.0)
    verdicts = sum(row.over_oracle == row.over_compiled and not row.error for row in rows)
    speed_ok = ratio >= SPEED_TARGET
    all_ok = speed_ok and all(row.ok for row in rows)
    print(
        f"SUMMARY: total oracle {total_oracle:.2f} s, compiled {total_compiled:.3f} s, "
        f"speed ratio {ratio:.0f}x "
        f"(target >= {SPEED_TARGET:.0f}x: {'met' if speed_ok else 'MISSED'}); "
        f"worst |d theta_max| {worst:.2e} (target <= {THETA_RTOL:.1e}); "
        f"same verdict {verdicts}/{len(rows)}; targets {'HOLD' if all_ok else 'NOT MET'}"
    )
    return 0 if all_ok else 2


if __name__ == "__main__":
    sys.exit(main())
