"""The neutral report model: what every archive kind is turned into before rendering.

An adapter per archive kind (``pipeline.report.html.adapters``) reads its archive and
returns one :class:`ReportModel`; :func:`pipeline.report.html.render.render_html` turns
any model into the page. Adding an archive kind is therefore one adapter.

Everything here is plain data (str, float, int, bool, None, lists and dicts of them)
so that the model serialises to JSON for the page's scripts. Text is stored raw; the
renderer escapes it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

__all__ = [
    "Column",
    "Curve",
    "Figure",
    "HeaderItem",
    "ReportModel",
    "Series",
    "Sheet",
    "finite",
]


def finite(value: Any) -> float | None:
    """Return ``value`` as a float, or None when it is missing, NaN or infinite.

    Parameters
    ----------
    value : Any
        A number (any units) or None.

    Returns
    -------
    float or None
        The number; None for JSON (which has no NaN or infinity).
    """
    try:
        number = float(value)
    except (TypeError, ValueError):
        return None
    return number if math.isfinite(number) else None


@dataclass(frozen=True)
class Column:
    """One column of the towers table.

    Attributes
    ----------
    key : str
        Key of the value in each tower row.
    label : str
        Translation key of the header (:mod:`pipeline.report.html.i18n`), or raw text.
    unit : str
        Unit shown in the header in brackets (``"g"``, ``"1/y"``, ``"-"``); ``""`` for text.
    kind : str
        ``"num"`` (numbers, sorted numerically), ``"text"`` or ``"class"`` (risk class).
    digits : int
        Significant digits shown for numbers.
    """

    key: str
    label: str
    unit: str = ""
    kind: str = "num"
    digits: int = 3


@dataclass(frozen=True)
class HeaderItem:
    """One line of the header.

    Attributes
    ----------
    label : str
        Translation key of the label.
    value : str
        Raw value text, or a translation key when ``translate`` is true.
    translate : bool
        Whether ``value`` is a translation key (fixed texts such as model limits).
    """

    label: str
    value: str
    translate: bool = False


@dataclass
class Series:
    """A reduced time history on a uniform time grid, as min/max pairs per bin.

    Attributes
    ----------
    label : str
        Legend text (record, component, model).
    t0 : float
        Start of the first bin [s].
    dt : float
        Bin width [s].
    scale : float
        Value of the int16 code 32767, in the series' units.
    data : str
        Base64 of little-endian int16 pairs (min, max) per bin, times ``scale / 32767``.
    unit : str
        Units of the values (``"1"`` for theta/alpha, ``"m/s2"`` for accelerations).
    ref : str
        Key of a shared series (input motion) in :attr:`ReportModel.motions`, or ``""``.
    """

    label: str
    t0: float
    dt: float
    scale: float
    data: str
    unit: str
    ref: str = ""


@dataclass
class Curve:
    """A plain x-y curve or point set (fragility curve, stripe points, spectra)."""

    label: str
    x: list[float]
    y: list[float]
    style: str = "line"  # "line", "points" or "dashed"


@dataclass
class Figure:
    """One chart of a sheet.

    Attributes
    ----------
    kind : str
        ``"history"`` (series against time, with ±1 lines when ``bounds``) or ``"xy"``.
    title : str
        Translation key or raw text.
    xlabel, ylabel : str
        Axis labels with units in brackets.
    series : list of Series
        Reduced time histories (``kind == "history"``).
    curves : list of Curve
        Curves (``kind == "xy"``).
    bounds : bool
        Draw dashed lines at ±1 (theta = ±alpha).
    logx : bool
        Logarithmic x axis.
    """

    kind: str
    title: str
    xlabel: str
    ylabel: str
    series: list[Series] = field(default_factory=list)
    curves: list[Curve] = field(default_factory=list)
    bounds: bool = False
    logx: bool = False


@dataclass
class Sheet:
    """The sheet of one tower.

    Attributes
    ----------
    inputs : list of (str, str)
        Label (translation key or raw text) and value text with units.
    figures : list of Figure
        Charts, in display order.
    verdict : list of (str, dict)
        Translation keys of the verdict sentences and their named values.
    notes : list of str
        Free notes from the archive (raw text).
    """

    inputs: list[tuple[str, str]] = field(default_factory=list)
    figures: list[Figure] = field(default_factory=list)
    verdict: list[tuple[str, dict[str, Any]]] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)


@dataclass
class ReportModel:
    """Everything the page shows, independent of the archive kind.

    Attributes
    ----------
    kind : str
        ``"run"``, ``"assess"``, ``"scenario"`` or ``"sweep"``.
    title : str
        Page title (raw text).
    header : list of HeaderItem
        What was computed and from which inputs.
    assumptions : list of HeaderItem
        The assumptions that matter (defaults, distances, model limits).
    columns : list of Column
        Columns of the towers table (the first is the tower id).
    towers : list of dict
        One row per tower: the column keys plus ``lat``, ``lon`` [deg] (None when unknown)
        and ``risk_class``.
    sheets : dict
        Tower id -> :class:`Sheet`.
    stations : list of dict
        Map context: ``{"key", "lat", "lon"}`` [deg].
    contours : list of dict
        Map context: ``{"level", "label", "lines": [[[lon, lat], ...], ...]}`` [deg].
    motions : dict
        Shared input motions: key -> :class:`Series` (stored once, referenced by sheets).
    method : str
        Which method text to show: ``"run"``, ``"risk"`` or ``"sweep"``.
    classes : list of str
        Risk classes in legend order (worst first).
    """

    kind: str
    title: str
    header: list[HeaderItem] = field(default_factory=list)
    assumptions: list[HeaderItem] = field(default_factory=list)
    columns: list[Column] = field(default_factory=list)
    towers: list[dict[str, Any]] = field(default_factory=list)
    sheets: dict[str, Sheet] = field(default_factory=dict)
    stations: list[dict[str, Any]] = field(default_factory=list)
    contours: list[dict[str, Any]] = field(default_factory=list)
    motions: dict[str, Series] = field(default_factory=dict)
    method: str = "run"
    classes: list[str] = field(default_factory=list)
