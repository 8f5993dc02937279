"""Errors of the risk stage (fragility, hazard integral, ShakeMap, scenario)."""

from rockscreen.stations.errors import RockscreenError

__all__ = ["RiskError", "ShakeMapError"]


class RiskError(RockscreenError):
    """Invalid input to a fragility fit, a hazard integral or a risk-class band."""


class ShakeMapError(RockscreenError):
    """A ShakeMap grid that cannot be read: bad XML, DOCTYPE, fields, units or row count."""
