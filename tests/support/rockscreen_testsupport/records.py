"""Stochastic suite records for the assess tests (``pipeline.motion.synthetic``, SI units).

Each test file builds its suite with its own parameters (seed base, length, frequencies,
duration, name): its expected numbers depend on them, so :func:`suite_record` takes them
all and reproduces a file's records exactly.
"""

from __future__ import annotations

import numpy as np

from rockscreen.pipeline.hazard.selection import SuiteRecord
from rockscreen.pipeline.motion.synthetic import stochastic_accelerogram


def suite_record(
    i: int,
    *,
    seed_base: int = 0,
    n_samples: int = 1500,
    dt_s: float = 0.01,
    pga_m_s2: float = 2.0,
    frequency_hz: tuple[float, float] = (1.5, 0.3),
    ground_damping: float = 0.6,
    envelope_duration_s: float = 8.0,
    onset_s: float = 1.0,
    pad_samples: int = 0,
    vertical_share: float = 0.5,
    name: str = "T-{i:02d}",
    source: str = "test",
) -> SuiteRecord:
    """Return record ``i`` of a stochastic test suite.

    Three accelerograms (x, y, z) are drawn in turn from one generator seeded
    ``seed_base + i``; the vertical one is scaled by ``vertical_share``.

    Parameters
    ----------
    i : int
        Index of the record in its suite.
    seed_base : int
        The generator's seed is ``seed_base + i``.
    n_samples : int
        Samples of motion per component.
    dt_s : float
        Time step [s].
    pga_m_s2 : float
        Peak ground acceleration of the model [m/s²].
    frequency_hz : tuple of float
        ``(f0, df)``: record ``i`` has the ground frequency ``f0 + df * i`` [Hz].
    ground_damping : float
        Damping ratio of the ground filter [-].
    envelope_duration_s : float
        Duration of the envelope's strong phase [s].
    onset_s : float
        Start of the strong phase [s].
    pad_samples : int
        Zeros appended to each component (0: none).
    vertical_share : float
        Factor on the vertical component [-].
    name : str
        Format of the record's name, given ``i`` (``"R-{i}"``, ``"T-{i:02d}"``).
    source : str
        The record's ``source``.

    Returns
    -------
    SuiteRecord
        The record, time step ``dt_s``.
    """
    rng = np.random.default_rng(seed_base + i)
    f0_hz, df_hz = frequency_hz
    acc = [
        stochastic_accelerogram(
            rng,
            n_samples=n_samples,
            dt=dt_s,
            pga=pga_m_s2,
            ground_frequency=f0_hz + df_hz * i,
            ground_damping=ground_damping,
            envelope_duration=envelope_duration_s,
            onset=onset_s,
        )
        for _ in range(3)
    ]
    if pad_samples:
        acc = [np.pad(a, (0, pad_samples)) for a in acc]
    return SuiteRecord(name.format(i=i), acc[0], acc[1], vertical_share * acc[2], dt_s, source)
