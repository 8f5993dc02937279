"""What the main process of ``assess`` keeps until the archive is written (issue 30: memory).

Each pool record once (:class:`~rockscreen.pipeline.risk.assess.plan.KeptRecords`: the sets
arriving from the workers take the first object of each record, whatever the record cache
kept), the sets' references by column
(:class:`~rockscreen.pipeline.risk.assess.plan.References`) and the ``/selection`` rows as a
:class:`~rockscreen.pipeline.risk.assess.row_table.RowTable`, each reading back exactly as
the tuples and dicts they replace.
"""

from __future__ import annotations

import pickle

import numpy as np

from rockscreen.pipeline.hazard.stochastic_suite import pool_record
from rockscreen.pipeline.hazard.suite import site_record_set
from rockscreen.pipeline.risk.assess.plan import (
    KeptRecords,
    References,
    record_id,
    set_references,
)
from rockscreen.pipeline.risk.assess.row_table import RowTable


def _arrived(record_set):
    """The set as the main process receives it from a worker (pickled, records by key)."""
    return pickle.loads(pickle.dumps(record_set))


def test_every_set_holds_the_same_object_of_a_record_and_its_id_is_digested_once():
    sets = [site_record_set(13.40, 42.35, tr, "B", kind="stochastic") for tr in (30.0, 50.0, 475.0)]
    kept = KeptRecords()
    first = [kept.kept(_arrived(s)) for s in sets]
    pool_record.cache_clear()  # the record cache forgot them: other objects arrive
    arrived = [_arrived(s) for s in sets]
    assert arrived[0].records[0] is not first[0].records[0]
    again = [kept.kept(s) for s in arrived]  # the same sets arriving twice
    for a, b, original in zip(first, again, sets, strict=True):
        assert all(x is y for x, y in zip(a.records, b.records, strict=True))
        assert np.array_equal(a.scale_factors, original.scale_factors)
        for x, y in zip(a.records, original.records, strict=True):
            assert x.pool_key == y.pool_key and np.array_equal(x.acc_x_m_s2, y.acc_x_m_s2)
            assert kept.id_of(x) == record_id(y)
    record = first[0].records[0]
    assert kept.id_of(record) is kept.id_of(record)  # digested once


def test_references_read_back_as_the_tuples_they_keep():
    record_set = site_record_set(13.40, 42.35, 475.0, "B", kind="stochastic")
    expected = set_references(0, record_set) + set_references(7, record_set)
    references = References()
    references.extend(set_references(0, record_set))
    references.extend([])
    references.extend(set_references(7, record_set))
    assert len(references) == len(expected) == 2 * len(record_set.records)
    assert list(references) == expected and references == expected
    assert references[len(record_set.records)] == expected[len(record_set.records)]
    assert all(type(f) is float and type(r) is int for r, _, f in references)


def test_a_row_table_equals_the_rows_it_holds():
    rows = [{"a": 1.5, "b": "x", "c": True}, {"a": 2.0, "b": "y", "c": False}]
    table = RowTable(rows[:1])
    table.extend(rows[1:])
    assert table == rows and table == RowTable(rows) and RowTable() == []
    assert table != rows[:1] and table != [{**rows[0], "a": 1.0}, rows[1]]


def test_a_kept_pool_record_reads_as_the_pool_record_from_its_pools_float32():
    """The main process keeps a pool record's samples as views of its pool's float32 arrays
    (no float64 copy); they read as the pool record's float64 samples, it pickles as the
    pool record, and the archive is given the float32 views."""
    from rockscreen.pipeline.hazard.record_pool import record_pool
    from rockscreen.pipeline.hazard.selection import SuiteRecord
    from rockscreen.pipeline.risk.assess.pool_samples import (
        Float32PoolRecord,
        float32_record,
        stored_samples,
    )

    record_set = _arrived(site_record_set(13.40, 42.35, 475.0, "B", kind="stochastic"))
    kept = KeptRecords().kept(record_set)
    original, light = record_set.records[0], kept.records[0]
    assert isinstance(light, Float32PoolRecord) and light.pool_key == original.pool_key
    pool = record_pool(*original.pool_key[:3])
    names = ("acc_x_m_s2", "acc_y_m_s2", "acc_z_m_s2")
    for name, x in zip(names, stored_samples(light), strict=True):
        value = getattr(light, name)
        assert value.dtype == np.float64 and not value.flags.writeable
        assert np.array_equal(value, getattr(original, name))
        assert x.dtype == np.float32 and np.shares_memory(x, pool.x) | np.shares_memory(
            x, pool.y
        ) | np.shares_memory(x, pool.z)
    assert (light.name, light.dt_s, light.source) == (original.name, original.dt_s, original.source)
    assert record_id(light) == record_id(original)
    back = pickle.loads(pickle.dumps(light))
    assert type(back) is not Float32PoolRecord and np.array_equal(
        back.acc_x_m_s2, original.acc_x_m_s2
    )
    user = SuiteRecord("user", np.array([0.1, 0.2]), None, None, 0.01, "file")
    assert float32_record(user) is user  # not a pool record: kept as it is


class _Rows:
    """A work file's summary rows (:meth:`AssessJournal.rows`), counting what is read."""

    def __init__(self, rows):
        self.stored, self.reads = rows, []

    def rows(self, indices):
        self.reads.append(list(indices))
        return [dict(self.stored[i]) for i in indices]


def test_a_journal_summary_reads_kept_rows_back_a_part_at_a_time_and_completes_them():
    from rockscreen.pipeline.archive.kept_rows import JournalSummary

    stored = {i: {"id": f"T{i}", "x": float(i)} for i in range(5)}
    journal = _Rows(stored)
    table = JournalSummary(journal, lambda i, row: row.update(risk=10 * i), part=2)
    for i in (0, 1):
        table.append_kept(i)
    table.append({"id": "lost", "x": None})  # a row kept in memory (a tower not assessed)
    for i in (3, 4):
        table.append_kept(i)
    parts = list(table.chunks())
    assert [len(p) for p in parts] == [2, 2, 1] and len(table) == 5
    assert journal.reads == [[0, 1], [3], [4]]
    assert [r["id"] for r in table] == ["T0", "T1", "lost", "T3", "T4"]
    assert table[3] == {"id": "T3", "x": 3.0, "risk": 30}
    assert table[2] == {"id": "lost", "x": None}
