"""Snapshot and compare the verdicts of ``assess`` runs (issue 30: the adaptive IDA).

Not part of the test suite. ``snapshot`` assesses the twelve-tower example
(``examples/tower_population/towers_geometry.csv`` and ``towers_shaft_lc1.csv``, the
embedded suite, seed 0) and ``--bench N`` towers of ``benchmarks/assess_bench.py`` at their
own sites (``--sites per-tower``), and writes every tower's verdict (risk class, governing
check, I_S, the collapse and SLV fit medians and betas, the annual rate, solves) and its
``/ida`` rows to a JSON file. ``compare`` reads two snapshots and prints, per verdict, how
many towers differ and by how much, and the solves per tower of each.

    python benchmarks/ida_verdicts.py snapshot before.json --bench 40
    python benchmarks/ida_verdicts.py snapshot after.json --bench 40
    python benchmarks/ida_verdicts.py compare before.json after.json
"""

from __future__ import annotations

import argparse
import json
import math
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import h5py
import numpy as np

HERE = Path(__file__).resolve().parent
EXAMPLE = HERE.parent / "examples" / "tower_population"
#: Summary columns compared (text exactly, numbers to a relative tolerance).
TEXT_KEYS = ("risk_class", "governing", "governing_check", "governing_bound")
NUMBER_KEYS = (
    "safety_index",
    "governing_safety_index",
    "collapse_median_g",
    "collapse_beta",
    "slv_median_g",
    "slv_beta",
    "annual_rate_overturning_per_y",
    "capacity_pga_g",
    "stripe_median_g",
    "stripe_beta",
)


def read_table(path: Path, name: str) -> list[dict]:
    """Return the rows of one table of an assess archive."""
    with h5py.File(path, "r") as f:
        group = f[name]
        columns = json.loads(group.attrs["columns"])
        data = {}
        for c in columns:
            values = group[c][()]
            if values.dtype.kind in "OS":
                values = [v.decode() if isinstance(v, bytes) else str(v) for v in values]
            else:
                values = values.tolist()
            data[c] = values
    n = len(next(iter(data.values()))) if data else 0
    return [{c: data[c][i] for c in columns} for i in range(n)]


def fit_columns(row: dict) -> dict:
    """Return the fit columns of a summary row under stable names."""
    out = {}
    for key, value in row.items():
        if key.endswith(("_median_g", "_beta")) or key in NUMBER_KEYS or key in TEXT_KEYS:
            out[key] = value
    return out


def assess_cli(inventory: Path, out: Path) -> float:
    """Run ``rockscreen assess`` on an inventory; return the wall time [s]."""
    start = time.perf_counter()
    cmd = [str(Path(sys.executable).with_name("rockscreen")), "assess", "--towers"]
    cmd += [str(inventory), "--out", str(out)]
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - start


def bench_archive(n: int, out: Path, jobs: int) -> float:
    """Assess ``n`` benchmark towers at their own sites into ``out``; return the wall [s]."""
    sys.path.insert(0, str(HERE))
    from assess_bench import make_towers, options_for

    from rockscreen.pipeline.risk.assess.batch import AssessInputs, assess_to_archive

    start = time.perf_counter()
    inputs = AssessInputs(inventory=Path("benchmark towers"), suite=None)
    assess_to_archive(
        make_towers(n, None), options_for("stochastic"), out, inputs, jobs=jobs,
        notify=lambda text: None,
    )  # fmt: skip
    return time.perf_counter() - start


def snapshot(args) -> None:
    """Assess the cases and write their verdicts to ``args.out``."""
    cases: dict[str, dict] = {}
    with tempfile.TemporaryDirectory() as scratch:
        runs = [
            (name, lambda out, name=name: assess_cli(EXAMPLE / f"towers_{name}.csv", out))
            for name in args.example
        ]
        if args.bench:
            runs.append(
                (f"bench{args.bench}", lambda out: bench_archive(args.bench, out, args.jobs))
            )
        for name, go in runs:
            out = Path(scratch) / f"{name}.h5"
            wall = go(out)
            summary = read_table(out, "summary")
            ida = read_table(out, "ida") if "ida" in h5py.File(out, "r") else []
            cases[name] = {
                "wall_s": wall,
                "towers": {r["id"]: fit_columns(r) for r in summary},
                "solves": {r["id"]: r.get("n_solves", 0) for r in summary},
                "ida_solves": {r["id"]: r.get("ida_n_solves", 0) for r in summary},
                "ida": [
                    [
                        r["tower_id"],
                        r["record"],
                        r["component"],
                        r["models"],
                        r["collapse_ag_g"],
                        r["slv_ag_g"],
                        r["censored"],
                        r["slv_censored"],
                    ]
                    for r in ida
                ],  # fmt: skip
            }
            n = max(len(summary), 1)
            print(
                f"{name}: {len(summary)} towers, {wall:.1f} s, "
                f"{sum(cases[name]['solves'].values()) / n:.0f} solves per tower "
                f"(IDA {sum(cases[name]['ida_solves'].values()) / n:.0f})",
                flush=True,
            )
    Path(args.out).write_text(json.dumps(cases, indent=1))


def relative(a: float, b: float) -> float:
    """Relative difference of two numbers (0 for two NaNs or two equal infinities)."""
    if isinstance(a, str) or isinstance(b, str):
        return 0.0 if a == b else math.inf
    if (math.isnan(a) and math.isnan(b)) or a == b:
        return 0.0
    if math.isnan(a) or math.isnan(b) or math.isinf(a) or math.isinf(b):
        return math.inf
    return abs(a - b) / max(abs(a), abs(b), 1e-300)


def compare(args) -> None:
    """Print the differences between two snapshots."""
    before = json.loads(Path(args.before).read_text())
    after = json.loads(Path(args.after).read_text())
    for name in before:
        if name not in after:
            continue
        b, a = before[name], after[name]
        n = len(b["towers"])
        sb, sa = sum(b["solves"].values()) / n, sum(a["solves"].values()) / n
        ib, ia = sum(b["ida_solves"].values()) / n, sum(a["ida_solves"].values()) / n
        print(
            f"{name}: {n} towers; solves per tower {sb:.0f} -> {sa:.0f} ({sa / sb - 1:+.0%}), "
            f"IDA {ib:.0f} -> {ia:.0f}; wall {b['wall_s']:.1f} -> {a['wall_s']:.1f} s"
        )
        keys = sorted({k for row in b["towers"].values() for k in row})
        for key in keys:
            diffs = [
                relative(b["towers"][t].get(key, math.nan), a["towers"][t].get(key, math.nan))
                for t in b["towers"]
            ]
            changed = [d for d in diffs if d > args.rtol]
            if changed:
                print(
                    f"  {key}: {len(changed)}/{n} towers differ, largest "
                    f"{max(changed):.3g} relative, median of the changed "
                    f"{float(np.median(changed)):.3g}"
                )
        rows_b = {tuple(r[:4]): r[4:] for r in b["ida"]}
        rows_a = {tuple(r[:4]): r[4:] for r in a["ida"]}
        common = rows_b.keys() & rows_a.keys()
        flags = sum(rows_b[k][2:] != rows_a[k][2:] for k in common)
        dev = [max(relative(rows_b[k][0], rows_a[k][0]), relative(rows_b[k][1], rows_a[k][1]))
               for k in common]  # fmt: skip
        if dev:
            print(
                f"  /ida rows (per component): {len(common)}, censoring flags differ on {flags}; "
                f"intensities: {sum(d > args.rtol for d in dev)} differ, largest {max(dev):.3g} "
                f"relative"
            )
        for level in (0, 1):
            mine, theirs = per_record(a["ida"], level), per_record(b["ida"], level)
            differ = [
                key for key in theirs
                if key not in mine or mine[key][1] != theirs[key][1]
                or relative(mine[key][0], theirs[key][0]) > args.rtol
            ]  # fmt: skip
            print(
                f"  records' {('collapse', 'SLV')[level]} intensity (components combined, as "
                f"the fits read it): {len(differ)} of {len(theirs)} differ"
            )


def per_record(rows: list, level: int) -> dict:
    """Return (tower, record) -> (intensity, censored) of one level, components combined."""
    out: dict = {}
    for tower, record, _component, _models, collapse, slv, censored, slv_censored in rows:
        item = (collapse, censored) if level == 0 else (slv, slv_censored)
        key = (tower, record)
        if key not in out or item < out[key]:
            out[key] = item
    return out


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    snap = sub.add_parser("snapshot")
    snap.add_argument("out")
    snap.add_argument("--bench", type=int, default=40)
    snap.add_argument("--jobs", type=int, default=2)
    snap.add_argument("--example", nargs="*", default=["geometry", "shaft_lc1"])
    comp = sub.add_parser("compare")
    comp.add_argument("before")
    comp.add_argument("after")
    comp.add_argument("--rtol", type=float, default=1e-9)
    args = parser.parse_args()
    snapshot(args) if args.command == "snapshot" else compare(args)


if __name__ == "__main__":
    main()
