"""The tower inventory's columns: units, meanings, groups, categories and plausible ranges."""

from __future__ import annotations

#: Column name -> (unit, meaning), in the order :func:`write_inventory` writes them.
COLUMNS: dict[str, tuple[str, str]] = {
    "id": ("-", "unique tower identifier (text)"),
    "name": ("-", "free text"),
    "comune": ("-", "municipality (text): assess and scenario count the towers per class in it"),
    "provincia": ("-", "province (text, e.g. 'AQ'): counts per class as for comune"),
    "lat": ("deg", "latitude, WGS84, in [-90, 90]"),
    "lon": ("deg", "longitude, WGS84, in [-180, 180]"),
    "azimuth_deg": ("deg", "direction of the tower's x (width) axis, clockwise from north"),
    "width_m": ("m", "full base width 2b of the rocking block along x, > 0"),
    "height_m": ("m", "full height 2h of the rocking block, > 0"),
    "depth_m": ("m", "second plan dimension (along y), > 0; square when absent"),
    "eta": ("-", "restitution coefficient of angular velocity, in (0, 1]"),
    "tower_mass_kg": ("kg", "mass of the rocking block, > 0"),
    "building_mass_kg": ("kg", "mass of the building (church complex), > 0"),
    "mu_s": ("-", "static friction coefficient of the building foundation, > 0"),
    "mu_k": ("-", "kinetic friction coefficient, > 0 and <= mu_s"),
    "building_height_m": ("m", "height of the building, > 0"),
    "base_height_m": ("m", "height of the tower's springing, in [0, building_height_m]"),
    "building_period_s": ("s", "fundamental period of the building, > 0"),
    "belfry_height_m": ("m", "height of the belfry above the top of the shaft, < height_m"),
    "belfry_width_m": ("m", "effective base width of the belfry's piers along x, <= width_m"),
    "belfry_depth_m": (
        "m",
        "effective base width of the belfry's piers along y, <= the plan depth; "
        "belfry_width_m when absent",
    ),
    "belfry_mass_kg": ("kg", "mass of the belfry's piers and arches, > 0"),
    "bells_mass_kg": ("kg", "mass of the bells and their frame, >= 0"),
    "bells_height_m": ("m", "height of the bells above the belfry's base, in [0, belfry_height_m]"),
    "shaft_period_s": (
        "s",
        "first period of the tower (measured), > 0; needs the belfry group; 0.0187 H when absent",
    ),
    "station": ("-", "explicit record station, 'NET.STA' or 'STA'"),
    "nominal_life_y": ("y", "nominal life V_N (NTC 2018 §2.4.1), > 0"),
    "use_class": ("-", "use class (NTC 2018 §2.4.2): I, II, III or IV"),
    "soil_class": ("-", "subsoil category (NTC 2018 Tab. 3.2.II): A, B, C, D or E"),
    "topography": ("-", "topographic category (NTC 2018 Tab. 3.2.III): T1, T2, T3 or T4"),
}

REQUIRED_COLUMNS: tuple[str, ...] = ("id", "width_m", "height_m")

#: Columns read as text (the others are numbers).
TEXT_COLUMNS = frozenset(
    {"id", "name", "comune", "provincia", "station", "use_class", "soil_class", "topography"}
)
#: Text columns that group towers by area (counts per class in assess and scenario).
AREA_COLUMNS: tuple[str, ...] = ("comune", "provincia")

#: Code categories of the hazard columns -> allowed values (upper case; read case-insensitively).
CATEGORIES: dict[str, tuple[str, ...]] = {
    "use_class": ("I", "II", "III", "IV"),
    "soil_class": ("A", "B", "C", "D", "E"),
    "topography": ("T1", "T2", "T3", "T4"),
}

#: Columns that only make sense together (the double-block model needs all four).
DOUBLE_BLOCK_GROUP: tuple[str, ...] = ("tower_mass_kg", "building_mass_kg", "mu_s", "mu_k")
#: The floor model needs the building height and the height of the springing.
FLOOR_GROUP: tuple[str, ...] = ("building_height_m", "base_height_m")
#: The belfry model needs the belfry's geometry, its mass and the bells' mass and height
#: (``belfry_depth_m`` and ``shaft_period_s`` are optional and need the group).
BELFRY_GROUP: tuple[str, ...] = (
    "belfry_height_m",
    "belfry_width_m",
    "belfry_mass_kg",
    "bells_mass_kg",
    "bells_height_m",
)


#: Plausible ranges of the numeric columns: a value outside is a unit slip (mm for m,
#: t for kg) or a typo, refused before anything is computed. Bell towers in the Italian
#: inventories range from small bell gables (~0.5 m wide) to tall campanili (~100 m).
PLAUSIBLE_RANGES: dict[str, tuple[float, float, str]] = {
    "width_m": (0.1, 100.0, "m"),
    "height_m": (0.5, 300.0, "m"),
    "depth_m": (0.1, 100.0, "m"),
    "tower_mass_kg": (0.0, 1.0e9, "kg"),
    "building_mass_kg": (0.0, 1.0e10, "kg"),
    "mu_s": (0.01, 5.0, ""),
    "mu_k": (0.01, 5.0, ""),
    "building_height_m": (1.0, 300.0, "m"),
    "building_period_s": (0.01, 20.0, "s"),
    # A belfry (cella campanaria) is a storey of a tower: metres, not tens of metres; its
    # piers and arches weigh tonnes to thousands of tonnes; the heaviest single bells
    # weigh a few tens of tonnes.
    "belfry_height_m": (0.5, 30.0, "m"),
    "belfry_width_m": (0.1, 50.0, "m"),
    "belfry_depth_m": (0.1, 50.0, "m"),
    "belfry_mass_kg": (100.0, 1.0e8, "kg"),
    "bells_mass_kg": (0.0, 1.0e6, "kg"),
    "bells_height_m": (0.0, 30.0, "m"),
    "shaft_period_s": (0.01, 20.0, "s"),
    "nominal_life_y": (1.0, 1000.0, "years"),
}
