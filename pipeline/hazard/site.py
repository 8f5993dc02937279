"""The hazard of one tower or site with every default stated (what ``rockscreen hazard`` shows).

:func:`resolve_hazard` fills what the user and the inventory leave out with the tower
defaults of :data:`pipeline.hazard.limit_states.TOWER_DEFAULTS` and records each default as
an assumption, so that an unknown soil is never silently rock: the result carries
``soil_class_source`` (``"option"``, ``"inventory"`` or ``"default"``) and
``assumptions``, one sentence per default.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rockscreen.pipeline.errors import HazardError
from rockscreen.pipeline.hazard.grid import RETURN_PERIODS_Y, SiteHazard, site_hazard
from rockscreen.pipeline.hazard.limit_states import TOWER_DEFAULTS, limit_state_return_period
from rockscreen.pipeline.hazard.spectrum import (
    SpectrumParameters,
    elastic_spectrum,
    spectrum_parameters,
    vertical_spectrum,
)

__all__ = ["HazardResult", "resolve_hazard", "tower_hazard"]


@dataclass(frozen=True)
class HazardResult:
    """The code hazard at a site with the choices that produced it."""

    #: ag [g], F0 [-], T*C [s] at the return period used.
    site: SiteHazard
    #: Soil and topography factors, corner periods [s], PGA [g].
    spectrum: SpectrumParameters
    #: SLO/SLD/SLV/SLC, or None when a return period was given.
    limit_state: str | None
    #: V_N [years] (limit states only).
    nominal_life_y: float | None
    #: I-IV (limit states only).
    use_class: str | None
    #: Categories used.
    soil_class: str
    topography: str
    #: ``"option"``, ``"inventory"`` or ``"default"``.
    soil_class_source: str
    topography_source: str
    #: Damping ratio [-].
    damping: float
    #: Every default and adjustment applied, one sentence each.
    assumptions: tuple[str, ...]

    def to_dict(self, periods_s=None) -> dict:
        """Return the result as JSON-ready values (keys with units).

        Parameters
        ----------
        periods_s : array_like, optional
            Periods [s] at which ``se_g`` and ``sve_g`` (horizontal and vertical elastic
            spectra [g]) are added.

        Returns
        -------
        dict
        """
        out = {
            "lon_deg": self.site.lon_deg,
            "lat_deg": self.site.lat_deg,
            "limit_state": self.limit_state,
            "nominal_life_y": self.nominal_life_y,
            "use_class": self.use_class,
            "return_period_y": self.site.return_period_y,
            "ag_g": self.site.ag_g,
            "F0": self.site.F0,
            "Tc_star_s": self.site.Tc_star_s,
            "soil_class": self.soil_class,
            "soil_class_source": self.soil_class_source,
            "topography": self.topography,
            "topography_source": self.topography_source,
            "damping": self.damping,
        }
        out.update({k: getattr(self.spectrum, k) for k in self.spectrum.__dataclass_fields__})
        if periods_s is not None:
            t = np.asarray(periods_s, float)
            args = (self.site, self.soil_class, self.topography, self.damping)
            out["periods_s"] = t.tolist()
            out["se_g"] = elastic_spectrum(t, *args).tolist()
            out["sve_g"] = vertical_spectrum(t, *args).tolist()
        out["assumptions"] = list(self.assumptions)
        return out


def _category(value, inventory_value, default, name, assumptions) -> tuple[str, str]:
    if value is not None:
        return str(value).upper(), "option"
    if inventory_value is not None:
        return str(inventory_value).upper(), "inventory"
    assumptions.append(
        f"{name} unknown: assumed {default} ({_MEANING[name]}), a stated assumption, not data"
    )
    return default, "default"


_MEANING = {
    "soil class": "rock or very stiff soil, NTC 2018 Tab. 3.2.II: no stratigraphic amplification",
    "topography": "flat ground or slopes below 15 deg, NTC 2018 Tab. 3.2.III",
}


def resolve_hazard(
    lon_deg: float,
    lat_deg: float,
    *,
    return_period_y: float | None = None,
    limit_state: str | None = None,
    nominal_life_y: float | None = None,
    use_class: str | None = None,
    soil_class: str | None = None,
    topography: str | None = None,
    damping: float = 0.05,
    inventory: dict | None = None,
) -> HazardResult:
    """Return the hazard at a site, filling and stating the defaults.

    Parameters
    ----------
    lon_deg, lat_deg : float
        Site [deg].
    return_period_y : float, optional
        TR [years], in [30, 2475]; exclusive with ``limit_state``.
    limit_state : str, optional
        SLO/SLD/SLV/SLC; SLV when neither it nor ``return_period_y`` is given. A limit
        state whose TR falls below 30 years (short reference periods) uses the 30-year
        hazard, which is higher, and says so.
    nominal_life_y, use_class : optional
        V_N [years] and use class; the inventory's, else the tower defaults (stated).
    soil_class, topography : str, optional
        Categories; the inventory's, else A and T1 (stated).
    damping : float
        Damping ratio [-].
    inventory : dict, optional
        The tower's ``nominal_life_y``, ``use_class``, ``soil_class``, ``topography``.

    Returns
    -------
    HazardResult
        The site hazard, the categories used and every assumption stated.

    Raises
    ------
    HazardError
        For a site off the grid or an invalid value.
    """
    inventory = inventory or {}
    assumptions: list[str] = []
    if return_period_y is not None and limit_state is not None:
        raise HazardError("give a return period or a limit state, not both")
    vn = uc = None
    if return_period_y is None:
        limit_state = (limit_state or "SLV").upper()
        vn, uc = nominal_life_y, use_class
        for key, label in (("nominal_life_y", "nominal life"), ("use_class", "use class")):
            if (vn if key == "nominal_life_y" else uc) is None:
                value = inventory.get(key)
                if value is None:
                    value = TOWER_DEFAULTS[key]
                    assumptions.append(
                        f"{label} not given: {value} for a church bell tower (NTC 2018 §2.4)"
                    )
                vn, uc = (value, uc) if key == "nominal_life_y" else (vn, value)
        tr = limit_state_return_period(limit_state, vn, uc)
        if tr < RETURN_PERIODS_Y[0]:
            assumptions.append(
                f"TR={tr:.1f} y of {limit_state} is below the tabulated 30 y: the 30-y hazard "
                "is used (higher, on the safe side; Allegato A has no shorter TR)"
            )
        site = site_hazard(lon_deg, lat_deg, tr, out_of_range="clamp" if tr < 30 else "refuse")
    else:
        site = site_hazard(lon_deg, lat_deg, return_period_y)
    categories: dict[str, str] = {}
    for key, label, given in (
        ("soil_class", "soil class", soil_class),
        ("topography", "topography", topography),
    ):
        value, source = _category(
            given, inventory.get(key), TOWER_DEFAULTS[key], label, assumptions
        )
        categories[key], categories[f"{key}_source"] = value, source
    return HazardResult(
        site=site,
        spectrum=spectrum_parameters(
            site, categories["soil_class"], categories["topography"], damping
        ),
        limit_state=limit_state if return_period_y is None else None,
        nominal_life_y=None if vn is None else float(vn),
        use_class=uc,
        damping=float(damping),
        assumptions=tuple(assumptions),
        **categories,
    )


def tower_hazard(tower, **options) -> HazardResult:
    """Return the hazard at an inventory tower (:class:`rockscreen.stations.inventory.Tower`).

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        A tower with coordinates; its hazard columns are used unless overridden.
    **options
        Keyword arguments of :func:`resolve_hazard` (an option given overrides the
        inventory).

    Returns
    -------
    HazardResult
        As :func:`resolve_hazard` returns it, with the tower's inventory columns.

    Raises
    ------
    HazardError
        If the tower has no coordinates, or as :func:`resolve_hazard`.
    """
    if not tower.has_coordinates:
        raise HazardError(f"tower {tower.id!r} has no lat/lon: its code hazard is unknown")
    inventory = {
        key: getattr(tower, key)
        for key in ("nominal_life_y", "use_class", "soil_class", "topography")
    }
    return resolve_hazard(tower.lon, tower.lat, inventory=inventory, **options)
