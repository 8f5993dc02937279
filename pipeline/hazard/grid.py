"""The code hazard at a site: ag, F0 and T*C of NTC 2018 at any return period.

The table is the reference grid of Allegato B of the NTC 2008 (D.M. 14/01/2008), kept by
the NTC 2018 (D.M. 17/01/2018, §3.2): 10,751 nodes, at each the peak ground acceleration
on rock ``ag`` (tabulated in g/10), the amplification factor ``F0`` [-] and the period
``T*C`` [s] at nine return periods. It ships gzipped as package data
(``pipeline/hazard/data/ntc2018_grid.csv.gz``; provenance in ``docs/hazard.md``).

Rules (NTC 2008/2018 Allegato A):

- in space, the parameter at the site is the inverse-distance weighted mean of the four
  nearest nodes, with great-circle distances: ``p = sum(p_i / d_i) / sum(1 / d_i)``
  [Allegato A, eq. (3)]; at a node (``d = 0``) the node's own values are returned;
- between tabulated return periods, ``log p = log p1 + log(p2/p1) log(TR/TR1) /
  log(TR2/TR1)`` [Allegato A, eq. (4)];
- outside the tabulated 30-2475 years the hazard is not defined by the table: a return
  period there is refused (``out_of_range="refuse"``, the default), or, on request,
  replaced by the nearest tabulated one (``out_of_range="clamp"``), which is on the safe
  side below 30 years (the SLO of short reference periods) and unsafe above 2475 years;
- a site farther than one grid spacing (:data:`MAX_NODE_DISTANCE_KM`) from its nearest
  node is refused: it is off the grid (at sea, abroad, or on the small islands that
  Allegato B, Tab. 2 covers separately), and the table is never extrapolated.
"""

from __future__ import annotations

import gzip
import io
import math
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources

import numpy as np
from scipy.spatial import cKDTree

from rockscreen.pipeline.errors import HazardError
from rockscreen.stations.tower import swapped_hint

__all__ = [
    "EARTH_RADIUS_KM",
    "GRID_RESOURCE",
    "MAX_NODE_DISTANCE_KM",
    "RETURN_PERIODS_Y",
    "HazardGrid",
    "SiteHazard",
    "great_circle_km",
    "hazard_curve",
    "hazard_grid",
    "site_hazard",
    "site_hazards",
]

#: The nine return periods of the table [years] (Allegato B).
RETURN_PERIODS_Y = np.array([30.0, 50.0, 72.0, 101.0, 140.0, 201.0, 475.0, 975.0, 2475.0])
#: Mean Earth radius (IUGG) used for great-circle distances [km].
EARTH_RADIUS_KM = 6371.0088
#: The table inside the package (``importlib.resources``: package, file).
GRID_RESOURCE = ("rockscreen.pipeline.hazard", "data/ntc2018_grid.csv.gz")
#: Farthest a site may be from its nearest node [km]: one grid spacing. The median distance
#: between neighbouring nodes is 5.55 km (0.05 deg of latitude; measured on the table, see
#: ``HazardGrid.spacing_km``); inside the grid no point is farther than half a diagonal
#: (3.9 km) from a node.
MAX_NODE_DISTANCE_KM = 5.6
#: Accepted values of ``out_of_range``.
OUT_OF_RANGE_RULES = ("refuse", "clamp")


@dataclass(frozen=True)
class SiteHazard:
    """The code hazard parameters at one site and return period (on rock, flat ground)."""

    #: Site longitude and latitude, WGS84 [deg].
    lon_deg: float
    lat_deg: float
    #: Return period TR [years].
    return_period_y: float
    #: Peak ground acceleration on rock ag [g].
    ag_g: float
    #: Maximum spectral amplification factor [-].
    F0: float
    #: T*C, start of the constant-velocity branch on rock [s].
    Tc_star_s: float


@dataclass(frozen=True)
class HazardGrid:
    """The reference grid."""

    #: Node coordinates [deg], shape (n,).
    lon_deg: np.ndarray
    lat_deg: np.ndarray
    #: Parameters, shape (n, 9), columns in the order of :data:`RETURN_PERIODS_Y`; ``ag_g`` in g
    #: (the table's g/10 divided by 10).
    ag_g: np.ndarray
    F0: np.ndarray
    Tc_star_s: np.ndarray
    #: Nodes as unit vectors, for the nearest-node search.
    tree: cKDTree

    @property
    def spacing_km(self) -> float:
        """Median great-circle distance between each node and its nearest neighbour [km]."""
        chord, _ = self.tree.query(self.tree.data, k=2)
        return float(np.median(_chord_to_km(chord[:, 1])))


def _unit_vectors(lon_deg, lat_deg) -> np.ndarray:
    lon, lat = np.radians(lon_deg), np.radians(lat_deg)
    return np.stack([np.cos(lat) * np.cos(lon), np.cos(lat) * np.sin(lon), np.sin(lat)], -1)


def _chord_to_km(chord):
    return 2.0 * EARTH_RADIUS_KM * np.arcsin(np.clip(np.asarray(chord) / 2.0, 0.0, 1.0))


def great_circle_km(lon1_deg, lat1_deg, lon2_deg, lat2_deg):
    """Great-circle distance on a sphere of radius :data:`EARTH_RADIUS_KM`.

    Parameters
    ----------
    lon1_deg, lat1_deg, lon2_deg, lat2_deg : float or array_like
        Coordinates [deg].

    Returns
    -------
    float or numpy.ndarray
        Distance [km] (haversine formula).
    """
    lon1, lat1, lon2, lat2 = map(np.radians, (lon1_deg, lat1_deg, lon2_deg, lat2_deg))
    h = (
        np.sin((lat2 - lat1) / 2) ** 2
        + np.cos(lat1) * np.cos(lat2) * np.sin((lon2 - lon1) / 2) ** 2
    )
    return 2.0 * EARTH_RADIUS_KM * np.arcsin(np.sqrt(np.clip(h, 0.0, 1.0)))


@lru_cache(maxsize=1)
def hazard_grid() -> HazardGrid:
    """Read the shipped grid (once per process).

    Returns
    -------
    HazardGrid
        The 10,751 nodes of Allegato B.
    """
    package, name = GRID_RESOURCE
    raw = (resources.files(package) / name).read_bytes()
    text = gzip.decompress(raw).decode("ascii")
    header = [name.strip() for name in text.split("\n", 1)[0].split(",")]
    data = np.loadtxt(io.StringIO(text), delimiter=",", skiprows=1)
    columns = {name: i for i, name in enumerate(header)}

    def block(pattern: str) -> np.ndarray:
        return np.stack([data[:, columns[pattern.format(int(tr))]] for tr in RETURN_PERIODS_Y], 1)

    lon, lat = data[:, columns["lon_deg"]], data[:, columns["lat_deg"]]
    return HazardGrid(
        lon_deg=lon,
        lat_deg=lat,
        ag_g=block("ag_{}_g10") / 10.0,
        F0=block("F0_{}"),
        Tc_star_s=block("Tc_{}_s"),
        tree=cKDTree(_unit_vectors(lon, lat)),
    )


def _check_coordinates(lon_deg: float, lat_deg: float) -> None:
    for name, value, limit in (("lon_deg", lon_deg, 180.0), ("lat_deg", lat_deg, 90.0)):
        if not (isinstance(value, (int, float, np.floating, np.integer)) and math.isfinite(value)):
            raise HazardError(f"site {name}={value!r} must be a finite number [deg]")
        if abs(value) > limit:
            raise HazardError(f"site {name}={value:g} must be in [-{limit:g}, {limit:g}] deg")


def _site_nodes(lon_deg: float, lat_deg: float) -> tuple[np.ndarray, np.ndarray]:
    """Return the four nearest nodes and their great-circle distances [km]; refuse off-grid."""
    _check_coordinates(lon_deg, lat_deg)
    grid = hazard_grid()
    chord, index = grid.tree.query(_unit_vectors(lon_deg, lat_deg), k=4)
    distance = _chord_to_km(chord)
    if distance[0] > MAX_NODE_DISTANCE_KM:
        i = index[0]
        raise HazardError(
            f"site lon={lon_deg:g} lat={lat_deg:g} deg is outside the NTC 2018 hazard grid: "
            f"its nearest node ({grid.lon_deg[i]:g}, {grid.lat_deg[i]:g}) is "
            f"{distance[0]:.1f} km away, more than one grid spacing "
            f"({MAX_NODE_DISTANCE_KM:g} km); the grid covers Italy and is never extrapolated"
            f"{swapped_hint(lat_deg, lon_deg)}"
        )
    return index, distance


def _spatial(values: np.ndarray, index: np.ndarray, distance: np.ndarray) -> np.ndarray:
    """Inverse-distance weighted mean of the rows ``index`` (Allegato A, eq. 3)."""
    if distance[0] == 0.0:
        return values[index[0]].copy()
    weights = 1.0 / distance
    return weights @ values[index] / weights.sum()


def hazard_curve(lon_deg: float, lat_deg: float) -> tuple[np.ndarray, np.ndarray]:
    """Return the nine tabulated points of the hazard curve at a site.

    Parameters
    ----------
    lon_deg, lat_deg : float
        Site coordinates, WGS84 [deg].

    Returns
    -------
    return_periods_y : numpy.ndarray
        :data:`RETURN_PERIODS_Y` [years].
    ag_g : numpy.ndarray
        ag on rock at each [g] (spatially interpolated, Allegato A).

    Raises
    ------
    HazardError
        If the site is off the grid.
    """
    index, distance = _site_nodes(lon_deg, lat_deg)
    return RETURN_PERIODS_Y.copy(), _spatial(hazard_grid().ag_g, index, distance)


def _check_return_period(return_period_y: float, out_of_range: str) -> float:
    if out_of_range not in OUT_OF_RANGE_RULES:
        raise HazardError(
            f"out_of_range={out_of_range!r}; allowed: {', '.join(OUT_OF_RANGE_RULES)}"
        )
    try:
        tr = float(return_period_y)
    except (TypeError, ValueError):
        raise HazardError(f"return period {return_period_y!r} is not a number [years]") from None
    low, high = RETURN_PERIODS_Y[0], RETURN_PERIODS_Y[-1]
    if not math.isfinite(tr) or tr <= 0:
        raise HazardError(f"return period TR={tr:g} years must be a finite number > 0")
    if low <= tr <= high:
        return tr
    if out_of_range == "clamp":
        return float(np.clip(tr, low, high))
    raise HazardError(
        f"return period TR={tr:g} years is outside the tabulated {low:g}-{high:g} years of the "
        "NTC 2018 hazard (Allegato A/B); the table is not extrapolated (clamp to the nearest "
        "tabulated TR explicitly if that is intended)"
    )


def _log_log(tr: float, table: np.ndarray) -> float:
    """Interpolate one parameter between tabulated return periods (Allegato A, eq. 4)."""
    k = int(np.searchsorted(RETURN_PERIODS_Y, tr))
    if k < len(RETURN_PERIODS_Y) and RETURN_PERIODS_Y[k] == tr:
        return float(table[k])
    tr1, tr2 = RETURN_PERIODS_Y[k - 1], RETURN_PERIODS_Y[k]
    p1, p2 = table[k - 1], table[k]
    return float(
        math.exp(math.log(p1) + math.log(p2 / p1) * math.log(tr / tr1) / math.log(tr2 / tr1))
    )


def site_hazard(
    lon_deg: float, lat_deg: float, return_period_y: float, *, out_of_range: str = "refuse"
) -> SiteHazard:
    """Return ag, F0 and T*C at a site and return period (NTC 2018 §3.2.1, Allegato A).

    Parameters
    ----------
    lon_deg, lat_deg : float
        Site coordinates, WGS84 [deg].
    return_period_y : float
        Return period TR [years], in [30, 2475].
    out_of_range : {"refuse", "clamp"}
        What to do with TR outside [30, 2475]: refuse (default) or use the nearest
        tabulated return period (the returned ``return_period_y`` is then the clamped one).

    Returns
    -------
    SiteHazard
        Four-node inverse-distance interpolation in space, log-log between return periods;
        exactly the node's values at a node and a tabulated TR.

    Raises
    ------
    HazardError
        For a site off the grid, a non-numeric coordinate or a TR outside the table.
    """
    tr = _check_return_period(return_period_y, out_of_range)
    _check_coordinates(lon_deg, lat_deg)
    values = [_log_log(tr, p) for p in _site_tables(float(lon_deg), float(lat_deg))]
    return SiteHazard(float(lon_deg), float(lat_deg), tr, *values)


def site_hazards(
    lon_deg: float, lat_deg: float, return_periods_y, *, out_of_range: str = "refuse"
) -> list[SiteHazard]:
    """Return :func:`site_hazard` at many return periods of one site.

    Element ``i`` is ``site_hazard(lon_deg, lat_deg, return_periods_y[i])`` bit for bit (the
    same checks, the same log-log interpolation of Allegato A, eq. 4, with its logarithms
    of the table taken once per interval): for a search evaluating one site at many return
    periods at once.

    Parameters
    ----------
    lon_deg, lat_deg : float
        Site coordinates, WGS84 [deg].
    return_periods_y : iterable of float
        Return periods TR [years], each in [30, 2475] (``out_of_range``).
    out_of_range : {"refuse", "clamp"}
        As :func:`site_hazard`'s.

    Returns
    -------
    list of SiteHazard
    """
    trs = [_check_return_period(tr, out_of_range) for tr in return_periods_y]
    _check_coordinates(lon_deg, lat_deg)
    lon, lat = float(lon_deg), float(lat_deg)
    tables = _site_tables(lon, lat)
    n = len(RETURN_PERIODS_Y)
    logs: dict[int, tuple] = {}
    out = []
    for tr, k in zip(trs, np.searchsorted(RETURN_PERIODS_Y, trs).tolist(), strict=True):
        if k < n and RETURN_PERIODS_Y[k] == tr:
            out.append(SiteHazard(lon, lat, tr, *(float(table[k]) for table in tables)))
            continue
        if k not in logs:
            tr1, tr2 = RETURN_PERIODS_Y[k - 1], RETURN_PERIODS_Y[k]
            logs[k] = (
                tr1,
                math.log(tr2 / tr1),
                [(math.log(t[k - 1]), math.log(t[k] / t[k - 1])) for t in tables],
            )
        tr1, span, table_logs = logs[k]
        x = math.log(tr / tr1)
        values = (float(math.exp(low + step * x / span)) for low, step in table_logs)
        out.append(SiteHazard(lon, lat, tr, *values))
    return out


@lru_cache(maxsize=4096)
def _site_tables(lon_deg: float, lat_deg: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Return ag [g], F0 and T*C [s] of a site at the nine tabulated TR (read-only arrays).

    The four-node interpolation in space (Allegato A, eq. 3) of a site, made once per site
    and process: a capacity's inversion asks the same site for tens of return periods
    (the values are those computed on every call before, bit for bit).
    """
    index, distance = _site_nodes(lon_deg, lat_deg)
    grid = hazard_grid()
    tables = tuple(_spatial(p, index, distance) for p in (grid.ag_g, grid.F0, grid.Tc_star_s))
    for table in tables:
        table.flags.writeable = False
    return tables
