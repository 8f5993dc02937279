"""Every archive reader refuses a crafted file that reads outside itself (issue 12, class)."""

from __future__ import annotations

import h5py
import pytest
from click.testing import CliRunner

from rockscreen.pipeline.cli import main


def _secret(tmp_path):
    secret = tmp_path / "secret.txt"
    secret.write_bytes(b"root:x:0:0:SECRET-LINE" + b"\0" * 64)
    return secret


def _craft(archive, secret):
    """Replace /summary/name with external raw storage pointing at a local file."""
    with h5py.File(archive, "r+") as f:
        n = len(f["summary/id"])
        del f["summary/name"]
        f.create_dataset("summary/name", shape=(n,), dtype="S8", external=[(str(secret), 0, n * 8)])


@pytest.fixture(scope="module")
def run_archive(tmp_path_factory):
    folder = tmp_path_factory.mktemp("run")
    with pytest.MonkeyPatch.context() as mp:
        mp.chdir(folder)
        result = CliRunner().invoke(main, ["run", "--example", "--jobs", "1", "-q"])
    assert result.exit_code == 0, result.output
    return folder / "rockscreen-example.h5"


@pytest.mark.parametrize(
    "command",
    [
        ["inspect", "--json"],
        ["export", "--csv", "x.csv"],
        ["report", "--out", "x.html"],
        ["plot", "--map", "--out", "x.png"],
    ],
)
def test_commands_refuse_external_storage(run_archive, tmp_path, monkeypatch, command):
    monkeypatch.chdir(tmp_path)
    crafted = tmp_path / "crafted.h5"
    crafted.write_bytes(run_archive.read_bytes())
    _craft(crafted, _secret(tmp_path))
    result = CliRunner().invoke(main, [command[0], str(crafted), *command[1:]])
    assert result.exit_code == 1
    assert "external" in result.stderr and "SECRET" not in result.stdout + result.stderr
    assert not any((tmp_path / name).exists() for name in ("x.csv", "x.html", "x.png"))


def test_risk_and_sweep_readers_refuse_external_links(tmp_path):
    from rockscreen.pipeline.archive.risk_archive import write_risk_archive
    from rockscreen.pipeline.archive.risk_reader import read_summary as read_risk_summary
    from rockscreen.pipeline.errors import ArchiveError

    path = tmp_path / "assess.h5"
    write_risk_archive(path, "assess", {"summary": [{"id": "T1", "note": ""}]}, {})
    other = tmp_path / "other.h5"
    with h5py.File(other, "w") as f:
        f["x"] = [1.0]
    with h5py.File(path, "r+") as f:
        f["leak"] = h5py.ExternalLink(str(other), "/x")
    with pytest.raises(ArchiveError, match="external link"):
        read_risk_summary(path)


def test_a_number_column_stored_as_text_is_one_line(run_archive, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    crafted = tmp_path / "sf_text.h5"
    crafted.write_bytes(run_archive.read_bytes())
    with h5py.File(crafted, "r+") as f:
        n = len(f["summary/id"])
        del f["summary/safety_factor"]
        f.create_dataset("summary/safety_factor", data=["x"] * n, dtype=h5py.string_dtype())
    for command in (["plot", "--tower", "ARC-08", "--out", "t.png"], ["inspect"]):
        result = CliRunner().invoke(main, [command[0], str(crafted), *command[1:]])
        assert result.exit_code == 1, result.output
        assert "safety_factor" in result.stderr and "Traceback" not in result.stderr
