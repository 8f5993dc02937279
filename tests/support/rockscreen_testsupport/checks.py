"""Checks not made, as the verdict tests give them to the rules and the labels."""

from __future__ import annotations

from rockscreen.pipeline.verdict.checks import CheckResult, Family, Method
from rockscreen.pipeline.verdict.messages import message
from rockscreen.pipeline.verdict.status import Status

#: The belfry's rocking, not made (the belfry's columns are missing).
BELFRY_MISSING = CheckResult(
    "belfry.rocking",
    "belfry",
    Family.PART_ROCKING,
    Method.ROCKING,
    Status.NOT_MADE,
    reason=message("not_made.belfry"),
)
#: The shaft's LV1 check, not made (no wall thickness and masonry type in the inventory).
LV1_MISSING = CheckResult(
    "shaft.lv1",
    "shaft",
    Family.SHAFT_FLEXURE,
    Method.LV1,
    Status.NOT_MADE,
    reason=message("not_made.lv1_columns", a="wall_thickness_m", b="masonry_type"),
)
