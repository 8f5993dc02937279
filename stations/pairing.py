"""Pairing towers with the stations whose records shake them.

The rule, per tower, first match wins:

1. an explicit ``station`` in the inventory (``"NET.STA"``, or ``"STA"`` matching that
   station code in any network) pairs the tower with that station only; when no
   record comes from it, the tower gets no pair and the reason says so;
2. a tower without coordinates, or a campaign where no station has coordinates, is
   paired with every station (nothing allows choosing one);
3. otherwise the nearest station with coordinates, by geodesic distance on the WGS84
   ellipsoid (:func:`obspy.geodetics.gps2dist_azimuth`), when it lies within
   ``max_distance_km``; beyond it the tower gets no pair. Stations without
   coordinates are then added to every such tower too: a record that cannot be placed
   cannot be ruled out, and a screening errs on the safe side.

Ties in distance (to 1 mm) go to the first key in alphabetical order, so a pairing never
depends on the order of the files.

``DEFAULT_MAX_DISTANCE_KM = 50`` km: the Italian strong-motion network (RAN, several
hundred stations; Gorini et al., 2010, Bull. Earthquake Eng. 8:1075-1090) has a mean
spacing of roughly 20-25 km, so a tower's nearest station is usually within 10-20 km
and 50 km keeps almost every tower paired; farther away a record stands for a
different shaking level (peak ground acceleration typically falls by a factor 2-3
between 10 and 40 km from a moderate event, e.g. the ITA10 model of Bindi et al.,
2011), so using it would misstate the demand and the tower is reported unpaired.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass

from obspy.geodetics import gps2dist_azimuth

from rockscreen.stations.errors import RockscreenError
from rockscreen.stations.tower import Tower, swapped_hint

__all__ = [
    "DEFAULT_MAX_DISTANCE_KM",
    "Pairing",
    "StationSite",
    "pair_towers",
    "pair_towers_detailed",
]

#: Default largest tower-station distance for nearest-station pairing [km] (see module doc).
DEFAULT_MAX_DISTANCE_KM = 50.0


@dataclass(frozen=True)
class StationSite:
    """A station that recorded at least one record of the campaign."""

    #: ``"NET.STA"``.
    key: str
    #: WGS84 coordinates [deg]; None (or NaN) when unknown.
    latitude: float | None = None
    longitude: float | None = None

    @property
    def has_coordinates(self) -> bool:
        """Whether latitude and longitude are both known and finite."""
        return _finite(self.latitude) and _finite(self.longitude)

    @property
    def station_code(self) -> str:
        """The station code: the part of the key after the network code."""
        return self.key.split(".", 1)[-1]


@dataclass(frozen=True)
class Pairing:
    """How one tower was paired."""

    #: Station keys ``"NET.STA"`` paired with the tower (empty: unpaired).
    keys: tuple[str, ...]
    #: ``"explicit"``, ``"nearest"``, ``"all"`` or ``"unpaired"``.
    rule: str
    #: Distance to the nearest paired station with coordinates [km], when known.
    distance_km: float | None
    #: One line a user reads: why these stations, or why none.
    reason: str


def pair_towers(
    towers: Sequence[Tower],
    sites: Sequence[StationSite],
    *,
    max_distance_km: float = DEFAULT_MAX_DISTANCE_KM,
) -> dict[str, list[str]]:
    """Pair each tower with the station keys whose records it is screened against.

    Parameters
    ----------
    towers, sites, max_distance_km
        As in :func:`pair_towers_detailed`, which this keeps only the keys of.

    Returns
    -------
    dict
        Tower id -> list of station keys (empty when the tower cannot be paired; see
        :func:`pair_towers_detailed` for the reason).
    """
    detailed = pair_towers_detailed(towers, sites, max_distance_km=max_distance_km)
    return {tower_id: list(pairing.keys) for tower_id, pairing in detailed.items()}


def pair_towers_detailed(
    towers: Sequence[Tower],
    sites: Sequence[StationSite],
    *,
    max_distance_km: float = DEFAULT_MAX_DISTANCE_KM,
) -> dict[str, Pairing]:
    """Pair each tower with stations, keeping the rule, the distance and the reason.

    Parameters
    ----------
    towers : sequence of Tower
        The inventory.
    sites : sequence of StationSite
        The stations of the campaign's records.
    max_distance_km : float
        Largest distance for nearest-station pairing [km], > 0.

    Returns
    -------
    dict
        Tower id -> :class:`Pairing`, in inventory order.

    Raises
    ------
    RockscreenError
        When ``max_distance_km`` is not a positive number or two sites share a key.
    """
    if not _finite(max_distance_km) or max_distance_km <= 0:
        raise RockscreenError(f"max_distance_km={max_distance_km!r} must be a number > 0 [km]")
    ordered = sorted(sites, key=lambda site: site.key)
    keys = [site.key for site in ordered]
    if len(set(keys)) != len(keys):
        duplicates = sorted({key for key in keys if keys.count(key) > 1})
        raise RockscreenError(f"station sites: duplicate key(s) {', '.join(duplicates)}")
    return {tower.id: _pair_one(tower, ordered, max_distance_km) for tower in towers}


def _pair_one(tower: Tower, sites: list[StationSite], max_distance_km: float) -> Pairing:
    """Apply the pairing rule (module docstring) to one tower; ``sites`` sorted by key."""
    if tower.station is not None:
        return _pair_explicit(tower, sites)
    located = [site for site in sites if site.has_coordinates]
    unlocated = tuple(site.key for site in sites if not site.has_coordinates)
    if not sites:
        return Pairing((), "unpaired", None, "no station records in the campaign")
    if not tower.has_coordinates or not located:
        why = (
            "the tower has no coordinates"
            if not tower.has_coordinates
            else ("no station has coordinates")
        )
        return Pairing(tuple(site.key for site in sites), "all", None, f"every station: {why}")
    # Rounded to 1 mm so that equal distances up to floating-point noise tie, and a tie
    # goes to the first key.
    distances = [(round(_distance_km(tower, site), 6), site.key) for site in located]
    distance, key = min(distances)
    if distance > max_distance_km:
        if unlocated:
            return Pairing(
                unlocated,
                "all",
                None,
                f"nearest located station {key} is {distance:.1f} km away "
                f"(> {max_distance_km:g} km); stations without coordinates: "
                f"{', '.join(unlocated)}",
            )
        return Pairing(
            (),
            "unpaired",
            distance,
            f"no station within {max_distance_km:g} km (nearest {key} at {distance:.1f} km)"
            f"{swapped_hint(tower.lat, tower.lon)}",
        )
    extra = f"; plus stations without coordinates: {', '.join(unlocated)}" if unlocated else ""
    return Pairing(
        (key, *unlocated), "nearest", distance, f"nearest station {key} at {distance:.1f} km{extra}"
    )


def _pair_explicit(tower: Tower, sites: list[StationSite]) -> Pairing:
    """Pair with the station named in the inventory; ``"STA"`` matches any network."""
    wanted = tower.station.upper()
    if "." in wanted:
        matches = [site for site in sites if site.key.upper() == wanted]
    else:
        matches = [site for site in sites if site.station_code.upper() == wanted]
    if not matches:
        return Pairing(
            (),
            "unpaired",
            None,
            f"explicit station {tower.station!r} is not among the records' stations "
            f"({', '.join(site.key for site in sites) or 'none'})",
        )
    distance = None
    if tower.has_coordinates and matches[0].has_coordinates:
        distance = _distance_km(tower, matches[0])
    where = f" at {distance:.1f} km" if distance is not None else ""
    keys = tuple(site.key for site in matches)
    return Pairing(keys, "explicit", distance, f"explicit station {', '.join(keys)}{where}")


def _distance_km(tower: Tower, site: StationSite) -> float:
    """Geodesic distance between a tower and a station on the WGS84 ellipsoid [km]."""
    with warnings.catch_warnings():
        # Without geographiclib, ObsPy's Vincenty formula warns near antipodes and
        # returns half the circumference: far beyond any pairing distance either way.
        warnings.simplefilter("ignore", UserWarning)
        metres, _, _ = gps2dist_azimuth(tower.lat, tower.lon, site.latitude, site.longitude)
    return metres / 1000.0


def _finite(value: object) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)
