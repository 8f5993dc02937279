"""The assess archive keeps the inventory as read (/inventory): round trip, sheet, older, hostile.

An assess archive kept only its verdicts and a few identity columns: not the shaft's
masonry, the belfry's or the bell gable's columns its verdicts were computed from. It now
stores the inventory with the run archive's columns and units; an archive written before
reads and renders as it did, and a hostile ``/inventory`` is refused in one line.
"""

from __future__ import annotations

import math
from functools import partial

import h5py
import numpy as np
import pytest
from click.testing import CliRunner

from rockscreen.pipeline.archive import risk_reader
from rockscreen.pipeline.archive.kinds import open_archive
from rockscreen.pipeline.archive.risk_archive import write_risk_archive
from rockscreen.pipeline.archive.risk_reader import read_inventory
from rockscreen.pipeline.archive.risk_schema import assess_tables
from rockscreen.pipeline.archive.schema import TOWER_COLUMNS
from rockscreen.pipeline.cli import main
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.report.html.adapters.risk import risk_archive_model
from rockscreen.pipeline.risk.assess.batch import AssessInputs, assess_to_archive
from rockscreen.pipeline.risk.assess.run import AssessOptions
from rockscreen.stations.inventory import Tower, inventory_table

from rockscreen_testsupport.cli import run_rockscreen
from rockscreen_testsupport.records import suite_record

CERVINO = (41.04, 14.42)  # lat, lon [deg]
#: A squat tower with the shaft's masonry (LV1), a belfry and a bell gable, in a comune.
VELA = Tower(
    id="VELA",
    width_m=4.0,
    height_m=6.0,
    name="Torre con vela à Cervinara",
    comune="Cervinara",
    provincia="AV",
    lat=CERVINO[0],
    lon=CERVINO[1],
    wall_thickness_m=1.0,
    wall_thickness_top_m=0.6,
    masonry_type="rubble",
    knowledge_level="LC1",
    belfry_height_m=2.5,
    belfry_width_m=1.5,
    belfry_mass_kg=2.0e4,
    bells_mass_kg=500.0,
    bells_height_m=1.5,
    gable_height_m=1.5,
    gable_width_m=2.0,
    gable_thickness_m=0.5,
    gable_base_height_m=6.0,
    gable_bells_mass_kg=200.0,
    gable_opening_ratio=0.3,
    gable_axis="y",
)
#: A tower with the required columns only.
BARE = Tower(id="BARE", width_m=4.0, height_m=6.0, lat=CERVINO[0], lon=CERVINO[1])


_record = partial(
    suite_record,
    seed_base=100,
    n_samples=1000,
    frequency_hz=(2.0, 0.4),
    envelope_duration_s=6.0,
    name="R-{i}",
)


@pytest.fixture(scope="module")
def archive(tmp_path_factory):
    """An assess archive of VELA and BARE (four records, basis not compliant: a quick one)."""
    folder = tmp_path_factory.mktemp("assess-inventory")
    path = folder / "a.h5"
    options = AssessOptions(
        return_periods_y=(475.0,),
        selection={"n_records": 4},
        allow_noncompliant=True,
        bootstrap_resamples=0,
    )
    suite = [_record(i) for i in range(4)]
    assess_to_archive(
        [VELA, BARE],
        options,
        path,
        AssessInputs(inventory=folder / "towers.csv", suite=suite, suite_label="test"),
        jobs=1,
    )
    return path


def test_the_inventory_round_trips_with_the_run_archives_units(archive, inventory_rows):
    rows = read_inventory(archive)
    assert [row["id"] for row in rows] == ["VELA", "BARE"]
    assert inventory_rows.same(rows[0], inventory_rows.expected(VELA)) and inventory_rows.same(
        rows[1], inventory_rows.expected(BARE)
    )
    assert rows[0]["masonry_type"] == "rubble" and rows[0]["gable_axis"] == "y"
    assert rows[0]["knowledge_level"] == "LC1" and rows[0]["comune"] == "Cervinara"
    assert math.isnan(rows[1]["gable_height_m"]) and rows[1]["masonry_type"] == ""
    again = open_archive(archive).inventory()
    assert all(inventory_rows.same(a, b) for a, b in zip(again, rows, strict=True))
    with h5py.File(archive, "r") as f:
        assert "towers" not in f  # /towers is the work file's: not reused
        units = {name: f["inventory"][name].attrs["units"] for name in f["inventory"]}
    assert units == {name: spec[1] for name, spec in TOWER_COLUMNS.items()}
    assert units == assess_tables()["inventory"]
    assert units["masonry_strength_mpa"] == "MPa" and units["gable_opening_ratio"] == "1"


def test_the_assess_sheet_shows_the_stored_inputs(archive):
    model = risk_archive_model(archive, "assess")
    inputs = dict(model.sheets["VELA"].inputs)
    assert inputs["i_comune"] == "Cervinara" and inputs["i_provincia"] == "AV"
    assert inputs["i_masonry_type"] == "rubble" and inputs["i_knowledge_level"] == "LC1"
    assert inputs["i_gable_axis"] == "y"
    assert inputs["i_gable_height"]["num"] == 1.5 and inputs["i_gable_height"]["unit"] == "m"
    assert inputs["i_wall_thickness"]["num"] == 1.0
    assert inputs["i_wall_thickness_top"]["num"] == 0.6
    assert inputs["i_belfry_height"]["num"] == 2.5 and inputs["i_bells_mass"]["unit"] == "kg"
    assert inputs["i_width"]["num"] == 4.0
    bare = dict(model.sheets["BARE"].inputs)
    for label in (
        "i_gable_height",
        "i_masonry_type",
        "i_wall_thickness_top",
        "i_belfry_height",
        "i_comune",
        "i_knowledge_level",  # the level assessed (the default), not given
    ):
        assert label not in bare, label
    assert bare["i_soil"] == inputs["i_soil"]  # the site's, as assessed


def test_the_sheet_labels_are_in_english_and_italian():
    import json
    from importlib import resources

    strings = json.loads(
        resources.files("rockscreen.pipeline.report.html")
        .joinpath("assets/strings.json")
        .read_text("utf-8")
    )
    from rockscreen.pipeline.report.html.adapters.common import TOWER_INPUTS

    for label, _ in TOWER_INPUTS.values():
        assert strings[label]["en"] and strings[label]["it"], label


def _older(archive, tmp_path):
    path = tmp_path / "older.h5"
    path.write_bytes(archive.read_bytes())
    with h5py.File(path, "r+") as f:
        del f["inventory"]
    return path


def test_an_older_archive_without_the_inventory_reads_and_renders(archive, tmp_path):
    path = _older(archive, tmp_path)
    reader = open_archive(path)
    assert reader.inventory() == [] and [r["id"] for r in reader.summary()] == ["VELA", "BARE"]
    assert risk_reader.read_summary(path, "assess")[0]["id"] == "VELA"  # what scenario reads
    inputs = dict(risk_archive_model(path, "assess").sheets["VELA"].inputs)
    assert inputs["i_comune"] == "Cervinara"  # the summary's identity columns
    assert "i_gable_height" not in inputs and "i_width" not in inputs
    assert "i_knowledge_level" not in inputs  # the summary's is the level assessed
    runner = CliRunner()
    for args in (
        ["inspect", str(path)],
        ["inspect", "--json", str(path)],
        ["report", str(path), "--out", str(tmp_path / "r.html")],
        ["export", str(path), "--csv", str(tmp_path / "o.csv")],
    ):
        result = runner.invoke(main, args)
        assert result.exit_code == 0, (args, result.output)
    assert (tmp_path / "r.html").is_file() and (tmp_path / "o.csv").is_file()


def _replace(f, name, data):
    del f[name]
    dtype = h5py.string_dtype("utf-8") if np.asarray(data).dtype == object else None
    f.create_dataset(name, data=data, dtype=dtype)


HOSTILE = {
    "text as numbers": (
        lambda f, secret: _replace(f, "inventory/masonry_type", np.zeros(2)),
        "/inventory/masonry_type holds numbers where rockscreen writes text",
    ),
    "flags as text": (
        lambda f, secret: _replace(f, "inventory/gable_axis", np.array([True, False])),
        "/inventory/gable_axis holds flags where rockscreen writes text",
    ),
    "numbers as text": (
        lambda f, secret: _replace(
            f, "inventory/gable_height_m", np.array(["a", "b"], dtype=object)
        ),
        "/inventory/gable_height_m holds text where rockscreen writes numbers",
    ),
    "short column": (
        lambda f, secret: _replace(f, "inventory/wall_thickness_m", np.zeros(3)),
        "/inventory/wall_thickness_m has 3 rows where",
    ),
    "no id": (lambda f, secret: f.__delitem__("inventory/id"), "/inventory lacks column(s) id"),
    "a dataset": (
        lambda f, secret: (f.__delitem__("inventory"), f.create_dataset("inventory", data=[1.0])),
        "/inventory is a dataset",
    ),
    "latitude": (
        lambda f, secret: f["inventory/lat_deg"].__setitem__(0, 91.0),
        "/inventory/lat_deg row 0 holds 91.0, outside [-90, 90]",
    ),
    "external storage": (
        lambda f, secret: (
            f.__delitem__("inventory/name"),
            f.create_dataset("inventory/name", shape=(2,), dtype="S8", external=[(secret, 0, 16)]),
        ),
        "stores its data in external files",
    ),
    "external link": (
        lambda f, secret: f["inventory"].__setitem__(
            "extra", h5py.ExternalLink("/etc/passwd", "/")
        ),
        "external link",
    ),
}


@pytest.mark.parametrize("name", list(HOSTILE))
def test_a_hostile_inventory_is_refused_in_one_line(archive, tmp_path, name):
    craft, needle = HOSTILE[name]
    secret = tmp_path / "secret.txt"  # a local file the crafted storage points at
    secret.write_bytes(b"SECRET-LINE" + b"\0" * 64)
    path = tmp_path / "hostile.h5"
    path.write_bytes(archive.read_bytes())
    with h5py.File(path, "r+") as f:
        craft(f, str(secret))
    for read in (open_archive, read_inventory, risk_reader.read_summary):
        with pytest.raises(ArchiveError) as info:
            read(path)
        message = str(info.value)
        assert "\n" not in message and needle in message, (read, message)
        assert "SECRET" not in message
    with pytest.raises(ArchiveError, match="refused|holds|rows where|lacks|is a dataset"):
        risk_archive_model(path, "assess")


def test_every_command_refuses_a_hostile_inventory_in_one_line(archive, tmp_path):
    path = tmp_path / "hostile.h5"
    path.write_bytes(archive.read_bytes())
    with h5py.File(path, "r+") as f:
        _replace(f, "inventory/masonry_type", np.zeros(2))
    for command in (["inspect"], ["report", "--out", "r.html"], ["export", "--csv", "o.csv"]):
        proc = run_rockscreen(command[0], path, *command[1:], cwd=tmp_path, timeout_s=120)
        lines = proc.stderr.strip().splitlines()
        assert proc.returncode == 1 and len(lines) == 1, proc.stderr
        assert "/inventory/masonry_type holds numbers" in lines[0]


def test_only_an_assess_archive_keeps_an_inventory(tmp_path):
    with pytest.raises(ArchiveError, match="a scenario archive keeps no inventory"):
        write_risk_archive(
            tmp_path / "s.h5",
            "scenario",
            {"summary": [{"id": "T1"}]},
            {},
            inventory=inventory_table([BARE]),
        )
    assert not (tmp_path / "s.h5").exists()
