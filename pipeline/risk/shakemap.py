"""ShakeMap ``grid.xml`` (versions 3 and 4): reading and bilinear interpolation of PGA.

Format (USGS ShakeMap manual, "grid.xml"): a ``shakemap_grid`` root with an ``event``
element, a ``grid_specification`` (``lon_min``, ``lat_min``, ``lon_max``, ``lat_max``,
``nlon``, ``nlat``), ``grid_field`` elements (``index``, ``name``, ``units``) and the
rows of ``grid_data``, one line per node. PGA is in ``pctg`` (ShakeMap 3) or ``%g``
(ShakeMap 4), converted to g; ``STDPGA`` (ShakeMap 3; in ``ln(pctg)``) is the standard
deviation of ln PGA, unit-free, used as is. ShakeMap 4 keeps uncertainties in
``uncertainty.xml``: without ``STDPGA`` the event's PGA is taken as known.

Safety: the file is refused when it declares a DOCTYPE or an ENTITY (``xml.etree``
fetches no external entity, but expands internal ones: "billion laughs").

Truncated grids: a grid with fewer rows than ``nlon * nlat`` is **accepted with a
warning** (``ShakeMapGrid.warning``): the nodes present are placed by their coordinates
and a tower is interpolated only when the nodes with non-zero bilinear weight are all
present; otherwise it is reported outside the grid (never extrapolated). ``strict=True``
refuses such a grid.
"""

from __future__ import annotations

import math
import re
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from rockscreen.pipeline.errors import ShakeMapError

__all__ = ["ShakeMapGrid", "read_shakemap_grid"]

#: PGA units -> factor to g.
PGA_UNITS = {"pctg": 0.01, "%g": 0.01, "g": 1.0}
_FORBIDDEN = re.compile(rb"<!\s*(DOCTYPE|ENTITY)", re.IGNORECASE)
#: ``grid_specification`` attributes of the extent [deg], as named in :class:`ShakeMapGrid`.
_EXTENT = ("lon_min", "lat_min", "lon_max", "lat_max")


@dataclass
class ShakeMapGrid:
    """A ShakeMap grid: nodes of PGA [g] and, when given, sigma of ln PGA [-]."""

    #: The ``event`` attributes (``event_id``, ``magnitude``, ``lat``, ``lon``, ...).
    event: dict[str, Any]
    #: Grid extent [deg].
    lon_min: float
    lat_min: float
    lon_max: float
    lat_max: float
    #: Nodes per row and per column, from the header.
    nlon: int
    nlat: int
    #: Shape (nlat, nlon), row 0 at ``lat_min``; NaN where a node is missing [g].
    pga_g: np.ndarray
    #: Same shape, standard deviation of ln PGA [-]; None without STDPGA.
    sigma_ln_pga: np.ndarray | None
    #: Data rows read.
    n_rows: int
    #: ``""`` for a complete grid; otherwise what is missing.
    warning: str = ""
    #: ``code_version`` of the ShakeMap that wrote it.
    version: str = ""
    source: str = field(default="")

    @property
    def dlon(self) -> float:
        """Node spacing in longitude [deg]."""
        return (self.lon_max - self.lon_min) / (self.nlon - 1)

    @property
    def dlat(self) -> float:
        """Node spacing in latitude [deg]."""
        return (self.lat_max - self.lat_min) / (self.nlat - 1)

    def at(self, lon_deg: float, lat_deg: float) -> tuple[float, float] | None:
        """Return (PGA [g], sigma ln PGA [-] or NaN) at a point by bilinear interpolation.

        None when the point is outside the grid or a node it needs is missing.
        """
        x = (lon_deg - self.lon_min) / self.dlon
        y = (lat_deg - self.lat_min) / self.dlat
        eps = 1e-9
        if not (-eps <= x <= self.nlon - 1 + eps and -eps <= y <= self.nlat - 1 + eps):
            return None
        i0 = min(int(math.floor(x + eps)), self.nlon - 1)
        j0 = min(int(math.floor(y + eps)), self.nlat - 1)
        fx, fy = max(x - i0, 0.0), max(y - j0, 0.0)
        fx, fy = (0.0 if fx < eps else fx), (0.0 if fy < eps else fy)
        pga = sigma = 0.0
        for di, wx in ((0, 1 - fx), (1, fx)):
            for dj, wy in ((0, 1 - fy), (1, fy)):
                w = wx * wy
                if w == 0.0:
                    continue
                i, j = i0 + di, j0 + dj
                if i >= self.nlon or j >= self.nlat or math.isnan(self.pga_g[j, i]):
                    return None
                pga += w * self.pga_g[j, i]
                if self.sigma_ln_pga is not None:
                    sigma += w * self.sigma_ln_pga[j, i]
        return float(pga), (float(sigma) if self.sigma_ln_pga is not None else math.nan)


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


def _float(attrs: dict[str, str], key: str, path: Path) -> float:
    try:
        return float(attrs[key])
    except (KeyError, ValueError):
        raise ShakeMapError(
            f"{path}: grid_specification attribute {key!r} is missing or not a number "
            f"(found {attrs.get(key)!r})"
        ) from None


def read_shakemap_grid(path: str | Path, *, strict: bool = False) -> ShakeMapGrid:
    """Read a ShakeMap 3 or 4 ``grid.xml`` (module docstring).

    Parameters
    ----------
    path : str or Path
        The grid file.
    strict : bool
        Refuse a grid whose row count differs from ``nlon * nlat`` (default: accept with a
        warning).

    Returns
    -------
    ShakeMapGrid

    Raises
    ------
    ShakeMapError
        For a DOCTYPE/ENTITY, malformed XML, missing fields, unknown PGA units, bad rows.
    """
    path = Path(path)
    raw = path.read_bytes()
    if _FORBIDDEN.search(raw):
        raise ShakeMapError(
            f"{path}: declares a DOCTYPE or ENTITY; refused (a ShakeMap grid.xml has none, "
            "and entity expansion can exhaust memory)"
        )
    try:
        root = ET.fromstring(raw)
    except ET.ParseError as exc:
        raise ShakeMapError(f"{path}: not well-formed XML ({exc})") from None
    if _local(root.tag) != "shakemap_grid":
        raise ShakeMapError(f"{path}: root element {_local(root.tag)!r}, expected 'shakemap_grid'")
    elements: dict[str, list[ET.Element]] = {}
    for child in root:
        elements.setdefault(_local(child.tag), []).append(child)
    if "grid_specification" not in elements or "grid_data" not in elements:
        raise ShakeMapError(f"{path}: no grid_specification or grid_data element")
    spec = elements["grid_specification"][0].attrib
    extent = {key: _float(spec, key, path) for key in _EXTENT}
    lon_min, lat_min, lon_max, lat_max = extent.values()
    nlon, nlat = int(_float(spec, "nlon", path)), int(_float(spec, "nlat", path))
    if nlon < 2 or nlat < 2 or lon_max <= lon_min or lat_max <= lat_min:
        raise ShakeMapError(f"{path}: grid_specification {dict(spec)} does not describe a grid")
    fields = {
        e.attrib.get("name", "").upper(): (int(e.attrib["index"]) - 1, e.attrib.get("units", ""))
        for e in elements.get("grid_field", [])
    }
    for name in ("LON", "LAT", "PGA"):
        if name not in fields:
            raise ShakeMapError(f"{path}: no grid_field {name!r} (fields: {', '.join(fields)})")
    pga_units = fields["PGA"][1]
    if pga_units not in PGA_UNITS:
        raise ShakeMapError(f"{path}: PGA units {pga_units!r}; allowed: {', '.join(PGA_UNITS)}")
    text = elements["grid_data"][0].text or ""
    try:
        data = np.array([line.split() for line in text.strip().splitlines()], dtype=float)
    except ValueError:
        raise ShakeMapError(f"{path}: grid_data rows are not all numbers of equal count") from None
    if data.ndim != 2 or data.shape[0] == 0 or data.shape[1] < len(fields):
        raise ShakeMapError(
            f"{path}: grid_data has shape {data.shape}; expected rows of {len(fields)} numbers"
        )
    grid = ShakeMapGrid(
        event=dict(elements.get("event", [ET.Element("event")])[0].attrib),
        **extent,
        nlon=nlon,
        nlat=nlat,
        pga_g=np.full((nlat, nlon), np.nan),
        sigma_ln_pga=np.full((nlat, nlon), np.nan) if "STDPGA" in fields else None,
        n_rows=int(data.shape[0]),
        version=root.attrib.get("code_version", ""),
        source=str(path),
    )
    i = np.rint((data[:, fields["LON"][0]] - lon_min) / grid.dlon).astype(int)
    j = np.rint((data[:, fields["LAT"][0]] - lat_min) / grid.dlat).astype(int)
    if np.any((i < 0) | (i >= nlon) | (j < 0) | (j >= nlat)):
        raise ShakeMapError(f"{path}: grid_data rows outside the grid_specification extent")
    grid.pga_g[j, i] = data[:, fields["PGA"][0]] * PGA_UNITS[pga_units]
    if grid.sigma_ln_pga is not None:
        grid.sigma_ln_pga[j, i] = data[:, fields["STDPGA"][0]]
    expected = nlon * nlat
    if grid.n_rows != expected:
        message = (
            f"{path}: grid_data has {grid.n_rows} rows but the header describes "
            f"{nlon} x {nlat} = {expected} nodes (truncated grid)"
        )
        if strict:
            raise ShakeMapError(message + "; refused (strict)")
        grid.warning = message + "; only towers whose surrounding nodes are present are used"
    return grid


#: Largest number of grid nodes kept in an archive (a coarser grid is kept beyond it).
MAX_ARCHIVED_NODES = 250_000


def shakemap_arrays(grid: ShakeMapGrid) -> dict[str, tuple[np.ndarray, str]]:
    """Return the grid as archive datasets: ``shakemap/lon_deg``, ``lat_deg``, ``pga_g``.

    Nodes along each axis are thinned by a common stride so that at most
    :data:`MAX_ARCHIVED_NODES` are kept (for the report's contours); missing nodes are NaN.
    """
    stride = max(1, int(np.ceil(np.sqrt(grid.pga_g.size / MAX_ARCHIVED_NODES))))
    lon = np.linspace(grid.lon_min, grid.lon_max, grid.nlon)[::stride]
    lat = np.linspace(grid.lat_min, grid.lat_max, grid.nlat)[::stride]
    return {
        "shakemap/lon_deg": (lon, "deg"),
        "shakemap/lat_deg": (lat, "deg"),
        "shakemap/pga_g": (grid.pga_g[::stride, ::stride], "9.81 m/s2"),
    }
