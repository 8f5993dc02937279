"""ShakeMap ``grid.xml`` (versions 3 and 4): reading and bilinear interpolation of PGA.

Format (USGS ShakeMap manual, "grid.xml"): a ``shakemap_grid`` root with an ``event``
element, a ``grid_specification`` (``lon_min``, ``lat_min``, ``lon_max``, ``lat_max``,
``nlon``, ``nlat``), ``grid_field`` elements (``index``, ``name``, ``units``) and the
rows of ``grid_data``, one line per node. PGA is in ``pctg`` (ShakeMap 3) or ``%g``
(ShakeMap 4), converted to g; ``STDPGA`` (ShakeMap 3; in ``ln(pctg)``) is the standard
deviation of ln PGA, unit-free, used as is. ShakeMap 4 keeps uncertainties in
``uncertainty.xml``, a file of the same layout beside ``grid.xml`` (fields ``LON``,
``LAT``, ``STDPGA`` in ``ln(g)``, ...): :func:`find_uncertainty` looks for it and
:func:`read_uncertainty` reads its ``STDPGA`` onto the grid's nodes. A ``STDPGA`` that is
not a number, negative or above :data:`SIGMA_LN_PGA_MAX` is refused with its file and row
(never read as 0). Without any, :data:`DEFAULT_SIGMA_LN_PGA` applies (``docs/risk.md``).

Safety (a grid.xml comes from the network, by mail, on a USB stick): the file is read,
parsed, and its header, fields and rows checked by
:mod:`rockscreen.pipeline.hazard.shakemap_xml` (a regular file of bounded size, no DOCTYPE,
a header that describes the rows, unique fields, rows on distinct nodes). A ``PGA`` that
is not finite, negative or above :data:`PGA_MAX_G` (the usual slip: a grid labelled ``g``
holding %g values) is refused with its row.

Truncated grids: a grid with fewer rows than ``nlon * nlat`` is **accepted with a
warning** (``ShakeMapGrid.warning``): the nodes present are placed by their coordinates
and a tower is interpolated only when the nodes with non-zero bilinear weight are all
present; otherwise it is reported outside the grid (never extrapolated). ``strict=True``
refuses such a grid.
"""

from __future__ import annotations

import math
import xml.etree.ElementTree as ET
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from rockscreen.pipeline.errors import ShakeMapError
from rockscreen.pipeline.hazard.shakemap_xml import (
    EXTENT,
    node_indices,
    parse_grid_file,
    refuse_bad_row,
)
from rockscreen.pipeline.text import printable

__all__ = [
    "DEFAULT_SIGMA_LN_PGA",
    "DEFAULT_SIGMA_SOURCE",
    "PGA_MAX_G",
    "SIGMA_LN_PGA_MAX",
    "ShakeMapGrid",
    "find_uncertainty",
    "read_shakemap_grid",
    "read_uncertainty",
]

#: Default standard deviation of ln PGA [-] when the ShakeMap gives none: the total sigma
#: of the Italian GMPE ITA10 for PGA, 0.337 in log10 units (Bindi et al. 2011, Bull.
#: Earthquake Eng. 9(6) 1899-1920, Table 5; the same coefficient in OpenQuake's
#: ``BindiEtAl2011``), times ln 10: 0.776. It is the scatter of an unconditioned
#: prediction; a ShakeMap constrained by nearby stations is tighter, so this errs wide.
DEFAULT_SIGMA_LN_PGA = 0.337 * math.log(10.0)
#: How the default is named in notes and archives.
DEFAULT_SIGMA_SOURCE = (
    f"default sigma_lnPGA = {DEFAULT_SIGMA_LN_PGA:.3f} (total sigma of ITA10 for PGA, "
    "Bindi et al. 2011: 0.337 in log10)"
)
#: Largest credible standard deviation of ln PGA [-]: a factor e^2 = 7.4 at one sigma,
#: well above any GMPE's total sigma (0.5-0.8); a larger value is an error of the file.
SIGMA_LN_PGA_MAX = 2.0

#: PGA units -> factor to g.
PGA_UNITS = {"pctg": 0.01, "%g": 0.01, "g": 1.0}
#: Largest plausible PGA [g]: above any recorded peak (about 4 g, Iwate-Miyagi 2008).
PGA_MAX_G = 5.0


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
    #: Where ``sigma_ln_pga`` comes from (``"STDPGA of grid.xml"``, ...); ``""`` without it.
    sigma_source: str = ""

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


def _checked_sigma(values: np.ndarray, path: Path) -> np.ndarray:
    """Return STDPGA [-], refusing NaN, negative or absurd values with their row."""
    bad = ~np.isfinite(values) | (values < 0) | (values > SIGMA_LN_PGA_MAX)
    if np.any(bad):
        row = int(np.nonzero(bad)[0][0])
        raise ShakeMapError(
            f"{printable(path)}: STDPGA {float(values[row])!r} at grid_data row {row + 1} (of "
            f"{values.size}) is not a standard deviation of ln PGA in 0-{SIGMA_LN_PGA_MAX:g}; "
            "refused (a missing or broken uncertainty is never read as 0)"
        )
    return values


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
        For a file that is not regular or too large, a DOCTYPE/ENTITY, malformed XML, a
        header that does not describe the rows, missing or repeated fields, unknown PGA
        units, bad or duplicated rows, a PGA that is not finite, negative or above
        :data:`PGA_MAX_G`, a STDPGA that is not a number, negative or absurd.
    """
    path = Path(path)
    root, elements, extent, nlon, nlat, fields, data = parse_grid_file(path)
    if "PGA" not in fields:
        raise ShakeMapError(
            f"{printable(path)}: no grid_field 'PGA' (fields: {printable(', '.join(fields))[:200]})"
        )
    pga_units = fields["PGA"][1]
    if pga_units not in PGA_UNITS:
        raise ShakeMapError(
            f"{printable(path)}: PGA units {printable(pga_units)[:40]!r}; allowed: "
            f"{', '.join(PGA_UNITS)}"
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
    i, j = node_indices(data, fields, extent, nlon, nlat, path)
    pga_g = data[:, fields["PGA"][0]] * PGA_UNITS[pga_units]
    refuse_bad_row(path, "PGA", pga_g, ~np.isfinite(pga_g), "is not a finite number")
    refuse_bad_row(path, "PGA", pga_g, pga_g < 0, "[g] is negative")
    refuse_bad_row(
        path,
        "PGA",
        pga_g,
        pga_g > PGA_MAX_G,
        f"[g] is above {PGA_MAX_G:g} g, not a plausible PGA (units {pga_units!r} declared: "
        "a grid labelled 'g' that holds %g values?)",
    )
    grid.pga_g[j, i] = pga_g
    if grid.sigma_ln_pga is not None:
        grid.sigma_ln_pga[j, i] = _checked_sigma(data[:, fields["STDPGA"][0]], path)
        grid.sigma_source = f"STDPGA of {path.name}"
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


def find_uncertainty(grid_path: str | Path) -> Path | None:
    """Return the ShakeMap 4 ``uncertainty.xml`` beside a grid file, or None.

    Looked for: ``uncertainty.xml`` in the grid's folder, then the grid's own name with
    ``grid`` replaced by ``uncertainty`` (``us1234-grid.xml`` -> ``us1234-uncertainty.xml``).
    """
    grid_path = Path(grid_path)
    candidates = [grid_path.with_name("uncertainty.xml")]
    if "grid" in grid_path.name:
        candidates.append(grid_path.with_name(grid_path.name.replace("grid", "uncertainty")))
    return next((c for c in candidates if c.is_file() and c != grid_path), None)


def read_uncertainty(path: str | Path, grid: ShakeMapGrid) -> ShakeMapGrid:
    """Read ``STDPGA`` [ln units] of a ShakeMap 4 ``uncertainty.xml`` onto a grid's nodes.

    Parameters
    ----------
    path : str or Path
        The uncertainty file (same layout as ``grid.xml``; the same grid specification).
    grid : ShakeMapGrid
        The event grid; its ``sigma_ln_pga`` and ``sigma_source`` are set.

    Returns
    -------
    ShakeMapGrid
        ``grid``.

    Raises
    ------
    ShakeMapError
        For a file that is not a ShakeMap grid, has no STDPGA, describes another grid, or
        holds a STDPGA that is not a number, negative or absurd (file and row named).
    """
    path = Path(path)
    _, _, extent, nlon, nlat, fields, data = parse_grid_file(path)
    if "STDPGA" not in fields:
        raise ShakeMapError(f"{path}: no grid_field 'STDPGA' (fields: {', '.join(fields)})")
    same = (nlon, nlat) == (grid.nlon, grid.nlat) and all(
        math.isclose(extent[key], getattr(grid, key), abs_tol=1e-6) for key in EXTENT
    )
    if not same:
        raise ShakeMapError(
            f"{path}: its grid ({nlon} x {nlat}, {extent}) is not the event grid's "
            f"({grid.nlon} x {grid.nlat}, lon {grid.lon_min}-{grid.lon_max}, lat "
            f"{grid.lat_min}-{grid.lat_max}); give the uncertainty.xml of the same ShakeMap"
        )
    i, j = node_indices(data, fields, extent, nlon, nlat, path)
    sigma = np.full((nlat, nlon), np.nan)
    sigma[j, i] = _checked_sigma(data[:, fields["STDPGA"][0]], path)
    grid.sigma_ln_pga = sigma
    grid.sigma_source = f"STDPGA of {path.name}"
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
