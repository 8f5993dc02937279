"""The case engine: tower × ground motion × component × model → one solved case.

Every product (``run`` screening, ``assess`` stripes, ``sweep`` studies, ``simulate``)
is a thin calculator over this package (``docs/architecture.md``):

- :mod:`~rockscreen.pipeline.engine.registry`: the tower models (``ground``, ``floor``,
  ``double``, ``sliding``), each one registered object that says what inventory fields it
  requires, how its excitation is built and how it solves (OpenQuake's hazardlib registers
  its GMPEs the same way). A new model is one module in ``pipeline/engine/models/``;
- :mod:`~rockscreen.pipeline.engine.motion`: :class:`GroundMotion`, the one record type
  (horizontal components with their orientation, vertical, ``dt``, provenance), and the
  components a tower is checked against;
- :mod:`~rockscreen.pipeline.engine.cases`: one case solved (the block cache and the
  uplift pre-check written once);
- :mod:`~rockscreen.pipeline.engine.solvers`: the solvers the models call, a method of
  :mod:`rockscreen.solver.methods` unless work runs inside ``use_solvers`` (a test's
  stand-ins, the campaign's choice in its workers);
- :mod:`~rockscreen.pipeline.engine.loop`: the case loop of ``run``, the stripes and the
  IDA: a motion's components × a tower's models, each model's excitation built once at
  scale 1, screened at a scale factor (optionally stopping at the first overturning) or
  solved in full.

Importing this package loads neither numba nor ObsPy: the solvers load on first solve.
"""
