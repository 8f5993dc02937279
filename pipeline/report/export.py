"""Export of the per-tower risk summary: CSV for spreadsheets, GeoJSON for GIS.

The rows are the dicts of :func:`pipeline.archive.campaign.read_summary` (one per tower). Both
formats keep the archive's row order (the inventory's) and all its keys, the most read
first (:data:`LEADING_COLUMNS`), with the unit in every name: archives of format
version 2 name the coordinates ``lat_deg``/``lon_deg``; the ``lat``/``lon`` of version 1
rows are renamed so (``theta_max_rad`` already carries its unit; ``theta_max_over_alpha``
and ``safety_factor`` are dimensionless).

CSV: UTF-8, comma-separated, one header row; floats written in full precision (Python
``repr``); a missing value (NaN) is an empty cell; a safety factor with no overturning
under the search cap is ``inf``; booleans are ``true``/``false``. Formula injection
(OWASP "CSV injection"): a text cell (header included) that starts with ``=``, ``+``,
``-``, ``@``, a tab or a carriage return would be run as a formula by a spreadsheet, so
it is written with a leading apostrophe (``'=cmd|...``); numbers are written as
numbers, a negative one included (``-0.5`` stays ``-0.5``).

Bounds (:mod:`rockscreen.pipeline.archive.bounds`): a value that is only a bound is written
with its relation, in both formats, never as a plain number: ``>1.67`` (at least),
``<0.2`` (at most); its bound column (``slv_bound``, ...) says the same in words.

GeoJSON (RFC 7946): a ``FeatureCollection`` of ``Point`` features with coordinates
``[lon, lat]`` in WGS84 degrees, the tower id as the feature ``id`` and the whole
summary row as ``properties``. JSON has no NaN or infinity: both are written as
``null`` (for ``safety_factor``, ``null`` with ``overturned`` false means "nothing up to
the cap overturned" or "not searched"; the CSV keeps the distinction). Towers without
coordinates cannot be placed and are left out (the writer returns their ids).
"""

from __future__ import annotations

import csv
import io
import json
import math
from collections.abc import Iterable, Sequence
from pathlib import Path
from typing import cast

import numpy as np

from rockscreen.pipeline.archive.atomic import write_text_atomic
from rockscreen.pipeline.archive.bounds import relation
from rockscreen.pipeline.report.risk_summary import json_number
from rockscreen.pipeline.report.values import ColumnValue, JSONValue, Row
from rockscreen.pipeline.verdict.messages import note_messages, render_all

__all__ = [
    "LEADING_COLUMNS",
    "area_csv_text",
    "UNIT_NAMES",
    "export_columns",
    "rows_without_coordinates",
    "csv_safe_text",
    "summary_csv_text",
    "summary_feature_collection",
    "summary_geojson_text",
    "write_summary_csv",
    "write_summary_geojson",
]

#: Summary keys whose export name carries the unit.
UNIT_NAMES: dict[str, str] = {"lat": "lat_deg", "lon": "lon_deg"}

#: Columns written first, in this order (what a reader looks at first), when present.
LEADING_COLUMNS: tuple[str, ...] = (
    "id",
    "name",
    "lat_deg",
    "lon_deg",
    "lat",
    "lon",
    "risk_class",
    "theta_max_over_alpha",
    "theta_max_rad",
    "overturned",
    "safety_factor",
    "governing_record",
    "governing_model",
    "governing_component",
    "n_records",
)

#: Decimal places of GeoJSON coordinates: 1e-7 deg is about 1 cm, more than any inventory.
COORDINATE_DECIMALS = 7


def export_columns(rows: Sequence[Row]) -> list[str]:
    """Return the summary keys of all rows, the most read first.

    Parameters
    ----------
    rows : sequence of mapping
        Summary rows.

    Returns
    -------
    list of str
        The keys (not yet renamed with units): those of :data:`LEADING_COLUMNS`
        first, in that order, then the others in order of first appearance.
    """
    keys: dict[str, None] = {}
    for row in rows:
        keys.update(dict.fromkeys(row))
    leading = [key for key in LEADING_COLUMNS if key in keys]
    return leading + [key for key in keys if key not in LEADING_COLUMNS]


def _labelled(row: Row) -> Row:
    """Return the row with its note rendered from its codes (``risk_class`` stays one word).

    The ``note`` is rendered in English from ``note_codes`` when the row has them (the codes
    are checked against the catalogue; the text is the archive's own), the ``note_codes``
    column exported beside it. ``risk_class`` is exported as stored, one word of its scale,
    with its marks in their own columns (``completeness``, ``basis_compliant``,
    ``class_bound``: :mod:`rockscreen.pipeline.verdict.scales`).
    """
    said = note_messages(row)
    if said is not None:
        row = {**row, "note": render_all(said)}
    return row


def _export_name(key: str) -> str:
    return UNIT_NAMES.get(key, key)


def _python(value: object) -> ColumnValue:
    """Convert numpy scalars and bytes to plain Python values."""
    if isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, bytes):
        value = value.decode("utf-8")
    return cast(ColumnValue, value)  # a cell: text, a Python number or flag, None


#: First characters that make a spreadsheet read a cell as a formula.
_FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")


def csv_safe_text(text: str) -> str:
    """Return a text cell that no spreadsheet runs as a formula.

    Parameters
    ----------
    text : str
        A text cell (not a number).

    Returns
    -------
    str
        ``text`` with a leading apostrophe when it starts with ``=``, ``+``, ``-``,
        ``@``, a tab or a carriage return; ``text`` otherwise.

    Examples
    --------
    >>> csv_safe_text("=HYPERLINK(1)")
    "'=HYPERLINK(1)"
    >>> csv_safe_text("T-01")
    'T-01'
    """
    return "'" + text if text.startswith(_FORMULA_STARTS) else text


def _is_coordinate(key: str) -> bool:
    """Tell whether a column is a coordinate (never rounded by ``digits``)."""
    return key in ("lat", "lon") or key.endswith(("lat_deg", "lon_deg"))


def _csv_cell(value: object, digits: int | None = None, decimal: str = ".") -> str:
    value = _python(value)
    if value is None:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        if math.isnan(value):
            return ""
        if math.isinf(value) or digits is None:
            text = repr(value)  # 'inf' / '-inf' for infinities, full precision otherwise
        else:
            text = f"{value:.{digits}g}"
        return text.replace(".", decimal)
    if isinstance(value, int):
        return str(value)
    return csv_safe_text(str(value))


#: The CSV dialects: ``"c"`` (comma, decimal point) and ``"it"`` (Italian Excel:
#: semicolon, decimal comma, UTF-8 with a byte-order mark so that Excel reads accents).
CSV_LOCALES: dict[str, tuple[str, str, str]] = {"c": (",", ".", ""), "it": (";", ",", "\ufeff")}


def summary_csv_text(rows: Sequence[Row], locale: str = "c", digits: int | None = None) -> str:
    """Return the summary as CSV text.

    Parameters
    ----------
    rows : sequence of mapping
        Summary rows (see module docstring).
    locale : {"c", "it"}, optional
        ``"c"``: comma-separated, decimal point (the default). ``"it"``: as Italian Excel
        writes and reads it: semicolon-separated, decimal comma, a UTF-8 byte-order mark
        first (the inventory reader, :mod:`rockscreen.stations.inventory`, accepts the
        same).
    digits : int, optional
        Significant digits of the floats (coordinates excepted, which stay whole); full
        precision (Python ``repr``) when None.

    Returns
    -------
    str
        Header and one line per row, LF line ends.

    Raises
    ------
    ValueError
        For an unknown ``locale`` or ``digits`` below 1.
    """
    if locale not in CSV_LOCALES:
        raise ValueError(f"unknown CSV locale {locale!r} (known: {', '.join(CSV_LOCALES)})")
    if digits is not None and digits < 1:
        raise ValueError(f"digits must be at least 1, not {digits}")
    delimiter, decimal, bom = CSV_LOCALES[locale]
    keys = export_columns(rows)
    lines = [_csv_line([csv_safe_text(_export_name(key)) for key in keys], delimiter)]
    rows = [_labelled(row) for row in rows]
    lines += [
        _csv_line(
            [
                _bounded(
                    row,
                    key,
                    _csv_cell(row.get(key), None if _is_coordinate(key) else digits, decimal),
                )
                for key in keys
            ],
            delimiter,
        )
        for row in rows
    ]
    return bom + "".join(lines)


def _bounded(row: Row, key: str, text: ColumnValue) -> ColumnValue:
    """Prefix a bound's relation (``>``, ``<``) to its written value (module docstring)."""
    sign = relation(row, key)
    if not sign or text is None or text == "":
        return text
    return f"{sign}{text}"


def area_csv_text(rows: Sequence[Row], column: str, locale: str = "c") -> str:
    """Return the towers per class per area of ``column`` as CSV text (``export --by``).

    Parameters
    ----------
    rows : sequence of mapping
        Summary rows.
    column : {"comune", "provincia"}
        The area column (:func:`rockscreen.pipeline.report.areas.area_counts`).
    locale : {"c", "it"}, optional
        As for :func:`summary_csv_text`.

    Returns
    -------
    str
        Header ``column, <class>..., towers`` and one line per area, the largest first.
    """
    from rockscreen.pipeline.report.areas import area_counts
    from rockscreen.pipeline.verdict.scales import SAFETY_COUNTED, SCENARIO_CLASS

    delimiter, _, bom = CSV_LOCALES[locale]
    met, areas = area_counts(rows, column)
    order = list(dict.fromkeys([*SCENARIO_CLASS.classes, *SAFETY_COUNTED]))
    classes = [c for c in order if c in met] + [c for c in met if c not in order]
    lines = [_csv_line([csv_safe_text(c) for c in (column, *classes, "towers")], delimiter)]
    for area, counts, total in areas:
        cells = [csv_safe_text(area), *(str(counts.get(c, 0)) for c in classes), str(total)]
        lines.append(_csv_line(cells, delimiter))
    return bom + "".join(lines)


def _csv_line(cells: list[str], delimiter: str = ",") -> str:
    r"""Return one CSV line ending in LF; a cell holding CR or LF is quoted.

    (The csv module quotes only the characters of its line terminator: written with
    ``"\r\n"`` both are quoted, then the row's own terminator becomes ``"\n"``.)
    """
    buffer = io.StringIO()
    csv.writer(buffer, delimiter=delimiter, lineterminator="\r\n").writerow(cells)
    return buffer.getvalue()[:-2] + "\n"


def _json_value(value: object) -> ColumnValue:
    return json_number(_python(value))


def _coordinate(row: Row, key: str) -> float | None:
    value = _python(row.get(f"{key}_deg", row.get(key)))
    if value is None or isinstance(value, (bool, str)):
        return None
    value = float(value)
    return value if math.isfinite(value) else None


def summary_feature_collection(
    rows: Sequence[Row],
) -> tuple[dict[str, JSONValue], list[str]]:
    """Return the summary as a GeoJSON FeatureCollection.

    Parameters
    ----------
    rows : sequence of mapping
        Summary rows with ``id``, ``lat_deg`` and ``lon_deg`` [deg] (or the ``lat``
        and ``lon`` of format version 1).

    Returns
    -------
    collection : dict
        The FeatureCollection (JSON-serialisable, no NaN or infinity).
    skipped : list of str
        Ids of the towers left out because they have no coordinates.
    """
    keys = export_columns(rows)
    features: list[JSONValue] = []
    skipped = []
    for row in map(_labelled, rows):
        lat, lon = _coordinate(row, "lat"), _coordinate(row, "lon")
        if lat is None or lon is None:
            skipped.append(str(_python(row.get("id", ""))))
            continue
        features.append(
            {
                "type": "Feature",
                "id": _json_value(row.get("id")),
                "geometry": {
                    "type": "Point",
                    "coordinates": [
                        round(lon, COORDINATE_DECIMALS),
                        round(lat, COORDINATE_DECIMALS),
                    ],
                },
                "properties": {
                    _export_name(k): _bounded(row, k, _json_value(row.get(k))) for k in keys
                },
            }
        )
    return {"type": "FeatureCollection", "features": features}, skipped


def summary_geojson_text(rows: Sequence[Row]) -> tuple[str, list[str]]:
    """Return the summary as GeoJSON text and the ids of the towers left out.

    Parameters
    ----------
    rows : sequence of mapping
        Summary rows.

    Returns
    -------
    text : str
        Strict JSON (``allow_nan=False``), UTF-8 characters kept, newline at the end.
    skipped : list of str
        Ids of the towers without coordinates.
    """
    collection, skipped = summary_feature_collection(rows)
    text = json.dumps(collection, ensure_ascii=False, allow_nan=False, indent=1)
    return text + "\n", skipped


def write_summary_csv(
    rows: Sequence[Row],
    path: str | Path,
    locale: str = "c",
    digits: int | None = None,
) -> int:
    """Write the summary to a CSV file (atomically: a complete file or none).

    Parameters
    ----------
    rows : sequence of mapping
        Summary rows.
    path : str or Path
        Output file.
    locale, digits
        As in :func:`summary_csv_text`.

    Returns
    -------
    int
        Number of towers written.
    """
    write_text_atomic(Path(path), summary_csv_text(rows, locale=locale, digits=digits))
    return len(rows)


def write_summary_geojson(rows: Sequence[Row], path: str | Path) -> tuple[int, list[str]]:
    """Write the summary to a GeoJSON file (atomically: a complete file or none).

    Parameters
    ----------
    rows : sequence of mapping
        Summary rows.
    path : str or Path
        Output file (``.geojson``).

    Returns
    -------
    written : int
        Number of towers written.
    skipped : list of str
        Ids of the towers left out for want of coordinates.
    """
    text, skipped = summary_geojson_text(rows)
    write_text_atomic(Path(path), text)
    return len(rows) - len(skipped), skipped


def rows_without_coordinates(rows: Iterable[Row]) -> list[str]:
    """Return the ids of the rows without finite ``lat_deg`` and ``lon_deg``.

    Parameters
    ----------
    rows : iterable of mapping
        Summary rows.

    Returns
    -------
    list of str
        Tower ids, in row order.
    """
    return [
        str(_python(row.get("id", "")))
        for row in rows
        if _coordinate(row, "lat") is None or _coordinate(row, "lon") is None
    ]
