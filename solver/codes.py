"""Named regime, event and status codes of the compiled kernel (:mod:`rockscreen.solver.kernel`).

They are :class:`enum.IntEnum` members, which numba compiles in nopython mode as plain
integers: they compare with each other and with ints, index arrays and are stored in the
int8 regime history unchanged. Their values are part of the public results (the
``regime`` history of :class:`rockscreen.solver.response.Response`), so they must not be renumbered.
"""

from __future__ import annotations

from enum import IntEnum


class Regime(IntEnum):
    """Which parts of the model move (docs/theory.md)."""

    REST = 0  # everything at rest: the input is scanned for the next threshold crossing
    ROCKING = 1  # tower rocking on a stuck base (the single Housner block)
    SLIDING = 2  # base (building) sliding, tower at rest on it (the sliding block)
    BOTH = 3  # tower rocking on a sliding base


class Event(IntEnum):
    """What ends a stretch of smooth motion; the kernel changes regime only at one."""

    NONE = -1  # no event within the step
    IMPACT = 0  # s theta = 0: the tower lands and rocks on the other corner
    OVERTURN = 1  # |theta| = pi/2: the tower has fallen (terminal)
    STICK = 2  # u_dot = 0: the sliding base stops, or reverses
    SLIP = 3  # |F| = mu_s N: the rocking tower drags its base loose
    ONSET = 4  # at rest, |a| reaches the lower of the uplift and slip thresholds
    CHATTER = 5  # too many events within one sample: settle at rest (documented)


class Status(IntEnum):
    """Outcome of :func:`rockscreen.solver.kernel.simulate`."""

    REST = 0  # at rest after the input ended (or never moved)
    OVERTURNED = 1
    MOVING = 2  # still moving when the free-motion bound was reached
    SAFE = 3  # free motion below the energy barrier with eta < 1: rest is certain
