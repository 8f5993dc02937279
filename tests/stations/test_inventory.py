"""Tower inventory CSV: reading, every validation rule, the embedded example, the table."""

from __future__ import annotations

import math
from dataclasses import fields, replace

import numpy as np
import pytest

from rockscreen.solver.constants import G
from rockscreen.stations.errors import InventoryError, RockscreenError
from rockscreen.stations.inventory import (
    COLUMNS,
    REQUIRED_COLUMNS,
    Tower,
    example_inventory_path,
    inventory_table,
    read_inventory,
    write_inventory,
)

HEADER = "id,width_m,height_m"


def write(tmp_path, text, name="towers.csv", encoding="utf-8"):
    path = tmp_path / name
    path.write_text(text, encoding=encoding)
    return path


def refused(tmp_path, text) -> str:
    """Read an inventory that must be refused; return the message."""
    path = write(tmp_path, text)
    with pytest.raises(InventoryError) as info:
        read_inventory(path)
    message = str(info.value)
    assert "towers.csv" in message  # every message names the file
    return message


def test_minimal_inventory_reads_with_defaults(tmp_path):
    path = write(tmp_path, f"{HEADER}\nT-1,2.06,5.8\nT-2,3,12\n")
    towers = read_inventory(path)
    assert [t.id for t in towers] == ["T-1", "T-2"]
    first = towers[0]
    assert (first.width_m, first.height_m) == (2.06, 5.8)
    assert first.plan_depth_m == 2.06  # square plan when depth_m is absent
    assert first.lat is None and first.eta is None and first.station is None
    assert not first.has_coordinates
    assert not first.has_floor_model and not first.has_double_block


def test_all_columns_and_properties(tmp_path):
    header = ",".join(COLUMNS)
    row = (
        'T-9,"Tower, with comma",Cervino,CE,41.04,14.42,30,2.06,5.8,3.0,0.9,34556.6,9871627.9,'
        "1.25,1.0,12,8,0.3,1.5,1.2,1.0,9000,800,1.0,0.4,0.6,0.45,Rubble,,lc2,"
        "3.0,2.0,0.5,12,300,0.3,Y,IT.AQV,50,iii,B,T2"
    )
    (tower,) = read_inventory(write(tmp_path, f"{header}\n{row}\n"))
    # categories are read case-insensitively and stored as the allowed value spells them
    assert (tower.wall_thickness_m, tower.masonry_type, tower.knowledge_level) == (
        0.6,
        "rubble",
        "LC2",
    )
    assert tower.wall_thickness_top_m == 0.45
    assert tower.has_gable and tower.lv1_missing == ()
    assert (tower.gable_bells_mass_kg, tower.gable_opening_ratio) == (300.0, 0.3)
    assert tower.gable_axis == "y"  # a tower axis, read case-insensitively as x or y
    assert tower.name == "Tower, with comma"
    assert (tower.comune, tower.provincia) == ("Cervino", "CE")
    assert tower.plan_depth_m == 3.0
    assert tower.azimuth_deg == 30.0
    assert tower.has_coordinates and tower.has_floor_model and tower.has_double_block
    assert tower.station == "IT.AQV"
    assert (tower.nominal_life_y, tower.use_class, tower.soil_class, tower.topography) == (
        50.0,
        "III",
        "B",
        "T2",
    )


def test_lv1_and_gable_columns_are_refused_with_the_allowed_values(tmp_path):
    header = "id,width_m,height_m,masonry_type,knowledge_level"
    message = refused(tmp_path, f"{header}\nT-1,3,20,marble,LC1\n")
    assert "row 1 (line 2)" in message and "column 'masonry_type'" in message
    assert "must be one of rubble, roughly_cut_stone" in message and "solid_brick" in message
    message = refused(tmp_path, f"{header}\nT-1,3,20,rubble,LC4\n")
    assert "column 'knowledge_level'" in message and "LC1, LC2, LC3" in message
    gable = "id,width_m,height_m,gable_height_m,gable_width_m"
    message = refused(tmp_path, f"{gable}\nT-1,3,20,3,2\n")
    assert "gable_thickness_m" in message and "bell-gable check needs all" in message
    message = refused(tmp_path, "id,width_m,height_m,gable_opening_ratio\nT-1,3,20,0.2\n")
    assert "needs the bell gable's columns" in message
    message = refused(tmp_path, "id,width_m,height_m,gable_axis\nT-1,3,20,x\n")
    assert "column 'gable_axis'" in message and "needs the bell gable's columns" in message
    full = f"{gable},gable_thickness_m,gable_base_height_m,gable_axis"
    for bad in ("z", "N", "xy", "1"):
        message = refused(tmp_path, f"{full}\nT-1,3,20,3,2,0.5,9,x\nT-2,3,20,3,2,0.5,9,{bad}\n")
        where = "towers.csv: row 2 (line 3), tower 'T-2', column 'gable_axis'"
        assert f"{where}: value {bad!r}" in message
        assert "must be one of x, y (allowed values)" in message
    towers = read_inventory(write(tmp_path, f"{full}\nT-1,3,20,3,2,0.5,9,X\nT-2,3,20,3,2,0.5,9,\n"))
    assert [t.gable_axis for t in towers] == ["x", None]
    with pytest.raises(InventoryError, match="column 'gable_axis'.*must be one of x, y"):
        replace(towers[1], gable_axis="Y")  # a Tower built in code: the spelling of the list
    message = refused(tmp_path, "id,width_m,height_m,wall_thickness_m\nT-1,3,20,600\n")
    assert "column 'wall_thickness_m'" in message and "check the units" in message
    (tower,) = read_inventory(write(tmp_path, "id,width_m,height_m,wall_thickness_m\nT,3,20,1\n"))
    assert tower.lv1_missing == ("masonry_type",) and not tower.has_gable


def test_the_shafts_top_wall_thickness_reads_and_round_trips(tmp_path):
    header = "id,width_m,height_m,depth_m,wall_thickness_m,wall_thickness_top_m"
    tapered, prismatic, even = read_inventory(
        write(tmp_path, f"{header}\nT-1,10,55,8,1.67,0.8\nT-2,10,55,8,1.2,\nT-3,4,20,4,1,1\n")
    )
    assert (tapered.wall_thickness_m, tapered.wall_thickness_top_m) == (1.67, 0.8)
    assert prismatic.wall_thickness_top_m is None
    assert even.wall_thickness_top_m == 1.0  # the base's: allowed (a prismatic shaft)
    again = read_inventory(write_inventory([tapered, prismatic, even], tmp_path / "copy.csv"))
    assert again == [tapered, prismatic, even]


@pytest.mark.parametrize(
    ("cells", "expected"),
    [
        # it is the top of a shaft whose base thickness is wall_thickness_m
        (",0.8", "needs wall_thickness_m, the wall thickness at the shaft's base"),
        # the walls thin upwards: a top thicker than the base is refused, with the range
        ("0.8,1.2", "must not exceed wall_thickness_m=0.8 m, the thickness at the base"),
        ("0.8,1.2", "(allowed: 0.1 m up to it; the walls of a tower thin upwards"),
        # no thicker than half the smaller plan dimension (depth 3 m: 1.5 m)
        ("2,1.6", "must not exceed half the smaller plan dimension, 1.5 m (allowed: 0.1 m"),
        # the plausible range and the sign, as wall_thickness_m's
        ("2,0.05", "value 0.05 is not plausible for a bell tower: allowed 0.1 to 10 m"),
        ("2,-1", "value -1 must be > 0"),
        ("2,nan", "must be a finite number"),
    ],
)
def test_the_shafts_top_wall_thickness_is_refused_naming_file_row_and_column(
    tmp_path, cells, expected
):
    header = "id,width_m,height_m,depth_m,wall_thickness_m,wall_thickness_top_m"
    message = refused(tmp_path, f"{header}\nT-0,4,20,3,1,\nT-1,4,20,3,{cells}\n")
    where = "towers.csv: row 2 (line 3), tower 'T-1', column 'wall_thickness_top_m'"
    assert where in message
    assert expected in message


def test_measured_masonry_strength_is_read_in_mpa_at_lc3(tmp_path):
    header = "id,width_m,height_m,masonry_type,masonry_strength_mpa,knowledge_level"
    (at_lc3, run_level) = read_inventory(
        write(tmp_path, f"{header}\nT-1,3,20,solid_brick,3.2,lc3\nT-2,3,20,rubble,1.5,\n")
    )
    assert (at_lc3.masonry_strength_mpa, at_lc3.knowledge_level) == (3.2, "LC3")
    # without the row's level the run's decides (assess refuses it below LC3)
    assert (run_level.masonry_strength_mpa, run_level.knowledge_level) == (1.5, None)
    again = read_inventory(write_inventory([at_lc3, run_level], tmp_path / "copy.csv"))
    assert again == [at_lc3, run_level]


@pytest.mark.parametrize(
    ("cells", "expected"),
    [
        # the plausible range, with the allowed values and the unit (a value in kPa or Pa)
        (
            "solid_brick,3200,LC3",
            "value 3200 is not plausible for a bell tower: allowed 0.3 to 20 MPa",
        ),
        ("solid_brick,0.1,LC3", "allowed 0.3 to 20 MPa (check the units)"),
        ("solid_brick,-2,LC3", "value -2 must be > 0"),
        # a measured f_m is used at LC3 only (Circolare 2019 §C8.5.4.1)
        ("solid_brick,3.2,LC2", "is a measured f_m, used only at knowledge_level LC3"),
        ("solid_brick,3.2,lc1", "this row's knowledge_level LC1 takes Table C8.5.I's value"),
        # it refines a masonry type's strength
        (",3.2,LC3", "needs masonry_type"),
    ],
)
def test_measured_masonry_strength_is_refused_naming_file_row_and_column(tmp_path, cells, expected):
    header = "id,width_m,height_m,masonry_type,masonry_strength_mpa,knowledge_level"
    message = refused(tmp_path, f"{header}\nT-0,3,20,rubble,,\nT-1,3,20,{cells}\n")
    assert "towers.csv: row 2 (line 3), tower 'T-1', column 'masonry_strength_mpa'" in message
    assert expected in message


def test_bom_blank_lines_whitespace_and_column_order(tmp_path):
    text = "\ufeff height_m , id ,width_m\n\n5.8, T-1 ,2.06\n   \n\n12,T-2,3\n\n"
    towers = read_inventory(write(tmp_path, text))
    assert [(t.id, t.width_m, t.height_m) for t in towers] == [("T-1", 2.06, 5.8), ("T-2", 3, 12)]


def test_blank_lines_do_not_shift_row_numbers_but_lines_count_them(tmp_path):
    message = refused(tmp_path, f"{HEADER}\n\nT-1,2,5\n\nT-2,-1,5\n")
    assert "row 2 (line 5)" in message
    assert "column 'width_m'" in message and "-1" in message and "> 0" in message


@pytest.mark.parametrize(
    ("header", "expected"),
    [
        ("id,width_m", "missing required column(s) height_m"),
        ("id,widht_m,height_m", "unknown column 'widht_m' (did you mean 'width_m'?)"),
        ("id,width_m,height_m,colour", "unknown column 'colour'"),
        ("id,width_m,height_m,id", "column 'id' appears twice"),
        ("id,width_m,,height_m", "empty column name"),
    ],
)
def test_header_rules(tmp_path, header, expected):
    message = refused(tmp_path, f"{header}\nT-1,2,5,1\n")
    assert expected in message
    assert "header (line 1)" in message


@pytest.mark.parametrize(
    ("columns", "good", "bad", "column", "rule"),
    [
        ("width_m", "2", "2.0x", "width_m", "is not a number"),
        ("lat,lon", "1,1", "91,1", "lat", "must be in [-90, 90]"),
        ("lat,lon", "1,1", "-90.5,1", "lat", "must be in [-90, 90]"),
        ("lat,lon", "1,1", "1,180.01", "lon", "must be in [-180, 180]"),
        ("lat,lon", "1,1", "nan,1", "lat", "finite"),
        ("eta", "0.5", "0", "eta", "must be in (0, 1]"),
        ("eta", "0.5", "1.2", "eta", "must be in (0, 1]"),
        ("eta", "0.5", "NaN", "eta", "finite"),
        ("depth_m", "3", "0", "depth_m", "must be > 0"),
        ("depth_m", "3", "inf", "depth_m", "finite"),
        ("azimuth_deg", "0", "360", "azimuth_deg", "must be in [0, 360)"),
        ("azimuth_deg", "0", "-10", "azimuth_deg", "must be in [0, 360)"),
        ("building_height_m,base_height_m", "9,9", "0,0", "building_height_m", "must be > 0"),
        (
            "building_height_m,base_height_m,building_period_s",
            "9,9,0.3",
            "9,9,-1",
            "building_period_s",
            "must be > 0",
        ),
        ("building_period_s", "", "0.3", "building_period_s", "needs building_height_m"),
        ("station", "AQV", "IT.AQV.00", "station", "must be 'NET.STA' or 'STA'"),
        ("station", "IT.AQV", "A Q V", "station", "must be 'NET.STA' or 'STA'"),
    ],
)
def test_value_rules_name_row_column_value_and_rule(tmp_path, columns, good, bad, column, rule):
    header = "id,height_m" + ("" if columns == "width_m" else ",width_m") + f",{columns}"
    fill = "" if columns == "width_m" else ",2"
    text = f"{header}\nT-1,5{fill},{good}\nT-2,5{fill},{bad}\n"
    message = refused(tmp_path, text)
    assert "row 2 (line 3)" in message
    assert f"tower 'T-2', column {column!r}" in message
    assert rule in message
    cell = dict(zip(columns.split(","), bad.split(","), strict=True))[column]
    assert f"value {cell}" in message or f"value '{cell}'" in message


@pytest.mark.parametrize("column", ["width_m", "height_m"])
@pytest.mark.parametrize("value", ["0", "-2.5"])
def test_sizes_must_be_positive(tmp_path, column, value):
    cells = {"id": "T-1", "width_m": "2", "height_m": "5", column: value}
    text = f"{HEADER}\n{cells['id']},{cells['width_m']},{cells['height_m']}\n"
    message = refused(tmp_path, text)
    assert f"row 1 (line 2), tower 'T-1', column {column!r}: value {value}" in message
    assert "must be > 0" in message


def test_required_value_missing(tmp_path):
    message = refused(tmp_path, f"{HEADER}\nT-1,,5\n")
    assert "column 'width_m'" in message and "is required" in message


def test_empty_id_is_refused(tmp_path):
    message = refused(tmp_path, f"{HEADER}\n,2,5\n")
    assert "column 'id'" in message and "required" in message


def test_duplicate_id_names_both_rows(tmp_path):
    message = refused(tmp_path, f"{HEADER}\nA,2,5\nB,2,5\nA,3,6\n")
    assert "row 3 (line 4)" in message
    assert "'A' is a duplicate (first used in row 1, line 2)" in message


def test_wrong_field_count(tmp_path):
    message = refused(tmp_path, f"{HEADER}\nA,2,5,7\n")
    assert "row 1 (line 2)" in message and "4 fields" in message and "3 columns" in message


def test_mu_k_must_not_exceed_mu_s(tmp_path):
    header = f"{HEADER},tower_mass_kg,building_mass_kg,mu_s,mu_k"
    message = refused(tmp_path, f"{header}\nT-017,2,5,3e4,1e7,1.0,1.2\n")
    assert "tower 'T-017', column 'mu_k': value 1.2 must not exceed mu_s=1" in message


@pytest.mark.parametrize(
    "given", [("tower_mass_kg",), ("mu_s", "mu_k"), ("tower_mass_kg", "building_mass_kg", "mu_s")]
)
def test_double_block_group_is_all_or_none(tmp_path, given):
    values = {"tower_mass_kg": "3e4", "building_mass_kg": "1e7", "mu_s": "1", "mu_k": "0.7"}
    header = f"{HEADER}," + ",".join(given)
    row = "T-1,2,5," + ",".join(values[name] for name in given)
    message = refused(tmp_path, f"{header}\n{row}\n")
    assert "the double-block model needs all of" in message
    missing = next(name for name in values if name not in given)
    assert f"column {missing!r}" in message


def test_floor_group_and_base_height(tmp_path):
    header = f"{HEADER},building_height_m,base_height_m"
    assert "the floor model needs all of" in refused(tmp_path, f"{header}\nT-1,2,5,12,\n")
    assert "the floor model needs all of" in refused(tmp_path, f"{header}\nT-1,2,5,,6\n")
    message = refused(tmp_path, f"{header}\nT-1,2,5,12,12.5\n")
    assert "column 'base_height_m': value 12.5 must not exceed building_height_m=12" in message
    assert "must be >= 0" in refused(tmp_path, f"{header}\nT-1,2,5,12,-1\n")
    (tower,) = read_inventory(write(tmp_path, f"{header}\nT-1,2,5,12,0\n"))
    assert tower.has_floor_model and tower.base_height_m == 0.0


def test_lat_without_lon_is_refused(tmp_path):
    message = refused(tmp_path, f"{HEADER},lat,lon\nT-1,2,5,41,\n")
    assert "column 'lon'" in message and "both lat and lon" in message


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        ("", "the inventory is empty"),
        ("\n\n", "the inventory is empty"),
        (f"{HEADER}\n", "has a header but no towers"),
        (f"{HEADER}\n\n  \n", "has a header but no towers"),
    ],
)
def test_empty_inventory_is_an_error(tmp_path, text, expected):
    assert expected in refused(tmp_path, text)


def test_unreadable_files(tmp_path):
    with pytest.raises(InventoryError, match="cannot read the inventory"):
        read_inventory(tmp_path / "absent.csv")
    path = tmp_path / "latin1.csv"
    path.write_bytes(f"{HEADER},name\nT-1,2,5,Sant\xe0\n".encode("latin-1"))
    with pytest.raises(InventoryError, match="not UTF-8"):
        read_inventory(path)


def test_inventory_error_is_a_rockscreen_error():
    assert issubclass(InventoryError, RockscreenError)


def test_tower_validates_on_construction():
    with pytest.raises(InventoryError, match=r"tower 'X', column 'eta': value 1.5 must be in"):
        Tower("X", 2.0, 5.0, eta=1.5)
    with pytest.raises(InventoryError, match="must be a number"):
        Tower("X", "2", 5.0)  # type: ignore[arg-type]
    tower = Tower("X", 2.0, 5.0)
    with pytest.raises(InventoryError, match="must not exceed mu_s"):
        replace(tower, tower_mass_kg=1.0, building_mass_kg=2.0, mu_s=0.5, mu_k=0.6)


def test_columns_match_the_dataclass():
    names = [f.name for f in fields(Tower)]
    assert set(names) == set(COLUMNS)
    assert names[:3] == list(REQUIRED_COLUMNS)


def test_write_then_read_round_trip(tmp_path):
    towers = read_inventory(example_inventory_path())
    again = read_inventory(write_inventory(towers, tmp_path / "copy.csv"))
    assert again == towers


def test_example_inventory_holds_the_seed_paper_tower():
    towers = read_inventory(example_inventory_path())
    assert 6 <= len(towers) <= 11
    cervino = next(t for t in towers if t.id == "CE-SANNA")
    assert (cervino.width_m, cervino.height_m, cervino.eta) == (2.06, 5.80, 0.9)
    assert cervino.tower_mass_kg == pytest.approx(339e3 / G, abs=0.01)
    assert cervino.building_mass_kg == pytest.approx(96_840.67e3 / G, abs=0.01)
    assert (cervino.mu_s, cervino.mu_k) == (1.25, 1.0)
    assert cervino.lat == pytest.approx(41.04, abs=0.05)
    assert cervino.lon == pytest.approx(14.42, abs=0.05)
    # the tower is the light body; overturning angle atan(b/h) = 0.35 rad (REFERENCES R9)
    assert math.atan(cervino.width_m / cervino.height_m) == pytest.approx(0.35, abs=0.01)
    # the archetypes cover ground-only, floor-model and double-block data
    assert any(not t.has_floor_model and not t.has_double_block for t in towers)
    assert any(t.has_floor_model and t.building_period_s for t in towers)
    assert any(t.has_double_block and t.id != "CE-SANNA" for t in towers)
    slenderness = [t.height_m / t.width_m for t in towers]
    assert min(slenderness) < 2.0 < 4.0 < max(slenderness)


def test_inventory_table_units_and_missing_values():
    towers = read_inventory(example_inventory_path())
    table = inventory_table(towers)
    assert table.shape == (len(towers),)
    for name in ("lat_deg", "lon_deg", "width_m", "height_m", "depth_m", "tower_mass_kg"):
        assert table.dtype[name] == np.float64
    assert [cell.decode() for cell in table["id"]] == [t.id for t in towers]
    assert table["name"][0].decode() == towers[0].name
    row = {t.id: i for i, t in enumerate(towers)}
    assert math.isnan(table["azimuth_deg"][row["CE-SANNA"]])
    assert table["depth_m"][row["CE-SANNA"]] == 2.06  # resolved square plan
    assert table["station"][row["ARC-07"]].decode() == "XX.SYN2"
    assert math.isnan(table["lat_deg"][row["ARC-07"]])


def test_inventory_table_is_h5py_writable(tmp_path):
    h5py = pytest.importorskip("h5py")
    table = inventory_table([Tower("Torre \u00e0", 2.0, 5.0, name="Santa Maria")])
    with h5py.File(tmp_path / "t.h5", "w") as handle:
        handle["towers"] = table
    with h5py.File(tmp_path / "t.h5", "r") as handle:
        assert handle["towers"]["id"][0].decode() == "Torre \u00e0"


@pytest.mark.parametrize(
    ("column", "bad", "rule"),
    [
        ("nominal_life_y", "0", "must be > 0"),
        ("nominal_life_y", "-50", "must be > 0"),
        ("use_class", "V", "must be one of I, II, III, IV"),
        ("soil_class", "S1", "must be one of A, B, C, D, E"),
        ("topography", "T5", "must be one of T1, T2, T3, T4"),
    ],
)
def test_hazard_columns_validated(tmp_path, column, bad, rule):
    message = refused(tmp_path, f"{HEADER},{column}\nT-1,2,5,{bad}\n")
    assert "row 1 (line 2)" in message
    assert f"column {column!r}" in message
    assert repr(bad) in message or bad in message
    assert rule in message


def test_hazard_columns_optional_and_case_insensitive(tmp_path):
    text = f"{HEADER},use_class,soil_class,topography\nT-1,2,5,ii,c,t3\nT-2,2,5,,,\n"
    first, second = read_inventory(write(tmp_path, text))
    assert (first.use_class, first.soil_class, first.topography) == ("II", "C", "T3")
    assert (second.use_class, second.soil_class, second.topography) == (None, None, None)
    assert second.nominal_life_y is None


def test_semicolon_csv_with_decimal_comma(tmp_path):
    # As Italian Excel saves "CSV (delimitato dal separatore di elenco)".
    text = (
        "id;name;lat;lon;width_m;height_m;soil_class\r\n"
        "CE-1;Torre, campanaria;41,04;14,42;2,06;5,8;B\r\n"
        "CE-2;Altra;41;14,5;3;12;\r\n"
    )
    first, second = read_inventory(write(tmp_path, text, encoding="utf-8-sig"))
    assert (first.lat, first.lon, first.width_m, first.height_m) == (41.04, 14.42, 2.06, 5.8)
    assert first.name == "Torre, campanaria"  # a comma in text stays text
    assert first.soil_class == "B"
    assert (second.lat, second.lon) == (41.0, 14.5)


@pytest.mark.parametrize(
    ("text", "expected"),
    [
        pytest.param(
            f'{HEADER}\nT-1,"2,06",5.8\n',
            "column 'width_m': value '2,06' is not a number",
            id="decimal-comma-only-with-semicolons",
        ),
        pytest.param(
            "id;width_m;height_m\nT-1;2,0,6;5\n",
            "row 1 (line 2), tower 'T-1', column 'width_m': value '2,0,6' is not a number",
            id="semicolon-file-bad-number-named",
        ),
    ],
)
def test_a_bad_number_is_named(tmp_path, text, expected):
    message = refused(tmp_path, text)
    assert expected in message


def test_header_with_other_delimiter_says_so(tmp_path):
    # Mixed: more commas than semicolons, so ',' is used, and a name holds ';'.
    message = refused(tmp_path, "id;width_m;height_m,name,station\nT-1;2;5,a,b\n")
    assert "the delimiter looks like ';'" in message
    assert "did you mean" not in message
    tab = refused(tmp_path, "id\twidth_m\theight_m\nT-1\t2\t5\n")
    assert "the delimiter looks like a tab" in tab
    assert "building_height_m" not in tab.split("known columns")[0]


def test_inventory_table_hazard_columns():
    tower = Tower("T", 2.0, 5.0, nominal_life_y=50.0, use_class="III", soil_class="B")
    table = inventory_table([tower, Tower("U", 2.0, 5.0)])
    assert table["nominal_life_y"][0] == 50.0 and math.isnan(table["nominal_life_y"][1])
    assert table["use_class"][0].decode() == "III" and table["soil_class"][1].decode() == ""


@pytest.mark.parametrize(
    ("column", "value"),
    [("height_m", 1e308), ("width_m", 1e308), ("width_m", 1e-300), ("mu_s", 50.0)],
)
def test_implausible_values_are_refused_with_row_and_range(tmp_path, column, value):
    path = tmp_path / "towers.csv"
    row = {"id": "T1", "width_m": 3.0, "height_m": 20.0, "mu_s": "", "mu_k": ""}
    row[column] = value
    if column == "mu_s":
        row.update(mu_k=0.5, tower_mass_kg=1e5, building_mass_kg=1e6)
    header = ",".join(row)
    path.write_text(header + "\n" + ",".join(str(v) for v in row.values()) + "\n")
    with pytest.raises(InventoryError, match=rf"row 1 .*'{column}'.*not plausible.*allowed"):
        read_inventory(path)


def test_control_characters_in_ids_are_refused(tmp_path):
    path = tmp_path / "towers.csv"
    path.write_text("id,width_m,height_m\nA\x1b]0;x\x07,3,20\n", encoding="utf-8")
    with pytest.raises(InventoryError, match="control characters"):
        read_inventory(path)


# ------------------------------------------------------------- every invalid row at once (issue 30)


def test_three_invalid_rows_are_named_in_one_error(tmp_path):
    text = f"{HEADER},lat,lon\nA,2,5,41,14\nB,-2,5,41,14\nC,2,5,41\nD,2,x,41,14\nE,2,5,41,14\n"
    message = refused(tmp_path, text)
    assert message.startswith(f"{tmp_path / 'towers.csv'}: 3 invalid rows of 5 ")
    assert "--skip-invalid" in message and "\n" not in message
    assert "row 2 (line 3), tower 'B', column 'width_m': value -2 must be > 0" in message
    assert "row 3 (line 4): has 4 fields, the header has 5 columns" in message
    assert "row 4 (line 5), tower 'D', column 'height_m': value 'x' is not a number" in message
    assert "A," not in message and "'E'" not in message


def test_invalid_rows_are_capped_with_a_count(tmp_path):
    from rockscreen.stations.inventory import MAX_LISTED_ROWS

    rows = "".join(f"T{i},-1,5\n" for i in range(MAX_LISTED_ROWS + 5))
    message = refused(tmp_path, f"{HEADER}\nOK,2,5\n{rows}")
    assert f"{MAX_LISTED_ROWS + 5} invalid rows of {MAX_LISTED_ROWS + 6}" in message
    assert f"tower 'T{MAX_LISTED_ROWS - 1}'" in message
    assert f"tower 'T{MAX_LISTED_ROWS}'" not in message
    assert message.endswith("; and 5 more invalid row(s)")


def test_read_inventory_rows_keeps_the_valid_towers_and_names_the_others(tmp_path):
    from rockscreen.stations.inventory import read_inventory_rows

    path = write(tmp_path, f"{HEADER}\nA,2,5\nB,0,5\nA,3,6\nB,2,5\nC,2,5\n")
    reading = read_inventory_rows(path)
    assert [t.id for t in reading.towers] == ["A", "C"]
    # B's id is taken by its invalid row: the later B is a duplicate, as once B is fixed
    assert [(r.row, r.line, r.tower_id, r.column) for r in reading.invalid] == [
        (2, 3, "B", "width_m"),
        (3, 4, "A", "id"),
        (4, 5, "B", "id"),
    ]
    assert "duplicate (first used in row 1, line 2)" in reading.invalid[1].detail
    with pytest.raises(InventoryError, match="3 invalid rows of 5"):
        read_inventory(path)
