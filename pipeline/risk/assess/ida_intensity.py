"""What an incremental dynamic analysis searches and finds: its options, the intensities.

The options of the search (:class:`IdaOptions`: the models, the scan's ratio, the
bisection's tolerance, the cap :data:`DEFAULT_CAP_PGA_G`, the SLV level
:data:`SLV_THETA_RATIO`), what it finds for one record component (:class:`CollapseIntensity`,
censored with one of :data:`CENSOR_REASONS`), the intensity measure (:func:`motion_pga_g`),
and the records' intensities combined and fitted (:func:`record_collapse`,
:func:`ida_fragility`). The search itself is
:mod:`rockscreen.pipeline.risk.assess.ida_search`; the IDA's method, its intensity measure
and its censoring are described in :mod:`rockscreen.pipeline.risk.assess.ida`.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field

import numpy as np

from rockscreen.pipeline.engine.motion import GroundMotion
from rockscreen.pipeline.engine.registry import model_names
from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.measures.censored_fit import CensoredFit, fit_censored_lognormal
from rockscreen.solver.constants import G

__all__ = [
    "CENSOR_REASONS",
    "DEFAULT_CAP_PGA_G",
    "SLV_THETA_RATIO",
    "CollapseIntensity",
    "IdaOptions",
    "ida_fragility",
    "motion_pga_g",
    "record_collapse",
]

#: SLV (life-safety) level of a local mechanism as theta_max/alpha [-]: the Circolare 2019
#: (Circ. 21/01/2019 n. 7, §C8.7.1.2.1.6, PDF p. 276) places the SLV displacement of a local
#: mechanism at "il 40% dello spostamento d_0" at which its capacity vanishes (the kinematic
#: analysis' ``d_SLV = 0.4 d_0``); for the rigid block the overturning rotation is alpha, so
#: the level is ``theta_max / alpha >= 0.4``.
SLV_THETA_RATIO = 0.4

#: Default cap of the search as the PGA of the scaled motion [g] (why:
#: :mod:`rockscreen.pipeline.risk.assess.ida`, "Censoring").
DEFAULT_CAP_PGA_G = 3.0

#: ``censor_reason`` values: no overturning up to the cap; the model's vertical limit first;
#: the record's other component reaches the level lower, so this one's search stopped.
CENSOR_REASONS = ("cap", "vertical_limit", "other_component")


@dataclass(frozen=True)
class IdaOptions:
    """How the collapse intensity is searched."""

    #: Models enabled (names of the campaign models of the registry; default all).
    models: tuple[str, ...] = field(default_factory=model_names)
    #: Geometric step of the upward scan, > 1 [-] (the resolution of the search).
    ratio: float = 1.2
    #: Relative width of the final bisection bracket, > 0 [-].
    tolerance: float = 0.01
    #: The search stops where the scaled motion's PGA reaches this [g].
    cap_pga_g: float = DEFAULT_CAP_PGA_G
    #: Free motion followed after the record [s] (the solvers' ``max_free_time``).
    free_motion_s: float = 60.0
    #: Damage level searched besides overturning, theta_max/alpha [-].
    slv_theta_ratio: float = SLV_THETA_RATIO
    #: Stop each solve's free motion once its verdict is certain (``docs/theory.md``,
    #: :func:`rockscreen.pipeline.engine.cases.screen_case`); False: the reference path.
    early_stop: bool = True
    #: Search a record's components together and stop a component's level once the other
    #: component reaches it lower (the record's intensities are those of the full search,
    #: with fewer solves: :func:`rockscreen.pipeline.engine.search.joint_first_exceedances`);
    #: False: every component searched in full (the reference).
    adaptive: bool = True

    def __post_init__(self) -> None:
        if not (self.ratio > 1.0 and math.isfinite(self.ratio)):
            raise RiskError(f"IDA: ratio={self.ratio!r} must be a finite number > 1")
        if not (0.0 < self.tolerance < 1.0):
            raise RiskError(f"IDA: tolerance={self.tolerance!r} must be in (0, 1)")
        if not (self.cap_pga_g > 0.0 and math.isfinite(self.cap_pga_g)):
            raise RiskError(f"IDA: cap_pga_g={self.cap_pga_g!r} g must be a finite number > 0")
        if not (0.0 < self.slv_theta_ratio <= 1.0):
            raise RiskError(f"IDA: slv_theta_ratio={self.slv_theta_ratio!r} must be in (0, 1]")


@dataclass(frozen=True)
class CollapseIntensity:
    """The collapse and SLV intensities of one record component against a tower's models.

    When ``censored`` (``slv_censored``) the scale and intensity are the censoring values:
    the largest factor, and its PGA, up to which the search saw no overturning (no SLV
    level), a lower bound of the capacity.
    """

    #: The motion's name (``GroundMotion.record_id``).
    record: str
    #: The component (``"X"``, ``"Y"``, or a channel's letter).
    component: str
    #: The models searched together (comma-separated names): any of them counts.
    models: str
    #: PGA of the motion at scale 1 [g]: the larger peak of its horizontal channels.
    pga_g: float
    #: Smallest scale factor found to overturn the tower [-] (censoring factor if censored).
    collapse_scale: float
    #: ``collapse_scale * pga_g`` [g] (``cap_pga_g`` for a component without motion, whose
    #: scale is ``inf``).
    collapse_pga_g: float
    #: Smallest scale factor found to reach theta_max/alpha >= the SLV level or overturn [-].
    slv_scale: float
    #: ``slv_scale * pga_g`` [g].
    slv_pga_g: float
    #: No overturning found up to the censoring factor.
    censored: bool
    #: No SLV level found up to the censoring factor.
    slv_censored: bool
    #: Why the search stopped short of a level: ``"cap"`` or ``"vertical_limit"``; ``""``
    #: when neither level is censored.
    censor_reason: str
    #: Largest factor known safe below ``collapse_scale`` [-] (the bisection's lower end;
    #: the uplift-free factor when the scan's first factor overturned).
    collapse_lower_scale: float
    #: Solver calls made (motionless cases and shared verdicts are not solves).
    n_solves: int


def motion_pga_g(motion: GroundMotion) -> float:
    """Return the PGA of ``motion`` [g]: the larger peak of its horizontal channels.

    Parameters
    ----------
    motion : GroundMotion
        Horizontal accelerations in [m/s²].
    """
    peaks = [float(np.max(np.abs(h))) for h in motion.horizontals if len(h)]
    return max(peaks, default=0.0) / G


def record_collapse(results: Sequence[CollapseIntensity], level: str = "collapse") -> dict:
    """Combine the components of each record: the tower is lost when either component fails.

    The record's scale is the smallest of its components'; it is censored when that
    smallest one is (the record then survived every component up to it). Components of a
    record share its PGA, so the intensity combines the same way.

    Parameters
    ----------
    results : sequence of CollapseIntensity
    level : {'collapse', 'slv'}

    Returns
    -------
    dict
        record -> ``(intensity [g], censored, censor_reason)``, in first-seen order.
    """
    if level not in ("collapse", "slv"):
        raise RiskError(f"IDA: level {level!r} is not 'collapse' or 'slv'")
    out: dict[str, tuple[float, bool, str]] = {}
    for r in results:
        if level == "collapse":
            value, censored = r.collapse_pga_g, r.censored
        else:
            value, censored = r.slv_pga_g, r.slv_censored
        reason = r.censor_reason if censored else ""
        best = out.get(r.record)
        # Ties: an observed level beats a censoring at the same intensity.
        if best is None or (value, censored) < (best[0], best[1]):
            out[r.record] = (value, censored, reason)
    return out


def ida_fragility(results: Sequence[CollapseIntensity], level: str = "collapse") -> CensoredFit:
    """Fit the censored lognormal fragility in PGA to the records' intensities.

    Parameters
    ----------
    results : sequence of CollapseIntensity
        Components of the records (combined per record by :func:`record_collapse`).
    level : {'collapse', 'slv'}

    Returns
    -------
    CensoredFit
    """
    combined = record_collapse(results, level)
    intensities = [value for value, _, _ in combined.values()]
    censored = [flag for _, flag, _ in combined.values()]
    return fit_censored_lognormal(intensities, censored)
