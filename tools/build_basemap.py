"""Build the offline base map shipped with the report: coastlines and national borders.

Source: Natural Earth 1:10m Admin 0 countries, version 4.1.0 (public domain,
https://www.naturalearthdata.com/about/terms-of-use/), as redistributed in TopoJSON by the
npm package ``world-atlas`` 2.0.2 (ISC licence, file ``countries-10m.json``). Not part of
the package or the test suite: run once by a maintainer, the output is committed.

    npm pack world-atlas@2.0.2 && tar xzf world-atlas-2.0.2.tgz
    python tools/build_basemap.py package/countries-10m.json \
        pipeline/report/data/basemap_italy.json

Every TopoJSON arc (a coastline or a border segment, each stored once) that has a point in
the box of Italy and its neighbours (:data:`BOX`) is kept, simplified (Douglas-Peucker,
:data:`TOLERANCE_DEG`) and written as integer microdegree/1000 coordinates (about 100 m),
delta-encoded.
"""

from __future__ import annotations

import json
import sys

import numpy as np

#: lon_min, lon_max, lat_min, lat_max [deg]: Italy, Malta, Corsica and the borders around.
BOX = (5.0, 20.5, 35.0, 48.0)
#: Simplification tolerance [deg] (about 200 m).
TOLERANCE_DEG = 0.002
#: Coordinates are stored as round(value / QUANTUM_DEG).
QUANTUM_DEG = 0.001


def _decode_arcs(topology: dict) -> list[np.ndarray]:
    scale = np.array(topology["transform"]["scale"], float)
    translate = np.array(topology["transform"]["translate"], float)
    out = []
    for arc in topology["arcs"]:
        q = np.cumsum(np.asarray(arc, float), axis=0)
        out.append(q * scale + translate)
    return out


def _simplify(points: np.ndarray, tol: float) -> np.ndarray:
    keep = np.zeros(len(points), bool)
    keep[[0, -1]] = True
    stack = [(0, len(points) - 1)]
    while stack:
        i, j = stack.pop()
        if j <= i + 1:
            continue
        a, b = points[i], points[j]
        seg = b - a
        norm = np.hypot(*seg)
        rel = points[i + 1 : j] - a
        dist = (
            np.abs(seg[0] * rel[:, 1] - seg[1] * rel[:, 0]) / norm
            if norm > 0
            else np.hypot(rel[:, 0], rel[:, 1])
        )
        k = int(np.argmax(dist))
        if dist[k] > tol:
            keep[i + 1 + k] = True
            stack += [(i, i + 1 + k), (i + 1 + k, j)]
    return points[keep]


def main(source: str, target: str) -> None:
    """Read the TopoJSON ``source`` and write the base map JSON ``target``."""
    with open(source, encoding="utf-8") as handle:
        topology = json.load(handle)
    lon0, lon1, lat0, lat1 = BOX
    lines = []
    for arc in _decode_arcs(topology):
        inside = (
            (arc[:, 0] >= lon0) & (arc[:, 0] <= lon1) & (arc[:, 1] >= lat0) & (arc[:, 1] <= lat1)
        )
        if not inside.any():
            continue
        simple = _simplify(arc, TOLERANCE_DEG)
        q = np.round(simple / QUANTUM_DEG).astype(np.int64)
        q = q[np.r_[True, np.any(np.diff(q, axis=0) != 0, axis=1)]]
        if len(q) < 2:
            continue
        delta = np.vstack([q[:1], np.diff(q, axis=0)])
        lines.append(delta.ravel().tolist())
    payload = {
        "source": "Natural Earth 1:10m Admin 0 countries v4.1.0 (public domain), "
        "via world-atlas 2.0.2 countries-10m.json",
        "box_deg": list(BOX),
        "quantum_deg": QUANTUM_DEG,
        "tolerance_deg": TOLERANCE_DEG,
        "encoding": "each line: flat [lon0, lat0, dlon1, dlat1, ...] in quantum_deg units",
        "lines": lines,
    }
    with open(target, "w", encoding="utf-8") as handle:
        json.dump(payload, handle, separators=(",", ":"))
    n_points = sum(len(line) // 2 for line in lines)
    print(f"{len(lines)} lines, {n_points} points -> {target}")


if __name__ == "__main__":
    main(*sys.argv[1:3])
