"""The assess job (``rockscreen assess``): plan, job, worker, stripes, IDA, compliance.

What ``assess`` runs for an inventory, from the sites to the archive. The measures it fits
are in :mod:`rockscreen.pipeline.risk.measures`, the code's checks it adds beside the
rocking in :mod:`rockscreen.pipeline.risk.checks` (``docs/risk.md``).

Modules:

- :mod:`.archived_sets`: The record sets an assess archive stores, as the sets a rerun takes.
- :mod:`.batch`: A pre-event assessment from an inventory to its archive (``rockscreen assess``).
- :mod:`.compliance`: Code compliance of the record sets an assessment is built on (NTC 2018
  §3.2.3.6, §7.3.5).
- :mod:`.ida`: Collapse intensity per record: incremental dynamic analysis of one tower.
- :mod:`.options`: The options of ``rockscreen assess`` (:class:`AssessOptions`), apart from its
  orchestration.
- :mod:`.plan`: The sites of an assessment: their hazard, their towers, their record sets' rows.
- :mod:`.record_sets`: A site's record set that could not be made: a typed result, not an error
  string.
- :mod:`.row_table`: A table of rows kept as column arrays: the assessment's large tables in little
  memory.
- :mod:`.run`: ``rockscreen assess``: per-tower fragility, annual rate of overturning and LV1
  indices.
- :mod:`.screening_risk`: The screening risk of ``assess``: the uncertainty library wired per tower
  and per region.
- :mod:`.sites`: Tower sites of an assessment: location rounded into shared sites, soil and use
  assumptions.
- :mod:`.stripes`: The multiple-stripe evaluation of one tower: records x components x models per
  stripe.
- :mod:`.tower_ida`: Collapse and SLV fragilities of one tower from its records' IDA intensities
  (``assess``).
- :mod:`.tower_summary`: One tower's ``/summary`` row of ``rockscreen assess``: what the worker
  computes per tower.
"""
