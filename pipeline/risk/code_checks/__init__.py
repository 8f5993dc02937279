"""The code's own checks of a bell tower, beside the rocking dynamics (issue 22).

- :mod:`~rockscreen.pipeline.risk.code_checks.kinematic`: kinematic analysis of a rigid
  overturning mechanism, linear and non-linear (Circolare 2019 §C8.7.1.2.1, formerly C8A.4):
  its capacity and the checks;
- :mod:`~rockscreen.pipeline.risk.code_checks.kinematic_demand`: the demand at the
  mechanism's level (the structure beneath, activation and SLV demands);
- :mod:`~rockscreen.pipeline.risk.code_checks.floor_spectrum`: the Circolare's floor spectra
  for mechanisms at height (§C7.2.3);
- :mod:`~rockscreen.pipeline.risk.code_checks.mechanisms`: whole tower, belfry, bell gable;
- :mod:`~rockscreen.pipeline.risk.code_checks.tower_lv1`: the LV1 model of the Guidelines for
  towers (DPCM 9/2/2011 §5.4.4);
- :mod:`~rockscreen.pipeline.risk.code_checks.confidence`: knowledge levels, FC, Table C8.5.I;
- :mod:`~rockscreen.pipeline.risk.code_checks.site_capacity`: the capacity of a check on the
  site's hazard (T_R,C, a_C, I_S, f_a).

SI units throughout (m, kg, N, s, m/s2); accelerations in g only where a name ends in
``_g``. See ``docs/code_checks.md``.
"""

from rockscreen.pipeline.risk.code_checks.confidence import (
    CONFIDENCE_FACTORS,
    MASONRY_TYPES,
    MasonryType,
    confidence_factor,
    design_compressive_strength,
    masonry_elastic_modulus,
    masonry_strength,
)
from rockscreen.pipeline.risk.code_checks.kinematic import (
    KinematicCapacity,
    KinematicCheck,
    Mechanism,
    PointMass,
    RigidBlock,
    cantilever_period,
    kinematic_capacity,
    kinematic_check,
)
from rockscreen.pipeline.risk.code_checks.kinematic_demand import (
    ElevatedSupport,
    activation_demand,
    displacement_demand,
    elastic_spectral_demand,
    linear_demand,
)
from rockscreen.pipeline.risk.code_checks.mechanisms import (
    belfry_mechanism,
    bell_gable_mechanism,
    whole_tower_mechanism,
)
from rockscreen.pipeline.risk.code_checks.site_capacity import (
    SiteCapacity,
    SiteConditions,
    capacity_on_site,
)
from rockscreen.pipeline.risk.code_checks.tower_lv1 import (
    SectionCheck,
    ShaftSegment,
    TowerLV1,
    TowerModel,
    lv1_demand,
    lv1_tower,
    section_ultimate_moment,
    tower_period_guidelines,
)

__all__ = [
    "CONFIDENCE_FACTORS",
    "MASONRY_TYPES",
    "ElevatedSupport",
    "KinematicCapacity",
    "KinematicCheck",
    "MasonryType",
    "Mechanism",
    "PointMass",
    "RigidBlock",
    "SectionCheck",
    "ShaftSegment",
    "SiteCapacity",
    "SiteConditions",
    "TowerLV1",
    "TowerModel",
    "activation_demand",
    "belfry_mechanism",
    "bell_gable_mechanism",
    "cantilever_period",
    "capacity_on_site",
    "confidence_factor",
    "design_compressive_strength",
    "displacement_demand",
    "elastic_spectral_demand",
    "kinematic_capacity",
    "kinematic_check",
    "linear_demand",
    "lv1_demand",
    "lv1_tower",
    "masonry_elastic_modulus",
    "masonry_strength",
    "section_ultimate_moment",
    "tower_period_guidelines",
    "whole_tower_mechanism",
]
