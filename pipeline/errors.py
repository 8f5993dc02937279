"""Every error rockscreen reports to a user, in one place.

All derive from :class:`RockscreenError`; the CLI turns them into one line on stderr and
exit code 1. The hierarchy::

    RockscreenError
    ├── InventoryError            a tower inventory (stations)
    │   └── InventoryValueError   one value of a tower breaks a rule
    ├── StationMetadataError      StationXML (stations)
    ├── RecordFormatError         a record file
    ├── UnitsError                units of a record or an amplitude
    ├── ProcessingError           a processing step
    │   └── QualityError          a trace refused by the quality checks
    ├── ConfigError               a configuration or study file, an option
    ├── ArchiveError              an HDF5 archive
    ├── HazardError               the code hazard at a site
    ├── RiskError                 fragility, hazard integral, risk classes, scenario
    ├── ShakeMapError             a ShakeMap grid
    ├── ReportError               the HTML report
    └── DistributedError          the Dask cluster

The first three are defined in :mod:`rockscreen.stations.errors` (``stations`` raises them
and imports nothing of ``pipeline``) and re-exported here; import every error from this
module. The solver's :class:`rockscreen.solver.errors.ParameterError` (a ``ValueError``) is
the physics layer's own. :class:`Interrupted` is not an error but a stop signal.
"""

from collections.abc import Sequence

from rockscreen.stations.errors import (
    InventoryError,
    InventoryValueError,
    RockscreenError,
    StationMetadataError,
)

__all__ = [
    "ArchiveError",
    "ConfigError",
    "DistributedError",
    "HazardError",
    "Interrupted",
    "InventoryError",
    "InventoryValueError",
    "ProcessingError",
    "QualityError",
    "RecordFormatError",
    "ReportError",
    "RiskError",
    "RockscreenError",
    "ShakeMapError",
    "StationMetadataError",
    "UnitsError",
]


class RecordFormatError(RockscreenError):
    """A record file is unreadable, truncated, empty or of an unknown format."""


class UnitsError(RockscreenError):
    """The physical units of a record or an amplitude are unknown or not allowed."""


class ProcessingError(RockscreenError):
    """A processing step cannot be applied (e.g. a filter corner at or above Nyquist)."""


class QualityError(ProcessingError):
    """A trace failed quality checks; ``findings`` lists why.

    Parameters
    ----------
    message : str
        The one-line message (the trace and every reason).
    findings : sequence of Finding
        The failed checks (:class:`rockscreen.pipeline.records.quality.Finding`).
    """

    def __init__(self, message: str, findings: Sequence[object]):
        super().__init__(message)
        self.findings = list(findings)


class ConfigError(RockscreenError):
    """A configuration file or option is invalid."""


class ArchiveError(RockscreenError):
    """An HDF5 archive is missing, unreadable or not a rockscreen archive."""


class HazardError(RockscreenError):
    """A site outside the code hazard grid, or a bad return period, limit state or class."""


class RiskError(RockscreenError):
    """Invalid input to a fragility fit, a hazard integral or a risk-class band."""


class ShakeMapError(RockscreenError):
    """A ShakeMap grid that cannot be read: bad XML, DOCTYPE, fields, units or row count."""


class ReportError(RockscreenError):
    """An archive cannot be turned into a report (unknown kind, nothing to show, bad asset)."""


class DistributedError(RockscreenError):
    """The Dask cluster cannot be used: not installed, unreachable, no or wrong workers."""


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
