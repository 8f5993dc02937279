"""Issue 24: the inputs users have -- several StationXML files (repeated ``--stations``, a
folder of StationXML, a quoted glob) and several record folders (repeated ``--suite``).

The command line runs as a real subprocess; each variant must give the very table that
the same records and metadata in one file or one folder give.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from obspy import read_inventory

from rockscreen.pipeline.archive.campaign import read_metadata
from rockscreen.pipeline.motion.synthetic import write_example_records
from rockscreen.stations.errors import StationMetadataError
from rockscreen.stations.inventory import example_inventory_path
from rockscreen.stations.stationxml import read_station_metadata

from rockscreen_testsupport.cli import run_rockscreen

STATIONS = ("SYN1", "SYN2", "SYN3")


@pytest.fixture
def split(tmp_path):
    """The example records in ``rec/`` and their StationXML in ``all.xml`` and, one file per
    station, in ``meta/``; the example inventory's first three towers in ``towers.csv``."""
    paths, xml = write_example_records(tmp_path / "example")
    (tmp_path / "rec").mkdir()
    for path in paths:
        shutil.copy(path, tmp_path / "rec")
    shutil.copy(xml, tmp_path / "all.xml")
    (tmp_path / "meta").mkdir()
    inventory = read_inventory(str(xml))
    for code in STATIONS:
        inventory.select(station=code).write(
            str(tmp_path / "meta" / f"{code}.xml"), format="STATIONXML"
        )
    lines = example_inventory_path().read_text().splitlines()
    (tmp_path / "towers.csv").write_text("\n".join(lines[:4]) + "\n")
    return tmp_path


@pytest.mark.parametrize(
    "stations",
    [
        [
            "--stations",
            "meta/SYN1.xml",
            "--stations",
            "meta/SYN2.xml",
            "--stations",
            "meta/SYN3.xml",
        ],
        ["--stations", "meta"],
        ["--stations", "meta/*.xml"],
    ],
    ids=["repeated", "folder", "glob"],
)
def test_several_stationxml_files_are_merged(split, stations):
    base = ["run", "rec", "--towers", "towers.csv", "--jobs", "1"]
    reference = run_rockscreen(*base, "--stations", "all.xml", "--out", "ref.h5", cwd=split)
    assert reference.returncode == 0, reference.stderr
    merged = run_rockscreen(*base, *stations, "--out", "merged.h5", cwd=split)
    assert merged.returncode == 0, merged.stderr
    assert merged.stdout == reference.stdout
    assert "WARNING" not in merged.stderr and "skipped" not in merged.stderr.replace(
        "0 inputs skipped", ""
    )
    source = read_metadata(split / "merged.h5")["stations_source"]
    assert [Path(p).name for p in source.split(", ")] == [f"{s}.xml" for s in STATIONS]


def test_a_missing_stationxml_or_an_empty_pattern_is_one_line(split):
    base = ["run", "rec", "--towers", "towers.csv", "--stations", "meta/SYN1.xml"]
    for extra, needle in (
        (["--stations", "nope.xml"], "station metadata 'nope.xml': no such file"),
        (["--stations", "meta/*.stationxml"], "no file matches this pattern"),
        (["--stations", "rec"], "holds no StationXML file"),
    ):
        done = run_rockscreen(*base, *extra, cwd=split)
        lines = done.stderr.strip().splitlines()
        assert done.returncode == 1 and len(lines) == 1, done.stderr
        assert lines[0].startswith("rockscreen: error: ") and needle in lines[0]


def test_one_station_at_two_places_is_refused(split):
    moved = split / "moved.xml"
    inventory = read_inventory(str(split / "meta" / "SYN1.xml"))
    station = inventory[0][0]
    station.latitude = float(station.latitude) + 0.5
    inventory.write(str(moved), format="STATIONXML")
    with pytest.raises(StationMetadataError, match=r"station XX\.SYN1 is at lat .* give one"):
        read_station_metadata([split / "meta" / "SYN1.xml", moved])


def test_repeated_suite_folders_are_one_suite(split):
    for name, codes in (("A", STATIONS[:2]), ("B", STATIONS[2:])):
        folder = split / name
        folder.mkdir()
        for code in codes:
            for path in (split / "rec").glob(f"XX.{code}..*"):
                shutil.copy(path, folder)
        shutil.copy(split / "all.xml", folder / "stations.xml")
    shutil.copytree(split / "rec", split / "together")
    shutil.copy(split / "all.xml", split / "together" / "stations.xml")
    (split / "one.csv").write_text(
        "id,name,lat,lon,width_m,height_m\nT1,one,41.04,14.42,2.06,5.8\n"
    )
    base = ["assess", "--towers", "one.csv", "--return-periods", "475", "--bootstrap", "0"]
    base += ["--models", "ground", "--jobs", "1", "--records", "3", "--allow-noncompliant"]
    together = run_rockscreen(*base, "--suite", "together", "--out", "t.h5", cwd=split)
    assert together.returncode == 0, together.stderr
    repeated = run_rockscreen(*base, "--suite", "A", "--suite", "B", "--out", "ab.h5", cwd=split)
    assert repeated.returncode == 0, repeated.stderr
    assert repeated.stdout == together.stdout
