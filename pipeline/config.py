"""The screening configuration: a TOML file with a documented default for every key.

A campaign reads ``--config FILE`` or, when absent, ``rockscreen.toml`` in the
current directory; with neither, every default below applies. Unknown keys are an
error (:class:`rockscreen.pipeline.errors.ConfigError`) that names the key and the allowed ones,
so a typo never silently falls back to a default. Every value is checked against its
specification in :data:`rockscreen.pipeline.config_keys.KEYS` (TOML type -- a boolean must be
``true``/``false``, never ``"false"`` --, finiteness, bounds, allowed strings); that
table also writes the key table of docs/campaign.md.

Layout and defaults (the resolved configuration is stored in every archive)::

    inventory = ""            # tower inventory CSV; "" = --towers, ./towers.csv or the example
    stations = ""             # StationXML with station coordinates; "" = --stations or none

    [processing]              # keyword arguments of pipeline.processing.steps.ProcessingConfig
                              # (empty = that class's defaults)

    [pairing]
    max_distance_km = 50.0    # nearest station farther than this -> tower not paired [km]

    [models]
    run = ["ground", "floor", "double", "belfry", "gable"]  # where the tower's data allow
    free_motion_s = 60.0      # longest free motion integrated after the record ends [s]

    [safety_factor]
    enabled = true
    start = 0.05              # smallest factor the scan may start from [-]
    ratio = 1.2               # geometric step of the upward scan [-]
    cap = 10.0                # largest factor tried; none found -> inf [-]
    tolerance = 0.01          # relative width of the final bisection bracket [-]

    [risk]                    # thresholds, see pipeline.screening.risk and docs/campaign.md
    rocking_from = 0.01       # theta_max/alpha at which a tower counts as rocking [-]
    moderate_from = 0.2       # theta_max/alpha of class "moderate" [-]
    high_from = 0.5           # theta_max/alpha of class "high" [-]
    sf_high_below = 1.5       # safety factor below which a tower is at least "high" [-]
    sf_moderate_below = 2.5   # safety factor below which a tower is at least "moderate" [-]

    [output]
    histories = "decimated"   # "none" | "decimated" | "full"
    history_points = 1000     # samples kept per decimated history [-]
"""

from __future__ import annotations

import codecs
import dataclasses
import difflib
import hashlib
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from rockscreen.pipeline.config_schema import (
    HISTORY_MODES,
    check_value,
    fail,
    keys_of,
    spec_for,
    toml_text,
    toml_type,
    tomllib,
)
from rockscreen.pipeline.engine.registry import model_names
from rockscreen.pipeline.errors import ConfigError, RockscreenError
from rockscreen.pipeline.processing.steps import ProcessingConfig
from rockscreen.pipeline.records.quality import QualityLimits

#: The configuration file read from the current directory when ``--config`` is not given.
DEFAULT_CONFIG_NAME = "rockscreen.toml"
#: Most steps of the safety-factor scan, ``log(cap / start) / log(ratio)`` (default: 29).
MAX_SCAN_STEPS = 500

__all__ = [
    "MAX_SCAN_STEPS",
    "DEFAULT_CONFIG_NAME",
    "HISTORY_MODES",
    "CampaignConfig",
    "config_from_mapping",
    "load_config",
    "processing_config",
]


@dataclass(frozen=True)
class PairingConfig:
    """Pairing of towers with stations."""

    #: A tower farther than this from its nearest station is not paired [km].
    max_distance_km: float = 50.0


@dataclass(frozen=True)
class ModelsConfig:
    """Which models run, and how long free motion is followed."""

    #: Names of campaign models of the registry (default all: ``ground``, ``floor``,
    #: ``double``, ``belfry``, ``gable``); each runs only for towers with the inventory
    #: data it requires.
    run: tuple[str, ...] = field(default_factory=model_names)
    #: Longest free motion integrated after the end of the record [s] (the solvers'
    #: ``max_free_time``); a tower still rocking then has status ``moving_at_end``.
    free_motion_s: float = 60.0


@dataclass(frozen=True)
class SafetyFactorConfig:
    """Search of the safety factor (see :func:`pipeline.screening.risk.safety_factor`)."""

    #: Search the safety factor of every tower (on its governing case).
    enabled: bool = True
    #: Smallest scale factor the upward scan may start from [-].
    start: float = 0.05
    #: Geometric step between scanned factors, > 1 [-].
    ratio: float = 1.2
    #: Largest factor tried; when none up to it overturns, the factor is inf [-].
    cap: float = 10.0
    #: Relative width of the bracket that ends the bisection [-].
    tolerance: float = 0.01


@dataclass(frozen=True)
class RiskConfig:
    """Thresholds of the risk classes (see :func:`pipeline.screening.risk.risk_class`)."""

    rocking_from: float = 0.01
    moderate_from: float = 0.2
    high_from: float = 0.5
    sf_high_below: float = 1.5
    sf_moderate_below: float = 2.5


@dataclass(frozen=True)
class OutputConfig:
    """What the archive keeps."""

    #: ``"none"``; ``"decimated"`` (per tower, the worst component of every record-model pair, at
    #: most ``history_points`` samples, peaks kept); or ``"full"`` (every case at full resolution:
    #: for small campaigns).
    histories: str = "decimated"
    #: Samples kept per decimated history.
    history_points: int = 1000


@dataclass(frozen=True)
class CampaignConfig:
    """The resolved configuration of a screening campaign."""

    #: Tower inventory CSV named by the configuration ("" = not named).
    inventory: str = ""
    #: StationXML named by the configuration ("" = not named).
    stations: str = ""
    #: Keyword arguments of ``rockscreen.pipeline.processing.steps.ProcessingConfig``.
    processing: dict[str, Any] = field(default_factory=dict)
    pairing: PairingConfig = PairingConfig()
    models: ModelsConfig = ModelsConfig()
    safety_factor: SafetyFactorConfig = SafetyFactorConfig()
    risk: RiskConfig = RiskConfig()
    output: OutputConfig = OutputConfig()
    #: Where the configuration came from (file path or "defaults").
    source: str = "defaults"

    def to_toml(self) -> str:
        """Return the resolved configuration as TOML text (``source`` excluded)."""
        lines = [
            f"inventory = {toml_text(self.inventory)}",
            f"stations = {toml_text(self.stations)}",
        ]
        # Every processing parameter, defaults included, so the archive shows what ran.
        lines += ["", "[processing]"]
        items = sorted(processing_config(self.processing).to_dict().items())
        lines += [_toml_line(key, v) for key, v in items if not isinstance(v, dict)]
        for key, table in items:
            if isinstance(table, dict):
                lines += ["", f"[processing.{key}]"]
                lines += [_toml_line(k, v) for k, v in sorted(table.items())]
        for name in _SECTIONS:
            section = getattr(self, name)
            lines += ["", f"[{name}]"]
            for fld in dataclasses.fields(section):
                lines.append(f"{fld.name} = {toml_text(getattr(section, fld.name))}")
        return "\n".join(lines) + "\n"

    def fingerprint(self) -> str:
        """Return a SHA-256 of the resolved TOML text: equal configs, equal prints."""
        return hashlib.sha256(self.to_toml().encode()).hexdigest()


_SECTIONS = {
    "pairing": PairingConfig,
    "models": ModelsConfig,
    "safety_factor": SafetyFactorConfig,
    "risk": RiskConfig,
    "output": OutputConfig,
}
_TOP_LEVEL = ("inventory", "stations", "processing", *_SECTIONS)


def _toml_line(key: str, value: Any) -> str:
    # TOML has no null: an unset option (None, e.g. no resampling) is written as a comment.
    return f"# {key} = (not set)" if value is None else f"{key} = {toml_text(value)}"


def load_config(path: str | Path | None = None, *, cwd: str | Path | None = None) -> CampaignConfig:
    """Read a campaign configuration, or the defaults.

    Parameters
    ----------
    path : str or Path, optional
        A TOML file (UTF-8; a leading byte-order mark is ignored). When None,
        ``rockscreen.toml`` in ``cwd`` is read if present.
    cwd : str or Path, optional
        Directory searched for ``rockscreen.toml`` (default: the current directory).

    Returns
    -------
    CampaignConfig
        Defaults overridden by the file. Relative ``inventory`` and ``rockscreen.stations`` paths
        are resolved against the file's directory.

    Raises
    ------
    ConfigError
        If the file is missing, unreadable, not UTF-8, not valid TOML, holds an unknown
        key or a value of the wrong type or out of its bounds (one line, file and key
        named).
    """
    if path is None:
        candidate = Path(cwd or Path.cwd()) / DEFAULT_CONFIG_NAME
        if not candidate.is_file():
            return CampaignConfig()
        path = candidate
    path = Path(path)
    try:
        raw = path.read_bytes()
    except FileNotFoundError as exc:
        raise ConfigError(f"configuration file {str(path)!r} does not exist") from exc
    except OSError as exc:
        raise ConfigError(f"{path}: cannot read the configuration ({exc.strerror})") from exc
    # A byte-order mark (Windows editors write one) is not TOML: strip it, as the inventory does.
    bom = len(codecs.BOM_UTF8) if raw.startswith(codecs.BOM_UTF8) else 0
    try:
        text = raw[bom:].decode("utf-8")
    except UnicodeDecodeError as exc:
        raise ConfigError(
            f"{path}: the configuration is not UTF-8 text ({exc.reason} at byte "
            f"{exc.start + bom}: 0x{raw[exc.start + bom]:02x})"
        ) from exc
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise ConfigError(f"configuration file {str(path)!r} is not valid TOML: {exc}") from exc
    return config_from_mapping(data, source=str(path), base=path.parent)


def config_from_mapping(
    data: dict[str, Any], *, source: str = "mapping", base: Path | None = None
) -> CampaignConfig:
    """Build and validate a :class:`CampaignConfig` from a parsed TOML mapping.

    Every value is checked against its key in :data:`rockscreen.pipeline.config_keys.KEYS`
    (TOML type, finiteness, bounds, allowed values), then the rules between keys.

    Parameters
    ----------
    data : dict
        Parsed TOML.
    source : str
        Where the mapping came from, for messages.
    base : Path, optional
        Directory that relative ``inventory`` and ``rockscreen.stations`` paths are relative to.

    Returns
    -------
    CampaignConfig

    Raises
    ------
    ConfigError
        On unknown keys or invalid values.
    """
    _check_keys(data, _TOP_LEVEL, "top level", source)
    kwargs: dict[str, Any] = {"source": source}
    for key in keys_of("").values():
        if key.name in data:
            value = check_value(key, data[key.name], source)
            if value and base is not None and not Path(value).is_absolute():
                value = str(base / value)
            kwargs[key.name] = value
    if "processing" in data:
        kwargs["processing"] = _processing(data["processing"], source)
    for name, cls in _SECTIONS.items():
        if name in data:
            kwargs[name] = cls(**_table(data[name], name, source))
    config = CampaignConfig(**kwargs)
    _validate(config, source)
    return config


def _check_keys(table: Any, allowed: tuple[str, ...], where: str, source: str) -> None:
    if not isinstance(table, dict):  # pragma: no cover - callers check tables first
        raise ConfigError(f"{source}: [{where}] must be a table, got {table!r}")
    for key in table:
        if key not in allowed:
            close = difflib.get_close_matches(str(key), allowed, n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise ConfigError(
                f"{source}: unknown key {key!r} in {where}; allowed: {', '.join(allowed)}{hint}"
            )


def _table(
    table: Any, name: str, source: str, fields: dict[str, Any] | None = None
) -> dict[str, Any]:
    """Check the table ``[name]`` key by key; return its checked values.

    ``fields`` maps the allowed keys to their defaults when a dataclass defines them
    (``[processing]``, ``[processing.quality]``); otherwise the key table does.
    """
    if not isinstance(table, dict):
        parent, _, leaf = name.rpartition(".")
        where = f"[{parent}] {leaf}" if parent else name
        raise fail(source, where, table, f"expected a table ([{name}]), got {toml_type(table)}")
    if fields is None:
        fields = {key: spec.default for key, spec in keys_of(name).items()}
    _check_keys(table, tuple(fields), f"[{name}]", source)
    return {
        key: value
        if key == "quality"
        else check_value(spec_for(name, key, fields[key]), value, source)
        for key, value in table.items()
    }


def _processing(table: Any, source: str) -> dict[str, Any]:
    values = _table(table, "processing", source, _field_defaults(ProcessingConfig))
    if "quality" in values:
        quality = _field_defaults(QualityLimits)
        values["quality"] = _table(values["quality"], "processing.quality", source, quality)
    try:
        processing_config(values)
    except (RockscreenError, TypeError) as exc:
        raise ConfigError(f"{source}: [processing]: {exc}") from exc
    return values


def _field_defaults(cls: type) -> dict[str, Any]:
    defaults = cls()
    return {f.name: getattr(defaults, f.name) for f in dataclasses.fields(cls)}


def processing_config(values: dict[str, Any]) -> Any:
    """Return the ``pipeline.processing.steps.ProcessingConfig`` of a ``[processing]`` table."""
    values = dict(values)
    if "quality" in values:
        values["quality"] = QualityLimits(**values["quality"])
    return ProcessingConfig(**values)


def _validate(config: CampaignConfig, source: str) -> None:
    """Check the rules between keys (each key alone is checked by ``check_value``)."""

    def refuse(key: str, value: Any, rule: str) -> None:
        raise ConfigError(f"{source}: {key}={value!r} {rule}")

    sf = config.safety_factor
    if not sf.cap > sf.start:
        refuse("[safety_factor] cap", sf.cap, f"must exceed start={sf.start}")
    if not sf.tolerance < sf.ratio - 1:
        refuse(
            "[safety_factor] tolerance",
            sf.tolerance,
            f"must be in (0, ratio - 1 = {sf.ratio - 1:g})",
        )
    steps = math.log(sf.cap / sf.start) / math.log(sf.ratio)
    if steps > MAX_SCAN_STEPS:
        refuse(
            "[safety_factor] ratio",
            sf.ratio,
            f"gives {steps:.0f} scan steps from start={sf.start} to cap={sf.cap}; at most "
            f"{MAX_SCAN_STEPS} (raise ratio or start, or lower cap)",
        )
    risk = config.risk
    if not risk.rocking_from < risk.moderate_from < risk.high_from:
        refuse(
            "[risk] thresholds",
            (risk.rocking_from, risk.moderate_from, risk.high_from),
            "must satisfy 0 < rocking_from < moderate_from < high_from <= 1",
        )
    if not risk.sf_high_below <= risk.sf_moderate_below:
        refuse(
            "[risk] safety-factor thresholds",
            (risk.sf_high_below, risk.sf_moderate_below),
            "must satisfy 1 <= sf_high_below <= sf_moderate_below",
        )
