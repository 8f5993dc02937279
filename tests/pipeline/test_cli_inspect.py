"""``rockscreen inspect``: text and JSON views of an archive."""

from __future__ import annotations

import json

from click.testing import CliRunner

from rockscreen.pipeline.cli import main


def test_inspect_json_keys(example_archive):
    result = CliRunner().invoke(main, ["inspect", str(example_archive), "--json"])
    assert result.exit_code == 0, result.output
    document = json.loads(result.stdout)
    assert set(document) == {"metadata", "towers", "failures"}
    assert document["metadata"]["format"] == "rockscreen-archive"
    assert "config_toml" in document["metadata"]
    tower = document["towers"][0]
    for key in (
        "id",
        "theta_max_over_alpha",
        "overturned",
        "safety_factor",
        "risk_class",
        "governing_record",
        "governing_model",
    ):
        assert key in tower
    assert len(tower["governing_record"].split(".")) == 4  # NET.STA.LOC.CHA
    for tower in document["towers"]:
        if tower["safety_factor"] is None:
            assert "safety_factor_note" in tower


def test_inspect_text_shows_metadata_tree_and_summary(example_archive):
    result = CliRunner().invoke(main, ["inspect", str(example_archive)])
    assert result.exit_code == 0, result.output
    for needle in ("rockscreen_version", "tree:", "summary/", "theta_max_rad", "[rad]", "CE-SANNA"):
        assert needle in result.stdout


def test_inspect_a_missing_file_is_one_line_error(tmp_path):
    result = CliRunner().invoke(main, ["inspect", str(tmp_path / "none.h5")])
    assert result.exit_code == 1
    assert "does not exist" in result.stderr
