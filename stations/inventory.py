"""The tower inventory: a CSV file of towers with units in the column names.

One row per tower. The rocking block is the tower above its springing (the belfry or
the free-standing upper shaft); ``width_m`` is its full base width 2b along the
tower's x axis and ``height_m`` its full height 2h. Optional columns add a location,
an orientation, the second plan dimension, the restitution coefficient, the data of
the double-block model (tower and building masses, foundation friction) and the
data of the floor model (building height, height of the springing, building period).

Every value is checked when read; an error names the file, the data row (1-based,
blank lines not counted), the line of the file, the column, the value and the rule
(see ``docs/inventory.md``).
"""

from __future__ import annotations

import csv
import difflib
import io
import math
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

from rockscreen.stations.errors import InventoryError
from rockscreen.stations.inventory_columns import (
    _CATEGORIES,
    _DOUBLE_BLOCK_GROUP,
    _FLOOR_GROUP,
    _TEXT_COLUMNS,
    COLUMNS,
    PLAUSIBLE_RANGES,
    REQUIRED_COLUMNS,
)
from rockscreen.stations.inventory_table import inventory_table

__all__ = [
    "COLUMNS",
    "REQUIRED_COLUMNS",
    "Tower",
    "example_inventory_path",
    "inventory_table",
    "read_inventory",
    "write_inventory",
]

# A number written with a decimal comma: 12,5 or -0,25 or 1,5e3 (';'-separated files only).
_DECIMAL_COMMA = re.compile(r"^[-+]?\d*,\d+([eE][-+]?\d+)?$")

# SEED network and station codes: letters, digits, '-' or '_' (a NET.STA key or a bare STA).
_STATION_PATTERN = re.compile(r"^[A-Za-z0-9_\-]{1,8}(\.[A-Za-z0-9_\-]{1,8})?$")


class _FieldError(InventoryError):
    """A rule broken by one value of a tower; carries the column for row/column messages."""

    def __init__(self, tower_id: str, column: str, value: object, rule: str):
        self.tower_id = tower_id
        self.column = column
        self.value = value
        self.rule = rule
        super().__init__(self.detail)

    @property
    def detail(self) -> str:
        """Describe the broken rule without file or row (``tower 'X', column 'c': ...``)."""
        who = f"tower {self.tower_id!r}, " if self.tower_id else ""
        return f"{who}column {self.column!r}: value {_show(self.value)} {self.rule}"


def _show(value: object) -> str:
    """Format a value for a message: text quoted, numbers as written."""
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)


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
        return all(getattr(self, name) is not None for name in _DOUBLE_BLOCK_GROUP)


def _validate(tower: Tower) -> None:
    """Check every rule on a tower; raise :class:`_FieldError` at the first broken one."""
    tid = tower.id

    def fail(column: str, rule: str) -> None:
        raise _FieldError(tid, column, getattr(tower, column), rule)

    if not isinstance(tid, str) or not tid.strip():
        raise _FieldError("", "id", tid, "must be non-empty text")
    for column in COLUMNS:
        value = getattr(tower, column)
        if column in _TEXT_COLUMNS or value is None:
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
    for column in ("id", "name", "station"):
        value = getattr(tower, column)
        if isinstance(value, str) and any(ord(c) < 32 or 127 <= ord(c) < 160 for c in value):
            fail(column, "must not contain control characters")
    if tower.lat is not None and not -90.0 <= tower.lat <= 90.0:
        fail("lat", "must be in [-90, 90] deg")
    if tower.lon is not None and not -180.0 <= tower.lon <= 180.0:
        fail("lon", "must be in [-180, 180] deg")
    if (tower.lat is None) != (tower.lon is None):
        missing = "lon" if tower.lon is None else "lat"
        raise _FieldError(tid, missing, "", "is missing: give both lat and lon, or neither")
    if tower.azimuth_deg is not None and not 0.0 <= tower.azimuth_deg < 360.0:
        fail("azimuth_deg", "must be in [0, 360) deg")
    if tower.eta is not None and not 0.0 < tower.eta <= 1.0:
        fail("eta", "must be in (0, 1]")
    _check_group(tower, _DOUBLE_BLOCK_GROUP, "the double-block model")
    if tower.mu_s is not None and tower.mu_k is not None and tower.mu_k > tower.mu_s:
        fail("mu_k", f"must not exceed mu_s={tower.mu_s:g}")
    _check_group(tower, _FLOOR_GROUP, "the floor model")
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
    if tower.station is not None and not _STATION_PATTERN.match(tower.station):
        fail("station", "must be 'NET.STA' or 'STA' (letters, digits, '-' or '_')")
    if not isinstance(tower.name, str):
        fail("name", "must be text")
    for column, allowed in _CATEGORIES.items():
        value = getattr(tower, column)
        if value is not None and value not in allowed:
            fail(column, f"must be one of {', '.join(allowed)}")


def _check_group(tower: Tower, group: Sequence[str], purpose: str) -> None:
    """Columns that only make sense together: all given or none."""
    given = [name for name in group if getattr(tower, name) is not None]
    if given and len(given) < len(group):
        missing = [name for name in group if getattr(tower, name) is None]
        raise _FieldError(
            tower.id,
            missing[0],
            "",
            f"is missing: {purpose} needs all of {', '.join(group)} "
            f"(given: {', '.join(given)}; leave all empty to skip it)",
        )


def read_inventory(path: str | Path) -> list[Tower]:
    """Read and validate a tower inventory CSV.

    Parameters
    ----------
    path : str or Path
        CSV file, UTF-8 (a byte-order mark is accepted), one header row with the column
        names of :data:`COLUMNS`; blank lines are ignored. Comma-separated, or
        semicolon-separated as Italian Excel writes it: the delimiter is the one of ``,``
        and ``;`` that the header line holds more of, and with ``;`` numbers may use a
        decimal comma (``12,5``).

    Returns
    -------
    list of Tower
        The towers in file order.

    Raises
    ------
    InventoryError
        On the first invalid header, row or value; the message names the file, the
        data row (1-based) and line, the column, the value and the rule. An inventory
        without towers is an error.
    """
    path = Path(path)
    try:
        with path.open(newline="", encoding="utf-8-sig") as handle:
            text = handle.read()
        delimiter = _sniff_delimiter(text)
        rows = list(_numbered_rows(csv.reader(io.StringIO(text, newline=""), delimiter=delimiter)))
    except UnicodeDecodeError as exc:
        raise InventoryError(f"{path}: not UTF-8 text ({exc.reason})") from exc
    except csv.Error as exc:
        raise InventoryError(f"{path}: not a valid CSV file ({exc})") from exc
    except OSError as exc:
        raise InventoryError(f"{path}: cannot read the inventory ({exc.strerror})") from exc
    if not rows:
        raise InventoryError(f"{path}: the inventory is empty (no header row)")
    header_line, header = rows[0]
    columns = _check_header(path, header_line, header)
    towers: list[Tower] = []
    first_row_of: dict[str, tuple[int, int]] = {}
    for number, (line, cells) in enumerate(rows[1:], start=1):
        where = f"{path}: row {number} (line {line})"
        if len(cells) != len(columns):
            raise InventoryError(
                f"{where}: has {len(cells)} fields, the header has {len(columns)} columns"
            )
        values = dict(zip(columns, (cell.strip() for cell in cells), strict=True))
        try:
            tower = Tower(**_parse_row(values, decimal_comma=delimiter == ";"))
        except _FieldError as exc:
            raise InventoryError(f"{where}, {exc.detail}") from exc
        if tower.id in first_row_of:
            first, first_line = first_row_of[tower.id]
            raise InventoryError(
                f"{where}, column 'id': value {tower.id!r} is a duplicate "
                f"(first used in row {first}, line {first_line}); ids must be unique"
            )
        first_row_of[tower.id] = (number, line)
        towers.append(tower)
    if not towers:
        raise InventoryError(f"{path}: the inventory has a header but no towers")
    return towers


def _sniff_delimiter(text: str) -> str:
    """Return ``";"`` when the first non-blank line holds more semicolons than commas."""
    header = next((line for line in text.splitlines() if line.strip()), "")
    return ";" if header.count(";") > header.count(",") else ","


def _numbered_rows(reader: Iterable[list[str]]) -> Iterable[tuple[int, list[str]]]:
    """Yield (line number, cells) of the non-blank rows; the line is where the row starts."""
    line = 1
    for cells in reader:
        start = line
        line = reader.line_num + 1  # type: ignore[attr-defined]
        if any(cell.strip() for cell in cells):
            yield start, cells


def _check_header(path: Path, line: int, header: list[str]) -> list[str]:
    """Return the stripped column names; refuse unknown, duplicate or missing columns."""
    columns = [name.strip() for name in header]
    seen: set[str] = set()
    for position, name in enumerate(columns, start=1):
        where = f"{path}: header (line {line}), column {position}"
        if not name:
            raise InventoryError(f"{where}: empty column name")
        if name in seen:
            raise InventoryError(f"{where}: column {name!r} appears twice")
        seen.add(name)
        if name not in COLUMNS:
            close = difflib.get_close_matches(name, list(COLUMNS), n=1, cutoff=0.6)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            for other, label in ((";", "';'"), ("\t", "a tab"), (",", "','")):
                if other in name:
                    hint = (
                        f" (the delimiter looks like {label}, not the one this header was "
                        "split with: use ',' throughout, or ';' throughout)"
                    )
                    break
            raise InventoryError(
                f"{where}: unknown column {name!r}{hint}; known columns: {', '.join(COLUMNS)}"
            )
    missing = [name for name in REQUIRED_COLUMNS if name not in seen]
    if missing:
        raise InventoryError(
            f"{path}: header (line {line}): missing required column(s) {', '.join(missing)} "
            f"(required: {', '.join(REQUIRED_COLUMNS)})"
        )
    return columns


def _parse_row(values: dict[str, str], decimal_comma: bool = False) -> dict[str, object]:
    """Convert the text cells of one row to Tower keyword arguments.

    With ``decimal_comma`` (a ';'-separated file), ``12,5`` is read as 12.5.
    """
    tower_id = values.get("id", "")
    kwargs: dict[str, object] = {}
    for column, text in values.items():
        if not text:
            if column in REQUIRED_COLUMNS:
                raise _FieldError(tower_id, column, text, "is required and must not be empty")
            continue
        if column in _CATEGORIES:
            kwargs[column] = text.upper()
            continue
        if column in _TEXT_COLUMNS:
            kwargs[column] = text
            continue
        if decimal_comma and _DECIMAL_COMMA.match(text):
            text = text.replace(",", ".")
        try:
            number = float(text)
        except ValueError:
            raise _FieldError(tower_id, column, text, "is not a number") from None
        if not math.isfinite(number):
            raise _FieldError(tower_id, column, text, "must be a finite number (not NaN or inf)")
        kwargs[column] = number
    return kwargs


def write_inventory(towers: Sequence[Tower], path: str | Path) -> Path:
    """Write towers to an inventory CSV that :func:`read_inventory` reads back unchanged.

    Parameters
    ----------
    towers : sequence of Tower
        The towers; only columns with at least one value are written.
    path : str or Path
        Output CSV file (UTF-8, no byte-order mark).

    Returns
    -------
    Path
        The written file.
    """
    path = Path(path)
    columns = [
        name
        for name in COLUMNS
        if name in REQUIRED_COLUMNS or any(getattr(t, name) not in (None, "") for t in towers)
    ]
    with path.open("w", newline="", encoding="utf-8") as handle:
        writer = csv.writer(handle, lineterminator="\n")
        writer.writerow(columns)
        for tower in towers:
            writer.writerow([_cell(getattr(tower, name)) for name in columns])
    return path


def _cell(value: object) -> str:
    """Text of one CSV cell; floats with repr so they read back bit for bit."""
    if value is None:
        return ""
    if isinstance(value, float):
        return repr(value)
    return str(value)


def example_inventory_path() -> Path:
    """Return the path of the embedded example inventory (``stations/data/example_towers.csv``).

    Returns
    -------
    Path
        The installed CSV: the seed paper's S. Anna in Cervino tower and illustrative
        archetypes of Italian masonry bell towers (see ``docs/inventory.md``).
    """
    return Path(str(resources.files("rockscreen.stations") / "data" / "example_towers.csv"))
