"""Build a rockscreen inventory of the Italian towers of the public TURRIS database.

TURRIS (Montabert et al., Buildings 2023; GitHub ``MArnaud/TURRIS``, AGPL) collects the
geometry and the measured fundamental frequency of historic masonry towers. Nothing of it
is part of rockscreen: this script takes the path of a local TURRIS checkout (the folder
holding ``TURRIS.xlsx``, or the file itself) and writes an inventory CSV where the user
says, never inside this repository. It reads the spreadsheet with the standard library
(an ``.xlsx`` is a zip of XML sheets), so it needs nothing beyond rockscreen.

The towers kept: in Italy (the NTC 2018 hazard grid covers Italy only), with a location,
a height and both plan sides, and at least one surveyed wall thickness. A tower surveyed
several times is one row of TURRIS per survey: the first survey that gives all of these is
kept. Columns written:

- ``id`` ``TURRIS-<id>``, ``name`` the building's name, ``comune`` its town;
- ``lat``, ``lon`` [deg] as surveyed;
- ``height_m`` = TURRIS ``H`` (the whole tower from the ground: the rocking block and the
  LV1 shaft start at the base; TURRIS ``Heff``, the height above adjacent buildings, is
  not used);
- ``width_m`` = ``width`` (the shorter plan side), ``depth_m`` = ``length`` (the longer;
  circular and octagonal towers: their diameter both ways); both are needed;
- ``wall_thickness_m`` = the larger surveyed thickness (the base), and
  ``wall_thickness_top_m`` = the smaller one when both are given and differ (walls thinning
  upwards, capped at half the smaller plan side as the inventory requires);
- ``masonry_type`` ``solid_brick``, ``knowledge_level`` ``LC1``, ``soil_class`` ``B``
  (assumptions of issue 30's acceptance case, not TURRIS data).

Each row is checked by :class:`rockscreen.stations.inventory.Tower` before it is written;
a row it refuses is left out and named. Printed: how many TURRIS rows, Italian towers,
towers with a wall thickness, towers written, and the distinct sites at 0.01 deg.

    python benchmarks/turris_inventory.py /tmp/TURRIS --out /tmp/turris79.csv
    rockscreen assess --towers /tmp/turris79.csv --out /tmp/turris79.h5
"""

from __future__ import annotations

import argparse
import re
import sys
import xml.etree.ElementTree as ET
import zipfile
from pathlib import Path

from rockscreen.stations.errors import InventoryError
from rockscreen.stations.inventory import Tower, write_inventory

#: The spreadsheet's XML namespace.
_NS = "{http://schemas.openxmlformats.org/spreadsheetml/2006/main}"
#: The repository this script lives in: the inventory is never written inside it.
REPOSITORY = Path(__file__).resolve().parents[1]
#: Assumptions of the acceptance case (issue 30), written in every row.
MASONRY_TYPE = "solid_brick"
KNOWLEDGE_LEVEL = "LC1"
SOIL_CLASS = "B"


def read_sheet(path: Path) -> list[dict[str, str]]:
    """Return the rows of the first sheet of an ``.xlsx`` as dicts keyed by the header row.

    Parameters
    ----------
    path : Path
        The workbook.

    Returns
    -------
    list of dict
        One dict per data row: header name -> cell text (cells absent from a row are
        absent from its dict).
    """
    with zipfile.ZipFile(path) as book:
        shared = []
        if "xl/sharedStrings.xml" in book.namelist():
            root = ET.fromstring(book.read("xl/sharedStrings.xml"))
            for item in root.iter(f"{_NS}si"):
                shared.append("".join(t.text or "" for t in item.iter(f"{_NS}t")))
        sheet = ET.fromstring(book.read("xl/worksheets/sheet1.xml"))
    rows = []
    for row in sheet.iter(f"{_NS}row"):
        cells = {}
        for cell in row.findall(f"{_NS}c"):
            column = re.match(r"[A-Z]+", cell.get("r", "")).group()
            value = cell.find(f"{_NS}v")
            kind = cell.get("t")
            if kind == "s" and value is not None:
                cells[column] = shared[int(value.text)]
            elif kind == "inlineStr":
                cells[column] = "".join(t.text or "" for t in cell.iter(f"{_NS}t"))
            elif value is not None and value.text is not None:
                cells[column] = value.text
        rows.append(cells)
    if not rows:
        return []
    header = {column: name.strip() for column, name in rows[0].items() if name.strip()}
    return [
        {header[c]: v.strip() for c, v in cells.items() if c in header}
        for cells in rows[1:]
        if cells
    ]


def _number(text: str | None) -> float | None:
    """Return a positive number of a TURRIS cell; None for -1 (TURRIS's 'unknown') or text."""
    try:
        value = float(str(text).replace(",", "."))
    except ValueError:
        return None
    return value if value > 0 else None


def tower_of(row: dict[str, str]) -> Tower | str:
    """Return the inventory tower of one TURRIS row, or why it is left out.

    Parameters
    ----------
    row : dict
        A TURRIS row (:func:`read_sheet`).

    Returns
    -------
    Tower or str
    """
    lat, lon = _number(row.get("latitude")), _number(row.get("longitude"))
    height = _number(row.get("H"))
    width, length = _number(row.get("width")), _number(row.get("length"))
    thicknesses = [
        t
        for t in (_number(row.get("min_wall_thickness")), _number(row.get("max_wall_thickness")))
        if t is not None
    ]
    if lat is None or lon is None:
        return "no location"
    if height is None or width is None or length is None:
        return "no height or plan (both sides)"
    if not thicknesses:
        return "no wall thickness"
    width, length = min(width, length), max(width, length)
    base = max(thicknesses)
    top = min(min(thicknesses), width / 2)
    try:
        return Tower(
            id=f"TURRIS-{row['id']}",
            name=row.get("building_name") or None,
            comune=row.get("town") or None,
            lat=lat,
            lon=lon,
            width_m=width,
            height_m=height,
            depth_m=length,
            wall_thickness_m=base,
            wall_thickness_top_m=top if top < base else None,
            masonry_type=MASONRY_TYPE,
            knowledge_level=KNOWLEDGE_LEVEL,
            soil_class=SOIL_CLASS,
        )
    except InventoryError as exc:
        return f"refused by the inventory's rules: {exc}"


def main(argv: list[str] | None = None) -> int:
    """Write the inventory; print what was kept and left out."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("turris", type=Path, help="TURRIS checkout folder, or its TURRIS.xlsx")
    parser.add_argument("--out", type=Path, required=True, help="inventory CSV to write")
    args = parser.parse_args(argv)
    book = args.turris / "TURRIS.xlsx" if args.turris.is_dir() else args.turris
    if not book.is_file():
        parser.error(f"{book}: no TURRIS.xlsx there")
    out = args.out.resolve()
    if out == REPOSITORY or REPOSITORY in out.parents:
        parser.error(
            f"{args.out}: inside the rockscreen repository; TURRIS data is never kept here"
        )
    rows = [r for r in read_sheet(book) if r.get("id")]
    italian = [r for r in rows if r.get("country", "").strip().lower() == "italy"]
    towers: dict[str, Tower] = {}
    left_out: dict[str, str] = {}
    for row in italian:
        if f"TURRIS-{row['id']}" in towers:
            continue  # another survey of a tower already kept
        tower = tower_of(row)
        if isinstance(tower, str):
            left_out.setdefault(row["id"], tower)
        else:
            towers[tower.id] = tower
            left_out.pop(row["id"], None)  # a later survey gave what an earlier one lacked
    write_inventory(list(towers.values()), out)
    sites = {(round(t.lon / 0.01), round(t.lat / 0.01)) for t in towers.values()}
    n_italian = len({r["id"] for r in italian})
    print(f"TURRIS rows: {len(rows)} ({len({r['id'] for r in rows})} towers)")
    print(f"Italian towers: {n_italian}")
    reasons: dict[str, int] = {}
    for reason in left_out.values():
        key = reason.split(":")[0]
        reasons[key] = reasons.get(key, 0) + 1
    for reason, count in sorted(reasons.items()):
        print(f"  left out, {reason}: {count}")
    for tower_id, reason in left_out.items():
        if reason.startswith("refused"):
            print(f"  TURRIS-{tower_id}: {reason}")
    print(f"towers written: {len(towers)} at {len(sites)} sites (0.01 deg) -> {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
