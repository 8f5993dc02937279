"""Helpers shared by the adapters: number text, distances, HDF5 attributes, config TOML."""

from __future__ import annotations

import datetime
import json
import math
from collections.abc import Sequence
from typing import TypeAlias, cast

import numpy as np

from rockscreen.pipeline.report.html.model import (
    Column,
    HeaderItem,
    Key,
    Number,
    Sentence,
    SheetValue,
    finite,
)
from rockscreen.pipeline.report.values import Attrs, AttrValue, ColumnValue, Row

try:  # Python 3.11+; ``tomli`` before (the report reads the stored configuration only)
    import tomllib
except ModuleNotFoundError:  # pragma: no cover - Python 3.10
    import tomli as tomllib

__all__ = [
    "AREA_INPUTS",
    "BELFRY_INPUTS",
    "BODY_INPUTS",
    "CLASS_COLUMN",
    "GABLE_INPUTS",
    "MASONRY_INPUTS",
    "ID_COLUMN",
    "NAME_COLUMN",
    "NOTE_COLUMN",
    "PATH_ATTRS",
    "TOWER_INPUTS",
    "TOMLValue",
    "attr_text",
    "distance_km",
    "body_inputs",
    "friction_inputs",
    "header_items",
    "inventory_inputs",
    "motion_verdict",
    "num",
    "number_inputs",
    "number_text",
    "parse_toml",
    "python_value",
    "short_paths",
]

_EARTH_RADIUS_KM = 6371.0088

#: A value of a TOML document (:mod:`tomllib`): a table is a dict of them.
TOMLValue: TypeAlias = (
    str
    | int
    | float
    | bool
    | datetime.datetime
    | datetime.date
    | datetime.time
    | list["TOMLValue"]
    | dict[str, "TOMLValue"]
)

#: Columns of the towers table that every report has (the id) or most have.
ID_COLUMN = Column("id", "col_id", "", "text")
NAME_COLUMN = Column("name", "col_name", "", "text")
CLASS_COLUMN = Column("risk_class", "col_class", "", "class")
NOTE_COLUMN = Column("note", "col_note", "", "text")

#: A tower's inputs a sheet may show: key -> (label, unit), units as the archives spell
#: them (``"1"`` dimensionless, ``""`` text).
TOWER_INPUTS = {
    "width_m": ("i_width", "m"),
    "depth_m": ("i_depth", "m"),
    "height_m": ("i_height", "m"),
    "alpha_rad": ("i_alpha", "rad"),
    "eta": ("i_eta", "1"),
    "tower_mass_kg": ("i_tower_mass", "kg"),
    "building_mass_kg": ("i_building_mass", "kg"),
    "building_height_m": ("i_building_height", "m"),
    "base_height_m": ("i_base_height", "m"),
    "building_period_s": ("i_period", "s"),
    "azimuth_deg": ("i_azimuth", "deg"),
    "soil_class": ("i_soil", ""),
    "comune": ("i_comune", ""),
    "provincia": ("i_provincia", ""),
    "belfry_height_m": ("i_belfry_height", "m"),
    "belfry_width_m": ("i_belfry_width", "m"),
    "belfry_depth_m": ("i_belfry_depth", "m"),
    "belfry_mass_kg": ("i_belfry_mass", "kg"),
    "bells_mass_kg": ("i_bells_mass", "kg"),
    "bells_height_m": ("i_bells_height", "m"),
    "shaft_period_s": ("i_shaft_period", "s"),
    "wall_thickness_m": ("i_wall_thickness", "m"),
    "wall_thickness_top_m": ("i_wall_thickness_top", "m"),
    "masonry_type": ("i_masonry_type", ""),
    "masonry_strength_mpa": ("i_masonry_strength", "MPa"),
    "knowledge_level": ("i_knowledge_level", ""),
    "gable_height_m": ("i_gable_height", "m"),
    "gable_width_m": ("i_gable_width", "m"),
    "gable_thickness_m": ("i_gable_thickness", "m"),
    "gable_base_height_m": ("i_gable_base_height", "m"),
    "gable_bells_mass_kg": ("i_gable_bells_mass", "kg"),
    "gable_opening_ratio": ("i_gable_opening_ratio", "1"),
    "gable_axis": ("i_gable_axis", ""),
}
#: The tower's area (text), shown after its name.
AREA_INPUTS: tuple[str, ...] = ("comune", "provincia")
#: The rocking block, the building and the tower's direction, shown before the friction.
BODY_INPUTS: tuple[str, ...] = (
    "width_m",
    "depth_m",
    "height_m",
    "eta",
    "tower_mass_kg",
    "building_mass_kg",
    "building_height_m",
    "base_height_m",
    "building_period_s",
    "azimuth_deg",
)
#: The shaft's masonry: the LV1 tower model's inputs (and the bell gable's unit weight).
MASONRY_INPUTS: tuple[str, ...] = (
    "wall_thickness_m",
    "wall_thickness_top_m",
    "masonry_type",
    "masonry_strength_mpa",
    "knowledge_level",
)
#: The belfry on the shaft and its bells (``belfry_depth_m`` the resolved depth), and the
#: tower's measured first period.
BELFRY_INPUTS: tuple[str, ...] = (
    "belfry_height_m",
    "belfry_width_m",
    "belfry_depth_m",
    "belfry_mass_kg",
    "bells_mass_kg",
    "bells_height_m",
    "shaft_period_s",
)
#: The bell gable (vela) and its bells.
GABLE_INPUTS: tuple[str, ...] = (
    "gable_height_m",
    "gable_width_m",
    "gable_thickness_m",
    "gable_base_height_m",
    "gable_bells_mass_kg",
    "gable_opening_ratio",
    "gable_axis",
)


def python_value(value: object) -> AttrValue:
    """Return an HDF5 attribute or cell as plain Python (bytes decoded, numpy unwrapped)."""
    if isinstance(value, bytes):
        return value.decode("utf-8", errors="replace")
    if isinstance(value, np.ndarray):
        return [python_value(item) for item in value.tolist()]
    if isinstance(value, np.generic):
        return cast(ColumnValue, value.item())
    return cast(AttrValue, value)  # already plain: text, a Python number or flag, None


def attr_text(value: object) -> str:
    """Return an attribute as display text (JSON lists joined by commas)."""
    value: object = python_value(value)
    if isinstance(value, str) and value[:1] in "[{":
        try:
            value = json.loads(value)
        except ValueError:
            return value
    if isinstance(value, list):
        return ", ".join(str(item) for item in value)
    if isinstance(value, dict):
        return ", ".join(f"{key}={item}" for key, item in value.items())
    return str(value)


def number_text(value: object, unit: str = "", digits: int = 3) -> str:
    """Format a number with ``digits`` significant digits and its unit.

    Parameters
    ----------
    value : object
        The number or its text (None, NaN, not a number: "-"; infinity: "∞").
    unit : str
        Unit appended after a space (``"m"``, ``"kg"``); ``""`` for none.
    digits : int
        Significant digits.

    Returns
    -------
    str
        E.g. ``"2.06 m"``, ``"1.2e+06 kg"``.
    """
    try:
        number = float(value)  # type: ignore[arg-type]  # what float() refuses: "-"
    except (TypeError, ValueError):
        return "-"
    if math.isnan(number):
        return "-"
    if math.isinf(number):
        text = "∞" if number > 0 else "-∞"
    else:
        text = f"{number:.{digits}g}"
    return f"{text} {unit}".strip()


def num(
    value: object, unit: str = "", digits: int = 3, bound: str = "", relation: bool = False
) -> Number:
    """Return a number for a sheet line, written in the page's language by the renderer.

    Parameters
    ----------
    value : object
        The number, as a cell or an attribute holds it (None or NaN: "-"; infinity: "∞").
    unit : str
        Its unit (``"g"``, ``"y"``); ``""`` for none.
    digits : int
        Significant digits.
    bound : str
        ``">"`` for a lower bound, ``"<"`` for an upper bound, ``""`` for a value.
    relation : bool
        Write ``"= "`` before a value that is not a bound (``I_S = 0.7``, ``I_S > 3.5``).

    Returns
    -------
    Number
        ``{"num", "unit", "digits", "bound", "relation"}`` (JSON-safe: ``num`` is a float,
        ``"inf"`` or None); :func:`rockscreen.pipeline.report.html.i18n.number` writes it.
    """
    number = python_value(value)
    if isinstance(number, (int, float)) and math.isinf(number) and number > 0:
        shown: float | str | None = "inf"
    else:
        shown = finite(number)
    return {"num": shown, "unit": unit, "digits": digits, "bound": bound, "relation": relation}


def distance_km(
    lat1: ColumnValue, lon1: ColumnValue, lat2: ColumnValue, lon2: ColumnValue
) -> float | None:
    """Great-circle distance on a sphere of the mean Earth radius [km] (within 0.5 %).

    Parameters
    ----------
    lat1, lon1, lat2, lon2 : float
        Coordinates [deg].

    Returns
    -------
    float or None
        Distance [km]; None when a coordinate is missing.
    """
    values = [finite(v) for v in (lat1, lon1, lat2, lon2)]
    if any(v is None for v in values):
        return None
    p1, l1, p2, l2 = (math.radians(v) for v in values if v is not None)
    h = math.sin((p2 - p1) / 2) ** 2 + math.cos(p1) * math.cos(p2) * math.sin((l2 - l1) / 2) ** 2
    return 2 * _EARTH_RADIUS_KM * math.asin(min(1.0, math.sqrt(h)))


def parse_toml(text: AttrValue) -> dict[str, TOMLValue]:
    """Parse a stored configuration (TOML text); an empty or bad text gives ``{}``."""
    try:
        return tomllib.loads(str(python_value(text) or ""))
    except tomllib.TOMLDecodeError:
        return {}


def number_inputs(
    values: Row, keys: Sequence[str], dimensionless: str = "1"
) -> list[tuple[str, Number]]:
    """Return the sheet lines of the numeric tower inputs that are finite numbers.

    Parameters
    ----------
    values : mapping
        The tower's values.
    keys : sequence of str
        The inputs to show, in order (:data:`TOWER_INPUTS`).
    dimensionless : str
        How the report spells the unit of a dimensionless input.

    Returns
    -------
    list of (str, dict)
        Label and number (:func:`num`, 4 significant digits, written in the page's language).
    """
    out = []
    for key in keys:
        label, unit = TOWER_INPUTS[key]
        value = finite(values.get(key))
        if value is not None:
            out.append((label, num(value, dimensionless if unit == "1" else unit, 4)))
    return out


def inventory_inputs(
    values: Row, keys: Sequence[str], dimensionless: str = "-"
) -> list[tuple[str, str | Number]]:
    """Return the sheet lines of the given tower inputs, text or numbers, left out when not given.

    Parameters
    ----------
    values : mapping
        The tower's values (an inventory row: NaN or ``""`` not given).
    keys : sequence of str
        The inputs to show, in order (:data:`TOWER_INPUTS`).
    dimensionless : str
        How the report spells the unit of a dimensionless number.

    Returns
    -------
    list of (str, str or Number)
        Label and text (a text input that is not empty) or number (:func:`num`, 4
        significant digits, a finite one).
    """
    out: list[tuple[str, str | Number]] = []
    for key in keys:
        label, unit = TOWER_INPUTS[key]
        if unit == "":
            text = str(python_value(values.get(key)) or "")
            if text:
                out.append((label, text))
        else:
            out += number_inputs(values, (key,), dimensionless)
    return out


def body_inputs(values: Row) -> list[tuple[str, str | Number]]:
    """Return a sheet's lines on the tower's area, block, building and friction.

    The inputs both kinds of sheet show after the tower's name (:data:`AREA_INPUTS`,
    :data:`BODY_INPUTS`, :func:`friction_inputs`), each left out when not given.

    Parameters
    ----------
    values : mapping
        The tower's values (an inventory row: NaN or ``""`` not given).

    Returns
    -------
    list of (str, str or Number)
    """
    return [
        *inventory_inputs(values, AREA_INPUTS),
        *number_inputs(values, BODY_INPUTS, "-"),
        *friction_inputs(values),
    ]


def friction_inputs(values: Row) -> list[tuple[str, str]]:
    """Return the sheet line of the friction coefficients ``mu_s / mu_k``, none without them."""
    mu_s, mu_k = finite(values.get("mu_s")), finite(values.get("mu_k"))
    if mu_s is None and mu_k is None:
        return []
    return [("i_friction", f"{number_text(mu_s)} / {number_text(mu_k)}")]


def motion_verdict(row: Row, record: str, model: str) -> Sentence:
    """Return the verdict line on a case's motion: overturned, rocked, or still.

    Parameters
    ----------
    row : mapping
        The case: ``overturned`` and ``theta_max_over_alpha`` [-] (rocked from 0.01).
    record, model : str
        The record (or excitation) and the model named in the line.

    Returns
    -------
    (str, dict)
        Translation key (``v_overturned``, ``v_rocks``, ``v_still``) and its values.
    """
    label: Key = {"key": f"model_{model}", "raw": model}  # the registry's label, translated
    values: dict[str, SheetValue] = {
        "record": record,
        "model": label,
        "ratio": num(row.get("theta_max_over_alpha"), "", 2),
    }
    if row.get("overturned"):
        return "v_overturned", values
    if (finite(row.get("theta_max_over_alpha")) or 0.0) >= 0.01:
        return "v_rocks", values
    return "v_still", values


#: Attributes that name files: the header shows their file names, the full paths on hover.
PATH_ATTRS = frozenset(
    {
        "inventory_source",
        "stations_source",
        "record_files",
        "config_source",
        "hazard_source",
        "shakemap_source",
        "study_source",
        "fragility_source",
    }
)


def short_paths(value: AttrValue) -> tuple[str, str]:
    """Return (file names, full paths) of an attribute that names one or more files.

    Parameters
    ----------
    value : str or list
        A path, a JSON list of paths or a comma-separated text of paths.

    Returns
    -------
    (str, str)
        The file names joined by ", " (the same name twice shown once, with a count), and
        the full text, one path a line; ``(text, "")`` when nothing was shortened.
    """
    value = python_value(value)
    if isinstance(value, str) and value[:1] == "[":
        try:
            value = json.loads(value)
        except ValueError:
            pass
    paths = value if isinstance(value, list) else str(value).split(",")
    paths = [str(p).strip() for p in paths if str(p).strip()]
    names: dict[str, int] = {}
    for path in paths:
        name = path.replace("\\", "/").rstrip("/").rsplit("/", 1)[-1] or path
        names[name] = names.get(name, 0) + 1
    text = ", ".join(name if n == 1 else f"{name} (×{n})" for name, n in names.items())
    full = "\n".join(paths)
    return text, "" if full == text else full


def header_items(attrs: Attrs, keys: list[tuple[str, str]]) -> list[HeaderItem]:
    """Return header lines for the attributes that exist and are not empty.

    Attributes that name files (:data:`PATH_ATTRS`) show the file names; the full paths
    are the item's ``title`` (shown on hover).

    Parameters
    ----------
    attrs : mapping
        Archive attributes.
    keys : list of (str, str)
        (attribute name, translation key of the label), in display order.
    """
    items = []
    for name, label in keys:
        if name not in attrs:
            continue
        if name in PATH_ATTRS:
            text, full = short_paths(attrs[name])
            if text.strip():
                items.append(HeaderItem(label, text, title=full))
            continue
        text = attr_text(attrs[name])
        if text.strip():
            items.append(HeaderItem(label, text))
    return items
