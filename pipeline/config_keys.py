"""The table of every configuration key: name, TOML type, default, bounds, allowed values, doc.

:data:`KEYS` is the single source of truth: :mod:`rockscreen.pipeline.config_schema` checks values
against it and writes the key table of docs/campaign.md from it.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal

from rockscreen.pipeline.engine.registry import model_names
from rockscreen.solver.constants import G

#: History settings of the archive.
HISTORY_MODES = ("none", "decimated", "full")
#: ``[processing] detrend`` values.
DETREND_TYPES = ("linear", "constant")


@dataclass(frozen=True)
class Key:
    """The specification of one configuration key."""

    #: ``""`` for the top level, else the TOML table (``"processing.quality"``).
    table: str
    #: Key name.
    name: str
    #: TOML type, in the order of the annotation: boolean; integer; number (integer or float,
    #: never a boolean, finite); string naming a path; string from ``choices``; non-empty array
    #: of distinct strings from ``choices``.
    kind: Literal["bool", "int", "float", "path", "choice", "choices"]
    #: Value when the key is absent (None: the option is off; TOML cannot write None).
    default: Any
    #: One sentence of documentation, with the unit in brackets.
    doc: str
    #: Bounds of a number; ``low_open``/``high_open`` exclude them.
    low: float | None = None
    high: float | None = None
    low_open: bool = False
    high_open: bool = False
    #: Allowed strings of a ``choice`` or ``choices`` key.
    choices: tuple[str, ...] = ()
    #: None is accepted from a Python mapping (the processing defaults that can be off).
    optional: bool = False

    @property
    def where(self) -> str:
        """Return ``[table] name`` (or ``name`` at the top level)."""
        return f"[{self.table}] {self.name}" if self.table else self.name

    def bounds_text(self) -> str:
        """Return the bounds in words, e.g. ``"> 0 and <= 0.5"`` (``""`` when unbounded)."""
        parts = []
        if self.low is not None:
            parts.append(f"{'>' if self.low_open else '>='} {_number(self.low)}")
        if self.high is not None:
            parts.append(f"{'<' if self.high_open else '<='} {_number(self.high)}")
        return " and ".join(parts)

    def allowed_text(self) -> str:
        """Return what values are allowed, for messages and documentation."""
        if self.kind in ("choice", "choices"):
            return ", ".join(f'"{c}"' for c in self.choices)
        if self.kind == "float":
            bounds = self.bounds_text()
            return f"finite, {bounds}" if bounds else "finite"
        if self.kind == "bool":
            return "true, false"
        if self.kind == "path":
            return "any path"
        return self.bounds_text()


def _number(value: float) -> str:
    return str(int(value)) if float(value).is_integer() else f"{value:g}"


def _n(table: str, name: str, default: float, doc: str, **bounds: Any) -> Key:
    return Key(table, name, "float", default, doc, **bounds)


_P, _Q = "processing", "processing.quality"
_SF = "safety_factor"

#: Every configuration key, in documentation order.
KEYS: tuple[Key, ...] = (
    Key("", "inventory", "path", "", "Tower inventory CSV; relative to the file's folder."),
    Key("", "stations", "path", "", "StationXML with station coordinates; relative as above."),
    Key(_P, "demean", "bool", True, "Remove the mean first."),
    Key(_P, "detrend", "choice", "linear", "Trend removed.", choices=DETREND_TYPES, optional=True),
    _n(
        _P,
        "taper_fraction",
        0.05,
        "Cosine taper at each end, fraction of the record [-].",
        low=0.0,
        high=0.5,
    ),
    _n(_P, "freqmin_hz", 0.1, "Band-pass low corner [Hz].", low=0.0, low_open=True, optional=True),
    _n(
        _P,
        "freqmax_hz",
        20.0,
        "Band-pass high corner, below the Nyquist frequency [Hz].",
        low=0.0,
        low_open=True,
        optional=True,
    ),
    Key(_P, "filter_order", "int", 4, "Butterworth order of each pass [-].", low=1, high=10),
    Key(_P, "zerophase", "bool", True, "Acausal (forward-backward) filtering."),
    _n(
        _P,
        "resample_hz",
        None,
        "New sampling rate after filtering; absent = keep [Hz].",
        low=0.0,
        low_open=True,
        high=1000.0,
        optional=True,
    ),
    Key(_P, "baseline_correction", "bool", False, "Polynomial baseline correction."),
    Key(_P, "baseline_order", "int", 6, "Degree of the baseline polynomial [-].", low=2, high=10),
    Key(_P, "check_quality", "bool", True, "Refuse traces failing the quality checks."),
    _n(_Q, "min_sampling_rate_hz", 20.0, "Lowest acceptable sampling rate [Hz].", low=0.0),
    _n(_Q, "min_duration_s", 5.0, "Shortest acceptable record [s].", low=0.0),
    _n(_Q, "flat_tolerance", 1e-9, "Peak-to-peak amplitude of a flat record [m/s2].", low=0.0),
    Key(_Q, "clip_run", "int", 5, "Samples at the extreme that make a record clipped [-].", low=2),
    _n(
        _Q,
        "clip_tolerance",
        1e-6,
        "Relative distance from the extreme counted as at it [-].",
        low=0.0,
        high=1.0,
        high_open=True,
    ),
    _n(
        _Q,
        "max_peak_m_s2",
        5.0 * G,
        "Largest plausible peak about the median [m/s2].",
        low=0.0,
        low_open=True,
    ),
    _n(
        _Q,
        "spike_ratio",
        8.0,
        "A sample above this times its neighbours is a spike [-].",
        low=0.0,
        low_open=True,
    ),
    Key(_Q, "spike_half_window", "int", 3, "Neighbours on each side of a spike test [-].", low=1),
    _n(
        _Q,
        "spike_floor",
        0.25,
        "Fraction of the peak below which no sample is a spike [-].",
        low=0.0,
        high=1.0,
    ),
    _n(
        _Q,
        "max_vertical_ratio",
        2.0,
        "Vertical over horizontal peak that is flagged [-].",
        low=0.0,
        low_open=True,
    ),
    _n(
        "pairing",
        "max_distance_km",
        50.0,
        "Nearest station farther -> tower not paired [km].",
        low=0.0,
        low_open=True,
        high=20040.0,
    ),
    Key(
        "models",
        "run",
        "choices",
        model_names(),
        "Models run where the tower's data allow.",
        choices=model_names(),
    ),
    _n(
        "models",
        "free_motion_s",
        60.0,
        "Longest free motion after the record ends [s].",
        low=0.0,
        low_open=True,
        high=3600.0,
    ),
    Key(_SF, "enabled", "bool", True, "Search the safety factor of every tower."),
    _n(
        _SF,
        "start",
        0.05,
        "Smallest factor the scan may start from [-].",
        low=0.0,
        low_open=True,
        high=1.0,
    ),
    _n(
        _SF,
        "ratio",
        1.2,
        "Geometric step of the upward scan [-].",
        low=1.0,
        low_open=True,
        high=10.0,
    ),
    _n(
        _SF,
        "cap",
        10.0,
        "Largest factor tried, > start; none found -> inf [-].",
        low=1.0,
        high=1000.0,
    ),
    _n(
        _SF,
        "tolerance",
        0.01,
        "Relative width of the final bracket, < ratio - 1 [-].",
        low=0.0,
        low_open=True,
        high=0.5,
    ),
    _n(
        "risk",
        "rocking_from",
        0.01,
        "theta_max/alpha at which a tower rocks [-].",
        low=0.0,
        low_open=True,
        high=1.0,
    ),
    _n(
        "risk",
        "moderate_from",
        0.2,
        "theta_max/alpha of class moderate [-].",
        low=0.0,
        low_open=True,
        high=1.0,
    ),
    _n(
        "risk",
        "high_from",
        0.5,
        "theta_max/alpha of class high [-].",
        low=0.0,
        low_open=True,
        high=1.0,
    ),
    _n(
        "risk",
        "sf_high_below",
        1.5,
        "Safety factor below which at least high [-].",
        low=1.0,
        high=1000.0,
    ),
    _n(
        "risk",
        "sf_moderate_below",
        2.5,
        "Safety factor below which at least moderate [-].",
        low=1.0,
        high=1000.0,
    ),
    Key(
        "output",
        "histories",
        "choice",
        "decimated",
        "Histories kept in the archive.",
        choices=HISTORY_MODES,
    ),
    Key(
        "output",
        "history_points",
        "int",
        1000,
        "Samples kept per decimated history [-].",
        low=10,
        high=1_000_000,
    ),
)

#: The TOML tables, in documentation order (``""`` is the top level).
TABLES: tuple[str, ...] = tuple(dict.fromkeys(key.table for key in KEYS))


def keys_of(table: str) -> dict[str, Key]:
    """Return the keys of one table (``""``: the top level), by name."""
    return {key.name: key for key in KEYS if key.table == table}


def spec_for(table: str, name: str, default: Any) -> Key:
    """Return the key ``[table] name``, or a spec derived from a field's ``default``.

    The derived spec (a field of ``ProcessingConfig`` or ``QualityLimits`` added without
    a row in :data:`KEYS`) still checks the TOML type and finiteness; the documentation
    test reports the missing row.
    """
    key = keys_of(table).get(name)
    if key is not None:
        return key
    if isinstance(default, bool):
        return Key(table, name, "bool", default, "")
    if isinstance(default, int):
        return Key(table, name, "int", default, "")
    if isinstance(default, str):
        return Key(table, name, "path", default, "")
    return Key(table, name, "float", default, "", optional=True)
