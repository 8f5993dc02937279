"""Assess format 4: the summary as long tables, pivoted back into one row per tower.

``/fits``, ``/checks`` and ``/messages`` hold one row per tower x fit, check and note, each
column with its units declared once (``long_schema.LONG_TABLES``); ``/pivot`` says where
each column of the wide row is, so the reader gives back the rows a format-3 archive gave
(same keys, order, values and types) and the exports do not change. A format-3 archive
(its wide ``/summary``) is still read; a new check or a third part model is rows, not
columns.
"""

from __future__ import annotations

import math

import h5py
import pytest
from click.testing import CliRunner

from rockscreen.pipeline.archive import long_tables, risk_archive
from rockscreen.pipeline.archive.kinds import open_archive
from rockscreen.pipeline.archive.long_pivot import pivot_summary
from rockscreen.pipeline.archive.long_schema import LONG_TABLES, CheckColumns
from rockscreen.pipeline.archive.long_tables import split_summary
from rockscreen.pipeline.archive.risk_reader import read_summary
from rockscreen.pipeline.archive.safety import read_column
from rockscreen.pipeline.archive.schema import G_UNITS, TEXT
from rockscreen.pipeline.cli import main
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.report.export import summary_csv_text
from rockscreen.pipeline.risk.checks.governing import check_columns


def _same(a, b):
    """Whether two rows are equal key for key, in order, value and type (NaN equal)."""
    if list(a) != list(b):
        return False
    for key in a:
        x, y = a[key], b[key]
        if type(x) is not type(y):
            return False
        if not (x == y or (isinstance(x, float) and math.isnan(x) and math.isnan(y))):
            return False
    return True


def _write_v3(path, rows, monkeypatch):
    """Write ``rows`` in the format-3 layout: the writer without the split (wide /summary)."""
    with monkeypatch.context() as m:
        m.setattr(
            risk_archive,
            "split_summary",
            lambda rows, parts, checks: long_tables.LongSummary(list(rows), {}),
        )
        m.setitem(risk_archive.FORMAT_VERSIONS, "assess", "3")
        risk_archive.write_risk_archive(path, "assess", {"summary": rows}, {"command_line": "t"})
    return path


@pytest.fixture(scope="module")
def example(tmp_path_factory):
    """``rockscreen assess --example``: its archive and the wide rows the writer was given."""
    folder = tmp_path_factory.mktemp("assess-example")
    given = []
    real = risk_archive.write_summary_in_parts

    def spy(f, rows, parts, checks, write_table):
        # the command's summary reaches the writer in parts (the work file's rows)
        given.extend(dict(row) for part in rows.chunks() for row in part)
        return real(f, rows, parts, checks, write_table)

    with pytest.MonkeyPatch.context() as m:
        m.setattr(risk_archive, "write_summary_in_parts", spy)
        out = folder / "example.h5"
        result = CliRunner().invoke(main, ["assess", "--example", "--jobs", "1", "--out", out])
    assert result.exit_code == 0, result.output
    return out, given


def test_the_example_is_stored_as_long_tables_with_their_units(example):
    path, given = example
    with h5py.File(path, "r") as f:
        assert f.attrs["format_version"] == "4"
        for table, units in LONG_TABLES.items():
            for column in f[table]:
                assert f[table][column].attrs["units"] == units[column], (table, column)
        summary = set(f["summary"])
        fits = set(read_column(f["fits/fit"], path, "fits/fit"))
        checks = set(read_column(f["checks/check"], path, "checks/check"))
    # the fits and checks left /summary; the tower's own columns stayed
    assert {"collapse_median_g", "stripe_beta", "belfry_slv_bound", "note_codes"}.isdisjoint(
        summary
    )
    assert {"id", "lat_deg", "risk_class", "governing_check", "completeness", "note"} <= summary
    assert {"risk_p50_best", "risk_band"} <= summary
    assert {"collapse", "slv", "stripe", "belfry.collapse", "gable.slv"} <= fits
    assert {"tower.rocking", "belfry.rocking", "shaft.lv1", "gable.kinematic_nonlinear"} <= checks
    assert risk_archive.units_of("assess", "checks", "capacity_ag_g") == G_UNITS
    assert risk_archive.units_of("assess", "fits", "bound") == TEXT
    assert len(summary) < len(given[0]) - 30


def test_the_example_reads_back_the_wide_rows_and_exports_them_unchanged(
    example, tmp_path, monkeypatch
):
    """Pivoted, the rows are those a format-3 archive of the same rows reads back."""
    path, given = example
    rows = read_summary(path, "assess")
    older = read_summary(_write_v3(tmp_path / "v3.h5", given, monkeypatch), "assess")
    assert len(rows) == len(older) == 9
    assert all(_same(a, b) for a, b in zip(older, rows, strict=True))
    assert summary_csv_text(rows) == summary_csv_text(older)
    reader = open_archive(path)
    assert reader.version == "4" and [r["id"] for r in reader.summary()] == [r["id"] for r in rows]
    by_id = {row["id"]: row for row in rows}
    assert by_id["ARC-07"]["checks_not_made_codes"] == ""  # not assessed: no check rows
    assert by_id["ARC-03"]["checks_not_made_codes"] == "[]"


def test_the_checks_rows_carry_status_and_reason(example):
    path, given = example
    with h5py.File(path, "r") as f:
        table = {c: read_column(f["checks"][c], path, c) for c in f["checks"]}
    text = table  # text columns come back as str
    rows = {text["check"][i]: i for i, tower in enumerate(table["tower"]) if tower == 0}
    belfry = rows["belfry.rocking"]
    assert text["status"][belfry] == "not_made"
    assert text["reason_code"][belfry] == "not_made.belfry"
    tower = rows["tower.rocking"]
    assert text["status"][tower] == "made"
    assert table["capacity_ag_g"][tower] == pytest.approx(given[0]["capacity_pga_g"])
    assert table["safety_index"][tower] == pytest.approx(given[0]["safety_index"])


def test_a_version_3_archive_is_still_read(example, tmp_path, monkeypatch):
    _, given = example
    path = _write_v3(tmp_path / "v3.h5", given, monkeypatch)
    with h5py.File(path, "r") as f:
        assert f.attrs["format_version"] == "3" and "pivot" not in f
        assert "collapse_median_g" in f["summary"]
    rows = read_summary(path, "assess")
    assert [r["id"] for r in rows] == [r["id"] for r in given]
    assert rows[0]["collapse_median_g"] == pytest.approx(given[0]["collapse_median_g"])
    reader = open_archive(path)
    assert reader.version == "3" and len(reader.summary()) == len(given)


def _toy_rows():
    return [
        {
            "id": f"T{i}",
            "collapse_median_g": 0.5 + i,
            "collapse_n_records": 11,
            "spire_fragility_median_g": 0.3 * (i + 1),
            "spire_slv_bound": "lower" if i else "",
            "toy_capacity_ag_g": 0.2 + i / 10 if i else math.nan,
            "toy_safety_index": 1.5,
            "toy_bound": "",
            "checks_not_made_codes": '[["tower.toy", ["not_made.belfry", {}]]]' if not i else "[]",
            "note_codes": '[["site.no_coordinates", {}]]',
        }
        for i in range(3)
    ]


def test_a_new_check_and_a_third_part_model_are_rows_without_a_schema_edit(tmp_path):
    """``toy_*`` and ``spire_*`` are declared nowhere: they are stored as rows, read back."""
    toy = CheckColumns(
        "tower.toy",
        "tower",
        "kinematic",
        "kinematic",
        ("toy_capacity_ag_g", "toy_safety_index", "toy_bound"),
    )
    rows = _toy_rows()
    split = split_summary(rows, ("spire",), [toy])
    assert set(split.summary[0]) == {"id"}  # everything else moved
    checks = split.tables["checks"]
    assert checks["check"] == ["tower.toy"] * 3 and checks["status"][0] == "not_made"
    assert checks["reason_code"] == ["not_made.belfry", "", ""]
    assert set(split.tables["fits"]["fit"]) == {"collapse", "spire.collapse", "spire.slv"}
    # through the file, the reader does not need the toy check registered
    rows = [{k: v for k, v in row.items() if not k.startswith("spire_")} for row in rows]
    path = tmp_path / "toy.h5"
    risk_archive.write_risk_archive(
        path, "assess", {"summary": rows}, {"command_line": "t"}, checks=[toy]
    )
    back = read_summary(path, "assess")
    assert all(_same(a, b) for a, b in zip(rows, back, strict=True))


def test_the_registered_checks_are_declared_in_the_verdicts_order():
    ids = [c.check for c in check_columns()]
    assert ids[: ids.index("tower.rocking")] == [f"{p}.rocking" for p in ("belfry", "gable")]
    assert ids.index("shaft.lv1") < ids.index("tower.kinematic_linear")
    assert len(ids) == len(set(ids))


def test_a_column_the_long_tables_cannot_hold_exactly_stays_in_the_summary(tmp_path):
    rows = _toy_rows()
    rows[1]["note_codes"] = '[["site.no_coordinates",{}]]'  # not the stored spelling
    rows[2]["collapse_median_g"] = "n/a"  # text where the fit holds a number
    split = split_summary(rows, ("spire",), ())
    assert {"note_codes", "collapse_median_g", "checks_not_made_codes"} <= set(split.summary[0])
    back = pivot_summary(split.summary, split.tables)
    assert all(_same(a, b) for a, b in zip(rows, back, strict=True))


@pytest.mark.parametrize("at", [99, -1])
def test_long_tables_pointing_at_no_tower_are_refused(example, tmp_path, at):
    path, _ = example
    copy = tmp_path / "bad.h5"
    copy.write_bytes(path.read_bytes())
    with h5py.File(copy, "r+") as f:
        tower = f["fits"]["tower"][:]
        tower[-1] = at
        attrs = dict(f["fits"]["tower"].attrs)
        del f["fits"]["tower"]
        f["fits"].create_dataset("tower", data=tower).attrs.update(attrs)
    with pytest.raises(ArchiveError, match="do not pivot into the summary"):
        read_summary(copy, "assess")


def test_reasons_out_of_the_checks_order_stay_in_the_summary():
    """The stored list of the checks not made is kept as it is when the rows cannot say it."""
    first, second = (
        CheckColumns(
            f"tower.toy{i}", "tower", "kinematic", "kinematic", (f"a{i}", f"i{i}", f"b{i}")
        )
        for i in (1, 2)
    )
    reversed_ = '[["tower.toy2", ["not_made.belfry", {}]], ["tower.toy1", ["not_made.belfry", {}]]]'
    rows = [
        {"id": "T", "a1": math.nan, "i1": math.nan, "b1": "", "checks_not_made_codes": reversed_},
        {"id": "U", "a1": 0.3, "i1": 1.2, "b1": "", "checks_not_made_codes": "[]"},
    ]
    split = split_summary(rows, (), [first, second])
    assert "checks_not_made_codes" in split.summary[0]
    assert "a1" not in split.summary[0]
    assert split.tables["checks"]["reason_code"][:2] == ["not_made.belfry"] * 2
    in_order = split_summary(rows[1:], (), [first, second])
    assert "checks_not_made_codes" not in in_order.summary[0]


def test_an_empty_note_and_a_tower_without_a_verdict_read_back():
    toy = CheckColumns("tower.toy", "tower", "kinematic", "kinematic", ("a", "i", "b"))
    rows = [
        {"id": "T", "a": math.nan, "i": math.nan, "b": "", "checks_not_made_codes": "",
         "note_codes": "[]"},
        {"id": "U", "a": 0.3, "i": 1.2, "b": "lower", "checks_not_made_codes": "[]",
         "note_codes": '[["site.no_coordinates", {}]]'},
    ]  # fmt: skip
    split = split_summary(rows, (), [toy])
    assert set(split.summary[0]) == {"id"}
    assert split.tables["checks"]["tower"] == [1]  # T has no verdict: no rows
    assert split.tables["messages"]["tower"] == [1]
    back = pivot_summary(split.summary, split.tables)
    assert all(_same(a, b) for a, b in zip(rows, back, strict=True))
    # a value where the tower has no verdict: that column stays in /summary
    rows[0]["b"] = "upper"
    assert "b" in split_summary(rows, (), [toy]).summary[0]


class _InParts(list):
    """Wide rows given to the writer a part of ``size`` rows at a time (as the work file's)."""

    def __init__(self, rows, size):
        super().__init__(rows)
        self.size = size

    def chunks(self):
        for start in range(0, len(self), self.size):
            yield [dict(row) for row in self[start : start + self.size]]


def _datasets(path):
    """Every dataset's dtype, shape, values and attributes, and every group's attributes."""
    out = {}
    with h5py.File(path, "r") as f:

        def take(name, obj):
            attrs = {k: str(v) for k, v in obj.attrs.items()}
            if isinstance(obj, h5py.Dataset):
                out[name] = (obj.dtype.str, obj.shape, repr(obj[()].tolist()), attrs)
            else:
                out[name] = attrs

        f.visititems(take)
    return out


@pytest.mark.parametrize("size", [1, 2, 100])
def test_a_summary_given_in_parts_is_stored_as_the_same_rows_given_whole(example, tmp_path, size):
    """The work file's rows, read back a part at a time, give the archive the rows given
    whole give: same datasets (dtype, shape, values) and attributes."""
    _, given = example
    paths = []
    for name, rows in (("whole", given), ("parts", _InParts(given, size))):
        paths.append(tmp_path / f"{name}.h5")
        risk_archive.write_risk_archive(
            paths[-1], "assess", {"summary": rows}, {"command_line": "t"}, checks=check_columns()
        )
    whole, parts = (_datasets(p) for p in paths)
    assert "fits/tower" in whole and "checks/reason_params" in whole
    assert parts == whole


def test_a_column_that_only_a_late_part_keeps_in_the_summary_stays_there(example, tmp_path):
    """Where a column goes is decided from every part: a fit's text field given as a number
    in the last row only, or a note that is not a message list, keeps its column in
    ``/summary``."""
    _, given = example
    rows = [dict(row) for row in given]
    assert isinstance(rows[0]["collapse_bound"], str)
    rows[-1]["collapse_bound"] = 3
    rows[-1]["note_codes"] = "not a list"
    paths = []
    for name, table in (("whole", rows), ("parts", _InParts(rows, 1))):
        paths.append(tmp_path / f"{name}.h5")
        risk_archive.write_risk_archive(
            paths[-1], "assess", {"summary": table}, {"command_line": "t"}, checks=check_columns()
        )
    whole, parts = (_datasets(p) for p in paths)
    assert "summary/collapse_bound" in whole and "summary/note_codes" in whole
    assert parts == whole
