"""One door to every archive (issue 21): open_archive, the kind registry, faces without kinds."""

from __future__ import annotations

import ast
import importlib
from pathlib import Path

import h5py
import pytest

from rockscreen.pipeline.archive import risk_archive, sweep_archive
from rockscreen.pipeline.archive.kinds import (
    ARCHIVE_KINDS,
    ArchiveReader,
    AssessReader,
    RunReader,
    ScenarioReader,
    SweepReader,
    archive_kind,
    open_archive,
)
from rockscreen.pipeline.archive.schema import FORMAT
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.report.presenters import COMMANDS, PRESENTERS, face

PIPELINE = Path(__file__).resolve().parents[2] / "pipeline"


def _h5(path: Path, **attrs) -> Path:
    with h5py.File(path, "w") as f:
        for key, value in attrs.items():
            f.attrs[key] = value
        f.create_group("summary").create_dataset("id", shape=(0,), dtype=h5py.string_dtype())
    return path


def _risk(path: Path, kind: str) -> Path:
    summary = [{"id": "T1", "name": "one", "lat_deg": 41.0, "lon_deg": 14.0, "note": ""}]
    return risk_archive.write_risk_archive(path, kind, {"summary": summary}, {})


def test_each_kind_opens_as_its_reader(tmp_path):
    cases = {
        RunReader: _h5(tmp_path / "run.h5", format=FORMAT, format_version="2"),
        SweepReader: _h5(tmp_path / "sweep.h5", format=FORMAT, kind="sweep", format_version="2"),
        AssessReader: _risk(tmp_path / "assess.h5", "assess"),
        ScenarioReader: _risk(tmp_path / "scenario.h5", "scenario"),
    }
    for cls, path in cases.items():
        reader = open_archive(path)
        assert type(reader) is cls
        assert reader.path == path and reader.kind == archive_kind(path)
        assert reader.attrs["format_version"] in cls.versions
    legacy = _h5(tmp_path / "v1.h5", kind="rockscreen-sweep", format_version=1)
    assert type(open_archive(legacy)) is SweepReader


def test_the_registry_covers_every_kind_the_writers_produce():
    written = {"run", sweep_archive.ARCHIVE_KIND, *risk_archive.KINDS}
    assert set(ARCHIVE_KINDS) == written
    assert set(PRESENTERS) == set(ARCHIVE_KINDS)
    for kind, cls in ARCHIVE_KINDS.items():
        assert issubclass(cls, ArchiveReader) and cls.kind == kind
        assert cls.versions and cls.stored_kinds and cls.schema
        for table, units in cls.schema.items():
            assert units, f"{kind}: table {table} declares no columns"
    stored = [key for cls in ARCHIVE_KINDS.values() for key in cls.stored_kinds]
    assert len(stored) == len(set(stored)), "one root kind attribute, one reader"


def test_every_presenter_function_resolves():
    for kind, presenter in PRESENTERS.items():
        for command in COMMANDS:
            target = getattr(presenter, command)
            if target is None:
                continue
            module, name = target.split(":")
            assert callable(getattr(importlib.import_module(module), name)), (kind, command)


def test_a_face_a_kind_lacks_is_one_line(tmp_path):
    reader = open_archive(
        _h5(tmp_path / "sweep.h5", format=FORMAT, kind="sweep", format_version="2")
    )
    with pytest.raises(ArchiveError, match="rockscreen inspect does not read sweep archives") as e:
        face(reader, "inspect")
    assert "\n" not in str(e.value) and "run, assess, scenario" in str(e.value)


@pytest.mark.parametrize(
    ("attrs", "needle"),
    [
        ({"format": FORMAT, "kind": "tide-gauge", "format_version": "2"}, "kind 'tide-gauge'"),
        ({"format": FORMAT, "kind": "assess", "format_version": "9"}, "format_version '9'"),
        ({"format": FORMAT, "format_version": "7"}, "run archive format_version '7'"),
        ({"format": "other-tool"}, "not a rockscreen archive"),
        ({}, "format attribute: none"),
    ],
)
def test_unknown_kind_or_version_is_one_clear_line(tmp_path, attrs, needle):
    path = _h5(tmp_path / "x.h5", **attrs)
    with pytest.raises(ArchiveError, match=needle) as info:
        open_archive(path)
    message = str(info.value)
    assert "\n" not in message and str(path) in message
    if "kind" in needle or "version" in needle:
        assert "this rockscreen reads" in message


def test_not_hdf5_missing_and_external_links_are_one_line(tmp_path):
    text = tmp_path / "notes.h5"
    text.write_text("my notes")
    with pytest.raises(ArchiveError, match="is not a readable HDF5 file"):
        open_archive(text)
    with pytest.raises(ArchiveError, match="does not exist"):
        open_archive(tmp_path / "absent.h5")
    path = _risk(tmp_path / "assess.h5", "assess")
    other = _h5(tmp_path / "other.h5")
    with h5py.File(path, "r+") as f:
        f["leak"] = h5py.ExternalLink(str(other), "/summary")
    with pytest.raises(ArchiveError, match="external link"):
        open_archive(path)


def test_risk_units_are_declared_not_inferred(tmp_path):
    assert risk_archive.units_of("assess", "stripes", "n_damage_0p2") == "1"
    assert risk_archive.units_of("scenario", "summary", "event_pga_g") == "9.81 m/s2"
    with pytest.raises(ArchiveError, match="no declared units"):
        risk_archive.write_risk_archive(
            tmp_path / "x.h5", "assess", {"summary": [{"id": "T", "depth_m": 1.0}]}, {}
        )


KIND_NAMES = set(ARCHIVE_KINDS) | {"campaign", "rockscreen-sweep"}
FACES = [*sorted((PIPELINE / "cli").glob("*.py")), PIPELINE / "report/html/adapters/__init__.py"]


def _kind_comparisons(path: Path) -> list[str]:
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if not isinstance(node, ast.Compare):
            continue
        for operand in [node.left, *node.comparators]:
            values = (
                operand.elts if isinstance(operand, (ast.Tuple, ast.List, ast.Set)) else [operand]
            )
            for value in values:
                if isinstance(value, ast.Constant) and value.value in KIND_NAMES:
                    found.append(f"{path.name}:{node.lineno}: {value.value!r}")
    return found


@pytest.mark.parametrize("path", FACES, ids=lambda p: p.name)
def test_faces_never_compare_archive_kinds(path):
    assert not _kind_comparisons(path)
    assert "archive_kind(" not in path.read_text(encoding="utf-8")


def test_one_archive_kind_function():
    defined = [
        path.relative_to(PIPELINE).as_posix()
        for path in PIPELINE.rglob("*.py")
        if "def archive_kind(" in path.read_text(encoding="utf-8")
    ]
    assert defined == ["archive/kinds.py"]
