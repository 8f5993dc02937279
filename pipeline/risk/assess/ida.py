"""Collapse intensity per record: incremental dynamic analysis of one tower.

For one tower, one ground motion and each of its horizontal components (against the
tower's enabled models), the **collapse scale** is the smallest amplitude scale factor at
which the tower first overturns (any model: the tower is lost whatever the model that
predicts it), and the **SLV scale** the smallest factor at which it reaches the
life-safety damage level :data:`SLV_THETA_RATIO` (or overturns). The records of a set
give a sample of collapse intensities, fitted by
:func:`rockscreen.pipeline.risk.measures.censored_fit.fit_censored_lognormal` (Baker 2015,
Earthquake Spectra 31(1), 579-599, "incremental dynamic analysis"; Vamvatsikos & Cornell 2002).

Intensity measure
-----------------
The intensity of a scaled motion is its PGA: ``collapse_pga_g = collapse_scale *
pga_g``, where ``pga_g`` [g] is the motion's own PGA at scale 1 (the larger peak of its
horizontal channels, as given). The IM is a property of the motion alone, so the
components of one record share it and the record's collapse intensity is the smaller of
its components' (:func:`record_collapse`). A caller that scaled a record to a target
(e.g. a stripe's ag on rock with the record's factor ``k``) passes the scaled motion and
reads intensities in that motion's PGA; converting to the stripe's IM
(``collapse_scale * ag``) is the caller's business, not this module's.

The search
----------
Rocking is not monotone in amplitude (a block that overturns at ``f`` may survive at
``1.1 f``: the safe regions of Zhang & Makris 2001), so the search is the engine's one
scan-then-bisect (:func:`rockscreen.pipeline.engine.search.first_exceedance_factors`, also
the campaign's safety factor), not a plain bisection:

1. an upward geometric scan ``f_k = f_0 ratio**k`` (default ratio 1.2, steps of 20 %)
   from ``f_0`` = the uplift-free factor
   (:func:`rockscreen.pipeline.engine.uplift.uplift_free_factor`: up to it no sample can
   lift the block, so nothing moves, and the first factor solved is ``f_0 ratio``) up to
   the cap (always on the grid), until the tower overturns; the first grid factor
   reaching the SLV level is noted on the way;
2. for each level, bisection between the last grid factor below it and the first one
   reaching it, until the bracket is narrower than ``tolerance`` (default 1 %) of its
   upper end; the upper end, a factor that reaches the level, is reported.

A window of overturning narrower than one grid step below the first overturning grid
factor can be missed: the grid step is the stated resolution of the search. Each scale
factor is solved once (both levels read the same verdicts). Overturning implies the SLV
level, so the SLV scale is never above the collapse scale.

The components of a record are searched together (``IdaOptions.adaptive``, default;
:func:`rockscreen.pipeline.engine.search.joint_first_exceedances`): the record's intensity
is the smaller of its components', so a component's level is left **settled** (censored
where its search stopped, reason ``"other_component"``) once the other component reaches it
lower. The record's intensities, censoring and reasons are those of the full search of
every component (:func:`record_collapse`), with fewer solves.

Censoring
---------
A component is **right-censored** (never dropped, never counted as overturning) when

- ``cap``: no overturning up to the cap, the factor at which the motion's PGA reaches
  ``cap_pga_g`` (default :data:`DEFAULT_CAP_PGA_G` = 3 g): the level of the largest PGAs
  ever recorded (about 3-4 g, e.g. Iwate-Miyagi 2008) and about three times the largest
  surface PGA of the Italian code hazard (the shipped NTC grid's largest ag on rock is
  0.62 g at T_R = 2475 y; times the soil and topography factors, about 1 g), where the
  annual rate of exceedance, and so the contribution to ``lambda_C``, is nil; for a
  slender tower (``tan(alpha) <= 0.3``) it is at least ten times the uplift threshold
  ``g tan(alpha)`` (20 times for the 0.6 m x 4 m block of the tests);
- ``other_component``: the record's other component reaches the level lower (the adaptive
  search above): a lower bound of this component's capacity, never the record's;
- ``vertical_limit``: the scaled vertical reaches -g first (the base would fall away
  from the tower; the rigid-block model no longer holds; the search stops just below
  that factor, ``-g / min(a_v)``, as the campaign's safety factor does), or the solver
  refuses the scaled motion as out of the model's validity
  (:func:`rockscreen.pipeline.engine.cases.screen_case` status ``vertical_limit``).

A censored component's scale and intensity are the censoring values: the largest factor
(and PGA) up to which the search saw no overturning, a lower bound of the capacity.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rockscreen.pipeline.engine.cases import BlockCache
from rockscreen.pipeline.engine.motion import GroundMotion, TowerComponent, tower_components
from rockscreen.pipeline.risk.assess.ida_intensity import (
    CENSOR_REASONS,
    DEFAULT_CAP_PGA_G,
    SLV_THETA_RATIO,
    CollapseIntensity,
    IdaOptions,
    ida_fragility,
    motion_pga_g,
    record_collapse,
)
from rockscreen.pipeline.risk.assess.ida_search import prepare_search, search_record
from rockscreen.stations.tower import Tower

__all__ = [
    "CENSOR_REASONS",
    "DEFAULT_CAP_PGA_G",
    "SLV_THETA_RATIO",
    "CollapseIntensity",
    "IdaOptions",
    "component_collapse_intensity",
    "ida_fragility",
    "motion_pga_g",
    "record_collapse",
    "record_collapse_intensities",
]


def component_collapse_intensity(
    tower: Tower,
    record: str,
    component: str,
    acc: np.ndarray,
    width_m: float,
    axis: str | None,
    vertical: np.ndarray | None,
    dt: float,
    pga_g: float,
    options: IdaOptions | None = None,
    blocks: Any = None,
) -> CollapseIntensity:
    """Search the collapse and SLV scale factors of one component (module docstring).

    The component alone, searched in full (:func:`record_collapse_intensities` searches
    a record's components together).

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
    record : str
        The motion's name.
    component : str
        The component's name.
    acc : numpy.ndarray
        The component's ground acceleration at scale 1 [m/s²].
    width_m : float
        Block width in the component's direction [m].
    axis : {"x", "y"} or None
        The tower axis the component is along, None when it is along neither
        (:class:`rockscreen.pipeline.engine.motion.TowerComponent`): a part model's block
        follows it.
    vertical : numpy.ndarray or None
        Vertical ground acceleration at scale 1 [m/s²], positive up; scaled with ``acc``.
    dt : float
        Sampling step [s].
    pga_g : float
        The motion's PGA at scale 1 [g] (:func:`motion_pga_g`): the intensity is
        ``scale * pga_g``.
    options : IdaOptions, optional
    blocks : rockscreen.pipeline.engine.cases.BlockCache, optional
        The tower's blocks by width and axis.

    Returns
    -------
    CollapseIntensity
    """
    options = options or IdaOptions()
    blocks = BlockCache(tower) if blocks is None else blocks
    part = TowerComponent(component, acc, width_m, axis)
    search = prepare_search(tower, record, part, vertical, dt, pga_g, options, blocks)
    (result,) = search_record([search], options)
    return result


def record_collapse_intensities(
    tower: Tower,
    motion: GroundMotion,
    options: IdaOptions | None = None,
    blocks: Any = None,
) -> tuple[CollapseIntensity, ...]:
    """Return the collapse and SLV intensities of every component of ``motion``.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
    motion : GroundMotion
        The ground motion at scale 1 (e.g. ``suite_motion(record, 1.0)``); its vertical,
        when present, is scaled with the horizontals.
    options : IdaOptions, optional
    blocks : rockscreen.pipeline.engine.cases.BlockCache, optional
        The tower's blocks by width and axis, shared between records.

    Returns
    -------
    tuple of CollapseIntensity
        One per component of :func:`rockscreen.pipeline.engine.motion.tower_components`.
    """
    options = options or IdaOptions()
    blocks = BlockCache(tower) if blocks is None else blocks
    pga_g = motion_pga_g(motion)
    searches = [
        prepare_search(
            tower,
            motion.record_id,
            TowerComponent(component, acc, width, axis),
            motion.vertical,
            motion.dt,
            pga_g,
            options,
            blocks,
        )
        for component, acc, width, axis in tower_components(tower, motion)
    ]
    return search_record(searches, options)
