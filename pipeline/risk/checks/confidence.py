"""Knowledge levels, confidence factors and the reference masonry parameters of the Circolare.

Source: Circolare 21/1/2019 n. 7 C.S.LL.PP., read in the verified transcription of the
public repository ``claudiopagani/structural-codes`` (``corpus/units/circ2019/c8.5.4.json``,
``c8.5.4.1.json``, ``corpus/assets/circ2019/C8.5-step1.json``; the extract used is
summarised in ``docs/code_checks.md`` §4).

- **Confidence factor** FC of the knowledge level (Circolare 2019 §C8.5.4 (PDF p. 265)):
  LC1 1.35, LC2 1.2, LC3 1.0. FC divides the material parameters; at LC3 FC = 1 applies only
  to the parameters that were tested. Table C8.5.IV, with the same digits, is for reinforced
  concrete and steel buildings (§C8.5.4.2), not for masonry. The Guidelines for cultural
  heritage (DPCM 9/2/2011 §4.2, *to be verified*) build their own FC = 1 + sum of partial
  factors (between 1.00 and 1.35); pass such a value directly where a function takes
  ``fc``.
- **Masonry types** (Circolare 2019 §C8.5.3.1, Table C8.5.I (PDF p. 261)): for each of the
  table's eight types the ranges of the mean compressive strength f, of the mean shear
  strengths tau0 and (where given) f_v0, of the mean moduli E and G, and the mean unit
  weight w.
- **Which value a knowledge level takes** (Circolare 2019 §C8.5.4.1 (PDF p. 266)): LC1 the
  minimum of the strength ranges and the mean of the modulus ranges; LC2 the mean of both.
  LC3 rests on tests (the table is the prior of a Bayesian update of the mean, eqs.
  [C8.5.4.1]-[C8.5.4.3] with kappa from Table C8.5.III): the strength must be given
  (``measured_pa``); a modulus that was not tested keeps the table's mean.

Table C8.5.II (correction coefficients for good mortar, courses, transverse connections
and consolidation) is not applied.
"""

from __future__ import annotations

from dataclasses import dataclass

from rockscreen.pipeline.errors import RiskError
from rockscreen.pipeline.risk.checks.validation import check_number
from rockscreen.solver.constants import G
from rockscreen.stations.inventory_columns import MASONRY_UNIT_WEIGHTS_KN_M3

__all__ = [
    "CONFIDENCE_FACTORS",
    "MASONRY_TYPES",
    "MasonryType",
    "confidence_factor",
    "design_compressive_strength",
    "masonry_elastic_modulus",
    "masonry_strength",
]

#: Knowledge level -> confidence factor FC [-] (Circolare 2019 §C8.5.4 (PDF p. 265)).
CONFIDENCE_FACTORS = {"LC1": 1.35, "LC2": 1.20, "LC3": 1.00}


@dataclass(frozen=True)
class MasonryType:
    """One row of Circolare 2019 Table C8.5.I (PDF p. 261), in SI units.

    Every strength and modulus is a mean value of the material; the table gives its range
    over the masonry type (min-max).
    """

    #: Description of the type, in English (the table's Italian name after it).
    name: str
    #: Range of the mean compressive strength f [Pa].
    fm_min_pa: float
    fm_max_pa: float
    #: Range of the mean shear strength without normal stress tau0 [Pa].
    tau0_min_pa: float
    tau0_max_pa: float
    #: Range of the mean shear strength without normal stress f_v0 [Pa]; None where the
    #: table gives none ("-").
    fv0_min_pa: float | None
    fv0_max_pa: float | None
    #: Range of the mean Young's modulus E [Pa].
    e_min_pa: float
    e_max_pa: float
    #: Range of the mean shear modulus G [Pa].
    g_min_pa: float
    g_max_pa: float
    #: Mean unit weight w [N/m3].
    unit_weight_n_m3: float

    @property
    def density_kg_m3(self) -> float:
        """Return the mass density w / g [kg/m3]."""
        return self.unit_weight_n_m3 / G

    @property
    def e_mean_pa(self) -> float:
        """Return the mean of the range of E [Pa] (the value of LC1 and LC2)."""
        return 0.5 * (self.e_min_pa + self.e_max_pa)


_MPA = 1.0e6  # N/mm2 -> Pa
_KN = 1.0e3  # kN/m3 -> N/m3


def _row(
    name: str,
    f: tuple[float, float],
    tau0: tuple[float, float],
    fv0: tuple[float, float] | None,
    e: tuple[float, float],
    g: tuple[float, float],
    w: float,
) -> MasonryType:
    """Build a row from the table's units (N/mm2, kN/m3), stored in Pa and N/m3."""
    return MasonryType(
        name,
        f[0] * _MPA,
        f[1] * _MPA,
        tau0[0] * _MPA,
        tau0[1] * _MPA,
        None if fv0 is None else fv0[0] * _MPA,
        None if fv0 is None else fv0[1] * _MPA,
        e[0] * _MPA,
        e[1] * _MPA,
        g[0] * _MPA,
        g[1] * _MPA,
        w * _KN,
    )


#: Circolare 2019 §C8.5.3.1, Table C8.5.I (PDF p. 261): the eight rows, in the table's order.
#: Arguments of ``_row``: f, tau0, f_v0 [N/mm2] (min, max), E, G [N/mm2] (min, max), the
#: table's digits; w [kN/m3] from the inventory's one list of the table's unit weights
#: (:data:`rockscreen.stations.inventory_columns.MASONRY_UNIT_WEIGHTS_KN_M3`). The table's
#: notes and how they bear on the numbers:
#:
#: - (*) "conci sbozzati": the strengths may be raised by a coefficient 1.2 only where deep
#:   stone wedges are systematically present; that needs evidence of the tower, so it is
#:   not applied here;
#: - (**) soft stone: the unit weight is very variable and can be measured (the table gives
#:   13 ÷ 16 kN/m3 for both soft-stone rows); for regular soft-stone blocks with the units
#:   characterised directly, f may follow NTC 2018 §11.10 instead (not done here);
#: - (***) solid brick: with mortar joints thicker than 13 mm the values are reduced, by 0.7
#:   for the strengths and 0.8 for the moduli; the inventory does not record the joints, so
#:   the reduction is not applied (apply it to a measured value where it holds).
MASONRY_TYPES: dict[str, MasonryType] = {
    "rubble": _row(
        "irregular stone rubble (pietrame disordinata: ciottoli, pietre erratiche e irregolari)",
        f=(1.0, 2.0),
        tau0=(0.018, 0.032),
        fv0=None,
        e=(690.0, 1050.0),
        g=(230.0, 350.0),
        w=MASONRY_UNIT_WEIGHTS_KN_M3["rubble"],
    ),
    "roughly_cut_stone": _row(
        "roughly cut stone, uneven leaves (conci sbozzati, paramenti di spessore disomogeneo)",
        # The table gives f as the single value 2,0 (no range): min = max = 2.0, so LC1
        # and LC2 both take 2.0 N/mm2. Note (*)'s 1.2 is an increase with evidence only.
        f=(2.0, 2.0),
        tau0=(0.035, 0.051),
        fv0=None,
        e=(1020.0, 1440.0),
        g=(340.0, 480.0),
        w=MASONRY_UNIT_WEIGHTS_KN_M3["roughly_cut_stone"],
    ),
    "split_stone": _row(
        "split stone with good texture (pietre a spacco con buona tessitura)",
        f=(2.6, 3.8),
        tau0=(0.056, 0.074),
        fv0=None,
        e=(1500.0, 1980.0),
        g=(500.0, 660.0),
        w=MASONRY_UNIT_WEIGHTS_KN_M3["split_stone"],
    ),
    "soft_stone": _row(
        "irregular soft stone, tuff or calcarenite (irregolare di pietra tenera)",
        f=(1.4, 2.2),
        tau0=(0.028, 0.042),
        fv0=None,
        e=(900.0, 1260.0),
        g=(300.0, 420.0),
        # Table: 13 ÷ 16 (**), very variable, measure it: 16 (stations.inventory_columns).
        w=MASONRY_UNIT_WEIGHTS_KN_M3["soft_stone"],
    ),
    "regular_soft_stone": _row(
        "regular soft stone blocks, tuff or calcarenite (conci regolari di pietra tenera)",
        f=(2.0, 3.2),
        tau0=(0.04, 0.08),
        fv0=(0.10, 0.19),
        e=(1200.0, 1620.0),
        g=(400.0, 500.0),
        # The same merged cell 13 ÷ 16 (**) as the row above: 16.
        w=MASONRY_UNIT_WEIGHTS_KN_M3["regular_soft_stone"],
    ),
    "dressed_stone": _row(
        "squared stone blocks (blocchi lapidei squadrati)",
        f=(5.8, 8.2),
        tau0=(0.09, 0.12),
        fv0=(0.18, 0.28),
        e=(2400.0, 3300.0),
        g=(800.0, 1100.0),
        w=MASONRY_UNIT_WEIGHTS_KN_M3["dressed_stone"],
    ),
    "solid_brick": _row(
        "solid brick and lime mortar (mattoni pieni e malta di calce)",
        # (***): joints thicker than 13 mm -> 0.7 f and 0.8 E, G (not applied).
        f=(2.6, 4.3),
        tau0=(0.05, 0.13),
        fv0=(0.13, 0.27),
        e=(1200.0, 1800.0),
        g=(400.0, 600.0),
        w=MASONRY_UNIT_WEIGHTS_KN_M3["solid_brick"],
    ),
    "semi_solid_brick": _row(
        "semi-solid brick and cement mortar, e.g. double UNI, holes <= 40 % "
        "(mattoni semipieni con malta cementizia)",
        f=(5.0, 8.0),
        tau0=(0.08, 0.17),
        fv0=(0.20, 0.36),
        e=(3500.0, 5600.0),
        g=(875.0, 1400.0),
        w=MASONRY_UNIT_WEIGHTS_KN_M3["semi_solid_brick"],
    ),
}


def confidence_factor(knowledge_level: str) -> float:
    """Return FC of a knowledge level (Circolare 2019 §C8.5.4 (PDF p. 265)).

    LC1 1.35, LC2 1.2, LC3 1.0 (the masonry values are in the text of §C8.5.4; Table
    C8.5.IV, with the same digits, is for reinforced concrete and steel).

    Parameters
    ----------
    knowledge_level : {"LC1", "LC2", "LC3"}
        Knowledge level (case and surrounding blanks ignored).

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


def _masonry_row(masonry_type: str, parameter: str) -> MasonryType:
    """Return the row of a masonry type, or raise naming the parameter and the types."""
    if masonry_type not in MASONRY_TYPES:
        raise RiskError(
            f"{parameter}={masonry_type!r} is not one of {', '.join(MASONRY_TYPES)} "
            "(Circolare 2019 Table C8.5.I)"
        )
    return MASONRY_TYPES[masonry_type]


def _measured(knowledge_level: str, measured_pa: float | None, what: str) -> float | None:
    """Check the level and a measured value; return the value at LC3, None otherwise."""
    level = str(knowledge_level).strip().upper()
    confidence_factor(level)  # refuses an unknown level by name
    if measured_pa is None:
        return None
    if level != "LC3":
        raise RiskError(
            f"measured_pa={measured_pa!r} is allowed only with knowledge_level='LC3' "
            f"(LC1 and LC2 take the {what} from Table C8.5.I, Circolare 2019 §C8.5.4.1); "
            f"got knowledge_level={knowledge_level!r}"
        )
    return check_number("measured_pa", measured_pa, low=0.0, low_open=True, unit="Pa")


def masonry_strength(
    masonry: str, knowledge_level: str, *, measured_pa: float | None = None
) -> float:
    """Return the mean compressive strength f [Pa] a knowledge level takes.

    Circolare 2019 §C8.5.4.1 (PDF p. 266) on Table C8.5.I: LC1 the minimum of the range, LC2
    the mean of the range. LC3 rests on tests: the measured value (the mean updated with the
    tests, eqs. [C8.5.4.1]-[C8.5.4.3]) must be given, and is returned.

    Parameters
    ----------
    masonry : str
        A key of :data:`MASONRY_TYPES`.
    knowledge_level : {"LC1", "LC2", "LC3"}
        Knowledge level.
    measured_pa : float, optional
        The f from the tests [Pa], > 0; required with LC3, refused with LC1 and LC2.

    Returns
    -------
    float
        f [Pa] (not yet divided by FC).

    Raises
    ------
    RiskError
        For an unknown type or level, LC3 without ``measured_pa``, or ``measured_pa`` with
        LC1 or LC2 or out of range.
    """
    row = _masonry_row(masonry, "masonry")
    measured = _measured(knowledge_level, measured_pa, "strengths")
    level = str(knowledge_level).strip().upper()
    if level == "LC1":
        return row.fm_min_pa
    if level == "LC2":
        return 0.5 * (row.fm_min_pa + row.fm_max_pa)
    if measured is None:
        raise RiskError(
            "knowledge_level='LC3' rests on test results: give the measured f as measured_pa "
            "[Pa] instead of a Table C8.5.I value (Circolare 2019 §C8.5.4.1)"
        )
    return measured


def masonry_elastic_modulus(
    masonry_type: str, knowledge_level: str, *, measured_pa: float | None = None
) -> float:
    """Return the Young's modulus E [Pa] a knowledge level takes.

    Circolare 2019 §C8.5.4.1 (PDF p. 266) on Table C8.5.I: LC1 and LC2 both take the mean of
    the range of E. At LC3, FC = 1 applies only to the parameters that were tested
    (§C8.5.4 (PDF p. 265)): a measured E is returned when given, otherwise the table's mean
    as at LC1 and LC2. The value is not reduced for cracking (the Circolare suggests a
    reduced E for cracked conditions in the period T0 of [C8.7.1.7]: the caller applies it).

    Parameters
    ----------
    masonry_type : str
        A key of :data:`MASONRY_TYPES`.
    knowledge_level : {"LC1", "LC2", "LC3"}
        Knowledge level.
    measured_pa : float, optional
        The E from the tests [Pa], > 0; only with LC3.

    Returns
    -------
    float
        E [Pa].

    Raises
    ------
    RiskError
        For an unknown type or level, or ``measured_pa`` with LC1 or LC2 or out of range.
    """
    row = _masonry_row(masonry_type, "masonry_type")
    measured = _measured(knowledge_level, measured_pa, "elastic moduli")
    return row.e_mean_pa if measured is None else measured


def design_compressive_strength(fm_pa: float, fc: float, gamma_m: float = 2.0) -> float:
    """Return the design compressive strength f_d = f_m / (gamma_M FC) [Pa].

    ``gamma_M = 2`` is the partial factor of existing masonry under seismic actions
    (Circolare 2019 §C8.7.1, PDF p. 270: "le verifiche nei riguardi delle azioni sismiche
    sono eseguite utilizzando gamma_M = 2"); whether the Guidelines' LV1 keeps it or takes
    the mean strength over FC alone is to be verified: pass ``gamma_m`` explicitly then.

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
