"""The assess and scenario archives store their tables compactly and read back the same.

Text with few distinct values is stored as ``uint8`` codes with a code table (the
``codes`` attribute), other text as fixed-length UTF-8 (variable-length beyond
``MAX_FIXED_TEXT_BYTES``), every non-empty column chunked and compressed (gzip + shuffle):
what every reader gives back is what was written (issue 30: 10,000 towers under 200 MB).
"""

from __future__ import annotations

import json
import math

import h5py
import numpy as np
import pytest

from rockscreen.pipeline.archive import risk_archive, risk_reader
from rockscreen.pipeline.archive.kinds import open_archive
from rockscreen.pipeline.errors import ArchiveError
from rockscreen.pipeline.report.html.adapters.risk import risk_archive_model
from rockscreen.pipeline.risk.assess.row_table import RowTable

N_TOWERS = 6
LONG = "a long note, " * 400  # over MAX_FIXED_TEXT_BYTES: variable-length


def _summary(n=N_TOWERS):
    return [
        {
            "id": f"T{i:03d}",
            "name": f"torre {i} è" if i % 2 else "",
            "lat_deg": 42.0 + i / 100,
            "lon_deg": 13.4,
            "risk_class": ("low", "meets", "high")[i % 3],
            "fragility_median_g": 0.3 + i / 7 if i != 2 else math.nan,
            "collapse_n_records": 11 - i,
            "basis_compliant": i % 2 == 0,
            "note": LONG if i == 1 else f"note {i}",
        }
        for i in range(n)
    ]


def _outcomes():
    rows = []
    for i in range(N_TOWERS):
        for tr in (30.0, 475.0, 2475.0):
            for r in range(5):
                for component in ("X", "Y"):
                    for model in ("ground", "floor", "belfry"):
                        rows.append(
                            {
                                "tower_id": f"T{i:03d}",
                                "return_period_y": tr,
                                "record": f"STO-0-900-{r + 7 * i:04d}",
                                "scale_factor": 1.0 + r / 3,
                                "component": component,
                                "model": model,
                                "status": ("no_uplift", "rocked", "overturned")[(r + i) % 3],
                                "overturned": (r + i) % 3 == 2,
                                "theta_max_over_alpha": (r + 1) * (i + 1) / 97,
                            }
                        )
    return rows


def _ida():
    return [
        {
            "tower_id": f"T{i:03d}",
            "return_period_y": 712.0,
            "set_ag_g": 0.21,
            "record": f"STO-{r}",
            "set_scale_factor": 1.5,
            "component": component,
            "models": "ground,floor",
            "collapse_scale": 2.0 + r,
            "collapse_ag_g": 0.4 + r / 10,
            "slv_scale": 1.0,
            "slv_ag_g": 0.2,
            "censored": r == 0,
            "slv_censored": False,
            "censor_reason": "cap" if r == 0 else "",
            "n_solves": 9,
        }
        for i in range(N_TOWERS)
        for r in range(4)
        for component in ("X", "Y")
    ]


def _tables():
    return {
        "summary": _summary(),
        "stripes": [
            {
                "tower_id": f"T{i:03d}",
                "return_period_y": tr,
                "ag_g": tr / 5000,
                "models": "ground,floor",
                "n_records": 5,
                "n_overturned": i % 2,
            }
            for i in range(N_TOWERS)
            for tr in (30.0, 475.0, 2475.0)
        ],
        "outcomes": RowTable(_outcomes()),  # as assess keeps them: columns
        "ida": _ida(),
        "selection": [
            {
                "site_lon_deg": 13.4,
                "site_lat_deg": 42.0,
                "soil_class": "B",
                "topography": "T1",
                "return_period_y": tr,
                "ratio_min": 0.95,
                "ratio_max": 1.2,
                "meets_tolerance": True,
                "message": f"meets the tolerance at {tr:g} y",
                "n_records": 5,
                "compliant": True,
                "compliance_note": "",
                "period_from_s": 0.15,
                "period_to_s": 2.0,
            }
            for tr in (30.0, 475.0, 712.0, 2475.0)
        ],
        "failures": [{"kind": "site", "subject": "T999", "reason": "no coordinates"}],
    }


def _same(a, b):
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return a == b and type(a) is type(b)


def _assert_rows(written, read):
    written = list(written)
    assert len(read) == len(written)
    for w, r in zip(written, read, strict=True):
        assert list(r) == list(w)
        assert all(_same(w[k], r[k]) for k in w), (w, r)


def test_every_table_kind_reads_back_the_same(tmp_path):
    path = tmp_path / "a.h5"
    tables = _tables()
    records = {
        f"STO-{r}": {
            "x": np.arange(5, dtype=float) * (r + 1),
            "y": np.ones(3),
            "z": None,
            "dt_s": 0.01,
            "name": f"STO-{r}",
            "source": "stochastic pool B",
        }
        for r in range(4)
    }
    set_records = [(2, f"STO-{r}", 1.25 + r) for r in range(4)]
    risk_archive.write_risk_archive(
        path, "assess", tables, {"command_line": "x"}, records=records, set_records=set_records
    )
    for name, rows in tables.items():
        _assert_rows(rows, getattr(risk_reader, f"read_{name}")(path))
    assert risk_reader.read_set_records(path)[2] == [(r, f) for _, r, f in set_records]
    back = risk_reader.read_records(path)
    assert list(back) == list(records)
    assert all(np.array_equal(back[k]["x"], records[k]["x"]) for k in records)
    reader = open_archive(path)  # the one door and the HTML report read the same text
    assert reader.outcomes() == risk_reader.read_outcomes(path)
    model = risk_archive_model(path, "assess")
    shown = [t["risk_class"] for t in model.towers]  # the class, with the basis' mark
    assert [c.split(" (")[0] for c in shown] == [r["risk_class"] for r in _summary()]


def test_columns_are_coded_fixed_or_variable_and_compressed(tmp_path):
    path = tmp_path / "a.h5"
    risk_archive.write_risk_archive(path, "assess", _tables(), {})
    with h5py.File(path) as f:
        status = f["outcomes/status"]
        assert status.dtype == np.uint8 and status.attrs["units"] == ""
        assert json.loads(status.attrs["codes"]) == ["no_uplift", "overturned", "rocked"]
        record = f["outcomes/record"]  # 30 distinct of 540 rows: coded too
        assert record.dtype == np.uint8
        ids = f["summary/id"]  # every value distinct: fixed-length UTF-8
        assert h5py.check_string_dtype(ids.dtype).length == 4
        note = f["summary/note"]  # one value over MAX_FIXED_TEXT_BYTES: variable-length
        assert h5py.check_string_dtype(note.dtype).length is None
        for column in ("theta_max_over_alpha", "overturned", "status", "tower_id"):
            ds = f[f"outcomes/{column}"]
            assert ds.compression == "gzip" and ds.shuffle, column
        units = {c: f[f"outcomes/{c}"].attrs["units"] for c in ("overturned", "scale_factor")}
        assert units == {"overturned": "", "scale_factor": "1"}  # flags are text, not numbers
        assert f.attrs["format_version"] == risk_archive.FORMAT_VERSIONS["assess"]


def test_many_distinct_values_are_not_coded(tmp_path):
    path = tmp_path / "a.h5"
    n = 2 * (risk_archive.MAX_CODES + 1)
    rows = [{"id": f"T{i % (risk_archive.MAX_CODES + 1)}", "risk_class": "low"} for i in range(n)]
    risk_archive.write_risk_archive(path, "scenario", {"summary": rows}, {})
    with h5py.File(path) as f:
        assert h5py.check_string_dtype(f["summary/id"].dtype) is not None
        assert f["summary/risk_class"].dtype == np.uint8
    _assert_rows(rows, risk_reader.read_summary(path, "scenario"))


def test_empty_tables_read_back_empty(tmp_path):
    path = tmp_path / "a.h5"
    risk_archive.write_risk_archive(
        path,
        "assess",
        {"summary": _summary(1), "ida": [], "failures": []},
        {},
        empty_columns={"ida": ("tower_id",), "failures": ("kind", "subject", "reason")},
    )
    assert risk_reader.read_ida(path) == [] and risk_reader.read_failures(path) == []
    _assert_rows(_summary(1), risk_reader.read_summary(path))


@pytest.mark.parametrize(
    "craft, expected",
    [
        (lambda ds: ds.attrs.__setitem__("codes", "not json"), "not a coded text column"),
        (lambda ds: ds.attrs.__setitem__("codes", json.dumps([1, 2])), "not a coded text"),
        (lambda ds: ds.attrs.__setitem__("codes", json.dumps(["a"])), "outside its code table"),
    ],
)
def test_a_malformed_code_table_is_refused_in_one_line(tmp_path, craft, expected):
    path = tmp_path / "a.h5"
    risk_archive.write_risk_archive(path, "assess", _tables(), {})
    with h5py.File(path, "r+") as f:
        craft(f["outcomes/status"])
    with pytest.raises(ArchiveError, match=expected) as err:
        risk_reader.read_outcomes(path)
    assert "\n" not in str(err.value) and "/outcomes/status" in str(err.value)


def test_codes_in_a_number_column_are_refused(tmp_path):
    path = tmp_path / "a.h5"
    risk_archive.write_risk_archive(path, "assess", _tables(), {})
    with h5py.File(path, "r+") as f:
        del f["outcomes/scale_factor"]
        f["outcomes/scale_factor"] = np.zeros(len(_outcomes()), dtype=np.uint8)
        f["outcomes/scale_factor"].attrs["codes"] = json.dumps(["1.0"])
    with pytest.raises(ArchiveError, match="holds text where rockscreen writes numbers"):
        risk_reader.read_outcomes(path)


class _Parts:
    """A table given in parts, as the assess work file gives its towers' rows."""

    def __init__(self, rows, size):
        self.rows, self.size = rows, size

    def chunks(self):
        for start in range(0, len(self.rows), self.size):
            yield self.rows[start : start + self.size]

    def __len__(self):
        return len(self.rows)

    def __getitem__(self, index):
        return self.rows[index]


def _datasets(path):
    out = {}
    with h5py.File(path) as f:
        for table in ("stripes", "outcomes", "ida"):
            for name, ds in f[table].items():
                out[f"{table}/{name}"] = (ds.dtype, ds[:].tolist(), dict(ds.attrs), ds.chunks)
            out[table] = dict(f[table].attrs)
    return out


@pytest.mark.parametrize("size", [1, 7, 10_000])
def test_a_table_written_in_parts_is_the_table_written_whole(tmp_path, size):
    tables = {k: v for k, v in _tables().items() if k in ("summary", "stripes", "ida")}
    tables["outcomes"] = _outcomes()
    whole, parts = tmp_path / "whole.h5", tmp_path / "parts.h5"
    risk_archive.write_risk_archive(whole, "assess", tables, {})
    given = {k: (_Parts(v, size) if k != "summary" else v) for k, v in tables.items()}
    risk_archive.write_risk_archive(parts, "assess", given, {})
    a, b = _datasets(whole), _datasets(parts)
    assert a.keys() == b.keys()
    for key in a:
        assert repr(a[key]) == repr(b[key]), key  # repr: NaN equal to NaN
    for name in ("stripes", "outcomes", "ida"):
        _assert_rows(tables[name], getattr(risk_reader, f"read_{name}")(parts))


def test_the_work_file_keeps_the_rows_and_gives_them_back_in_order(tmp_path):
    from rockscreen.pipeline.archive.assess_part import AssessJournal
    from rockscreen.pipeline.archive.kept_rows import JournalRows, KeptRows, light_result

    outcomes = _outcomes()
    results = [
        {
            "index": i,
            "row": {"id": f"T{i:03d}"},
            "n_solves": 3,
            "stripes": [],
            "ida": [r for r in _ida() if r["tower_id"] == f"T{i:03d}"],
            "outcomes": [r for r in outcomes if r["tower_id"] == f"T{i:03d}"],
        }
        for i in range(N_TOWERS)
    ]
    with AssessJournal(tmp_path / "a.h5", {"v": 1}) as journal:
        light = [light_result(item) for item in journal.append(results)]
    assert all(isinstance(item["outcomes"], KeptRows) for item in light)
    assert light[0]["row"] == {"id": "T000"} and light[0]["outcomes"].n == 90
    view = JournalRows(journal, "outcomes")
    for item in reversed(light):  # the archive's order, not the work file's
        view.extend(item["outcomes"])
    assert len(view) == len(outcomes) and view.columns == list(outcomes[0])
    expected = [
        r for i in reversed(range(N_TOWERS)) for r in outcomes if r["tower_id"] == f"T{i:03d}"
    ]
    _assert_rows(expected, list(view))


def test_a_tower_changed_in_the_work_file_is_refused_not_written(tmp_path):
    from rockscreen.pipeline.archive.assess_part import AssessJournal
    from rockscreen.pipeline.archive.kept_rows import JournalRows, light_result

    results = [
        {"index": i, "row": {"id": f"T{i}"}, "n_solves": 1, "stripes": [], "ida": [], "outcomes": [
            {"tower_id": f"T{i}", "theta_max_over_alpha": 0.5}
        ]}
        for i in range(3)
    ]  # fmt: skip
    with AssessJournal(tmp_path / "a.h5", {"v": 1}) as journal:
        light = [light_result(item) for item in journal.append(results)]
    with h5py.File(journal.part, "r+") as f:
        text = f["towers/result"].asstr()[1]
        f["towers/result"][1] = text.replace("0.5", "0.6")
    view = JournalRows(journal, "outcomes")
    for item in light:
        view.extend(item["outcomes"])
    with pytest.raises(ArchiveError, match="tower 1 changed since it was written") as err:
        list(view)
    assert "\n" not in str(err.value)
