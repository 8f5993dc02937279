"""Tower sites of an assessment: location rounded into shared sites, soil and use assumptions.

A tower's site is its location rounded to ``site_resolution_deg`` (default 0.01 deg, about
1 km; 0 keeps it exact) with its soil class, topography, use class and nominal life: the
inventory's values when it has them (optional columns ``soil_class``, ``topography``,
``use_class``, ``nominal_life_y``), else the tower defaults of
:data:`rockscreen.pipeline.hazard.TOWER_DEFAULTS`, recorded as assumptions in the output.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from rockscreen.pipeline.hazard import TOWER_DEFAULTS
from rockscreen.stations.tower import Tower

__all__ = ["TowerSite", "tower_defaults", "tower_sites"]


def tower_defaults() -> dict[str, Any]:
    """Return the defaults for tower attributes the inventory may lack (V_N, class, soil...)."""
    return dict(TOWER_DEFAULTS)


@dataclass(frozen=True)
class TowerSite:
    """A tower, its site and the assumptions made for it."""

    #: Position in the inventory.
    index: int
    tower: Tower
    #: The site: the tower's location rounded to the site resolution [deg] (NaN if none).
    lon_deg: float
    lat_deg: float
    soil_class: str
    topography: str
    use_class: str
    #: Nominal life V_N [y].
    nominal_life_y: float
    #: Attributes taken from the defaults: ``(name, value)``, e.g. ``("soil_class", "A")``.
    defaults: tuple[tuple[str, Any], ...]

    @property
    def assumptions(self) -> tuple[str, ...]:
        """The defaults in words, e.g. ``"soil_class=A (default)"``."""
        return tuple(f"{name}={value} (default)" for name, value in self.defaults)

    @property
    def key(self) -> tuple[float, float, str, str]:
        """The record sets' key: (lon [deg], lat [deg], soil class, topography)."""
        return (self.lon_deg, self.lat_deg, self.soil_class, self.topography)

    @property
    def soil_class_source(self) -> str:
        """``"inventory"`` or ``"default"`` (an assumption)."""
        return (
            "default" if any(name == "soil_class" for name, _ in self.defaults) else ("inventory")
        )


def _round(value: float, resolution: float) -> float:
    if resolution <= 0:
        return float(value)
    return float(round(round(value / resolution) * resolution, 6))


def tower_sites(towers: Sequence[Any], resolution_deg: float = 0.01) -> list[TowerSite]:
    """Return every tower's site and the attributes it assumed (module docstring, step 1)."""
    defaults = tower_defaults()
    out = []
    for index, tower in enumerate(towers):
        values, defaulted = {}, []
        for name in ("soil_class", "topography", "use_class", "nominal_life_y"):
            value = getattr(tower, name, None)
            if value is None:
                value = defaults[name]
                defaulted.append((name, value))
            values[name] = value
        has = tower.lat is not None and tower.lon is not None
        out.append(
            TowerSite(
                index=index,
                tower=tower,
                lon_deg=_round(tower.lon, resolution_deg) if has else math.nan,
                lat_deg=_round(tower.lat, resolution_deg) if has else math.nan,
                soil_class=str(values["soil_class"]).upper(),
                topography=str(values["topography"]).upper(),
                use_class=str(values["use_class"]),
                nominal_life_y=float(values["nominal_life_y"]),
                defaults=tuple(defaulted),
            )
        )
    return out
