"""RowTable: rows kept as columns read back exactly as the dict rows they came from."""

from __future__ import annotations

import math

import pytest

from rockscreen.pipeline.risk.assess.row_table import RowTable


def _rows(n, start=0):
    return [
        {
            "tower_id": f"T{(start + i) // 3}",
            "tr_y": 475.0,
            "n": start + i,
            "overturned": bool(i % 2),
            "theta": math.nan if i == 1 else 0.1 * i,
            "note": None if i % 3 else "x",
        }
        for i in range(n)
    ]


def test_rows_read_back_exactly_in_every_way():
    rows = _rows(5) + _rows(4, start=5)
    table = RowTable(_rows(5))
    table.extend(_rows(4, start=5))
    other = RowTable()
    other.extend(table)  # another table's blocks, not copied row by row
    for t in (table, other):
        assert len(t) == 9
        back = list(t)
        for a, b in zip(back, rows, strict=True):
            assert a.keys() == b.keys()
            for key in a:
                assert type(a[key]) is type(b[key]), key
                assert a[key] == b[key] or (a[key] != a[key] and b[key] != b[key])
        assert t[0] == back[0] and t[-1] == back[-1] and t[2:4] == back[2:4]
        assert t.column("n") == [r["n"] for r in rows]
        assert t.column("note") == [r["note"] for r in rows]
    with pytest.raises(IndexError):
        table[9]


def test_columns_take_far_less_memory_than_dicts():
    table = RowTable(_rows(1000))
    assert table.nbytes < 60 * 1000  # 6 columns: 8 bytes a value
