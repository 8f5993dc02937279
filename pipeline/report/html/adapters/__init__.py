"""Adapters: one per archive kind, each returning a :class:`ReportModel`.

=============  ==============================================  ===========================
kind           how it is recognised                            adapter
=============  ==============================================  ===========================
``sweep``      :func:`rockscreen.pipeline.study.sweep.is_sweep_archive`   :mod:`.sweep`
``assess``     root attribute ``kind = "assess"``              :mod:`.risk`
``scenario``   root attribute ``kind = "scenario"``            :mod:`.risk`
``run``        root ``format = "rockscreen-archive"`` or       :mod:`.run`
               ``kind = "run"``, with a ``/summary`` table
=============  ==============================================  ===========================
"""

from __future__ import annotations

from pathlib import Path

import h5py

from rockscreen.pipeline.errors import ArchiveError, ReportError
from rockscreen.pipeline.report.html.adapters.common import python_value
from rockscreen.pipeline.report.html.adapters.risk import risk_archive_model
from rockscreen.pipeline.report.html.adapters.run import run_model
from rockscreen.pipeline.report.html.adapters.sweep import sweep_model
from rockscreen.pipeline.report.html.model import ReportModel
from rockscreen.pipeline.study.sweep import is_sweep_archive

__all__ = ["KINDS", "archive_kind", "report_model"]

KINDS = ("run", "assess", "scenario", "sweep")


def archive_kind(path: str | Path) -> str:
    """Return the kind of an archive: ``"run"``, ``"assess"``, ``"scenario"`` or ``"sweep"``.

    Raises
    ------
    ArchiveError
        If the file is missing or not HDF5.
    ReportError
        If it is HDF5 but no rockscreen archive kind is recognised.
    """
    path = Path(path)
    if not path.is_file():
        raise ArchiveError(f"archive {str(path)!r} does not exist")
    if not h5py.is_hdf5(path):
        raise ArchiveError(f"{str(path)!r} is not an HDF5 file")
    if is_sweep_archive(path):
        return "sweep"
    with h5py.File(path, "r") as f:
        kind = str(python_value(f.attrs.get("kind", "")))
        fmt = str(python_value(f.attrs.get("format", "")))
        has_summary = "summary" in f
    if kind in {"assess", "scenario"}:
        return kind
    if (kind == "run" or fmt == "rockscreen-archive") and has_summary:
        return "run"
    raise ReportError(
        f"{str(path)!r}: no report for this archive (kind {kind!r}, format {fmt!r}); "
        f"known kinds: {', '.join(KINDS)}"
    )


def report_model(path: str | Path) -> ReportModel:
    """Read any supported archive into the report model (see the table above)."""
    kind = archive_kind(path)
    if kind == "sweep":
        return sweep_model(path)
    if kind in {"assess", "scenario"}:
        return risk_archive_model(path, kind)

    return run_model(path)
