"""Risk that means something: fragility, annual rate of overturning, LV1 quantities, scenarios.

``risk/`` is four role packages and the uncertainty library (``docs/risk.md``,
``docs/architecture.md``):

- :mod:`rockscreen.pipeline.risk.assess`: the assess job (``rockscreen assess``) -- the sites'
  plan, the record sets, the multiple-stripe analysis, the IDA, compliance of the record
  sets, one tower's summary row, the job from an inventory to its archive;
- :mod:`rockscreen.pipeline.risk.checks`: the code's own checks, one module per check, their
  registry and their wiring into ``assess`` (the governing check);
- :mod:`rockscreen.pipeline.risk.measures`: the fragility fits, the hazard integral, the LV1
  indices and the classes of I_S (pure functions; they import no other role);
- :mod:`rockscreen.pipeline.risk.scenario`: ``rockscreen scenario`` (post-event) from a
  ShakeMap grid (an input format, read by :mod:`rockscreen.pipeline.hazard.shakemap`) and an
  assess archive;
- :mod:`rockscreen.pipeline.risk.uncertainty`: best estimates and their epistemic
  uncertainty (``docs/uncertainty.md``).
"""
