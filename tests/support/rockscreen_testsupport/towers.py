"""The L'Aquila site and tower rows shared by the uncertainty tests (SI units, degrees).

:func:`belfry_tower` is the 6 m x 5 m brick tower, 36 m high, with a 6 m belfry that the
kinematic and shaft tests both start from; each test file adds the fields it needs (the
walls, the strength, the bells' mass).
"""

from __future__ import annotations

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
