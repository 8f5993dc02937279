"""The code's own checks of a bell tower, beside the rocking dynamics (issue 22).

One module per check of the codes (kinematic mechanisms, the Guidelines' LV1 tower
model, the confidence factor), their registry (:mod:`.registry`: the ``CodeCheck``
objects the governing slots iterate) and their wiring into ``assess`` (the
``tower_*`` modules, the governing check, the knowledge level). SI units throughout
(m, kg, N, s, m/s2); accelerations in g only where a name ends in ``_g``. See
``docs/code_checks.md``.

Modules:

- :mod:`.code`: The code checks added as modules, one module each; importing one registers its
  check.
- :mod:`.confidence`: Knowledge levels, confidence factors and the reference masonry parameters of
  the Circolare.
- :mod:`.floor_spectrum`: Floor spectra of the Circolare 2019 for local mechanisms at height
  (§C7.2.3).
- :mod:`.governing`: The mechanism that governs a tower's verdict in ``assess`` (issue 22).
- :mod:`.kinematic`: Kinematic analysis of a rigid overturning mechanism (Circolare 2019
  §C8.7.1.2.1).
- :mod:`.kinematic_demand`: The seismic demand on a kinematic mechanism at its level (Circolare 2019
  §C8.7.1.2.1).
- :mod:`.knowledge`: A tower's knowledge level (Circolare 2019 §C8.5.4) and the measured strength it
  allows.
- :mod:`.mechanisms`: The three overturning mechanisms of a bell tower, built from its dimensions.
- :mod:`.registry`: The code's checks as registered objects (issue 29): one :class:`CodeCheck` each.
- :mod:`.site_capacity`: The capacity of a code check on the site's hazard: T_R,C, a_C, I_S and f_a.
- :mod:`.tower_checks`: The code's own checks of one tower in ``assess`` and the mechanism that
  governs (issue 22).
- :mod:`.tower_code_checks`: Every registered code check of one tower in ``assess``'s worker: the
  one loop.
- :mod:`.tower_lv1`: LV1 model of the Guidelines for towers and bell towers (DPCM 9/2/2011, §5.4.4).
- :mod:`.tower_lv1_checks`: The LV1 tower model of the Guidelines in ``assess``, from the
  inventory's shaft columns.
- :mod:`.tower_mechanisms`: A tower's local mechanisms from its inventory columns, for the kinematic
  checks.
- :mod:`.validation`: Input checks of the code checks: every message names the parameter and its
  allowed range.
"""

from rockscreen.solver.lazy import lazy_exports

#: Public name -> the module that defines it (loaded on first use: importing one
#: module of the package, such as the registry, loads no other).
_EXPORTS = {
    "CONFIDENCE_FACTORS": "rockscreen.pipeline.risk.checks.confidence",
    "ElevatedSupport": "rockscreen.pipeline.risk.checks.kinematic_demand",
    "KinematicCapacity": "rockscreen.pipeline.risk.checks.kinematic",
    "KinematicCheck": "rockscreen.pipeline.risk.checks.kinematic",
    "MASONRY_TYPES": "rockscreen.pipeline.risk.checks.confidence",
    "MasonryType": "rockscreen.pipeline.risk.checks.confidence",
    "Mechanism": "rockscreen.pipeline.risk.checks.kinematic",
    "PointMass": "rockscreen.pipeline.risk.checks.kinematic",
    "RigidBlock": "rockscreen.pipeline.risk.checks.kinematic",
    "SectionCheck": "rockscreen.pipeline.risk.checks.tower_lv1",
    "ShaftSegment": "rockscreen.pipeline.risk.checks.tower_lv1",
    "SiteCapacity": "rockscreen.pipeline.risk.checks.site_capacity",
    "SiteConditions": "rockscreen.pipeline.risk.checks.site_capacity",
    "TowerLV1": "rockscreen.pipeline.risk.checks.tower_lv1",
    "TowerModel": "rockscreen.pipeline.risk.checks.tower_lv1",
    "activation_demand": "rockscreen.pipeline.risk.checks.kinematic_demand",
    "belfry_mechanism": "rockscreen.pipeline.risk.checks.mechanisms",
    "bell_gable_mechanism": "rockscreen.pipeline.risk.checks.mechanisms",
    "cantilever_period": "rockscreen.pipeline.risk.checks.kinematic",
    "capacity_on_site": "rockscreen.pipeline.risk.checks.site_capacity",
    "confidence_factor": "rockscreen.pipeline.risk.checks.confidence",
    "design_compressive_strength": "rockscreen.pipeline.risk.checks.confidence",
    "displacement_demand": "rockscreen.pipeline.risk.checks.kinematic_demand",
    "elastic_spectral_demand": "rockscreen.pipeline.risk.checks.kinematic_demand",
    "kinematic_capacity": "rockscreen.pipeline.risk.checks.kinematic",
    "kinematic_check": "rockscreen.pipeline.risk.checks.kinematic",
    "linear_demand": "rockscreen.pipeline.risk.checks.kinematic_demand",
    "lv1_demand": "rockscreen.pipeline.risk.checks.tower_lv1",
    "lv1_tower": "rockscreen.pipeline.risk.checks.tower_lv1",
    "masonry_elastic_modulus": "rockscreen.pipeline.risk.checks.confidence",
    "masonry_strength": "rockscreen.pipeline.risk.checks.confidence",
    "section_ultimate_moment": "rockscreen.pipeline.risk.checks.tower_lv1",
    "tower_period_guidelines": "rockscreen.pipeline.risk.checks.tower_lv1",
    "whole_tower_mechanism": "rockscreen.pipeline.risk.checks.mechanisms",
}

__all__ = [
    "CONFIDENCE_FACTORS",
    "ElevatedSupport",
    "KinematicCapacity",
    "KinematicCheck",
    "MASONRY_TYPES",
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

__getattr__, __dir__ = lazy_exports("rockscreen.pipeline.risk.checks", _EXPORTS, globals())
