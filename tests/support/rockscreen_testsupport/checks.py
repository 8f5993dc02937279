"""Checks not made, as the verdict tests give them to the rules and the labels."""

from __future__ import annotations

from rockscreen.pipeline.risk.checks.governing import belfry_not_made
from rockscreen.pipeline.risk.checks.registry import code_check
from rockscreen.pipeline.verdict.messages import message

#: The belfry's rocking, not made (the belfry's columns are missing).
BELFRY_MISSING = belfry_not_made()
#: The shaft's LV1 check, not made (no wall thickness and masonry type in the inventory).
LV1_MISSING = code_check("shaft.lv1").not_made(
    message("not_made.lv1_columns", a="wall_thickness_m", b="masonry_type")
)
