"""Best estimates and their epistemic uncertainty (issue 31): priors, capacities, risk, rank.

The code's checks (:mod:`rockscreen.pipeline.risk.checks`) answer "does the tower meet
the code?"; this package answers "how likely is it to fail, and how sure are we?": the
priors of what a geometry-only inventory does not say (:mod:`.priors`, a region's priors
file :mod:`.region`; a belfry's, the default of ``assess``, :mod:`.belfry`) and the
best-estimate capacity of the shaft at mean strengths, with no partial or confidence factor,
for each sample of them (:mod:`.shaft`), the kinematic capacities at F_C = 1
(:mod:`.kinematic`, all samples' checks at once in :mod:`.kinematic_batch`), the tower's
risk over the samples (:mod:`.risk`), the region's ranking (:mod:`.rank`) and what to
survey first (:mod:`.sensitivity`).
``docs/uncertainty.md``.
"""

from rockscreen.pipeline.risk.uncertainty.priors import RegionPriors, TowerPriors
from rockscreen.pipeline.risk.uncertainty.region import read_region_priors
from rockscreen.pipeline.risk.uncertainty.shaft import (
    ShaftCapacity,
    best_estimate_lv1,
    shaft_capacity,
)

__all__ = [
    "RegionPriors",
    "ShaftCapacity",
    "TowerPriors",
    "best_estimate_lv1",
    "read_region_priors",
    "shaft_capacity",
]
