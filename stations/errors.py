"""The rockscreen exception hierarchy shared by ``stations`` and ``pipeline``.

``RockscreenError`` lives here because ``rockscreen.stations`` is the lowest package that both
``stations`` and ``pipeline`` may import (``solver`` stays free of both and raises
:class:`rockscreen.solver.errors.ParameterError`, a ``ValueError``).
"""


class RockscreenError(Exception):
    """Base class of every error rockscreen reports to a user as one clear line."""


class InventoryError(RockscreenError):
    """A tower inventory is invalid; the message names file, row, column, value and rule."""


class StationMetadataError(RockscreenError):
    """Station metadata (StationXML) is missing, unreadable or inconsistent."""
