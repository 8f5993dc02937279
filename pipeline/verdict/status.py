"""Status and bound of a check result: enums the code branches on, never text it parses.

SciPy's ``OdeResult`` is the model: a status the caller branches on, and a message looked up
from it (:mod:`rockscreen.pipeline.verdict.messages`) for the reader.
"""

from __future__ import annotations

import enum

__all__ = ["Bound", "Status"]


class Status(enum.Enum):
    """Whether a check was made.

    ``MADE``: the check ran and gave a capacity; ``NOT_MADE``: the inventory lacks what it
    requires (its message says what); ``FAILED``: it was attempted and could not be completed
    (its message says why).
    """

    MADE = "made"
    NOT_MADE = "not_made"
    FAILED = "failed"


class Bound(enum.Enum):
    """What a value is: a value, or a bound of the true one.

    ``LOWER``: the true value is at least this (a fragility that no record reached, a check
    that still holds at 2475 y); ``UPPER``: at most this (overturned at every stripe, a check
    that fails at 30 y). The archive and the exports spell them ``""``, ``"lower"``,
    ``"upper"`` (:meth:`spelling`, :meth:`parse`).
    """

    NONE = ""
    LOWER = "lower"
    UPPER = "upper"

    @property
    def sign(self) -> str:
        """Return the sign printed before a bounded number: ``">"``, ``"<"`` or ``""``."""
        return {Bound.LOWER: ">", Bound.UPPER: "<"}.get(self, "")

    def spelling(self) -> str:
        """Return the stored spelling (``""``, ``"lower"``, ``"upper"``)."""
        return self.value

    @classmethod
    def parse(cls, value: object) -> Bound:
        """Return the bound of a stored spelling (bytes, str, None or a :class:`Bound`).

        Raises
        ------
        ValueError
            For any other spelling (a stored table is checked, not guessed).
        """
        if isinstance(value, Bound):
            return value
        if value is None:
            return cls.NONE
        if isinstance(value, bytes):
            value = value.decode("utf-8")
        text = str(value).strip().lower()
        try:
            return cls(text)
        except ValueError:
            raise ValueError(f"bound {value!r}: expected one of '', 'lower', 'upper'") from None
