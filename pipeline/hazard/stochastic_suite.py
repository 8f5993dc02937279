"""The stochastic record suite: site-based records that keep their record-to-record scatter.

:func:`stochastic_suite` draws a pool of three-component records of the Rezaeian & Der
Kiureghian (2010) model with velocity pulses
(:func:`rockscreen.pipeline.motion.stochastic.simulate_record`), each from its own scenario
(:func:`suite_scenario`: :data:`STOCHASTIC_SCENARIOS`, V_s30 from :data:`VS30_OF_SOIL`),
selects a set in the pool's order by the code's mean rule
(:func:`rockscreen.pipeline.hazard.selection.select_in_order`) and scales it, never
matching a record. It is the ``kind="stochastic"`` suite of
:func:`rockscreen.pipeline.hazard.suite.site_record_set`; see ``docs/hazard.md``.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from rockscreen.pipeline.hazard.grid import site_hazard
from rockscreen.pipeline.hazard.matching import batch_spectrum
from rockscreen.pipeline.hazard.selection import (
    SuiteRecord,
    select_from_spectra,
    select_in_order,
)
from rockscreen.pipeline.hazard.spectrum import elastic_spectrum, vertical_spectrum
from rockscreen.pipeline.hazard.suite_common import (
    SELECTION_PERIODS_S,
    SUITE_DOCS,
    SYNTHETIC_DT_S,
    frozen,
    suite_key,
)
from rockscreen.pipeline.motion.stochastic import Scenario, simulate_record
from rockscreen.solver.constants import G
from rockscreen.solver.docstrings import fill_doc

__all__ = [
    "STOCHASTIC_RECORDS",
    "STOCHASTIC_SCENARIOS",
    "VS30_OF_SOIL",
    "stochastic_selection",
    "stochastic_suite",
    "suite_scenario",
]

#: Scenario distribution of the stochastic suite: magnitude uniform in [M_min, M_max],
#: rupture distance log-uniform in [R_min, R_max] km, and the faulting indicator F of
#: :class:`~rockscreen.pipeline.motion.stochastic.Scenario`: 1, non-strike-slip, because
#: the seismogenic zones of peninsular Italy that dominate its hazard are mostly normal
#: faulting (ZS9 source model, Meletti et al. 2008; ``docs/hazard.md``).
STOCHASTIC_SCENARIOS = {"magnitude": (5.0, 7.0), "distance_km": (3.0, 100.0), "non_strike_slip": 1}
#: Representative V_s30 [m/s] of the NTC 2018 soil classes (Tab. 3.2.II ranges: A > 800,
#: B 360-800, C 180-360, D 100-180; E: a thin C or D layer on rock).
VS30_OF_SOIL = {"A": 900.0, "B": 580.0, "C": 270.0, "D": 150.0, "E": 270.0}
#: Records of a stochastic stripe (NTC 2018 takes the mean response from 7; 11 give a
#: usable dispersion) and the pool they are selected from, as a multiple.
STOCHASTIC_RECORDS = 11
STOCHASTIC_POOL_FACTOR = 3
#: Largest pool, as a multiple of the set, when no set of the first pool complies (12: L'Aquila
#: on soil B at 2475 y needs 9, the example sites at most 6).
STOCHASTIC_MAX_POOL_FACTOR = 12
#: Periods at which the vertical of a stochastic record is scaled to the code [s].
VERTICAL_PERIODS_S = np.geomspace(0.05, 1.0, 12)


def _seed_key(lon, lat, tr) -> tuple[int, int, int]:
    """Non-negative integers naming a site and return period (part of a record's seed)."""
    return round((lon + 180.0) * 1e4), round((lat + 90.0) * 1e4), round(tr * 1e3)


def suite_scenario(rng: np.random.Generator, soil_class: str) -> Scenario:
    """Draw the scenario of one stochastic record (:data:`STOCHASTIC_SCENARIOS`).

    Parameters
    ----------
    rng : numpy.random.Generator
        Consumed: two uniform draws.
    soil_class : str
        NTC 2018 soil class (A-E): gives V_s30 (:data:`VS30_OF_SOIL`).

    Returns
    -------
    rockscreen.pipeline.motion.stochastic.Scenario
    """
    m_low, m_high = STOCHASTIC_SCENARIOS["magnitude"]
    r_low, r_high = STOCHASTIC_SCENARIOS["distance_km"]
    magnitude = rng.uniform(m_low, m_high)
    distance = math.exp(rng.uniform(math.log(r_low), math.log(r_high)))
    return Scenario(
        float(magnitude),
        float(distance),
        VS30_OF_SOIL[soil_class],
        int(STOCHASTIC_SCENARIOS["non_strike_slip"]),
    )


def _padded(arrays) -> np.ndarray:
    """Stack records of different lengths, zero-padded at the end."""
    n = max(len(a) for a in arrays)
    return np.array([np.pad(a, (0, n - len(a))) for a in arrays])


def _pool_records(seed, key, soil, first, last):
    """Simulate records ``first`` to ``last - 1`` of a pool (each from its own seed)."""
    records = []
    for i in range(first, last):
        rng = np.random.default_rng([seed, *key, i])
        records.append(simulate_record(rng, suite_scenario(rng, soil), SYNTHETIC_DT_S))
    return records


def _select(pool, names, target, n_records):
    """Select in the pool's order, else the best-fitting set (the first that complies)."""
    x = _padded([r.x for r in pool])
    spectra = batch_spectrum(x, SYNTHETIC_DT_S, SELECTION_PERIODS_S) / G
    candidates = [
        SuiteRecord(name, a, None, None, SYNTHETIC_DT_S, "")
        for name, a in zip(names, x, strict=True)
    ]
    chosen = select_in_order(candidates, spectra, SELECTION_PERIODS_S, target, n_records=n_records)
    if not chosen.meets_tolerance:  # no random-order set fits: the best-fitting set of the pool
        best = select_from_spectra(
            candidates, spectra, SELECTION_PERIODS_S, target, n_records=n_records
        )
        chosen = best if best.meets_tolerance else chosen
    return chosen


@lru_cache(maxsize=64)
def _cached_stochastic(lon, lat, tr, soil, topography, n_records, seed):
    """Return the chosen records at the model amplitude (vertical in proportion), factors."""
    site = site_hazard(lon, lat, tr)
    target = elastic_spectrum(SELECTION_PERIODS_S, site, soil, topography)
    key = _seed_key(lon, lat, tr)
    pool = _pool_records(seed, key, soil, 0, STOCHASTIC_POOL_FACTOR * n_records)
    names = [f"STO-{seed}-{i:02d}" for i in range(len(pool))]
    chosen = _select(pool, names, target, n_records)
    # No compliant set: the pool grows by n records at a time (earlier records unchanged).
    while not chosen.meets_tolerance and len(pool) < STOCHASTIC_MAX_POOL_FACTOR * n_records:
        pool += _pool_records(seed, key, soil, len(pool), len(pool) + n_records)
        names = [f"STO-{seed}-{i:02d}" for i in range(len(pool))]
        chosen = _select(pool, names, target, n_records)
    n = max(len(r.x) for r in pool)
    indices = [names.index(r.name) for r in chosen.records]
    z = _padded([pool[i].z for i in indices] + [np.zeros(n)])[:-1]
    vertical_target = vertical_spectrum(VERTICAL_PERIODS_S, site, soil, topography)
    vertical_sa = batch_spectrum(z, SYNTHETIC_DT_S, VERTICAL_PERIODS_S) / G
    suite = []
    for k, (i, factor) in enumerate(zip(indices, chosen.scale_factors, strict=True)):
        record = pool[i]
        factor_v = float(np.exp(np.mean(np.log(vertical_target / vertical_sa[k]))))
        p, sc = record.parameters, record.scenario
        pulse = (
            "no pulse"
            if record.pulse is None
            else f"pulse T_p={record.pulse.period_s:.2f} s gamma={record.pulse.gamma:.2f}"
        )
        source = (
            f"stochastic (Rezaeian & Der Kiureghian 2010; M={sc.magnitude:.2f} "
            f"R={sc.distance_km:.1f} km Vs30={sc.vs30_m_s:g} m/s F={sc.non_strike_slip}; "
            f"D5-95={p.d5_95_s:.1f} s "
            f"t_mid={p.t_mid_s:.1f} s f_mid={p.f_mid_hz:.2f} Hz f'={p.f_slope_hz_s:.3f} Hz/s "
            f"zeta_f={p.zeta_f:.2f}; {pulse}; seed=({seed}, {key}, {i})), selected for "
            f"lon={lon:g} lat={lat:g} TR={tr:g} y soil {soil} {topography}"
        )
        suite.append(
            SuiteRecord(
                names[i],
                frozen(np.pad(record.x, (0, n - len(record.x)))),
                frozen(np.pad(record.y, (0, n - len(record.y)))),
                frozen(z[k] * (factor_v / float(factor))),
                SYNTHETIC_DT_S,
                source,
            )
        )
    return tuple(suite), tuple(float(f) for f in chosen.scale_factors)


@fill_doc(SUITE_DOCS)
def stochastic_selection(
    lon_deg: float,
    lat_deg: float,
    return_period_y: float,
    soil_class: str = "A",
    topography: str = "T1",
    *,
    n_records: int = STOCHASTIC_RECORDS,
    seed: int = 0,
) -> list[SuiteRecord]:
    """Return the records :func:`stochastic_suite` chooses, before their scale factor.

    The horizontals are at the model's amplitude, the vertical in proportion (times its
    own factor over the horizontals'), so that one factor per record, applied by
    :func:`rockscreen.pipeline.hazard.selection.select_records`, gives the suite's scaling
    without applying the factor caps twice. This is what
    :func:`rockscreen.pipeline.hazard.suite.site_record_set` selects from.

    Parameters
    ----------
    %(site)s
    n_records : int
        Number of records (11 by default).
    seed : int
        Seed of the suite (with the site, TR and record index).

    Returns
    -------
    list of SuiteRecord
        Three components each [m/s²], dt 0.01 s, zero-padded to one length; read-only.

    %(raises)s
    """
    key = suite_key(lon_deg, lat_deg, return_period_y, soil_class, topography, n_records, seed)
    return list(_cached_stochastic(*key)[0])


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
    """Return site-based stochastic records selected and scaled by the code's mean rule.

    A pool of ``3 n_records`` three-component records of the Rezaeian & Der Kiureghian
    (2010) model with velocity pulses
    (:func:`rockscreen.pipeline.motion.stochastic.simulate_record`), each from its own
    scenario (:func:`suite_scenario`) and seed ``(seed, site, TR, index)``; the first
    ``n_records`` are kept and swapped for later ones only while their scaled mean
    departs from the NTC 2018 band (:func:`rockscreen.pipeline.hazard.selection.select_in_order`);
    when that finds no compliant set, the best-fitting set of the pool
    (:func:`rockscreen.pipeline.hazard.selection.select_from_spectra`) is used if it complies.
    Every record keeps its own spectral shape: it is amplitude-scaled, never matched. The
    vertical is scaled to the code's vertical spectrum (least squares in logs over
    0.05-1 s).

    Parameters
    ----------
    %(site)s
    n_records : int
        Number of records (11 by default).
    seed : int
        Seed of the suite (with the site, TR and record index).

    Returns
    -------
    list of SuiteRecord
        Three components each [m/s²], dt 0.01 s, zero-padded to one length; read-only.

    %(raises)s
    """
    key = suite_key(lon_deg, lat_deg, return_period_y, soil_class, topography, n_records, seed)
    records, factors = _cached_stochastic(*key)
    return [
        SuiteRecord(
            r.name,
            frozen(r.acc_x_m_s2 * f),
            frozen(r.acc_y_m_s2 * f),
            frozen(r.acc_z_m_s2 * f),
            r.dt_s,
            f"{r.source}, scaled by {f:.3g}",
        )
        for r, f in zip(records, factors, strict=True)
    ]
