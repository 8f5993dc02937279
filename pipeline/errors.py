"""Errors of the record pipeline, the campaign and the archive.

All derive from :class:`rockscreen.stations.errors.RockscreenError`; the CLI turns them into
one line on stderr and a non-zero exit code.
"""

from rockscreen.stations.errors import InventoryError, RockscreenError, StationMetadataError

__all__ = [
    "ArchiveError",
    "ConfigError",
    "HazardError",
    "Interrupted",
    "InventoryError",
    "ProcessingError",
    "RecordFormatError",
    "RockscreenError",
    "StationMetadataError",
    "UnitsError",
]


class RecordFormatError(RockscreenError):
    """A record file is unreadable, truncated, empty or of an unknown format."""


class UnitsError(RockscreenError):
    """The physical units of a record or an amplitude are unknown or not allowed."""


class ProcessingError(RockscreenError):
    """A processing step cannot be applied (e.g. a filter corner at or above Nyquist)."""


class ConfigError(RockscreenError):
    """A configuration file or option is invalid."""


class ArchiveError(RockscreenError):
    """An HDF5 archive is missing, unreadable or not a rockscreen archive."""


class HazardError(RockscreenError):
    """A site outside the code hazard grid, or a bad return period, limit state or class."""


class Interrupted(BaseException):  # noqa: N818  (a signal, not an error of the user's)
    """A run stopped by Ctrl-C (SIGINT), SIGTERM or SIGHUP; what it computed so far is kept.

    A ``BaseException``, like :class:`KeyboardInterrupt`, so that no ``except Exception``
    on the way swallows it. The CLI prints :attr:`message` as one line and exits with
    :attr:`exit_code` (128 + the signal number: 130 for SIGINT, 143 for SIGTERM, 129 for SIGHUP).
    """

    def __init__(self, message: str, exit_code: int) -> None:
        super().__init__(message)
        self.message = message
        self.exit_code = exit_code
