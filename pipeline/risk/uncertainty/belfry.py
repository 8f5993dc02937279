"""Priors of the belfry of a tower whose inventory row has no belfry columns (issue 31).

A geometry-only row (``id, lat, lon, width_m, depth_m, height_m``) says nothing of the
belfry (the bell cell on its piers), the part of a bell tower that failed most often in
L'Aquila 2009, Emilia 2012 and Central Italy 2016 (``docs/belfry.md``). These priors let
the best-estimate kinematic capacities (:func:`~.kinematic.kinematic_capacities`) check a
sampled belfry. In the library they are asked for (:meth:`~.priors.TowerPriors.sample`'s
``belfry``); the screening risk of ``assess`` samples them **by default** for a row
without the belfry columns (:func:`belfry_for_row`, the region's
:attr:`~.priors.RegionPriors.belfry`; a priors file's ``[belfry] sampled = false`` turns
them off; ``docs/uncertainty.md`` "Belfry priors").

What the data say and what is judgement (each labelled so by ``judgement``):

- **presence** :data:`BELFRY_PRESENCE` = 0.9 (judgement): the towers of an inventory of
  bell towers carry a bell cell; in TURRIS the seven Italian towers that report a bells'
  mass and are bell towers or a palace's tower all carry bells (the six with 0 are civic,
  fortress and water towers), and 71 of its 109 unique Italian towers (65 %) are named a
  bell tower, a belfry or a church's tower; an inventory mixing civic towers should lower
  it (a priors file's ``[belfry] presence``).
- **belfry height / tower height** uniform :data:`BELFRY_HEIGHT_SHARE` (judgement: the three
  archetypes of ``stations/data/example_belfries.csv`` have 0.14-0.20; no survey of it is
  available to this work).
- **opening ratio** ``r``, the share of the belfry's face taken by its openings, uniform
  :data:`BELFRY_OPENING_RATIO` (judgement: the archetypes' piers' effective width is 0.32-0.5
  of the tower's side, ``1 - r``). It sets the piers' effective width ``(1 - r) x`` the
  side along each plan axis and the piers' mass, ``(1 - r)`` of a hollow storey of the
  shaft's top wall.
- **bells' mass** lognormal, median :data:`BELLS_MASS_MEDIAN_KG`, log-std
  :data:`BELLS_MASS_LOG_STD`, capped at :data:`BELLS_MASS_MAX_KG`: the geometric mean and
  log-std of the seven Italian towers of TURRIS that report a non-zero bells' mass (1256 to
  40000 kg; Montabert et al., *Buildings* 2023), the cap their largest.
- **bells' height / belfry height** uniform :data:`BELLS_HEIGHT_SHARE` (judgement: the
  archetypes have 0.67-0.70).

**Quadrature** (:meth:`BelfryPriors.sample`): the belfry's four continuous inputs are drawn
as :data:`BELFRY_SCENARIOS` equal-probability scenarios (a Latin hypercube: one draw per
stratum of each input, paired at random), and each sample takes one at random: a tower
builds at most ``scenarios x types`` belfry mechanisms (each sample then checked at its own
period, all at once: :mod:`~rockscreen.pipeline.risk.uncertainty.kinematic_batch`). 16
scenarios: with 4 the seed-to-seed spread of the best estimate doubled on 20 TURRIS towers
(median 9.1 % against 4.7 % without a belfry, seeds 0-2); with 16 it is 4.6 %
(``docs/uncertainty.md``).

Friction and restitution enter no capacity of this library: the kinematic checks are
equilibrium (alpha0 from statics, no sliding, no impact) and the shaft's LV1 a section
check; they matter only for the IDA's rocking medians (Housner's restitution ``eta`` of
the block; the friction of the double-block model's building), which the library takes as
given (``docs/uncertainty.md``).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
from scipy.special import ndtri

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.uncertainty.distributions import LogNormal, Uniform
from rockscreen.pipeline.verdict.messages import Message, message
from rockscreen.solver.constants import G
from rockscreen.stations.inventory_columns import PLAUSIBLE_RANGES
from rockscreen.stations.tower import Tower

__all__ = [
    "BELFRY_HEIGHT_SHARE",
    "BELFRY_KEYS",
    "BELFRY_MIN_HEIGHT_M",
    "BELFRY_OPENING_RATIO",
    "BELFRY_PRESENCE",
    "BELFRY_SCENARIOS",
    "BELLS_HEIGHT_SHARE",
    "BELLS_MASS_LOG_STD",
    "BELLS_MASS_MAX_KG",
    "BELLS_MASS_MEDIAN_KG",
    "BelfryPriors",
    "belfry_for_row",
    "belfry_row",
]

#: Probability that a tower of a bell-tower inventory has a belfry [-] (judgement).
BELFRY_PRESENCE = 0.9
#: Belfry height / the tower's height [-]: uniform bounds (judgement).
BELFRY_HEIGHT_SHARE = (0.10, 0.20)
#: Share of the belfry's face taken by openings [-]: uniform bounds (judgement).
BELFRY_OPENING_RATIO = (0.4, 0.7)
#: Bells' mass [kg]: TURRIS, the seven Italian towers reporting one (geometric mean,
#: log-std of ln m), capped at their largest.
BELLS_MASS_MEDIAN_KG = 5445.0
BELLS_MASS_LOG_STD = 1.264
BELLS_MASS_MAX_KG = 40000.0
#: Bells' height / the belfry's height [-]: uniform bounds (judgement).
BELLS_HEIGHT_SHARE = (0.5, 0.8)
#: Equal-probability belfry scenarios per tower (the quadrature, module docstring).
BELFRY_SCENARIOS = 16
#: The lowest belfry an inventory row may have [m] (the column's plausible range).
BELFRY_MIN_HEIGHT_M = PLAUSIBLE_RANGES["belfry_height_m"][0]
#: The per-sample keys of a sampled belfry (:meth:`BelfryPriors.sample`).
BELFRY_KEYS = (
    "belfry_present",
    "belfry_height_share",
    "belfry_opening_ratio",
    "bells_mass_kg",
    "bells_height_share",
)
_JUDGEMENT = "judgement (docs/uncertainty.md, belfry priors)"
_PRESENCE = f"{_JUDGEMENT}: an inventory of bell towers"
_TURRIS_BELLS = (
    "TURRIS (Montabert et al., Buildings 2023), the 7 Italian towers reporting a bells' mass"
)


@dataclass(frozen=True)
class BelfryPriors:
    """The priors of a belfry the inventory does not describe (module docstring)."""

    #: Probability of a belfry [-], and its source.
    presence: float = BELFRY_PRESENCE
    presence_source: str = _PRESENCE
    presence_judgement: bool = True
    height_share: Uniform = field(
        default_factory=lambda: Uniform(*BELFRY_HEIGHT_SHARE, _JUDGEMENT, judgement=True)
    )
    opening_ratio: Uniform = field(
        default_factory=lambda: Uniform(*BELFRY_OPENING_RATIO, _JUDGEMENT, judgement=True)
    )
    bells_mass: LogNormal = field(
        default_factory=lambda: LogNormal(
            BELLS_MASS_MEDIAN_KG, BELLS_MASS_LOG_STD, _TURRIS_BELLS, upper=BELLS_MASS_MAX_KG
        )
    )
    bells_height_share: Uniform = field(
        default_factory=lambda: Uniform(*BELLS_HEIGHT_SHARE, _JUDGEMENT, judgement=True)
    )
    #: Equal-probability scenarios of the four continuous inputs, >= 1.
    scenarios: int = BELFRY_SCENARIOS

    def __post_init__(self):
        if not 0.0 <= float(self.presence) <= 1.0:
            raise RiskError(f"belfry priors: presence={self.presence!r}; allowed: [0, 1]")
        if int(self.scenarios) < 1:
            raise RiskError(f"belfry priors: scenarios={self.scenarios!r}; allowed: >= 1")
        lo, hi = self.height_share.low, self.height_share.high
        if not (0.0 < lo and hi < 1.0):
            raise RiskError(f"belfry priors: height share {lo}-{hi}; allowed: inside (0, 1)")
        lo, hi = self.opening_ratio.low, self.opening_ratio.high
        if not (0.0 <= lo and hi < 1.0):
            raise RiskError(f"belfry priors: opening ratio {lo}-{hi}; allowed: inside [0, 1)")
        lo, hi = self.bells_height_share.low, self.bells_height_share.high
        if not (0.0 <= lo and hi <= 1.0):
            raise RiskError(f"belfry priors: bells' height share {lo}-{hi}; allowed: [0, 1]")

    @property
    def judgements(self) -> tuple[str, ...]:
        """Return the names of the belfry priors that are judgements (to be labelled so)."""
        named = {
            "belfry_present": self.presence_judgement,
            "belfry_height_share": self.height_share.judgement,
            "belfry_opening_ratio": self.opening_ratio.judgement,
            "bells_mass_kg": self.bells_mass.judgement,
            "bells_height_share": self.bells_height_share.judgement,
        }
        return tuple(k for k, v in named.items() if v)

    @property
    def sources(self) -> dict[str, str]:
        """Return the source of each belfry prior by its sample key (:data:`BELFRY_KEYS`)."""
        return {
            "belfry_present": self.presence_source,
            "belfry_height_share": self.height_share.source,
            "belfry_opening_ratio": self.opening_ratio.source,
            "bells_mass_kg": self.bells_mass.source,
            "bells_height_share": self.bells_height_share.source,
        }

    def sample(self, rng: np.random.Generator, n: int) -> dict[str, np.ndarray]:
        """Return ``n`` samples of the belfry: presence and one of the scenarios each.

        Draws, in this order: the presence of each sample, the scenarios (a Latin
        hypercube of :attr:`scenarios` points over the four continuous priors, by their
        quantiles), the scenario of each sample.

        Returns
        -------
        dict
            :data:`BELFRY_KEYS` arrays of ``n``: ``belfry_present`` (bool), the height
            share, the opening ratio, ``bells_mass_kg`` [kg], the bells' height share.
        """
        n = int(n)
        present = rng.uniform(0.0, 1.0, n) < float(self.presence)
        k = int(self.scenarios)
        u = (rng.permuted(np.tile(np.arange(k), (4, 1)), axis=1) + rng.uniform(size=(4, k))) / k
        values = np.array(
            [
                _uniform_ppf(self.height_share, u[0]),
                _uniform_ppf(self.opening_ratio, u[1]),
                _lognormal_ppf(self.bells_mass, u[2]),
                _uniform_ppf(self.bells_height_share, u[3]),
            ]
        )
        which = rng.integers(0, k, n)
        out = {"belfry_present": present}
        for name, row in zip(BELFRY_KEYS[1:], values, strict=True):
            out[name] = row[which]
        return out


def _uniform_ppf(prior: Uniform, u: np.ndarray) -> np.ndarray:
    return prior.low + (prior.high - prior.low) * u


def _lognormal_ppf(prior: LogNormal, u: np.ndarray) -> np.ndarray:
    x = prior.median_value * np.exp(prior.log_std * ndtri(u))
    return x if prior.upper is None else np.minimum(x, prior.upper)


def belfry_row(
    tower: Tower,
    *,
    height_share: float,
    opening_ratio: float,
    bells_mass_kg: float,
    bells_height_share: float,
    wall_top_m: float,
    unit_weight_n_m3: float,
) -> Tower:
    """Return the row with a sampled belfry's columns (``docs/belfry.md``'s group).

    The belfry ``height_share x height_m`` tall on the top of the shaft; its piers'
    effective width ``(1 - r)`` of the tower's side along each axis; the piers' mass ``(1 -
    r)`` of a hollow storey of the shaft's top wall (``wall_top_m``, at most half the
    smaller side) and unit weight; the bells at ``bells_height_share`` of its height.

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        A row without the belfry columns.
    height_share, opening_ratio, bells_mass_kg, bells_height_share : float
        The sampled belfry (:meth:`BelfryPriors.sample`).
    wall_top_m, unit_weight_n_m3 : float
        The shaft's top wall [m] and the masonry's unit weight [N/m3].

    Returns
    -------
    Tower
    """
    if tower.has_belfry:
        raise RiskError(f"tower {tower.id}: the row has its belfry; nothing to sample")
    b, d = float(tower.width_m), float(tower.plan_depth_m)
    t = min(float(wall_top_m), 0.5 * min(b, d))
    h = float(height_share) * float(tower.height_m)
    area = b * d - max(b - 2.0 * t, 0.0) * max(d - 2.0 * t, 0.0)
    solid = 1.0 - float(opening_ratio)
    return replace(
        tower,
        belfry_height_m=h,
        belfry_width_m=solid * b,
        belfry_depth_m=solid * d,
        belfry_mass_kg=solid * area * h * float(unit_weight_n_m3) / G,
        bells_mass_kg=float(bells_mass_kg),
        bells_height_m=float(bells_height_share) * h,
    )


def belfry_for_row(
    tower: Tower, priors: BelfryPriors | None
) -> tuple[BelfryPriors | None, tuple[str, ...], list[Message]]:
    """Return the belfry priors to sample for a row, its judgement inputs and its notes.

    The screening risk's default (``assess``): a row without the belfry columns gets a
    sampled belfry (``priors``, the region's :attr:`~.priors.RegionPriors.belfry`), said
    in a note (``risk.belfry_sampled``) with each judgement prior labelled
    (``risk.judgement_prior``); a row with its columns is checked as given (nothing
    sampled, no note); priors None (a priors file's ``[belfry] sampled = false``): none,
    said (``risk.belfry_not_sampled``); nor on a row with a bell gable (its bells are checked
    there, ``risk.belfry_in_gable``) or a tower too low for the prior's shortest belfry to be
    a plausible one (``risk.belfry_too_low``, :data:`BELFRY_MIN_HEIGHT_M`).

    Parameters
    ----------
    tower : rockscreen.stations.inventory.Tower
        The row.
    priors : BelfryPriors or None
        The region's belfry priors.

    Returns
    -------
    belfry : BelfryPriors or None
        What to pass to :meth:`~.priors.TowerPriors.sample`.
    judgement : tuple of str
        The sampled inputs whose prior is a judgement (labelled so wherever shown).
    notes : list of Message
    """
    if tower.has_belfry:
        return None, (), []
    if priors is None:
        return None, (), [message("risk.belfry_not_sampled")]
    if tower.has_gable:
        return None, (), [message("risk.belfry_in_gable")]
    shortest = float(priors.height_share.low) * float(tower.height_m)
    if shortest < BELFRY_MIN_HEIGHT_M:
        too_low = message(
            "risk.belfry_too_low",
            height=float(tower.height_m),
            shortest=shortest,
            minimum=BELFRY_MIN_HEIGHT_M,
        )
        return None, (), [too_low]
    judgement = priors.judgements
    sources = priors.sources
    notes = [
        message("risk.belfry_sampled", presence=float(priors.presence)),
        *(
            message("risk.judgement_prior", input=k, source=_source_message(sources[k]))
            for k in judgement
        ),
    ]
    return priors, judgement, notes


def _source_message(text: str) -> Message | str:
    """Return a default belfry prior's source as a catalogue code, a region's as written."""
    if text == _PRESENCE:
        return message("risk.source_belfry_presence")
    if text == _JUDGEMENT:
        return message("risk.source_belfry_judgement")
    return text
