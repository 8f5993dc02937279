"""Campaign configuration: defaults, files, unknown keys, bad values, TOML round trip."""

from __future__ import annotations

import pytest

from rockscreen.pipeline.config import CampaignConfig, config_from_mapping, load_config
from rockscreen.pipeline.errors import ConfigError


def test_defaults_when_no_file(tmp_path):
    config = load_config(cwd=tmp_path)
    assert config == CampaignConfig()
    assert config.output.histories == "decimated"
    assert config.output.history_points <= 2000
    assert config.safety_factor.cap == 10.0
    assert config.safety_factor.tolerance == 0.01
    assert config.pairing.max_distance_km == 50.0
    assert config.models.run == ("ground", "floor", "double", "belfry", "gable")


def test_rockscreen_toml_in_cwd_is_read_and_names_the_inventory(tmp_path):
    (tmp_path / "rockscreen.toml").write_text(
        'inventory = "towers/region.csv"\n[output]\nhistories = "none"\n'
    )
    config = load_config(cwd=tmp_path)
    assert config.output.histories == "none"
    assert config.inventory == str(tmp_path / "towers" / "region.csv")


@pytest.mark.parametrize(
    ("text", "needle"),
    [
        ("colour = 1\n", "unknown key 'colour' in top level; allowed: inventory, stations"),
        ("[output]\nhistory = 'full'\n", "unknown key 'history' in [output]; allowed: histories"),
        ("[processing]\nlowcut = 0.1\n", "unknown key 'lowcut' in [processing]"),
        ("[output]\nhistories = 'some'\n", "histories='some'"),
        ("[safety_factor]\nratio = 1.0\n", "must be > 1"),
        ("[models]\nrun = ['tower']\n", "may only name ground, floor, double"),
        ("[pairing]\nmax_distance_km = 'far'\n", "must be of type float"),
        ("[processing]\nfreqmin_hz = 30.0\nfreqmax_hz = 20.0\n", "freqmin_hz=30.0"),
        ("[output\n", "not valid TOML"),
    ],
)
def test_bad_configuration_is_refused_with_the_key(tmp_path, text, needle):
    path = tmp_path / "c.toml"
    path.write_text(text)
    with pytest.raises(ConfigError) as info:
        load_config(path)
    assert needle in str(info.value)


def test_missing_file_is_a_config_error(tmp_path):
    with pytest.raises(ConfigError, match="does not exist"):
        load_config(tmp_path / "absent.toml")


def test_resolved_toml_round_trips_and_fingerprints_differ():
    from rockscreen.pipeline.config_schema import tomllib

    config = config_from_mapping(
        {
            "processing": {"freqmin_hz": 0.2, "quality": {"min_duration_s": 1.0}},
            "risk": {"high_from": 0.6},
        }
    )
    again = config_from_mapping(tomllib.loads(config.to_toml()))
    assert again.to_toml() == config.to_toml()
    assert config.fingerprint() != CampaignConfig().fingerprint()
