"""The code seismic hazard of NTC 2018 at a tower and the records that represent it.

- :mod:`rockscreen.pipeline.hazard.grid`: ag, F0, T*C at any site and return period (Allegato A/B);
- :mod:`pipeline.hazard.limit_states`: SLO, SLD, SLV, SLC and their return periods (§2.4, §3.2.1);
- :mod:`rockscreen.pipeline.hazard.spectrum`: elastic spectra (§3.2.3.2);
- :mod:`rockscreen.pipeline.hazard.selection`: spectrum-compatible record sets (§3.2.3.6);
- :mod:`rockscreen.pipeline.hazard.suite_io`: a suite of records read from files;
- :mod:`rockscreen.pipeline.hazard.suite`: the matched suite and the site's record set;
- :mod:`rockscreen.pipeline.hazard.stochastic_suite`: the stochastic suite (the default);
- :mod:`rockscreen.pipeline.hazard.record_pool`: its shared pools, cached per user on disk;
- :mod:`rockscreen.pipeline.hazard.suite_common`: what the two embedded suites share;
- :mod:`rockscreen.pipeline.hazard.shakemap`: an event's ShakeMap ``grid.xml`` (the hazard of
  ``rockscreen scenario``), the file itself checked by
  :mod:`rockscreen.pipeline.hazard.shakemap_xml`.

See ``docs/hazard.md``.
"""

from rockscreen.pipeline.hazard.grid import RETURN_PERIODS_Y, SiteHazard, hazard_curve, site_hazard
from rockscreen.pipeline.hazard.limit_states import (
    LIMIT_STATES,
    TOWER_DEFAULTS,
    limit_state_return_period,
    reference_period,
)
from rockscreen.pipeline.hazard.selection import RecordSet, SuiteRecord, select_records
from rockscreen.pipeline.hazard.spectrum import (
    SpectrumParameters,
    displacement_spectrum,
    elastic_spectrum,
    spectrum_parameters,
    vertical_spectrum,
)
from rockscreen.pipeline.hazard.suite import site_record_set, synthetic_suite, target_spectrum
from rockscreen.pipeline.hazard.suite_io import load_suite

__all__ = [
    "LIMIT_STATES",
    "RETURN_PERIODS_Y",
    "TOWER_DEFAULTS",
    "RecordSet",
    "SiteHazard",
    "SpectrumParameters",
    "SuiteRecord",
    "displacement_spectrum",
    "elastic_spectrum",
    "hazard_curve",
    "limit_state_return_period",
    "load_suite",
    "reference_period",
    "select_records",
    "site_hazard",
    "site_record_set",
    "spectrum_parameters",
    "synthetic_suite",
    "target_spectrum",
    "vertical_spectrum",
]
