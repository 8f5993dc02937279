"""Safe reading of a ShakeMap-layout XML file (``grid.xml``, ``uncertainty.xml``): header and rows.

Format (USGS ShakeMap manual, "grid.xml"): a ``shakemap_grid`` root with an ``event``
element, a ``grid_specification`` (``lon_min``, ``lat_min``, ``lon_max``, ``lat_max``,
``nlon``, ``nlat``), ``grid_field`` elements (``index``, ``name``, ``units``) and the
rows of ``grid_data``, one line per node. What the fields mean (PGA, STDPGA) and the grid
built from them are :mod:`rockscreen.pipeline.hazard.shakemap`.

Safety (a grid.xml comes from the network, by mail, on a USB stick): only a regular file
of at most :data:`MAX_FILE_BYTES` is read (a FIFO or ``/dev/zero`` is refused before
reading); it is parsed by ``defusedxml`` with every DOCTYPE refused (no entity expansion,
"billion laughs", and no external entity, whatever the file's encoding: a UTF-16 file is
no way around it). The header is bounded: ``nlon`` and ``nlat`` integers of at least 2
with at most :data:`MAX_NODES` nodes, rows on its nodes, no more rows than nodes and no
node twice (duplicated rows are named); a finite extent with ``min < max``; each
``grid_field`` with a unique name and a unique integer ``index`` within the row (a second
``PGA`` is refused, never silently replacing the first).
"""

from __future__ import annotations

import math
import os
import re
import stat
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
from defusedxml import DefusedXmlException
from defusedxml import ElementTree as SafeET

from rockscreen.pipeline.errors import ShakeMapError
from rockscreen.pipeline.text import printable

__all__ = [
    "EXTENT",
    "MAX_FILE_BYTES",
    "MAX_NODES",
    "NODE_TOLERANCE",
    "node_indices",
    "parse_grid_file",
    "refuse_bad_row",
]

#: Largest grid file read [bytes]: 256 MiB, several times a ShakeMap 4 grid of a large
#: event at 30 arc-second spacing (about 10^6 nodes of ~100 bytes).
MAX_FILE_BYTES = 256 * 1024**2
#: Largest ``nlon * nlat`` accepted [-] (two float64 grids of this size: 256 MB).
MAX_NODES = 16_000_000
#: How far a row may lie from its node, in node spacings [-] (coordinates are printed
#: with 4 decimals; a larger offset means nlon/nlat do not describe the rows).
NODE_TOLERANCE = 0.25
_INTEGER = re.compile(r"\s*\+?\d{1,9}\s*")
#: ``grid_specification`` attributes of the extent [deg], as named in
#: :class:`rockscreen.pipeline.hazard.shakemap.ShakeMapGrid`.
EXTENT = ("lon_min", "lat_min", "lon_max", "lat_max")


def _local(tag: str) -> str:
    return tag.rsplit("}", 1)[-1]


def _float(attrs: dict[str, str], key: str, path: Path) -> float:
    try:
        value = float(attrs[key])
    except (KeyError, ValueError):
        value = math.nan
    if not math.isfinite(value):
        raise ShakeMapError(
            f"{printable(path)}: grid_specification attribute {key!r} is missing or not a "
            f"finite number (found {printable(repr(attrs.get(key)))[:60]})"
        )
    return value


def _count(attrs: dict[str, str], key: str, path: Path) -> int:
    """Return ``nlon`` or ``nlat``: an integer of at least 2 (``"361"`` or ``"361.0"``)."""
    value = _float(attrs, key, path)
    if not (value.is_integer() and 2 <= value <= MAX_NODES):
        raise ShakeMapError(
            f"{printable(path)}: grid_specification {key}={printable(attrs[key])[:40]!r} must "
            f"be an integer from 2 to {MAX_NODES}"
        )
    return int(value)


def _read_bytes(path: Path) -> bytes:
    """Return the bytes of a regular file of at most :data:`MAX_FILE_BYTES`, refusing others."""
    shown = printable(path)
    try:
        # O_NONBLOCK: opening a FIFO does not wait for a writer; it is then refused.
        fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    except OSError as exc:
        raise ShakeMapError(f"{shown}: cannot read the ShakeMap ({exc.strerror})") from None
    with os.fdopen(fd, "rb") as stream:
        info = os.fstat(stream.fileno())
        if not stat.S_ISREG(info.st_mode):
            raise ShakeMapError(
                f"{shown}: not a regular file (a FIFO, device or folder); refused before reading"
            )
        if info.st_size > MAX_FILE_BYTES:
            raise ShakeMapError(
                f"{shown}: {info.st_size} bytes, above the {MAX_FILE_BYTES // 1024**2} MiB "
                "accepted for a ShakeMap grid; refused before reading"
            )
        raw = stream.read(MAX_FILE_BYTES + 1)
    if len(raw) > MAX_FILE_BYTES:
        raise ShakeMapError(f"{shown}: grew beyond {MAX_FILE_BYTES // 1024**2} MiB while read")
    return raw


def _fields(elements: dict, path: Path) -> dict[str, tuple[int, str]]:
    """Return ``grid_field`` name -> (0-based column, units); unique names and indices."""
    fields: dict[str, tuple[int, str]] = {}
    by_index: dict[int, str] = {}
    for element in elements.get("grid_field", []):
        name = element.attrib.get("name", "").strip().upper()
        index_text = element.attrib.get("index", "")
        shown = printable(name)[:40]
        if not name:
            raise ShakeMapError(f"{printable(path)}: a grid_field without a name")
        if not _INTEGER.fullmatch(index_text) or int(index_text) < 1:
            raise ShakeMapError(
                f"{printable(path)}: grid_field {shown!r} has index "
                f"{printable(index_text)[:40]!r}; expected an integer >= 1"
            )
        index = int(index_text)
        if name in fields:
            raise ShakeMapError(
                f"{printable(path)}: grid_field {shown!r} is declared twice (index "
                f"{fields[name][0] + 1} and {index}); refused, one is not silently chosen"
            )
        if index in by_index:
            raise ShakeMapError(
                f"{printable(path)}: grid_fields {printable(by_index[index])[:40]!r} and "
                f"{shown!r} have the same index {index}"
            )
        by_index[index] = name
        fields[name] = (index - 1, element.attrib.get("units", ""))
    return fields


def parse_grid_file(path: Path) -> tuple[ET.Element, dict, dict, int, int, dict, np.ndarray]:
    """Parse and check a ``shakemap_grid`` file (module docstring).

    Parameters
    ----------
    path : Path
        The ``grid.xml`` or ``uncertainty.xml`` file.

    Returns
    -------
    tuple
        The root element, the root's child elements by local name, the extent (:data:`EXTENT`
        -> deg), ``nlon``, ``nlat``, the fields (name -> (0-based column, units)) and the
        ``grid_data`` rows as a 2-D array.

    Raises
    ------
    ShakeMapError
        For a file that is not regular or too large, a DOCTYPE/ENTITY, malformed XML, a
        header that does not describe a grid, missing ``LON``/``LAT`` or repeated fields,
        rows that are not numbers, too narrow, or more than the nodes.
    """
    raw = _read_bytes(path)
    shown = printable(path)
    try:
        root = SafeET.fromstring(raw, forbid_dtd=True)
    except DefusedXmlException:
        raise ShakeMapError(
            f"{shown}: declares a DOCTYPE or ENTITY; refused (a ShakeMap grid.xml has none, "
            "and entity expansion can exhaust memory)"
        ) from None
    except (ET.ParseError, ValueError, LookupError) as exc:
        raise ShakeMapError(f"{shown}: not well-formed XML ({printable(exc)[:200]})") from None
    if _local(root.tag) != "shakemap_grid":
        raise ShakeMapError(
            f"{shown}: root element {printable(_local(root.tag))[:40]!r}, expected 'shakemap_grid'"
        )
    elements: dict[str, list[ET.Element]] = {}
    for child in root:
        if isinstance(child.tag, str):
            elements.setdefault(_local(child.tag), []).append(child)
    if "grid_specification" not in elements or "grid_data" not in elements:
        raise ShakeMapError(f"{shown}: no grid_specification or grid_data element")
    spec = elements["grid_specification"][0].attrib
    extent = {key: _float(spec, key, path) for key in EXTENT}
    lon_min, lat_min, lon_max, lat_max = extent.values()
    nlon, nlat = _count(spec, "nlon", path), _count(spec, "nlat", path)
    if (
        not (-360.0 <= lon_min < lon_max <= 360.0 and -90.0 <= lat_min < lat_max <= 90.0)
        or nlon * nlat > MAX_NODES
    ):
        raise ShakeMapError(
            f"{shown}: grid_specification lon {lon_min:g} to {lon_max:g}, lat {lat_min:g} to "
            f"{lat_max:g} deg, {nlon} x {nlat} nodes does not describe a grid (min < max, "
            f"lat within +-90 deg, at most {MAX_NODES} nodes)"
        )
    fields = _fields(elements, path)
    for name in ("LON", "LAT"):
        if name not in fields:
            raise ShakeMapError(
                f"{shown}: no grid_field {name!r} (fields: {printable(', '.join(fields))[:200]})"
            )
    text = elements["grid_data"][0].text or ""
    try:
        data = np.array([line.split() for line in text.strip().splitlines()], dtype=float)
    except ValueError:
        raise ShakeMapError(f"{shown}: grid_data rows are not all numbers of equal count") from None
    if data.ndim != 2 or data.shape[0] == 0:
        raise ShakeMapError(f"{shown}: grid_data has shape {data.shape}; expected rows of numbers")
    widest = max(index for index, _ in fields.values()) + 1
    if data.shape[1] < widest:
        raise ShakeMapError(
            f"{shown}: grid_data rows have {data.shape[1]} numbers but a grid_field has "
            f"index {widest}"
        )
    if data.shape[0] > nlon * nlat:
        raise ShakeMapError(
            f"{shown}: grid_data has {data.shape[0]} rows but the header describes {nlon} x "
            f"{nlat} = {nlon * nlat} nodes: more rows than nodes; refused"
        )
    return root, elements, extent, nlon, nlat, fields, data


def refuse_bad_row(path: Path, what: str, column: np.ndarray, bad: np.ndarray, rule: str) -> None:
    """Raise the refusal of the first row where ``bad`` holds (none: return).

    Parameters
    ----------
    path : Path
        The file, named in the message.
    what : str
        The quantity (``"PGA"``, ``"LON"``, ...).
    column : numpy.ndarray
        Its value at each ``grid_data`` row.
    bad : numpy.ndarray of bool
        Which rows are refused.
    rule : str
        Why, as the end of the message.

    Raises
    ------
    ShakeMapError
        Naming the first bad row and its value.
    """
    if np.any(bad):
        row = int(np.nonzero(bad)[0][0])
        raise ShakeMapError(
            f"{printable(path)}: {what} {float(column[row])!r} at grid_data row {row + 1} (of "
            f"{column.size}) {rule}; refused"
        )


def node_indices(data, fields, extent, nlon, nlat, path) -> tuple[np.ndarray, np.ndarray]:
    """Return the (column, row) node index of every data row, refusing rows off the grid.

    Parameters
    ----------
    data, fields, extent, nlon, nlat
        As returned by :func:`parse_grid_file`.
    path : Path
        The file, named in messages.

    Returns
    -------
    tuple of numpy.ndarray
        Node indices along longitude (``i``) and latitude (``j``) of each row.

    Raises
    ------
    ShakeMapError
        For a coordinate that is not finite, a row outside the extent or off a node, or two
        rows on one node.
    """
    lon, lat = data[:, fields["LON"][0]], data[:, fields["LAT"][0]]
    for name, values in (("LON", lon), ("LAT", lat)):
        refuse_bad_row(path, name, values, ~np.isfinite(values), "is not a finite number [deg]")
    dlon = (extent["lon_max"] - extent["lon_min"]) / (nlon - 1)
    dlat = (extent["lat_max"] - extent["lat_min"]) / (nlat - 1)
    x = (lon - extent["lon_min"]) / dlon
    y = (lat - extent["lat_min"]) / dlat
    outside = (x < -NODE_TOLERANCE) | (x > nlon - 1 + NODE_TOLERANCE)
    outside |= (y < -NODE_TOLERANCE) | (y > nlat - 1 + NODE_TOLERANCE)
    if np.any(outside):
        row = int(np.nonzero(outside)[0][0])
        raise ShakeMapError(
            f"{printable(path)}: grid_data row {row + 1} (lon {lon[row]:g}, lat {lat[row]:g}) "
            "is outside the grid_specification extent"
        )
    i, j = np.rint(x).astype(np.int64), np.rint(y).astype(np.int64)
    off = (np.abs(x - i) > NODE_TOLERANCE) | (np.abs(y - j) > NODE_TOLERANCE)
    if np.any(off):
        row = int(np.nonzero(off)[0][0])
        raise ShakeMapError(
            f"{printable(path)}: grid_data row {row + 1} (lon {lon[row]:g}, lat {lat[row]:g}) "
            f"is not on a node of the {nlon} x {nlat} grid_specification (spacing {dlon:g}, "
            f"{dlat:g} deg): nlon/nlat do not describe the rows"
        )
    node = j * nlon + i
    order = np.argsort(node, kind="stable")
    repeated = np.nonzero(node[order][1:] == node[order][:-1])[0]
    if repeated.size:
        first, second = sorted((int(order[repeated[0]]), int(order[repeated[0] + 1])))
        raise ShakeMapError(
            f"{printable(path)}: grid_data rows {first + 1} and {second + 1} are the same node "
            f"(lon {lon[first]:g}, lat {lat[first]:g}): duplicated rows; refused"
        )
    return i, j
