"""The tower inventory's columns: units, meanings, groups, categories and plausible ranges."""

from __future__ import annotations

#: Masonry types of Circolare 2019 Table C8.5.I (§C8.5.3.1, PDF p. 261; docs/code_checks.md
#: §4) the inventory accepts -> their mean unit weight w [kN/m3], in the table's order. The
#: one source of the unit weights: the code checks' ``MASONRY_TYPES`` (with their strengths
#: and moduli) and the bell-gable model read it here. Both soft-stone rows share the table's
#: cell "13 ÷ 16" (note (**): very variable, measure it): 16, the heavier end, the safe side
#: of the LV1 crushing term sigma0 = w H.
MASONRY_UNIT_WEIGHTS_KN_M3: dict[str, float] = {
    "rubble": 19.0,
    "roughly_cut_stone": 20.0,
    "split_stone": 21.0,
    "soft_stone": 16.0,
    "regular_soft_stone": 16.0,
    "dressed_stone": 22.0,
    "solid_brick": 18.0,
    "semi_solid_brick": 15.0,
}
#: The masonry types' names, in the table's order.
MASONRY_TYPE_NAMES: tuple[str, ...] = tuple(MASONRY_UNIT_WEIGHTS_KN_M3)
#: Masonry type assumed when a row has none (where a mass must be estimated; stated).
ASSUMED_MASONRY_TYPE = "rubble"

#: The tower's plan axes, as every table and the case engine spell them: ``x`` along
#: ``width_m`` (its direction is ``azimuth_deg``), ``y`` along the plan depth ``depth_m``
#: (90 degrees clockwise from x). The components of a motion along them are labelled in
#: upper case (``X``, ``Y``: :data:`rockscreen.pipeline.vocabulary.ROTATED_COMPONENTS`).
TOWER_AXES: tuple[str, ...] = ("x", "y")

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
        "first period of the tower (measured), > 0; 0.0187 H when absent",
    ),
    "wall_thickness_m": (
        "m",
        "wall thickness of the shaft (LV1 tower model), > 0; a solid section when it reaches "
        "half the smaller plan dimension; the thickness at the base when "
        "wall_thickness_top_m is given",
    ),
    "wall_thickness_top_m": (
        "m",
        "wall thickness of the shaft at its top, below the belfry (LV1 tower model: walls "
        "tapering linearly from wall_thickness_m at the base), in (0, wall_thickness_m], at "
        "most half the smaller plan dimension; needs wall_thickness_m; a prismatic shaft of "
        "wall_thickness_m when absent",
    ),
    "masonry_type": (
        "-",
        "masonry type of Circolare 2019 Table C8.5.I (LV1 tower model): "
        + ", ".join(MASONRY_TYPE_NAMES),
    ),
    "masonry_strength_mpa": (
        "MPa",
        "mean compressive strength f_m of the shaft's masonry from tests (Circolare 2019 "
        "§C8.5.4.1), in [0.3, 20]; used by the LV1 tower model at knowledge level LC3 only "
        "(refused with LC1 or LC2); needs masonry_type",
    ),
    "knowledge_level": (
        "-",
        "knowledge level (Circolare 2019 §C8.5.4): LC1, LC2 or LC3; --knowledge-level when absent",
    ),
    "gable_height_m": ("m", "height of the bell gable (vela) above its base, > 0"),
    "gable_width_m": ("m", "width of the bell gable in its own plane, > 0"),
    "gable_thickness_m": ("m", "thickness of the bell gable (out of its plane), > 0"),
    "gable_base_height_m": ("m", "height of the bell gable's base above the ground, >= 0"),
    "gable_bells_mass_kg": ("kg", "mass of the gable's bells and their frame, >= 0; 0 when absent"),
    "gable_opening_ratio": (
        "-",
        "share of the gable's elevation taken by its bell openings, in [0, 0.8]; 0 when absent",
    ),
    "gable_axis": (
        "-",
        "the tower axis normal to the gable's plane (its out-of-plane direction): x or y; "
        "its thickness in every direction when absent",
    ),
    "station": ("-", "explicit record station, 'NET.STA' or 'STA'"),
    "nominal_life_y": ("y", "nominal life V_N (NTC 2018 §2.4.1), > 0"),
    "use_class": ("-", "use class (NTC 2018 §2.4.2): I, II, III or IV"),
    "soil_class": ("-", "subsoil category (NTC 2018 Tab. 3.2.II): A, B, C, D or E"),
    "topography": ("-", "topographic category (NTC 2018 Tab. 3.2.III): T1, T2, T3 or T4"),
}

REQUIRED_COLUMNS: tuple[str, ...] = ("id", "width_m", "height_m")

#: Text columns that group towers by area (counts per class in assess and scenario).
AREA_COLUMNS: tuple[str, ...] = ("comune", "provincia")

#: Columns read as text (the others are numbers).
TEXT_COLUMNS = frozenset(
    {
        "id",
        "name",
        "comune",
        "provincia",
        "station",
        "use_class",
        "soil_class",
        "topography",
        "masonry_type",
        "knowledge_level",
        "gable_axis",
    }
)

#: Code categories -> allowed values (read case-insensitively, stored as spelled here).
CATEGORIES: dict[str, tuple[str, ...]] = {
    "use_class": ("I", "II", "III", "IV"),
    "soil_class": ("A", "B", "C", "D", "E"),
    "topography": ("T1", "T2", "T3", "T4"),
    "masonry_type": MASONRY_TYPE_NAMES,
    "knowledge_level": ("LC1", "LC2", "LC3"),
    "gable_axis": TOWER_AXES,
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

#: The bell-gable check needs the gable's height, width, thickness and the height of its
#: base (``gable_bells_mass_kg``, ``gable_opening_ratio`` and ``gable_axis`` are optional and
#: need the group).
GABLE_GROUP: tuple[str, ...] = (
    "gable_height_m",
    "gable_width_m",
    "gable_thickness_m",
    "gable_base_height_m",
)
#: The LV1 tower model needs these columns (it is not made, with a note, without them).
LV1_COLUMNS: tuple[str, ...] = ("wall_thickness_m", "masonry_type")
#: The shaft's wall thickness at its top (optional; needs ``wall_thickness_m``, then the
#: thickness at the base): the LV1 model tapers the walls linearly between the two.
WALL_TOP_COLUMN = "wall_thickness_top_m"
#: The measured masonry strength, used at knowledge level LC3 only (the LV1 model at LC3
#: needs it; Circolare 2019 §C8.5.4.1): LC1 and LC2 take Table C8.5.I's value.
MEASURED_STRENGTH_COLUMN = "masonry_strength_mpa"
#: The knowledge level that rests on tests (Circolare 2019 §C8.5.4: FC = 1).
TESTED_KNOWLEDGE_LEVEL = "LC3"


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
    # Shaft walls of Italian towers: tens of centimetres to a few metres at the base.
    "wall_thickness_m": (0.1, 10.0, "m"),
    "wall_thickness_top_m": (0.1, 10.0, "m"),
    # Mean compressive strength of masonry from tests: Table C8.5.I spans 1.0-8.2 MPa; tests
    # on poor rubble give less, on good brick or dressed stone more. Outside 0.3-20 MPa the
    # value is in another unit (kPa, Pa, kg/cm2) or a typo.
    "masonry_strength_mpa": (0.3, 20.0, "MPa"),
    # Bell gables (vele): a few metres high and wide, tens of centimetres thick.
    "gable_height_m": (0.5, 30.0, "m"),
    "gable_width_m": (0.2, 30.0, "m"),
    "gable_thickness_m": (0.1, 5.0, "m"),
    "gable_base_height_m": (0.0, 300.0, "m"),
    "gable_bells_mass_kg": (0.0, 1.0e5, "kg"),
    "gable_opening_ratio": (0.0, 0.8, ""),
}
