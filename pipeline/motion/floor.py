"""Floor motion at the base of a tower that stands on a building.

Two ways to obtain the motion a bell tower feels when it rests on a church or
another building rather than on the ground (see ``docs/floor_motion.md``):

1. **Code floor spectra** give the spectral acceleration of an element of period
   ``T_a`` at height ``z`` of a building of height ``H`` and period ``T_1``:
   :func:`ec8_floor_acceleration` (Eurocode 8 Part 1, §4.3.5.2, eq. 4.25) and
   :func:`ntc_floor_acceleration` (Circolare 21 gennaio 2019 n. 7 to NTC 2018,
   §C7.2.3, eq. C7.2.11, Table C7.2.I). Both return ``S_a`` as a fraction of g
   [-]; :func:`floor_amplitude` turns it into the amplitude [m/s^2] of a harmonic
   or pulse of period ``T_a``.
2. **A modal floor accelerogram** (:func:`modal_floor_accelerogram`): the ground
   record filtered through the building's first mode,
   ``a_floor(t) = a_g(t) + Gamma phi(z) u1''(t)``, with ``u1`` the relative response
   of a linear oscillator of period ``T_1`` computed with the exact recurrence of
   :mod:`rockscreen.pipeline.motion.spectra`. ``T_1`` may come from an empirical law for masonry,
   :func:`building_period_from_height`.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from scipy.signal import lfilter

from rockscreen.pipeline.motion.spectra import check_damping, check_record, recurrence
from rockscreen.solver.constants import G
from rockscreen.solver.errors import ParameterError

#: Empirical fundamental period T_1 [s] of masonry structures from their height H [m].
PERIOD_LAWS: dict[str, Callable[[float], float]] = {
    # Faccio, Paolucci & Zanotti (2010): T_1 = 0.0187 H, used by the TURRIS database
    # (244 Italian masonry towers).
    "faccio2010": lambda height: 0.0187 * height,
    # Eurocode 8 Part 1, §4.3.3.2.2 eq. 4.6, C_t = 0.05 ("all other structures").
    "ec8": lambda height: 0.05 * height**0.75,
    # Rainieri & Fabbrocino, masonry towers (regression on identified periods).
    "rainieri-fabbrocino": lambda height: 0.01137 * height**1.138,
    # Shakya et al., masonry towers (regression on identified periods).
    "shakya": lambda height: 0.0151 * height**1.08,
}

#: First-mode participation factor of a cantilever with a linear mode shape and
#: uniform mass, in the limit of many storeys (3n/(2n+1) -> 3/2); phi(H) = 1.
LINEAR_MODE_PARTICIPATION = 1.5

#: Circolare 2019, Table C7.2.I: (upper bound of T_1 [s], a, b, a_p).
NTC_FLOOR_TABLE = ((0.5, 0.8, 1.4, 5.0), (1.0, 0.3, 1.2, 4.0), (np.inf, 0.3, 1.0, 2.5))


def ec8_floor_acceleration(
    ag_over_g: float,
    soil_factor: float,
    z: float,
    H: float,
    Ta: float,
    T1: float,
) -> float:
    """Seismic coefficient of a non-structural element, Eurocode 8 Part 1 eq. 4.25.

    ``S_a = alpha S [3 (1 + z/H) / (1 + (1 - T_a/T_1)^2) - 0.5] >= alpha S``
    (EN 1998-1:2004, §4.3.5.2(3)). For a rigid element (``T_a = 0``) this is
    ``alpha S`` at the base (z = 0) and ``2.5 alpha S`` at the top (z = H); it peaks
    at resonance ``T_a = T_1`` (``5.5 alpha S`` at the top).

    Parameters
    ----------
    ag_over_g : float
        alpha = a_g / g, design ground acceleration on type-A ground over g [-], >= 0.
    soil_factor : float
        S, soil factor [-], > 0.
    z : float
        Height of the element above the foundation [m], 0 <= z <= H.
    H : float
        Building height from the foundation [m], > 0.
    Ta : float
        Fundamental period of the element (here the tower) [s], >= 0.
    T1 : float
        Fundamental period of the building in the relevant direction [s], > 0.

    Returns
    -------
    float
        S_a as a fraction of g [-] (multiply by g for m/s^2).
    """
    alpha_s = _check_common(ag_over_g, soil_factor, z, H, Ta, T1)
    ratio = 1.0 - Ta / T1
    value = alpha_s * (3.0 * (1.0 + z / H) / (1.0 + ratio**2) - 0.5)
    return float(max(value, alpha_s))


def ntc_floor_parameters(T1: float) -> tuple[float, float, float]:
    """Return (a, b, a_p) of Circolare 2019 Table C7.2.I for a building period T_1 [s].

    ``T_1 <= 0.5 s``: (0.8, 1.4, 5.0); ``0.5 < T_1 <= 1.0 s``: (0.3, 1.2, 4.0);
    ``T_1 > 1.0 s``: (0.3, 1.0, 2.5).
    """
    _check_positive("T1", T1)
    row = next(row for row in NTC_FLOOR_TABLE if T1 <= row[0])  # the last row has no bound
    return row[1], row[2], row[3]


def ntc_floor_acceleration(
    ag_over_g: float,
    soil_factor: float,
    z: float,
    H: float,
    Ta: float,
    T1: float,
) -> float:
    """Floor spectral acceleration, Circolare 2019 §C7.2.3 eq. C7.2.11 (NTC 2018 §7.2.3).

    Simplified floor spectrum for buildings whose response is dominated by the
    first mode (framed structures in the Circolare), with (a, b, a_p) from
    :func:`ntc_floor_parameters` (Table C7.2.I)::

        S_a = alpha S (1 + z/H) a_p / [1 + (a_p - 1)(1 - T_a/(a T_1))^2]   T_a < a T_1
        S_a = alpha S (1 + z/H) a_p                                         a T_1 <= T_a <= b T_1
        S_a = alpha S (1 + z/H) a_p / [1 + (a_p - 1)(1 - T_a/(b T_1))^2]   T_a > b T_1

    The branches meet continuously at ``a T_1`` and ``b T_1``; at ``T_a = 0`` the
    floor PGA is ``alpha S (1 + z/H)``. No lower bound is applied for long ``T_a``.

    Parameters
    ----------
    ag_over_g : float
        alpha = a_g / g, ground acceleration on type-A ground over g [-], >= 0.
    soil_factor : float
        S, soil (stratigraphic x topographic) factor [-], > 0.
    z : float
        Height of the element above the foundation [m], 0 <= z <= H.
    H : float
        Building height from the foundation [m], > 0.
    Ta : float
        Fundamental period of the element (here the tower) [s], >= 0.
    T1 : float
        Fundamental period of the building [s], > 0.

    Returns
    -------
    float
        S_a as a fraction of g [-] (multiply by g for m/s^2).
    """
    alpha_s = _check_common(ag_over_g, soil_factor, z, H, Ta, T1)
    a, b, a_p = ntc_floor_parameters(T1)
    plateau = alpha_s * (1.0 + z / H) * a_p
    if Ta < a * T1:
        return float(plateau / (1.0 + (a_p - 1.0) * (1.0 - Ta / (a * T1)) ** 2))
    if Ta <= b * T1:
        return float(plateau)
    return float(plateau / (1.0 + (a_p - 1.0) * (1.0 - Ta / (b * T1)) ** 2))


#: Floor-spectrum formulas by code name, for :func:`floor_amplitude`.
FLOOR_SPECTRA = {"ec8": ec8_floor_acceleration, "ntc": ntc_floor_acceleration}


def floor_amplitude(
    code: str,
    *,
    ag_over_g: float,
    soil_factor: float,
    z: float,
    H: float,
    Ta: float,
    T1: float,
) -> float:
    """Amplitude [m/s^2] of a harmonic or pulse of period ``Ta`` at the floor spectral acceleration.

    Use it as ``A`` in :func:`rockscreen.pipeline.motion.excitations.harmonic` or
    :func:`rockscreen.pipeline.motion.excitations.pulse` with frequency ``1/Ta``.

    Parameters
    ----------
    code : {"ec8", "ntc"}
        Which floor spectrum: Eurocode 8 eq. 4.25 or Circolare 2019 eq. C7.2.11.
    ag_over_g, soil_factor, z, H, Ta, T1
        As in :func:`ec8_floor_acceleration` and :func:`ntc_floor_acceleration`.

    Returns
    -------
    float
        S_a * g [m/s^2], with g = 9.81 m/s^2.
    """
    if code not in FLOOR_SPECTRA:
        raise ParameterError(f"code={code!r} is not a floor spectrum; allowed: ec8, ntc")
    return G * FLOOR_SPECTRA[code](ag_over_g, soil_factor, z, H, Ta, T1)


def building_period_from_height(H: float, law: str = "faccio2010") -> float:
    """Empirical fundamental period T_1 [s] of a masonry structure of height H [m].

    Laws (``law`` names): ``faccio2010`` 0.0187 H (Faccio et al. 2010, TURRIS
    towers; default), ``ec8`` 0.05 H^0.75 (EN 1998-1 eq. 4.6), ``rainieri-fabbrocino``
    0.01137 H^1.138, ``shakya`` 0.0151 H^1.08. The tower laws were fitted on
    slender towers; for a church hall they are an order-of-magnitude estimate,
    to be replaced by an identified period when one is known.

    Parameters
    ----------
    H : float
        Height [m], > 0.
    law : str
        One of :data:`PERIOD_LAWS`.

    Returns
    -------
    float
        T_1 [s].
    """
    _check_positive("H", H)
    if law not in PERIOD_LAWS:
        raise ParameterError(
            f"law={law!r} is not a period law; allowed: {', '.join(sorted(PERIOD_LAWS))}"
        )
    return float(PERIOD_LAWS[law](H))


def linear_mode_participation(n_storeys: int | None = None) -> float:
    """First-mode participation Gamma of a linear mode shape phi = z/H, uniform mass.

    ``Gamma = sum(m phi) / sum(m phi^2) = 3n / (2n + 1)`` for ``n`` equal storeys
    (1.0 for one storey, 1.2 for two), and 3/2 for a continuous cantilever
    (``n_storeys=None``). With phi(H) = 1 the product Gamma phi(z) is ``Gamma z/H``.

    Parameters
    ----------
    n_storeys : int, optional
        Number of equal storeys with equal masses; None for distributed mass.

    Returns
    -------
    float
        Gamma [-].
    """
    if n_storeys is None:
        return LINEAR_MODE_PARTICIPATION
    if int(n_storeys) != n_storeys or n_storeys < 1:
        raise ParameterError(f"n_storeys={n_storeys!r} must be an integer >= 1")
    return 3.0 * n_storeys / (2.0 * n_storeys + 1.0)


def modal_floor_accelerogram(
    acc: np.ndarray,
    dt: float,
    *,
    building_period: float,
    damping: float = 0.05,
    participation: float = LINEAR_MODE_PARTICIPATION,
    mode_shape_at_base: float = 1.0,
) -> np.ndarray:
    """Absolute acceleration at the tower's base from a ground record, first mode only.

    ``a_floor(t) = a_g(t) + Gamma phi(z) u1''(t)``, where ``u1`` solves
    ``u1'' + 2 zeta omega1 u1' + omega1^2 u1 = -a_g`` (modal coordinate, relative
    to the ground) and is integrated exactly for piecewise-linear ``a_g`` with the
    recurrence of :func:`rockscreen.pipeline.motion.spectra.sdof_response` (run as one filter on the
    record), so ``u1'' = (total acceleration of the oscillator) - a_g``. Higher modes and
    soil-structure interaction are neglected; the building stays elastic.

    Defaults: ``Gamma = 1.5`` and ``phi = 1``, i.e. the tower stands at the top
    (z = H) of a building with distributed uniform mass and a linear first mode
    (:func:`linear_mode_participation`); for a base at height z use
    ``mode_shape_at_base = z/H``. A very stiff building (``T_1 -> 0``) returns the
    ground motion; at resonance the floor motion is amplified.

    Parameters
    ----------
    acc : numpy.ndarray
        Ground acceleration a_g [m/s^2] at ``t_k = k*dt``, shape (n,).
    dt : float
        Sampling step [s], > 0.
    building_period : float
        First-mode period T_1 [s], > 0 (see :func:`building_period_from_height`).
    damping : float
        First-mode damping ratio zeta [-], 0 <= zeta < 1 (default 0.05).
    participation : float
        Participation factor Gamma [-] of the first mode (mode shape normalised to 1
        at the top), > 0.
    mode_shape_at_base : float
        phi(z) at the tower's base [-], >= 0 (1 at the top of the building).

    Returns
    -------
    numpy.ndarray
        Floor acceleration [m/s^2] on the same grid, shape (n,).

    Notes
    -----
    The output is sampled at ``dt`` like the input; keep ``dt`` well below
    ``T_1 / 10`` so that the amplified component is well resolved.
    """
    _check_positive("building_period", building_period)
    _check_positive("participation", participation)
    if not np.isfinite(mode_shape_at_base) or mode_shape_at_base < 0.0:
        raise ParameterError(
            f"mode_shape_at_base={mode_shape_at_base!r} must be a finite number >= 0"
        )
    ground = np.asarray(acc, dtype=float)
    total = _total_acceleration(ground, dt, building_period, damping)
    relative = total - ground
    return ground + participation * mode_shape_at_base * relative


def _total_acceleration(acc: np.ndarray, dt: float, period: float, damping: float) -> np.ndarray:
    """Total acceleration of an oscillator from rest, as ``sdof_response``, in one filter.

    ``period`` [s] is checked by the caller (:func:`modal_floor_accelerogram`).

    The exact recurrence (:func:`rockscreen.pipeline.motion.spectra.recurrence`) is a second-order
    all-pole filter fed by ``g[i] = gamma0 a[i] + gamma1 a[i+1]``; the total
    acceleration ``-(omega^2 u + 2 zeta omega u')`` (equal to the third output of
    :func:`pipeline.motion.spectra.sdof_response` to rounding) is a linear combination of its two
    states, hence one filter with a 3-tap numerator on the record itself. The initial
    state makes the oscillator start at rest (``u[0] = u'[0] = 0``). One
    :func:`scipy.signal.lfilter` pass instead of two plus a dozen array passes: the
    campaign computes this for every component of every tower with building data.
    """
    acc = check_record(acc, dt)
    check_damping(damping)
    coefficients = recurrence(period, damping, dt)
    phi, g0, g1 = coefficients.phi, coefficients.gamma0, coefficients.gamma1
    # Numerators of u and u' (adjugate of zI - phi applied to g, delayed once).
    # e: the adjugate terms of a step before the record (g[-1]), which must not count.
    e_u = -phi[1, 1] * g1[0] + phi[0, 1] * g1[1]
    e_v = -phi[0, 0] * g1[1] + phi[1, 0] * g1[0]
    b_u = np.array([g1[0], g0[0] + e_u, -phi[1, 1] * g0[0] + phi[0, 1] * g0[1]])
    b_v = np.array([g1[1], g0[1] + e_v, -phi[0, 0] * g0[1] + phi[1, 0] * g0[0]])
    omega = 2.0 * np.pi / period
    weights = np.array([omega**2, 2.0 * damping * omega])
    b_total = -(weights[0] * b_u + weights[1] * b_v)
    e_total = -(weights[0] * e_u + weights[1] * e_v)
    denominator = coefficients.denominator
    # Transposed direct form II: this initial state makes the output start at rest and
    # drops the terms of the (nonexistent) step before the first sample.
    initial = [-b_total[0] * acc[0], -e_total * acc[0]]
    total, _ = lfilter(b_total, denominator, acc, zi=initial)
    return total


def _check_positive(name: str, value: float) -> None:
    if not np.isfinite(value) or value <= 0.0:
        raise ParameterError(f"{name}={value!r} must be a finite number > 0")


def _check_common(
    ag_over_g: float,
    soil_factor: float,
    z: float,
    H: float,
    Ta: float,
    T1: float,
) -> float:
    """Validate the floor-spectrum inputs; return alpha S [-]."""
    if not np.isfinite(ag_over_g) or ag_over_g < 0.0:
        raise ParameterError(f"ag_over_g={ag_over_g!r} must be a finite number >= 0")
    _check_positive("soil_factor", soil_factor)
    _check_positive("H", H)
    _check_positive("T1", T1)
    if not np.isfinite(z) or not 0.0 <= z <= H:
        raise ParameterError(f"z={z!r} must lie in [0, H] = [0, {H!r}] [m]")
    if not np.isfinite(Ta) or Ta < 0.0:
        raise ParameterError(f"Ta={Ta!r} must be a finite number >= 0 [s]")
    return ag_over_g * soil_factor
