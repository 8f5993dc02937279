"""The archive schema: format name, versions, units spellings and every table's columns.

One place for what rockscreen writes into HDF5: the campaign writer and readers use the
column specs below, and the sweep, assess and scenario archives import the version
constants and the units spellings from here.

Units follow UDUNITS spelling, one spelling each: ``"1"`` for a dimensionless number
(never ``"-"``), ``"m/s2"`` for an acceleration (never ``"m/s**2"``), ``"rad"``,
``"rad/s"``, ``"m"``, ``"km"``, ``"s"``, ``"kg"``, ``"deg"``, ``"MPa"`` (the inventory's
measured masonry strength), and ``""`` for text, flags and codes.

Format versions of the campaign archive (``format = "rockscreen-archive"``):

- ``"1"``: summary coordinates ``lat``/``lon``; units ``"m/s**2"``; ``towers/mu_s``
  in ``"s"``; ``histories/index/record_id`` the record id (``IT.AQV..HN``).
- ``"2"``: summary coordinates ``lat_deg``/``lon_deg`` (as in ``/towers``); one units
  spelling (``"m/s2"``, ``"1"``); ``towers/mu_s``/``mu_k`` in ``"1"``;
  ``histories/index/record_id`` the channel id of the component (``IT.AQV..HNX``), as
  in the summary's ``governing_record``.

The readers read both (version 1 summaries are returned with the version 2 names).

``/towers`` holds every inventory column (:data:`TOWER_COLUMNS`, derived from the
inventory's column registry); the assess archive's ``/inventory`` holds the same columns
with the same units (:mod:`rockscreen.pipeline.archive.inventory_group`). Columns added
to it (``comune``, ``provincia``, the shaft's masonry and the bell gable's columns) did
not bump the version: no column changed its name, unit or meaning, a version 2 reader
ignores a column it does not know, and the readers take a column an older version 2
archive lacks as not given.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from typing import Any

from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.text import printable
from rockscreen.stations.inventory_columns import TEXT_COLUMNS
from rockscreen.stations.inventory_table import TABLE_COLUMNS

__all__ = [
    "ACCELERATION",
    "ANGLE",
    "ANGULAR_VELOCITY",
    "DEGREES",
    "DIMENSIONLESS",
    "FAILURE_COLUMNS",
    "FORMAT",
    "FORMAT_VERSION",
    "HISTORY_ARRAYS",
    "HISTORY_INDEX_COLUMNS",
    "KILOMETRES",
    "LENGTH",
    "MASS",
    "MEGAPASCALS",
    "RESULT_COLUMNS",
    "SUMMARY_COLUMNS",
    "SUMMARY_RENAMED_V1",
    "SUMMARY_REQUIRED",
    "SUPPORTED_VERSIONS",
    "TEXT",
    "TIME",
    "TOWER_COLUMNS",
    "UNITS",
    "YEARS",
    "G_UNITS",
    "PER_YEAR",
    "ColumnSpec",
    "check_format",
    "units_from_name",
]

#: The ``format`` root attribute of a campaign archive.
FORMAT = "rockscreen-archive"
#: The ``format_version`` this rockscreen writes.
FORMAT_VERSION = "2"
#: The ``format_version`` values this rockscreen reads, oldest first.
SUPPORTED_VERSIONS: tuple[str, ...] = ("1", "2")

# --------------------------------------------------------------------- units spellings
DIMENSIONLESS = "1"
ACCELERATION = "m/s2"
ANGLE = "rad"
ANGULAR_VELOCITY = "rad/s"
LENGTH = "m"
KILOMETRES = "km"
TIME = "s"
MASS = "kg"
DEGREES = "deg"
YEARS = "year"
#: Stress in megapascals: the inventory's measured masonry strength (``masonry_strength_mpa``).
MEGAPASCALS = "MPa"
PER_YEAR = "1/year"
#: Accelerations stored in g: standard gravity as rockscreen uses it (``G = 9.81`` m/s²).
G_UNITS = "9.81 m/s2"
TEXT = ""
#: Every units spelling an archive of this rockscreen may carry.
UNITS: frozenset[str] = frozenset(
    {
        DIMENSIONLESS,
        ACCELERATION,
        ANGLE,
        ANGULAR_VELOCITY,
        LENGTH,
        KILOMETRES,
        TIME,
        MASS,
        DEGREES,
        YEARS,
        MEGAPASCALS,
        PER_YEAR,
        G_UNITS,
        TEXT,
    }
)

#: Column spec: name -> (kind, units). Kinds: "str", "f8", "i8", "bool".
ColumnSpec = dict[str, tuple[str, str]]

#: Columns that name a case (tower, record, component, model): the results table and the
#: history index start with them.
_CASE_COLUMNS: ColumnSpec = {
    "tower_id": ("str", TEXT),
    "record_id": ("str", TEXT),
    "component": ("str", TEXT),
    "model": ("str", TEXT),
}
#: Columns that name a tower, and its WGS84 coordinates: the summary and /towers have both.
_TOWER_NAME_COLUMNS: ColumnSpec = {"id": ("str", TEXT), "name": ("str", TEXT)}
_COORDINATE_COLUMNS: ColumnSpec = {"lat_deg": ("f8", DEGREES), "lon_deg": ("f8", DEGREES)}

#: Columns of the results table: one row per tower-record-component-model case.
RESULT_COLUMNS: ColumnSpec = {
    **_CASE_COLUMNS,
    "status": ("str", TEXT),
    "width_m": ("f8", LENGTH),
    "alpha_rad": ("f8", ANGLE),
    "p_rad_s": ("f8", ANGULAR_VELOCITY),
    "eta": ("f8", DIMENSIONLESS),
    "pga_m_s2": ("f8", ACCELERATION),
    "theta_max_rad": ("f8", ANGLE),
    "theta_max_over_alpha": ("f8", DIMENSIONLESS),
    "overturned": ("bool", TEXT),
    "uplifted": ("bool", TEXT),
    "slipped": ("bool", TEXT),
    "n_impacts": ("i8", DIMENSIONLESS),
    "t_overturn_s": ("f8", TIME),
    "slip_max_m": ("f8", LENGTH),
    "slip_residual_m": ("f8", LENGTH),
    "friction_demand_max": ("f8", DIMENSIONLESS),
}

#: Columns of the per-tower summary table.
SUMMARY_COLUMNS: ColumnSpec = {
    **_TOWER_NAME_COLUMNS,
    **_COORDINATE_COLUMNS,
    "stations": ("str", TEXT),
    "n_records": ("i8", DIMENSIONLESS),
    "n_cases": ("i8", DIMENSIONLESS),
    "theta_max_over_alpha": ("f8", DIMENSIONLESS),
    "theta_max_rad": ("f8", ANGLE),
    "alpha_rad": ("f8", ANGLE),
    "overturned": ("bool", TEXT),
    "safety_factor": ("f8", DIMENSIONLESS),
    "safety_factor_lower": ("f8", DIMENSIONLESS),
    "safety_factor_solves": ("i8", DIMENSIONLESS),
    "risk_class": ("str", TEXT),
    "governing_record": ("str", TEXT),
    "governing_model": ("str", TEXT),
    "governing_component": ("str", TEXT),
    "safety_factor_limit": ("str", TEXT),
    "pairing": ("str", TEXT),
    "pairing_distance_km": ("f8", KILOMETRES),
    "note": ("str", TEXT),
    # the note's messages as codes (verdict.messages.dumps); an archive written before
    # notes were stored as codes lacks the column
    "note_codes": ("str", TEXT),
}

#: Summary columns every readable archive has (those of format version 1, with the
#: version 2 names); the others are read when present.
SUMMARY_REQUIRED: tuple[str, ...] = tuple(SUMMARY_COLUMNS)[:18]

#: Summary columns renamed in format version 2: version 1 name -> version 2 name.
SUMMARY_RENAMED_V1: dict[str, str] = {"lat": "lat_deg", "lon": "lon_deg"}

#: Columns of the failures table.
FAILURE_COLUMNS: ColumnSpec = {
    "kind": ("str", TEXT),
    "subject": ("str", TEXT),
    "reason": ("str", TEXT),
}

#: Inventory units (as :data:`rockscreen.stations.inventory_columns.COLUMNS` spells them)
#: -> the archive's spelling; ``"-"`` is a dimensionless number or text.
_INVENTORY_UNITS: dict[str, str] = {
    "deg": DEGREES,
    "m": LENGTH,
    "kg": MASS,
    "s": TIME,
    "y": YEARS,
    "MPa": MEGAPASCALS,
    "-": DIMENSIONLESS,
}


def _tower_columns() -> ColumnSpec:
    """Return the /towers column specs, one per inventory column (:data:`TABLE_COLUMNS`)."""
    specs: ColumnSpec = {}
    for name, (column, unit) in TABLE_COLUMNS.items():
        if column in TEXT_COLUMNS:
            specs[name] = ("str", TEXT)
        elif unit in _INVENTORY_UNITS:
            specs[name] = ("f8", _INVENTORY_UNITS[unit])
        else:  # a unit added to the inventory registry without its archive spelling
            raise ValueError(
                f"inventory column {column!r}: unit {unit!r} has no archive units spelling "
                "(add it to rockscreen.pipeline.archive.schema._INVENTORY_UNITS and UNITS)"
            )
    return specs


#: Columns of /towers (``rockscreen.stations.inventory.inventory_table``), derived from the
#: inventory's column registry: every column a ``Tower`` carries, in the registry's order.
#: NaN or empty text = value absent (not given). Version 2 archives written before the
#: comune, provincia, LV1 (``wall_thickness_m``, ``wall_thickness_top_m``, ``masonry_type``,
#: ``masonry_strength_mpa``, ``knowledge_level``) and bell-gable columns were stored lack
#: them: a reader takes a missing column as absent for every tower.
TOWER_COLUMNS: ColumnSpec = _tower_columns()

#: Columns of /histories/index: rows [start, start+count) of the history arrays.
HISTORY_INDEX_COLUMNS: ColumnSpec = {
    **_CASE_COLUMNS,
    "alpha_rad": ("f8", ANGLE),
    "start": ("i8", DIMENSIONLESS),
    "count": ("i8", DIMENSIONLESS),
}

#: History arrays: name -> (numpy dtype, units). ``regime`` is a code (0 rest, 1 tower
#: rocking, 2 building sliding, 3 both), hence no units.
HISTORY_ARRAYS: dict[str, tuple[str, str]] = {
    "t": ("f4", TIME),
    "theta": ("f4", ANGLE),
    "u": ("f4", LENGTH),
    "regime": ("i1", TEXT),
}

_SUFFIX_UNITS = (
    ("_deg", DEGREES),
    ("_km", KILOMETRES),
    ("_m_s2", ACCELERATION),
    ("_rad_s", ANGULAR_VELOCITY),
    ("_rad", ANGLE),
    ("_kg", MASS),
    ("_m", LENGTH),
    ("_s", TIME),
    ("_y", YEARS),
)
_DIMENSIONLESS_NAMES = frozenset({"eta", "mu_s", "mu_k"})


def units_from_name(name: str) -> str:
    """Return the units of a column named with its unit as suffix (``width_m`` -> ``"m"``).

    ``eta``, ``mu_s`` and ``mu_k`` (friction coefficients, not seconds) are ``"1"``;
    a name without a unit suffix is text (``""``).
    """
    if name in _DIMENSIONLESS_NAMES:
        return DIMENSIONLESS
    for suffix, units in _SUFFIX_UNITS:
        if name.endswith(suffix):
            return units
    return TEXT


def _shown(value: Any) -> str:
    """Return a short one-line rendering of an attribute value for a message."""
    if isinstance(value, bytes):
        value = value.decode("utf-8", "replace")
    text = printable(value if isinstance(value, str) else repr(value))
    return text if len(text) <= 40 else text[:37] + "..."


def _path(path: Any) -> str:
    return printable(os.fspath(path))


def _attribute_text(h5file: Any, name: str) -> str | None:
    """Return a root attribute as text (``None`` when absent or not a scalar)."""
    try:
        value = h5file.attrs.get(name)
    except Exception:  # noqa: BLE001 - a crafted attribute must not escape as a traceback
        return None
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    if isinstance(value, str):
        return value
    if hasattr(value, "item") and getattr(value, "shape", None) == ():
        value = value.item()
    if isinstance(value, bool) or value is None:
        return None
    if isinstance(value, int):
        return str(value)
    return None if not isinstance(value, str) else value


def check_format(
    h5file: Any,
    path: Any,
    kinds: Iterable[str] = (FORMAT,),
    versions: Iterable[str] = SUPPORTED_VERSIONS,
) -> str:
    """Check the ``format`` and ``format_version`` root attributes of an open archive.

    Every reader calls this on open.

    Parameters
    ----------
    h5file : h5py.File
        The open archive.
    path : str or path-like
        Its path, for messages.
    kinds : iterable of str
        The ``format`` values accepted (default the campaign archive).
    versions : iterable of str
        The ``format_version`` values accepted (default :data:`SUPPORTED_VERSIONS`);
        an integer attribute counts as its decimal text.

    Returns
    -------
    str
        The archive's format version.

    Raises
    ------
    ArchiveError
        One line naming the file and the format or version found and those accepted.
    """
    kinds, versions = tuple(kinds), tuple(versions)
    found = _attribute_text(h5file, "format")
    if found not in kinds:
        shown = "none" if found is None else _shown(found)
        raise ArchiveError(
            f"{_path(path)}: not a rockscreen archive (format attribute: {shown}; "
            f"this reader takes {', '.join(kinds)})"
        )
    version = _attribute_text(h5file, "format_version")
    if version not in versions:
        try:
            raw = h5file.attrs.get("format_version")
        except Exception:  # noqa: BLE001
            raw = None
        shown = "none" if raw is None else repr(_shown(version if version is not None else raw))
        raise ArchiveError(
            f"{_path(path)}: archive format_version {shown} is not supported "
            f"(this rockscreen reads {', '.join(versions)})"
        )
    return version
