"""The units of every column of the assess and scenario archives, declared per table.

The campaign archive's columns are in :mod:`rockscreen.pipeline.archive.schema` with the
format constants and unit spellings this module uses; the risk archives
(:mod:`rockscreen.pipeline.archive.risk_archive`) read and write through these tables,
and the writer refuses a column that is not declared here. The assess archive's
``/inventory`` declares the campaign archive's ``/towers`` units
(:data:`~rockscreen.pipeline.archive.schema.TOWER_COLUMNS`): one inventory table, one set
of units.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from functools import lru_cache

from rockscreen.pipeline.archive.check_units import (
    DECLARED,
    KINEMATIC_PARTS,
    KINEMATIC_UNITS,
    LV1_UNITS,
)
from rockscreen.pipeline.archive.long_schema import FIT_FIELDS, LONG_TABLES, fit_cells
from rockscreen.pipeline.archive.schema import (
    ACCELERATION,
    DEGREES,
    DIMENSIONLESS,
    FAILURE_COLUMNS,
    G_UNITS,
    PER_YEAR,
    TEXT,
    TIME,
    TOWER_COLUMNS,
    YEARS,
)
from rockscreen.pipeline.engine.registry import CAMPAIGN, models

__all__ = [
    "EXTRAPOLATION_SHARE_LIMIT",
    "KINEMATIC_PARTS",
    "RISK_BOUND_COLUMNS",
    "RISK_ROOT_ATTRIBUTES",
    "RISK_SUMMARY_UNITS",
    "RISK_TABLES",
    "PART_SUFFIXES",
    "SCENARIO_TABLES",
    "UnitsTable",
    "KINEMATIC_UNITS",
    "LV1_UNITS",
    "assess_tables",
    "bound_columns",
    "declare_check_columns",
    "part_model_names",
    "table_units",
    "withdraw_check_columns",
]

#: Share of lambda_C [-] from the extrapolated hazard curve (beyond its last or below its
#: first tabulated point) above which the rate is flagged (the summary's
#: ``rate_extrapolated``): from there on, more than half of the number rests on a hazard the
#: code does not define. Here, beside the column, so the outputs' legends read it without
#: importing the hazard integral (:mod:`rockscreen.pipeline.risk.measures.hazard_integral`).
EXTRAPOLATION_SHARE_LIMIT = 0.5
#: Columns of one part model's fragility, ``<model>_<suffix>``: suffix -> units.
PART_SUFFIXES = {
    "fragility_median_g": G_UNITS,  # collapse (overturning) median, ag on rock
    "fragility_beta": DIMENSIONLESS,
    "fragility_bound": TEXT,  # "", "lower", "upper"
    "p_overturning_50y": DIMENSIONLESS,
    "slv_median_g": G_UNITS,
    "slv_bound": TEXT,  # the SLV fit's bound: that of the capacity and I_S
    "capacity_ag_g": G_UNITS,  # a_SLV = SLV median / F_C
    "safety_index": DIMENSIONLESS,
    "ida_n_solves": DIMENSIONLESS,
}


def part_model_names() -> tuple[str, ...]:
    """Return the names of the campaign models that rock a part of the tower (own block).

    Read from the engine's registry (:mod:`rockscreen.pipeline.engine.registry`): each has
    its own IDA and the ``<model>_*`` columns of :data:`PART_SUFFIXES`, so a part model is
    one module of :mod:`rockscreen.pipeline.engine.models`.
    """
    return tuple(m.name for m in models(CAMPAIGN) if m.own_block is not None)


def declare_check_columns(units: Mapping[str, str], bounds: Mapping[str, str]) -> None:
    """Declare a code check's summary columns with their units, and which are bounds.

    Called by :func:`rockscreen.pipeline.risk.checks.registry.register`: the ``summary`` of
    :func:`assess_tables` and :func:`bound_columns` follow a check added as a module (the
    built-in checks' columns are declared already, :mod:`.check_units`).

    Parameters
    ----------
    units : mapping
        Column -> units spelling (:mod:`rockscreen.pipeline.archive.schema`).
    bounds : mapping
        Value column -> its bound column (``""``, ``"lower"``, ``"upper"``).

    Raises
    ------
    ValueError
        For a column of the summary that is not a built-in check's, or one declared
        twice with different units.
    """
    builtin = {**KINEMATIC_UNITS, **LV1_UNITS}
    for column, spelling in units.items():
        if column in _ASSESS_TABLES["summary"] and builtin.get(column) != spelling:
            raise ValueError(f"summary column {column!r} is not a code check's to declare")
        if DECLARED.units.get(column, spelling) != spelling:
            raise ValueError(f"summary column {column!r} declared with two units")
    DECLARED.units.update((c, u) for c, u in units.items() if c not in _ASSESS_TABLES["summary"])
    DECLARED.bounds.update(bounds)


def withdraw_check_columns(columns: Iterable[str]) -> None:
    """Withdraw columns declared by :func:`declare_check_columns` (a check unregistered)."""
    for column in columns:
        DECLARED.units.pop(column, None)
        DECLARED.bounds.pop(column, None)


#: Units of the columns of one table: column name -> units. A key ending in ``*`` covers
#: every column starting with what precedes it (columns named after a model or a level).
UnitsTable = dict[str, str]

#: Columns every assess and scenario summary shares: the tower and its fragility.
_RISK_TOWER_UNITS: UnitsTable = {
    "id": TEXT,
    "name": TEXT,
    "comune": TEXT,
    "provincia": TEXT,
    "lat_deg": DEGREES,
    "lon_deg": DEGREES,
    "soil_class": TEXT,
    "fragility_median_g": G_UNITS,
    "fragility_beta": DIMENSIONLESS,
    "median_is_bound": TEXT,
    "risk_class": TEXT,
    "note": TEXT,
    # the note's messages as codes (verdict.messages.dumps); an archive written before
    # notes were stored as codes lacks the column
    "note_codes": TEXT,
}

#: The screening risk's columns of the assess summary (issue 31, docs/risk.md "The screening
#: risk in assess"): best estimates at mean strengths, no partial factor, the epistemic
#: uncertainty as a 90 % interval; apart from the code's verdict. ``*_bound`` columns hold
#: ``""``, ``"at_most"``, ``"at_least"`` or ``"both"`` (``verdict.screening_risk.RiskBound``).
RISK_SUMMARY_UNITS: UnitsTable = {
    "risk_p50_best": DIMENSIONLESS,
    "risk_p50_best_bound": TEXT,
    "risk_p50_lo90": DIMENSIONLESS,
    "risk_p50_lo90_bound": TEXT,
    "risk_p50_hi90": DIMENSIONLESS,
    "risk_p50_hi90_bound": TEXT,
    "risk_p50_mean": DIMENSIONLESS,
    "risk_p50_mean_bound": TEXT,
    "risk_rate_best_per_y": PER_YEAR,
    "risk_rate_lo90_per_y": PER_YEAR,
    "risk_rate_hi90_per_y": PER_YEAR,
    "risk_rank": DIMENSIONLESS,  # 1 = riskiest by the best estimate; 0: no risk
    "risk_band": TEXT,  # top_10, top_25, top_50, rest
    "risk_band_uncertain": TEXT,  # yes / no: the 90 % interval reaches another band
    "risk_governing_mechanism": TEXT,
    "risk_governing_share": DIMENSIONLESS,
    # share of samples whose capacity is continued beyond the NTC 2018 table (a value)
    "risk_extrapolated_share": DIMENSIONLESS,
    "risk_survey_first": TEXT,
    "risk_survey_first_index": DIMENSIONLESS,  # first-order Sobol' index of ln P
    "risk_survey_first_narrowing": DIMENSIONLESS,  # expected narrowing of the interval
    "risk_beta": DIMENSIONLESS,
    "risk_beta_source": TEXT,  # ida_fit, judgement_fema_p695
    "risk_samples": DIMENSIONLESS,
    "risk_judgement_inputs": TEXT,  # ";"-joined inputs whose prior is a judgement
    "risk_note_codes": TEXT,  # the risk side's messages as codes (verdict.messages.dumps)
}

#: The screening risk's value columns -> their bound column (flags ``at_most``,
#: ``at_least``, ``both``: not the ``lower``/``upper`` of :func:`bound_columns`).
RISK_BOUND_COLUMNS: dict[str, str] = {
    "risk_p50_best": "risk_p50_best_bound",
    "risk_p50_lo90": "risk_p50_lo90_bound",
    "risk_p50_hi90": "risk_p50_hi90_bound",
    "risk_p50_mean": "risk_p50_mean_bound",
    "risk_rate_best_per_y": "risk_p50_best_bound",
    "risk_rate_lo90_per_y": "risk_p50_lo90_bound",
    "risk_rate_hi90_per_y": "risk_p50_hi90_bound",
}

#: Root attributes of the assess archive that say how the screening risk was computed.
RISK_ROOT_ATTRIBUTES = (
    "risk_priors_source",  # the priors file's name, or "default"
    "risk_seed",
    "risk_samples",
    "risk_methods",  # JSON list: shaft_lv1_mean, kinematic_mean, rocking_ida, hazard_integral
    "risk_top_n",  # N of /risk_top_n
)

#: The screening risk's long tables (one row per tower x ag, per tower x input, per tower).
RISK_TABLES: dict[str, UnitsTable] = {
    "risk_fragility": {
        "tower_id": TEXT,
        "ag_g": G_UNITS,
        "p_median": DIMENSIONLESS,
        "p_lo90": DIMENSIONLESS,
        "p_hi90": DIMENSIONLESS,
        "p_mean": DIMENSIONLESS,
        "bounded_share": DIMENSIONLESS,
    },
    "risk_sensitivity": {
        "tower_id": TEXT,
        "input": TEXT,
        "index": DIMENSIONLESS,
        "narrowing": DIMENSIONLESS,
        "judgement": TEXT,  # yes / no
    },
    "risk_top_n": {
        "tower_id": TEXT,
        "side": TEXT,  # in / out of the top N
        "input": TEXT,
        "p_crosses": DIMENSIONLESS,
    },
}

#: Units of every column of the assess archive but the part models', per table.
_ASSESS_TABLES: dict[str, UnitsTable] = {
    "summary": {
        **_RISK_TOWER_UNITS,
        "site_lat_deg": DEGREES,
        "site_lon_deg": DEGREES,
        "soil_class_source": TEXT,
        "topography": TEXT,
        "use_class": TEXT,
        "nominal_life_y": YEARS,
        # the IDA fits (censored lognormal fits in ag on rock: collapse, SLV, the collapse
        # median's 90 % bootstrap interval) and the stripe fit (binomial likelihood of the
        # stripe counts, a check beside): the units of their /fits fields (long_schema)
        **{col: FIT_FIELDS[name] for col, (_, name) in fit_cells(()).items()},
        # 90 % bootstrap intervals over the records
        "annual_rate_lo90_per_y": PER_YEAR,
        "annual_rate_hi90_per_y": PER_YEAR,
        "safety_index_lo90": DIMENSIONLESS,
        "safety_index_hi90": DIMENSIONLESS,
        "bootstrap_resamples": DIMENSIONLESS,
        "bootstrap_fitted_collapse": DIMENSIONLESS,
        "bootstrap_fitted_slv": DIMENSIONLESS,
        "knowledge_level": TEXT,
        "confidence_factor": DIMENSIONLESS,
        "ida_n_solves": DIMENSIONLESS,
        "annual_rate_overturning_per_y": PER_YEAR,
        "p_overturning_50y": DIMENSIONLESS,
        # shares of lambda_C from the hazard curve extrapolated beyond TR 2475 y / below 30 y
        "rate_share_tr_over_2475": DIMENSIONLESS,
        "rate_share_tr_under_30": DIMENSIONLESS,
        "rate_extrapolated": TEXT,  # flag: the two shares exceed 50 %
        "basis_compliant": TEXT,  # flag: record sets meet NTC 2018 §3.2.3.6 / §7.3.5
        "capacity_pga_g": G_UNITS,
        "capacity_return_period_y": YEARS,
        "tr_slv_y": YEARS,
        "ag_slv_g": G_UNITS,
        "safety_index": DIMENSIONLESS,
        "acceleration_factor": DIMENSIONLESS,
        "n_stripes": DIMENSIONLESS,
        "n_solves": DIMENSIONLESS,
        "models": TEXT,
        # the code's kinematic checks (docs/code_checks.md) and the LV1 tower model of the
        # Guidelines (NaN: not in the inventory's data, see note)
        **KINEMATIC_UNITS,
        **LV1_UNITS,
        # the mechanism of lowest capacity; risk_class comes from its I_S
        "governing": TEXT,
        "governing_kind": TEXT,  # shaft flexure, tower rocking, belfry rocking, kinematic, gable
        "governing_check": TEXT,  # its id: tower.rocking, belfry.rocking, shaft.lv1, ...
        "governing_shown": TEXT,  # flag: false for a lower bound among other checks
        "governing_capacity_ag_g": G_UNITS,
        "governing_safety_index": DIMENSIONLESS,
        "governing_bound": TEXT,
        "completeness": TEXT,  # complete, partial, rocking_only (verdict.scales.Completeness)
        "checks_not_made": TEXT,  # checks that could fail earlier, not made, and why
        "checks_not_made_codes": TEXT,  # the same as JSON [[check id, [code, {params}]], ...]
        "checks_disagree": TEXT,  # one sentence when rocking and kinematic classes differ
        **RISK_SUMMARY_UNITS,
    },
    "stripes": {
        "tower_id": TEXT,
        "return_period_y": YEARS,
        "ag_g": G_UNITS,
        "models": TEXT,
        "n_records": DIMENSIONLESS,
        "n_overturned": DIMENSIONLESS,
        "n_vertical_limit": DIMENSIONLESS,
        "n_overturned_*": DIMENSIONLESS,  # one per model
        "n_damage_*": DIMENSIONLESS,  # one per damage level (0.2 -> n_damage_0p2)
    },
    "outcomes": {
        "tower_id": TEXT,
        "return_period_y": YEARS,
        "record": TEXT,
        "scale_factor": DIMENSIONLESS,
        "component": TEXT,
        "model": TEXT,
        "status": TEXT,
        "overturned": TEXT,
        "theta_max_over_alpha": DIMENSIONLESS,
    },
    "ida": {
        "tower_id": TEXT,
        "return_period_y": YEARS,  # the set's T_R (the tower's T_R,SLV)
        "set_ag_g": G_UNITS,  # the set's target ag on rock: scale 1
        "record": TEXT,
        "set_scale_factor": DIMENSIONLESS,  # the record's factor in its set
        "component": TEXT,
        "models": TEXT,
        "collapse_scale": DIMENSIONLESS,
        "collapse_ag_g": G_UNITS,
        "slv_scale": DIMENSIONLESS,
        "slv_ag_g": G_UNITS,
        "censored": TEXT,
        "slv_censored": TEXT,
        "censor_reason": TEXT,
        "n_solves": DIMENSIONLESS,
    },
    "selection": {
        "site_lon_deg": DEGREES,
        "site_lat_deg": DEGREES,
        "soil_class": TEXT,
        "topography": TEXT,
        "return_period_y": YEARS,
        "ratio_min": DIMENSIONLESS,
        "ratio_max": DIMENSIONLESS,
        "meets_tolerance": TEXT,
        "message": TEXT,
        "n_records": DIMENSIONLESS,
        "compliant": TEXT,
        "compliance_note": TEXT,
        # the period range of ratio_min/ratio_max (the compliance is measured over it)
        "period_from_s": TIME,
        "period_to_s": TIME,
    },
    # one row per record of each set, in /selection order then the set's order: the
    # set's row in /selection, the record's row in /records/index, its factor (exact)
    "set_records": {
        "set": DIMENSIONLESS,
        "record": DIMENSIONLESS,
        "scale_factor": DIMENSIONLESS,
    },
    # every record of the sets, stored once: one row per record; its samples in the
    # concatenated /records/x, y, z at [start, start + count) (count 0: no such component)
    "records/index": {
        "id": TEXT,
        "name": TEXT,
        "source": TEXT,
        "dt_s": TIME,
        "x_start": DIMENSIONLESS,
        "x_count": DIMENSIONLESS,
        "y_start": DIMENSIONLESS,
        "y_count": DIMENSIONLESS,
        "z_start": DIMENSIONLESS,
        "z_count": DIMENSIONLESS,
    },
    # the concatenated samples, before the sets' factors (float32 when every sample is
    # a float32 exactly, as the embedded pools' are; else float64)
    "records": {"x": ACCELERATION, "y": ACCELERATION, "z": ACCELERATION},
    "failures": {name: units for name, (_, units) in FAILURE_COLUMNS.items()},
    # the tower inventory as read, every column with the run archive's units (its
    # /towers: TOWER_COLUMNS); an assess archive written before it lacks the table
    "inventory": {name: units for name, (_, units) in TOWER_COLUMNS.items()},
    **RISK_TABLES,
}

#: Units of every column and array of the scenario archive (``rockscreen scenario``).
SCENARIO_TABLES: dict[str, UnitsTable] = {
    "summary": {
        **_RISK_TOWER_UNITS,
        "status": TEXT,
        "event_pga_g": G_UNITS,
        "sigma_ln_pga": DIMENSIONLESS,
        "sigma_source": TEXT,
        "soil_factor": DIMENSIONLESS,
        "ag_equiv_g": G_UNITS,
        "beta_total": DIMENSIONLESS,
        "p_overturning": DIMENSIONLESS,
        "p_overturning_bound": TEXT,
        "class_bound": TEXT,  # "", "at_most", "at_least" (verdict.scales.ClassBound)
    },
    "failures": {name: units for name, (_, units) in FAILURE_COLUMNS.items()},
    "shakemap": {"lon_deg": DEGREES, "lat_deg": DEGREES, "pga_g": G_UNITS},
}


@lru_cache(maxsize=8)
def _assess_tables(
    parts: tuple[str, ...], checks: tuple[tuple[str, str], ...]
) -> dict[str, UnitsTable]:
    summary = dict(_ASSESS_TABLES["summary"])
    items = list(summary.items())
    # the columns of the code checks registered beyond the built-ins, after LV1's
    at = list(summary).index("lv1_bound") + 1
    items = items[:at] + list(checks) + items[at:]
    # each part model alone (IDA on that model: the belfry, the bell gable, ...): its
    # fragility and SLV capacity, placed after the kinematic checks
    at = list(summary).index("kinematic_mechanism") + 1
    part_items = [
        (f"{part}_{suffix}", units) for part in parts for suffix, units in PART_SUFFIXES.items()
    ]
    # format 4's long tables (one row per tower x fit, check, message) and the pivot
    return {
        **_ASSESS_TABLES,
        "summary": dict(items[:at] + part_items + items[at:]),
        **LONG_TABLES,
    }


def assess_tables() -> dict[str, UnitsTable]:
    """Return the units of every column of the assess archive, per table (``assess``).

    The ``summary`` table holds the columns of every part model of the registry
    (:func:`part_model_names`, :data:`PART_SUFFIXES`) and of every code check declared
    beyond the built-ins (:func:`declare_check_columns`). Do not change the tables returned.
    """
    return _assess_tables(part_model_names(), tuple(DECLARED.units.items()))


@lru_cache(maxsize=8)
def _bound_pairs(parts: tuple[str, ...], checks: tuple[tuple[str, str], ...]) -> dict[str, str]:
    """Return value column -> its bound column, every pair declared (:func:`bound_columns`)."""
    pairs = {
        "fragility_median_g": "median_is_bound",  # a scenario's (and an older archive's) one
        "collapse_median_g": "collapse_bound",
        "stripe_median_g": "stripe_bound",
        "p_overturning": "p_overturning_bound",
        # the SLV fit's bound holds for the capacity, its return period, I_S and f_a
        **dict.fromkeys(
            (
                "slv_median_g",
                "capacity_pga_g",
                "capacity_return_period_y",
                "safety_index",
                "acceleration_factor",
            ),
            "slv_bound",
        ),
        **dict.fromkeys(("governing_capacity_ag_g", "governing_safety_index"), "governing_bound"),
        **dict.fromkeys(
            ("lv1_capacity_ag_g", "lv1_safety_index", "lv1_acceleration_factor"), "lv1_bound"
        ),
    }
    # the kinematic checks: the governing mechanism's (prefix "") and each part's
    for prefix in ("", *(f"{part}_" for part in KINEMATIC_PARTS)):
        for kind in ("linear", "nonlinear"):
            for value in ("capacity_ag_g", "safety_index"):
                pairs[f"{prefix}kinematic_{kind}_{value}"] = f"{prefix}kinematic_{kind}_bound"
        pairs[f"{prefix}kinematic_safety_index"] = f"{prefix}kinematic_bound"
    # each part model's IDA: its collapse fit, and its SLV fit (capacity and I_S)
    for part in parts:
        pairs[f"{part}_fragility_median_g"] = f"{part}_fragility_bound"
        for value in ("slv_median_g", "capacity_ag_g", "safety_index"):
            pairs[f"{part}_{value}"] = f"{part}_slv_bound"
    # the code checks declared beyond the built-ins (declare_check_columns)
    pairs.update(dict(checks))
    return pairs


def bound_columns() -> dict[str, str]:
    """Return which summary values are bounds: value column -> its bound column.

    The bound column holds ``""``, ``"lower"`` or ``"upper"`` for the value
    (:class:`rockscreen.pipeline.verdict.status.Bound`). Every pair is declared here, beside
    the columns' units (each part model of the registry's too); no column name is parsed.
    Do not change the dict returned.
    """
    return _bound_pairs(part_model_names(), tuple(DECLARED.bounds.items()))


def table_units(tables: Mapping[str, UnitsTable], table: str, column: str) -> str | None:
    """Return the units of a column from an explicit units table, None if undeclared.

    Parameters
    ----------
    tables : dict
        Table name -> :data:`UnitsTable` (e.g. :func:`assess_tables`).
    table, column : str
        The table and the column.

    Returns
    -------
    str or None
        The units spelling, or None when the column is not declared.
    """
    units = tables.get(table, {})
    if column in units:
        return units[column]
    return next(
        (u for key, u in units.items() if key.endswith("*") and column.startswith(key[:-1])),
        None,
    )
