"""Fit the wall and period priors of ``rockscreen.pipeline.risk.uncertainty`` on TURRIS.

TURRIS (Montabert et al., *Buildings* 2023; public GitHub ``MArnaud/TURRIS``, AGPL) is a
database of historic masonry towers with a measured fundamental frequency. No file of it is
in this repository: give the path of a CSV export of its ``TURRIS.xlsx`` (columns
``country, town, building_name, f0, H, width, length, min_wall_thickness,
max_wall_thickness, ...``; ``-1`` or blank is missing)::

    python benchmarks/turris_priors.py /path/to/turris.csv

What it does, on the Italian rows (``country == "Italy"``), one tower per
``building_name`` + ``town`` (the Italian rows repeat a tower per survey; the first row
with a value is kept for the geometry, the median over its surveys for ``f0``):

- ``base wall / smaller side`` = ``max_wall_thickness / min(width, length)`` (TURRIS's
  ``width`` is the shorter side; the thicker wall is taken as the base's): a lognormal, the
  mean and standard deviation of the log (maximum likelihood), on the rows with a ratio of
  at most 0.5 (a solid section; the rows above, ratios of 1.02 to 1.27, walls thicker than
  the tower is wide, are errors of the data);
- ``top / base`` = ``min_wall_thickness / max_wall_thickness`` (the thinner wall as the
  top's): a mixture of a point mass at 1 (a prismatic shaft: the same thickness) with the
  observed share, and a beta on (0, 1) fitted by maximum likelihood (location 0, scale 1)
  to the rest;
- ``T_measured / (0.0187 H)`` with ``T = 1 / f0``: a lognormal (median, log-std).

It prints the sample sizes, the empirical quantiles and the fitted parameters; the
fitted numbers are the constants of ``pipeline/risk/uncertainty/priors.py``
(``docs/uncertainty.md`` quotes this output).
"""

from __future__ import annotations

import argparse
import csv
import math
import sys
from pathlib import Path

import numpy as np
from scipy import stats

#: The period law checked: T1 = 0.0187 H (Faccio, Paolucci & Zanotti; docs/code_checks.md §3).
PERIOD_COEFFICIENT_S_PER_M = 0.0187
#: Largest plausible base wall / smaller side: 0.5 is a solid section.
MAX_WALL_RATIO = 0.5


def _value(text: str) -> float:
    """Return a TURRIS number, NaN for ``-1`` or blank."""
    try:
        value = float(text)
    except (TypeError, ValueError):
        return math.nan
    return math.nan if value == -1.0 else value


def italian_towers(path: Path) -> list[dict[str, float | str]]:
    """Return the unique Italian towers of a TURRIS CSV (module docstring).

    Parameters
    ----------
    path : Path
        The CSV export of ``TURRIS.xlsx``.

    Returns
    -------
    list of dict
        One per ``building_name`` + ``town``: ``name``, ``town``, ``lat``, ``lon``,
        ``H``, ``width``, ``length``, ``min_wall``, ``max_wall`` (the first surveyed value,
        NaN if none), ``f0`` (the median over the surveys, NaN if none).
    """
    towers: dict[tuple[str, str], dict] = {}
    with open(path, newline="", encoding="utf-8") as handle:
        for row in csv.DictReader(handle):
            if row["country"].strip() != "Italy":
                continue
            key = (row["building_name"].strip(), row["town"].strip())
            tower = towers.setdefault(key, {"name": key[0], "town": key[1], "f0s": []})
            for name, column in (
                ("lat", "latitude"),
                ("lon", "longitude"),
                ("H", "H"),
                ("width", "width"),
                ("length", "length"),
                ("min_wall", "min_wall_thickness"),
                ("max_wall", "max_wall_thickness"),
            ):
                value = _value(row[column])
                usable = math.isfinite(value) if name in ("lat", "lon") else value > 0
                if usable and not math.isfinite(tower.get(name, math.nan)):
                    tower[name] = value
            f0 = _value(row["f0"])
            if f0 > 0:
                tower["f0s"].append(f0)
    out = []
    for tower in towers.values():
        for name in ("lat", "lon", "H", "width", "length", "min_wall", "max_wall"):
            tower.setdefault(name, math.nan)
        f0s = tower.pop("f0s")
        tower["f0"] = float(np.median(f0s)) if f0s else math.nan
        out.append(tower)
    return out


def fit(towers: list[dict]) -> dict[str, float]:
    """Return the fitted parameters and the quantiles (module docstring)."""
    out: dict[str, float] = {"n_towers": len(towers)}
    base = np.array(
        [
            t["max_wall"] / min(t["width"], t["length"])
            for t in towers
            if t["max_wall"] > 0 and t["width"] > 0 and t["length"] > 0
        ]
    )
    out["wall_n_all"] = base.size
    out["wall_all_p10"], out["wall_all_p50"], out["wall_all_p90"] = np.percentile(
        base, [10, 50, 90]
    )
    # A wall thicker than half the smaller side leaves no void: such rows (ratios above 1,
    # i.e. walls thicker than the tower is wide) are errors of the data, not towers.
    base = base[base <= MAX_WALL_RATIO]
    out["wall_n"] = base.size
    out["wall_p10"], out["wall_p50"], out["wall_p90"] = np.percentile(base, [10, 50, 90])
    logs = np.log(base)
    out["wall_median"] = float(np.exp(logs.mean()))
    out["wall_log_std"] = float(logs.std(ddof=0))
    taper = np.array(
        [
            t["min_wall"] / t["max_wall"]
            for t in towers
            if t["min_wall"] > 0 and t["max_wall"] > 0 and t["width"] > 0 and t["length"] > 0
        ]
    )
    out["taper_n"] = taper.size
    out["taper_p10"], out["taper_p50"], out["taper_p90"] = np.percentile(taper, [10, 50, 90])
    prismatic = taper >= 1.0 - 1e-9
    out["taper_prismatic_share"] = float(prismatic.mean())
    a, b, _, _ = stats.beta.fit(taper[~prismatic], floc=0.0, fscale=1.0)
    out["taper_beta_a"], out["taper_beta_b"] = float(a), float(b)
    ratio = np.array(
        [
            (1.0 / t["f0"]) / (PERIOD_COEFFICIENT_S_PER_M * t["H"])
            for t in towers
            if t["f0"] > 0 and t["H"] > 0
        ]
    )
    out["period_n"] = ratio.size
    out["period_median"] = float(np.exp(np.log(ratio).mean()))
    out["period_sample_median"] = float(np.median(ratio))
    out["period_log_std"] = float(np.log(ratio).std(ddof=0))
    return out


def main(argv: list[str] | None = None) -> int:
    """Print the fit (module docstring)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", type=Path, help="CSV export of TURRIS.xlsx")
    args = parser.parse_args(argv)
    if not args.csv.is_file():
        print(f"turris_priors: no file {args.csv}", file=sys.stderr)
        return 1
    towers = italian_towers(args.csv)
    r = fit(towers)
    print(f"unique Italian towers: {r['n_towers']}")
    print(
        f"base wall / smaller side, all rows (n {r['wall_n_all']}): quantiles 10/50/90 % "
        f"{r['wall_all_p10']:.3f} / {r['wall_all_p50']:.3f} / {r['wall_all_p90']:.3f}"
    )
    print(
        f"base wall / smaller side <= {MAX_WALL_RATIO} (n {r['wall_n']}): quantiles 10/50/90 % "
        f"{r['wall_p10']:.3f} / {r['wall_p50']:.3f} / {r['wall_p90']:.3f}; lognormal fit "
        f"median {r['wall_median']:.4f}, log-std {r['wall_log_std']:.4f}"
    )
    print(
        f"top / base wall (n {r['taper_n']}): quantiles 10/50/90 % {r['taper_p10']:.3f} / "
        f"{r['taper_p50']:.3f} / {r['taper_p90']:.3f}; prismatic (top = base) share "
        f"{r['taper_prismatic_share']:.4f}, beta on the rest a {r['taper_beta_a']:.4f}, "
        f"b {r['taper_beta_b']:.4f}"
    )
    print(
        f"T_measured / (0.0187 H) (n {r['period_n']}): sample median "
        f"{r['period_sample_median']:.4f}; lognormal fit median {r['period_median']:.4f}, "
        f"log-std {r['period_log_std']:.4f}"
    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
