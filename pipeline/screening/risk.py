"""Per-tower risk of a run: the safety factor and the risk classes.

Safety factor
-------------
The safety factor of a tower is the smallest scale factor ``f`` on its governing
record (same component, same model, horizontal and vertical scaled together) that
overturns it. Rocking is **not monotone** in amplitude: a block that overturns at
``f`` may survive at ``1.1 f`` (the "safe regions" of Zhang & Makris 2001 and
Makris & Konstantinidis 2003). A plain bisection on ``[0, cap]`` could therefore
land above the smallest overturning factor. The search
(:func:`rockscreen.pipeline.engine.search.safety_factor`, the engine's one search, which
``assess``'s collapse intensities use too) instead

1. scans upward on a geometric grid ``f_k = f_0 * ratio**k`` (default ratio 1.2, i.e.
   steps of 20 %) up to ``cap`` (default 10), with ``1`` and ``cap`` always on the
   grid, stopping at the first factor that overturns;
2. bisects between the last safe factor and that first overturning factor until the
   bracket is narrower than ``tolerance`` (default 1 %) of its upper end, and
   reports the upper end (an overturning factor, so the value is never optimistic
   by more than the bracket).

The scan starts at ``f_0 = max(start, f_uplift)``, where ``f_uplift`` is the largest
factor at which the block provably cannot uplift (``|f a_h| < tan(alpha) (g - f |a_v|)``
at every sample): below it nothing moves, so nothing overturns. A narrow
overturning window between two grid points can still be missed; the grid step is the
documented resolution of the search. No overturning up to ``cap`` gives ``inf``.
The search stops just below the factor at which the scaled vertical acceleration
reaches ``-g`` (the base would fall away from the tower: the rigid-block model no longer
holds); that limit of the model is reported as such (``safety_factor_limit``), never as
a failure (:func:`rockscreen.pipeline.engine.search.vertical_limit_factor`).
Because ``1`` is on the grid, a tower that overturns under the record itself has a
safety factor ``<= 1``, and one that does not has a factor ``> 1`` only when no
grid factor below 1 overturns.

Risk classes
------------
Classes on the governing ``theta_max/alpha`` (normalised peak rotation) and the
safety factor ``SF``, checked from the worst down:

=============  ==============================================================
``collapse``   overturned under at least one record (then ``SF <= 1``)
``high``       ``theta_max/alpha >= 0.5`` or ``SF < 1.5``
``moderate``   ``theta_max/alpha >= 0.2`` or ``SF < 2.5``
``low``        ``theta_max/alpha >= 0.01`` (the tower rocks)
``none``       no appreciable rocking
=============  ==============================================================

Source of the thresholds: the normalised peak rotation ``|theta_max/alpha|`` is the
demand parameter of rocking damage states in the fragility study of D'Angela et al.
(Procedia Structural Integrity 78, 2026, 1617-1624), whose damage-state limits run
from 0.01 (onset of rocking) to 1.0 (static overturning); rockscreen uses their
lower end, 0.01, as "rocks", and their upper end, 1.0, is the overturning limit of the
energy-barrier verdict. The intermediate cut points 0.2 and 0.5 and the safety-factor
limits 1.5 and 2.5 are rockscreen's screening choices on that scale (not taken from a
paper); they are configuration keys (``[risk]``) so that an assessor can substitute
the limits of a code or study.
"""

from __future__ import annotations

from rockscreen.pipeline.vocabulary import RECORD_RISK_CLASSES

#: Risk classes, from the worst down.
RISK_CLASSES = RECORD_RISK_CLASSES


def risk_class(
    theta_max_over_alpha: float,
    overturned: bool,
    safety_factor_value: float,
    *,
    rocking_from: float = 0.01,
    moderate_from: float = 0.2,
    high_from: float = 0.5,
    sf_high_below: float = 1.5,
    sf_moderate_below: float = 2.5,
) -> str:
    """Return the risk class of a tower (one of :data:`RISK_CLASSES`).

    Parameters
    ----------
    theta_max_over_alpha : float
        Governing peak rotation over the slenderness angle [-].
    overturned : bool
        Overturned under at least one record.
    safety_factor_value : float
        Safety factor [-] (``inf`` when none up to the cap; NaN when not searched).
    rocking_from, moderate_from, high_from : float
        ``theta_max/alpha`` thresholds [-] (module docstring: values and source).
    sf_high_below, sf_moderate_below : float
        Safety-factor thresholds [-]; a NaN safety factor never triggers them.

    Returns
    -------
    str
    """
    if overturned:
        return "collapse"
    sf = safety_factor_value
    if theta_max_over_alpha >= high_from or sf < sf_high_below:
        return "high"
    if theta_max_over_alpha >= moderate_from or sf < sf_moderate_below:
        return "moderate"
    if theta_max_over_alpha >= rocking_from:
        return "low"
    return "none"
