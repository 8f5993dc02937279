"""The work of a screening campaign: towers with their records, and what workers share.

A case is one tower × one record × one horizontal component × one model
(``docs/campaign.md``); the case engine (:mod:`rockscreen.pipeline.engine`) solves it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from rockscreen.pipeline.config import CampaignConfig
from rockscreen.pipeline.engine.motion import GroundMotion
from rockscreen.pipeline.engine.solvers import Solvers
from rockscreen.stations.tower import Tower

__all__ = ["CampaignShared", "TowerTask"]


@dataclass(frozen=True)
class TowerTask:
    """One tower and the records it is screened against."""

    #: Position of the tower in the inventory (orders the archive tables).
    index: int
    tower: Tower
    record_ids: tuple[str, ...]
    #: How the tower was paired, in words (``"nearest station IT.AQV at 3.2 km"``).
    pairing: str = ""
    #: Distance to the nearest paired station [km]; NaN when unknown.
    pairing_distance_km: float = math.nan


@dataclass(frozen=True)
class CampaignShared:
    """What every worker needs, shipped once per worker."""

    motions: dict[str, GroundMotion]
    config: CampaignConfig
    #: The solvers the workers make active (a process does not inherit the caller's
    #: :func:`~rockscreen.pipeline.engine.solvers.use_solvers`): default the compiled
    #: method's; tests give stand-ins.
    solvers: Solvers = Solvers()
