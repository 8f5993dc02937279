"""Risk that means something: fragility, annual rate of overturning, LV1 quantities, scenarios.

Flow (``docs/risk.md``):

- :mod:`rockscreen.pipeline.risk.stripes`: the multiple-stripe analysis of one tower (record sets of
  the site at each return period, every component and model);
- :mod:`rockscreen.pipeline.risk.fragility`: lognormal fragility in the site's ag fitted by maximum
  likelihood on the stripe counts (Baker 2015);
- :mod:`rockscreen.pipeline.risk.censored_fit`: the same fragility fitted on per-record collapse
  intensities with censoring (``fit_censored_lognormal``);
- :mod:`rockscreen.pipeline.risk.ida`: the collapse and SLV intensity of each record
  (incremental dynamic analysis: scan and bisection of the scale factor, censored at a cap
  or at the model's vertical limit);
- :mod:`pipeline.risk.hazard_integral`: the site hazard curve and the mean annual frequency
  of overturning (Cornell et al. 2002; Jalayer & Cornell 2009);
- :mod:`pipeline.risk.lv1`: capacity acceleration, its return period, the safety index and
  the acceleration factor of the MiC 2011 Guidelines;
- :mod:`rockscreen.pipeline.risk.classes`: risk classes from the safety index;
- :mod:`rockscreen.pipeline.risk.code_checks`: the code's own checks (kinematic mechanisms,
  the Guidelines' LV1 tower model, FC), a library not yet wired into ``assess``;
- :mod:`rockscreen.pipeline.risk.assess`: ``rockscreen assess`` (pre-event) over an inventory;
- :mod:`rockscreen.pipeline.risk.tower_summary`: one tower's ``/summary`` row of ``assess``
  (fragility, LV1 and rate columns, the code's checks), what the worker computes per tower;
- :mod:`pipeline.risk.scenario`: ``rockscreen scenario`` (post-event) from a ShakeMap grid
  (an input format, read by :mod:`pipeline.hazard.shakemap`) and an assess archive.
"""
