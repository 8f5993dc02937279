"""``rockscreen scenario``: probability of overturning of each tower under one event.

For a tower of an assess archive (its **collapse** fragility in the site's ag on rock, the
censored fit of its records' overturning intensities, :func:`collapse_fragility`;
``docs/risk.md``) and a ShakeMap grid of the event:

1. ``PGA`` [g] at the tower: bilinear interpolation on the grid
   (:meth:`rockscreen.pipeline.hazard.shakemap.ShakeMapGrid.at`); a tower outside the grid, or whose
   surrounding nodes are missing, is listed with status ``outside_grid``, not guessed;
2. the grid's PGA is at the surface, the fragility's ag on rock: ``ag_equiv = PGA / S``
   with ``S = S_S S_T`` of the tower's soil class and topography (NTC 2018 §3.2.3.2.1,
   :func:`pipeline.hazard.spectrum_parameters`); ``S_S`` depends on ``F0 ag``, so ``F0`` is
   taken from the site hazard at ``T_R,SLV`` and ``ag`` from the fixed point
   ``ag = PGA / S(ag)`` (a few iterations; exact for soil A, where ``S_S = 1``);
3. ``P(overturning) = Phi(ln(ag_equiv / median) / beta_tot)`` with
   ``beta_tot = sqrt(beta^2 + sigma_lnPGA^2)``: the ShakeMap's uncertainty of ln PGA at
   the tower (``STDPGA`` of the grid, ShakeMap 3, or of its ``uncertainty.xml``,
   ShakeMap 4; without either the default :data:`~rockscreen.pipeline.hazard.shakemap.
   DEFAULT_SIGMA_LN_PGA`, said in the row's note; 0 only with ``gm_uncertainty=False``)
   folded into the record-to-record dispersion of the fragility (both lognormal,
   independent).

A tower whose collapse median is only a bound still gets a probability, as a bound:
every record of a lower-bound median stood up to ``m`` (censored there), so the median is
at least ``m`` and, with a dispersion no larger than :data:`BOUND_BETA_MAX`,
``P(overturning) <= Phi(ln(ag_equiv / m) / sqrt(BOUND_BETA_MAX^2 + sigma^2))`` while
``ag_equiv < m`` (the supremum over every median above ``m`` and every beta up to the
maximum); symmetrically an upper-bound median gives a lower bound of P while
``ag_equiv > m``. The row's ``p_overturning_bound`` says ``upper`` or ``lower``, every
output prints the relation (``<0.031``, :mod:`rockscreen.pipeline.archive.bounds`), and the
class is the band of the bound, marked unless the band settles it (an upper bound in the
lowest band is that band). Beyond the bound (``ag_equiv >= m`` for a lower bound) nothing
is known: status ``no_fragility`` with the reason.

A tower without a usable fragility (not assessed, off the NTC 2018 grid, or an event
beyond its bound) is listed with status ``no_fragility`` and a note; the others are
computed (never an abort).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from typing import Any

from scipy.special import ndtr

from rockscreen.pipeline.errors import HazardError, RiskError
from rockscreen.pipeline.hazard import site_hazard, spectrum_parameters
from rockscreen.pipeline.hazard.shakemap import (
    DEFAULT_SIGMA_LN_PGA,
    ShakeMapGrid,
)
from rockscreen.pipeline.text import printable
from rockscreen.pipeline.verdict.messages import Message, message, note_columns, note_messages
from rockscreen.pipeline.verdict.scales import scenario_class_of
from rockscreen.pipeline.verdict.status import Bound

__all__ = [
    "BOUND_BETA_MAX",
    "collapse_fragility",
    "scenario_rows",
    "soil_factor",
    "tower_scenario",
]

#: The largest record-to-record dispersion [-] assumed for a bound fragility: the IDA
#: of rigid blocks on the real L'Aquila 2009 records gives beta 0.76-1.04 (docs/risk.md:
#: 0.82 for the 10 horizontals of ``../shared/data`` and a 0.6 x 4 m block; an independent
#: review found 1.04), so 1.0 covers what real records give.
BOUND_BETA_MAX = 1.0


def collapse_fragility(row: dict[str, Any]) -> tuple[float, float, str]:
    """Return ``(median [g], beta [-], bound)`` of the collapse fragility of an assess row.

    The IDA collapse fit (``collapse_median_g``, ``collapse_beta``, ``collapse_bound``); a
    row of an assess archive written before it carries the stripe fit under
    ``fragility_median_g``, ``fragility_beta``, ``median_is_bound``, read then.
    """
    if "collapse_median_g" in row:
        return row["collapse_median_g"], row["collapse_beta"], row["collapse_bound"]
    return row["fragility_median_g"], row["fragility_beta"], row["median_is_bound"]


def soil_factor(
    lon_deg: float,
    lat_deg: float,
    soil_class: str,
    topography: str,
    pga_g: float,
    tr_slv_y: float,
) -> float:
    """Return ``S = S_S S_T`` [-] for an event of surface PGA ``pga_g`` [g] (module docstring).

    Parameters
    ----------
    lon_deg, lat_deg : float
        Site [deg].
    soil_class, topography : str
        NTC 2018 categories.
    pga_g : float
        Surface PGA [g].
    tr_slv_y : float
        Return period whose F0 is used [y].
    """
    base = site_hazard(lon_deg, lat_deg, tr_slv_y, out_of_range="clamp")
    s = 1.0
    for _ in range(8):
        site = dataclasses.replace(base, ag_g=max(pga_g / s, 1e-6))
        s_new = spectrum_parameters(site, soil_class, topography).S
        if abs(s_new - s) < 1e-9:
            break
        s = s_new
    return s


def tower_scenario(
    row: dict[str, Any], grid: ShakeMapGrid, *, gm_uncertainty: bool = True
) -> dict[str, Any]:
    """Return the scenario row of one tower of an assess summary.

    Parameters
    ----------
    row : dict
        The tower's assess summary row (:func:`pipeline.archive.risk_reader.read_summary`).
    grid : ShakeMapGrid
    gm_uncertainty : bool
        Fold the uncertainty of the event's PGA into the probability (the grid's STDPGA,
        else :data:`~rockscreen.pipeline.hazard.shakemap.DEFAULT_SIGMA_LN_PGA`); False takes
        the ShakeMap's PGA as known (sigma 0, said in the note).

    Returns
    -------
    dict
        ``id``, ``name``, ``lat_deg``, ``lon_deg``, ``status`` (``ok``, ``outside_grid``,
        ``no_coordinates``, ``no_fragility``), ``event_pga_g`` [g],
        ``sigma_ln_pga`` [-], ``sigma_source``, ``soil_class``, ``soil_factor`` [-],
        ``ag_equiv_g`` [g],
        ``fragility_median_g`` [g], ``fragility_beta`` [-], ``median_is_bound``,
        ``beta_total`` [-], ``p_overturning`` [-], ``p_overturning_bound`` (``""``,
        ``"upper"``, ``"lower"``), ``note`` and ``note_codes``
        (:func:`rockscreen.pipeline.verdict.messages.note_columns`).
    """
    nan = math.nan
    median, beta, bound = collapse_fragility(row)
    out = {
        "id": row["id"],
        "name": row.get("name", ""),
        "comune": row.get("comune", ""),
        "provincia": row.get("provincia", ""),
        "lat_deg": row["lat_deg"],
        "lon_deg": row["lon_deg"],
        "status": "ok",
        "event_pga_g": nan,
        "sigma_ln_pga": nan,
        "sigma_source": "",
        "soil_class": row["soil_class"],
        "soil_factor": nan,
        "ag_equiv_g": nan,
        "fragility_median_g": median,
        "fragility_beta": beta,
        "median_is_bound": bound,
        "beta_total": nan,
        "p_overturning": nan,
        "p_overturning_bound": "",
        **note_columns(()),
    }
    if math.isnan(row["lat_deg"]) or math.isnan(row["lon_deg"]):
        return _noted({**out, "status": "no_coordinates"}, message("scenario.no_coordinates"))
    found = grid.at(row["lon_deg"], row["lat_deg"])
    if found is None:
        return _noted({**out, "status": "outside_grid"}, message("scenario.outside_grid"))
    pga, sigma = found
    said: list[Message] = []
    if not gm_uncertainty:
        sigma, said = 0.0, [message("scenario.sigma_known")]
    elif math.isnan(sigma):
        sigma, said = DEFAULT_SIGMA_LN_PGA, [message("scenario.sigma_default", sigma=sigma)]
    else:
        source = grid.sigma_source or "STDPGA of the grid"
    if said:
        source = said[0].render()
    out.update(event_pga_g=pga, sigma_ln_pga=sigma, sigma_source=source)
    if math.isnan(median):
        return _noted({**out, "status": "no_fragility"}, _no_fragility(row))
    if pga <= 0.0:
        out.update(
            ag_equiv_g=0.0,
            beta_total=math.hypot(beta, sigma) if math.isfinite(beta) else nan,
            p_overturning=0.0,
        )
        return _noted(out, message("scenario.no_shaking"))
    tr_slv = row["tr_slv_y"] if math.isfinite(row["tr_slv_y"]) else 475.0
    try:
        s = soil_factor(
            row["lon_deg"],
            row["lat_deg"],
            row["soil_class"],
            row.get("topography", "T1") or "T1",
            pga,
            tr_slv,
        )
    except HazardError as exc:  # e.g. a tower off the NTC 2018 grid (Sardinia)
        failed = message("scenario.no_site_hazard", error=str(exc))
        return _noted({**out, "status": "no_fragility"}, failed)
    out.update(soil_factor=s, ag_equiv_g=pga / s)
    if bound:
        return _bounded_probability(out, median, bound, pga / s, sigma)
    beta_total = math.hypot(beta, sigma)
    if beta_total > 0:
        p = float(ndtr(math.log(pga / s / median) / beta_total))
    else:  # a degenerate (beta = 0) fragility under a PGA taken as known: a step
        p = float(pga / s >= median)
    return _noted({**out, "beta_total": beta_total, "p_overturning": p}, *said)


def _noted(out: dict[str, Any], *said: Message) -> dict[str, Any]:
    """Return a scenario row with its note (``note``, ``note_codes``) said by ``said``."""
    return {**out, **note_columns(said)}


def _no_fragility(row: dict[str, Any]) -> Message:
    """Return why a tower has no fragility: its assessment's own note, as messages."""
    assessed = note_messages(row)
    if assessed is None:  # an assessment archive written before note codes
        if row.get("note"):
            return message("scenario.no_fragility_see_assessment")
        return message("scenario.not_assessed")
    if not assessed:
        return message("scenario.not_assessed")
    return message("scenario.no_fragility", notes=assessed)


def _bounded_probability(
    out: dict[str, Any],
    median: float,
    bound: str,
    ag: float,
    sigma: float,
) -> dict[str, Any]:
    """Return the row with the probability bound of a bound fragility, or ``no_fragility``."""
    informative = ag < median if bound == "lower" else ag > median
    words = {"lower": message("scenario.lower"), "upper": message("scenario.upper")}
    if not informative:
        relation = message("scenario.below" if ag < median else "scenario.at_or_above")
        why = message(
            "scenario.bound_uninformative",
            bound=words[bound],
            median_g=median,
            ag_g=ag,
            relation=relation,
        )
        return _noted({**out, "status": "no_fragility"}, why)
    beta_total = math.hypot(BOUND_BETA_MAX, sigma)
    p = float(ndtr(math.log(ag / median) / beta_total))
    side, relation = (
        ("upper", "scenario.at_most") if bound == "lower" else ("lower", "scenario.at_least")
    )
    note = message(
        "scenario.p_bound",
        relation=message(relation),
        p=p,
        bound=words[bound],
        median_g=median,
        ag_g=ag,
        beta=BOUND_BETA_MAX,
    )
    out.update(ag_equiv_g=ag, beta_total=beta_total, p_overturning=p, p_overturning_bound=side)
    return _noted(out, note)


def _scenario_class(row: Mapping[str, Any]) -> dict[str, str]:
    """Return the row's class (the band of P) and its bound when P is a bound that leaves it open.

    ``risk_class`` is one word of :data:`~rockscreen.pipeline.verdict.scales.SCENARIO_CLASS`;
    ``class_bound`` (:class:`~rockscreen.pipeline.verdict.scales.ClassBound`) is
    ``at_most`` for an upper bound of P that is not already in the lowest class,
    ``at_least`` for a lower bound not already in the highest, else ``""``.
    """
    side = Bound.parse(row.get("p_overturning_bound", ""))
    cls, bound = scenario_class_of(row["p_overturning"], side)
    return {"risk_class": cls, "class_bound": bound.value}


#: Ids named in a message before the rest are only counted.
SHOWN_IDS = 5


def _few(ids: Sequence[str]) -> str:
    """Return the first :data:`SHOWN_IDS` ids (printable, shortened) and a count of the rest."""
    shown = []
    for tower_id in ids[:SHOWN_IDS]:
        text = printable(tower_id)
        shown.append(repr(text if len(text) <= 40 else text[:37] + "..."))
    rest = len(ids) - len(shown)
    return ", ".join(shown) + (f" and {rest} more" if rest > 0 else "")


def scenario_rows(
    summary: Sequence[dict[str, Any]],
    grid: ShakeMapGrid,
    tower_ids: Sequence[str] | None = None,
    *,
    gm_uncertainty: bool = True,
) -> list[dict[str, Any]]:
    """Return the scenario rows of the towers of an assess summary (restricted to ``tower_ids``).

    ``gm_uncertainty`` as in :func:`tower_scenario`.

    Raises
    ------
    RiskError
        When a requested tower id is not in the summary.
    """
    rows = list(summary)
    if tower_ids:
        known = {r["id"] for r in rows}
        missing = [t for t in tower_ids if t not in known]
        if missing:
            raise RiskError(
                f"--towers: {_few(missing)} not in the assess archive (its towers: "
                f"{_few(sorted(known))})"
            )
        wanted = set(tower_ids)
        rows = [r for r in rows if r["id"] in wanted]
    out = [tower_scenario(r, grid, gm_uncertainty=gm_uncertainty) for r in rows]
    return [{**row, **_scenario_class(row)} for row in out]
