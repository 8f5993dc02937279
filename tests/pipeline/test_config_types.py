"""Every configuration value is type- and bound-checked against the key table (issue 12)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from rockscreen.pipeline.config import CampaignConfig, load_config
from rockscreen.pipeline.config_schema import KEYS, TABLES, Key, key_table_markdown, toml_text
from rockscreen.pipeline.errors import ConfigError

DOCS = Path(__file__).resolve().parents[2] / "docs" / "campaign.md"


def refusal(tmp_path, text: str | bytes, name: str = "rockscreen.toml") -> str:
    """Write ``text`` as a configuration, load it, return the (one-line) refusal."""
    path = tmp_path / name
    if isinstance(text, bytes):
        path.write_bytes(text)
    else:
        path.write_text(text, encoding="utf-8")
    with pytest.raises(ConfigError) as info:
        load_config(path)
    message = str(info.value)
    assert "\n" not in message
    assert str(path) in message
    return message


def toml_of(key: Key, value: str) -> str:
    """Return a TOML document setting ``key`` to the TOML text ``value``."""
    if not key.table:
        return f"{key.name} = {value}\n"
    return f"[{key.table}]\n{key.name} = {value}\n"


# --- the reported findings ------------------------------------------------------------


def test_string_false_is_not_a_true_baseline_correction(tmp_path):
    message = refusal(tmp_path, '[processing]\nbaseline_correction = "false"\n')
    assert message == (
        f'{tmp_path / "rockscreen.toml"}: [processing] baseline_correction = "false": '
        "expected a boolean (true or false), got a string"
    )


@pytest.mark.parametrize("value", ["inf", "nan", "-inf", "1e308"])
def test_infinite_or_absurd_cap_is_refused(tmp_path, value):
    message = refusal(tmp_path, f"[safety_factor]\ncap = {value}\n")
    assert "[safety_factor] cap = " in message
    assert "must be" in message


def test_utf8_byte_order_mark_is_accepted(tmp_path):
    path = tmp_path / "c.toml"
    path.write_bytes(b"\xef\xbb\xbf[models]\nfree_motion_s = 30.0\n")
    assert load_config(path).models.free_motion_s == 30.0


def test_non_utf8_file_names_the_file_and_the_byte(tmp_path):
    message = refusal(tmp_path, b"# \xff\xfe\n[models]\nfree_motion_s = 60.0\n", "c.toml")
    assert "not UTF-8" in message
    assert "at byte 2" in message


def test_non_utf8_after_a_bom_counts_bytes_in_the_file(tmp_path):
    message = refusal(tmp_path, b"\xef\xbb\xbf# \xff\n", "c.toml")
    assert "at byte 5" in message


def test_unknown_key_keeps_the_allowed_list_and_suggests(tmp_path):
    message = refusal(tmp_path, "[models]\nrunn = ['ground']\n")
    assert "unknown key 'runn' in [models]; allowed: run, free_motion_s" in message
    assert "did you mean 'run'?" in message


# --- the siblings: every key of every table --------------------------------------------

_WRONG_TYPE = {
    "bool": ['"false"', "1", "0.0", "[true]"],
    "int": ["4.5", "4.0", '"4"', "true", "[4]"],
    "float": ['"0.1"', "true", "[1.0]", "{a = 1}", "1979-05-27"],
    "path": ["5", "true", '["a.csv"]'],
    "choice": ["1", "false", '["none"]'],
    "choices": ['"ground"', "1", "[1, 2]", '["ground", 1]', '[["ground"]]'],
}


@pytest.mark.parametrize(
    ("key", "value"),
    [(key, value) for key in KEYS for value in _WRONG_TYPE[key.kind]],
    ids=lambda v: v.where if isinstance(v, Key) else v,
)
def test_every_key_refuses_a_value_of_the_wrong_type(tmp_path, key, value):
    message = refusal(tmp_path, toml_of(key, value))
    assert f"{key.where} = " in message
    assert ": expected " in message
    assert ", got " in message


@pytest.mark.parametrize("key", [k for k in KEYS if k.kind == "float"], ids=lambda k: k.where)
@pytest.mark.parametrize("value", ["nan", "inf", "-inf"])
def test_every_number_must_be_finite(tmp_path, key, value):
    message = refusal(tmp_path, toml_of(key, value))
    assert f"{key.where} = {value}: must be a finite number" in message


def _outside(key: Key) -> list[str]:
    values = []
    if key.low is not None:
        values.append(key.low if key.low_open else key.low - (1 if key.kind == "int" else 1e-3))
        values.append(-1)
    if key.high is not None:
        values.append(key.high if key.high_open else key.high * 10 + 1)
    if key.kind == "int":
        return [str(int(v)) for v in values]
    return [repr(float(v)) for v in values]


@pytest.mark.parametrize(
    ("key", "value"),
    [(key, value) for key in KEYS for value in _outside(key)],
    ids=lambda v: v.where if isinstance(v, Key) else v,
)
def test_every_bounded_key_refuses_values_outside_its_bounds(tmp_path, key, value):
    message = refusal(tmp_path, toml_of(key, value))
    assert f"{key.where} = {value}: must be {key.bounds_text()}" in message


def test_every_number_bound_is_documented_and_the_positive_ones_refuse_zero():
    positive = {"freqmin_hz", "freqmax_hz", "resample_hz", "max_distance_km", "free_motion_s"}
    for key in KEYS:
        if key.kind in ("int", "float"):
            assert key.low is not None, key.where
        if key.name in positive:
            assert (key.low, key.low_open) == (0.0, True), key.where


@pytest.mark.parametrize(
    ("text", "needle"),
    [
        # Reported: the string "no" does not leave quality checks on; a string where a
        # number is needed is refused in one line.
        (
            "[processing]\ncheck_quality = 'no'\n",
            '[processing] check_quality = "no": expected a boolean (true or false)',
        ),
        (
            "[processing]\nfreqmin_hz = '0.1'\n",
            '[processing] freqmin_hz = "0.1": expected a number, got a string',
        ),
        ("models = 5\n", "models = 5: expected a table ([models]), got an integer"),
        ("processing = [1]\n", "processing = [1]: expected a table ([processing]), got an array"),
        ("[processing]\nquality = 5\n", "[processing] quality = 5: expected a table"),
        ("inventory = 5\n", "inventory = 5: expected a path (a string), got an integer"),
        ("[risk]\nhigh_from = {a = 1}\n", "[risk] high_from = {a = 1}: expected a number"),
        ("[models]\nrun = []\n", "[models] run = []: must name at least one model"),
        ("[models]\nrun = 'ground'\n", "expected an array of strings"),
        ("[models]\nrun = 1\n", "[models] run = 1: expected an array of strings"),
        ("[models]\nrun = [1, 2]\n", "got an array holding an integer (1)"),
        ("[models]\nrun = ['ground', 'ground']\n", "names a model twice"),
        ("[output]\nhistories = 'all'\n", 'must be one of "none", "decimated", "full"'),
        ("[output]\nhistories = false\n", "expected a string, one of"),
        ("[processing]\ndetrend = 'foo'\n", '[processing] detrend = "foo": must be one of'),
        ("[processing]\nfilter_order = 4.5\n", "expected an integer, got a float"),
        ("[processing.quality]\nclip_run = '5'\n", '[processing.quality] clip_run = "5"'),
        ("[processing.quality]\nmin_rate = 1\n", "unknown key 'min_rate' in [processing.quality]"),
        ("[safety_factor]\ntolerance = 0.3\n", "must be in (0, ratio - 1 = 0.2)"),
        ("[safety_factor]\nstart = 1.0\ncap = 1.0\n", "must exceed start=1.0"),
        ("[safety_factor]\nratio = 1.000001\ntolerance = 1e-7\n", "at most 500"),
        ("[models]\nfree_motion_s = 1e9\n", "[models] free_motion_s = 1000000000.0: must be"),
        ("[processing]\nresample_hz = 100000\n", "resample_hz = 100000.0: must be > 0 and <="),
        ("[output]\nhistory_points = 1000000000000\n", "must be >= 10 and <= 1000000"),
        ("[risk]\nmoderate_from = 0.6\n", "rocking_from < moderate_from < high_from"),
        ("[risk]\nsf_high_below = 3.0\n", "sf_high_below <= sf_moderate_below"),
    ],
)
def test_tables_arrays_and_rules_between_keys(tmp_path, text, needle):
    assert needle in refusal(tmp_path, text)


def test_an_integer_is_accepted_where_a_number_is_expected(tmp_path):
    path = tmp_path / "c.toml"
    path.write_text("[pairing]\nmax_distance_km = 30\n[processing]\nfreqmax_hz = 15\n")
    config = load_config(path)
    assert config.pairing.max_distance_km == 30.0
    assert isinstance(config.pairing.max_distance_km, float)
    assert config.processing["freqmax_hz"] == 15.0


def test_true_booleans_still_work(tmp_path):
    path = tmp_path / "c.toml"
    path.write_text("[processing]\nbaseline_correction = true\ncheck_quality = false\n")
    assert load_config(path).processing == {"baseline_correction": True, "check_quality": False}


# --- one table for validation and documentation ----------------------------------------


def _defaults() -> dict[tuple[str, str], object]:
    from rockscreen.pipeline.processing.steps import ProcessingConfig
    from rockscreen.pipeline.records.quality import QualityLimits

    config = CampaignConfig()
    found: dict[tuple[str, str], object] = {("", "inventory"): "", ("", "stations"): ""}
    instances = {"processing": ProcessingConfig(), "processing.quality": QualityLimits()}
    sections = [name for name in TABLES if name and not name.startswith("processing")]
    instances.update({name: getattr(config, name) for name in sections})
    for table, instance in instances.items():
        for fld in dataclasses.fields(instance):
            if fld.name != "quality":
                found[(table, fld.name)] = getattr(instance, fld.name)
    return found


def test_the_key_table_names_every_field_with_its_default():
    specs = {(key.table, key.name): key.default for key in KEYS}
    assert specs == _defaults()


def test_docs_hold_the_generated_key_table():
    docs = DOCS.read_text(encoding="utf-8")
    assert key_table_markdown() in docs
    for key in KEYS:
        default = "absent (off)" if key.default is None else f"`{toml_text(key.default)}`"
        assert f"| `{key.where}` |" in docs
        row = next(line for line in docs.splitlines() if line.startswith(f"| `{key.where}` |"))
        assert default in row
