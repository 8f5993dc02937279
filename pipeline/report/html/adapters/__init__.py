"""Adapters: one per archive kind, each returning a :class:`ReportModel`.

:func:`report_model` opens the archive with
:func:`rockscreen.pipeline.archive.kinds.open_archive` (one check of format, kind and
version) and builds the model with the ``report`` function the presenter registry
(:data:`rockscreen.pipeline.report.presenters.PRESENTERS`) names for its kind:

=============  ==============================================
kind           adapter
=============  ==============================================
``run``        :mod:`.run` (``run_reader_model``)
``sweep``      :mod:`.sweep` (``sweep_reader_model``)
``assess``     :mod:`.risk` (``risk_reader_model``)
``scenario``   :mod:`.risk` (``risk_reader_model``)
=============  ==============================================
"""

from __future__ import annotations

from pathlib import Path

from rockscreen.pipeline.archive.kinds import ARCHIVE_KINDS, archive_kind, open_archive
from rockscreen.pipeline.report.html.model import ReportModel
from rockscreen.pipeline.report.presenters import face

__all__ = ["KINDS", "archive_kind", "report_model"]

#: The archive kinds (:data:`rockscreen.pipeline.archive.kinds.ARCHIVE_KINDS`).
KINDS = tuple(ARCHIVE_KINDS)


def report_model(path: str | Path) -> ReportModel:
    """Read any supported archive into the report model (see the table above).

    Raises
    ------
    ArchiveError
        If the archive is missing, unreadable, of an unknown kind or version.
    """
    reader = open_archive(path)
    return face(reader, "report")(reader)
