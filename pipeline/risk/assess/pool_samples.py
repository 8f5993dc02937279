"""The main process's copy of a pool record: its samples as views of the pool's float32.

The embedded stochastic pools hold their records in float32 (7 significant digits: the
records are rounded so when generated, :mod:`rockscreen.pipeline.hazard.record_pool`), and a
record taken from a pool is a float64 copy of its samples
(:func:`rockscreen.pipeline.hazard.stochastic_suite.pool_record`, about 44 kB). The main
process of ``assess`` keeps every record of every set until the archive is written
(``/records``): at one site per tower about 4,000 records, 175 MB of float64 copies of
numbers its pools already hold. :func:`float32_record` gives the record kept instead, a
:class:`Float32PoolRecord`: the same record whose samples are views of its pool's float32
arrays, read as the same float64 arrays (a copy made on each read), pickled as its place
in the pool as every pool record is. :func:`stored_samples` gives the archive writer the
float32 views themselves (stored as float32 either way: ``record_store.sample_dtype``).
"""

from __future__ import annotations

import dataclasses
from typing import Any

import numpy as np

from rockscreen.pipeline.hazard.record_pool import record_pool
from rockscreen.pipeline.hazard.stochastic_suite import PoolRecord, pool_record

__all__ = ["Float32PoolRecord", "float32_record", "forget_float64_copies", "stored_samples"]

#: The sample fields of a suite record, by pool component.
_FIELDS = {"x": "acc_x_m_s2", "y": "acc_y_m_s2", "z": "acc_z_m_s2"}


def _float64_view(name: str) -> property:
    """Return a property reading a float32 field as a read-only float64 array (None kept)."""

    def get(self: Any) -> np.ndarray | None:
        stored = self.__dict__[name]
        if stored is None:
            return None
        out = stored.astype(np.float64)
        out.setflags(write=False)
        return out

    def put(self: Any, value: Any) -> None:  # the dataclass's __init__ sets the field
        self.__dict__[name] = value

    return property(get, put, doc=f"``{name}`` [m/s²] as float64 (stored float32).")


class Float32PoolRecord(PoolRecord):
    """A pool record whose samples are float32 views of its pool (module docstring).

    Its fields read as the pool record's (the samples as float64 arrays, equal to the
    pool record's); pickled, it is the pool record (its place in the pool).
    """

    acc_x_m_s2 = _float64_view("acc_x_m_s2")  # type: ignore[assignment]
    acc_y_m_s2 = _float64_view("acc_y_m_s2")  # type: ignore[assignment]
    acc_z_m_s2 = _float64_view("acc_z_m_s2")  # type: ignore[assignment]


def float32_record(record: Any) -> Any:
    """Return a pool record as a :class:`Float32PoolRecord`, any other record as it is.

    Parameters
    ----------
    record : SuiteRecord
        A record of a set (a :class:`~rockscreen.pipeline.hazard.stochastic_suite.
        PoolRecord` from a pool, or a user's record).

    Returns
    -------
    SuiteRecord
        The pool record with its samples as views of the pool's float32 arrays when they
        equal its samples exactly; otherwise (a user's record, or samples that differ from
        the pool's) ``record`` itself.
    """
    if type(record) is not PoolRecord or len(record.pool_key) != 4:
        return record
    soil, seed, size, index = record.pool_key
    pool = record_pool(soil, seed, size)
    start, end = int(pool.offsets[index]), int(pool.offsets[index + 1])
    views = {}
    for component, name in _FIELDS.items():
        given = getattr(record, name)
        view = getattr(pool, component)[start:end]
        if given is None or not np.array_equal(view.astype(np.float64), given):
            return record  # not the pool's samples: kept as it is
        views[name] = view
    values = {f.name: getattr(record, f.name) for f in dataclasses.fields(record)}
    return Float32PoolRecord(**{**values, **views})


def stored_samples(record: Any) -> tuple[Any, Any, Any]:
    """Return a record's (x, y, z) samples [m/s²] as kept: float32 views, or its arrays."""
    if isinstance(record, Float32PoolRecord):
        return tuple(record.__dict__[name] for name in _FIELDS.values())  # type: ignore[return-value]
    return record.acc_x_m_s2, record.acc_y_m_s2, record.acc_z_m_s2


def forget_float64_copies() -> None:
    """Empty this process's cache of float64 pool records (:func:`pool_record`'s).

    The main process of ``assess`` keeps its sets' pool records as float32 views
    (:func:`float32_record`); the float64 copies the sets arrived with (up to
    ``stochastic_suite.RECORDS_KEPT``, about 22 MB) are not needed after. A record asked
    for again is taken from its pool again (the same arrays).
    """
    pool_record.cache_clear()
