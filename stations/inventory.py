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
import unicodedata
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

from rockscreen.stations.errors import InventoryError, InventoryValueError
from rockscreen.stations.inventory_columns import (
    CATEGORIES,
    COLUMNS,
    REQUIRED_COLUMNS,
    TEXT_COLUMNS,
)
from rockscreen.stations.inventory_table import inventory_table
from rockscreen.stations.tower import Tower

__all__ = [
    "COLUMNS",
    "MAX_LISTED_ROWS",
    "REQUIRED_COLUMNS",
    "InvalidRow",
    "InventoryRows",
    "Tower",
    "example_inventory_path",
    "inventory_table",
    "read_inventory",
    "read_inventory_rows",
    "write_inventory",
]

# A number as a CSV cell writes it: ASCII digits, one optional point and exponent (Python's
# float() also takes "1_0" and fullwidth or other Unicode digits: never a number here).
_NUMBER = re.compile(r"[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?", re.ASCII)
# Words float() reads as NaN or infinity: refused as "not finite" (a clearer message).
_NOT_FINITE = frozenset({"nan", "inf", "infinity"})
# A number written with a decimal comma: 12,5 or -0,25 or 1,5e3 (';'-separated files only).
_DECIMAL_COMMA = re.compile(r"^[-+]?\d*,\d+([eE][-+]?\d+)?$")


#: Invalid rows named in full in one :class:`InventoryError` (the rest are counted).
MAX_LISTED_ROWS = 20


@dataclass(frozen=True)
class InvalidRow:
    """One data row of an inventory that breaks a rule (:func:`read_inventory_rows`)."""

    #: Data row, 1-based (blank lines not counted).
    row: int
    #: Line of the file where the row starts (1-based).
    line: int
    #: The row's tower id as written (``""`` when it has none).
    tower_id: str
    #: The column holding the broken value (``""`` for a wrong field count).
    column: str
    #: The message without the file name: row, line, tower, column, value and rule.
    detail: str


@dataclass(frozen=True)
class InventoryRows:
    """An inventory read row by row: its valid towers and its invalid rows."""

    #: The file read.
    path: Path
    #: The valid towers, in file order.
    towers: list[Tower]
    #: The invalid rows, in file order.
    invalid: list[InvalidRow]

    def error(self) -> InventoryError:
        """Return the one error naming every invalid row (the first :data:`MAX_LISTED_ROWS`).

        Returns
        -------
        InventoryError
            With one invalid row, ``"<file>: row N (line L), tower 'X', column 'c': value
            ... <rule>"``; with several, ``"<file>: K invalid rows (...): <each row>; and M
            more"``.
        """
        if len(self.invalid) == 1:
            return InventoryError(f"{self.path}: {self.invalid[0].detail}")
        listed = [bad.detail for bad in self.invalid[:MAX_LISTED_ROWS]]
        more = len(self.invalid) - len(listed)
        if more:
            listed.append(f"and {more} more invalid row(s)")
        n_rows = len(self.invalid) + len(self.towers)
        return InventoryError(
            f"{self.path}: {len(self.invalid)} invalid rows of {n_rows} "
            "(each named; fix them, or assess the valid towers with --skip-invalid): "
            + "; ".join(listed)
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
        On an invalid header, at once; else naming every invalid row in one message (the
        first :data:`MAX_LISTED_ROWS`, the others counted): the file, the data row
        (1-based) and line, the tower, the column, the value and the rule
        (:meth:`InventoryRows.error`). An inventory without towers is an error.
    """
    reading = read_inventory_rows(path)
    if reading.invalid:
        raise reading.error()
    return reading.towers


def read_inventory_rows(path: str | Path) -> InventoryRows:
    """Read an inventory CSV row by row, keeping its valid towers and naming its invalid rows.

    Every data row is checked as :func:`read_inventory` checks it; a row that breaks a rule
    (a wrong field count, a value, a duplicate id) is kept as an :class:`InvalidRow`
    instead of stopping the reading, so that one pass names them all.

    Parameters
    ----------
    path : str or Path
        The inventory (:func:`read_inventory`).

    Returns
    -------
    InventoryRows

    Raises
    ------
    InventoryError
        When the file cannot be read, is not UTF-8 or CSV, or its header is invalid (nothing
        can be read then), or when it holds no data row.
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
    invalid: list[InvalidRow] = []
    first_row_of: dict[str, tuple[int, int, str]] = {}
    for number, (line, cells) in enumerate(rows[1:], start=1):
        where = f"row {number} (line {line})"
        if len(cells) != len(columns):
            position = columns.index("id")
            written_id = cells[position].strip() if len(cells) > position else ""
            invalid.append(
                InvalidRow(
                    number,
                    line,
                    written_id,
                    "",
                    f"{where}: has {len(cells)} fields, the header has {len(columns)} columns",
                )
            )
            continue
        values = dict(zip(columns, (cell.strip() for cell in cells), strict=True))
        try:
            tower = Tower(**_parse_row(values, decimal_comma=delimiter == ";"))
        except InventoryValueError as exc:
            written_id = values.get("id", "")
            invalid.append(
                InvalidRow(number, line, written_id, exc.column, f"{where}, {exc.detail}")
            )
            # Its id is taken: a later row of the same id is a duplicate, as it would be
            # once this row is fixed.
            if written_id:
                first_row_of.setdefault(_id_key(written_id), (number, line, written_id))
            continue
        key = _id_key(tower.id)
        if key in first_row_of:
            first, first_line, first_id = first_row_of[key]
            same = (
                "" if first_id == tower.id else f" {first_id!r}, equal up to case or Unicode form,"
            )
            invalid.append(
                InvalidRow(
                    number,
                    line,
                    tower.id,
                    "id",
                    f"{where}, column 'id': value {tower.id!r} is a duplicate "
                    f"(first used{same} in row {first}, line {first_line}); ids must be unique",
                )
            )
            continue
        first_row_of[key] = (number, line, tower.id)
        towers.append(tower)
    if not towers and not invalid:
        raise InventoryError(f"{path}: the inventory has a header but no towers")
    return InventoryRows(path, towers, invalid)


def _id_key(tower_id: str) -> str:
    """Return the key under which two ids are the same tower: NFKC form, case-folded.

    ``"Torre-1"``, ``"TORRE-1"``, a decomposed accent and a fullwidth letter name one tower
    for a reader; the archive, exports and ``--towers`` lists would keep them apart.
    """
    return unicodedata.normalize("NFKC", tower_id).casefold()


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
                raise InventoryValueError(
                    tower_id, column, text, "is required and must not be empty"
                )
            continue
        if column in CATEGORIES:
            # Case-insensitive: stored as the allowed value spells it (a value outside the
            # list is kept as written and refused by Tower with the allowed values).
            spelled = {value.upper(): value for value in CATEGORIES[column]}
            kwargs[column] = spelled.get(text.upper(), text)
            continue
        if column in TEXT_COLUMNS:
            kwargs[column] = text
            continue
        if decimal_comma and _DECIMAL_COMMA.match(text):
            text = text.replace(",", ".")
        if not (_NUMBER.fullmatch(text) or text.lower().lstrip("+-") in _NOT_FINITE):
            raise InventoryValueError(
                tower_id, column, text, "is not a number (digits 0-9, '.', exponent e)"
            )
        number = float(text)
        if not math.isfinite(number):
            raise InventoryValueError(
                tower_id, column, text, "must be a finite number (not NaN or inf)"
            )
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
