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
