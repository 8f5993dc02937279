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


class InventoryValueError(InventoryError):
    """One value of a tower breaks a rule; carries the column for row and column messages.

    Parameters
    ----------
    tower_id : str
        The tower's id ("" when the id itself is the broken value).
    column : str
        The inventory column.
    value : object
        The value as given.
    rule : str
        The rule it breaks, e.g. ``"must be > 0"``.
    """

    def __init__(self, tower_id: str, column: str, value: object, rule: str):
        self.tower_id = tower_id
        self.column = column
        self.value = value
        self.rule = rule
        super().__init__(self.detail)

    @property
    def detail(self) -> str:
        """Describe the broken rule without file or row (``tower 'X', column 'c': ...``)."""
        who = f"tower {self.tower_id!r}, " if self.tower_id else ""
        return f"{who}column {self.column!r}: value {_show(self.value)} {self.rule}"


def _show(value: object) -> str:
    """Format a value for a message: text quoted, numbers as written."""
    if isinstance(value, str):
        return repr(value)
    if isinstance(value, float):
        return f"{value:g}"
    return str(value)
