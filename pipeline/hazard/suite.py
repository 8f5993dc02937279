"""The embedded record suite: spectrum-matched synthetic accelerograms, and a site's record set.

For users without records, :func:`synthetic_suite` generates accelerograms compatible with
the code spectrum at a site (NTC 2018 §3.2.3.6 admits synthetic accelerograms):

1. a pool of ``POOL_FACTOR * n_records`` records of the project's stochastic model
   (:func:`rockscreen.pipeline.motion.synthetic.stochastic_accelerogram`: white noise, seeded,
   Saragoni-Hart envelope, Kanai-Tajimi ground filter, Clough-Penzien high-pass) with
   ground frequencies from 1.5 to 5 Hz and strong-motion durations from 8 to 20 s, so the
   pool varies in frequency content and duration;
2. each horizontal is matched to a spectral *shape* by iterative frequency-domain scaling
   (:func:`rockscreen.pipeline.hazard.matching.match_records`, the whole pool at once): its 5 %
   spectrum at ``MATCH_PERIODS_S`` is compared with the shape, the ratio multiplies the
   Fourier amplitudes at f = 1/T, phases unchanged; ``MATCH_ITERATIONS`` passes. The
   shape of Se(T) / (ag S) depends only on T_C, T_D and F0 (F0 below T_B), so a pool is
   matched once per shape with T_C rounded to ``SHAPE_STEPS[0]`` in ln T_C, T_D to
   ``SHAPE_STEPS[1]`` s and F0 to ``SHAPE_STEPS[2]`` (cached in memory): the return
   periods of a site, and nearby sites, share pools;
3. the pool is scaled linearly to the site's target (one factor, the geometric mean of
   target / shape over the selection periods) and
   :func:`rockscreen.pipeline.hazard.selection.select_from_spectra` picks the ``n_records`` best; if
   their mean is not inside the NTC band by ``REUSE_MARGIN``, the pool is matched again
   to the site's exact shape and the selection repeated;
4. the chosen records get a second horizontal (another realisation, matched to the same
   shape) and a vertical matched to the vertical shape (§3.2.3.2.2: fixed corners, so one
   vertical pool serves every site), scaled the same way.

Every call with the same arguments gives the same records (cached in memory per site,
return period, soil, topography, size and seed; which pool serves them depends on these
arguments only). The records are synthetic: their spectra match the code, but they carry
no near-source velocity pulse and a duration that is a model choice; see
``docs/hazard.md``.
"""

from __future__ import annotations

import math
from functools import lru_cache
from typing import NamedTuple

import numpy as np

from rockscreen.pipeline.errors import HazardError
from rockscreen.pipeline.hazard.grid import SiteHazard, site_hazard
from rockscreen.pipeline.hazard.matching import batch_spectrum, match_records
from rockscreen.pipeline.hazard.selection import (
    N_MATCH_PERIODS,
    RecordSet,
    SuiteRecord,
    select_from_spectra,
    select_in_order,
    select_records,
)
from rockscreen.pipeline.hazard.spectrum import (
    elastic_spectrum,
    spectrum_parameters,
    vertical_spectrum,
)
from rockscreen.pipeline.motion.stochastic import Scenario, simulate_record
from rockscreen.pipeline.motion.synthetic import stochastic_accelerogram
from rockscreen.solver.constants import G

__all__ = [
    "MATCH_PERIODS_S",
    "STOCHASTIC_SCENARIOS",
    "SUITE_KINDS",
    "SYNTHETIC_DT_S",
    "VS30_OF_SOIL",
    "site_record_set",
    "stochastic_suite",
    "suite_scenario",
    "synthetic_suite",
    "target_spectrum",
]

#: The embedded suites: ``matched`` (:func:`synthetic_suite`, the default) and
#: ``stochastic`` (:func:`stochastic_suite`).
SUITE_KINDS = ("matched", "stochastic")
#: Scenario distribution of the stochastic suite: magnitude uniform in [M_min, M_max],
#: rupture distance log-uniform in [R_min, R_max] km (``docs/hazard.md``).
STOCHASTIC_SCENARIOS = {"magnitude": (5.0, 7.0), "distance_km": (3.0, 100.0)}
#: Representative V_s30 [m/s] of the NTC 2018 soil classes (Tab. 3.2.II ranges: A > 800,
#: B 360-800, C 180-360, D 100-180; E: a thin C or D layer on rock).
VS30_OF_SOIL = {"A": 900.0, "B": 580.0, "C": 270.0, "D": 150.0, "E": 270.0}
#: Records of a stochastic stripe (NTC 2018 takes the mean response from 7; 11 give a
#: usable dispersion) and the pool they are selected from, as a multiple.
STOCHASTIC_RECORDS = 11
STOCHASTIC_POOL_FACTOR = 3
#: Periods at which the vertical of a stochastic record is scaled to the code [s].
VERTICAL_PERIODS_S = np.geomspace(0.05, 1.0, 12)

#: Time step and duration of the synthetic records [s].
SYNTHETIC_DT_S = 0.01
SYNTHETIC_DURATION_S = 25.0
#: Periods at which the records are matched [s]: beyond the default 0.15-2.0 s range on
#: both sides, so that a range up to 3 s can be selected from the same suite.
MATCH_PERIODS_S = np.geomspace(0.05, 4.0, 28)
#: Passes of the frequency-domain matching.
MATCH_ITERATIONS = 4
#: Pool size as a multiple of the set size.
POOL_FACTOR = 2
#: Periods at which target spectra are given to the selection [s].
TARGET_PERIODS_S = np.geomspace(0.02, 5.0, 120)
#: Periods at which the suite's own selection is made [s] (``select_records``' default).
SELECTION_PERIODS_S = np.geomspace(0.15, 2.0, N_MATCH_PERIODS)
#: Rounding of the spectral shape a pool is matched to: ln T_C [-], T_D [s], F0 [-].
SHAPE_STEPS = (0.1, 0.1, 0.1)
#: A pool matched to the rounded shape is kept when its set's mean / target lies inside
#: the NTC band narrowed by this much on both sides [-]; else it is matched exactly.
REUSE_MARGIN = 0.02
#: Site whose vertical spectrum is the vertical shape (the same for every site from
#: 0.05 s, where ``MATCH_PERIODS_S`` starts).
_VERTICAL_SITE = SiteHazard(0.0, 0.0, 0.0, 0.1, 2.5, 0.3)


def target_spectrum(
    lon_deg, lat_deg, return_period_y, soil_class="A", topography="T1", damping=0.05
):
    """Return the code target spectrum at a site (NTC 2018 §3.2.3.2.1).

    Parameters
    ----------
    lon_deg, lat_deg : float
        Site [deg].
    return_period_y : float
        TR [years].
    soil_class, topography : str
        Categories (A-E, T1-T4).
    damping : float
        Damping ratio [-].

    Returns
    -------
    periods_s : numpy.ndarray
        :data:`TARGET_PERIODS_S` [s].
    sa_g : numpy.ndarray
        Se [g].
    """
    site = site_hazard(lon_deg, lat_deg, return_period_y)
    return TARGET_PERIODS_S.copy(), elastic_spectrum(
        TARGET_PERIODS_S, site, soil_class, topography, damping
    )


def _pool_record(rng, pga_m_s2, ground_frequency, duration):
    n = round(SYNTHETIC_DURATION_S / SYNTHETIC_DT_S)
    return stochastic_accelerogram(
        rng,
        n_samples=n,
        dt=SYNTHETIC_DT_S,
        pga=pga_m_s2,
        ground_frequency=ground_frequency,
        ground_damping=0.6,
        envelope_duration=duration,
        onset=1.0,
    )


def _frozen(acc):
    acc = np.asarray(acc, float)
    acc.setflags(write=False)
    return acc


def _pool_parameters(n_pool):
    """Ground frequencies [Hz] and strong-motion durations [s] of the pool's records."""
    return np.geomspace(1.5, 5.0, n_pool), np.linspace(8.0, 20.0, n_pool)[::-1]


@lru_cache(maxsize=32)
def _generated(seed, n_pool, stream):
    """Unmatched records of realisation ``stream`` (0 = x, 1 = y, 2 = z), PGA 1 g."""
    frequencies, durations = _pool_parameters(n_pool)
    factor = 1.5 if stream == 2 else 1.0  # verticals: higher frequency content
    records = []
    for i in range(n_pool):
        rng = np.random.default_rng([seed, i] if stream == 0 else [seed, i, stream])
        records.append(_pool_record(rng, G, factor * frequencies[i], durations[i]))
    return _frozen(np.array(records))


def _shape_of(site, soil, topography):
    """(T_C [s], T_D [s], F0 [-]): what the shape of Se(T) / (ag S) depends on."""
    p = spectrum_parameters(site, soil, topography)
    return p.TC_s, p.TD_s, site.F0


def _rounded(shape):
    """Return the shape rounded to :data:`SHAPE_STEPS` (the key of a shared pool)."""
    (tc, td, f0), (s_tc, s_td, s_f0) = shape, SHAPE_STEPS
    return (
        round(math.exp(round(math.log(tc) / s_tc) * s_tc), 6),
        round(max(round(td / s_td) * s_td, 1.65), 6),
        round(max(round(f0 / s_f0) * s_f0, 1.0), 6),
    )


def _shape_site(shape):
    """Return a site whose soil-A, T1 spectrum has the shape (T_C = T*C, T_D = 4 ag + 1.6)."""
    tc, td, f0 = shape
    return SiteHazard(0.0, 0.0, 0.0, (td - 1.6) / 4.0, f0, tc)


class _Pool(NamedTuple):
    x: np.ndarray  # matched first horizontals (records, samples) [m/s²]
    y: np.ndarray  # matched second horizontals [m/s²]
    spectra_g: np.ndarray  # spectra of x at SELECTION_PERIODS_S [g]
    reference_g: np.ndarray  # the shape at SELECTION_PERIODS_S [g]


@lru_cache(maxsize=128)
def _matched_pool(shape, n_pool, seed):
    """Return the pool matched to one spectral shape (read-only arrays)."""
    site = _shape_site(shape)
    both = np.concatenate([_generated(seed, n_pool, 0), _generated(seed, n_pool, 1)])
    matched = match_records(
        both,
        SYNTHETIC_DT_S,
        MATCH_PERIODS_S,
        elastic_spectrum(MATCH_PERIODS_S, site),
        iterations=MATCH_ITERATIONS,
    )
    x, y = matched[:n_pool], matched[n_pool:]
    spectra = batch_spectrum(x, SYNTHETIC_DT_S, SELECTION_PERIODS_S) / G
    reference = elastic_spectrum(SELECTION_PERIODS_S, site)
    return _Pool(_frozen(x), _frozen(y), _frozen(spectra), _frozen(reference))


@lru_cache(maxsize=16)
def _verticals(n_pool, seed):
    """Return the verticals of the whole pool, matched to the vertical shape."""
    target = vertical_spectrum(MATCH_PERIODS_S, _VERTICAL_SITE)
    acc = _generated(seed, n_pool, 2)
    return _frozen(
        match_records(acc, SYNTHETIC_DT_S, MATCH_PERIODS_S, target, iterations=MATCH_ITERATIONS)
    )


def _select_from_pool(shape, target, n_records, seed):
    """Scale the pool matched to ``shape`` to ``target`` and select; (pool, factor, set)."""
    pool = _matched_pool(shape, POOL_FACTOR * n_records, seed)
    factor = float(np.exp(np.mean(np.log(target / pool.reference_g))))
    candidates = [
        SuiteRecord(f"SYN-{seed}-{i:02d}", a, None, None, SYNTHETIC_DT_S, "")
        for i, a in enumerate(pool.x)
    ]
    chosen = select_from_spectra(
        candidates, pool.spectra_g * factor, SELECTION_PERIODS_S, target, n_records=n_records
    )
    return pool, factor, chosen


@lru_cache(maxsize=64)
def _cached_suite(lon, lat, tr, soil, topography, n_records, seed):
    site = site_hazard(lon, lat, tr)
    target = elastic_spectrum(SELECTION_PERIODS_S, site, soil, topography)
    exact = _shape_of(site, soil, topography)
    shape = _rounded(exact)
    pool, factor, chosen = _select_from_pool(shape, target, n_records, seed)
    low, high = 0.9 + REUSE_MARGIN, 1.3 - REUSE_MARGIN
    if not (low <= chosen.ratio_min and chosen.ratio_max <= high):
        shape = exact
        pool, factor, chosen = _select_from_pool(shape, target, n_records, seed)
    n_pool = POOL_FACTOR * n_records
    indices = tuple(int(r.name.rsplit("-", 1)[1]) for r in chosen.records)
    vertical = _verticals(n_pool, seed)
    reference_v = vertical_spectrum(MATCH_PERIODS_S, _VERTICAL_SITE)
    actual_v = vertical_spectrum(MATCH_PERIODS_S, site, soil, topography)
    factor_v = float(np.exp(np.mean(np.log(actual_v / reference_v))))
    frequencies, durations = _pool_parameters(n_pool)
    suite = []
    for record, i in zip(chosen.records, indices, strict=True):
        source = (
            f"synthetic (Kanai-Tajimi/Clough-Penzien/Saragoni-Hart, f_g={frequencies[i]:.2f} Hz, "
            f"t_n={durations[i]:.1f} s, seed=({seed}, {i})), matched to the NTC 2018 shape "
            f"T_C={shape[0]:.4g} s T_D={shape[1]:.4g} s F0={shape[2]:.4g} and scaled to "
            f"lon={lon:g} lat={lat:g} TR={tr:g} y soil {soil} {topography}"
        )
        suite.append(
            SuiteRecord(
                record.name,
                _frozen(record.acc_x_m_s2 * factor),
                _frozen(pool.y[i] * factor),
                _frozen(vertical[i] * factor_v),
                SYNTHETIC_DT_S,
                source,
            )
        )
    return tuple(suite)


def synthetic_suite(
    lon_deg: float,
    lat_deg: float,
    return_period_y: float,
    soil_class: str = "A",
    topography: str = "T1",
    *,
    n_records: int = 7,
    seed: int = 0,
) -> list[SuiteRecord]:
    """Return spectrum-matched synthetic records for a site and return period.

    Parameters
    ----------
    lon_deg, lat_deg : float
        Site [deg].
    return_period_y : float
        TR [years], in [30, 2475].
    soil_class, topography : str
        Categories (A-E, T1-T4).
    n_records : int
        Number of records.
    seed : int
        Seed of the white noise.

    Returns
    -------
    list of SuiteRecord
        Three components each (``x``, ``y`` horizontal, ``z`` vertical) [m/s²], dt 0.01 s;
        the arrays are read-only (they are cached).

    Raises
    ------
    HazardError
        For a site off the grid or a bad TR, soil or topography.
    """
    return list(
        _cached_suite(
            float(lon_deg),
            float(lat_deg),
            float(return_period_y),
            str(soil_class).upper(),
            str(topography).upper(),
            int(n_records),
            int(seed),
        )
    )


def site_record_set(
    lon_deg: float,
    lat_deg: float,
    return_period_y: float,
    soil_class: str = "A",
    topography: str = "T1",
    suite=None,
    **selection_options,
) -> RecordSet:
    """Return the target spectrum at a site and a spectrum-compatible record set.

    Parameters
    ----------
    lon_deg, lat_deg, return_period_y, soil_class, topography
        The site, TR and categories, as in :func:`target_spectrum` (and passed on to
        :func:`synthetic_suite`).
    suite : sequence of SuiteRecord, optional
        Candidate records; None uses the embedded suite named by ``kind=`` among the
        options (:data:`SUITE_KINDS`: ``"matched"``, :func:`synthetic_suite`, the default;
        ``"stochastic"``, :func:`stochastic_suite`, with 11 records unless ``n_records``
        is given); its ``seed`` may be given as ``seed=``.
    **selection_options
        Keyword arguments of :func:`rockscreen.pipeline.hazard.selection.select_records`
        (``n_records``, ``period_range_s``, ``tolerance``, ``damping``, ``scale_limits``).

    Returns
    -------
    RecordSet
    """
    seed = selection_options.pop("seed", 0)
    kind = selection_options.pop("kind", "matched")
    if kind not in SUITE_KINDS:
        raise HazardError(f"suite kind {kind!r} is not one of {', '.join(SUITE_KINDS)}")
    damping = selection_options.get("damping", 0.05)
    site = (lon_deg, lat_deg, return_period_y, soil_class, topography)
    periods, target = target_spectrum(*site, damping=damping)
    if suite is None and kind == "stochastic":
        n = selection_options.setdefault("n_records", STOCHASTIC_RECORDS)
        suite = stochastic_suite(*site, n_records=n, seed=seed)
    elif suite is None:
        n = selection_options.get("n_records", 7)
        suite = synthetic_suite(*site, n_records=n, seed=seed)
    return select_records(suite, periods, target, **selection_options)


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
    return Scenario(float(magnitude), float(distance), VS30_OF_SOIL[soil_class])


def _padded(arrays) -> np.ndarray:
    """Stack records of different lengths, zero-padded at the end."""
    n = max(len(a) for a in arrays)
    return np.array([np.pad(a, (0, n - len(a))) for a in arrays])


@lru_cache(maxsize=64)
def _cached_stochastic(lon, lat, tr, soil, topography, n_records, seed):
    site = site_hazard(lon, lat, tr)
    target = elastic_spectrum(SELECTION_PERIODS_S, site, soil, topography)
    key = _seed_key(lon, lat, tr)
    pool = []
    for i in range(STOCHASTIC_POOL_FACTOR * n_records):
        rng = np.random.default_rng([seed, *key, i])
        pool.append(simulate_record(rng, suite_scenario(rng, soil), SYNTHETIC_DT_S))
    x, y, z = (_padded([getattr(r, c) for r in pool]) for c in "xyz")
    spectra = batch_spectrum(x, SYNTHETIC_DT_S, SELECTION_PERIODS_S) / G
    names = [f"STO-{seed}-{i:02d}" for i in range(len(pool))]
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
    indices = [names.index(r.name) for r in chosen.records]
    vertical_target = vertical_spectrum(VERTICAL_PERIODS_S, site, soil, topography)
    vertical_sa = batch_spectrum(z[indices], SYNTHETIC_DT_S, VERTICAL_PERIODS_S) / G
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
            f"R={sc.distance_km:.1f} km Vs30={sc.vs30_m_s:g} m/s; D5-95={p.d5_95_s:.1f} s "
            f"t_mid={p.t_mid_s:.1f} s f_mid={p.f_mid_hz:.2f} Hz f'={p.f_slope_hz_s:.3f} Hz/s "
            f"zeta_f={p.zeta_f:.2f}; {pulse}; seed=({seed}, {key}, {i})), scaled by "
            f"{float(factor):.3g} to lon={lon:g} lat={lat:g} TR={tr:g} y soil {soil} {topography}"
        )
        suite.append(
            SuiteRecord(
                names[i],
                _frozen(x[i] * factor),
                _frozen(y[i] * factor),
                _frozen(z[i] * factor_v),
                SYNTHETIC_DT_S,
                source,
            )
        )
    return tuple(suite)


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
    lon_deg, lat_deg : float
        Site [deg].
    return_period_y : float
        TR [years], in [30, 2475].
    soil_class, topography : str
        Categories (A-E, T1-T4).
    n_records : int
        Number of records (11 by default).
    seed : int
        Seed of the suite (with the site, TR and record index).

    Returns
    -------
    list of SuiteRecord
        Three components each [m/s²], dt 0.01 s, zero-padded to one length; read-only.

    Raises
    ------
    HazardError
        For a site off the grid or a bad TR, soil or topography.
    """
    return list(
        _cached_stochastic(
            float(lon_deg),
            float(lat_deg),
            float(return_period_y),
            str(soil_class).upper(),
            str(topography).upper(),
            int(n_records),
            int(seed),
        )
    )
