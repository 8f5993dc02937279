"""The code checks beyond the built-in ones, as every output shows them (issue 29).

The outputs have their own columns for the checks rockscreen is built with (rocking of the
whole tower and of each part model, the kinematic checks of the whole tower, the belfry
and the bell gable, the shaft's LV1 model). A code check added as a module
(:mod:`rockscreen.pipeline.risk.checks.code`) is shown by iterating the checks an archive
stores (:meth:`rockscreen.pipeline.archive.kinds.AssessReader.checks`, from ``/checks`` and
``/pivot``) or, in ``assess``'s own process, the registry's
(:func:`rockscreen.pipeline.risk.checks.governing.check_columns`): both are
:class:`~rockscreen.pipeline.archive.long_schema.CheckColumns`. Its label is the
catalogue's (``check.<id>``, English and Italian), its reason for not being made the
message stored in ``checks_not_made_codes``. Nothing here imports the risk computation.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

from rockscreen.pipeline.archive.risk_schema import KINEMATIC_PARTS
from rockscreen.pipeline.report.values import Row
from rockscreen.pipeline.verdict.checks import DETAIL_UNITS, Method, check_label, loads_not_made
from rockscreen.pipeline.verdict.messages import Message, message

if TYPE_CHECKING:  # the archive's long tables import h5py: `rockscreen --help` does not
    from rockscreen.pipeline.archive.long_schema import CheckColumns

__all__ = ["added_checks", "capacity", "check_details", "not_made_reason"]

#: What the built-in kinematic checks are called after their part (``<part>.<what>``).
_KINEMATIC = ("kinematic_linear", "kinematic_nonlinear")


def _built_in(check: CheckColumns) -> bool:
    """Whether the outputs' own columns show ``check`` (rocking, kinematic, LV1)."""
    if check.method == Method.ROCKING.value or check.check == "shaft.lv1":
        return True
    part, _, what = check.check.partition(".")
    return part in KINEMATIC_PARTS and what in _KINEMATIC


def added_checks(checks: Sequence[CheckColumns]) -> list[CheckColumns]:
    """Return the checks of ``checks`` the outputs' own columns do not show, in order."""
    return [c for c in checks if not _built_in(c) and c.keys[0]]


def capacity(row: Row, check: CheckColumns) -> float | None:
    """Return the check's a_C [g] on a summary row, None when it was not made."""
    value = row.get(check.keys[0])
    return value if isinstance(value, float) and math.isfinite(value) else None


def not_made_reason(row: Row, check: CheckColumns) -> Message:
    """Return why ``check`` was not made on a summary row (its stored reason)."""
    codes = row.get("checks_not_made_codes")
    reason = loads_not_made(codes).get(check.check) if codes else None
    if reason is not None:
        return reason
    return message("not_made.code_check_result", check=check_label(check.check, check.part))


def check_details(row: Row, check: CheckColumns) -> Message | None:
    """Return the check's details on a row (``name value units; ...``), None without any."""
    items = []
    for name, column in check.details.items():
        value = row.get(column)
        if isinstance(value, float) and math.isfinite(value):
            word = DETAIL_UNITS[name]
            units = "" if word == "1" else f" {word}"
            items.append(message("check.detail", name=name, value=value, units=units))
    return message("check.details", items=tuple(items)) if items else None
