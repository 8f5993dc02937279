"""The neutral report model: what every archive kind is turned into before rendering.

An adapter per archive kind (``rockscreen.pipeline.report.html.adapters``) reads its archive and
returns one :class:`ReportModel`; :func:`rockscreen.pipeline.report.html.render.render_html` turns
any model into the page. Adding an archive kind is therefore one adapter.

Everything here is plain data (str, float, int, bool, None, lists and dicts of them)
so that the model serialises to JSON for the page's scripts. Text is stored raw; the
renderer escapes it.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TypeAlias, TypedDict

from rockscreen.pipeline.report.values import ColumnValue
from rockscreen.pipeline.verdict.messages import Message
from rockscreen.pipeline.verdict.rules import NotMadeText

__all__ = [
    "CheckCell",
    "CheckRow",
    "Column",
    "Contour",
    "Note",
    "Curve",
    "Figure",
    "HeaderItem",
    "Key",
    "Masonry",
    "MethodParagraph",
    "MethodValue",
    "ModelNames",
    "Number",
    "RankedList",
    "RankedRow",
    "ReportModel",
    "RiskValue",
    "Sentence",
    "SensitivityBar",
    "Series",
    "Sheet",
    "SheetValue",
    "Station",
    "SurveyLine",
    "TowerCell",
    "TowerCells",
    "finite",
    "tower_extent",
]


def finite(value: object) -> float | None:
    """Return ``value`` as a float, or None when it is missing, NaN or infinite.

    Parameters
    ----------
    value : object
        A number (any units), its text, or None.

    Returns
    -------
    float or None
        The number; None for JSON (which has no NaN or infinity).
    """
    try:
        number = float(value)  # type: ignore[arg-type]  # what float() refuses is None
    except (TypeError, ValueError):
        return None
    return number if math.isfinite(number) else None


class Number(TypedDict):
    """A number of a sheet line (:func:`~rockscreen.pipeline.report.html.adapters.common.num`).

    Written in the page's language by :func:`rockscreen.pipeline.report.html.i18n.number`.
    """

    #: The value: a finite float, ``"inf"`` (positive infinity) or None (missing, NaN).
    num: float | str | None
    #: Its unit (``"g"``, ``"y"``); ``""`` for none.
    unit: str
    #: Significant digits shown.
    digits: int
    #: ``">"`` a lower bound, ``"<"`` an upper bound (``"<="``, ``">="`` the screening
    #: risk's), ``""`` a value.
    bound: str
    #: Whether ``"= "`` is written before a value that is not a bound.
    relation: bool


class _KeyOnly(TypedDict):
    #: A translation key of :mod:`rockscreen.pipeline.report.html.i18n`.
    key: str


class Key(_KeyOnly, total=False):
    """A translation key on a sheet, with the text shown when the table has no entry for it."""

    #: The text shown when :attr:`key` is not in the table (a class label carrying its
    #: typed marks, :class:`~rockscreen.pipeline.verdict.labels.ClassLabel`, is one).
    raw: str


class Station(TypedDict):
    """A station on the map."""

    #: The station's id (``NET.STA``).
    key: str
    #: Latitude, longitude [deg]; None when unknown.
    lat: float | None
    lon: float | None


class Contour(TypedDict):
    """One PGA contour of a ShakeMap on the map."""

    #: PGA [g].
    level: float
    #: Its label (``"0.1 g"``).
    label: str
    #: The lines: ``[[[lon, lat], ...], ...]`` [deg].
    lines: list[list[list[float]]]


class RiskValue(TypedDict):
    """A value of the screening risk on the ranked list."""

    #: The value [1]; None when missing.
    value: float | None
    #: Its bound: ``"<="`` (at most), ``">="`` (at least), ``"both"`` (not a value) or ``""``.
    sign: str


class RankedRow(TypedDict):
    """One tower of the screening risk's ranked list."""

    rank: int
    id: str
    #: P(collapse in 50 y): best estimate, 5 % and 95 % of its interval [1].
    p50: RiskValue
    lo: RiskValue
    hi: RiskValue
    band: str
    #: Whether the interval reaches another band.
    uncertain: bool
    #: The governing mechanism and its share of the samples [1] (None: missing).
    mechanism: str
    share: float | None
    #: The input to survey first, its expected narrowing [1] and whether its prior is a
    #: judgement.
    survey: str
    narrowing: float | None
    survey_judgement: bool
    #: The code's verdict beside: the tower's class as its summary row holds it, its
    #: governing check.
    code_class: ColumnValue
    code_check: str


class SurveyLine(TypedDict):
    """A line of the region's "what to survey first" (``/risk_top_n``)."""

    id: str
    #: ``"in"`` or ``"out"`` of the top N.
    side: str
    input: str
    #: Probability that surveying the input moves the tower across the line [1] (a line
    #: without one is left out).
    p: float
    #: Whether the input's prior is a judgement.
    judgement: bool


class Masonry(TypedDict, total=False):
    """The tower whose place a masonry survey changes most.

    From ``/risk_top_n`` (``basis`` ``"top_n"``: the keys of :class:`SurveyLine`) or from
    ``/risk_sensitivity`` (``basis`` ``"sensitivity"``: ``id``, ``input``, ``judgement``,
    ``index`` and ``narrowing`` [1]).
    """

    id: str
    side: str
    input: str
    p: float
    judgement: bool
    index: float
    narrowing: float | None
    basis: str


class RankedList(TypedDict):
    """The screening risk's ranked list of an assess archive (the first screen)."""

    #: Whether the archive has the screening risk.
    computed: bool
    #: The towers with a rank, riskiest first.
    rows: list[RankedRow]
    #: The ids of the towers without a risk.
    unranked: list[str]
    top_n: int
    #: The region's "what to survey first", most likely to change the list first.
    survey: list[SurveyLine]
    masonry: Masonry | None


@dataclass(frozen=True)
class Column:
    """One column of the towers table."""

    #: Key of the value in each tower row.
    key: str
    #: Translation key of the header (:mod:`rockscreen.pipeline.report.html.i18n`), or raw text.
    label: str
    #: Unit shown in the header in brackets (``"g"``, ``"1/y"``, ``"-"``); ``""`` for text.
    unit: str = ""
    #: ``"num"`` (numbers, sorted numerically), ``"text"`` or ``"class"`` (risk class).
    kind: str = "num"
    #: Significant digits shown for numbers.
    digits: int = 3
    #: Prefix of the translation keys of the values (``"model_"``: ``ground`` is shown as
    #: ``model_ground`` in the page's language); ``""``: values shown as they are.
    labels: str = ""


@dataclass(frozen=True)
class HeaderItem:
    """One line of the header."""

    #: Translation key of the label.
    label: str
    #: Raw value text, or a translation key when ``translate`` is true.
    value: str
    #: Whether ``value`` is a translation key (fixed texts such as model limits).
    translate: bool = False
    #: Full text shown on hover (the absolute paths behind shortened file names); ``""``: none.
    title: str = ""


@dataclass(frozen=True)
class ModelNames:
    """Models of the engine's registry named in a sentence.

    Written with their labels in the page's language (``model_<name>`` of
    :mod:`rockscreen.pipeline.report.html.i18n`).
    """

    #: The models' names, in the archive's order.
    names: tuple[str, ...]


#: A value of a sheet line: text, a number, a translation key, a catalogue message, the
#: checks not made, the models named in a sentence.
SheetValue: TypeAlias = str | Number | Key | Message | NotMadeText | ModelNames
#: A sentence: a translation key (or catalogue code) and its named values.
Sentence: TypeAlias = tuple[str, dict[str, SheetValue]]
#: A cell of the checks table: a label, a number, text, or a sentence (the details).
CheckCell: TypeAlias = SheetValue | Sentence
#: A row of the checks table: ``(label, a_C, I_S, details)`` (label: a translation key,
#: raw text or a message of the catalogue, a check added as a module's; a_C and I_S: numbers
#: or ``"-"``; details: text, a key, a message or a sentence).
CheckRow: TypeAlias = tuple[str | Message, str | Number, str | Number, CheckCell]
#: A sensitivity bar: ``(input translation key, first-order Sobol' index, expected
#: narrowing, judgement)`` ([1]; None: missing).
SensitivityBar: TypeAlias = tuple[str, float | None, float | None, bool]
#: A parameter of a method sentence (:class:`MethodParagraph`): a number, text, a message
#: (a check's label, the priors' source), messages listed, or the models named.
MethodValue: TypeAlias = str | int | float | Message | tuple[Message, ...] | ModelNames
#: A cell of a tower's row in the towers table: a column value (the class a
#: :class:`~rockscreen.pipeline.verdict.labels.ClassLabel`), a message rendered per
#: language, or the ``bounds`` (column key -> ``">"``, ``"<"``, ``"≤"``, ``"≥"``).
TowerCell: TypeAlias = ColumnValue | Message | dict[str, str]
#: A tower's row in the towers table: column key -> cell.
TowerCells: TypeAlias = dict[str, TowerCell]


@dataclass
class Series:
    """A reduced time history on a uniform time grid, as min/max pairs per bin."""

    #: Legend text (record, component, model).
    label: str
    #: Start of the first bin [s].
    t0: float
    #: Bin width [s].
    dt: float
    #: Value of the int16 code 32767, in the series' units.
    scale: float
    #: Base64 of little-endian int16 pairs (min, max) per bin, times ``scale / 32767``.
    data: str
    #: Units of the values (``"1"`` for theta/alpha, ``"m/s2"`` for accelerations).
    unit: str
    #: Key of a shared series (input motion) in :attr:`ReportModel.motions`, or ``""``.
    ref: str = ""


@dataclass
class Curve:
    """A plain x-y curve or point set (fragility curve, stripe points, spectra)."""

    #: Legend text: a translation key (filled with ``values``) or raw text.
    label: str
    x: list[float]
    y: list[float]
    style: str = "line"  # "line", "points" or "dashed"
    #: Fields of the label's template (numbers of ``adapters.common.num``, text).
    values: dict[str, SheetValue] = field(default_factory=dict)


@dataclass
class Figure:
    """One chart of a sheet."""

    #: ``"history"`` (series against time, with ±1 lines when ``bounds``) or ``"xy"``.
    kind: str
    #: Translation key or raw text.
    title: str
    #: Axis labels with units in brackets.
    xlabel: str
    ylabel: str
    #: Reduced time histories (``kind == "history"``).
    series: list[Series] = field(default_factory=list)
    #: Curves (``kind == "xy"``).
    curves: list[Curve] = field(default_factory=list)
    #: Draw dashed lines at ±1 (theta = ±alpha).
    bounds: bool = False
    #: Logarithmic x axis.
    logx: bool = False
    #: Fixed y range ``[low, high]`` (a probability: ``[0, 1]``); None: fitted to the data.
    yrange: list[float] | None = None
    #: Fixed x range ``[low, high]``; None: fitted to the data.
    xrange: list[float] | None = None


@dataclass(frozen=True)
class Note:
    """A note from the archive: its English text and its stored codes.

    Rendered per language by :func:`rockscreen.pipeline.report.html.notes.note_text`.
    """

    #: English text (the archive's ``note``, or a failure's ``kind: reason``).
    text: str
    #: The archive's ``note_codes`` (JSON text); None for text without codes (an archive
    #: written before them, a failure's reason): read by the adapter of older archives.
    codes: str | None = None


@dataclass
class Sheet:
    """The sheet of one tower."""

    #: Label (translation key or raw text) and value: text with units, or a number of
    #: :func:`~rockscreen.pipeline.report.html.adapters.common.num` (written per language).
    inputs: list[tuple[str, SheetValue]] = field(default_factory=list)
    #: Charts, in display order.
    figures: list[Figure] = field(default_factory=list)
    #: Translation keys of the verdict sentences and their named values.
    verdict: list[Sentence] = field(default_factory=list)
    #: Notes from the archive.
    notes: list[Note] = field(default_factory=list)
    #: The checks side by side (assess): one row per check, ``(label, a_C, I_S, details)``
    #: (label: translation key or raw text; a_C and I_S: numbers of ``num`` or text).
    checks: list[CheckRow] = field(default_factory=list)
    #: Sentences under that table, as translation keys and values: the governing check,
    #: where the methods disagree and why, the checks not made.
    checks_text: list[Sentence] = field(default_factory=list)
    #: The screening risk's lines (translation keys and values): P50 best with its 90 %
    #: interval, rank, band, governing mechanism; apart from the code's verdict.
    risk: list[Sentence] = field(default_factory=list)
    #: The screening risk's sensitivity bars: ``(input translation key, first-order Sobol'
    #: index, expected narrowing, judgement (bool: the input's prior is a judgement))``.
    sensitivity: list[SensitivityBar] = field(default_factory=list)


@dataclass
class MethodParagraph:
    """One paragraph of the "Method, references and limits" section, built from an archive.

    Every sentence is a code of the message catalogue
    (:mod:`rockscreen.pipeline.verdict.catalogue`) with its parameters, rendered in the
    page's language; a parameter may be a :class:`ModelNames` (the registry's labels).
    """

    #: The paragraph's heading, a catalogue code without parameters (``"method.h_fragility"``).
    heading: str
    #: The sentences: (catalogue code, parameters).
    sentences: list[tuple[str, dict[str, MethodValue]]] = field(default_factory=list)


@dataclass
class ReportModel:
    """Everything the page shows, independent of the archive kind."""

    #: ``"run"``, ``"assess"``, ``"scenario"`` or ``"sweep"``.
    kind: str
    #: Page title (raw text).
    title: str
    #: What was computed and from which inputs.
    header: list[HeaderItem] = field(default_factory=list)
    #: The assumptions that matter (defaults, distances, model limits).
    assumptions: list[HeaderItem] = field(default_factory=list)
    #: Columns of the towers table (the first is the tower id).
    columns: list[Column] = field(default_factory=list)
    #: One row per tower: the column keys plus ``lat``, ``lon`` [deg] (None when unknown),
    #: ``risk_class`` and, when a cell is a bound, ``bounds``: column key -> ``">"`` (the value
    #: is a lower bound) or ``"<"`` (an upper bound).
    towers: list[TowerCells] = field(default_factory=list)
    #: Tower id -> :class:`Sheet`.
    sheets: dict[str, Sheet] = field(default_factory=dict)
    #: Map context: ``{"key", "lat", "lon"}`` [deg].
    stations: list[Station] = field(default_factory=list)
    #: Map context: ``{"level", "label", "lines": [[[lon, lat], ...], ...]}`` [deg].
    contours: list[Contour] = field(default_factory=list)
    #: Shared input motions: key -> :class:`Series` (stored once, referenced by sheets).
    motions: dict[str, Series] = field(default_factory=dict)
    #: Which method text to show: ``"run"``, ``"risk"`` or ``"sweep"``.
    method: str = "run"
    #: The method section built from the archive (:class:`MethodParagraph`); when given it
    #: replaces the fixed text of :attr:`method`.
    method_text: list[MethodParagraph] = field(default_factory=list)
    #: Risk classes in legend order (worst first).
    classes: list[str] = field(default_factory=list)
    #: The screening risk's ranked list (an assess archive:
    #: :func:`rockscreen.pipeline.report.html.adapters.risk_rank.ranked_list`); None for the
    #: kinds that have none.
    risk: RankedList | None = None


def tower_extent(
    towers: Sequence[Mapping[str, TowerCell]],
    fallback: Sequence[tuple[float, float]] = (),
    margin: float = 0.15,
    min_span_deg: float = 0.02,
) -> list[float] | None:
    """Return the map's initial extent: the towers with a margin (not every station).

    Parameters
    ----------
    towers : sequence of mapping
        Tower rows with ``lat`` and ``lon`` [deg] (None when unknown).
    fallback : sequence of (lon, lat)
        Points [deg] to fit when no tower has coordinates (stations, contours).
    margin : float
        Share of the span added on each side [-].
    min_span_deg : float
        Smallest span [deg] (about 2 km): one tower, or towers in one village, still show
        their surroundings.

    Returns
    -------
    list of float or None
        ``[lon_min, lat_min, lon_max, lat_max]`` [deg]; None when there is nothing to fit.
    """
    located = [(finite(t.get("lon")), finite(t.get("lat"))) for t in towers]
    points = [(x, y) for x, y in located if x is not None and y is not None] or [
        (float(x), float(y)) for x, y in fallback
    ]
    if not points:
        return None
    lons, lats = [p[0] for p in points], [p[1] for p in points]
    out = []
    for lo, hi in ((min(lons), max(lons)), (min(lats), max(lats))):
        span = max(hi - lo, min_span_deg)
        centre = (lo + hi) / 2
        out.append((centre - span * (0.5 + margin), centre + span * (0.5 + margin)))
    (x0, x1), (y0, y1) = out
    return [round(x0, 6), round(y0, 6), round(x1, 6), round(y1, 6)]
