"""The result types the products store: what the archive writes and reads back.

They live below both the products that fill them and the archive that stores them, so
that the archive never imports a product (``docs/architecture.md``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["Failure", "History", "TowerOutcome"]


@dataclass(frozen=True)
class Failure:
    """Something that could not be read, processed, paired or solved."""

    #: ``"read"``, ``"process"``, ``"pair"`` or ``"solve"``.
    kind: str
    #: The file, record, tower or case concerned.
    subject: str
    #: One line a user reads.
    reason: str

    def as_row(self) -> dict[str, str]:
        """Return the failure as a row of the failures table."""
        return {"kind": self.kind, "subject": self.subject, "reason": self.reason}


@dataclass
class History:
    """A (possibly decimated) time history of one case."""

    tower_id: str
    record_id: str
    component: str
    model: str
    #: Times [s].
    t: np.ndarray
    #: Tower rotation [rad].
    theta: np.ndarray
    #: Building slip relative to the ground [m] (zeros for single-block models).
    u: np.ndarray
    #: 0 rest, 1 tower rocking, 2 building sliding, 3 both.
    regime: np.ndarray
    #: Slenderness angle of the block [rad].
    alpha: float


@dataclass
class TowerOutcome:
    """Everything a worker computed for one tower."""

    index: int
    tower_id: str
    summary: dict[str, Any]
    rows: list[dict[str, Any]]
    histories: list[History]
    failures: list[Failure]
