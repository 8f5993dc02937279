"""LV1 quantities of the MiC 2011 Guidelines from a fragility and the site hazard.

The Guidelines for cultural heritage (DPCM 9/2/2011, "Linee Guida per la valutazione e
riduzione del rischio sismico del patrimonio culturale", §2.4 and §5.4; Circolare 2019
C8 for existing buildings) measure the seismic safety of a monument (LV1) by

- the capacity acceleration ``a_C``: the ag on rock at which the limit state is reached,
  divided by the confidence factor ``F_C`` of the knowledge level (capacity / F_C, as the
  kinematic analysis divides its capacity curve, ``a = alpha g / (e* FC)``: FC "si applica
  direttamente alla capacità in termini di resistenza", Circolare 2019 §C8.7.1.2.1.3, eq.
  [C8.7.1.3] (PDF p. 274); FC = 1.35, 1.2, 1.0 for LC1, LC2, LC3, §C8.5.4 (PDF p. 265); that
  the LV1 of the Guidelines divides its capacity the same way, DPCM 9/2/2011 §4.2 and §5.4:
  to be verified). ``assess`` passes the **SLV** fragility (theta_max/alpha >= 0.4,
  Circolare 2019 §C8.7.1.2.1.6 (PDF p. 276): d_SLV of a local mechanism is at most 40 % of
  the displacement d0 at which its capacity vanishes): ``a_C`` = its median / F_C [g];
- its return period ``T_R,C`` [y] on the site's hazard curve (log-log interpolation
  between the tabulated points, Allegato A eq. 4; beyond 30 or 2475 years the end segment
  of the site's curve is continued as a power law, and the value says it is extrapolated:
  the code's table does not define the hazard there);
- the safety index ``I_S = T_R,C / T_R,SLV`` [-], with ``T_R,SLV`` the return period of the
  life-safety limit state for the tower's nominal life and use class (NTC 2018 §2.4,
  §3.2.1);
- the acceleration factor ``f_a = a_C / a_g,SLV`` [-], ``a_g,SLV`` the site's ag at
  ``T_R,SLV``.

``I_S >= 1`` (equivalently ``f_a >= 1``) means the code's SLV action does not reach the
capacity. When the fragility median is a bound (``Fragility.bound``) every quantity here
is the same kind of bound and its note says so.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from rockscreen.pipeline.risk.measures.censored_fit import CensoredFit
from rockscreen.pipeline.risk.measures.fragility import Fragility
from rockscreen.pipeline.risk.measures.hazard_integral import HazardCurve
from rockscreen.pipeline.verdict.messages import Message, message, render_all

__all__ = ["LV1", "lv1_indices"]


@dataclass(frozen=True)
class LV1:
    """The LV1 quantities of one tower."""

    #: Capacity acceleration a_C on rock [g].
    capacity_pga_g: float
    #: Return period T_R,C of a_C on the site's hazard curve [y].
    capacity_return_period_y: float
    #: Return period of the SLV action T_R,SLV [y].
    tr_slv_y: float
    #: Site's ag at T_R,SLV [g].
    ag_slv_g: float
    #: I_S = T_R,C / T_R,SLV [-].
    safety_index: float
    #: f_a = a_C / a_g,SLV [-].
    acceleration_factor: float
    #: ``""``, ``"lower"`` or ``"upper"``: all four values above are that kind of bound.
    bound: str = ""
    #: Bounds and extrapolation (codes of :mod:`rockscreen.pipeline.verdict.catalogue.fits`);
    #: empty otherwise.
    messages: tuple[Message, ...] = field(default=())

    @property
    def note(self) -> str:
        """Return :attr:`messages` in English, joined by ``"; "`` (``""`` for none)."""
        return render_all(self.messages)


def lv1_indices(
    fragility: Fragility | CensoredFit,
    curve: HazardCurve,
    tr_slv_y: float,
    ag_slv_g: float,
    confidence_factor: float = 1.0,
) -> LV1:
    """Return the capacity acceleration, its return period, I_S and f_a of a tower.

    Parameters
    ----------
    fragility : Fragility or CensoredFit
        The tower's fragility of the limit state (a_C = its median / ``confidence_factor``).
    curve : HazardCurve
        The site's hazard curve.
    tr_slv_y : float
        Return period of the SLV action [y].
    ag_slv_g : float
        ag of the site at ``tr_slv_y`` [g].
    confidence_factor : float
        F_C [-] of the knowledge level (1: none).

    Returns
    -------
    LV1
    """
    a_c = float(fragility.median_g) / float(confidence_factor)
    tr_c = curve.return_period(a_c)
    notes = []
    if fragility.bound == "lower":
        notes.append(message("indices.lower_bounds"))
    elif fragility.bound == "upper":
        notes.append(message("indices.upper_bounds"))
    if not curve.covers(a_c):
        lo, hi = 1.0 / curve.rate_per_y[0], 1.0 / curve.rate_per_y[-1]
        notes.append(message("indices.tr_extrapolated", low=lo, high=hi))
    return LV1(
        capacity_pga_g=a_c,
        capacity_return_period_y=tr_c,
        tr_slv_y=float(tr_slv_y),
        ag_slv_g=float(ag_slv_g),
        safety_index=tr_c / float(tr_slv_y),
        acceleration_factor=a_c / float(ag_slv_g) if ag_slv_g > 0 else math.nan,
        bound=fragility.bound,
        messages=tuple(notes),
    )
