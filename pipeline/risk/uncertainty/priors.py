"""Priors for what a geometry-only inventory does not say about a tower's shaft (issue 31).

A territorial inventory gives a tower's location, plan and height; the shaft's best-estimate
capacity (:mod:`rockscreen.pipeline.risk.uncertainty.shaft`) also needs the walls, the
masonry and the period. Each is a documented distribution with its source
(``docs/uncertainty.md``):

- **base wall thickness** ``t_0 = r s`` (``s`` the smaller plan side): ``r`` lognormal,
  median :data:`WALL_RATIO_MEDIAN`, log-std :data:`WALL_RATIO_LOG_STD`, capped at 0.5 (a
  solid section), fitted on the 74 unique Italian towers of TURRIS with a plausible base
  wall (Montabert et al., *Buildings* 2023; ``benchmarks/turris_priors.py``);
- **top / base wall** ``t_top / t_0``: a point mass at 1 (prismatic) with probability
  :data:`TAPER_PRISMATIC_SHARE`, else a beta(:data:`TAPER_BETA_A`, :data:`TAPER_BETA_B`) on
  (0, 1) (TURRIS, 69 towers);
- **masonry type**: categorical, uniform over :data:`BELL_TOWER_MASONRY_TYPES` (a
  judgement: the seven historic types of Circolare 2019 Table C8.5.I; the cement-mortar
  ``semi_solid_brick`` left out), unless a region's priors file gives sourced weights;
- **mean compressive strength** ``f_m`` given the type: uniform between the ends of the
  type's range in Circolare 2019 §C8.5.3.1 Table C8.5.I (the table gives the range of the
  mean over a type, no distribution inside it: uniform is the choice stated here);
- **unit weight** ``w`` given the type: the table's value; for the two soft-stone rows
  (the table's ``13 ÷ 16 kN/m3``, note (**)) uniform over that range;
- **period** ``T1``: lognormal, median :data:`PERIOD_RATIO_MEDIAN` x ``0.0187 H`` (the law
  of :func:`~rockscreen.pipeline.risk.checks.tower_lv1.tower_period_guidelines`, H
  the whole tower's height) and log-std :data:`PERIOD_LOG_STD`, the scatter of the 98
  unique Italian towers of TURRIS with a measured frequency.

Each prior is a small frozen dataclass of
:mod:`rockscreen.pipeline.risk.uncertainty.distributions` with ``sample(rng, n)``,
``median``, ``interval(p)``, ``source`` and ``judgement`` (True where the prior is a
judgement, never a fit of data: it is labelled so wherever it is shown). A value the
inventory gives collapses its prior to a
:class:`~rockscreen.pipeline.risk.uncertainty.distributions.Point`; a region's priors file
(:func:`read_region_priors`) replaces the defaults where the inventory is silent.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.checks.confidence import MASONRY_TYPES
from rockscreen.pipeline.risk.checks.tower_lv1 import tower_period_guidelines
from rockscreen.pipeline.risk.uncertainty.belfry import BelfryPriors
from rockscreen.pipeline.risk.uncertainty.distributions import (
    Categorical,
    LogNormal,
    Point,
    Taper,
    Uniform,
)
from rockscreen.stations.tower import Tower

__all__ = [
    "BELL_TOWER_MASONRY_TYPES",
    "COLLAPSING_COLUMNS",
    "PERIOD_LOG_STD",
    "PERIOD_RATIO_MEDIAN",
    "SOFT_STONE_UNIT_WEIGHT_N_M3",
    "TAPER_BETA_A",
    "TAPER_BETA_B",
    "TAPER_PRISMATIC_SHARE",
    "TURRIS_SOURCE",
    "WALL_RATIO_LOG_STD",
    "WALL_RATIO_MAX",
    "WALL_RATIO_MEDIAN",
    "RegionPriors",
    "TowerPriors",
    "masonry_prior",
    "strength_prior",
    "unit_weight_prior",
]

#: Where the TURRIS fits come from.
TURRIS_SOURCE = (
    "TURRIS (Montabert et al., Buildings 2023; GitHub MArnaud/TURRIS), unique Italian "
    "towers, fitted by benchmarks/turris_priors.py"
)
#: Base wall / smaller plan side: lognormal fit (74 towers; 10/50/90 % of the data 0.134 /
#: 0.240 / 0.347), capped at :data:`WALL_RATIO_MAX`.
WALL_RATIO_MEDIAN = 0.2271
WALL_RATIO_LOG_STD = 0.3561
#: A wall of half the smaller side or more leaves no void: a solid section.
WALL_RATIO_MAX = 0.5
#: Top / base wall: share of prismatic shafts, and the beta of the others (69 towers).
TAPER_PRISMATIC_SHARE = 0.2319
TAPER_BETA_A = 1.8287
TAPER_BETA_B = 1.0983
#: T_measured / (0.0187 H): lognormal fit (98 towers; sample median 0.972).
PERIOD_RATIO_MEDIAN = 0.9501
PERIOD_LOG_STD = 0.4479
#: The historic types of Table C8.5.I a bell tower may be built of (a judgement).
BELL_TOWER_MASONRY_TYPES: tuple[str, ...] = tuple(
    name for name in MASONRY_TYPES if name != "semi_solid_brick"
)
#: Circolare 2019 Table C8.5.I, note (**): soft stone's unit weight 13 ÷ 16 kN/m3 [N/m3].
SOFT_STONE_UNIT_WEIGHT_N_M3 = (13.0e3, 16.0e3)
_SOFT_STONES = ("soft_stone", "regular_soft_stone")
_TABLE = "Circolare 2019 §C8.5.3.1 Table C8.5.I"


def masonry_prior() -> Categorical:
    """Return the default masonry-type prior: uniform over the bell towers' types (judgement)."""
    share = 1.0 / len(BELL_TOWER_MASONRY_TYPES)
    return Categorical(
        tuple((name, share) for name in BELL_TOWER_MASONRY_TYPES),
        source=(
            "judgement: uniform over the seven historic types of "
            f"{_TABLE} (semi_solid_brick, with cement mortar, left out)"
        ),
        judgement=True,
    )


def strength_prior(masonry_type: str) -> Uniform | Point:
    """Return the prior of the mean compressive strength f_m [Pa] of a masonry type.

    Uniform between the ends of the type's range in Table C8.5.I (a point where the table
    gives one value, ``roughly_cut_stone``'s 2.0 MPa).

    Parameters
    ----------
    masonry_type : str
        A key of :data:`~rockscreen.pipeline.risk.checks.confidence.MASONRY_TYPES`.

    Returns
    -------
    Uniform or Point
    """
    row = MASONRY_TYPES[masonry_type]
    source = f"{_TABLE}, {masonry_type}: uniform over the range of the mean f"
    if row.fm_max_pa > row.fm_min_pa:
        return Uniform(row.fm_min_pa, row.fm_max_pa, source)
    return Point(row.fm_min_pa, f"{_TABLE}, {masonry_type}: one value of the mean f")


def unit_weight_prior(masonry_type: str) -> Uniform | Point:
    """Return the prior of the unit weight w [N/m3] of a masonry type.

    The table's value; for the two soft-stone rows uniform over the table's 13 ÷ 16 kN/m3
    (note (**): very variable).

    Parameters
    ----------
    masonry_type : str
        A key of :data:`~rockscreen.pipeline.risk.checks.confidence.MASONRY_TYPES`.

    Returns
    -------
    Uniform or Point
    """
    if masonry_type in _SOFT_STONES:
        low, high = SOFT_STONE_UNIT_WEIGHT_N_M3
        return Uniform(low, high, f"{_TABLE}, note (**): 13 ÷ 16 kN/m3, uniform")
    w = MASONRY_TYPES[masonry_type].unit_weight_n_m3
    return Point(w, f"{_TABLE}, {masonry_type}: w = {w / 1e3:g} kN/m3")


@dataclass(frozen=True)
class RegionPriors:
    """The priors a region applies where the inventory is silent (defaults: TURRIS, judgement).

    Read from a priors file by
    :func:`~rockscreen.pipeline.risk.uncertainty.region.read_region_priors`.
    """

    #: Base wall / smaller plan side (a ratio, capped at 0.5).
    wall_ratio: LogNormal | Point = field(
        default_factory=lambda: LogNormal(
            WALL_RATIO_MEDIAN, WALL_RATIO_LOG_STD, TURRIS_SOURCE, upper=WALL_RATIO_MAX
        )
    )
    #: Top / base wall ratio.
    taper: Taper | Point = field(
        default_factory=lambda: Taper(
            TAPER_PRISMATIC_SHARE, TAPER_BETA_A, TAPER_BETA_B, TURRIS_SOURCE
        )
    )
    #: Masonry type.
    masonry: Categorical | Point = field(default_factory=masonry_prior)
    #: T_measured / (0.0187 H).
    period_ratio: LogNormal | Point = field(
        default_factory=lambda: LogNormal(PERIOD_RATIO_MEDIAN, PERIOD_LOG_STD, TURRIS_SOURCE)
    )
    #: The belfry the screening risk samples for a row without the belfry columns
    #: (:func:`~rockscreen.pipeline.risk.uncertainty.belfry.belfry_for_row`); None: none
    #: (a priors file's ``[belfry] sampled = false``).
    belfry: BelfryPriors | None = field(default_factory=BelfryPriors)
    #: The file it was read from ("" for the defaults).
    path: str = ""

    def period_prior(self, height_m: float) -> LogNormal | Point:
        """Return the prior of T1 [s] of a tower of height ``height_m`` (module docstring)."""
        law = tower_period_guidelines(height_m)
        r = self.period_ratio
        source = f"T1 = 0.0187 H x ({r.source})"
        if isinstance(r, Point):
            return Point(law * r.value, source, r.judgement)
        return LogNormal(law * r.median_value, r.log_std, source, r.judgement)


#: The inventory columns that collapse a prior (column -> the prior's name).
COLLAPSING_COLUMNS = {
    "wall_thickness_m": "wall_m",
    "wall_thickness_top_m": "taper",
    "masonry_type": "masonry_type",
    "masonry_strength_mpa": "fm_pa",
    "shaft_period_s": "period_s",
}
_PA_PER_MPA = 1.0e6


@dataclass(frozen=True)
class TowerPriors:
    """A tower's geometry and the priors of what its inventory row does not say.

    Build it from an inventory row with :meth:`from_tower`; a value the row gives is a
    :class:`Point` (:data:`COLLAPSING_COLUMNS`), the rest the region's priors.
    """

    #: The tower's id.
    tower_id: str
    #: Plan along x (``width_m``) and along y (the plan depth) [m], whole height H [m].
    width_m: float
    depth_m: float
    height_m: float
    #: Base wall thickness t_0 [m].
    wall: LogNormal | Point
    #: Top / base wall ratio [-].
    taper: Taper | Point
    #: Masonry type.
    masonry: Categorical | Point
    #: First period T1 [s].
    period: LogNormal | Point
    #: A measured mean strength f_m [Pa] (``masonry_strength_mpa``), else None: the prior
    #: of the type (:func:`strength_prior`).
    fm_given_pa: float | None = None

    def strength(self, masonry_type: str) -> Uniform | Point:
        """Return the prior of f_m [Pa] for a masonry type (a measured value collapses it)."""
        if self.fm_given_pa is not None:
            return Point(self.fm_given_pa, "inventory: masonry_strength_mpa")
        return strength_prior(masonry_type)

    def unit_weight(self, masonry_type: str) -> Uniform | Point:
        """Return the prior of w [N/m3] for a masonry type (:func:`unit_weight_prior`)."""
        return unit_weight_prior(masonry_type)

    def priors(self) -> dict[str, Any]:
        """Return the tower-level priors by name.

        ``wall_m``, ``taper``, ``masonry_type``, ``period_s``; f_m and w depend on the type
        (:meth:`strength`, :meth:`unit_weight`).
        """
        return {
            "wall_m": self.wall,
            "taper": self.taper,
            "masonry_type": self.masonry,
            "period_s": self.period,
        }

    @property
    def judgements(self) -> tuple[str, ...]:
        """Return the names of the priors that are judgements (to be labelled so)."""
        return tuple(name for name, prior in self.priors().items() if prior.judgement)

    def sample(
        self, rng: np.random.Generator, n: int, *, belfry: BelfryPriors | None = None
    ) -> dict[str, np.ndarray]:
        """Return ``n`` joint samples of the epistemic inputs, a dict of arrays (SI units).

        Draws, in this order: the base wall, the taper, the masonry type, then per type (in
        Table C8.5.I's order) f_m and w of the samples of that type, the period, and last
        (so the others are the same draws with or without it) the belfry.

        Parameters
        ----------
        rng : numpy.random.Generator
            The random generator (the same seed gives the same samples).
        n : int
            Number of samples, >= 1.
        belfry : BelfryPriors, optional
            Sample a belfry for a row without the belfry columns
            (:meth:`~rockscreen.pipeline.risk.uncertainty.belfry.BelfryPriors.sample`; its
            keys are added). None (this function's default): no belfry is sampled; ``assess``
            passes the region's (:attr:`RegionPriors.belfry`, sampled unless a priors file
            turns it off).

        Returns
        -------
        dict
            ``wall_m``, ``wall_top_m`` [m], ``masonry_type`` (object array of str),
            ``fm_pa`` [Pa], ``unit_weight_n_m3`` [N/m3], ``period_s`` [s]: arrays of ``n``.
        """
        n = int(n)
        if n < 1:
            raise RiskError(f"n={n!r} samples: must be >= 1")
        wall = np.asarray(self.wall.sample(rng, n), dtype=float)
        taper = np.asarray(self.taper.sample(rng, n), dtype=float)
        types = np.asarray(self.masonry.sample(rng, n), dtype=object)
        fm = np.empty(n)
        w = np.empty(n)
        for name in MASONRY_TYPES:
            mask = types == name
            k = int(mask.sum())
            if k:
                fm[mask] = self.strength(name).sample(rng, k)
                w[mask] = self.unit_weight(name).sample(rng, k)
        period = np.asarray(self.period.sample(rng, n), dtype=float)
        sampled_belfry = {} if belfry is None else belfry.sample(rng, n)
        return {
            **sampled_belfry,
            "wall_m": wall,
            "wall_top_m": wall * taper,
            "masonry_type": types,
            "fm_pa": fm,
            "unit_weight_n_m3": w,
            "period_s": period,
        }

    @classmethod
    def from_tower(cls, tower: Tower, region: RegionPriors | None = None) -> TowerPriors:
        """Return a tower's priors from its inventory row and the region's priors.

        Parameters
        ----------
        tower : rockscreen.stations.inventory.Tower
            The row: ``width_m``, the plan depth and ``height_m`` at least; each of
            :data:`COLLAPSING_COLUMNS` it gives collapses that prior to a point
            (``wall_thickness_top_m`` with ``wall_thickness_m``: the taper; a base wall
            alone keeps the taper's prior, the row saying nothing of the top).
        region : RegionPriors, optional
            The region's priors (default: :class:`RegionPriors`, TURRIS and judgement).

        Returns
        -------
        TowerPriors
        """
        region = RegionPriors() if region is None else region
        width, depth = float(tower.width_m), float(tower.plan_depth_m)
        height = float(tower.height_m)
        side = min(width, depth)
        base = getattr(tower, "wall_thickness_m", None)
        top = getattr(tower, "wall_thickness_top_m", None)
        if base is not None:
            wall: LogNormal | Point = Point(float(base), "inventory: wall_thickness_m")
        elif isinstance(region.wall_ratio, Point):
            r = region.wall_ratio
            wall = Point(min(r.value, WALL_RATIO_MAX) * side, r.source, r.judgement)
        else:
            r = region.wall_ratio
            wall = LogNormal(
                r.median_value * side,
                r.log_std,
                f"{r.median_value:g} x the smaller side {side:g} m ({r.source})",
                r.judgement,
                upper=WALL_RATIO_MAX * side,
            )
        if base is not None and top is not None:
            taper: Taper | Point = Point(
                float(top) / float(base), "inventory: wall_thickness_top_m / wall_thickness_m"
            )
        else:
            taper = region.taper
        kind = getattr(tower, "masonry_type", None)
        masonry = Point(kind, "inventory: masonry_type") if kind else region.masonry
        measured = getattr(tower, "masonry_strength_mpa", None)
        fm = None if measured is None else float(measured) * _PA_PER_MPA
        period_s = getattr(tower, "shaft_period_s", None)
        period = (
            Point(float(period_s), "inventory: shaft_period_s")
            if period_s
            else region.period_prior(height)
        )
        return cls(str(tower.id), width, depth, height, wall, taper, masonry, period, fm)
