"""What the embedded record suites share: time step, selection periods and call conventions.

The matched suite (:mod:`rockscreen.pipeline.hazard.suite`) and the stochastic suite
(:mod:`rockscreen.pipeline.hazard.stochastic_suite`) sample their records at
:data:`SYNTHETIC_DT_S`, select them at :data:`SELECTION_PERIODS_S`, hand out read-only
arrays (:func:`frozen`: they are cached), take a site by the same arguments (described once
in :data:`SUITE_DOCS`) and cache their sets under the same key (:func:`suite_key`).
"""

from __future__ import annotations

import numpy as np

from rockscreen.pipeline.hazard.selection import N_MATCH_PERIODS

__all__ = ["SELECTION_PERIODS_S", "SUITE_DOCS", "SYNTHETIC_DT_S", "frozen", "suite_key"]

#: Time step of the synthetic records [s].
SYNTHETIC_DT_S = 0.01
#: Periods at which the suite's own selection is made [s] (``select_records``' default).
SELECTION_PERIODS_S = np.geomspace(0.15, 2.0, N_MATCH_PERIODS)

#: Parameters and errors shared by :func:`~rockscreen.pipeline.hazard.suite.synthetic_suite`
#: and :func:`~rockscreen.pipeline.hazard.stochastic_suite.stochastic_suite`.
SUITE_DOCS = {
    "site": """
lon_deg, lat_deg : float
    Site [deg].
return_period_y : float
    TR [years], in [30, 2475].
soil_class, topography : str
    Categories (A-E, T1-T4).
""",
    "raises": """
Raises
------
HazardError
    For a site off the grid or a bad TR, soil or topography.
""",
}


def frozen(acc) -> np.ndarray:
    """Return ``acc`` as a read-only float array.

    Parameters
    ----------
    acc : array_like
        Accelerations (or spectra).

    Returns
    -------
    numpy.ndarray
        A float array whose ``writeable`` flag is off.
    """
    acc = np.asarray(acc, float)
    acc.setflags(write=False)
    return acc


def suite_key(lon_deg, lat_deg, return_period_y, soil_class, topography, n_records, seed):
    """Return the arguments of a suite as the key of its in-memory cache.

    Parameters
    ----------
    lon_deg, lat_deg, return_period_y : float
        Site [deg] and TR [years].
    soil_class, topography : str
        Categories, in any case.
    n_records, seed : int
        Size of the set and seed of the suite.

    Returns
    -------
    tuple
        ``(lon, lat, tr, soil, topography, n_records, seed)``: floats, upper-case strings
        and integers.
    """
    return (
        float(lon_deg),
        float(lat_deg),
        float(return_period_y),
        str(soil_class).upper(),
        str(topography).upper(),
        int(n_records),
        int(seed),
    )
