"""The distributions a prior is: a point, uniform, lognormal, the taper mixture, categorical.

Each is a small frozen dataclass with ``sample(rng, n)``, ``median``, ``interval(p)``,
``source`` and ``judgement`` (True where the prior is a judgement, never a fit of data: it
is labelled so wherever it is shown); the priors themselves, with their sources, are
:mod:`rockscreen.pipeline.risk.uncertainty.priors` (``docs/uncertainty.md``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy import stats

from rockscreen.pipeline.errors import RiskError

__all__ = ["Categorical", "LogNormal", "Point", "Taper", "Uniform", "check_level"]


def check_level(p: float) -> float:
    """Return ``p`` as a float, refusing a central-interval level outside (0, 1)."""
    p = float(p)
    if not 0.0 < p < 1.0:
        raise RiskError(f"interval level p={p!r} must be in (0, 1)")
    return p


@dataclass(frozen=True)
class Point:
    """A prior collapsed to one value (given by the inventory, or a fixed assumption)."""

    #: The value (SI units; a text for a category).
    value: Any
    #: Where the value comes from.
    source: str
    #: True when the value is a judgement, not data.
    judgement: bool = False

    def sample(self, rng: np.random.Generator, n: int) -> np.ndarray:
        """Return ``n`` copies of the value (no random draw)."""
        return np.full(int(n), self.value, dtype=object if isinstance(self.value, str) else float)

    @property
    def median(self) -> Any:
        """Return the value."""
        return self.value

    def interval(self, p: float = 0.9) -> tuple[Any, Any]:
        """Return ``(value, value)``."""
        check_level(p)
        return (self.value, self.value)


@dataclass(frozen=True)
class Uniform:
    """A uniform prior on [low, high]."""

    low: float
    high: float
    source: str
    judgement: bool = False

    def __post_init__(self):
        if not self.low < self.high:
            raise RiskError(f"uniform prior: low={self.low!r} must be below high={self.high!r}")

    def sample(self, rng: np.random.Generator, n: int) -> np.ndarray:
        """Return ``n`` draws."""
        return rng.uniform(self.low, self.high, int(n))

    @property
    def median(self) -> float:
        """Return the mid value."""
        return 0.5 * (self.low + self.high)

    def interval(self, p: float = 0.9) -> tuple[float, float]:
        """Return the central interval of probability ``p``."""
        p = check_level(p)
        half = 0.5 * (1.0 - p) * (self.high - self.low)
        return (self.low + half, self.high - half)


@dataclass(frozen=True)
class LogNormal:
    """A lognormal prior (median, log-std), optionally capped above (``upper``)."""

    median_value: float
    log_std: float
    source: str
    judgement: bool = False
    #: Values above are set to it (None: no cap).
    upper: float | None = None

    def __post_init__(self):
        if not self.median_value > 0.0:
            raise RiskError(f"lognormal prior: median={self.median_value!r} must be > 0")
        if not self.log_std > 0.0:
            raise RiskError(f"lognormal prior: log_std={self.log_std!r} must be > 0")

    def sample(self, rng: np.random.Generator, n: int) -> np.ndarray:
        """Return ``n`` draws (capped at ``upper``)."""
        x = self.median_value * np.exp(self.log_std * rng.standard_normal(int(n)))
        return x if self.upper is None else np.minimum(x, self.upper)

    @property
    def median(self) -> float:
        """Return the median (capped)."""
        return self.median_value if self.upper is None else min(self.median_value, self.upper)

    def interval(self, p: float = 0.9) -> tuple[float, float]:
        """Return the central interval of probability ``p`` (capped)."""
        z = stats.norm.ppf(0.5 + 0.5 * check_level(p))
        lo, hi = (
            self.median_value * np.exp(-z * self.log_std),
            self.median_value * np.exp(z * self.log_std),
        )
        if self.upper is not None:
            lo, hi = min(lo, self.upper), min(hi, self.upper)
        return (float(lo), float(hi))


@dataclass(frozen=True)
class Taper:
    """Top / base wall ratio: 1 (prismatic) with probability ``prismatic_share``, else beta."""

    prismatic_share: float
    beta_a: float
    beta_b: float
    source: str
    judgement: bool = False

    def __post_init__(self):
        if not 0.0 <= self.prismatic_share <= 1.0:
            raise RiskError(
                f"taper prior: prismatic_share={self.prismatic_share!r} must be in [0, 1]"
            )
        if not (self.beta_a > 0.0 and self.beta_b > 0.0):
            raise RiskError(
                f"taper prior: beta_a={self.beta_a!r}, beta_b={self.beta_b!r} must be > 0"
            )

    def _ppf(self, u: np.ndarray) -> np.ndarray:
        """Return the quantiles of the mixture (the point mass at 1 is the top)."""
        u = np.asarray(u, dtype=float)
        rest = 1.0 - self.prismatic_share
        inside = np.clip(u / rest, 0.0, 1.0) if rest > 0.0 else np.ones_like(u)
        return np.where(u < rest, stats.beta.ppf(inside, self.beta_a, self.beta_b), 1.0)

    def sample(self, rng: np.random.Generator, n: int) -> np.ndarray:
        """Return ``n`` draws in (0, 1]."""
        return self._ppf(rng.uniform(0.0, 1.0, int(n)))

    @property
    def median(self) -> float:
        """Return the median."""
        return float(self._ppf(0.5))

    def interval(self, p: float = 0.9) -> tuple[float, float]:
        """Return the central interval of probability ``p``."""
        p = check_level(p)
        lo, hi = self._ppf(np.array([0.5 - 0.5 * p, 0.5 + 0.5 * p]))
        return (float(lo), float(hi))


@dataclass(frozen=True)
class Categorical:
    """A categorical prior over masonry types (keys of Table C8.5.I)."""

    #: (category, probability) pairs; probabilities > 0, summing to 1.
    weights: tuple[tuple[str, float], ...]
    source: str
    judgement: bool = False

    def __post_init__(self):
        object.__setattr__(self, "weights", tuple((str(k), float(w)) for k, w in self.weights))
        if not self.weights or any(w <= 0.0 for _, w in self.weights):
            raise RiskError(f"categorical prior: weights {self.weights!r} must be > 0")
        if abs(sum(w for _, w in self.weights) - 1.0) > 1e-6:
            raise RiskError(f"categorical prior: weights {self.weights!r} must sum to 1")

    @property
    def categories(self) -> tuple[str, ...]:
        """Return the categories, in the given order."""
        return tuple(k for k, _ in self.weights)

    def sample(self, rng: np.random.Generator, n: int) -> np.ndarray:
        """Return ``n`` categories (an object array of str)."""
        p = np.array([w for _, w in self.weights])
        index = np.searchsorted(np.cumsum(p) / p.sum(), rng.uniform(0.0, 1.0, int(n)), "right")
        return np.array(self.categories, dtype=object)[np.minimum(index, len(p) - 1)]

    @property
    def median(self) -> str:
        """Return the most probable category (the first of equal ones): the mode."""
        return max(self.weights, key=lambda kw: kw[1])[0]

    def interval(self, p: float = 0.9) -> tuple[str, ...]:
        """Return the fewest most probable categories whose probability reaches ``p``."""
        p = check_level(p)
        out, total = [], 0.0
        for k, w in sorted(self.weights, key=lambda kw: -kw[1]):
            out.append(k)
            total += w
            if total >= p - 1e-12:
                break
        return tuple(out)
