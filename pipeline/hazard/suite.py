"""The embedded record suite: spectrum-matched synthetic accelerograms, and a site's record set.

For users without records, :func:`synthetic_suite` generates accelerograms compatible with
the code spectrum at a site (NTC 2018 §3.2.3.6 admits synthetic accelerograms):

1. a pool of ``POOL_FACTOR * n_records`` records of the project's stochastic model
   (:func:`pipeline.motion.synthetic.stochastic_accelerogram`: white noise, seeded,
   Saragoni-Hart envelope, Kanai-Tajimi ground filter, Clough-Penzien high-pass) with
   ground frequencies from 1.5 to 5 Hz and strong-motion durations from 8 to 20 s, so the
   pool varies in frequency content and duration;
2. each horizontal is matched to the target by iterative frequency-domain scaling: its
   5 % spectrum at ``MATCH_PERIODS_S`` is compared with the target, the ratio target / SA
   (interpolated in log period, held constant beyond the matched periods) multiplies
   the Fourier amplitudes at f = 1/T, phases unchanged, and the record is transformed
   back (zero-padded, so nothing wraps around); ``MATCH_ITERATIONS`` passes;
3. :func:`pipeline.hazard.selection.select_records` picks the ``n_records`` best;
   they get a second horizontal (another realisation, matched the same way) and a
   vertical matched to the vertical spectrum (§3.2.3.2.2).

Every call with the same arguments gives the same records (cached in memory per site,
return period, soil, topography, size and seed). The records are synthetic: their
spectra match the code, but they carry no near-source velocity pulse and a duration that
is a model choice; see ``docs/hazard.md``.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from pipeline.hazard.grid import site_hazard
from pipeline.hazard.selection import RecordSet, SuiteRecord, select_records
from pipeline.hazard.spectrum import elastic_spectrum, vertical_spectrum
from pipeline.motion.spectra import response_spectrum
from pipeline.motion.synthetic import stochastic_accelerogram
from solver.constants import G

__all__ = [
    "MATCH_PERIODS_S",
    "SYNTHETIC_DT_S",
    "match_spectrum",
    "site_record_set",
    "synthetic_suite",
    "target_spectrum",
]

#: Time step and duration of the synthetic records [s].
SYNTHETIC_DT_S = 0.01
SYNTHETIC_DURATION_S = 25.0
#: Periods at which the records are matched [s]: beyond the default 0.15-2.0 s range on
#: both sides, so that a range up to 3 s can be selected from the same suite.
MATCH_PERIODS_S = np.geomspace(0.05, 4.0, 28)
#: Passes of the frequency-domain matching.
MATCH_ITERATIONS = 5
#: Largest change of a Fourier amplitude in one pass, as |ln(gain)|.
GAIN_LIMIT = np.log(2.0)
#: Pool size as a multiple of the set size.
POOL_FACTOR = 2
#: Periods at which target spectra are given to the selection [s].
TARGET_PERIODS_S = np.geomspace(0.02, 5.0, 120)


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


def match_spectrum(acc, dt, target_g, *, iterations=MATCH_ITERATIONS, damping=0.05):
    """Scale a record's Fourier amplitudes until its spectrum follows a target.

    Parameters
    ----------
    acc : numpy.ndarray
        Acceleration [m/s²].
    dt : float
        Time step [s].
    target_g : numpy.ndarray
        Target SA [g] at :data:`MATCH_PERIODS_S`.
    iterations : int
        Passes.
    damping : float
        Damping ratio [-].

    Returns
    -------
    numpy.ndarray
        Matched acceleration [m/s²], same length.
    """
    n = acc.size
    n_fft = 1 << int(np.ceil(np.log2(2 * n)))
    frequency = np.fft.rfftfreq(n_fft, dt)
    log_t = np.log(MATCH_PERIODS_S)
    with np.errstate(divide="ignore"):
        log_period = np.log(1.0 / frequency)
    out = np.asarray(acc, float).copy()
    taper = np.ones(n)
    ramp = int(round(1.0 / dt))
    taper[n - ramp :] = 0.5 * (1 + np.cos(np.linspace(0.0, np.pi, ramp)))
    for _ in range(iterations):
        sa, _ = response_spectrum(out, dt, MATCH_PERIODS_S, damping)
        log_ratio = np.log(target_g * G / sa)
        gain = np.exp(np.clip(np.interp(log_period, log_t, log_ratio), -GAIN_LIMIT, GAIN_LIMIT))
        spectrum = np.fft.rfft(out, n_fft) * gain
        out = np.fft.irfft(spectrum, n_fft)[:n] * taper
    return out


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


@lru_cache(maxsize=64)
def _cached_suite(lon, lat, tr, soil, topography, n_records, seed):
    site = site_hazard(lon, lat, tr)
    horizontal = elastic_spectrum(MATCH_PERIODS_S, site, soil, topography)
    vertical = vertical_spectrum(MATCH_PERIODS_S, site, soil, topography)
    pga = site.ag_g * G
    n_pool = POOL_FACTOR * n_records
    frequencies = np.geomspace(1.5, 5.0, n_pool)
    durations = np.linspace(8.0, 20.0, n_pool)[::-1]
    pool = []
    for i in range(n_pool):
        rng = np.random.default_rng([seed, i])
        acc = _pool_record(rng, pga, frequencies[i], durations[i])
        pool.append(match_spectrum(acc, SYNTHETIC_DT_S, horizontal))
    candidates = [
        SuiteRecord(f"SYN-{seed}-{i:02d}", a, None, None, SYNTHETIC_DT_S, "")
        for i, a in enumerate(pool)
    ]
    chosen = select_records(candidates, MATCH_PERIODS_S, horizontal, n_records=n_records)
    suite = []
    for record in chosen.records:
        i = int(record.name.rsplit("-", 1)[1])
        rng = np.random.default_rng([seed, i, 1])
        y = match_spectrum(
            _pool_record(rng, pga, frequencies[i], durations[i]), SYNTHETIC_DT_S, horizontal
        )
        rng = np.random.default_rng([seed, i, 2])
        z = _pool_record(rng, pga, 1.5 * frequencies[i], durations[i])
        z = match_spectrum(z, SYNTHETIC_DT_S, vertical)
        source = (
            f"synthetic (Kanai-Tajimi/Clough-Penzien/Saragoni-Hart, f_g={frequencies[i]:.2f} Hz, "
            f"t_n={durations[i]:.1f} s, seed=({seed}, {i})), matched to NTC 2018 at "
            f"lon={lon:g} lat={lat:g} TR={tr:g} y soil {soil} {topography}"
        )
        suite.append(
            SuiteRecord(
                record.name,
                _frozen(record.acc_x_m_s2),
                _frozen(y),
                _frozen(z),
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
    lon_deg, lat_deg : float
        Site [deg].
    return_period_y : float
        TR [years].
    soil_class, topography : str
        Categories (A-E, T1-T4).
    suite : sequence of SuiteRecord, optional
        Candidate records; None uses :func:`synthetic_suite` (its ``seed`` may be given as
        ``seed=`` among the options).
    **selection_options
        Keyword arguments of :func:`pipeline.hazard.selection.select_records`
        (``n_records``, ``period_range_s``, ``tolerance``, ``damping``, ``scale_limits``).

    Returns
    -------
    RecordSet
    """
    seed = selection_options.pop("seed", 0)
    damping = selection_options.get("damping", 0.05)
    periods, target = target_spectrum(
        lon_deg, lat_deg, return_period_y, soil_class, topography, damping
    )
    if suite is None:
        n = selection_options.get("n_records", 7)
        suite = synthetic_suite(
            lon_deg, lat_deg, return_period_y, soil_class, topography, n_records=n, seed=seed
        )
    return select_records(suite, periods, target, **selection_options)
