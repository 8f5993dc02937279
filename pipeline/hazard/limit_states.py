"""Limit states, reference period and return period of the seismic action (NTC 2018 §2.4, §3.2.1).

- Reference period V_R = V_N C_U (NTC 2018 §2.4.3, eq. 2.4.1), with C_U = 0.7, 1.0, 1.5,
  2.0 for use classes I-IV (Tab. 2.4.II); when V_R < 35 years, V_R = 35 years (§2.4.3).
- Probability of exceedance in V_R: P_VR = 81 % (SLO), 63 % (SLD), 10 % (SLV), 5 % (SLC)
  (NTC 2018 §3.2.1, Tab. 3.2.I).
- Return period TR = -V_R / ln(1 - P_VR) (NTC 2018 §3.2.1; Allegato A).

Defaults for a church bell tower (``docs/hazard.md``): nominal life V_N = 50 years, the
code's value for ordinary constructions (NTC 2018 Tab. 2.4.I), which the Guidelines for
cultural heritage (DPCM 9/2/2011 §2.4) also use as the reference for monumental
buildings; use class III, "constructions whose use involves significant crowding" (NTC
2018 §2.4.2), because a parish church gathers congregations and the tower stands over it
and the churchyard (the Guidelines, §2.4, tie the class to the actual use: a church no
longer open to the public may be class II). The functions keep the code's neutral
defaults (class II); :data:`TOWER_DEFAULTS` holds the tower ones.
"""

from __future__ import annotations

import math

from rockscreen.pipeline.errors import HazardError

__all__ = [
    "LIMIT_STATES",
    "MIN_REFERENCE_PERIOD_Y",
    "P_VR",
    "TOWER_DEFAULTS",
    "USE_CLASS_CU",
    "limit_state_return_period",
    "reference_period",
]

#: The four seismic limit states, from the most to the least frequent (NTC 2018 §3.2.1).
LIMIT_STATES = ("SLO", "SLD", "SLV", "SLC")
#: Probability of exceedance in the reference period (NTC 2018 Tab. 3.2.I) [-].
P_VR = {"SLO": 0.81, "SLD": 0.63, "SLV": 0.10, "SLC": 0.05}
#: Use class -> coefficient C_U (NTC 2018 Tab. 2.4.II) [-].
USE_CLASS_CU = {"I": 0.7, "II": 1.0, "III": 1.5, "IV": 2.0}
#: Smallest reference period (NTC 2018 §2.4.3) [years].
MIN_REFERENCE_PERIOD_Y = 35.0
#: Defaults for a church bell tower when the inventory is silent (see the module docstring).
TOWER_DEFAULTS = {"nominal_life_y": 50.0, "use_class": "III", "soil_class": "A", "topography": "T1"}


def _check_use_class(use_class: str) -> str:
    key = str(use_class).strip().upper()
    if key not in USE_CLASS_CU:
        raise HazardError(
            f"use class {use_class!r} is not one of {', '.join(USE_CLASS_CU)} (NTC 2018 §2.4.2)"
        )
    return key


def reference_period(nominal_life_y: float = 50.0, use_class: str = "II") -> float:
    """Return the reference period V_R = max(V_N C_U, 35) (NTC 2018 §2.4.3).

    Parameters
    ----------
    nominal_life_y : float
        Nominal life V_N [years], > 0.
    use_class : {"I", "II", "III", "IV"}
        Use class (NTC 2018 §2.4.2).

    Returns
    -------
    float
        V_R [years].

    Raises
    ------
    HazardError
        For a non-positive V_N or an unknown use class.
    """
    try:
        vn = float(nominal_life_y)
    except (TypeError, ValueError):
        raise HazardError(f"nominal life V_N={nominal_life_y!r} is not a number [years]") from None
    if not (math.isfinite(vn) and vn > 0):
        raise HazardError(f"nominal life V_N={vn:g} years must be a finite number > 0")
    return max(vn * USE_CLASS_CU[_check_use_class(use_class)], MIN_REFERENCE_PERIOD_Y)


def limit_state_return_period(
    limit_state: str, nominal_life_y: float = 50.0, use_class: str = "II"
) -> float:
    """Return the return period of the seismic action of a limit state.

    TR = -V_R / ln(1 - P_VR) (NTC 2018 §3.2.1, Tab. 3.2.I; V_R from §2.4.3).

    Parameters
    ----------
    limit_state : {"SLO", "SLD", "SLV", "SLC"}
        Limit state.
    nominal_life_y : float
        Nominal life V_N [years].
    use_class : {"I", "II", "III", "IV"}
        Use class.

    Returns
    -------
    float
        TR [years]; may fall below the tabulated 30 years (SLO with V_R < 52.3 years).

    Raises
    ------
    HazardError
        For an unknown limit state or use class, or a non-positive nominal life.
    """
    key = str(limit_state).strip().upper()
    if key not in P_VR:
        raise HazardError(
            f"limit state {limit_state!r} is not one of {', '.join(LIMIT_STATES)} (NTC 2018 §3.2.1)"
        )
    return -reference_period(nominal_life_y, use_class) / math.log(1.0 - P_VR[key])
