"""The site hazard curve and the mean annual frequency of overturning.

Hazard curve: at the tabulated return periods ``TR_i`` of NTC 2018 (Allegato B) the site's
ag on rock ``a_i`` [g] is exceeded with mean annual frequency ``lambda_i = 1 / TR_i``
[1/y]. Between points ``log lambda`` is linear in ``log a`` (a power law per segment: the
log-log rule of Allegato A, eq. 4, read the other way). Beyond the first and the last
point the end segments continue as power laws ``lambda = lambda_i (a / a_i)^-k`` with
their own slope ``k``: the table itself stops at 30 and 2475 years (NTC 2018), so any
value there is an extrapolation and is flagged as such by the callers.

Risk integral (Cornell et al. 2002, J. Struct. Eng. 128(4); Jalayer & Cornell 2009,
Earthquake Eng. Struct. Dyn. 38(8)):

    lambda_C = integral P(C | a) |d lambda(a)|

computed on ``x = ln a`` as ``int Phi((x - ln theta) / beta) k(x) lambda(x) dx`` (``k(x)``
the local slope, ``|d lambda / dx| = k lambda``) with the trapezoidal rule on a fine
uniform grid from ``ln theta - (12 + k_max beta) beta`` (below it the integrand is
negligible) to ``ln theta + 12 beta``; above that ``P(C | a) = 1`` to machine precision and
the rest of the integral is exactly ``lambda`` at the grid's end, which is added. For a
single power law ``lambda(a) = k0 a^-k`` it reproduces Cornell's closed form
``lambda_C = k0 theta^-k exp(k^2 beta^2 / 2)`` (tested to much better than 2 %).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.special import ndtr

from rockscreen.pipeline.archive.risk_schema import EXTRAPOLATION_SHARE_LIMIT
from rockscreen.pipeline.errors import RiskError
from rockscreen.solver.docstrings import fill_doc

__all__ = [
    "EXTRAPOLATION_SHARE_LIMIT",
    "HazardCurve",
    "annual_rate_of_overturning",
    "cornell_closed_form",
    "extrapolated_shares",
    "probability_in",
]


@dataclass(frozen=True)
class HazardCurve:
    """A piecewise power-law hazard curve of ag on rock."""

    #: Strictly increasing ag [g].
    ag_g: np.ndarray
    #: Mean annual frequency of exceedance at each [1/y], strictly decreasing.
    rate_per_y: np.ndarray

    @classmethod
    def from_return_periods(cls, return_periods_y, ag_g) -> HazardCurve:
        """Build the curve from tabulated return periods [y] and ag [g].

        Points whose ag does not increase with the return period (a tie of rounded table
        values) are dropped, keeping the shortest return period of the tie.

        Raises
        ------
        RiskError
            For fewer than two usable points, or non-positive values.
        """
        tr = np.asarray(return_periods_y, dtype=float)
        a = np.asarray(ag_g, dtype=float)
        if tr.shape != a.shape or tr.ndim != 1:
            raise RiskError(f"hazard curve: {tr.size} return periods for {a.size} ag values")
        if not (np.all(tr > 0) and np.all(a > 0) and np.all(np.isfinite(tr * a))):
            raise RiskError(
                f"hazard curve: return periods [y] and ag [g] must be finite and > 0; got "
                f"TR={tr.tolist()}, ag={a.tolist()}"
            )
        order = np.argsort(tr)
        tr, a = tr[order], a[order]
        keep = [0]
        for i in range(1, len(a)):
            if a[i] > a[keep[-1]]:
                keep.append(i)
        if len(keep) < 2:
            raise RiskError(
                f"hazard curve: ag must grow with the return period at two points at least; "
                f"got ag={a.tolist()} [g]"
            )
        return cls(a[keep].copy(), 1.0 / tr[keep])

    @cached_property
    def _logs(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Return ``ln a_i``, ``ln lambda_i`` and the slopes, computed once (read-only).

        The risk integrals read them thousands of times per tower (the bootstrap's
        ``lambda_C``, the screening risk's rates); the values are those computed on every
        call before, bit for bit. The curve's arrays are not to be changed in place.
        """
        ln_a, ln_l = np.log(self.ag_g), np.log(self.rate_per_y)
        slopes = -np.diff(ln_l) / np.diff(ln_a)
        for values in (ln_a, ln_l, slopes):
            values.setflags(write=False)
        return ln_a, ln_l, slopes

    @property
    def slopes(self) -> np.ndarray:
        """Return ``k_i = -d ln(lambda) / d ln(a)`` of each segment [-] (read-only)."""
        return self._logs[2]

    def _segment(self, ln_a: np.ndarray) -> np.ndarray:
        edges = self._logs[0][1:-1]
        return np.searchsorted(edges, ln_a, side="right")

    def rate(self, ag_g) -> np.ndarray | float:
        """Return the mean annual frequency of exceedance of ``ag`` [1/y] (module docstring)."""
        ln_a = np.log(np.asarray(ag_g, dtype=float))
        seg = self._segment(ln_a)
        log_a, log_l, slopes = self._logs
        ln_a0 = log_a[seg]
        ln_l0 = log_l[seg]
        out = np.exp(ln_l0 - slopes[seg] * (ln_a - ln_a0))
        return float(out) if np.ndim(out) == 0 else out

    def return_period(self, ag_g: float) -> float:
        """Return the return period of ``ag`` [y]: ``1 / rate(ag)``."""
        return 1.0 / float(self.rate(ag_g))

    def ag_at(self, return_period_y: float) -> float:
        """Return the ag [g] whose return period is ``return_period_y`` [y] (inverse of rate)."""
        ln_l = -math.log(return_period_y)
        ln_rates = self._logs[1]
        seg = int(np.searchsorted(-ln_rates[1:-1], -ln_l, side="right"))
        ln_a0, ln_l0 = math.log(self.ag_g[seg]), ln_rates[seg]
        return math.exp(ln_a0 - (ln_l - ln_l0) / self.slopes[seg])

    def covers(self, ag_g: float) -> bool:
        """Whether ``ag`` lies inside the tabulated range (no extrapolation)."""
        return bool(self.ag_g[0] <= ag_g <= self.ag_g[-1])


#: Docstring blocks the rate functions share (:func:`rockscreen.solver.docstrings.fill_doc`).
_DOCS = {
    "curve_fragility": """
curve : HazardCurve
    The site's hazard curve.
median_g : float
    Fragility median [g], > 0.
beta : float
    Fragility dispersion [-], > 0.
n_points : int
    Points of the integration grid in ``ln a``.
""",
}


@fill_doc(_DOCS)
def annual_rate_of_overturning(
    curve: HazardCurve, median_g: float, beta: float, *, n_points: int = 4001
) -> float:
    """Return ``lambda_C = int P(C | a) |d lambda(a)|`` [1/y] (module docstring).

    Parameters
    ----------
    %(curve_fragility)s

    Raises
    ------
    RiskError
        For a non-positive or non-finite median or dispersion.
    """
    if not (math.isfinite(median_g) and median_g > 0 and math.isfinite(beta) and beta > 0):
        raise RiskError(
            f"risk integral: median {median_g!r} [g] and beta {beta!r} [-] must be finite > 0"
        )
    ln_m = math.log(median_g)
    k_max = float(np.max(curve.slopes))
    x = np.linspace(ln_m - (12.0 + k_max * beta) * beta, ln_m + 12.0 * beta, n_points)
    seg = curve._segment(x)
    integrand = ndtr((x - ln_m) / beta) * curve.slopes[seg] * curve.rate(np.exp(x))
    # Above the grid P(C | a) = 1 to machine precision: the rest is lambda at the grid's end.
    return float(np.trapezoid(integrand, x)) + float(curve.rate(math.exp(x[-1])))


def _hazard_weighted(
    curve: HazardCurve, ln_m: float, beta: float, lo: float, hi: float, n_points: int
) -> float:
    """Return ``int_lo^hi lambda(e^x) phi((x - ln_m) / beta) / beta dx`` (``x = ln a``) [1/y].

    ``lambda_C`` by parts: ``int lambda(a) dP(C | a)``, the hazard read at every capacity
    the fragility allows, weighted by the fragility's density. The product peaks near
    ``ln_m - k beta^2``; the grid spans 12 dispersions around it (``k`` the steepest slope).
    """
    k_max = float(np.max(curve.slopes))
    a = max(lo, ln_m - k_max * beta * beta - 12.0 * beta)
    b = min(hi, ln_m + 12.0 * beta)
    if b <= a:
        return 0.0
    x = np.linspace(a, b, n_points)
    density = np.exp(-0.5 * ((x - ln_m) / beta) ** 2) / (beta * math.sqrt(2.0 * math.pi))
    return float(np.trapezoid(curve.rate(np.exp(x)) * density, x))


@fill_doc(_DOCS)
def extrapolated_shares(
    curve: HazardCurve, median_g: float, beta: float, *, n_points: int = 4001
) -> tuple[float, float]:
    """Return the shares of ``lambda_C`` that read the extrapolated hazard curve [-].

    The tabulated curve stops at its last point (TR = 2475 y for the NTC table) and its
    first (TR = 30 y); beyond them :class:`HazardCurve` continues the end segments as power
    laws, which the code does not define. Integrated by parts, ``lambda_C = int lambda(a)
    dP(C | a)``: each capacity ``a`` the fragility allows contributes the hazard at ``a``.
    The shares are the parts whose hazard value comes from the extrapolation,
    ``int_{a > a_last} lambda dP / lambda_C`` and ``int_{a < a_first} lambda dP /
    lambda_C``. (The other form, ``int_{a > a_last} P(C | a) |d lambda|``, would count
    ``lambda(a_last) P(C | a_last)``, a tabulated value, as extrapolated: a steep fragility
    with its median at ``a_last`` would read as mostly extrapolated when it is not.) For a
    power-law hazard ``k0 a^-k`` the upper share is ``Phi((ln m - k beta^2 - ln a_last) /
    beta)``.

    Parameters
    ----------
    %(curve_fragility)s

    Returns
    -------
    above, below : float
        Shares from beyond the last and from below the first tabulated point [-].

    Raises
    ------
    RiskError
        For a non-positive or non-finite median or dispersion.
    """
    total = annual_rate_of_overturning(curve, median_g, beta, n_points=n_points)
    ln_m = math.log(median_g)
    ln_first, ln_last = math.log(curve.ag_g[0]), math.log(curve.ag_g[-1])
    above = _hazard_weighted(curve, ln_m, beta, ln_last, math.inf, n_points)
    below = _hazard_weighted(curve, ln_m, beta, -math.inf, ln_first, n_points)
    return min(above / total, 1.0), min(below / total, 1.0)


def cornell_closed_form(k0: float, k: float, median_g: float, beta: float) -> float:
    """Return ``k0 median^-k exp(k^2 beta^2 / 2)`` [1/y] (Cornell et al. 2002, eq. 11).

    The mean annual frequency for the power-law hazard ``lambda(a) = k0 a^-k`` [1/y] and a
    lognormal fragility of median ``median_g`` [g] and dispersion ``beta`` [-].
    """
    return k0 * median_g ** (-k) * math.exp(0.5 * k * k * beta * beta)


def probability_in(rate_per_y: float, years: float = 50.0) -> float:
    """Return the Poisson probability of at least one event in ``years`` [-].

    ``1 - exp(-years * rate_per_y)``, with ``rate_per_y`` [1/y] and ``years`` [y].
    """
    return -math.expm1(-years * rate_per_y)
