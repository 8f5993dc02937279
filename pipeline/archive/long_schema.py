"""The units of assess format 4's long tables, declared once per field.

``/fits``, ``/checks``, ``/messages`` and ``/pivot`` (:mod:`rockscreen.pipeline.archive.
long_tables`, docs/risk.md "The summary as long tables"): each field's units, from which the
assess schema (:func:`rockscreen.pipeline.archive.risk_schema.assess_tables`), the writer, the
readers' checks and ``docs/archive_layout.md`` follow. The details of a check take their units
from the verdict (:data:`rockscreen.pipeline.verdict.checks.DETAIL_UNITS`). Which columns of
the wide summary row are fits is :func:`fit_cells`; the wide summary's units of those columns
are the fields' (``assess_tables()["summary"]``), declared nowhere else. This module imports no
HDF5, so the command line's help reads the schema without it.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

from rockscreen.pipeline.archive.schema import DIMENSIONLESS, G_UNITS, LENGTH, TEXT, TIME
from rockscreen.pipeline.verdict.checks import DETAIL_UNITS

__all__ = [
    "CheckColumns",
    "CHECK_FIELDS",
    "FIT_FIELDS",
    "LONG_TABLES",
    "MESSAGE_FIELDS",
    "PIVOT_FIELDS",
    "fit_cells",
]

#: Units of the schema words of :data:`~rockscreen.pipeline.verdict.checks.DETAIL_UNITS`.
_WORD_UNITS = {"g": G_UNITS, "1": DIMENSIONLESS, "s": TIME, "m": LENGTH}

#: ``/fits``: one row per tower x fit; field -> units (NaN or ``""``: the fit has no such
#: field, or it was not made).
FIT_FIELDS: dict[str, str] = {
    "tower": DIMENSIONLESS,  # the tower's row in /summary
    "fit": TEXT,  # collapse, slv, stripe, <part>.collapse, <part>.slv
    "median_g": G_UNITS,  # ag on rock
    "beta": DIMENSIONLESS,
    "bound": TEXT,  # "", "lower", "upper" (verdict.status.Bound)
    "se_ln_median": DIMENSIONLESS,
    "se_beta": DIMENSIONLESS,
    "loglik": DIMENSIONLESS,  # densities in 1/g
    "n_records": DIMENSIONLESS,
    "n_censored": DIMENSIONLESS,
    "deviance": DIMENSIONLESS,  # the stripe fit's
    "dof": DIMENSIONLESS,
    "max_residual": DIMENSIONLESS,
    "median_lo90_g": G_UNITS,  # 90 % bootstrap interval over the records
    "median_hi90_g": G_UNITS,
    "n_solves": DIMENSIONLESS,  # a part model's IDA
}

#: ``/checks``: one row per tower x check; field -> units.
CHECK_FIELDS: dict[str, str] = {
    "tower": DIMENSIONLESS,  # the tower's row in /summary
    "check": TEXT,  # <part>.<what>: tower.rocking, shaft.lv1, belfry.kinematic_nonlinear, ...
    "part": TEXT,
    "family": TEXT,  # verdict.checks.Family
    "method": TEXT,  # verdict.checks.Method
    "status": TEXT,  # verdict.status.Status: made, not_made
    "capacity_ag_g": G_UNITS,  # a_C, ag on rock
    "safety_index": DIMENSIONLESS,  # I_S
    "bound": TEXT,  # "", "lower", "upper"
    "reason_code": TEXT,  # why not made: a message code ("" when none is stored)
    "reason_params": TEXT,  # its parameters, JSON
    **{name: _WORD_UNITS[word] for name, word in DETAIL_UNITS.items()},
}

#: ``/messages``: one row per tower x message of a message column; field -> units.
MESSAGE_FIELDS: dict[str, str] = {
    "tower": DIMENSIONLESS,
    "column": TEXT,  # the summary column the message belongs to (note_codes)
    "code": TEXT,
    "params": TEXT,  # JSON
}

#: ``/pivot``: one row per column of the wide summary row, in its order.
PIVOT_FIELDS: dict[str, str] = {
    "column": TEXT,
    "kind": TEXT,  # bool, i8, f8, str
    "table": TEXT,  # fits, checks, messages; "" : in /summary
    "key": TEXT,  # the fit or check (the row's fit/check field)
    "field": TEXT,
}

#: The long tables of assess format 4 and their units (in
#: :func:`~rockscreen.pipeline.archive.risk_schema.assess_tables`).
LONG_TABLES: dict[str, dict[str, str]] = {
    "fits": FIT_FIELDS,
    "checks": CHECK_FIELDS,
    "messages": MESSAGE_FIELDS,
    "pivot": PIVOT_FIELDS,
}

#: The censored IDA fits' columns, ``<level>_<suffix>``: suffix -> field.
_CENSORED = ("median_g", "beta", "bound", "se_ln_median", "se_beta", "loglik")
_COUNTS = ("n_records", "n_censored")
_STRIPE = (
    "median_g",
    "beta",
    "bound",
    "loglik",
    "deviance",
    "dof",
    "max_residual",
    "se_ln_median",
    "se_beta",
)


def fit_cells(parts: Sequence[str]) -> dict[str, tuple[str, str]]:
    """Return the fits' columns of a wide summary row: column -> (fit, field).

    Parameters
    ----------
    parts : sequence of str
        The part models' names (``<part>_fragility_*``, ``<part>_slv_*``).
    """
    cells: dict[str, tuple[str, str]] = {}
    for level in ("collapse", "slv"):
        for suffix in (*_CENSORED, *_COUNTS):
            cells[f"{level}_{suffix}"] = (level, suffix)
    cells["collapse_median_lo90_g"] = ("collapse", "median_lo90_g")
    cells["collapse_median_hi90_g"] = ("collapse", "median_hi90_g")
    for suffix in _STRIPE:
        cells[f"stripe_{suffix}"] = ("stripe", suffix)
    for part in parts:
        cells[f"{part}_fragility_median_g"] = (f"{part}.collapse", "median_g")
        cells[f"{part}_fragility_beta"] = (f"{part}.collapse", "beta")
        cells[f"{part}_fragility_bound"] = (f"{part}.collapse", "bound")
        cells[f"{part}_ida_n_solves"] = (f"{part}.collapse", "n_solves")
        cells[f"{part}_slv_median_g"] = (f"{part}.slv", "median_g")
        cells[f"{part}_slv_bound"] = (f"{part}.slv", "bound")
    return cells


@dataclass(frozen=True)
class CheckColumns:
    """Where one check's result is in a wide summary row (the writer's caller declares it)."""

    #: The check's id, ``<part>.<what>``.
    check: str
    part: str
    #: :class:`~rockscreen.pipeline.verdict.checks.Family` value.
    family: str
    #: :class:`~rockscreen.pipeline.verdict.checks.Method` value.
    method: str
    #: The columns of a_C [g], I_S [-] and their bound.
    keys: tuple[str, str, str]
    #: Detail name (:data:`~rockscreen.pipeline.verdict.checks.DETAIL_UNITS`) -> column.
    details: Mapping[str, str] = field(default_factory=dict)
