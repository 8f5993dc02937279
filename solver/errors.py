"""Exceptions raised by the solver for invalid input (never for physical outcomes)."""


class ParameterError(ValueError):
    """A model parameter or an input array is invalid.

    The message names the parameter, the bad value and what is allowed.
    Physical outcomes (overturning, no uplift) are never exceptions: they are a
    ``status`` on the result object.
    """
