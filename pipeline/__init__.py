"""rockscreen's record pipeline: records in, screening and risk out.

The stages, upstream first (``docs/architecture.md``): ``records`` (reading, units,
quality, grouping) → ``processing`` → ``motion`` (excitations, floor motion, spectra,
synthetic records) → ``hazard`` (the NTC 2018 code hazard at a site) → ``screening``
(towers × records × components × models) → ``risk`` (fragility, annual rate, LV1,
scenarios) → ``archive`` (HDF5) → ``report`` (tables, plots, the HTML report); ``study``
runs parameter sweeps, ``execution`` runs work on local processes or Dask, ``cli`` is
the command line.

The names below are the public API, importable from :mod:`rockscreen.pipeline` directly, e.g.::

    from rockscreen.pipeline import read_stream, site_hazard, run_screening, RunRequest

They load on first use (PEP 562), so ``import pipeline`` (and ``rockscreen --help``)
stays fast: no ObsPy, h5py or numba until a function needs them.
"""

from __future__ import annotations

from importlib.metadata import PackageNotFoundError, version

from rockscreen.solver.lazy import lazy_exports

try:
    __version__ = version("rockscreen")
except PackageNotFoundError:  # running from a source tree that was never installed
    __version__ = "0+unknown"

#: Public name -> the module that defines it.
_API = {
    # records and processing
    "read_stream": "rockscreen.pipeline.records.io",
    "expand_record_paths": "rockscreen.pipeline.records.paths",
    "group_records": "rockscreen.pipeline.records.grouping",
    "process_trace": "rockscreen.pipeline.processing.steps",
    # motion
    "harmonic": "rockscreen.pipeline.motion.excitations",
    "pulse": "rockscreen.pipeline.motion.excitations",
    "response_spectrum": "rockscreen.pipeline.motion.spectra",
    "modal_floor_accelerogram": "rockscreen.pipeline.motion.floor",
    # hazard
    "site_hazard": "rockscreen.pipeline.hazard",
    "hazard_curve": "rockscreen.pipeline.hazard",
    "limit_state_return_period": "rockscreen.pipeline.hazard",
    "elastic_spectrum": "rockscreen.pipeline.hazard",
    "site_record_set": "rockscreen.pipeline.hazard",
    # screening
    "RunRequest": "rockscreen.pipeline.screening.batch",
    "run_screening": "rockscreen.pipeline.screening.batch",
    # risk
    "run_assess": "rockscreen.pipeline.risk.assess.run",
    # archive and report
    "read_summary": "rockscreen.pipeline.archive.reader",
    "build_report": "rockscreen.pipeline.report.html",
}

__all__ = ["__version__", *sorted(_API)]


__getattr__, __dir__ = lazy_exports("rockscreen.pipeline", _API, globals())
