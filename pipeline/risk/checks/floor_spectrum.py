"""Floor spectra of the Circolare 2019 for local mechanisms at height (§C7.2.3).

The demand on a local mechanism at height ``z`` of a structure (the belfry on the shaft, a
tower or bell gable on the church) is read on the floor spectrum that §C8.7.1.2.1.4 of the
Circolare 21/1/2019 n. 7 prescribes: §C7.2.3, eqs. [C7.2.5]-[C7.2.10] (PDF pp. 203-204;
docs/code_checks.md §1.4). With the first mode only (§C7.2.3: "in genere, sufficiente
riferirsi al solo primo modo di vibrare"; §C8.7.1.2.1.8), of period ``T_k`` and damping
``xi_k`` of the structure:

- peak floor acceleration ``a_Z(z) = Se(T_k, xi_k) |gamma psi(z)| sqrt(1 + 0.0004 xi_k^2)``
  ([C7.2.7], [C7.2.8]; ``xi_k`` in percent), ``psi(z) = z/H`` and ``gamma = 3N/(2N+1)``
  ([C7.2.10]; 1.5 for a cantilever);
- floor spectrum of the element of damping ``xi`` ([C7.2.6]), with ``A = 1.1 xi_k^-0.5
  eta(xi)``, ``a = 0.8`` and ``b = 1.1``::

      S_eZ = A a_Z / (1 + (A - 1)(1 - T/(a T_k))^1.6)    T < a T_k
      S_eZ = A a_Z                                       a T_k <= T < b T_k
      S_eZ = A a_Z / (1 + (A - 1)(T/(b T_k) - 1)^1.2)    T >= b T_k

  and never below the ground spectrum ``Se(T, xi)`` for ``T > T_k`` ([C7.2.5]).

``xi_k`` in ``A`` is read as a ratio (``A = 4.9`` for 5 %, the peak amplification of floor
spectra and the ``a_p = 5`` of [C7.2.11]); the "in percentuale" of the Circolare is read as
applying to ``sqrt(1 + 0.0004 xi_k^2)``, where a ratio would make the term vanish. With the
percent in ``A`` the floor spectrum would peak at half the floor's own acceleration, which no
oscillator does: rockscreen's reading, stated in the doc.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from rockscreen.pipeline.hazard import SiteHazard, elastic_spectrum
from rockscreen.pipeline.hazard.spectrum import damping_factor
from rockscreen.pipeline.motion.floor import linear_mode_participation
from rockscreen.pipeline.risk.checks.site_capacity import SiteConditions
from rockscreen.pipeline.risk.checks.validation import check_number
from rockscreen.solver.constants import G

__all__ = [
    "FLOOR_A",
    "FLOOR_B",
    "StructureState",
    "floor_spectral_acceleration",
    "peak_floor_acceleration",
]

#: Bounds ``a T_k`` and ``b T_k`` of the floor spectrum's plateau (Circolare 2019 §C7.2.3:
#: "possono essere assunti pari a 0,8 e 1,1").
FLOOR_A = 0.8
FLOOR_B = 1.1


@dataclasses.dataclass(frozen=True)
class StructureState:
    """The structure beneath a mechanism as the floor spectrum sees it.

    Its height ``H`` and the mechanism's level ``z`` [m], its first period ``T_k`` [s] and
    damping ``xi_k`` [-] (elastic: ``T_1``, 5 %; at the ultimate limit states lengthened
    and more damped, §C8.7.1.2.1.4), and ``gamma`` (``3N/(2N+1)``, 1.5 for a cantilever).
    """

    height_m: float
    level_m: float
    period_s: float
    damping: float = 0.05
    n_storeys: int | None = None

    def __post_init__(self):
        h = check_number("height_m", self.height_m, low=0.0, low_open=True, unit="m")
        check_number("level_m", self.level_m, low=0.0, high=h, unit="m")
        check_number("period_s", self.period_s, low=0.0, low_open=True, unit="s")
        check_number("damping", self.damping, low=0.0, high=1.0, low_open=True, high_open=True)

    @property
    def participation(self) -> float:
        """Return ``gamma psi(z) = gamma z / H`` of the first mode [-]."""
        return linear_mode_participation(self.n_storeys) * self.level_m / self.height_m


def _ground(site: SiteConditions, damping: float) -> SiteConditions:
    return dataclasses.replace(site, damping=float(damping))


def peak_floor_acceleration(
    hazard: SiteHazard, site: SiteConditions, structure: StructureState
) -> float:
    """Return the peak floor acceleration ``a_Z(z)`` (Circolare 2019 [C7.2.7], [C7.2.8]) [m/s2].

    Parameters
    ----------
    hazard : SiteHazard
        ag, F0, T*C of the action.
    site : SiteConditions
        Soil and topography (its damping is not used).
    structure : StructureState
        The structure beneath and the mechanism's level.

    Returns
    -------
    float
        a_Z [m/s2].
    """
    xi_percent = 100.0 * structure.damping
    se = _ground(site, structure.damping).spectral_acceleration(structure.period_s, hazard)
    return se * abs(structure.participation) * math.sqrt(1.0 + 0.0004 * xi_percent**2)


def floor_spectral_acceleration(
    periods_s,
    hazard: SiteHazard,
    site: SiteConditions,
    structure: StructureState,
    damping: float,
) -> np.ndarray:
    """Return the floor spectrum ``S_eZ(T, xi, z)`` (Circolare 2019 [C7.2.5], [C7.2.6]) [m/s2].

    Parameters
    ----------
    periods_s : array_like
        Periods T of the element [s], >= 0.
    hazard : SiteHazard
        ag, F0, T*C of the action.
    site : SiteConditions
        Soil and topography.
    structure : StructureState
        The structure beneath and the mechanism's level.
    damping : float
        Damping ratio of the element ``xi`` [-], in (0, 1).

    Returns
    -------
    numpy.ndarray
        S_eZ [m/s2], shape of ``periods_s``.
    """
    check_number("damping", damping, low=0.0, high=1.0, low_open=True, high_open=True)
    t = np.asarray(periods_s, dtype=float)
    tk = structure.period_s
    a_z = peak_floor_acceleration(hazard, site, structure)
    amp = 1.1 * structure.damping**-0.5 * damping_factor(damping)
    rise = np.clip(1.0 - t / (FLOOR_A * tk), 0.0, None)
    fall = np.clip(t / (FLOOR_B * tk) - 1.0, 0.0, None)
    s_ez = np.select(
        [t < FLOOR_A * tk, t < FLOOR_B * tk],
        [amp * a_z / (1.0 + (amp - 1.0) * rise**1.6), np.full_like(t, amp * a_z)],
        amp * a_z / (1.0 + (amp - 1.0) * fall**1.2),
    )
    se = elastic_spectrum(t, hazard, site.soil_class, site.topography, damping) * G
    return np.where(t > tk, np.maximum(s_ez, se), s_ez)
