"""The example event grid: a ShakeMap 4-style ``grid.xml`` that rockscreen generates itself.

The event is **hypothetical** (no real earthquake): an epicentre at lon 14.55, lat 41.12
(among the example towers of ``stations/data/example_towers.csv``), magnitude 6.0, depth
10 km. PGA on the grid follows a simple attenuation chosen for illustration, **not a
published ground-motion model**:

    PGA [g] = 0.40 (10 / sqrt(R^2 + 10^2))^1.3,   R = epicentral distance [km]

(about 0.40 g at the epicentre, 0.16 g at 20 km, 0.05 g at 50 km), with a constant
``STDPGA = 0.6`` (ln units, of the order of ShakeMap's far-from-station uncertainty),
written in ShakeMap 4 units (``%g``) on a 0.02 deg grid over lon 14.0-15.2, lat 40.8-41.6.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from rockscreen.pipeline.archive.atomic import write_text_atomic

__all__ = ["EXAMPLE_EVENT", "example_pga_g", "write_example_grid"]

EXAMPLE_EVENT = {"lon": 14.55, "lat": 41.12, "magnitude": 6.0, "depth": 10.0}
_EXTENT = (14.0, 40.8, 15.2, 41.6)  # lon_min, lat_min, lon_max, lat_max [deg]
_SPACING = 0.02  # [deg]


def example_pga_g(lon_deg, lat_deg):
    """Return the example event's PGA [g] at points [deg] (module docstring)."""
    lon, lat = np.asarray(lon_deg, float), np.asarray(lat_deg, float)
    dx = (lon - EXAMPLE_EVENT["lon"]) * 111.19 * math.cos(math.radians(EXAMPLE_EVENT["lat"]))
    dy = (lat - EXAMPLE_EVENT["lat"]) * 111.19
    r = np.hypot(dx, dy)
    return 0.40 * (10.0 / np.sqrt(r * r + 100.0)) ** 1.3


def write_example_grid(path: str | Path) -> Path:
    """Write the example grid.xml to ``path`` (atomically) and return the path."""
    lon_min, lat_min, lon_max, lat_max = _EXTENT
    nlon = round((lon_max - lon_min) / _SPACING) + 1
    nlat = round((lat_max - lat_min) / _SPACING) + 1
    lines = [
        '<?xml version="1.0" encoding="UTF-8" standalone="yes"?>',
        '<shakemap_grid xmlns="http://earthquake.usgs.gov/eqcenter/shakemap" '
        'event_id="rockscreen-example" shakemap_id="rockscreen-example" shakemap_version="1" '
        'code_version="rockscreen example (hypothetical event)" map_status="EXAMPLE" '
        'shakemap_event_type="SCENARIO">',
        f'<event event_id="rockscreen-example" magnitude="{EXAMPLE_EVENT["magnitude"]}" '
        f'depth="{EXAMPLE_EVENT["depth"]}" lat="{EXAMPLE_EVENT["lat"]}" '
        f'lon="{EXAMPLE_EVENT["lon"]}" event_description="hypothetical example event" />',
        f'<grid_specification lon_min="{lon_min}" lat_min="{lat_min}" lon_max="{lon_max}" '
        f'lat_max="{lat_max}" nominal_lon_spacing="{_SPACING}" '
        f'nominal_lat_spacing="{_SPACING}" nlon="{nlon}" nlat="{nlat}" />',
        '<grid_field index="1" name="LON" units="dd" />',
        '<grid_field index="2" name="LAT" units="dd" />',
        '<grid_field index="3" name="PGA" units="%g" />',
        '<grid_field index="4" name="STDPGA" units="ln(%g)" />',
        "<grid_data>",
    ]
    for j in range(nlat - 1, -1, -1):  # ShakeMap order: from the north, west to east
        lat = lat_min + j * _SPACING
        lons = lon_min + np.arange(nlon) * _SPACING
        pga = example_pga_g(lons, np.full(nlon, lat)) * 100.0
        lines.extend(f"{lo:.4f} {lat:.4f} {p:.4g} 0.6" for lo, p in zip(lons, pga, strict=True))
    lines += ["</grid_data>", "</shakemap_grid>", ""]
    return write_text_atomic(path, "\n".join(lines))
