"""How much restitution and friction move the rocking IDA and the screening risk (issue 31).

The screening risk takes the rocking capacities of the IDA at the row's inputs: the
restitution ``eta`` of the whole tower's block (the row's, else Housner's
``1 - 1.5 sin^2(alpha)``) and the double-block model's friction (``mu_s``, ``mu_k``) are
not sampled. This script measures whether they should be: it writes each inventory with
the inputs at the ends of their ranges in the literature and runs ``rockscreen assess``
(the assess path, same seed) on the inventory as given and on each variant:

- **restitution** ``eta`` = 0.95 x Housner's (the measured coefficient of restitution of
  slender blocks on a stiff base, about 0.95-0.97 of Housner's: ElGawady et al., *Earthquake
  Engng Struct. Dyn.* 40, 2011) and ``1 - (1 - eta_H) / 2``, half Housner's velocity loss
  (experiments lose less energy than Housner's edge impact: Kalliontzis et al., *J. Struct.
  Eng.* 142(12), 2016; Ther & Kollár, *Bull. Earthquake Eng.* 15, 2017; the magnitude "half"
  a judgement); a row's own ``eta`` is the centre instead of Housner's; Housner's of the
  smaller plan side, used for both axes;
- **friction** (rows with ``mu_s``): ``mu_s`` = 0.6 and 0.8 with ``mu_k = 0.75 mu_s``, the
  range of stone and brick masonry joints in direct shear (Vasconcelos & Lourenço,
  *Construction and Building Materials* 23, 2009: friction coefficients about 0.6-0.7).

Printed per variant: the change of the rocking collapse median (``collapse_median_g``) and
of the screening risk's P50 (best, 5 %, 95 %, mean) relative to the width of the tower's
90 % interval. ``docs/risk.md``, "Restitution and friction: measured, not sampled".

    python benchmarks/rocking_inputs.py /tmp/geom20.csv --out-dir /tmp/rocking
"""

from __future__ import annotations

import argparse
import csv
import math
import subprocess
import sys
from pathlib import Path

from rockscreen.solver.block import RockingBlock

#: Restitution: the ends as functions of the centre (Housner's or the row's).
ETA_ENDS = {"eta_lo": lambda eta: 0.95 * eta, "eta_hi": lambda eta: 1.0 - 0.5 * (1.0 - eta)}
#: Friction: mu_s at the ends, mu_k = MU_K_RATIO mu_s.
MU_ENDS = {"mu_lo": 0.6, "mu_hi": 0.8}
MU_K_RATIO = 0.75
#: The P50 statistics compared.
P50_COLUMNS = ("risk_p50_best", "risk_p50_lo90", "risk_p50_hi90", "risk_p50_mean")


def _number(text: str) -> float:
    try:
        return float(str(text).lstrip("'<>~?"))
    except ValueError:
        return math.nan


def _centre_eta(row: dict[str, str]) -> float:
    if row.get("eta"):
        return float(row["eta"])
    width = float(row["width_m"])
    depth = float(row["depth_m"]) if row.get("depth_m") else width
    return RockingBlock.from_dimensions(min(width, depth), float(row["height_m"])).eta


def variants(path: Path, out_dir: Path) -> dict[str, Path]:
    """Write the inventory as given and its variants; return name -> path."""
    rows = list(csv.DictReader(path.open(encoding="utf-8")))
    fields = list(rows[0]) + [k for k in ("eta", "mu_s", "mu_k") if k not in rows[0]]
    out = {"base": [dict(r) for r in rows]}
    for name, end in ETA_ENDS.items():
        out[name] = [{**r, "eta": f"{end(_centre_eta(r)):.5f}"} for r in rows]
    if any(r.get("mu_s") for r in rows):
        for name, mu in MU_ENDS.items():
            out[name] = [
                {**r, "mu_s": f"{mu:g}", "mu_k": f"{MU_K_RATIO * mu:g}"} if r.get("mu_s") else r
                for r in rows
            ]
    paths = {}
    for name, table in out.items():
        paths[name] = out_dir / f"{path.stem}_{name}.csv"
        with paths[name].open("w", newline="", encoding="utf-8") as f:
            writer = csv.DictWriter(f, fieldnames=fields)
            writer.writeheader()
            writer.writerows(table)
    return paths


def assess(inventory: Path, seed: int) -> dict[str, dict[str, str]]:
    """Run ``rockscreen assess`` and ``export --csv``; return the rows by id."""
    archive, table = inventory.with_suffix(".h5"), inventory.with_suffix(".out.csv")
    exe = Path(sys.executable).with_name("rockscreen")
    common = ["--jobs", "1", "--seed", str(seed), "--overwrite"]
    subprocess.run(
        [exe, "assess", "--towers", inventory, "--out", archive, *common],
        check=True,
        capture_output=True,
    )
    subprocess.run(
        [exe, "export", archive, "--csv", table, "--order", "inventory"],
        check=True,
        capture_output=True,
    )
    return {r["id"]: r for r in csv.DictReader(table.open(encoding="utf-8"))}


def compare(base: dict, other: dict, name: str) -> float:
    """Print the changes of one variant; return the largest P50 change / interval width."""
    medians, worst = [], 0.0
    for tower, row in base.items():
        new = other.get(tower)
        if new is None or not math.isfinite(_number(row["risk_p50_best"])):
            continue
        a, b = row["collapse_median_g"], new["collapse_median_g"]
        if a and b and a[0] not in "'<>" and b[0] not in "'<>":
            medians.append(_number(b) / _number(a) - 1.0)
        width = _number(row["risk_p50_hi90"]) - _number(row["risk_p50_lo90"])
        if width > 0:
            for column in P50_COLUMNS:
                change = abs(_number(new[column]) - _number(row[column])) / width
                worst = max(worst, change)
    ordered = sorted(abs(m) for m in medians)
    middle = ordered[len(ordered) // 2] if ordered else math.nan
    print(
        f"{name}: collapse median changed by a median {100 * middle:.1f} % (|.|, {len(medians)} "
        f"towers with a value in both runs; range {100 * min(medians, default=math.nan):+.1f} "
        f"to {100 * max(medians, default=math.nan):+.1f} %); largest change of a P50 "
        f"statistic {100 * worst:.3f} % of the tower's 90 % interval"
    )
    return worst


def main(argv: list[str] | None = None) -> int:
    """Run the measurement on each inventory given."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("inventories", nargs="+", type=Path)
    parser.add_argument("--out-dir", type=Path, required=True)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args(argv)
    args.out_dir.mkdir(parents=True, exist_ok=True)
    worst = 0.0
    for inventory in args.inventories:
        paths = variants(inventory, args.out_dir)
        base = assess(paths.pop("base"), args.seed)
        print(f"{inventory.name}: {len(base)} towers")
        for name, path in paths.items():
            worst = max(worst, compare(base, assess(path, args.seed), name))
    print(f"largest change of a P50 statistic over all: {100 * worst:.3f} % of the 90 % interval")
    return 0


if __name__ == "__main__":
    sys.exit(main())
