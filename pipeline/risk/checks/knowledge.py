"""A tower's knowledge level (Circolare 2019 §C8.5.4) and the measured strength it allows.

The level sets the confidence factor F_C that divides the SLV capacity
(:func:`rockscreen.pipeline.risk.checks.confidence.confidence_factor`). A tower's level
is its row's ``knowledge_level``, else the run's ``--knowledge-level``, else
:data:`DEFAULT_KNOWLEDGE_LEVEL`, an assumption written in every row's note
(:func:`tower_knowledge_level`); a measured ``masonry_strength_mpa`` is used only at LC3
(§C8.5.4.1), and :func:`check_measured_strengths` refuses one at LC1 or LC2 before any work.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from rockscreen.pipeline.errors import RiskError
from rockscreen.stations.inventory_columns import (
    MEASURED_STRENGTH_COLUMN,
    TESTED_KNOWLEDGE_LEVEL,
)
from rockscreen.stations.tower import Tower

__all__ = ["DEFAULT_KNOWLEDGE_LEVEL", "check_measured_strengths", "tower_knowledge_level"]

#: Knowledge level taken when none is given (an assumption, written in every row's note).
DEFAULT_KNOWLEDGE_LEVEL = "LC1"


def tower_knowledge_level(tower: Tower, knowledge_level: str | None = None) -> tuple[str, str]:
    """Return a tower's knowledge level and where it comes from.

    The row's ``knowledge_level`` wins, else the run's, else :data:`DEFAULT_KNOWLEDGE_LEVEL`
    (an assumption).

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
    knowledge_level : str, optional
        The run's level (``--knowledge-level``), LC1, LC2 or LC3 (case ignored).

    Returns
    -------
    level : str
        ``"LC1"``, ``"LC2"`` or ``"LC3"``.
    source : str
        ``"inventory"``, ``"run"`` or ``"assumed"``.
    """
    if tower.knowledge_level:
        return tower.knowledge_level, "inventory"
    if knowledge_level:
        return str(knowledge_level).strip().upper(), "run"
    return DEFAULT_KNOWLEDGE_LEVEL, "assumed"


def check_measured_strengths(towers: Sequence[Any], knowledge_level: str | None = None) -> None:
    """Refuse a measured masonry strength on a tower assessed at LC1 or LC2, before any work.

    ``masonry_strength_mpa`` is a mean compressive strength from tests, used only at
    knowledge level LC3 (Circolare 2019 §C8.5.4.1; LC1 and LC2 take Table C8.5.I's value).
    The inventory refuses it on a row whose own ``knowledge_level`` is LC1 or LC2; a row
    without one takes the run's level (:func:`tower_knowledge_level`), checked here.

    Parameters
    ----------
    towers : sequence of rockscreen.stations.inventory.Tower
    knowledge_level : str, optional
        The run's level (``--knowledge-level``); None: :data:`DEFAULT_KNOWLEDGE_LEVEL`.

    Raises
    ------
    RiskError
        Naming the towers, their level and its source, and the ways out.
    """
    wrong = []
    for tower in towers:
        if getattr(tower, MEASURED_STRENGTH_COLUMN, None) is None:
            continue
        level, source = tower_knowledge_level(tower, knowledge_level)
        if level != TESTED_KNOWLEDGE_LEVEL:
            wrong.append((tower.id, level, source))
    if not wrong:
        return
    level, source = wrong[0][1:]
    why = {
        "run": "the run's --knowledge-level; no knowledge_level in the row",
        "assumed": "the default: no knowledge_level in the row and no --knowledge-level",
        "inventory": "the row's knowledge_level",
    }[source]
    shown = ", ".join(repr(tid) for tid, _, _ in wrong[:5])
    more = f" and {len(wrong) - 5} more" if len(wrong) > 5 else ""
    raise RiskError(
        f"{MEASURED_STRENGTH_COLUMN} is a measured f_m, used only at knowledge level "
        f"{TESTED_KNOWLEDGE_LEVEL} (Circolare 2019 §C8.5.4.1), but tower(s) {shown}{more} "
        f"with it are assessed at {level} ({why}): set "
        f"knowledge_level={TESTED_KNOWLEDGE_LEVEL} in their rows, run with --knowledge-level "
        f"{TESTED_KNOWLEDGE_LEVEL}, or leave {MEASURED_STRENGTH_COLUMN} empty"
    )
