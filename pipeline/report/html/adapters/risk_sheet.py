"""A tower's sheet in the report of an assess or scenario archive: its inputs and verdict.

:func:`sheet_inputs` lists what the tower was assessed with (the stored inventory's values
as read, or an older archive's summary row), :func:`sheet_verdict` the fragility, risk,
capacity and class lines, and :func:`fragility_figure` the fitted fragilities with the
stripes. The side-by-side checks table is in
:mod:`rockscreen.pipeline.report.html.adapters.risk_checks`; the model they belong to in
:mod:`rockscreen.pipeline.report.html.adapters.risk`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from rockscreen.pipeline.archive.bounds import relation
from rockscreen.pipeline.report.html.adapters.common import (
    BELFRY_INPUTS,
    GABLE_INPUTS,
    MASONRY_INPUTS,
    body_inputs,
    inventory_inputs,
    num,
)
from rockscreen.pipeline.report.html.model import (
    Curve,
    Figure,
    Key,
    Number,
    Sentence,
    SheetValue,
    finite,
)
from rockscreen.pipeline.report.values import ColumnValue, Row

__all__ = ["fragility_figure", "sheet_inputs", "sheet_verdict"]

#: The parts' and the site's inputs of a sheet, after the block, the building and friction.
_PART_INPUTS = ("alpha_rad", "soil_class", *MASONRY_INPUTS, *BELFRY_INPUTS, *GABLE_INPUTS)


def _bound_sign(row: Row, level: str = "slv") -> str:
    """Return ``">"`` (lower-bound median), ``"<"`` (upper bound) or ``""`` (a fitted one).

    ``level``: ``"slv"``, the fragility the capacity, I_S and f_a rest on, or
    ``"collapse"``, the one of lambda_C and P50; an archive written before the IDA has one
    fragility (``median_is_bound``).
    """
    bound = row.get(f"{level}_bound", row.get("median_is_bound", ""))
    return {"lower": ">", "upper": "<"}.get(str(bound or ""), "")


def _given(row: Row, inventory: Row) -> dict[str, ColumnValue]:
    """Return the tower's values a sheet shows as its inputs.

    With the stored inventory: its values as read (NaN, ``""``: not given), but the site's
    soil class and the block's slenderness as the row has them (the soil class assessed:
    the inventory's, else the default or the map's, its source in the assumptions).
    Without it (an older archive, plain rows): the row's columns, but its
    ``knowledge_level``, the level assessed (the run's default when the inventory gave
    none), which is no input.
    """
    if not inventory:
        return {key: value for key, value in row.items() if key != "knowledge_level"}
    values = dict(inventory)
    for key in ("soil_class", "alpha_rad"):
        if row.get(key) not in (None, ""):
            values[key] = row[key]
    return values


def sheet_inputs(row: Row, inventory: Row) -> list[tuple[str, str | Number]]:
    """Return a tower sheet's inputs: name, area, block and building, friction, parts, site.

    Parameters
    ----------
    row : mapping
        The tower's summary row.
    inventory : mapping
        The tower's stored inventory row (``/inventory``); empty for an older archive.

    Returns
    -------
    list of (str, str or Number)
        Label key and value, left out when not given.
    """
    values = _given(row, inventory)
    out: list[tuple[str, str | Number]] = (
        [("i_name", str(values["name"]))] if values.get("name") else []
    )
    out += body_inputs(values)
    out += [
        (label, value)
        for label, value in inventory_inputs(values, _PART_INPUTS)
        if value != "-"  # an older row's soil class that was not given
    ]
    lat, lon = finite(row.get("lat_deg")), finite(row.get("lon_deg"))
    if lat is not None and lon is not None:
        out.append(("i_site", f"{lat:.5f}°N, {lon:.5f}°E"))
    return out


def sheet_verdict(kind: str, row: Row, cls: str) -> list[Sentence]:
    """Return a tower sheet's verdict lines: fragility, risk, capacity, I_S and class.

    Parameters
    ----------
    kind : {"assess", "scenario"}
        The archive's kind.
    row : mapping
        The tower's summary row.
    cls : str
        Its class as printed (:func:`rockscreen.pipeline.risk.measures.classes.row_class_label`).

    Returns
    -------
    list of (str, dict)
        Translation key and its values, one per line.
    """
    lines: list[Sentence] = []
    sign = _bound_sign(row)
    median = row.get("fragility_median_g")
    if "collapse_median_g" in row:
        lines.extend(_ida_verdict(row))
    elif "fragility_median_g" in row and sign:
        if sign == ">":  # "no record overturned it up to 0.254 g": the bound without its sign
            lines.append(("v_fragility_lower", {"median": num(median, "g")}))
        else:
            lines.append(("v_fragility_upper", {"median": num(median, "g", 3, sign)}))
    elif "fragility_median_g" in row and finite(median) is not None:
        lines.append(
            (
                "v_fragility",
                {"median": num(median, "g"), "beta": num(row.get("fragility_beta"), "", 2)},
            )
        )
    if kind == "scenario" and "p_overturning" in row:
        if finite(row.get("p_overturning")) is not None:
            sign = relation(row, "p_overturning")
            p = num(row.get("p_overturning"), "", 2, sign, relation=True)
            lines.append(("v_scenario_bound" if sign else "v_scenario", {"p": p}))
        else:
            lines.append(("v_scenario_none", {}))
    if "annual_rate_overturning_per_y" in row:
        rate = row.get("annual_rate_overturning_per_y")
        if finite(rate) is not None:
            values: dict[str, SheetValue] = {
                "rate": num(rate, "1/y", 2),
                "p50": num(row.get("p_overturning_50y"), "", 2),
            }
            lines.append(("v_rate", values))
            interval = _interval(row, "annual_rate_lo90_per_y", "annual_rate_hi90_per_y", "1/y")
            if interval:
                lines.append(("v_rate_interval", interval))
        elif _bound_sign(row, "collapse"):
            lines.append(("v_rate_bound", {}))
    if row.get("rate_extrapolated"):
        share = (row.get("rate_share_tr_over_2475") or 0.0) + (
            row.get("rate_share_tr_under_30") or 0.0
        )
        lines.append(("v_extrapolated", {"share": num(share, "", 2)}))
    if row.get("basis_compliant") is False:
        lines.append(("v_noncompliant", {}))
    if "capacity_pga_g" in row and finite(row.get("capacity_pga_g")) is not None:
        values = {
            "ac": num(row.get("capacity_pga_g"), "g", 3, sign, relation=True),
            "tr": num(row.get("capacity_return_period_y"), "y", 4, sign),
            "si": num(row.get("safety_index"), "", 2, sign, relation=True),
            "fa": num(row.get("acceleration_factor"), "", 2, sign, relation=True),
        }
        lines.append(("v_capacity", values))
        interval = _interval(row, "safety_index_lo90", "safety_index_hi90", "")
        if interval:
            lines.append(("v_si_interval", interval))
        if sign:
            lines.append(("v_capacity_lower" if sign == ">" else "v_capacity_upper", {}))
    lines.append(("v_class", {"cls": Key(key=f"class_{cls}", raw=cls)}))
    return lines


def _interval(row: Row, lo_key: str, hi_key: str, unit: str) -> dict[str, SheetValue]:
    """Return the 90 % bootstrap interval's ``lo`` and ``hi`` (numbers), ``{}`` without one."""
    lo, hi = finite(row.get(lo_key)), finite(row.get(hi_key))
    if lo is None or hi is None:
        return {}
    return {"lo": num(lo, "", 3), "hi": num(hi, unit, 3)}


def _ida_verdict(row: Row) -> list[Sentence]:
    """Verdict lines of the IDA fragilities: median, beta and censoring, or the bound."""
    lines: list[Sentence] = []
    for level in ("collapse", "slv"):
        median, bound = finite(row.get(f"{level}_median_g")), row.get(f"{level}_bound") or ""
        n, n_cens = row.get(f"{level}_n_records") or 0, row.get(f"{level}_n_censored") or 0
        if median is None:
            continue
        what = Key(key=f"v_what_{level}")
        counts = {"censored": str(n_cens), "n": str(n)}
        if bound:
            sign = ">" if bound == "lower" else "<"
            values: dict[str, SheetValue] = {
                "what": what,
                "median": num(median, "g", 3, sign, relation=True),
                **counts,
            }
            lines.append((f"v_ida_{bound}", values))
        else:
            interval = (
                _interval(row, "collapse_median_lo90_g", "collapse_median_hi90_g", "g")
                if level == "collapse"
                else {}
            )
            values = {
                "what": what,
                "median": num(median, "g", 3),
                "beta": num(row.get(f"{level}_beta"), "", 2),
                "se": num(row.get(f"{level}_se_beta"), "", 2),
                **counts,
            }
            lines.append(("v_ida_fit", values))
            if interval:
                lines.append(("v_ida_interval", {"what": what, **interval}))
    fc = finite(row.get("confidence_factor"))
    if fc is not None:
        values = {"fc": num(fc, "", 3), "lc": str(row.get("knowledge_level", ""))}
        lines.append(("v_capacity_fc", values))
    return lines


def fragility_figure(row: Row, stripes: Sequence[Row]) -> Figure | None:
    """Return the sheet's figure: the fitted fragility curves and the stripes' shares.

    Parameters
    ----------
    row : mapping
        The tower's summary row (its ``*_median_g`` and ``*_beta``).
    stripes : sequence of mapping
        The tower's stripe rows (``ag_g`` [g] and the counts).

    Returns
    -------
    Figure or None
        None when there is nothing to draw.
    """
    levels = [finite(s.get("ag_g")) for s in stripes]
    fits = [
        (label, finite(row.get(f"{key}_median_g")), finite(row.get(f"{key}_beta")))
        for key, label in (
            ("fragility", "s_fit_stripes"),
            ("collapse", "s_fit_collapse"),
            ("slv", "s_fit_slv"),
        )
        if not row.get("median_is_bound" if key == "fragility" else f"{key}_bound")
    ]
    medians = [m for _, m, _ in fits if m]
    top = max([v for v in levels if v is not None] + [3 * m for m in medians] + [0.0])
    if top <= 0:
        return None
    sign = _bound_sign(row, "collapse")
    median = finite(row.get("collapse_median_g", row.get("fragility_median_g")))
    figure = Figure("xy", "s_fragility", "s_im", "s_pexc", yrange=[0.0, 1.0])
    if sign and not fits:  # a bound has no curve beyond it: the stripes and the bound fill it
        right = max([v for v in levels if v is not None] + [median or 0.0])
        figure.xrange = [0.0, _round([1.25 * right])[0]]
    if sign and median is not None and median > 0:
        # A bound, not a curve: a vertical line at the bound, the side it bounds in the label.
        key = "s_median_lower" if sign == ">" else "s_median_upper"
        values: dict[str, SheetValue] = {"median": num(median, "g", 3, sign)}
        figure.curves.append(Curve(key, [median, median], [0.0, 1.0], "dashed", values))
    for name, median, beta in fits:
        if median is None or beta is None or not (median > 0 and beta > 0):
            continue
        x = np.geomspace(top / 100, top * 1.5, 80)
        y = 0.5 * (1 + np.vectorize(math.erf)(np.log(x / median) / (beta * math.sqrt(2))))
        values = {"name": Key(key=name), "median": num(median, "g", 3), "beta": num(beta, "", 2)}
        figure.curves.append(Curve("s_fit_curve", _round(x), _round(y), values=values))
    points = [
        (finite(s.get("ag_g")), finite(s.get("n_overturned")), finite(s.get("n_records")))
        for s in stripes
    ]
    points = [(a, k / n) for a, k, n in points if a is not None and k is not None and n]
    if points:
        points.sort()
        x, y = zip(*points, strict=True)
        figure.curves.append(Curve("s_stripes", _round(x), _round(y), "points"))
    return figure if figure.curves else None


def _round(values: Sequence[float]) -> list[float]:
    return [float(f"{v:.4g}") for v in values]
