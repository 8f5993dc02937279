"""Every registered code check of one tower in ``assess``'s worker: the one loop.

:func:`run_code_checks` runs each registered check's computation
(:func:`rockscreen.pipeline.risk.checks.registry.computations`, in their ``compute_order``):
a check whose inventory columns are missing (or that gives its own reason) is NOT_MADE with
that message, an error of the tower's data is FAILED with its message; neither raises. The
built-in checks (the kinematic checks, LV1) and a check added as a module of
:mod:`rockscreen.pipeline.risk.checks.code` go through the same loop, and
:func:`empty_check_columns` gives their columns of a row before it is filled.
"""

from __future__ import annotations

from rockscreen.pipeline.risk.checks import code
from rockscreen.pipeline.risk.checks.registry import (
    CheckContext,
    CheckOutput,
    CodeCheck,
    code_checks,
    computations,
    resolve,
)
from rockscreen.pipeline.verdict.checks import CheckResult, check_label
from rockscreen.pipeline.verdict.messages import Message, message
from rockscreen.pipeline.verdict.status import Status
from rockscreen.stations.errors import RockscreenError

__all__ = ["empty_check_columns", "registered_checks", "run_code_checks"]


def registered_checks() -> tuple[CodeCheck, ...]:
    """Return every code check, the modules of :mod:`.code` loaded first (tie-breaking order)."""
    code.load()
    return code_checks()


def empty_check_columns() -> dict[str, object]:
    """Return the columns every registered computation writes, empty (NaN, ``""``), in order."""
    registered_checks()
    out: dict[str, object] = {}
    for check in computations():
        out.update(check.empty_columns())
    return out


def _run(check: CodeCheck, context: CheckContext) -> CheckOutput:
    """Return one check's output on a tower: computed, else not made or failed with why."""
    reason = check.reason(context)
    if reason is not None:
        return CheckOutput(not_made=(check.not_made(reason),))
    try:
        output = resolve(check.compute)(context)
    except RockscreenError as exc:  # the tower's own data: said, not fatal
        label = check_label(check.id, check.part)
        error = message("not_made.code_check_error", check=label, error=str(exc))
        return CheckOutput(not_made=(check.not_made(error, Status.FAILED),))
    unknown = set(output.columns) - set(check.columns)
    if unknown:
        raise ValueError(f"code check {check.id!r} wrote undeclared columns {sorted(unknown)}")
    return output


def run_code_checks(
    context: CheckContext,
) -> tuple[dict[str, object], list[Message], list[CheckResult]]:
    """Return every registered check's columns, notes and checks not made for one tower.

    Parameters
    ----------
    context : CheckContext
        The tower, its site conditions, knowledge level and F_C.

    Returns
    -------
    columns : dict
        The summary columns the checks computed (those not computed keep their empty
        values, :func:`empty_check_columns`).
    notes : list of Message
        Their notes, in the computations' order.
    not_made : list of CheckResult
        The checks not made or failed, each with its reason (for the verdict).
    """
    registered_checks()
    columns: dict[str, object] = {}
    notes: list[Message] = []
    not_made: list[CheckResult] = []
    for check in computations():
        output = _run(check, context)
        columns.update(output.columns)
        notes += output.notes
        not_made += output.not_made
    return columns, notes, not_made
