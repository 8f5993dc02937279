"""Adapter: the record-based campaign archive (``rockscreen run``) -> :class:`ReportModel`."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from pathlib import Path

import h5py
import numpy as np

from rockscreen.pipeline.archive.campaign import (
    read_failures,
    read_metadata,
    read_stations,
    read_summary,
    read_towers,
)
from rockscreen.pipeline.archive.kinds import RunReader
from rockscreen.pipeline.archive.safety import open_checked
from rockscreen.pipeline.engine.registry import ground_input_model
from rockscreen.pipeline.report.html.adapters.common import (
    BELFRY_INPUTS,
    CLASS_COLUMN,
    GABLE_INPUTS,
    ID_COLUMN,
    MASONRY_INPUTS,
    NAME_COLUMN,
    NOTE_COLUMN,
    TOMLValue,
    body_inputs,
    distance_km,
    header_items,
    inventory_inputs,
    motion_verdict,
    num,
    number_text,
    parse_toml,
    python_value,
)
from rockscreen.pipeline.report.html.model import (
    Column,
    Figure,
    HeaderItem,
    Key,
    Note,
    ReportModel,
    Sentence,
    Sheet,
    SheetValue,
    TowerCells,
    finite,
)
from rockscreen.pipeline.report.html.notes import stored_codes
from rockscreen.pipeline.report.html.reduce import MOTION_BINS, reduce_series
from rockscreen.pipeline.report.values import Attrs, AttrValue, Row
from rockscreen.solver.constants import G

__all__ = ["MAX_HISTORIES", "RISK_CLASSES", "run_model", "run_reader_model"]

#: Risk classes of the campaign, worst first (rockscreen.pipeline.screening.risk plus "unknown").
RISK_CLASSES = ["collapse", "high", "moderate", "low", "none", "unknown"]
#: Histories shown per tower (the governing case first, then the largest peaks).
MAX_HISTORIES = 4

COLUMNS = [
    ID_COLUMN,
    NAME_COLUMN,
    CLASS_COLUMN,
    Column("theta_max_over_alpha", "col_theta", "-"),
    Column("safety_factor", "col_sf", "-"),
    Column("pga_g", "col_pga", "g"),
    Column("governing_record", "col_record", "", "text"),
    Column("governing_model", "col_model", "", "text", labels="model_"),
    Column("distance_km", "col_distance", "km", digits=3),
    NOTE_COLUMN,
]


def run_model(path: str | Path) -> ReportModel:
    """Build the report model of a campaign archive.

    Parameters
    ----------
    path : str or Path
        A complete archive of ``rockscreen run``.

    Returns
    -------
    ReportModel
        Header, assumptions, one row and one sheet per tower, stations, input motions.
    """
    meta = read_metadata(path)
    summary = read_summary(path)
    stations = read_stations(path)
    failures = read_failures(path)
    config = parse_toml(meta.get("config_toml", ""))
    site_of = {s["key"]: s for s in stations}
    model = ReportModel(kind="run", title="kind_run", method="run", classes=RISK_CLASSES)
    model.header = _header(meta, failures)
    model.assumptions = _assumptions(config)
    model.columns = COLUMNS
    model.stations = [
        {"key": s["key"], "lat": finite(s["latitude"]), "lon": finite(s["longitude"])}
        for s in stations
    ]
    with open_checked(path) as f:
        towers = _towers(path) if "towers" in f else {}
        pga = _governing_pga(f)
        histories = _history_index(f)
        for row in summary:
            tower_id = str(row["id"])
            inventory = towers.get(tower_id, {})
            model.towers.append(_row(row, site_of, pga))
            sheet = Sheet(inputs=_inputs(row, inventory), verdict=_verdict(row))
            sheet.figures = _history_figures(f, model, tower_id, row, histories.get(tower_id, []))
            sheet.notes = [
                Note(f"{fl['kind']}: {fl['reason']}")
                for fl in failures
                if fl["subject"] == tower_id
            ]
            model.sheets[tower_id] = sheet
    return model


def _header(meta: Attrs, failures: Sequence[Row]) -> list[HeaderItem]:
    items = [HeaderItem("h_kind", "kind_run", True)]
    items += header_items(
        meta,
        [
            ("rockscreen_version", "h_version"),
            ("created_utc", "h_created"),
            ("command_line", "h_command"),
            ("inventory_source", "h_inventory"),
            ("stations_source", "h_stations"),
            ("record_files", "h_records"),
            ("config_source", "h_config"),
            ("n_towers", "h_towers"),
            ("n_cases", "h_cases"),
            ("format_version", "h_format"),
        ],
    )
    if failures:
        shown = "; ".join(f"{f['kind']} {f['subject']}: {f['reason']}" for f in failures[:20])
        more = f" (+{len(failures) - 20})" if len(failures) > 20 else ""
        items.append(HeaderItem("h_failures", shown + more))
    return items


def _table(config: Mapping[str, TOMLValue], name: str) -> Mapping[str, TOMLValue]:
    """Return a table of the stored configuration (``[pairing]``, ...); ``{}`` without one."""
    table = config.get(name, {})
    return table if isinstance(table, dict) else {}


def _assumptions(config: Mapping[str, TOMLValue]) -> list[HeaderItem]:
    items = []
    pairing = _table(config, "pairing")
    if "max_distance_km" in pairing:
        items.append(HeaderItem("a_pairing", number_text(pairing["max_distance_km"], "km")))
    models = _table(config, "models")
    if "run" in models:
        items.append(HeaderItem("a_models", ", ".join(map(str, models["run"]))))
    if "free_motion_s" in models:
        items.append(HeaderItem("a_free", number_text(models["free_motion_s"], "s")))
    processing = _table(config, "processing")
    if processing:
        band = f"{processing.get('freqmin_hz', '-')}-{processing.get('freqmax_hz', '-')} Hz"
        detail = f"band-pass {band}, order {processing.get('filter_order', '-')}"
        detail += ", zero-phase" if processing.get("zerophase") else ""
        items.append(HeaderItem("a_processing", detail))
    sf = _table(config, "safety_factor")
    if sf:
        text = ", ".join(f"{key}={value}" for key, value in sf.items())
        items.append(HeaderItem("a_sf", text))
    risk = _table(config, "risk")
    if risk:
        items.append(HeaderItem("a_risk", ", ".join(f"{k}={v}" for k, v in risk.items())))
    items.append(HeaderItem("a_vertical", "a_vertical_text", True))
    items.append(HeaderItem("a_orientation", "a_orientation_text", True))
    return items


def _towers(path: str | Path) -> dict[str, Row]:
    """Read ``/towers`` as tower id -> {column: value} (a column an older archive lacks: absent)."""
    return {str(row["id"]): row for row in read_towers(path)}


def _governing_pga(f: h5py.File) -> dict[tuple[str, str, str], float]:
    """PGA of every case [m/s2], keyed by (tower, record id + component, model)."""
    if "results" not in f or "pga_m_s2" not in f["results"]:
        return {}
    r = f["results"]
    towers, records, components, models = (
        r[name].asstr()[:] for name in ("tower_id", "record_id", "component", "model")
    )
    values = r["pga_m_s2"][:]
    return {
        (str(t), _channel(str(rec), str(c))[2], str(m)): float(v)
        for t, rec, c, m, v in zip(towers, records, components, models, values, strict=True)
    }


def _latlon(row: Row) -> tuple[float | None, float | None]:
    """Summary coordinates [deg]: ``lat_deg``/``lon_deg`` (format 2) or ``lat``/``lon`` (1)."""
    return finite(row.get("lat_deg", row.get("lat"))), finite(row.get("lon_deg", row.get("lon")))


def _channel(record_id: str, component: str) -> tuple[str, str, str]:
    """Return (record group, channel dataset, channel id) of a history's component.

    Format 1 stores the record id (``XX.SYN1..HN``) and the component (``E``); format 2
    the channel id (``XX.SYN1..HNE``) as ``record_id``.
    """
    prefix = record_id.rsplit(".", 1)[-1]
    if len(prefix) == 2:  # band + instrument codes: a record id (format 1)
        return record_id, prefix + component, record_id + component
    return record_id[:-1], prefix, record_id


def _pairing_distance(row: Row, site_of: Mapping[str, Row]) -> float | None:
    """Distance to the nearest paired station [km]: stored by format 2, computed for 1."""
    if "pairing_distance_km" in row:
        return finite(row["pairing_distance_km"])
    governing = str(row.get("governing_record", ""))
    stations = [s for s in str(row.get("stations", "")).split(",") if s.strip()]
    distances = []
    for key in stations or [".".join(governing.split(".")[:2])]:
        site = site_of.get(key.strip())
        if site is not None:
            distances.append(distance_km(*_latlon(row), site["latitude"], site["longitude"]))
    distances = [d for d in distances if d is not None]
    return min(distances) if distances else None


def _row(
    row: Row, site_of: Mapping[str, Row], pga: Mapping[tuple[str, str, str], float]
) -> TowerCells:
    governing = str(row.get("governing_record", ""))
    # The ground PGA of the governing record component: the input of the case run on the
    # ground motion itself (the floor case's own input is the amplified floor motion).
    tower_id = str(row["id"])
    case_pga = finite(pga.get((tower_id, governing, ground_input_model().name)))
    sf = row.get("safety_factor")
    note, codes = str(row.get("note", "") or ""), stored_codes(row)
    if not note and sf is not None and np.isinf(sf):  # an archive of format 1
        note, codes = "safety factor: no overturning up to the cap", None
    bound = _sf_bound(row)
    out: TowerCells = {
        "id": str(row["id"]),
        "name": str(row.get("name", "")),
        "lat": _latlon(row)[0],
        "lon": _latlon(row)[1],
        "risk_class": str(row.get("risk_class", "")) or "unknown",
        "theta_max_over_alpha": finite(row.get("theta_max_over_alpha")),
        "safety_factor": "inf" if sf is not None and np.isinf(sf) else finite(sf),
        "pga_g": None if case_pga is None else case_pga / G,
        "governing_record": governing,
        "governing_model": str(row.get("governing_model", "")),
        "distance_km": _pairing_distance(row, site_of),
        "note": note,
        "note_codes": codes,
    }
    if bound is not None:  # the search stopped short of overturning: show where, as a bound
        out["safety_factor"] = bound
        out["bounds"] = {"safety_factor": ">"}
    return out


def _sf_bound(row: Row) -> float | None:
    """Return the factor a search stopped at without overturning (a lower bound), else None.

    The summary's ``safety_factor`` is infinite then; ``safety_factor_limit`` says why the
    search stopped (``"vertical_limit"``: the model's validity limit; ``"cap"``: the search
    cap) and ``safety_factor_lower`` where. Archives without them give None (shown as ∞).
    """
    sf = finite(row.get("safety_factor"))
    limit = str(row.get("safety_factor_limit", "") or "")
    lower = finite(row.get("safety_factor_lower"))
    if sf is not None or limit not in {"vertical_limit", "cap"} or lower is None:
        return None
    return lower


def _inputs(row: Row, inventory: Row) -> list[tuple[str, SheetValue]]:
    inputs: list[tuple[str, SheetValue]] = [("i_name", str(row.get("name", "")))]
    inputs += body_inputs(inventory)
    inputs += inventory_inputs(inventory, (*MASONRY_INPUTS, *BELFRY_INPUTS, *GABLE_INPUTS))
    alpha = finite(row.get("alpha_rad"))
    if alpha is not None:
        inputs.append(("i_alpha", number_text(alpha, "rad", 4)))
    lat, lon = _latlon(row)
    if lat is not None and lon is not None:
        inputs.append(("i_site", f"{lat:.5f}°N, {lon:.5f}°E"))
    if row.get("stations"):
        inputs.append(("i_station", str(row["stations"])))
    if row.get("pairing"):
        inputs.append(("col_distance", str(row["pairing"])))
    return inputs


def _verdict(row: Row) -> list[Sentence]:
    cls = str(row.get("risk_class", "")) or "unknown"
    if cls == "unknown":
        return [("v_unknown", {}), ("v_class", {"cls": Key(key="class_unknown")})]
    record, model = str(row.get("governing_record", "")), str(row.get("governing_model", ""))
    verdict: list[Sentence] = [motion_verdict(row, record, model)]
    sf = row.get("safety_factor")
    bound = _sf_bound(row)
    if bound is not None:
        key = "v_sf_vertical" if row.get("safety_factor_limit") == "vertical_limit" else "v_sf_cap"
        verdict.append((key, {"sf": num(bound, "", 3)}))
    elif sf is not None and np.isinf(sf):
        verdict.append(("v_sf_inf", {}))
    elif finite(sf) is not None:
        verdict.append(("v_sf", {"sf": num(sf, "", 3)}))
        if sf < 1 and not row.get("overturned"):
            verdict.append(("v_sf_low", {}))
    verdict.append(("v_class", {"cls": Key(key=f"class_{cls}", raw=cls)}))
    return verdict


def _history_index(f: h5py.File) -> dict[str, list[dict[str, AttrValue]]]:
    if "histories/index" not in f:
        return {}
    group = f["histories/index"]
    table = {
        name: group[name].asstr()[:]
        if h5py.check_string_dtype(group[name].dtype)
        else group[name][:]
        for name in group
    }
    out: dict[str, list[dict[str, AttrValue]]] = {}
    for i, tower_id in enumerate(table.get("tower_id", [])):
        out.setdefault(str(tower_id), []).append(
            {name: python_value(column[i]) for name, column in table.items()}
        )
    return out


def _history_figures(
    f: h5py.File,
    model: ReportModel,
    tower_id: str,
    row: Row,
    entries: Sequence[Mapping[str, AttrValue]],
) -> list[Figure]:
    if not entries:
        return []
    governing = (str(row.get("governing_record", "")), str(row.get("governing_model", "")))

    def rank(entry: Mapping[str, AttrValue]) -> tuple[int, float]:
        record = _channel(str(entry["record_id"]), str(entry["component"]))[2]
        is_governing = (record, entry["model"]) == governing
        theta = f["histories/theta"][entry["start"] : entry["start"] + entry["count"]]
        peak = float(np.max(np.abs(theta))) / entry["alpha_rad"] if len(theta) else 0.0
        return (0 if is_governing else 1, -peak)

    chosen = sorted(entries, key=rank)[:MAX_HISTORIES]
    figure = Figure("history", "s_histories", "s_time", "s_theta", bounds=True)
    for entry in chosen:
        s, n = int(entry["start"]), int(entry["count"])
        t = f["histories/t"][s : s + n]
        ratio = f["histories/theta"][s : s + n] / entry["alpha_rad"]
        channel_id = _channel(str(entry["record_id"]), str(entry["component"]))[2]
        label = f"{channel_id} · {entry['model']}"
        ref = _motion(f, model, str(entry["record_id"]), str(entry["component"]))
        figure.series.append(reduce_series(t, ratio, label=label, unit="1", ref=ref))
    figure.series[0].label += " ★"
    return [figure]


def _motion(f: h5py.File, model: ReportModel, record_id: str, component: str) -> str:
    """Reduce the record's component once into ``model.motions``; return its key or ``""``."""
    group, channel, key = _channel(record_id, component)
    if key in model.motions:
        return key
    path = f"records/{group}/{channel}"
    if path not in f:
        return ""  # rotated to the tower's axes: the rotated motion is not stored
    acc = f[path][:]
    dt = float(f[f"records/{group}"].attrs.get("dt", 0.0))
    if dt <= 0 or acc.size == 0:
        return ""
    t = np.arange(acc.size) * dt
    model.motions[key] = reduce_series(t, acc, label=f"{key} [m/s²]", unit="m/s2", bins=MOTION_BINS)
    return key


def run_reader_model(reader: RunReader) -> ReportModel:
    """Build the model of a campaign archive opened by ``open_archive`` (:func:`run_model`)."""
    return run_model(reader.path)
