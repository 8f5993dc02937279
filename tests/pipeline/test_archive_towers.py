"""The archive's /towers table: every inventory column, round trip, older archives, hostile ones."""

from __future__ import annotations

import dataclasses
import math

import h5py
import numpy as np
import pytest

from rockscreen.pipeline.archive.campaign import ArchiveWriter, read_towers
from rockscreen.pipeline.archive.kinds import open_archive
from rockscreen.pipeline.archive.schema import TOWER_COLUMNS
from rockscreen.pipeline.config import CampaignConfig, ModelsConfig
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.report.html.adapters.run import run_model
from rockscreen.pipeline.screening.cases import CampaignShared, TowerTask
from rockscreen.pipeline.screening.evaluate import run_chunk
from rockscreen.stations.inventory import Tower, inventory_table
from rockscreen.stations.inventory_columns import COLUMNS, TEXT_COLUMNS
from rockscreen.stations.inventory_table import TABLE_COLUMNS

#: A tower with every inventory column given (non-ASCII text included).
FULL = Tower(
    id="T-1",
    width_m=4.0,
    height_m=30.0,
    name="Torre di Santa Maria à Paganica",
    comune="L'Aquila",
    provincia="AQ",
    lat=42.35,
    lon=13.40,
    azimuth_deg=30.0,
    depth_m=5.0,
    eta=0.9,
    tower_mass_kg=9.0e5,
    building_mass_kg=4.0e6,
    mu_s=0.6,
    mu_k=0.5,
    building_height_m=12.0,
    base_height_m=10.0,
    building_period_s=0.3,
    belfry_height_m=4.0,
    belfry_width_m=3.0,
    belfry_depth_m=3.5,
    belfry_mass_kg=2.0e4,
    bells_mass_kg=1500.0,
    bells_height_m=2.0,
    shaft_period_s=0.6,
    wall_thickness_m=1.2,
    wall_thickness_top_m=0.8,
    masonry_type="solid_brick",
    masonry_strength_mpa=4.5,
    knowledge_level="LC3",
    gable_height_m=3.0,
    gable_width_m=2.5,
    gable_thickness_m=0.5,
    gable_base_height_m=30.0,
    gable_bells_mass_kg=300.0,
    gable_opening_ratio=0.3,
    gable_axis="y",
    station="XX.A",
    nominal_life_y=50.0,
    use_class="II",
    soil_class="B",
    topography="T1",
)
#: A tower with the required columns only.
BARE = Tower(id="T-2", width_m=2.0, height_m=8.0)
#: The columns this table did not store before (an older archive lacks them).
NEW_COLUMNS = (
    "comune",
    "provincia",
    "wall_thickness_m",
    "wall_thickness_top_m",
    "masonry_type",
    "masonry_strength_mpa",
    "knowledge_level",
    "gable_height_m",
    "gable_width_m",
    "gable_thickness_m",
    "gable_base_height_m",
    "gable_bells_mass_kg",
    "gable_opening_ratio",
    "gable_axis",
)


@pytest.fixture(scope="module")
def archive(tmp_path_factory, fake_solvers, make_motion):
    """A complete run archive of FULL and BARE (ground model only: the table is the subject)."""
    path = tmp_path_factory.mktemp("towers") / "towers.h5"
    towers = [FULL, BARE]
    config = CampaignConfig(models=ModelsConfig(run=("ground",)))
    motions = {"XX.A..HN": make_motion("XX.A..HN", 4.0, 2.0, info={"files": ["a.mseed"]})}
    writer = ArchiveWriter(
        path,
        fingerprint="abc",
        metadata={
            "rockscreen_version": "test",
            "inventory_source": "towers.csv",
            "config_toml": config.to_toml(),
        },
        towers_table=inventory_table(towers),
        motions=motions,
        failures=[],
    )
    shared = CampaignShared(motions, config, fake_solvers)
    with writer:
        writer.append(
            run_chunk(shared, [TowerTask(i, t, ("XX.A..HN",)) for i, t in enumerate(towers)])
        )
    writer.finalize()
    return path


def test_the_table_has_every_column_a_tower_carries():
    fields = {field.name for field in dataclasses.fields(Tower)}
    assert fields == set(COLUMNS)
    assert [column for column, _ in TABLE_COLUMNS.values()] == list(COLUMNS)
    assert list(TOWER_COLUMNS) == list(TABLE_COLUMNS)
    assert TABLE_COLUMNS["lat_deg"] == ("lat", "deg") and "lat" not in TABLE_COLUMNS
    table = inventory_table([FULL, BARE])
    assert table.dtype.names == tuple(TABLE_COLUMNS)
    for name, (column, _) in TABLE_COLUMNS.items():
        assert table.dtype[name].kind == ("S" if column in TEXT_COLUMNS else "f"), name
    assert table["masonry_type"][0] == b"solid_brick" and table["masonry_type"][1] == b""
    assert table["gable_opening_ratio"][0] == 0.3 and math.isnan(table["gable_height_m"][1])
    assert table["depth_m"][1] == 2.0 and math.isnan(table["belfry_depth_m"][1])


def test_every_column_round_trips_through_the_archive(archive, inventory_rows):
    rows = read_towers(archive)
    assert [row["id"] for row in rows] == ["T-1", "T-2"]
    assert inventory_rows.same(rows[0], inventory_rows.expected(FULL)) and inventory_rows.same(
        rows[1], inventory_rows.expected(BARE)
    )
    assert rows[0]["comune"] == "L'Aquila" and rows[0]["masonry_strength_mpa"] == 4.5
    again = open_archive(archive).towers()
    assert len(again) == 2 and all(
        inventory_rows.same(a, b) for a, b in zip(again, rows, strict=True)
    )
    with h5py.File(archive, "r") as f:
        units = {name: f["towers"][name].attrs["units"] for name in f["towers"]}
    assert units == {name: spec[1] for name, spec in TOWER_COLUMNS.items()}
    assert units["masonry_strength_mpa"] == "MPa" and units["gable_opening_ratio"] == "1"


def test_an_older_table_without_the_new_columns_still_reads(archive, tmp_path, inventory_rows):
    path = tmp_path / "old.h5"
    path.write_bytes(archive.read_bytes())
    with h5py.File(path, "r+") as f:
        for name in NEW_COLUMNS:
            del f["towers"][name]
    reader = open_archive(path)  # the tables check passes
    rows = reader.towers()
    assert list(rows[0]) == list(TOWER_COLUMNS)
    for name in NEW_COLUMNS:
        absent = "" if TOWER_COLUMNS[name][0] == "str" else math.nan
        assert inventory_rows.same({name: rows[0][name]}, {name: absent}), name
    assert rows[0]["width_m"] == 4.0 and rows[0]["belfry_depth_m"] == 3.5
    sheet = run_model(path).sheets["T-1"]
    labels = [label for label, _ in sheet.inputs]
    assert "i_width" in labels and "i_gable_height" not in labels


def test_the_report_sheet_shows_the_stored_inputs(archive):
    inputs = dict(run_model(archive).sheets["T-1"].inputs)
    assert inputs["i_masonry_type"] == "solid_brick"
    assert inputs["i_gable_axis"] == "y"
    assert "i_gable_height" in inputs and "i_wall_thickness" in inputs
    top = inputs["i_wall_thickness_top"]  # the shaft's masonry line: the LV1 model's input
    assert (top["num"], top["unit"]) == (0.8, "m")
    assert inputs["i_belfry_height"]["num"] == 4.0 and inputs["i_bells_mass"]["num"] == 1500.0
    assert inputs["i_belfry_depth"]["num"] == 3.5 and inputs["i_shaft_period"]["unit"] == "s"
    bare = dict(run_model(archive).sheets["T-2"].inputs)
    assert "i_gable_height" not in bare and "i_masonry_type" not in bare
    assert "i_belfry_height" not in bare and "i_shaft_period" not in bare
    assert "i_wall_thickness_top" not in bare


@pytest.mark.parametrize(
    ("column", "data", "needle"),
    [
        ("masonry_type", np.zeros(2), "holds numbers where rockscreen writes text"),
        ("gable_height_m", np.array(["a", "b"], dtype=object), "holds text where"),
        ("wall_thickness_m", np.zeros(3), "rows where"),
    ],
)
def test_a_hostile_towers_column_is_refused_in_one_line(archive, tmp_path, column, data, needle):
    path = tmp_path / "hostile.h5"
    path.write_bytes(archive.read_bytes())
    with h5py.File(path, "r+") as f:
        del f["towers"][column]
        dtype = h5py.string_dtype("utf-8") if data.dtype == object else data.dtype
        f["towers"].create_dataset(column, data=data, dtype=dtype)
    for read in (open_archive, read_towers):
        with pytest.raises(ArchiveError, match=needle) as info:
            read(path)
        assert "\n" not in str(info.value) and f"towers/{column}" in str(info.value)
