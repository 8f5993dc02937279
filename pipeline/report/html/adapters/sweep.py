"""Adapter: the sweep archive (``rockscreen sweep``) -> :class:`ReportModel`.

A sweep is one tower under a grid of idealised excitations, so the rows of the table
are the cases, not towers; each case has a sheet with its rotation history. Cases carry
no coordinates (no map). The class of a case is the campaign's rule on θ_max/α and
overturning (:func:`rockscreen.pipeline.screening.risk.risk_class`, default limits, no safety
factor).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from rockscreen.pipeline.archive.kinds import SweepReader
from rockscreen.pipeline.archive.sweep_archive import read_archive_attrs, read_cases, read_histories
from rockscreen.pipeline.report.html.adapters.common import (
    CLASS_COLUMN,
    ID_COLUMN,
    header_items,
    motion_verdict,
    number_inputs,
    number_text,
)
from rockscreen.pipeline.report.html.adapters.run import RISK_CLASSES
from rockscreen.pipeline.report.html.model import (
    Column,
    Figure,
    HeaderItem,
    Key,
    Number,
    ReportModel,
    Sentence,
    Sheet,
    finite,
)
from rockscreen.pipeline.report.html.reduce import reduce_series
from rockscreen.pipeline.report.values import Row
from rockscreen.pipeline.screening.risk import risk_class

__all__ = ["sweep_model", "sweep_reader_model"]

COLUMNS = [
    ID_COLUMN,
    Column("group", "col_group", "", "text"),
    Column("model", "col_model", "", "text", labels="model_"),
    CLASS_COLUMN,
    Column("amplitude_g", "col_amplitude", "g"),
    Column("frequency_hz", "col_frequency", "Hz"),
    Column("mu", "col_mu", "", "text"),
    Column("theta_max_over_alpha", "col_theta", "-"),
    Column("status", "col_status", "", "text"),
]
#: The swept tower's inputs shown on every sheet (:data:`~.common.TOWER_INPUTS`).
_INPUTS = ("width_m", "height_m", "alpha_rad", "eta", "tower_mass_kg", "building_mass_kg")


def sweep_model(path: str | Path) -> ReportModel:
    """Build the report model of a sweep archive.

    Parameters
    ----------
    path : str or Path
        An archive of ``rockscreen sweep``.

    Returns
    -------
    ReportModel
        One row and one sheet per case; the header names the study and the tower.
    """
    attrs = read_archive_attrs(path)
    tower = attrs.get("tower", {})
    cases = read_cases(path)
    histories = read_histories(path)  # one open and check for every case's figure
    model = ReportModel(kind="sweep", title="kind_sweep", method="sweep", classes=RISK_CLASSES)
    model.header = [HeaderItem("h_kind", "kind_sweep", True)]
    model.header += header_items(
        attrs,
        [
            ("study_title", "h_study"),
            ("study_source", "h_config"),
            ("rockscreen_version", "h_version"),
            ("created_utc", "h_created"),
            ("format_version", "h_format"),
        ],
    )
    model.header.append(HeaderItem("h_cases", str(len(cases))))
    model.assumptions = [HeaderItem("a_vertical", "a_vertical_text", True)]
    model.columns = COLUMNS
    inputs = _tower_inputs(tower)
    for row in cases:
        case_id = f"{row['index']}"
        ratio = finite(row.get("theta_max_over_alpha"))
        overturned = bool(row.get("overturned"))
        cls = risk_class(ratio if ratio is not None else 0.0, overturned, math.nan)
        mu = ""
        if finite(row.get("mu_s")) is not None:
            mu = f"{number_text(row['mu_s'])} / {number_text(row['mu_k'])}"
        model.towers.append(
            {
                "id": case_id,
                "group": str(row.get("group", "")),
                "model": str(row.get("model", "")),
                "lat": None,
                "lon": None,
                "risk_class": cls,
                "amplitude_g": finite(row.get("amplitude_g")),
                "frequency_hz": finite(row.get("frequency_hz")),
                "mu": mu,
                "theta_max_over_alpha": ratio,
                "status": str(row.get("status", "")),
            }
        )
        sheet = Sheet(inputs=[*inputs, *_case_inputs(row)], verdict=_verdict(row, cls))
        figure = _history(histories.get(int(row["index"])), row, tower)
        if figure is not None:
            sheet.figures.append(figure)
        model.sheets[case_id] = sheet
    return model


def _tower_inputs(tower: Row) -> list[tuple[str, str | Number]]:
    return [("i_name", str(tower.get("name", ""))), *number_inputs(tower, _INPUTS, "-")]


def _case_inputs(row: Row) -> list[tuple[str, str]]:
    excitation = f"{row.get('excitation', '')} {row.get('shape', '')}".strip()
    amplitude_g = number_text(row.get("amplitude_g"), "g")
    out = [
        ("col_group", f"{row.get('group', '')} ({row.get('model', '')}, {excitation})"),
        ("col_amplitude", f"{row.get('amplitude', '')} = {amplitude_g}"),
        ("col_frequency", number_text(row.get("frequency_hz"), "Hz")),
    ]
    if finite(row.get("mu_s")) is not None:
        out.append(("i_friction", f"{number_text(row['mu_s'])} / {number_text(row['mu_k'])}"))
    if finite(row.get("eta")) is not None:
        out.append(("i_eta", number_text(row["eta"], "-")))
    return out


def _verdict(row: Row, cls: str) -> list[Sentence]:
    record = f"{row.get('amplitude', '')} @ {number_text(row.get('frequency_hz'), 'Hz')}"
    return [
        motion_verdict(row, record, str(row.get("model", ""))),
        ("v_class", {"cls": Key(key=f"class_{cls}", raw=cls)}),
    ]


def _history(history: Mapping[str, np.ndarray] | None, row: Row, tower: Row) -> Figure | None:
    """Return the case's rotation history over alpha; None for a case without history."""
    alpha = finite(tower.get("alpha_rad"))
    if alpha is None or history is None or "t" not in history or "theta" not in history:
        return None
    figure = Figure("history", "s_histories", "s_time", "s_theta", bounds=True)
    label = f"{row.get('group', '')} · {row.get('amplitude', '')}"
    figure.series.append(
        reduce_series(history["t"], history["theta"] / alpha, label=label, unit="1")
    )
    return figure


def sweep_reader_model(reader: SweepReader) -> ReportModel:
    """Build the model of a sweep archive opened by ``open_archive`` (:func:`sweep_model`)."""
    return sweep_model(reader.path)
