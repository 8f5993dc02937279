"""The units of the code checks' summary columns of the assess archive, declared once.

The built-in checks' (the kinematic checks of the whole tower, the belfry and the bell
gable; the LV1 tower model) are declared here, beside the archive schema
(:mod:`rockscreen.pipeline.archive.risk_schema`), so that a reader without the check
registry knows them; a check registered as a module declares its own when it is registered
(:func:`rockscreen.pipeline.archive.risk_schema.declare_check_columns`, kept in
:data:`DECLARED`).
"""

from __future__ import annotations

from dataclasses import dataclass, field

from rockscreen.pipeline.archive.schema import DIMENSIONLESS, G_UNITS, LENGTH, TEXT, TIME

__all__ = ["DECLARED", "KINEMATIC_PARTS", "KINEMATIC_UNITS", "LV1_UNITS", "DeclaredColumns"]

#: The parts of the code's kinematic checks (``<part>_kinematic_*`` columns): mechanisms
#: of Circolare 2019 §C8.7.1, not models of the engine's registry.
KINEMATIC_PARTS = ("tower", "belfry", "gable")
#: The kinematic checks' summary columns -> units: the governing kinematic mechanism's
#: (prefix ``""``), the whole tower's (``tower_``), the belfry's (``belfry_``), the bell
#: gable's (``gable_``), and ``kinematic_mechanism`` (what the registered
#: ``<part>.kinematic_nonlinear`` checks of :mod:`rockscreen.pipeline.risk.checks.registry`
#: write; declared here so that a reader without the registry knows them).
KINEMATIC_UNITS: dict[str, str] = {
    **{
        f"{prefix}kinematic_{suffix}": units
        for prefix in ("", *(f"{part}_" for part in KINEMATIC_PARTS))
        for suffix, units in (
            ("alpha0", DIMENSIONLESS),
            ("e_star", DIMENSIONLESS),
            ("a0_g", G_UNITS),  # a0* with F_C
            ("du_star_m", LENGTH),  # d_SLV = 0.4 d0
            ("t_slv_s", TIME),  # T_SLV = 1.68 pi sqrt(d_SLV / a(d_SLV))
            ("t0_s", TIME),  # T0 of an element free to vibrate (0: rigidly held)
            ("linear_capacity_ag_g", G_UNITS),  # ag on rock at which the check holds
            ("nonlinear_capacity_ag_g", G_UNITS),
            ("linear_safety_index", DIMENSIONLESS),
            ("nonlinear_safety_index", DIMENSIONLESS),
            ("safety_index", DIMENSIONLESS),  # the non-linear check's (the code's verdict)
            ("linear_bound", TEXT),  # "", "lower" (holds at 2475 y), "upper"
            ("nonlinear_bound", TEXT),
            ("bound", TEXT),  # the non-linear check's
        )
    },
    "kinematic_mechanism": TEXT,
}
#: The LV1 tower model's summary columns -> units (the registered ``shaft.lv1`` check).
LV1_UNITS: dict[str, str] = {
    "lv1_capacity_ag_g": G_UNITS,
    "lv1_safety_index": DIMENSIONLESS,
    "lv1_acceleration_factor": DIMENSIONLESS,
    "lv1_period_s": TIME,
    "lv1_compression_ratio": DIMENSIONLESS,  # sigma_0 / (0.85 f_d) at the critical section
    "lv1_bound": TEXT,  # "", "lower" (holds at 2475 y), "upper" (fails at 30 y)
}


@dataclass
class DeclaredColumns:
    """Summary columns declared by code checks registered beyond the built-ins."""

    #: Column -> units spelling.
    units: dict[str, str] = field(default_factory=dict)
    #: Value column -> its bound column.
    bounds: dict[str, str] = field(default_factory=dict)


#: What the registered code checks declared
#: (:func:`rockscreen.pipeline.archive.risk_schema.declare_check_columns`).
DECLARED = DeclaredColumns()
