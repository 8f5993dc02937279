"""The campaign report: one self-contained HTML page per archive (``rockscreen report``).

Adapters (one per archive kind, :mod:`rockscreen.pipeline.report.html.adapters`) read an archive
into the neutral :class:`~rockscreen.pipeline.report.html.model.ReportModel`; one renderer
(:func:`~rockscreen.pipeline.report.html.render.render_html`) writes the page. docs/report.md
describes the page, its size and its choices.
"""

from __future__ import annotations

from pathlib import Path

from rockscreen.pipeline.archive.atomic import write_text_atomic
from rockscreen.pipeline.report.html.adapters import archive_kind, report_model
from rockscreen.pipeline.report.html.render import render_html

__all__ = ["archive_kind", "build_report", "render_html", "report_model"]


def build_report(archive: str | Path, out: str | Path, lang: str = "en") -> Path:
    """Write the HTML report of an archive.

    Parameters
    ----------
    archive : str or Path
        A run, assess, scenario or sweep archive (HDF5).
    out : str or Path
        The HTML file (written atomically).
    lang : str
        ``"en"`` (default) or ``"it"``.

    Returns
    -------
    Path
        The written page.

    Raises
    ------
    ReportError
        If the archive kind is not known or the language is not available.
    ArchiveError
        If the archive is missing or unreadable.
    """
    page = render_html(report_model(archive), lang)
    out = Path(out)
    write_text_atomic(out, page)
    return out
