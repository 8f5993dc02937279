"""The stochastic record suite: site-based records that keep their record-to-record scatter.

A site's set is drawn from a shared pool
(:func:`rockscreen.pipeline.hazard.record_pool.record_pool`:
:data:`~rockscreen.pipeline.hazard.record_pool.POOL_SIZE` three-component records of the
Rezaeian & Der Kiureghian (2010) model with velocity pulses per soil class and seed,
generated once, their spectra with them, and cached per user on disk): the records are
chosen and amplitude-scaled for the site's code spectrum
(:func:`rockscreen.pipeline.hazard.centred_selection.select_centred`: every set starts from
the pool's own order, the same at every site and return period, and swaps records only
until the mean lies well inside the NTC 2018 §3.2.3.6 band), never matched. Sets of one
pool therefore share records across sites and return periods (the archive stores each
once). It is the ``kind="stochastic"`` suite of
:func:`rockscreen.pipeline.hazard.suite.site_record_set`; see ``docs/hazard.md``.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from rockscreen.pipeline.hazard.centred_selection import centred_set, select_centred
from rockscreen.pipeline.hazard.grid import site_hazard
from rockscreen.pipeline.hazard.record_pool import (
    POOL_SIZE,
    STOCHASTIC_SCENARIOS,
    VS30_OF_SOIL,
    pool_spectra,
    record_pool,
    suite_scenario,
)
from rockscreen.pipeline.hazard.selection import (
    N_MATCH_PERIODS,
    SCALE_LIMITS,
    RecordSet,
    SuiteRecord,
    check_options,
)
from rockscreen.pipeline.hazard.spectrum import elastic_spectrum
from rockscreen.pipeline.hazard.suite_common import (
    SUITE_DOCS,
    SYNTHETIC_DT_S,
    frozen,
    suite_key,
)
from rockscreen.solver.docstrings import fill_doc

__all__ = [
    "PoolRecord",
    "STOCHASTIC_RECORDS",
    "STOCHASTIC_SCENARIOS",
    "VS30_OF_SOIL",
    "pool_record",
    "stochastic_record_set",
    "stochastic_suite",
    "suite_scenario",
]

#: Records of a stochastic stripe (NTC 2018 takes the mean response from 7; 11 give a
#: usable dispersion).
STOCHASTIC_RECORDS = 11


@dataclass(frozen=True)
class PoolRecord(SuiteRecord):
    """A record of a shared pool: pickled as its place in the pool, not as its samples.

    A set sent between processes (the workers of ``assess --jobs`` and the main process)
    carries ``(soil, seed, size, index)`` per record; the receiving process takes the
    record from its own copy of the pool (memory, the disk cache, or generated: the same
    arrays) through :func:`pool_record`, so the sets of a chunk of towers share them.
    """

    #: ``(soil_class, seed, size, index)``: where the record is in its pool.
    pool_key: tuple = ()

    def __reduce__(self):
        return pool_record, self.pool_key


#: Records :func:`pool_record` keeps (float64 copies of the pool's float32 samples, about
#: 44 kB each): the sets of the last few sites. A worker of ``assess`` at one site per tower
#: met most of a pool's 1,200 records when each set started from its own random order (now
#: that sets share records, 100 towers at their own sites use 588 of the four pools'); keeping
#: them all cost about 190 MB per process (issue 30), taking one again from the pool costs
#: microseconds and gives the same arrays.
RECORDS_KEPT = 512
#: Record sets :func:`stochastic_record_set` keeps (each holds its records).
SETS_KEPT = 16


@lru_cache(maxsize=RECORDS_KEPT)
def pool_record(soil_class: str, seed: int, size: int, index: int) -> PoolRecord:
    """Return record ``index`` of a pool (read-only arrays; the last :data:`RECORDS_KEPT` kept).

    Parameters
    ----------
    soil_class : str
        Soil class of the pool (A-E).
    seed, size : int
        The pool's seed and size (:func:`rockscreen.pipeline.hazard.record_pool.record_pool`).
    index : int
        The record's place in the pool.

    Returns
    -------
    PoolRecord
        Named ``STO-<seed>-<V_s30>-<index>``; unscaled, three components [m/s²].
    """
    pool = record_pool(soil_class, seed, size)
    x, y, z = pool.record(index)
    name = f"STO-{pool.seed}-{pool.vs30_m_s:g}-{index:03d}"
    key = (str(soil_class), int(seed), int(size), int(index))
    return PoolRecord(name, x, y, z, SYNTHETIC_DT_S, pool.source(index), key)


@lru_cache(maxsize=SETS_KEPT)
def _cached_set(lon, lat, tr, soil, topography, n_records, seed, options) -> RecordSet:
    period_range, tolerance, damping, scale_limits = options
    periods = np.geomspace(period_range[0], period_range[1], N_MATCH_PERIODS)
    target = elastic_spectrum(periods, site_hazard(lon, lat, tr), soil, topography, damping)
    spectra = pool_spectra(soil, seed, POOL_SIZE, tuple(periods), damping)
    # Candidates in the pool's own order, the same for every site and return period (its
    # records are independent draws, so it is as random as any): sets share the first ones.
    chosen, factors = select_centred(
        spectra,
        target,
        n_records=n_records,
        tolerance=tolerance,
        scale_limits=scale_limits,
    )
    records = [pool_record(soil, seed, POOL_SIZE, int(i)) for i in chosen]
    return centred_set(
        records,
        spectra[chosen],
        frozen(periods),
        frozen(target),
        frozen(factors),
        tolerance=tolerance,
        wanted=n_records,
    )


@fill_doc(SUITE_DOCS)
def stochastic_record_set(
    lon_deg: float,
    lat_deg: float,
    return_period_y: float,
    soil_class: str = "A",
    topography: str = "T1",
    *,
    n_records: int = STOCHASTIC_RECORDS,
    seed: int = 0,
    period_range_s: tuple[float, float] = (0.15, 2.0),
    tolerance: tuple[float, float] = (-0.10, 0.30),
    damping: float = 0.05,
    scale_limits: tuple[float, float] = SCALE_LIMITS,
) -> RecordSet:
    """Return a site's set of the stochastic suite: chosen from the shared pool and scaled.

    The pool of the site's soil class and ``seed``
    (:func:`rockscreen.pipeline.hazard.record_pool.record_pool`) is taken in its own order
    (record 0, 1, ...: independent draws, so a random order, and the same for every site,
    return period and topography), and
    :func:`rockscreen.pipeline.hazard.centred_selection.select_centred` keeps its first
    ``n_records`` candidates (the records whose own factor suits the site's amplitude),
    swapping them for the next ones while the scaled mean lies outside the NTC 2018
    §3.2.3.6 band narrowed by
    :data:`~rockscreen.pipeline.hazard.centred_selection.AIM_MARGIN`. Sets of similar
    amplitude therefore start from the same records and differ only where the site's
    spectral shape needs a swap: they share records across sites and return periods. Each
    record keeps its own spectral shape: one factor scales its three components. The same
    arguments give the same set; another ``seed`` draws another pool.

    Parameters
    ----------
    %(site)s
    n_records : int
        Number of records (11 by default).
    seed : int
        Seed of the pool (>= 0).
    period_range_s : (float, float)
        Matching range [s].
    tolerance : (float, float)
        Allowed relative departure of the mean below and above the target [-].
    damping : float
        Damping ratio of the spectra [-].
    scale_limits : (float, float)
        Smallest and largest factor of a record [-].

    Returns
    -------
    RecordSet
        The records unscaled (read-only arrays, each its own length), their factors, the
        mean and target at ``N_MATCH_PERIODS`` periods over the range.

    %(raises)s
    """
    check_options(n_records, period_range_s, tolerance, scale_limits)
    key = suite_key(lon_deg, lat_deg, return_period_y, soil_class, topography, n_records, seed)
    options = (
        tuple(float(p) for p in period_range_s),
        tuple(float(t) for t in tolerance),
        float(damping),
        tuple(float(s) for s in scale_limits),
    )
    return _cached_set(*key, options)


@fill_doc(SUITE_DOCS)
def stochastic_suite(
    lon_deg: float,
    lat_deg: float,
    return_period_y: float,
    soil_class: str = "A",
    topography: str = "T1",
    *,
    n_records: int = STOCHASTIC_RECORDS,
    seed: int = 0,
) -> list[SuiteRecord]:
    """Return site-based stochastic records, selected from the shared pool and scaled.

    The set of :func:`stochastic_record_set` (default matching options) with each record's
    factor applied to its three components. Every record keeps its own spectral shape: it
    is amplitude-scaled, never matched.

    Parameters
    ----------
    %(site)s
    n_records : int
        Number of records (11 by default).
    seed : int
        Seed of the pool.

    Returns
    -------
    list of SuiteRecord
        Three components each [m/s²], dt 0.01 s, each record its own length; read-only.

    %(raises)s
    """
    chosen = stochastic_record_set(
        lon_deg,
        lat_deg,
        return_period_y,
        soil_class,
        topography,
        n_records=n_records,
        seed=seed,
    )
    return [
        SuiteRecord(
            r.name,
            frozen(r.acc_x_m_s2 * f),
            frozen(r.acc_y_m_s2 * f),
            frozen(r.acc_z_m_s2 * f),
            r.dt_s,
            f"{r.source}, scaled by {f:.3g}",
        )
        for r, f in zip(chosen.records, chosen.scale_factors, strict=True)
    ]
