"""Malformed assess and scenario archives are refused in one line by the one door (issue 24).

The campaign reader checked its tables; the risk readers did not: a short, long, 2-D or
scalar column, a table stored as a dataset, a missing ``id``, a number column of text,
invalid UTF-8 and an oversized text attribute gave tracebacks or a wrong page.
"""

from __future__ import annotations

import h5py
import numpy as np
import pytest

from rockscreen.pipeline.archive import risk_archive, risk_reader
from rockscreen.pipeline.archive.kinds import open_archive
from rockscreen.pipeline.archive.safety import MAX_ATTRIBUTE_BYTES
from rockscreen.pipeline.errors import ArchiveError

from rockscreen_testsupport.cli import run_rockscreen

N = 4


def _archive(path, kind="assess"):
    summary = [
        {
            "id": f"T{i}",
            "name": f"tower {i}",
            "lat_deg": 42.0 + i / 100,
            "lon_deg": 13.4,
            "risk_class": "low",
            "fragility_median_g": 0.3,
            "note": "",
        }
        for i in range(N)
    ]
    failures = [{"kind": "record", "subject": "x", "reason": "y"}]
    return risk_archive.write_risk_archive(
        path, kind, {"summary": summary, "failures": failures}, {}
    )


def _replace(f, name, **kw):
    del f[name]
    f.create_dataset(name, **kw)


def _bad_utf8(f):
    _replace(f, "summary/name", shape=(N,), dtype=h5py.string_dtype("utf-8"))
    f["summary/name"][...] = np.array([b"\xff\xfe bad"] * N, dtype=object)


def _summary_dataset(f):
    del f["summary"]
    f.create_dataset("summary", data=np.arange(3.0))


CRAFTS = {
    "short": (lambda f: _replace(f, "summary/lat_deg", data=[1.0]), "has 1 rows where"),
    "long": (lambda f: _replace(f, "summary/lat_deg", data=np.ones(N + 3)), "rows where"),
    "2-D": (lambda f: _replace(f, "summary/lat_deg", data=np.ones((N, 2))), "1-D"),
    "scalar": (lambda f: _replace(f, "summary/lat_deg", data=1.0), "1-D"),
    "text number": (
        lambda f: _replace(f, "summary/lat_deg", data=["x"] * N, dtype=h5py.string_dtype()),
        "holds text where rockscreen writes numbers",
    ),
    "int id": (lambda f: _replace(f, "summary/id", data=np.arange(N)), "/summary/id holds numbers"),
    "summary dataset": (_summary_dataset, "/summary is a dataset"),
    "no id": (lambda f: f.__delitem__("summary/id"), "lacks column(s) id"),
    "no summary": (lambda f: f.__delitem__("summary"), "table /summary is missing"),
    "no reason": (lambda f: f.__delitem__("failures/reason"), "/failures lacks column(s) reason"),
    "bad utf-8": (_bad_utf8, "not valid UTF-8"),
    "inf latitude": (
        lambda f: f["summary/lat_deg"].__setitem__(1, np.inf),
        "/summary/lat_deg row 1 holds inf, outside [-90, 90]",
    ),
    "columns not json": (
        lambda f: f["summary"].attrs.__setitem__("columns", "[not json"),
        "/summary has a 'columns' attribute that is not the JSON list",
    ),
    "columns not members": (
        lambda f: f["summary"].attrs.__setitem__("columns", '["id", "../../etc"]'),
        "/summary has a 'columns' attribute",
    ),
    "columns not a list": (
        lambda f: f["summary"].attrs.__setitem__("columns", '{"id": 1}'),
        "/summary has a 'columns' attribute",
    ),
    "failures 2-D": (
        lambda f: _replace(
            f, "failures/kind", data=np.array([["a", "b"]], dtype=object), dtype=h5py.string_dtype()
        ),
        "/failures/kind has shape",
    ),
}


@pytest.mark.parametrize("kind", ["assess", "scenario"])
@pytest.mark.parametrize("name", list(CRAFTS))
def test_the_door_refuses_a_malformed_table_in_one_line(tmp_path, kind, name):
    craft, needle = CRAFTS[name]
    path = _archive(tmp_path / "a.h5", kind)
    open_archive(path)  # the sound archive opens
    with h5py.File(path, "r+") as f:
        craft(f)
    with pytest.raises(ArchiveError) as info:
        open_archive(path)
    message = str(info.value)
    assert "\n" not in message and str(path) in message and needle in message


def test_a_long_text_attribute_is_refused(tmp_path):
    path = _archive(tmp_path / "a.h5")
    with h5py.File(path, "r+") as f:
        f.attrs["command_line"] = "x" * (MAX_ATTRIBUTE_BYTES + 4 * 1024**2)
    with pytest.raises(ArchiveError, match="root attribute 'command_line' holds"):
        open_archive(path)


@pytest.mark.parametrize(
    "command",
    [
        ["inspect"],
        ["inspect", "--json"],
        ["report", "--out", "r.html"],
        ["export", "--csv", "o.csv"],
        ["plot", "--map", "--out", "m.png"],
    ],
)
def test_every_command_refuses_a_short_summary_column_in_one_line(tmp_path, command):
    path = _archive(tmp_path / "a.h5")
    with h5py.File(path, "r+") as f:
        _replace(f, "summary/id", data=np.array(["X"], dtype=object), dtype=h5py.string_dtype())
    proc = run_rockscreen(command[0], path, *command[1:], cwd=tmp_path, timeout_s=120)
    lines = proc.stderr.strip().splitlines()
    assert proc.returncode == 1, proc.stderr
    assert len(lines) == 1 and lines[0].startswith("rockscreen: error: "), lines
    assert "/summary/" in lines[0] and "rows where" in lines[0]
    assert not any((tmp_path / name).exists() for name in ("r.html", "o.csv", "m.png"))


def test_the_function_readers_check_the_tables_too(tmp_path):
    path = _archive(tmp_path / "a.h5")
    with h5py.File(path, "r+") as f:
        _replace(f, "summary/lat_deg", data=[1.0])
    with pytest.raises(ArchiveError, match="/summary/lat_deg has 1 rows where"):
        risk_reader.read_summary(path)
    with pytest.raises(ArchiveError, match="rows where"):
        risk_reader.read_failures(path)
    # a crafted column order is refused in one line, not a JSON traceback
    path = _archive(tmp_path / "b.h5")
    with h5py.File(path, "r+") as f:
        f["summary"].attrs["columns"] = "[not json"
    with pytest.raises(ArchiveError, match="'columns' attribute"):
        risk_reader.read_summary(path)


def _with_records(path):
    record = {"x": np.arange(5.0), "y": None, "z": -np.arange(5.0), "dt_s": 0.01}
    summary = [{"id": "T0", "note": ""}]
    return risk_archive.write_risk_archive(
        path, "assess", {"summary": summary}, {}, records={"R-1": {**record, "name": "R"}}
    )


def test_records_read_back_and_malformed_records_refused(tmp_path):
    path = _with_records(tmp_path / "a.h5")
    (record,) = risk_reader.read_records(path).values()
    assert record["dt_s"] == 0.01 and record["y"] is None and record["name"] == "R"
    np.testing.assert_array_equal(record["z"], -np.arange(5.0))

    def set_value(f, name, value):
        f[name][0] = value

    for damage, message in (
        (lambda f: set_value(f, "records/index/dt_s", -1.0), "no positive dt_s"),
        (lambda f: f["records/x"].attrs.__setitem__("units", "g"), "not in m/s2"),
        (
            lambda f: (
                f.__delitem__("records/x"),
                f.create_dataset("records/x", data=[[1.0]]),
            ),
            "not a 1-D float array",
        ),
        (lambda f: set_value(f, "records/index/z_start", 3), "points outside /records/z"),
        (lambda f: set_value(f, "records/index/x_count", 0), "points outside /records/x"),
    ):
        broken = _with_records(tmp_path / "b.h5")
        with h5py.File(broken, "r+") as f:
            damage(f)
        with pytest.raises(ArchiveError, match=message):
            risk_reader.read_records(broken)
    for record, message in (
        ({"x": None, "dt_s": 0.01}, "record 'a' cannot be stored: its x component is absent"),
        ({"x": [1.0], "y": [], "dt_s": 0.01}, "its y component is empty"),
    ):
        with pytest.raises(ArchiveError, match=message):
            risk_archive.write_risk_archive(
                tmp_path / "c.h5", "assess", {"summary": [{"id": "T0"}]}, {}, records={"a": record}
            )
    with pytest.raises(ArchiveError, match="keeps no records"):
        risk_archive.write_risk_archive(
            tmp_path / "d.h5",
            "scenario",
            {"summary": [{"id": "T0"}]},
            {},
            records={"a": {"x": [1.0], "dt_s": 0.01}},
        )
