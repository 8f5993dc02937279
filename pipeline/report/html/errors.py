"""Errors of the HTML report."""

from rockscreen.stations.errors import RockscreenError

__all__ = ["ReportError"]


class ReportError(RockscreenError):
    """An archive cannot be turned into a report (unknown kind, nothing to show, bad asset)."""
