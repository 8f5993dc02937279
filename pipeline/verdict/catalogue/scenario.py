"""Messages of an earthquake scenario's row (ShakeMap): no probability, sigma, bounds."""

from __future__ import annotations

from rockscreen.pipeline.verdict.messages import MessageSpec, register

register(
    MessageSpec("scenario.no_coordinates", "tower without coordinates", "torre senza coordinate"),
    MessageSpec(
        "scenario.outside_grid",
        "outside the ShakeMap grid (or its surrounding nodes are missing from a truncated grid): "
        "not estimated",
        "fuori dalla griglia ShakeMap (o i nodi circostanti mancano da una griglia troncata): "
        "non stimata",
    ),
    MessageSpec(
        # ``notes``: the assessment's own messages (its note_codes)
        "scenario.no_fragility",
        "no fragility: {notes}",
        "nessuna fragilità: {notes}",
    ),
    MessageSpec(
        "scenario.not_assessed", "no fragility: not assessed", "nessuna fragilità: non valutata"
    ),
    MessageSpec(
        "scenario.no_fragility_see_assessment",
        "no fragility (the assessment archive's note says why)",
        "nessuna fragilità (la nota dell'archivio della valutazione dice perché)",
    ),
    MessageSpec(
        "scenario.no_shaking",
        "ShakeMap PGA 0 at the tower: P = 0 (no shaking)",
        "PGA ShakeMap 0 alla torre: P = 0 (nessuno scuotimento)",
    ),
    MessageSpec(
        # ``error``: the hazard stage's error (one line, in English like every error)
        "scenario.no_site_hazard",
        "no site hazard for S: {error}",
        "nessuna pericolosità del sito per S: {error}",
    ),
    MessageSpec(
        "scenario.sigma_known",
        "none: event PGA taken as known (--no-gm-uncertainty)",
        "nessuna: PGA dell'evento considerata nota (--no-gm-uncertainty)",
    ),
    MessageSpec(
        "scenario.sigma_default",
        "default sigma_lnPGA = {sigma:.3f} (total sigma of ITA10 for PGA, Bindi et al. 2011: "
        "0.337 in log10): no STDPGA at the tower",
        "sigma_lnPGA predefinita = {sigma:.3f} (sigma totale di ITA10 per la PGA, Bindi et al. "
        "2011: 0,337 in log10): nessuna STDPGA alla torre",
    ),
    MessageSpec("scenario.lower", "lower", "inferiore"),
    MessageSpec("scenario.upper", "upper", "superiore"),
    MessageSpec("scenario.below", "below", "inferiore"),
    MessageSpec("scenario.at_or_above", "at or above", "pari o superiore"),
    MessageSpec("scenario.at_most", "at most", "al più"),
    MessageSpec("scenario.at_least", "at least", "almeno"),
    MessageSpec(
        # {bound}: scenario.lower/upper; {relation}: scenario.below/at_or_above
        "scenario.bound_uninformative",
        "fragility median is only a {bound} bound ({median_g:.3g} g); the event's ag_equiv "
        "{ag_g:.3g} g is {relation} it: no probability computed",
        "la mediana di fragilità è solo un limite {bound} ({median_g:.3g} g); l'ag_equiv "
        "dell'evento, {ag_g:.3g} g, è {relation}: nessuna probabilità calcolata",
    ),
    MessageSpec(
        # {relation}: scenario.at_most/at_least; {bound}: scenario.lower/upper
        "scenario.p_bound",
        "P(overturning) {relation} {p:.3g}: the collapse median is only a {bound} bound "
        "({median_g:.3g} g, ag_equiv {ag_g:.3g} g), beta taken as its largest plausible value "
        "{beta:g}",
        "P(ribaltamento) {relation} {p:.3g}: la mediana di collasso è solo un limite {bound} "
        "({median_g:.3g} g, ag_equiv {ag_g:.3g} g), beta assunta pari al suo massimo plausibile "
        "{beta:g}",
    ),
)
