"""Station coordinates, orientations and sensitivities from StationXML.

A thin layer over :func:`obspy.read_inventory` that answers the questions rockscreen
asks -- where is station ``NET.STA``, which way does channel ``NET.STA.LOC.CHA`` point,
what converts its counts to physical units -- and turns every failure into a
:class:`rockscreen.stations.errors.StationMetadataError` naming the file and the station.
"""

from __future__ import annotations

import glob
import math
from dataclasses import dataclass
from pathlib import Path

from obspy import Inventory, UTCDateTime, read_inventory

from rockscreen.stations.errors import StationMetadataError
from rockscreen.stations.station_files import expand_station_paths

#: Markup refused in StationXML: a document type declaration can declare entities that
#: read local files or URLs (XML external entities) or expand exponentially; StationXML
#: (an XML Schema document) never needs one.
_FORBIDDEN_MARKUP = (b"<!DOCTYPE", b"<!ENTITY")
_CHUNK_BYTES = 1 << 20


def _check_no_dtd(path: Path) -> None:
    """Refuse a file holding ``<!DOCTYPE`` or ``<!ENTITY`` (in any 8/16/32-bit encoding).

    The file is scanned in chunks; NUL bytes are dropped first so UTF-16 and UTF-32 text
    is caught as well.
    """
    tail = b""
    longest = max(len(m) for m in _FORBIDDEN_MARKUP)
    with open(path, "rb") as handle:
        while chunk := handle.read(_CHUNK_BYTES):
            text = tail + chunk.replace(b"\x00", b"")
            for markup in _FORBIDDEN_MARKUP:
                if markup in text.upper():
                    raise StationMetadataError(
                        f"station metadata {_shown(path)!r}: holds a {markup.decode()} "
                        "declaration; StationXML never needs one and rockscreen refuses it "
                        "(it could read other files or URLs)"
                    )
            tail = text[-longest:]


def _shown(path) -> str:
    """Return the text with control characters and undecodable bytes escaped (messages)."""
    text = str(path)
    return "".join(
        f"\\x{ord(c) & 0xFF:02x}"
        if ord(c) < 0x20 or 0x7F <= ord(c) <= 0x9F or 0xDC80 <= ord(c) <= 0xDCFF
        else c
        for c in text
    )


@dataclass(frozen=True)
class Sensitivity:
    """Overall sensitivity of a channel."""

    #: Counts per input unit [counts/(input unit)].
    value: float
    #: Physical input units as StationXML writes them (``M/S**2``, ``M/S``...).
    input_units: str
    #: Frequency at which ``value`` holds [Hz].
    frequency: float


class StationMetadata:
    """Station metadata of one StationXML file (or an ObsPy :class:`~obspy.Inventory`).

    Parameters
    ----------
    inventory : obspy.Inventory
        The parsed metadata.
    source : str
        Where it came from, for error messages.
    """

    def __init__(self, inventory: Inventory, source: str = "<inventory>"):
        self.inventory = inventory
        self.source = source

    def station_codes(self) -> list[str]:
        """Return the ``NET.STA`` codes the metadata describes, sorted."""
        return sorted({f"{net.code}.{sta.code}" for net in self.inventory for sta in net})

    def _station(self, code: str):
        network, _, station = code.partition(".")
        if not network or not station:
            raise StationMetadataError(
                f"station code {_shown(code)!r} must be NET.STA, e.g. IT.AQV"
            )
        for net in self.inventory:
            if net.code != network:
                continue
            for sta in net:
                if sta.code == station:
                    return sta
        known = ", ".join(self.station_codes()) or "none"
        raise StationMetadataError(
            f"{_shown(self.source)}: no station {_shown(code)!r} (stations: {_shown(known)})"
        )

    def coordinates(self, code: str) -> dict[str, float]:
        """Return the coordinates of station ``NET.STA``.

        Parameters
        ----------
        code : str
            ``NET.STA`` (a longer SEED id ``NET.STA.LOC.CHA`` is accepted too).

        Returns
        -------
        dict
            ``latitude`` [deg], ``longitude`` [deg], ``elevation`` [m].

        Raises
        ------
        StationMetadataError
            If the station is not in the metadata.
        """
        station = self._station(".".join(code.split(".")[:2]))
        return {
            "latitude": float(station.latitude),
            "longitude": float(station.longitude),
            "elevation": float(station.elevation) if station.elevation is not None else math.nan,
        }

    def _channel(self, seed_id: str, time: UTCDateTime | None):
        try:
            network, station, location, channel = seed_id.split(".")
        except ValueError as exc:
            raise StationMetadataError(
                f"channel id {seed_id!r} must be NET.STA.LOC.CHA, e.g. IT.AQV..HNN"
            ) from exc
        selected = self.inventory.select(
            network=network, station=station, location=location, channel=channel, time=time
        )
        channels = [cha for net in selected for sta in net for cha in sta]
        if not channels:
            when = f" at {time}" if time is not None else ""
            raise StationMetadataError(
                f"{_shown(self.source)}: no channel {_shown(seed_id)!r}{when}"
            )
        return channels[0]

    def has_channel(self, seed_id: str, time: UTCDateTime | None = None) -> bool:
        """Tell whether the metadata describe channel ``NET.STA.LOC.CHA`` (at ``time``)."""
        try:
            self._channel(seed_id, time)
        except StationMetadataError:
            return False
        return True

    def orientation(self, seed_id: str, time: UTCDateTime | None = None) -> dict[str, float]:
        """Return ``azimuth`` [deg clockwise from north] and ``dip`` [deg down] of a channel.

        Values are NaN where the StationXML leaves them out.
        """
        channel = self._channel(seed_id, time)
        return {
            "azimuth": float(channel.azimuth) if channel.azimuth is not None else math.nan,
            "dip": float(channel.dip) if channel.dip is not None else math.nan,
        }

    def sensitivity(self, seed_id: str, time: UTCDateTime | None = None) -> Sensitivity:
        """Return the overall instrument sensitivity of a channel.

        Raises
        ------
        StationMetadataError
            If the channel is missing or has no instrument sensitivity.
        """
        channel = self._channel(seed_id, time)
        response = channel.response
        sens = response.instrument_sensitivity if response is not None else None
        if sens is None or not sens.value or not sens.input_units:
            raise StationMetadataError(
                f"{self.source}: channel {seed_id!r} has no instrument sensitivity"
            )
        return Sensitivity(
            value=float(sens.value),
            input_units=str(sens.input_units),
            frequency=float(sens.frequency) if sens.frequency is not None else math.nan,
        )


def read_station_metadata(source) -> StationMetadata:
    """Read StationXML into :class:`StationMetadata`, merging several files.

    Parameters
    ----------
    source : str, path-like, sequence of them, obspy.Inventory or StationMetadata
        StationXML files, folders of StationXML (their ``*.xml`` files) or glob patterns
        (:func:`rockscreen.stations.station_files.expand_station_paths`), or metadata already
        in memory. Several files are merged into one metadata set.

    Returns
    -------
    StationMetadata

    Raises
    ------
    StationMetadataError
        If a file is missing, is not readable StationXML, or holds a ``<!DOCTYPE`` or
        ``<!ENTITY`` declaration (refused: entities could read other files or URLs); if a
        folder holds no StationXML or a pattern matches no file; if two files place the
        same station at different coordinates.
    """
    if isinstance(source, StationMetadata):
        return source
    if isinstance(source, Inventory):
        return StationMetadata(source)
    paths = expand_station_paths(source)
    if len(paths) == 1:
        return _read_file(paths[0])
    merged = Inventory(networks=[], source="rockscreen")
    where: dict[str, tuple[float, float, Path]] = {}
    for path in paths:
        inventory = _read_file(path).inventory
        for net in inventory:
            for sta in net:
                code = f"{net.code}.{sta.code}"
                place = (float(sta.latitude), float(sta.longitude), path)
                first = where.setdefault(code, place)
                if abs(first[0] - place[0]) > 1e-4 or abs(first[1] - place[1]) > 1e-4:
                    raise StationMetadataError(
                        f"station {_shown(code)} is at lat {first[0]:g}, lon {first[1]:g} in "
                        f"{_shown(first[2])!r} and at lat {place[0]:g}, lon {place[1]:g} in "
                        f"{_shown(path)!r}; give one of the two files"
                    )
        merged += inventory
    return StationMetadata(merged, source=", ".join(str(p) for p in paths))


def _read_file(path: Path) -> StationMetadata:
    """Read one StationXML file (checked for declarations first)."""
    if not path.is_file():
        raise StationMetadataError(f"station metadata {_shown(path)!r}: no such file")
    try:
        _check_no_dtd(path)
        # Read by path with the format named: read_inventory would otherwise expand glob
        # patterns in the name and download URLs.
        inventory = read_inventory(glob.escape(str(path.absolute())), format="STATIONXML")
    except StationMetadataError:
        raise
    except Exception as exc:  # ObsPy raises many types for bad XML; report them all as one
        reason = " ".join(str(exc).split()) or type(exc).__name__
        raise StationMetadataError(
            f"station metadata {_shown(path)!r} is not readable StationXML: {_shown(reason)}"
        ) from exc
    return StationMetadata(inventory, source=str(path))


def station_coordinates(source, code: str) -> dict[str, float]:
    """Return ``latitude`` [deg], ``longitude`` [deg], ``elevation`` [m] of ``NET.STA``."""
    return read_station_metadata(source).coordinates(code)


__all__ = ["Sensitivity", "StationMetadata", "read_station_metadata", "station_coordinates"]
