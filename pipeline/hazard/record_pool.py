"""The stochastic suite's shared record pools: generated once per soil, cached per user on disk.

A pool is :data:`POOL_SIZE` three-component records of the Rezaeian & Der Kiureghian (2010)
model with velocity pulses (:func:`rockscreen.pipeline.motion.stochastic.simulate_record`),
each from its own scenario (:func:`suite_scenario`) and seed ``(seed, V_s30, index)``. What
the record model needs from a site is only V_s30 (the soil class, :data:`VS30_OF_SOIL`) and
the scenario distribution (:data:`STOCHASTIC_SCENARIOS`, the same everywhere), so one pool
per soil class and seed serves every site, return period and topography: a site's set is a
selection and amplitude scaling from it
(:func:`rockscreen.pipeline.hazard.stochastic_suite.stochastic_record_set`). The pool's 5 %
spectra at :data:`~rockscreen.pipeline.hazard.suite_common.SELECTION_PERIODS_S` are computed
with it.

The pool is kept in memory (per process) and on disk, in :func:`pool_cache_dir` (as the
compiled solver is): ``$ROCKSCREEN_POOL_CACHE`` when set, else
``$XDG_CACHE_HOME/rockscreen/record-pools`` (``~/.cache``; ``%LOCALAPPDATA%`` on Windows).
A file is written to a temporary name and renamed (:func:`os.replace`), so concurrent
writers (the workers of ``assess --jobs``) never leave a partial file; one that cannot be
read, was written for other inputs or by other sources of the generator (the digest of its
modules, :func:`generator_digest`), or whose contents do not match the checksum it carries
is ignored and rebuilt. Rebuilding gives the same arrays: the cache only saves time.
"""

from __future__ import annotations

import contextlib
import dataclasses
import hashlib
import inspect
import json
import math
import os
import sys
import tempfile
from functools import lru_cache
from pathlib import Path
from typing import NamedTuple

import numpy as np

from rockscreen.pipeline.errors import HazardError
from rockscreen.pipeline.hazard.grid import SiteHazard
from rockscreen.pipeline.hazard.matching import batch_spectrum
from rockscreen.pipeline.hazard.spectrum import elastic_spectrum, vertical_spectrum
from rockscreen.pipeline.hazard.suite_common import SELECTION_PERIODS_S, SYNTHETIC_DT_S
from rockscreen.pipeline.motion import stochastic as stochastic_model
from rockscreen.pipeline.motion.stochastic import Scenario, simulate_record
from rockscreen.solver.constants import G

__all__ = [
    "POOL_CACHE_ENV",
    "POOL_FORMAT",
    "POOL_SIZE",
    "STOCHASTIC_SCENARIOS",
    "VERTICAL_PERIODS_S",
    "VS30_OF_SOIL",
    "RecordPool",
    "generator_digest",
    "pool_cache_dir",
    "pool_spectra",
    "record_pool",
    "suite_scenario",
]

#: Scenario distribution of the stochastic suite: magnitude uniform in [M_min, M_max],
#: rupture distance log-uniform in [R_min, R_max] km, and the faulting indicator F of
#: :class:`~rockscreen.pipeline.motion.stochastic.Scenario`: 1, non-strike-slip, because
#: the seismogenic zones of peninsular Italy that dominate its hazard are mostly normal
#: faulting (ZS9 source model, Meletti et al. 2008; ``docs/hazard.md``).
STOCHASTIC_SCENARIOS = {"magnitude": (5.0, 7.0), "distance_km": (3.0, 100.0), "non_strike_slip": 1}
#: Representative V_s30 [m/s] of the NTC 2018 soil classes (Tab. 3.2.II ranges: A > 800,
#: B 360-800, C 180-360, D 100-180; E: a thin C or D layer on rock). C and E share a pool.
VS30_OF_SOIL = {"A": 900.0, "B": 580.0, "C": 270.0, "D": 150.0, "E": 270.0}
#: Records of a pool (per soil class and seed): enough that every node of the grid, soil,
#: topography and TR finds a set well inside the NTC band (400 left 1 soil-D set in 5 at
#: 0.83-1.40 at high-hazard nodes: its wide plateau needs the rarer long-period records).
POOL_SIZE = 1200
#: Environment variable naming the folder of the cached pools.
POOL_CACHE_ENV = "ROCKSCREEN_POOL_CACHE"
#: Format name and version of a cached pool file (a change makes old files foreign).
POOL_FORMAT = "rockscreen-record-pool-1"
#: Periods at which a record's vertical is scaled to the code's vertical spectrum [s].
VERTICAL_PERIODS_S = np.geomspace(0.05, 1.0, 12)
#: Rock site whose shape gives a record its own intensity for the vertical (ag = 1 g, F0 =
#: 2.5, T*C = 0.3 s: a typical Italian shape; only the ratio to the record matters).
_REFERENCE_SITE = SiteHazard(0.0, 0.0, 0.0, 1.0, 2.5, 0.3)
#: Arrays of a pool file, in the order of the checksum.
_ARRAYS = (
    "x",
    "y",
    "z",
    "offsets",
    "spectra_g",
    "vertical_factor",
    "scenario",
    "parameters",
    "pulse",
)


class RecordPool(NamedTuple):
    """One pool: records concatenated (``offsets`` delimit them), spectra, what made them."""

    #: V_s30 [m/s] and seed of the pool.
    vs30_m_s: float
    seed: int
    #: First horizontal, second horizontal and vertical, concatenated [m/s²] (the vertical
    #: already times ``vertical_factor``), in float32 (7 significant digits: the records are
    #: rounded so when generated, so a cached and a generated pool are the same).
    x: np.ndarray
    y: np.ndarray
    z: np.ndarray
    #: Start of record i at ``offsets[i]``, end at ``offsets[i + 1]`` (size + 1 entries).
    offsets: np.ndarray
    #: 5 % spectra of ``x`` at ``SELECTION_PERIODS_S`` [g], shape (size, periods).
    spectra_g: np.ndarray
    #: Factor applied to each generated vertical [-].
    vertical_factor: np.ndarray
    #: Per record: (M, R [km], V_s30 [m/s], F); the six RDK parameters; the pulse
    #: (T_p [s], gamma [-]), NaN without one.
    scenario: np.ndarray
    parameters: np.ndarray
    pulse: np.ndarray

    def record(self, index: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Return record ``index``'s (x, y, z) [m/s²] as read-only float64 arrays."""
        start, end = int(self.offsets[index]), int(self.offsets[index + 1])
        out = []
        for component in (self.x, self.y, self.z):
            acc = component[start:end].astype(np.float64)
            acc.setflags(write=False)
            out.append(acc)
        return out[0], out[1], out[2]

    def source(self, index: int) -> str:
        """Return one line on how record ``index`` was made."""
        m, r, vs30, f = self.scenario[index]
        ia, d595, tmid, fmid, fslope, zeta = self.parameters[index]
        period, gamma = self.pulse[index]
        pulse = "no pulse" if math.isnan(period) else f"pulse T_p={period:.2f} s gamma={gamma:.2f}"
        return (
            f"stochastic (Rezaeian & Der Kiureghian 2010; M={m:.2f} R={r:.1f} km "
            f"Vs30={vs30:g} m/s F={int(f)}; D5-95={d595:.1f} s t_mid={tmid:.1f} s "
            f"f_mid={fmid:.2f} Hz f'={fslope:.3f} Hz/s zeta_f={zeta:.2f}; {pulse}; vertical x "
            f"{self.vertical_factor[index]:.3g}), pool record {index} of seed {self.seed}, "
            f"Vs30 {self.vs30_m_s:g} m/s"
        )


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


def pool_cache_dir() -> Path:
    """Return the folder of the cached pools (``$ROCKSCREEN_POOL_CACHE`` or the user cache).

    Returns
    -------
    pathlib.Path
        Not created here.
    """
    configured = os.environ.get(POOL_CACHE_ENV)
    if configured:
        return Path(configured)
    if sys.platform == "win32":  # pragma: no cover - not tested on this platform
        base = Path(os.environ.get("LOCALAPPDATA", Path.home() / "AppData" / "Local"))
    else:
        base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    return base / "rockscreen" / "record-pools"


@lru_cache(maxsize=1)
def generator_digest() -> str:
    """Return 12 hex digits of the SHA-256 of what makes a pool's arrays.

    Returns
    -------
    str
        Digest of the record model (:mod:`rockscreen.pipeline.motion.stochastic`), the
        batched spectra (:mod:`rockscreen.pipeline.hazard.matching`), the spectra of the code
        (:mod:`rockscreen.pipeline.hazard.spectrum`), and of this module's generating
        functions and constants (not of its cache handling): a change to any gives new files.
    """
    digest = hashlib.sha256()
    for module_file in (
        stochastic_model.__file__,
        inspect.getfile(batch_spectrum),
        inspect.getfile(elastic_spectrum),
    ):
        path = Path(module_file)
        digest.update(path.name.encode())
        digest.update(path.read_bytes())
    for function in (suite_scenario, _vertical_factor, _generate):
        digest.update(inspect.getsource(function).encode())
    constants = (STOCHASTIC_SCENARIOS, VS30_OF_SOIL, _REFERENCE_SITE, VERTICAL_PERIODS_S)
    digest.update(repr(constants).encode())
    return digest.hexdigest()[:12]


def _prune(path: Path, header: dict) -> None:
    """Remove the files of the same pool made by other generators (stale: never read again)."""
    stale = _file_name({**header, "generator": "*"})
    for other in path.parent.glob(stale):
        if other != path:
            with contextlib.suppress(OSError):
                other.unlink()
                other.with_name(other.name + ".lock").unlink(missing_ok=True)


def _header(vs30: float, seed: int, size: int) -> dict:
    """Return what a pool file must have been written for."""
    return {
        "format": POOL_FORMAT,
        "generator": generator_digest(),
        "vs30_m_s": float(vs30),
        "seed": int(seed),
        "size": int(size),
        "dt_s": SYNTHETIC_DT_S,
        "periods_s": [float(p) for p in SELECTION_PERIODS_S],
        "vertical_periods_s": [float(p) for p in VERTICAL_PERIODS_S],
    }


def _checksum(arrays: dict) -> str:
    digest = hashlib.sha256()
    for name in _ARRAYS:
        array = np.ascontiguousarray(arrays[name])
        digest.update(f"{name}:{array.dtype.str}:{array.shape}".encode())
        digest.update(array.tobytes())
    return digest.hexdigest()


def _soil_of(vs30: float) -> str:
    return next(soil for soil, value in VS30_OF_SOIL.items() if value == vs30)


def _vertical_factor(x: np.ndarray, z: np.ndarray) -> float:
    """Factor scaling ``z`` to the code's vertical spectrum at the record's own intensity.

    The record's ag is the least-squares (in logs) factor of its ``x`` spectrum over the
    rock shape of :data:`_REFERENCE_SITE`; the vertical is scaled (least squares in logs over
    :data:`VERTICAL_PERIODS_S`) to NTC 2018's vertical spectrum (§3.2.3.2.2, eq. 3.2.8) for
    that ag.
    """
    sa_x = batch_spectrum(x[None, :], SYNTHETIC_DT_S, SELECTION_PERIODS_S)[0] / G
    shape = elastic_spectrum(SELECTION_PERIODS_S, _REFERENCE_SITE)
    ag = float(np.exp(np.mean(np.log(sa_x / shape))))
    site = dataclasses.replace(_REFERENCE_SITE, ag_g=ag)
    target = vertical_spectrum(VERTICAL_PERIODS_S, site)
    sa_z = batch_spectrum(z[None, :], SYNTHETIC_DT_S, VERTICAL_PERIODS_S)[0] / G
    return float(np.exp(np.mean(np.log(target / sa_z))))


def _generate(vs30: float, seed: int, size: int) -> dict:
    """Simulate the pool (each record from its own seed) and compute its spectra."""
    soil = _soil_of(vs30)
    records = []
    for i in range(size):
        rng = np.random.default_rng([int(seed), round(vs30), i])
        records.append(simulate_record(rng, suite_scenario(rng, soil), SYNTHETIC_DT_S))
    x = [r.x.astype(np.float32) for r in records]
    lengths = np.array([len(a) for a in x])
    offsets = np.concatenate([[0], np.cumsum(lengths)]).astype(np.int64)
    spectra = np.empty((size, SELECTION_PERIODS_S.size))
    # Batches of similar length: zero-padding a short record to a long one costs time only.
    order = np.argsort(lengths, kind="stable")
    for batch in np.array_split(order, max(1, size // 25)):
        n = int(lengths[batch].max())
        stack = np.array([np.pad(x[i].astype(float), (0, n - lengths[i])) for i in batch])
        spectra[batch] = batch_spectrum(stack, SYNTHETIC_DT_S, SELECTION_PERIODS_S) / G
    vertical = np.array(
        [_vertical_factor(a.astype(float), r.z) for a, r in zip(x, records, strict=True)]
    )
    nan_pulse = (math.nan, math.nan)
    return {
        "x": np.concatenate(x),
        "y": np.concatenate([r.y for r in records]).astype(np.float32),
        "z": np.concatenate([r.z * f for r, f in zip(records, vertical, strict=True)]).astype(
            np.float32
        ),
        "offsets": offsets,
        "spectra_g": spectra,
        "vertical_factor": vertical,
        "scenario": np.array(
            [
                (s.magnitude, s.distance_km, s.vs30_m_s, s.non_strike_slip)
                for s in (r.scenario for r in records)
            ],
            dtype=float,
        ),
        "parameters": np.array([dataclasses.astuple(r.parameters) for r in records], dtype=float),
        "pulse": np.array(
            [nan_pulse if r.pulse is None else (r.pulse.period_s, r.pulse.gamma) for r in records]
        ),
    }


def _valid(arrays: dict, size: int) -> bool:
    """Whether the arrays of a pool file have the shapes and values of a pool of ``size``."""
    offsets = arrays["offsets"]
    n = SELECTION_PERIODS_S.size
    return (
        offsets.shape == (size + 1,)
        and offsets[0] == 0
        and bool(np.all(np.diff(offsets) > 0))
        and all(arrays[c].shape == (int(offsets[-1]),) for c in "xyz")
        and arrays["spectra_g"].shape == (size, n)
        and bool(np.all(arrays["spectra_g"] > 0))
        and arrays["vertical_factor"].shape == (size,)
        and arrays["scenario"].shape == (size, 4)
        and arrays["parameters"].shape == (size, 6)
        and arrays["pulse"].shape == (size, 2)
        and all(np.all(np.isfinite(arrays[name])) for name in _ARRAYS if name not in ("pulse",))
    )


def _read(path: Path, header: dict) -> dict | None:
    """Return the arrays of a pool file written for ``header``, else None (never raises)."""
    try:
        with open(path, "rb") as handle, np.load(handle, allow_pickle=False) as data:
            stored = json.loads(str(data["header"]))
            if stored.get("header") != header:
                return None
            arrays = {name: np.array(data[name]) for name in _ARRAYS}
    except Exception:  # noqa: BLE001 - whatever is wrong with the file, it is rebuilt
        return None
    kinds = {name: np.float64 for name in _ARRAYS} | {"x": np.float32, "y": np.float32}
    kinds |= {"z": np.float32, "offsets": np.int64}
    if any(arrays[name].dtype != kind for name, kind in kinds.items()):
        return None
    if stored.get("checksum") != _checksum(arrays) or not _valid(arrays, header["size"]):
        return None
    return arrays


def _write(path: Path, header: dict, arrays: dict) -> None:
    """Write a pool file atomically (temporary file in the folder, then ``os.replace``)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    meta = json.dumps({"header": header, "checksum": _checksum(arrays)})
    fd, temporary = tempfile.mkstemp(prefix=path.name + ".", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as handle:
            np.savez(handle, header=np.array(meta), **arrays)
        os.replace(temporary, path)
    finally:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(temporary)


def _file_name(header: dict) -> str:
    return (
        f"pool-vs30_{header['vs30_m_s']:g}-seed_{header['seed']}-n_{header['size']}-"
        f"{header['generator']}.npz"
    )


@contextlib.contextmanager
def _building(path: Path):
    """Hold an exclusive lock on ``path.lock`` where the platform has one (else nothing).

    Processes that need the same pool at once (the workers of ``assess --jobs``) wait for
    the first to write it instead of each generating it; correctness never depends on it
    (writes are atomic).
    """
    try:
        import fcntl

        path.parent.mkdir(parents=True, exist_ok=True)
        handle = open(path.with_name(path.name + ".lock"), "a")  # noqa: SIM115
    except (ImportError, OSError):  # no fcntl (Windows) or a read-only cache folder
        yield
        return
    with handle:
        try:
            fcntl.flock(handle, fcntl.LOCK_EX)
        except OSError:
            pass
        yield


@lru_cache(maxsize=16)
def _cached_pool(vs30: float, seed: int, size: int) -> RecordPool:
    header = _header(vs30, seed, size)
    path = pool_cache_dir() / _file_name(header)
    arrays = _read(path, header) if path.is_file() else None
    if arrays is None:
        with _building(path):
            arrays = _read(path, header) if path.is_file() else None
            if arrays is None:
                arrays = _generate(vs30, seed, size)
                try:
                    _write(path, header, arrays)
                    _prune(path, header)
                except OSError:  # a read-only or full cache folder: the pool is still right
                    pass
    for array in arrays.values():
        array.setflags(write=False)
    return RecordPool(float(vs30), int(seed), **arrays)


def record_pool(soil_class: str, seed: int = 0, size: int = POOL_SIZE) -> RecordPool:
    """Return the pool of a soil class and seed (from memory, the disk cache, or generated).

    Parameters
    ----------
    soil_class : str
        NTC 2018 soil class (A-E): its V_s30 (:data:`VS30_OF_SOIL`) names the pool.
    seed : int
        Seed of the pool (another seed, another pool), >= 0.
    size : int
        Records in the pool.

    Returns
    -------
    RecordPool
        Read-only arrays.

    Raises
    ------
    HazardError
        For an unknown soil class, a negative seed or a size below 1.
    """
    soil = str(soil_class).upper()
    if soil not in VS30_OF_SOIL:
        raise HazardError(f"soil class {soil_class!r} is not one of {', '.join(VS30_OF_SOIL)}")
    if int(seed) != seed or seed < 0:
        raise HazardError(f"seed={seed!r} must be an integer >= 0")
    if int(size) != size or size < 1:
        raise HazardError(f"pool size={size!r} must be an integer >= 1")
    return _cached_pool(VS30_OF_SOIL[soil], int(seed), int(size))


@lru_cache(maxsize=16)
def pool_spectra(
    soil_class: str, seed: int, size: int, periods_s: tuple, damping: float
) -> np.ndarray:
    """Return the 5 % (or ``damping``) spectra of a pool's ``x`` at other periods [g].

    The pool's own spectra (:data:`SELECTION_PERIODS_S`, 5 %) are cached with it; this
    computes them for another matching range or damping (kept in memory only).

    Parameters
    ----------
    soil_class : str
        Soil class of the pool.
    seed, size : int
        As in :func:`record_pool`.
    periods_s : tuple of float
        Periods [s].
    damping : float
        Damping ratio [-].

    Returns
    -------
    numpy.ndarray
        Shape (size, periods), read-only.
    """
    pool = record_pool(soil_class, seed, size)
    periods = np.asarray(periods_s, float)
    if periods.shape == SELECTION_PERIODS_S.shape and np.allclose(
        periods, SELECTION_PERIODS_S, rtol=1e-12
    ):
        if damping == 0.05:
            return pool.spectra_g
    out = np.empty((size, periods.size))
    for i in range(size):
        x = pool.record(i)[0]
        out[i] = batch_spectrum(x[None, :], SYNTHETIC_DT_S, periods, damping)[0] / G
    out.setflags(write=False)
    return out
