"""Adapter: the assess and scenario archives (``rockscreen assess`` / ``scenario``).

:func:`risk_model` builds the report model from plain rows (the per-tower summary, the
stripes, the record selection), so it serves any reader; :func:`risk_archive_model`
reads those rows from an archive whose root attribute ``kind`` is ``"assess"`` or
``"scenario"``: tables ``/summary``, ``/stripes``, ``/selection`` (a group of column
datasets or one compound dataset), and optionally ``/shakemap`` with ``lon_deg``,
``lat_deg`` [deg] and ``pga_g`` [g] for the map's PGA contours, and an assess archive's
``/inventory`` (the towers as read, through its checked reader) for the sheets' inputs.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import cast

import contourpy
import h5py
import numpy as np

from rockscreen.pipeline.archive.bounds import bounded_columns
from rockscreen.pipeline.archive.kinds import AssessReader, ScenarioReader
from rockscreen.pipeline.archive.long_pivot import read_long_tables, stored_checks
from rockscreen.pipeline.archive.long_schema import CheckColumns
from rockscreen.pipeline.archive.risk_reader import read_inventory, read_risk_table, summary_rows
from rockscreen.pipeline.archive.safety import open_checked, read_column
from rockscreen.pipeline.report.html.adapters.common import (
    CLASS_COLUMN,
    ID_COLUMN,
    NAME_COLUMN,
    NOTE_COLUMN,
    header_items,
    python_value,
)
from rockscreen.pipeline.report.html.adapters.risk_checks import checks_table, governing_label
from rockscreen.pipeline.report.html.adapters.risk_method import method_paragraphs
from rockscreen.pipeline.report.html.adapters.risk_rank import (
    band_sign,
    ranked_list,
    risk_curves,
    risk_sheet,
)
from rockscreen.pipeline.report.html.adapters.risk_sheet import (
    fragility_figure,
    sheet_inputs,
    sheet_verdict,
)
from rockscreen.pipeline.report.html.model import (
    Column,
    Contour,
    Figure,
    HeaderItem,
    Note,
    ReportModel,
    Sheet,
    TowerCells,
    finite,
)
from rockscreen.pipeline.report.html.notes import stored_codes
from rockscreen.pipeline.report.values import Attrs, ColumnValue, Row
from rockscreen.pipeline.verdict.labels import row_class_label
from rockscreen.pipeline.verdict.scales import SAFETY_COUNTED
from rockscreen.stations.inventory_columns import AREA_COLUMNS

__all__ = [
    "RISK_ARCHIVE_CLASSES",
    "risk_archive_model",
    "risk_model",
    "risk_reader_model",
    "shakemap_contours",
]

#: I_S classes as printed (rockscreen.pipeline.risk.measures.classes), worst first, then the
#: undefined one.
RISK_ARCHIVE_CLASSES = [*SAFETY_COUNTED, "undefined"]
#: Scenario classes on P(overturning) (pipeline.risk.measures.classes.scenario_class), worst first.
SCENARIO_ARCHIVE_CLASSES = ["very_high", "high", "moderate", "low", "undefined"]
#: First columns of both tables: the tower, its class and its site's soil class.
_TOWER_COLUMNS = [ID_COLUMN, NAME_COLUMN, CLASS_COLUMN, Column("soil_class", "i_soil", "", "text")]
#: The tower's fragility: median [g] and beta [-].
_FRAGILITY_COLUMNS = [
    Column("fragility_median_g", "col_median", "g"),
    Column("fragility_beta", "col_beta", "1"),
]
#: Known summary columns of an assessment, in display order (only those present are shown).
ASSESS_COLUMNS = [
    *_TOWER_COLUMNS,
    # the screening risk (issue 31): its rank and best estimate, beside the code's class
    Column("risk_rank", "col_risk_rank", "1", digits=6),
    Column("risk_p50_best", "col_risk_p50", "1", digits=2),
    *_FRAGILITY_COLUMNS,  # an archive before the IDA fragilities
    Column("collapse_median_g", "Collapse median", "g"),
    Column("collapse_median_lo90_g", "Collapse median, 90 % low", "g"),
    Column("collapse_median_hi90_g", "Collapse median, 90 % high", "g"),
    Column("collapse_beta", "Collapse β", "1", digits=2),
    Column("collapse_bound", "Collapse bound", "", "text"),
    Column("slv_median_g", "SLV median (θ/α ≥ 0.4)", "g"),
    Column("slv_beta", "SLV β", "1", digits=2),
    Column("slv_bound", "SLV bound", "", "text"),
    Column("annual_rate_overturning_per_y", "col_rate", "1/y"),
    Column("annual_rate_lo90_per_y", "λ_C, 90 % low", "1/y"),
    Column("annual_rate_hi90_per_y", "λ_C, 90 % high", "1/y"),
    Column("p_overturning_50y", "col_p50", "1"),
    Column("rate_share_tr_over_2475", "col_share_over", "1"),
    Column("rate_share_tr_under_30", "col_share_under", "1"),
    Column("confidence_factor", "F_C", "1", digits=3),
    Column("capacity_pga_g", "col_ac", "g"),
    Column("capacity_return_period_y", "col_trc", "y", digits=4),
    Column("safety_index", "col_is", "1"),
    Column("safety_index_lo90", "I_S, 90 % low", "1"),
    Column("safety_index_hi90", "I_S, 90 % high", "1"),
    Column("acceleration_factor", "col_fa", "1"),
    Column("stripe_median_g", "Stripe-fit median (check)", "g"),
    Column("governing", "col_governing", "", "text"),
    Column("governing_safety_index", "col_is_governing", "1"),
    NOTE_COLUMN,
]
#: Known summary columns of a scenario, in display order (only those present are shown).
SCENARIO_COLUMNS = [
    *_TOWER_COLUMNS,
    Column("event_pga_g", "col_site_pga", "g"),
    Column("pga_g", "col_site_pga", "g"),
    Column("p_overturning", "col_p_scenario", "1"),
    *_FRAGILITY_COLUMNS,
    Column("beta_total", "col_beta", "1"),
    NOTE_COLUMN,
]
#: The sheet's inputs after the rocking block and the friction: the block's slenderness
#: (a row's ``alpha_rad``), the site's soil class (the one assessed), then the shaft's
#: masonry, the belfry and the bell gable (:data:`~.common.TOWER_INPUTS`; shown when given).
_HEADER = [
    ("rockscreen_version", "h_version"),
    ("created_utc", "h_created"),
    ("command_line", "h_command"),
    ("inventory_source", "h_inventory"),
    ("hazard_source", "h_hazard"),
    ("shakemap_source", "h_shakemap"),
    ("record_files", "h_records"),
    ("format_version", "h_format"),
]
#: Archive attributes behind a verdict (the record suite, the stripes, the class limits, ...)
#: and the translation keys of their labels; an attribute absent from the archive is skipped.
_ASSUMPTIONS = [
    ("suite_source", "a_suite"),
    ("return_periods_y", "a_return_periods"),
    ("n_records_per_stripe", "a_records_per_stripe"),
    ("scale_limits", "a_scale_limits"),
    ("models", "a_models"),
    ("damage_levels", "a_damage_levels"),
    ("class_limits", "a_class_limits"),
    ("components", "a_components"),
    ("allow_noncompliant", "a_allow_noncompliant"),
    ("fragility_source", "a_fragility_source"),
    ("shakemap_event", "a_shakemap_event"),
    ("gm_uncertainty", "a_gm_uncertainty"),
    ("default_soil_class", "default_soil_class"),
    ("soil_class_default", "soil_class_default"),
    ("limit_state", "limit_state"),
    ("tr_slv_y", "tr_slv_y"),
    ("notes", "a_notes"),
]


#: The screening risk's long tables an assess archive may hold (RISK_CONTRACT).
_RISK_TABLES = ("risk_fragility", "risk_sensitivity", "risk_top_n")


def risk_model(
    kind: str,
    attrs: Attrs,
    summary: Sequence[Row],
    stripes: Sequence[Row] = (),
    contours: Sequence[Contour] = (),
    inventory: Sequence[Row] = (),
    failures: Sequence[Row] = (),
    risk: Mapping[str, Sequence[Row]] | None = None,
    checks: Sequence[CheckColumns] = (),
) -> ReportModel:
    """Build the report model of an assess or scenario result from plain rows.

    Parameters
    ----------
    kind : str
        ``"assess"`` or ``"scenario"``.
    attrs : mapping
        Archive attributes (version, sources, defaults, notes).
    summary : sequence of mapping
        One row per tower: ``id``, ``lat_deg``/``lon_deg`` [deg], ``risk_class`` and any
        of the known columns (``fragility_median_g`` [g], ``fragility_beta`` [1],
        ``annual_rate_overturning_per_y`` [1/y], ``p_overturning_50y`` [1],
        ``capacity_pga_g`` [g], ``capacity_return_period_y`` [y], ``safety_index`` [1],
        ``acceleration_factor`` [1], ``note``) and tower inputs (``width_m`` [m], ...).
    stripes : sequence of mapping
        Stripe rows: ``tower_id``, ``ag_g`` [g], ``n_records``, ``n_overturned``.
    contours : sequence of Contour
        Map context (:func:`shakemap_contours`).
    inventory : sequence of mapping
        The towers as read (an assess archive's ``/inventory``,
        :func:`rockscreen.pipeline.archive.risk_reader.read_inventory`): a tower's sheet
        shows the inputs it gives (area, rocking block, friction, shaft masonry, belfry,
        bell gable), a value not given left out; without it (an archive written before
        the inventory was kept, plain rows) the sheet shows the inputs its summary row
        carries.
    failures : sequence of mapping
        The towers not assessed (``/failures``: ``kind``, ``subject``, ``reason``): named in
        the header with their kind (the first 20, the others counted); the reason is the
        tower's note, in the page's language.
    risk : mapping, optional
        The screening risk's long tables of an assess archive (RISK_CONTRACT):
        ``risk_fragility``, ``risk_sensitivity``, ``risk_top_n`` -> their rows. The ranked
        list (the first screen) comes from the summary's ``risk_*`` columns and
        ``risk_top_n``; a sheet shows its tower's band on the fragility figure and its
        sensitivity bars. An archive without the screening risk gets a list that says so.
    checks : sequence of CheckColumns
        The checks an assess archive stores (:func:`~rockscreen.pipeline.archive.
        long_pivot.stored_checks`): a check added as a module gets its row on each tower's
        sheet (:func:`~rockscreen.pipeline.report.html.adapters.risk_checks.checks_table`).

    Returns
    -------
    ReportModel
        The model; its method section describes what this archive computed
        (:func:`~rockscreen.pipeline.report.html.adapters.risk_method.method_paragraphs`).
    """
    model = ReportModel(kind=kind, title=f"kind_{kind}", method="risk")
    model.classes = RISK_ARCHIVE_CLASSES if kind == "assess" else SCENARIO_ARCHIVE_CLASSES
    model.header = _header(kind, attrs, summary, failures)
    model.assumptions = _assumptions(kind, attrs, summary)
    present = set().union(*(row.keys() for row in summary)) if summary else set()
    model.method_text = method_paragraphs(kind, attrs, summary, present, checks)
    known = ASSESS_COLUMNS if kind == "assess" else SCENARIO_COLUMNS
    model.columns = [c for c in known if c.key in present or c.key == "id"]
    model.contours = list(contours)
    by_tower: dict[str, list[Row]] = {}
    for stripe in stripes:
        by_tower.setdefault(str(stripe.get("tower_id", "")), []).append(stripe)
    given = {str(tower.get("id", "")): tower for tower in inventory}
    risk = risk or {}
    if kind == "assess":
        model.risk = ranked_list(
            attrs, summary, risk.get("risk_top_n", ()), risk.get("risk_sensitivity", ())
        )
    n_ranked = len(model.risk["rows"]) if model.risk else 0
    fragility = _by_tower(risk.get("risk_fragility", ()))
    sensitivity = _by_tower(risk.get("risk_sensitivity", ()))
    for row in summary:
        tower_id = str(row.get("id", ""))
        out = _tower_cells(row, model.columns)
        model.towers.append(out)
        sheet = _sheet(kind, row, out, given.get(tower_id, {}), by_tower.get(tower_id, []))
        if kind == "assess":
            sheet.checks, sheet.checks_text = checks_table(row, checks)
        if model.risk and model.risk["computed"]:
            _risk_on_sheet(
                sheet, row, n_ranked, fragility.get(tower_id, []), sensitivity.get(tower_id, [])
            )
        model.sheets[tower_id] = sheet
    return model


def _by_tower(rows: Sequence[Row]) -> dict[str, list[Row]]:
    """Return a long table's rows per ``tower_id``."""
    out: dict[str, list[Row]] = {}
    for row in rows:
        out.setdefault(str(row.get("tower_id", "")), []).append(row)
    return out


def _risk_on_sheet(
    sheet: Sheet,
    row: Row,
    n_ranked: int,
    fragility: Sequence[Row],
    sensitivity: Sequence[Row],
) -> None:
    """Add the screening risk to a tower's sheet: its lines, bars and fragility band."""
    sheet.risk, sheet.sensitivity = risk_sheet(row, n_ranked, sensitivity)
    curves = risk_curves(fragility)
    if not curves:
        return
    figure = next((f for f in sheet.figures if f.kind == "xy"), None)
    if figure is None:
        figure = Figure("xy", "s_fragility", "s_im", "s_pexc", yrange=[0.0, 1.0])
        sheet.figures.append(figure)
    figure.curves.extend(curves)
    figure.xrange = None  # fitted to the band too
    figure.logx = True  # the band and the code's fits can lie a decade apart


def _header(
    kind: str,
    attrs: Attrs,
    summary: Sequence[Row],
    failures: Sequence[Row],
) -> list[HeaderItem]:
    """Return the header: the kind, the archive's attributes, the towers and those not assessed."""
    header = [HeaderItem("h_kind", f"kind_{kind}", True)]
    header += header_items(attrs, _HEADER)
    header.append(HeaderItem("h_towers", str(len(summary))))
    if failures:
        # the towers and what failed; each one's reason is its row's note, rendered from its
        # codes in the page's language (the /failures text is English: rockscreen inspect)
        shown = "; ".join(f"{f['subject']} ({f['kind']})" for f in failures[:20])
        more = f" (+{len(failures) - 20})" if len(failures) > 20 else ""
        header.append(HeaderItem("h_failures", shown + more))
    return header


def _assumptions(kind: str, attrs: Attrs, summary: Sequence[Row]) -> list[HeaderItem]:
    """Return the assumptions: the archive's, the soil classes not given, the vertical, classes."""
    items = header_items(attrs, _ASSUMPTIONS)
    sources: dict[str, int] = {}
    for row in summary:
        source = str(row.get("soil_class_source", "") or "")
        if source and source != "inventory":
            sources[source] = sources.get(source, 0) + 1
    if sources:
        text = ", ".join(f"{source}: {n}" for source, n in sorted(sources.items()))
        items.append(HeaderItem("i_soil", text))
    items.append(HeaderItem("a_vertical", "a_vertical_text", True))
    if kind == "scenario":
        items.append(HeaderItem("a_scenario_classes", "a_scenario_classes_text", True))
    return items


def _tower_cells(row: Row, columns: Sequence[Column]) -> TowerCells:
    """Return a tower's cells of the table: its columns, place, class label, codes, bounds."""
    out: TowerCells = {c.key: _cell(row.get(c.key), c) for c in columns}
    out["id"] = str(row.get("id", ""))
    out["lat"] = finite(row.get("lat_deg", row.get("lat")))
    out["lon"] = finite(row.get("lon_deg", row.get("lon")))
    out["risk_class"] = row_class_label(row)  # a label carrying its typed marks
    if row.get("governing_check"):  # which I_S the class comes from (answer.py)
        out["governing_check"] = str(row["governing_check"])
        if "governing" in out:  # its label from the catalogue, in the page's language
            out["governing"] = governing_label(row)
    if "note" in out:  # rendered per language from its codes (render.py)
        out["note_codes"] = stored_codes(row)
    for column in AREA_COLUMNS:  # counts per area (render.py)
        if row.get(column):
            out[column] = str(row[column])
    bounds = {key: sign for key, sign in bounded_columns(row).items() if out.get(key) is not None}
    for key in ("risk_p50_best",):  # the screening risk's flags: at_most, at_least, both
        sign = band_sign(row.get(f"{key}_bound"))
        if sign == "both" or (key in out and not _has_rank(row)):
            out[key] = None  # bounded both ways (or no risk): not a value
        elif sign and out.get(key) is not None:
            bounds[key] = {"<=": "≤", ">=": "≥"}[sign]
    if "risk_rank" in out and not _has_rank(row):
        out["risk_rank"] = None  # 0: the tower has no screening risk
    if any(bounds.values()):
        out["bounds"] = {key: sign for key, sign in bounds.items() if sign}
    return out


def _has_rank(row: Row) -> bool:
    rank = finite(row.get("risk_rank"))
    return rank is not None and rank >= 1


def _sheet(
    kind: str,
    row: Row,
    out: TowerCells,
    given: Row,
    stripes: Sequence[Row],
) -> Sheet:
    """Return a tower's sheet: its inputs, verdict, fragility figure, checks and note."""
    sheet = Sheet(
        inputs=sheet_inputs(row, given), verdict=sheet_verdict(kind, row, out["risk_class"])
    )
    figure = fragility_figure(row, stripes)
    if figure is not None:
        sheet.figures.append(figure)
    if row.get("note"):
        sheet.notes.append(Note(str(row["note"]), stored_codes(row)))
    return sheet


#: The part models' fragility columns of a row (``<part>_fragility_median_g``, ...) and
#: their labels' translation keys; the first (the belfry) says why when it was not checked.
def _cell(value: ColumnValue, column: Column) -> str | float | None:
    if column.kind != "num":
        return "" if value is None else str(python_value(value))
    number = python_value(value)
    if isinstance(number, float) and math.isinf(number) and number > 0:
        return "inf"
    return finite(number)


def shakemap_contours(
    lon_deg: np.ndarray, lat_deg: np.ndarray, pga_g: np.ndarray, levels: Sequence[float] = ()
) -> list[Contour]:
    """Contour a ShakeMap PGA grid for the map.

    Parameters
    ----------
    lon_deg, lat_deg : numpy.ndarray
        Grid coordinates [deg], 1-D (lengths nx and ny).
    pga_g : numpy.ndarray
        PGA [g], shape (ny, nx).
    levels : sequence of float
        Contour levels [g]; default 0.05, 0.1, 0.2, 0.3, 0.5, 0.8 within the grid's range.

    Returns
    -------
    list of Contour
        ``{"level": g, "label": "0.1 g", "lines": [[[lon, lat], ...], ...]}``.
    """
    pga = np.asarray(pga_g, dtype=float)
    levels = list(levels) or [v for v in (0.05, 0.1, 0.2, 0.3, 0.5, 0.8) if v <= np.nanmax(pga)]
    generator = contourpy.contour_generator(np.asarray(lon_deg), np.asarray(lat_deg), pga)
    out: list[Contour] = []
    for level in levels:
        lines = [
            [[round(float(x), 5), round(float(y), 5)] for x, y in line]
            for line in generator.lines(level)
        ]
        if lines:
            out.append({"level": level, "label": f"{level:g} g", "lines": lines})
    return out


def _table(f: h5py.File, name: str) -> list[dict[str, ColumnValue]]:
    """Read a table: a group of equal-length column datasets, or one compound dataset."""
    if name not in f:
        return []
    obj = f[name]

    def cell(value: object) -> ColumnValue:  # one item of a 1-D column: a scalar
        return cast(ColumnValue, python_value(value))

    if isinstance(obj, h5py.Dataset) and obj.dtype.names:
        data = obj[()]
        return [{k: cell(r[k]) for k in data.dtype.names} for r in np.atleast_1d(data)]
    columns = {}
    for key, ds in obj.items():
        if isinstance(ds, h5py.Dataset) and ds.ndim == 1:  # text as str however stored
            columns[key] = read_column(ds, f.filename, f"{name}/{key}")
    n = min((len(c) for c in columns.values()), default=0)
    return [{k: cell(c[i]) for k, c in columns.items()} for i in range(n)]


def risk_archive_model(path: str | Path, kind: str) -> ReportModel:
    """Read an assess or scenario archive and build its model (:func:`risk_model`)."""
    with open_checked(path) as f:
        attrs = {key: python_value(value) for key, value in f.attrs.items()}
        # format 4 keeps the summary as long tables: pivoted back, keys in the order of
        # the tables read here (HDF5 lists a group's members alphabetically)
        summary = (
            [dict(sorted(row.items())) for row in summary_rows(f)]
            if "pivot" in f
            else _table(f, "summary")
        )
        stripes = _table(f, "stripes")
        # every check stored, a check added as a module too (none before format 4)
        checks = stored_checks(read_long_tables(f)) if "pivot" in f else []
        failures = _table(f, "failures") if "failures" in f else []
        risk_tables = [name for name in _RISK_TABLES if name in f]
        stored = kind == "assess" and "inventory" in f
        contours: list[Contour] = []
        if "shakemap" in f and {"lon_deg", "lat_deg", "pga_g"} <= set(f["shakemap"]):
            grid = f["shakemap"]
            contours = shakemap_contours(grid["lon_deg"][:], grid["lat_deg"][:], grid["pga_g"][:])
    # The inventory through its checked reader (an archive written before it: none).
    inventory = read_inventory(path) if stored else []
    # The screening risk's tables through their checked reader (an older archive: none).
    risk = {name: read_risk_table(path, name) for name in risk_tables}
    return risk_model(kind, attrs, summary, stripes, contours, inventory, failures, risk, checks)


def risk_reader_model(reader: AssessReader | ScenarioReader) -> ReportModel:
    """Build the model of an assess or scenario archive opened by ``open_archive``."""
    return risk_archive_model(reader.path, reader.kind)
