"""Knowledge levels, confidence factors and the reference masonry strengths of the Circolare.

- **Confidence factor** FC of the knowledge level (Circolare 21/1/2019 n. 7, §C8.5.4 and
  its table of knowledge levels; Circolare 2/2/2009 n. 617, §C8A.1 and Tab. C8A.1.1 had the
  same values): LC1 1.35, LC2 1.20, LC3 1.00. The Guidelines for cultural heritage (DPCM
  9/2/2011 §4.2) build their own FC = 1 + sum of partial factors (between 1.00 and 1.35);
  pass such a value directly where a function takes ``fc``.
- **Masonry types** (Circolare 2019, Table C8.5.I): the range of the mean compressive
  strength f_m [N/mm2] and the unit weight w [kN/m3] of each type. Which value of the range a
  knowledge level uses (Circolare 2019 §C8.5.4.1, to be verified): LC1 the lower end, LC2
  the mid value; LC3 rests on tests and has no table value here (give f_m explicitly).

The digits of :data:`MASONRY_TYPES` were transcribed from the Circolare's table as the
authors know it and are **to be verified row by row** against the published text
(``docs/code_checks.md``); every function also takes an explicit strength.
"""

from __future__ import annotations

from dataclasses import dataclass

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.code_checks.validation import check_number
from rockscreen.solver.constants import G
from rockscreen.stations.inventory_columns import MASONRY_UNIT_WEIGHTS_KN_M3

__all__ = [
    "CONFIDENCE_FACTORS",
    "MASONRY_TYPES",
    "MasonryType",
    "confidence_factor",
    "design_compressive_strength",
    "masonry_strength",
]

#: Knowledge level -> confidence factor FC [-] (Circolare 2019 §C8.5.4).
CONFIDENCE_FACTORS = {"LC1": 1.35, "LC2": 1.20, "LC3": 1.00}


@dataclass(frozen=True)
class MasonryType:
    """One row of Circolare 2019 Table C8.5.I (strength range and unit weight)."""

    #: Description of the type, in English (the table's Italian name after it).
    name: str
    #: Range of the mean compressive strength f_m [Pa].
    fm_min_pa: float
    fm_max_pa: float
    #: Unit weight w [N/m3].
    unit_weight_n_m3: float

    @property
    def density_kg_m3(self) -> float:
        """Return the mass density w / g [kg/m3]."""
        return self.unit_weight_n_m3 / G


_MPA = 1.0e6
_KN = 1.0e3


def _w(name: str) -> float:
    """Return the unit weight of a masonry type [N/m3] (stations' inventory columns)."""
    return MASONRY_UNIT_WEIGHTS_KN_M3[name] * _KN


#: Circolare 2019 Table C8.5.I, the types found in bell towers (values to be verified).
MASONRY_TYPES: dict[str, MasonryType] = {
    "rubble": MasonryType(
        "irregular stone rubble (pietrame disordinata)", 1.0 * _MPA, 2.0 * _MPA, _w("rubble")
    ),
    "roughly_cut_stone": MasonryType(
        "roughly cut stone, uneven leaves (conci sbozzati)",
        2.0 * _MPA,
        3.0 * _MPA,
        _w("roughly_cut_stone"),
    ),
    "split_stone": MasonryType(
        "split stone with good texture (pietre a spacco)", 2.6 * _MPA, 3.8 * _MPA, _w("split_stone")
    ),
    "soft_stone": MasonryType(
        "soft stone blocks, tuff or calcarenite (pietra tenera)",
        1.4 * _MPA,
        2.4 * _MPA,
        _w("soft_stone"),
    ),
    "dressed_stone": MasonryType(
        "squared dressed stone blocks (blocchi lapidei squadrati)",
        6.0 * _MPA,
        8.0 * _MPA,
        _w("dressed_stone"),
    ),
    "solid_brick": MasonryType(
        "solid brick and lime mortar (mattoni pieni e malta di calce)",
        2.6 * _MPA,
        4.3 * _MPA,
        _w("solid_brick"),
    ),
}


def confidence_factor(knowledge_level: str) -> float:
    """Return FC of a knowledge level (Circolare 2019 §C8.5.4): LC1 1.35, LC2 1.20, LC3 1.00.

    Parameters
    ----------
    knowledge_level : {"LC1", "LC2", "LC3"}
        Knowledge level.

    Returns
    -------
    float
        FC [-].

    Raises
    ------
    RiskError
        For another level.
    """
    key = str(knowledge_level).strip().upper()
    if key not in CONFIDENCE_FACTORS:
        raise RiskError(
            f"knowledge_level={knowledge_level!r} is not one of "
            f"{', '.join(CONFIDENCE_FACTORS)} (Circolare 2019 §C8.5.4)"
        )
    return CONFIDENCE_FACTORS[key]


def masonry_strength(masonry: str, knowledge_level: str) -> float:
    """Return the mean compressive strength f_m [Pa] a knowledge level takes from Table C8.5.I.

    LC1: the lower end of the range; LC2: the mid value (Circolare 2019 §C8.5.4.1, to be
    verified). LC3 needs test results and is refused here.

    Parameters
    ----------
    masonry : str
        A key of :data:`MASONRY_TYPES`.
    knowledge_level : {"LC1", "LC2"}
        Knowledge level.

    Returns
    -------
    float
        f_m [Pa] (not yet divided by FC).

    Raises
    ------
    RiskError
        For an unknown type or level, or LC3.
    """
    if masonry not in MASONRY_TYPES:
        raise RiskError(
            f"masonry={masonry!r} is not one of {', '.join(MASONRY_TYPES)} "
            "(Circolare 2019 Table C8.5.I)"
        )
    level = str(knowledge_level).strip().upper()
    row = MASONRY_TYPES[masonry]
    if level == "LC1":
        return row.fm_min_pa
    if level == "LC2":
        return 0.5 * (row.fm_min_pa + row.fm_max_pa)
    confidence_factor(level)  # refuses an unknown level by name
    raise RiskError(
        "knowledge_level='LC3' rests on test results: give the measured f_m instead of a "
        "Table C8.5.I value"
    )


def design_compressive_strength(fm_pa: float, fc: float, gamma_m: float = 2.0) -> float:
    """Return the design compressive strength f_d = f_m / (gamma_M FC) [Pa].

    ``gamma_M = 2`` is the partial factor of masonry under seismic actions (NTC 2018
    §7.8.1.1, to be verified for the LV1 of the Guidelines, which may use ``gamma_M = 1``
    with the mean strengths of existing buildings: pass it explicitly).

    Parameters
    ----------
    fm_pa : float
        Mean compressive strength f_m [Pa], > 0.
    fc : float
        Confidence factor FC [-], in [1, 2].
    gamma_m : float
        Partial factor gamma_M [-], in [1, 5].

    Returns
    -------
    float
        f_d [Pa].
    """
    fm = check_number("fm_pa", fm_pa, low=0.0, low_open=True, unit="Pa")
    fc = check_number("fc", fc, low=1.0, high=2.0)
    gamma_m = check_number("gamma_m", gamma_m, low=1.0, high=5.0)
    return fm / (gamma_m * fc)
