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
    RecordSet,
    SuiteRecord,
    select_from_spectra,
    select_records,
)
from rockscreen.pipeline.hazard.spectrum import (
    elastic_spectrum,
    spectrum_parameters,
    vertical_spectrum,
)
from rockscreen.pipeline.hazard.stochastic_suite import STOCHASTIC_RECORDS, stochastic_record_set
from rockscreen.pipeline.hazard.suite_common import (
    SELECTION_PERIODS_S,
    SUITE_DOCS,
    SYNTHETIC_DT_S,
    frozen,
    suite_key,
)
from rockscreen.pipeline.motion.synthetic import stochastic_accelerogram
from rockscreen.solver.constants import G
from rockscreen.solver.docstrings import fill_doc

__all__ = [
    "DEFAULT_RECORDS",
    "DEFAULT_SUITE_KIND",
    "MATCH_PERIODS_S",
    "SUITE_KINDS",
    "default_n_records",
    "SYNTHETIC_DT_S",
    "site_record_set",
    "synthetic_suite",
    "target_spectrum",
]

#: The embedded suites: ``stochastic``
#: (:func:`rockscreen.pipeline.hazard.stochastic_suite.stochastic_suite`, the default: it
#: keeps the record-to-record scatter) and ``matched`` (:func:`synthetic_suite`).
SUITE_KINDS = ("stochastic", "matched")
#: The embedded suite used when none is named.
DEFAULT_SUITE_KIND = "stochastic"
#: Records of a set from the matched suite or a user suite when none is asked for (NTC
#: 2018 §7.3.5 takes the mean response of at least 7).
DEFAULT_RECORDS = 7
#: Duration of the synthetic records [s] (their time step: :data:`SYNTHETIC_DT_S`).
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
    return frozen(np.array(records))


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
    return _Pool(frozen(x), frozen(y), frozen(spectra), frozen(reference))


@lru_cache(maxsize=16)
def _verticals(n_pool, seed):
    """Return the verticals of the whole pool, matched to the vertical shape."""
    target = vertical_spectrum(MATCH_PERIODS_S, _VERTICAL_SITE)
    acc = _generated(seed, n_pool, 2)
    return frozen(
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
                frozen(record.acc_x_m_s2 * factor),
                frozen(pool.y[i] * factor),
                frozen(vertical[i] * factor_v),
                SYNTHETIC_DT_S,
                source,
            )
        )
    return tuple(suite)


@fill_doc(SUITE_DOCS)
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
    %(site)s
    n_records : int
        Number of records.
    seed : int
        Seed of the white noise.

    Returns
    -------
    list of SuiteRecord
        Three components each (``x``, ``y`` horizontal, ``z`` vertical) [m/s²], dt 0.01 s;
        the arrays are read-only (they are cached).

    %(raises)s
    """
    return list(
        _cached_suite(
            *suite_key(lon_deg, lat_deg, return_period_y, soil_class, topography, n_records, seed)
        )
    )


def default_n_records(suite=None, kind: str = DEFAULT_SUITE_KIND) -> int:
    """Return the records per set when none is asked for.

    Parameters
    ----------
    suite : sequence of SuiteRecord, optional
        A user suite (None: the embedded suite ``kind``).
    kind : str
        The embedded suite (:data:`SUITE_KINDS`).

    Returns
    -------
    int
        :data:`~rockscreen.pipeline.hazard.stochastic_suite.STOCHASTIC_RECORDS` (11) for the
        embedded stochastic suite, :data:`DEFAULT_RECORDS` (7) otherwise.
    """
    return STOCHASTIC_RECORDS if suite is None and kind == "stochastic" else DEFAULT_RECORDS


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
        options (:data:`SUITE_KINDS`: ``"stochastic"``,
        :func:`rockscreen.pipeline.hazard.stochastic_suite.stochastic_suite`, the default,
        with 11 records unless ``n_records`` is given; ``"matched"``,
        :func:`synthetic_suite`, with 7); its ``seed`` may be given as ``seed=``.
    **selection_options
        Keyword arguments of :func:`rockscreen.pipeline.hazard.selection.select_records`
        (``n_records``, ``period_range_s``, ``tolerance``, ``damping``, ``scale_limits``).

    Returns
    -------
    RecordSet
    """
    seed = selection_options.pop("seed", 0)
    kind = selection_options.pop("kind", DEFAULT_SUITE_KIND)
    if kind not in SUITE_KINDS:
        raise HazardError(f"suite kind {kind!r} is not one of {', '.join(SUITE_KINDS)}")
    site = (lon_deg, lat_deg, return_period_y, soil_class, topography)
    if selection_options.get("n_records") is None:
        selection_options["n_records"] = default_n_records(suite, kind)
    if suite is None and kind == "stochastic":
        return stochastic_record_set(*site, seed=seed, **selection_options)
    damping = selection_options.get("damping", 0.05)
    periods, target = target_spectrum(*site, damping=damping)
    n = selection_options["n_records"]
    if suite is None:
        suite = synthetic_suite(*site, n_records=n, seed=seed)
    return select_records(suite, periods, target, **selection_options)
