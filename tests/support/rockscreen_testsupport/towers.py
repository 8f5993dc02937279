"""Sites and tower rows shared by test files (SI units, degrees).

:func:`belfry_tower` is the 6 m x 5 m brick tower, 36 m high, with a 6 m belfry that the
kinematic and shaft tests both start from; each test file adds the fields it needs (the
walls, the strength, the bells' mass). :func:`block_tower` is the rocking block of the
assess tests, given by its half-diagonal and slenderness; :func:`lv1_shaft_tower` the hollow
brick shaft of the LV1 tests.
"""

from __future__ import annotations

import math

from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.stations.inventory import Tower

#: L'Aquila, a high-hazard site inside the NTC 2018 grid: (lon, lat) [deg].
LAQUILA = (13.3995, 42.3498)
#: The L'Aquila site on soil B (NTC 2018 §3.2.2); topography, nominal life and use class
#: are the inventory defaults.
LAQUILA_SITE = SiteConditions(lon_deg=LAQUILA[0], lat_deg=LAQUILA[1], soil_class="B")


def belfry_tower(tower_id: str, **fields) -> Tower:
    """Return the brick tower with a belfry at L'Aquila, with ``fields`` added.

    Parameters
    ----------
    tower_id : str
        The row's ``id``.
    **fields
        Further :class:`~rockscreen.stations.inventory.Tower` fields (``bells_mass_kg``,
        ``wall_thickness_m``, ...); they may not repeat the ones set here.

    Returns
    -------
    Tower
        6 m x 5 m in plan, 36 m high, soil B, solid brick; belfry 6 m high on piers 1 m wide
        and 80 t, the bells hung 2 m above its base.
    """
    return Tower(
        id=tower_id,
        width_m=6.0,
        depth_m=5.0,
        height_m=36.0,
        lat=LAQUILA[1],
        lon=LAQUILA[0],
        soil_class="B",
        masonry_type="solid_brick",
        belfry_height_m=6.0,
        belfry_width_m=1.0,
        belfry_mass_kg=80000.0,
        bells_height_m=2.0,
        **fields,
    )


def block_tower(
    tower_id: str, radius_m: float, alpha_rad: float, site: tuple[float, float], **fields
) -> Tower:
    """Return a block of half-diagonal ``radius_m`` and slenderness ``alpha_rad`` at ``site``.

    Parameters
    ----------
    tower_id : str
        The row's ``id``.
    radius_m : float
        Half-diagonal R of the block [m].
    alpha_rad : float
        Slenderness angle, tan(alpha) = width / height [rad].
    site : tuple of float
        ``(lat, lon)`` [deg].
    **fields
        Further :class:`~rockscreen.stations.inventory.Tower` fields (a floor's or a
        building's data).

    Returns
    -------
    Tower
        ``width_m = 2 R sin(alpha)``, ``height_m = 2 R cos(alpha)``.
    """
    return Tower(
        id=tower_id,
        width_m=2 * radius_m * math.sin(alpha_rad),
        height_m=2 * radius_m * math.cos(alpha_rad),
        lat=site[0],
        lon=site[1],
        **fields,
    )


def lv1_shaft_tower(tower_id: str, *, lat: float, lon: float, **fields) -> Tower:
    """Return the hollow brick shaft of the LV1 tests at ``(lat, lon)``, with ``fields`` added.

    Parameters
    ----------
    tower_id : str
        The row's ``id``.
    lat, lon : float
        The site [deg].
    **fields
        Further :class:`~rockscreen.stations.inventory.Tower` fields (the knowledge level, a
        measured strength, a gable, a church below).

    Returns
    -------
    Tower
        4 m x 5 m in plan, 20 m high, walls 0.9 m thick, solid brick (the data LV1 needs).
    """
    return Tower(
        id=tower_id,
        width_m=4.0,
        height_m=20.0,
        depth_m=5.0,
        lat=lat,
        lon=lon,
        wall_thickness_m=0.9,
        masonry_type="solid_brick",
        **fields,
    )
