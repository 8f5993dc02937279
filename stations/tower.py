"""One tower of the inventory and the rules its values obey.

:class:`Tower` validates itself on construction; :mod:`rockscreen.stations.inventory` reads
and writes towers as CSV and :mod:`rockscreen.stations.inventory_table` turns them into the
archive's structured array. The rules are listed in ``docs/inventory.md``.
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass

from rockscreen.stations.errors import InventoryValueError
from rockscreen.stations.inventory_columns import (
    BELFRY_GROUP,
    CATEGORIES,
    COLUMNS,
    DOUBLE_BLOCK_GROUP,
    FLOOR_GROUP,
    GABLE_GROUP,
    LV1_COLUMNS,
    MEASURED_STRENGTH_COLUMN,
    PLAUSIBLE_RANGES,
    TESTED_KNOWLEDGE_LEVEL,
    TEXT_COLUMNS,
    WALL_TOP_COLUMN,
)

__all__ = ["ITALY_LAT_DEG", "ITALY_LON_DEG", "Tower", "swapped_hint"]

# SEED network and station codes: letters, digits, '-' or '_' (a NET.STA key or a bare STA).
_STATION_PATTERN = re.compile(r"^[A-Za-z0-9_\-]{1,8}(\.[A-Za-z0-9_\-]{1,8})?$")


@dataclass(frozen=True)
class Tower:
    """One tower of an inventory; every value is validated on construction.

    Raises
    ------
    InventoryError
        When a value breaks a rule (the message names tower, column, value and rule).
    """

    #: Unique identifier.
    id: str
    #: Full base width 2b of the rocking block along the tower's x axis [m].
    width_m: float
    #: Full height 2h of the rocking block (the tower above its springing) [m].
    height_m: float
    #: Free text.
    name: str = ""
    #: Municipality and province (text; :data:`AREA_COLUMNS`): counts per class per area.
    comune: str = ""
    provincia: str = ""
    #: WGS84 coordinates [deg]; both or neither.
    lat: float | None = None
    lon: float | None = None
    #: Direction of the x (width) axis, clockwise from north [deg], in [0, 360).
    azimuth_deg: float | None = None
    #: Second plan dimension, along y [m]; the plan is square when None.
    depth_m: float | None = None
    #: Angular-velocity restitution coefficient [-] in (0, 1]; None lets the solver use Housner's 1
    #: - 1.5 sin^2(alpha).
    eta: float | None = None
    #: Masses of the rocking block and of the building [kg] (double-block model).
    tower_mass_kg: float | None = None
    building_mass_kg: float | None = None
    #: Static and kinetic friction coefficients of the building foundation [-].
    mu_s: float | None = None
    mu_k: float | None = None
    #: Height of the building [m] (floor model).
    building_height_m: float | None = None
    #: Height of the tower's springing on the building [m], <= building_height_m.
    base_height_m: float | None = None
    #: Fundamental period of the building [s]; needs building_height_m.
    building_period_s: float | None = None
    #: Height of the belfry (the bell cell) above the top of the shaft [m] (belfry model).
    belfry_height_m: float | None = None
    #: Effective base width of the belfry's piers along x [m].
    belfry_width_m: float | None = None
    #: Effective base width of the belfry's piers along y [m]; ``belfry_width_m`` when None.
    belfry_depth_m: float | None = None
    #: Mass of the belfry's piers and arches [kg].
    belfry_mass_kg: float | None = None
    #: Mass of the bells and their frame [kg], >= 0.
    bells_mass_kg: float | None = None
    #: Height of the bells above the belfry's base [m], in [0, belfry_height_m].
    bells_height_m: float | None = None
    #: First period of the tower (shaft and belfry), measured [s]; None: estimated from
    #: ``height_m`` (``docs/belfry.md``).
    shaft_period_s: float | None = None
    #: Wall thickness of the shaft [m] (LV1 tower model); at its base when
    #: ``wall_thickness_top_m`` is given.
    wall_thickness_m: float | None = None
    #: Wall thickness of the shaft at its top, below the belfry [m] (LV1 tower model: walls
    #: tapering linearly from ``wall_thickness_m``); None: a prismatic shaft.
    wall_thickness_top_m: float | None = None
    #: Masonry type of Circolare 2019 Table C8.5.I (LV1 tower model).
    masonry_type: str | None = None
    #: Mean compressive strength f_m of the masonry from tests [MPa] (Circolare 2019
    #: §C8.5.4.1); the LV1 model uses it at knowledge level LC3 only.
    masonry_strength_mpa: float | None = None
    #: Knowledge level ``"LC1"``-``"LC3"`` (Circolare 2019 §C8.5.4); None: the run's.
    knowledge_level: str | None = None
    #: Bell gable (vela): height above its base, width in its plane, thickness [m].
    gable_height_m: float | None = None
    gable_width_m: float | None = None
    gable_thickness_m: float | None = None
    #: Height of the gable's base above the ground [m] (0: on the ground).
    gable_base_height_m: float | None = None
    #: Mass of the gable's bells [kg] (None: 0).
    gable_bells_mass_kg: float | None = None
    #: Share of the gable's elevation taken by its openings [-] (None: 0).
    gable_opening_ratio: float | None = None
    #: The tower axis normal to the gable's plane, ``"x"`` or ``"y"``
    #: (:data:`rockscreen.stations.inventory_columns.TOWER_AXES`):
    #: the direction in which it overturns out of its plane; None: not known.
    gable_axis: str | None = None
    #: Explicit pairing with a record station, ``"NET.STA"`` or ``"STA"``.
    station: str | None = None
    #: Nominal life V_N [years] (NTC 2018 §2.4.1); None: the hazard default.
    nominal_life_y: float | None = None
    #: Use class ``"I"``-``"IV"`` (NTC 2018 §2.4.2); None: the hazard default.
    use_class: str | None = None
    #: Subsoil category ``"A"``-``"E"`` (NTC 2018 Tab. 3.2.II); None: unknown (the hazard assumes A
    #: and says so).
    soil_class: str | None = None
    #: Topographic category ``"T1"``-``"T4"`` (NTC 2018 Tab. 3.2.III); None: unknown.
    topography: str | None = None

    def __post_init__(self) -> None:
        _validate(self)

    @property
    def plan_depth_m(self) -> float:
        """Plan dimension along the y axis [m] (``depth_m``, or ``width_m`` when square)."""
        return self.width_m if self.depth_m is None else self.depth_m

    @property
    def belfry_plan_depth_m(self) -> float | None:
        """Belfry piers' width along y [m] (``belfry_depth_m``, else ``belfry_width_m``)."""
        return self.belfry_width_m if self.belfry_depth_m is None else self.belfry_depth_m

    @property
    def has_belfry(self) -> bool:
        """Whether the belfry's geometry and masses for the belfry model are given."""
        return all(getattr(self, name) is not None for name in BELFRY_GROUP)

    @property
    def has_gable(self) -> bool:
        """Whether the bell gable's geometry is given (the gable check)."""
        return all(getattr(self, name) is not None for name in GABLE_GROUP)

    @property
    def lv1_missing(self) -> tuple[str, ...]:
        """Return the LV1 tower model's columns this tower lacks (empty: it can be made)."""
        return tuple(name for name in LV1_COLUMNS if getattr(self, name) is None)

    @property
    def has_coordinates(self) -> bool:
        """Whether latitude and longitude are known."""
        return self.lat is not None and self.lon is not None

    @property
    def has_floor_model(self) -> bool:
        """Whether building data for the floor-motion model are given."""
        return self.building_height_m is not None

    @property
    def has_double_block(self) -> bool:
        """Whether masses and foundation friction for the double-block model are given."""
        return all(getattr(self, name) is not None for name in DOUBLE_BLOCK_GROUP)


def _validate(tower: Tower) -> None:
    """Check every rule on a tower; raise :class:`InventoryValueError` at the first broken one."""
    tid = tower.id

    def fail(column: str, rule: str) -> None:
        raise InventoryValueError(tid, column, getattr(tower, column), rule)

    if not isinstance(tid, str) or not tid.strip():
        raise InventoryValueError("", "id", tid, "must be non-empty text")
    for column in COLUMNS:
        value = getattr(tower, column)
        if column in TEXT_COLUMNS or value is None:
            continue
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            fail(column, "must be a number")
        if not math.isfinite(value):
            fail(column, "must be a finite number (not NaN or infinity)")
    for column in (
        "width_m",
        "height_m",
        "depth_m",
        "tower_mass_kg",
        "building_mass_kg",
        "mu_s",
        "mu_k",
        "building_height_m",
        "building_period_s",
        "nominal_life_y",
        "belfry_height_m",
        "belfry_width_m",
        "belfry_depth_m",
        "belfry_mass_kg",
        "shaft_period_s",
        "wall_thickness_m",
        "wall_thickness_top_m",
        "masonry_strength_mpa",
        "gable_height_m",
        "gable_width_m",
        "gable_thickness_m",
    ):
        value = getattr(tower, column)
        if value is not None and value <= 0:
            fail(column, "must be > 0")
    for column, (low, high, unit) in PLAUSIBLE_RANGES.items():
        value = getattr(tower, column)
        if value is not None and not low <= value <= high:
            fail(
                column,
                f"is not plausible for a bell tower: allowed {low:g} to {high:g} {unit} "
                "(check the units)",
            )
    for column in ("id", "name", "comune", "provincia", "station"):
        value = getattr(tower, column)
        if isinstance(value, str) and any(ord(c) < 32 or 127 <= ord(c) < 160 for c in value):
            fail(column, "must not contain control characters")
    if tower.lat is not None and not -90.0 <= tower.lat <= 90.0:
        fail("lat", "must be in [-90, 90] deg")
    if tower.lon is not None and not -180.0 <= tower.lon <= 180.0:
        fail("lon", "must be in [-180, 180] deg")
    if (tower.lat is None) != (tower.lon is None):
        missing = "lon" if tower.lon is None else "lat"
        raise InventoryValueError(tid, missing, "", "is missing: give both lat and lon, or neither")
    if tower.azimuth_deg is not None and not 0.0 <= tower.azimuth_deg < 360.0:
        fail("azimuth_deg", "must be in [0, 360) deg")
    if tower.eta is not None and not 0.0 < tower.eta <= 1.0:
        fail("eta", "must be in (0, 1]")
    _check_group(tower, DOUBLE_BLOCK_GROUP, "the double-block model")
    if tower.mu_s is not None and tower.mu_k is not None and tower.mu_k > tower.mu_s:
        fail("mu_k", f"must not exceed mu_s={tower.mu_s:g}")
    _check_group(tower, FLOOR_GROUP, "the floor model")
    if tower.base_height_m is not None:
        if tower.base_height_m < 0:
            fail("base_height_m", "must be >= 0")
        if tower.base_height_m > tower.building_height_m:
            fail(
                "base_height_m",
                f"must not exceed building_height_m={tower.building_height_m:g}",
            )
    if tower.building_period_s is not None and tower.building_height_m is None:
        fail("building_period_s", "needs building_height_m and base_height_m (floor model)")
    _check_belfry(tower, fail)
    _check_group(tower, GABLE_GROUP, "the bell-gable check")
    for column in ("gable_bells_mass_kg", "gable_opening_ratio", "gable_axis"):
        if getattr(tower, column) is not None and not tower.has_gable:
            fail(column, f"needs the bell gable's columns ({', '.join(GABLE_GROUP)})")
    if tower.station is not None and not _STATION_PATTERN.match(tower.station):
        fail("station", "must be 'NET.STA' or 'STA' (letters, digits, '-' or '_')")
    if not isinstance(tower.name, str):
        fail("name", "must be text")
    for column, allowed in CATEGORIES.items():
        value = getattr(tower, column)
        if value is not None and value not in allowed:
            fail(column, f"must be one of {', '.join(allowed)} (allowed values)")
    _check_measured_strength(tower, fail)
    _check_wall_top(tower, fail)


def _check_wall_top(tower: Tower, fail: Callable[[str, str], None]) -> None:
    """Check the shaft's wall thickness at its top: it needs the base's, and fits the shaft.

    A top wall thicker than the base's is refused (a tower's walls thin upwards: the two
    columns swapped, most likely), and so is one over half the smaller plan dimension (a
    wall of half of it already fills a solid section).
    """
    top = tower.wall_thickness_top_m
    if top is None:
        return
    base = tower.wall_thickness_m
    if base is None:
        fail(
            WALL_TOP_COLUMN,
            "needs wall_thickness_m, the wall thickness at the shaft's base (the LV1 model "
            "tapers the walls linearly from it to wall_thickness_top_m)",
        )
    if top > base:
        fail(
            WALL_TOP_COLUMN,
            f"must not exceed wall_thickness_m={base:g} m, the thickness at the base "
            "(allowed: 0.1 m up to it; the walls of a tower thin upwards: the two columns "
            "swapped?)",
        )
    half = 0.5 * min(tower.width_m, tower.plan_depth_m)
    if top > half:
        fail(
            WALL_TOP_COLUMN,
            f"must not exceed half the smaller plan dimension, {half:g} m (allowed: 0.1 m up "
            "to it: a wall of half the plan fills a solid section)",
        )


def _check_measured_strength(tower: Tower, fail: Callable[[str, str], None]) -> None:
    """Check a measured f_m: it needs the masonry type and is refused at LC1 and LC2."""
    if tower.masonry_strength_mpa is None:
        return
    if tower.masonry_type is None:
        fail(
            MEASURED_STRENGTH_COLUMN,
            "needs masonry_type (the LV1 model takes the unit weight from Table C8.5.I)",
        )
    level = tower.knowledge_level
    if level is not None and level != TESTED_KNOWLEDGE_LEVEL:
        fail(
            MEASURED_STRENGTH_COLUMN,
            f"is a measured f_m, used only at knowledge_level {TESTED_KNOWLEDGE_LEVEL} "
            f"(Circolare 2019 §C8.5.4.1); this row's knowledge_level {level} takes Table "
            f"C8.5.I's value: set {TESTED_KNOWLEDGE_LEVEL} or leave {MEASURED_STRENGTH_COLUMN} "
            "empty",
        )


def _check_belfry(tower: Tower, fail: Callable[[str, str], None]) -> None:
    """Check the belfry group: all or none, and a belfry that fits on its tower."""
    _check_group(tower, BELFRY_GROUP, "the belfry model")
    for column in ("belfry_depth_m",):
        if getattr(tower, column) is not None and not tower.has_belfry:
            fail(column, f"needs the belfry model's columns ({', '.join(BELFRY_GROUP)})")
    if not tower.has_belfry:
        return
    if not 0.0 <= tower.bells_height_m <= tower.belfry_height_m:
        fail("bells_height_m", f"must lie in [0, belfry_height_m={tower.belfry_height_m:g}]")
    if tower.belfry_height_m >= tower.height_m:
        fail("belfry_height_m", f"must be less than height_m={tower.height_m:g} (it tops a shaft)")
    if tower.belfry_width_m > tower.width_m:
        fail("belfry_width_m", f"must not exceed width_m={tower.width_m:g}")
    if tower.belfry_plan_depth_m > tower.plan_depth_m:
        column = "belfry_width_m" if tower.belfry_depth_m is None else "belfry_depth_m"
        fail(column, f"must not exceed the tower's plan depth {tower.plan_depth_m:g} (along y)")


def _check_group(tower: Tower, group: Sequence[str], purpose: str) -> None:
    """Columns that only make sense together: all given or none."""
    given = [name for name in group if getattr(tower, name) is not None]
    if given and len(given) < len(group):
        missing = [name for name in group if getattr(tower, name) is None]
        raise InventoryValueError(
            tower.id,
            missing[0],
            "",
            f"is missing: {purpose} needs all of {', '.join(group)} "
            f"(given: {', '.join(given)}; leave all empty to skip it)",
        )


#: Italy's bounding box [deg]: lat 35.2-47.1 (Lampedusa to Vetta d'Italia), lon 6.6-18.6
#: (Monginevro to Otranto), islands included; the screening's hazard grid covers it.
ITALY_LAT_DEG = (35.2, 47.1)
ITALY_LON_DEG = (6.6, 18.6)


def swapped_hint(lat_deg: float | None, lon_deg: float | None) -> str:
    """Return ``" (lat/lon swapped?)"`` when a point is outside Italy but its swap is inside.

    Parameters
    ----------
    lat_deg, lon_deg : float or None
        The point as given [deg].

    Returns
    -------
    str
        The hint to append to a message, or ``""`` (no coordinates, inside Italy, or the
        swapped point is outside Italy too).
    """

    def inside(lat: float, lon: float) -> bool:
        return (
            ITALY_LAT_DEG[0] <= lat <= ITALY_LAT_DEG[1]
            and ITALY_LON_DEG[0] <= lon <= ITALY_LON_DEG[1]
        )

    if lat_deg is None or lon_deg is None:
        return ""
    if not (math.isfinite(lat_deg) and math.isfinite(lon_deg)):
        return ""
    if inside(lat_deg, lon_deg) or not inside(lon_deg, lat_deg):
        return ""
    return f" (lat/lon swapped? lat={lon_deg:g}, lon={lat_deg:g} would be in Italy)"
