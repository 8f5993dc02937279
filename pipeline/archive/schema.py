"""The archive schema: format name, versions, and every table's columns with units.

One place for what rockscreen writes into HDF5: the column specs below are used by the
writers and the readers. Units follow UDUNITS spelling: ``"1"`` for a dimensionless
number, ``"m/s2"``, ``"rad"``, ``"deg"``, ``""`` for text and booleans.
"""

from __future__ import annotations

#: Column spec: name -> (kind, units). Kinds: "str", "f8", "i8", "bool".
ColumnSpec = dict[str, tuple[str, str]]

#: Columns of the results table: name -> (kind, units). Kinds: "str", "f8", "i8", "bool".
RESULT_COLUMNS: ColumnSpec = {
    "tower_id": ("str", ""),
    "record_id": ("str", ""),
    "component": ("str", ""),
    "model": ("str", ""),
    "status": ("str", ""),
    "width_m": ("f8", "m"),
    "alpha_rad": ("f8", "rad"),
    "p_rad_s": ("f8", "rad/s"),
    "eta": ("f8", "1"),
    "pga_m_s2": ("f8", "m/s**2"),
    "theta_max_rad": ("f8", "rad"),
    "theta_max_over_alpha": ("f8", "1"),
    "overturned": ("bool", ""),
    "uplifted": ("bool", ""),
    "slipped": ("bool", ""),
    "n_impacts": ("i8", "1"),
    "t_overturn_s": ("f8", "s"),
    "slip_max_m": ("f8", "m"),
    "slip_residual_m": ("f8", "m"),
    "friction_demand_max": ("f8", "1"),
}

#: Columns of the per-tower summary table: name -> (kind, units).
SUMMARY_COLUMNS: ColumnSpec = {
    "id": ("str", ""),
    "name": ("str", ""),
    "lat": ("f8", "deg"),
    "lon": ("f8", "deg"),
    "stations": ("str", ""),
    "n_records": ("i8", "1"),
    "n_cases": ("i8", "1"),
    "theta_max_over_alpha": ("f8", "1"),
    "theta_max_rad": ("f8", "rad"),
    "alpha_rad": ("f8", "rad"),
    "overturned": ("bool", ""),
    "safety_factor": ("f8", "1"),
    "safety_factor_lower": ("f8", "1"),
    "safety_factor_solves": ("i8", "1"),
    "risk_class": ("str", ""),
    "governing_record": ("str", ""),
    "governing_model": ("str", ""),
    "governing_component": ("str", ""),
}

#: Columns of the failures table.
FAILURE_COLUMNS: ColumnSpec = {
    "kind": ("str", ""),
    "subject": ("str", ""),
    "reason": ("str", ""),
}
