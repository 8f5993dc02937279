"""A site's record set that could not be made: a typed result, not an error string.

``assess`` asks the hazard stage for one spectrum-compatible record set per site and return
period (:func:`rockscreen.pipeline.hazard.suite.site_record_set`); the worker returns either
the set or a :class:`FailedSet`, and the towers of that site at that return period are
``selection`` failures carrying its reason (a ``site.records_failed`` message).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from rockscreen.pipeline.verdict.messages import Message, message, render

__all__ = ["FailedSet", "failed_set", "is_failed"]


@dataclass(frozen=True)
class FailedSet:
    """The record set of a site at one return period that could not be made."""

    #: The site's key ``(lon, lat, soil, topography)`` ([deg], [deg], category, category).
    key: tuple
    #: The return period [y].
    tr: float
    #: Why: a ``site.records_failed`` message naming the site, the return period and the error.
    reason: Message

    @property
    def reason_text(self) -> str:
        """The reason in English, one line (the ``/failures`` row's ``reason``)."""
        return render(self.reason)


def failed_set(key: tuple, tr: float, error: BaseException | str) -> FailedSet:
    """Return the failed record set of site ``key`` at ``tr`` [y] for ``error``.

    Parameters
    ----------
    key : tuple
        The site's key ``(lon, lat, soil, topography)``.
    tr : float
        The return period [y].
    error : BaseException or str
        What the hazard stage raised (its one-line message is kept).

    Returns
    -------
    FailedSet
        With ``reason`` the ``site.records_failed`` message.
    """
    lon, lat = key[0], key[1]
    reason = message("site.records_failed", lon=lon, lat=lat, tr=tr, error=str(error))
    return FailedSet(key=key, tr=float(tr), reason=reason)


def is_failed(record_set: Any) -> bool:
    """Return whether ``record_set`` is a :class:`FailedSet` (not a record set made)."""
    return isinstance(record_set, FailedSet)
