"""The result types the products store: what the archive writes and reads back.

They live below both the products that fill them and the archive that stores them, so
that the archive never imports a product (``docs/architecture.md``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["CaseResult", "Failure", "History", "TowerOutcome"]


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


@dataclass
class CaseResult:
    """Outcome of one case of a study (``sweep``), with its histories (empty when not kept)."""

    #: The study case (:class:`rockscreen.pipeline.study.study_file.Case`).
    case: Any
    status: str
    overturned: bool
    theta_max: float
    theta_max_over_alpha: float
    n_impacts: int
    slip_max: float
    slip_residual: float
    eta: float
    alpha: float
    p: float
    t_end: float
    histories: dict[str, np.ndarray] = field(default_factory=dict)
    #: Sampling step of the excitation [s] (the case's, or the default of its frequency).
    dt: float = math.nan
    #: Duration of the excitation [s] (a pulse without padding: one period, half for the
    #: short shapes).
    duration: float = math.nan
