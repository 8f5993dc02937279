"""Elastic response spectra of NTC 2018 §3.2.3.2 (horizontal and vertical).

Horizontal (§3.2.3.2.1, eq. 3.2.2), with ``S = S_S S_T`` and ``eta = sqrt(10/(5+xi)) >= 0.55``
(xi the damping in %, eq. 3.2.4):

- ``0 <= T < T_B``:   Se = ag S eta F0 [T/T_B + (1 - T/T_B) / (eta F0)]
- ``T_B <= T < T_C``: Se = ag S eta F0
- ``T_C <= T < T_D``: Se = ag S eta F0 (T_C / T)
- ``T_D <= T``:       Se = ag S eta F0 (T_C T_D / T^2)

with ``T_C = C_C T*C`` (eq. 3.2.5), ``T_B = T_C / 3`` (eq. 3.2.6), ``T_D = 4.0 ag/g + 1.6``
(eq. 3.2.7). Soil factors S_S and C_C: Tab. 3.2.IV (categories A-E of Tab. 3.2.II);
topographic factor S_T: Tab. 3.2.V (categories T1-T4 of Tab. 3.2.III, the value at the
top of the relief). The PGA at the surface is ``ag S`` (§3.2.3.2.1).

Vertical (§3.2.3.2.2, eq. 3.2.8): the same four branches with ``F_v = 1.35 F0 (ag/g)^0.5``
(eq. 3.2.9) in place of F0, ``S_S = 1`` (Tab. 3.2.VI), ``T_B = 0.05 s``, ``T_C = 0.15 s``,
``T_D = 1.0 s``.

Accelerations are in g, as the code writes them; multiply by ``solver.constants.G`` for m/s².
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rockscreen.pipeline.errors import HazardError
from rockscreen.pipeline.hazard.grid import SiteHazard
from rockscreen.solver.constants import G

__all__ = [
    "SOIL_CLASSES",
    "TOPOGRAPHY_FACTORS",
    "SpectrumParameters",
    "DISPLACEMENT_CORNERS_S",
    "damping_factor",
    "displacement_spectrum",
    "elastic_spectrum",
    "spectrum_parameters",
    "vertical_spectrum",
]

#: Soil class -> (a, b, lower, upper, c, d): S_S = clip(a - b F0 ag/g, lower, upper) and
#: C_C = c (T*C)^d (NTC 2018 Tab. 3.2.IV).
SOIL_CLASSES: dict[str, tuple[float, float, float, float, float, float]] = {
    "A": (1.00, 0.00, 1.00, 1.00, 1.00, 0.00),
    "B": (1.40, 0.40, 1.00, 1.20, 1.10, -0.20),
    "C": (1.70, 0.60, 1.00, 1.50, 1.05, -0.33),
    "D": (2.40, 1.50, 0.90, 1.80, 1.25, -0.50),
    "E": (2.00, 1.10, 1.00, 1.60, 1.15, -0.40),
}
#: Topographic category -> S_T (NTC 2018 Tab. 3.2.V).
TOPOGRAPHY_FACTORS: dict[str, float] = {"T1": 1.0, "T2": 1.2, "T3": 1.2, "T4": 1.4}
#: Soil class -> (T_E, T_F) [s] of the elastic displacement spectrum (NTC 2018 Tab. 3.2.VII,
#: PDF p. 53).
DISPLACEMENT_CORNERS_S: dict[str, tuple[float, float]] = {
    "A": (4.5, 10.0),
    "B": (5.0, 10.0),
    "C": (6.0, 10.0),
    "D": (6.0, 10.0),
    "E": (6.0, 10.0),
}
#: Vertical spectrum corner periods T_B, T_C, T_D [s] (NTC 2018 Tab. 3.2.VI).
VERTICAL_CORNERS_S = (0.05, 0.15, 1.0)


@dataclass(frozen=True)
class SpectrumParameters:
    """Parameters of the horizontal elastic spectrum at a site."""

    #: Soil-and-topography factor S = S_S S_T, stratigraphic and topographic factors [-].
    S: float
    S_S: float
    S_T: float
    #: Soil coefficient of T_C [-].
    C_C: float
    #: Damping correction factor [-].
    eta: float
    #: Corner periods [s].
    TB_s: float
    TC_s: float
    TD_s: float
    #: Peak ground acceleration at the surface ag S [g].
    pga_g: float


def damping_factor(damping: float) -> float:
    """Return eta = sqrt(10 / (5 + xi)) >= 0.55, xi = 100 damping (NTC 2018 eq. 3.2.4).

    Parameters
    ----------
    damping : float
        Viscous damping ratio [-] (0.05 for 5 %), in [0, 1).

    Returns
    -------
    float
        eta [-].
    """
    if not (isinstance(damping, (int, float, np.floating)) and 0.0 <= damping < 1.0):
        raise HazardError(f"damping={damping!r} must be a ratio in [0, 1) (0.05 for 5 %)")
    return max(math.sqrt(10.0 / (5.0 + 100.0 * damping)), 0.55)


def _soil(soil_class: str) -> tuple[str, tuple[float, ...]]:
    key = str(soil_class).strip().upper()
    if key not in SOIL_CLASSES:
        raise HazardError(
            f"soil class {soil_class!r} is not one of {', '.join(SOIL_CLASSES)} "
            "(NTC 2018 Tab. 3.2.II)"
        )
    return key, SOIL_CLASSES[key]


def _topography(topography: str) -> float:
    key = str(topography).strip().upper()
    if key not in TOPOGRAPHY_FACTORS:
        raise HazardError(
            f"topography {topography!r} is not one of {', '.join(TOPOGRAPHY_FACTORS)} "
            "(NTC 2018 Tab. 3.2.III)"
        )
    return TOPOGRAPHY_FACTORS[key]


def spectrum_parameters(
    site: SiteHazard, soil_class: str = "A", topography: str = "T1", damping: float = 0.05
) -> SpectrumParameters:
    """Return the parameters of the horizontal elastic spectrum (NTC 2018 §3.2.3.2.1).

    Parameters
    ----------
    site : SiteHazard
        ag [g], F0 [-], T*C [s] at the site.
    soil_class : {"A", "B", "C", "D", "E"}
        Subsoil category (Tab. 3.2.II).
    topography : {"T1", "T2", "T3", "T4"}
        Topographic category (Tab. 3.2.III).
    damping : float
        Damping ratio [-].

    Returns
    -------
    SpectrumParameters
    """
    _, (a, b, lower, upper, c, d) = _soil(soil_class)
    s_s = min(max(a - b * site.F0 * site.ag_g, lower), upper)
    c_c = c * site.Tc_star_s**d
    s_t = _topography(topography)
    tc = c_c * site.Tc_star_s
    s = s_s * s_t
    return SpectrumParameters(
        S=s,
        S_S=s_s,
        S_T=s_t,
        C_C=c_c,
        eta=damping_factor(damping),
        TB_s=tc / 3.0,
        TC_s=tc,
        TD_s=4.0 * site.ag_g + 1.6,
        pga_g=site.ag_g * s,
    )


def _four_branches(periods, amplitude, factor, eta, tb, tc, td) -> np.ndarray:
    """Se(T) / g of eq. 3.2.2 (or 3.2.8) with plateau ``amplitude eta factor`` [g]."""
    t = np.asarray(periods, dtype=float)
    if np.any(~np.isfinite(t)) or np.any(t < 0):
        raise HazardError("periods must be finite and >= 0 s")
    plateau = amplitude * eta * factor
    rising = amplitude * eta * factor * (t / tb + (1.0 - t / tb) / (eta * factor))
    return np.select(
        [t < tb, t < tc, t < td],
        [rising, np.full_like(t, plateau), plateau * tc / np.where(t > 0, t, 1.0)],
        plateau * tc * td / np.where(t > 0, t, 1.0) ** 2,
    )


def elastic_spectrum(
    periods_s,
    site: SiteHazard,
    soil_class: str = "A",
    topography: str = "T1",
    damping: float = 0.05,
    *,
    component: str = "horizontal",
) -> np.ndarray:
    """Return the horizontal Se(T) or the vertical Sve(T) elastic spectrum (NTC 2018 §3.2.3.2).

    Horizontal: §3.2.3.2.1, eq. 3.2.2, with :func:`spectrum_parameters`. Vertical:
    §3.2.3.2.2, eq. 3.2.8, the same branches with ``F_v = 1.35 F0 (ag/g)^0.5``, ``S = S_T``
    (S_S = 1 for every soil class, Tab. 3.2.VI) and the corners of Tab. 3.2.VI.

    Parameters
    ----------
    periods_s : array_like
        Periods T [s], >= 0.
    site : SiteHazard
        ag [g], F0 [-], T*C [s] (the vertical spectrum does not use T*C).
    soil_class, topography : str
        Subsoil (A-E) and topographic (T1-T4) categories; the vertical spectrum validates
        the soil class only.
    damping : float
        Damping ratio [-].
    component : {"horizontal", "vertical"}
        Which spectrum.

    Returns
    -------
    numpy.ndarray
        Se or Sve [g], shape of ``periods_s``; Se(0) = ag S.
    """
    if component == "horizontal":
        p = spectrum_parameters(site, soil_class, topography, damping)
        return _four_branches(periods_s, site.ag_g * p.S, site.F0, p.eta, p.TB_s, p.TC_s, p.TD_s)
    if component != "vertical":
        raise HazardError(f"component={component!r} is not one of horizontal, vertical")
    _soil(soil_class)
    s = 1.0 * _topography(topography)
    fv = 1.35 * site.F0 * math.sqrt(site.ag_g)
    tb, tc, td = VERTICAL_CORNERS_S
    return _four_branches(periods_s, site.ag_g * s, fv, damping_factor(damping), tb, tc, td)


def displacement_spectrum(
    periods_s,
    site: SiteHazard,
    soil_class: str = "A",
    topography: str = "T1",
    damping: float = 0.05,
) -> np.ndarray:
    """Return the horizontal elastic displacement spectrum S_De(T) (NTC 2018 §3.2.3.2.3).

    ``S_De(T) = Se(T) (T / 2 pi)^2`` up to ``T_E`` (eq. 3.2.10); beyond, eq. 3.2.11: from
    ``T_E`` to ``T_F`` a straight line in T from ``0.025 ag S T_C T_D F0 eta`` to the peak
    ground displacement ``d_g = 0.025 ag S T_C T_D`` (eq. 3.2.12, ag in m/s2), and ``d_g``
    past ``T_F``; ``T_E``, ``T_F`` from :data:`DISPLACEMENT_CORNERS_S` (Tab. 3.2.VII).

    Parameters
    ----------
    periods_s : array_like
        Periods T [s], >= 0.
    site : SiteHazard
        ag [g], F0 [-], T*C [s].
    soil_class, topography : str
        Subsoil (A-E) and topographic (T1-T4) categories.
    damping : float
        Damping ratio [-].

    Returns
    -------
    numpy.ndarray
        S_De [m], shape of ``periods_s``.
    """
    key, _ = _soil(soil_class)
    t = np.asarray(periods_s, dtype=float)
    p = spectrum_parameters(site, key, topography, damping)
    se = elastic_spectrum(t, site, key, topography, damping) * G
    te, tf = DISPLACEMENT_CORNERS_S[key]
    d_g = 0.025 * site.ag_g * G * p.S * p.TC_s * p.TD_s
    f0_eta = site.F0 * p.eta
    middle = d_g * (f0_eta + (1.0 - f0_eta) * (t - te) / (tf - te))
    return np.select(
        [t <= te, t <= tf], [se * (t / (2.0 * math.pi)) ** 2, middle], np.full_like(t, d_g)
    )


def vertical_spectrum(periods_s, site: SiteHazard, *categories, **options) -> np.ndarray:
    """Return the vertical elastic spectrum Sve(T) (NTC 2018 §3.2.3.2.2, eq. 3.2.8).

    :func:`elastic_spectrum` with ``component="vertical"``: ``categories`` and ``options``
    are its ``soil_class``, ``topography`` and ``damping``.
    """
    return elastic_spectrum(periods_s, site, *categories, component="vertical", **options)
