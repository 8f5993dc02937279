"""Messages of the fragility fits, the LV1 indices read from a fit and the rate of overturning."""

from __future__ import annotations

from rockscreen.pipeline.verdict.messages import MessageSpec, register

register(
    # what the records did, inside the censored fit's messages ({event})
    MessageSpec("fit.event_overturned", "overturned the tower", "ha ribaltato la torre"),
    MessageSpec("fit.event_slv", "reached the SLV level", "ha raggiunto il livello SLV"),
    MessageSpec("fit.none", "no record {event}", "nessun accelerogramma {event}"),
    MessageSpec("fit.one", "one record {event}", "un solo accelerogramma {event}"),
    MessageSpec(
        "fit.censored_all",
        "{k} of {n} records stand at {ag:.4g} g, the smallest censoring intensity: the median is "
        "above it (lower bound)",
        "{k} accelerogrammi su {n} si fermano a {ag:.4g} g, la minima intensità di censura: la "
        "mediana è superiore (limite inferiore)",
    ),
    MessageSpec(
        "fit.one_upper",
        "one record {event}, at {ag:.4g} g, and at least half of the {n} records have overturned "
        "there: the median is below it (upper bound)",
        "un solo accelerogramma {event}, a {ag:.4g} g, e almeno metà degli {n} accelerogrammi si "
        "sono ribaltati lì: la mediana è inferiore (limite superiore)",
    ),
    MessageSpec("fit.beta_undetermined", "beta undetermined", "beta non determinata"),
    MessageSpec(
        "fit.degenerate",
        "the {k} overturning records share one intensity: the likelihood grows without limit as "
        "beta -> 0 (degenerate fit, beta = 0, no standard errors)",
        "i {k} accelerogrammi che ribaltano hanno la stessa intensità: la verosimiglianza cresce "
        "senza limite per beta -> 0 (stima degenere, beta = 0, nessun errore standard)",
    ),
    MessageSpec(
        # ``reason``: the optimiser's own message (SciPy's, in English)
        "fit.not_converged",
        "the optimiser did not converge ({reason})",
        "l'ottimizzatore non è andato a convergenza ({reason})",
    ),
    MessageSpec(
        "fit.single",
        "one of the {n} records {event}: median and beta rest on it and on the {k} censoring "
        "intensities (wide standard errors)",
        "uno degli {n} accelerogrammi {event}: mediana e beta poggiano su di esso e sulle {k} "
        "intensità di censura (errori standard ampi)",
    ),
    MessageSpec(
        "fit.singular",
        "the information matrix is singular: no standard errors",
        "la matrice d'informazione è singolare: nessun errore standard",
    ),
    MessageSpec(
        "fit.median_extrapolated",
        "median extrapolated above every intensity of the data",
        "mediana estrapolata oltre ogni intensità dei dati",
    ),
    # the fits of a tower's row, with their messages
    MessageSpec("fit.collapse", "collapse fit: {notes}", "stima al collasso: {notes}"),
    MessageSpec(
        "fit.slv",
        "SLV fit (theta_max/alpha >= {ratio:g}): {notes}",
        "stima allo SLV (theta_max/alpha >= {ratio:g}): {notes}",
    ),
    # {part}: fit.part_<model> (a part model of the engine's registry: one entry each)
    MessageSpec("fit.part", "{part} fragility: {notes}", "fragilità {part}: {notes}"),
    MessageSpec("fit.part_belfry", "belfry", "della cella campanaria"),
    MessageSpec("fit.part_gable", "gable", "della vela campanaria"),
    # a part model without an entry of its own (a third part model): its registry name
    MessageSpec("fit.part_other", "{part}", "della parte {part}"),
    # the stripe fit (binomial)
    MessageSpec(
        "stripes.none_overturned",
        "no record overturned the tower up to ag = {ag:.4g} g: the median is above it (lower "
        "bound)",
        "nessun accelerogramma ha ribaltato la torre fino ad ag = {ag:.4g} g: la mediana è "
        "superiore (limite inferiore)",
    ),
    MessageSpec(
        "stripes.all_overturned",
        "every record overturned the tower from ag = {ag:.4g} g: the median is below it (upper "
        "bound)",
        "ogni accelerogramma ha ribaltato la torre da ag = {ag:.4g} g: la mediana è inferiore "
        "(limite superiore)",
    ),
    MessageSpec(
        "stripes.beta_min",
        "beta at its lower limit {beta:g}: the counts jump from none to all between two stripes "
        "(no finite maximum-likelihood beta)",
        "beta al suo limite inferiore {beta:g}: i conteggi passano da nessuno a tutti tra due "
        "strisce (nessuna beta di massima verosimiglianza finita)",
    ),
    MessageSpec(
        "stripes.beta_max",
        "beta at its upper limit {beta:g}: the counts barely rise with ag",
        "beta al suo limite superiore {beta:g}: i conteggi crescono appena con ag",
    ),
    MessageSpec(
        "stripes.median_extrapolated",
        "median extrapolated above the largest stripe",
        "mediana estrapolata oltre la striscia più alta",
    ),
    MessageSpec(
        "stripes.vertical_limit",
        "every record of every stripe reaches the vertical limit of the rigid-block model "
        "(scaled vertical <= -g): no stripe fit",
        "ogni accelerogramma di ogni striscia raggiunge il limite verticale del modello a blocco "
        "rigido (verticale scalata <= -g): nessuna stima a strisce",
    ),
    MessageSpec(
        "assess.no_ida",
        "no IDA intensities: no fragility",
        "nessuna intensità IDA: nessuna fragilità",
    ),
    # the LV1 indices read from a fit (I_S, f_a)
    MessageSpec(
        "indices.from_slv",
        "I_S and f_a from the SLV fragility: {notes}",
        "I_S e f_a dalla fragilità allo SLV: {notes}",
    ),
    MessageSpec(
        "indices.lower_bounds",
        "lower bounds: the fragility median is a lower bound (no record reached the limit state "
        "up to its censoring intensity), so a_C, T_R,C, I_S and f_a are at least these values",
        "limiti inferiori: la mediana di fragilità è un limite inferiore (nessun accelerogramma "
        "ha raggiunto lo stato limite fino alla sua intensità di censura), quindi a_C, T_R,C, "
        "I_S e f_a valgono almeno questi valori",
    ),
    MessageSpec(
        "indices.upper_bounds",
        "upper bounds: the fragility median is an upper bound, so a_C, T_R,C, I_S and f_a are at "
        "most these values",
        "limiti superiori: la mediana di fragilità è un limite superiore, quindi a_C, T_R,C, I_S "
        "e f_a valgono al più questi valori",
    ),
    MessageSpec(
        "indices.tr_extrapolated",
        "T_R,C extrapolated outside the tabulated {low:g}-{high:g} y along the end power law of "
        "the site's hazard curve",
        "T_R,C estrapolato fuori dall'intervallo tabellato {low:g}-{high:g} anni lungo la legge "
        "di potenza terminale della curva di pericolosità del sito",
    ),
    # the annual rate of overturning
    MessageSpec(
        "rate.extrapolated",
        "{share:.0f} % of lambda_C comes from the hazard curve extrapolated beyond TR = "
        "{tr_high:.0f} y ({over:.0f} %) or below TR = {tr_low:.0f} y ({under:.0f} %), where the "
        "code defines no hazard: lambda_C and P50 rest mostly on that extrapolation",
        "il {share:.0f} % di lambda_C proviene dalla curva di pericolosità estrapolata oltre "
        "TR = {tr_high:.0f} anni ({over:.0f} %) o sotto TR = {tr_low:.0f} anni ({under:.0f} %), "
        "dove la norma non definisce la pericolosità: lambda_C e P50 poggiano soprattutto su "
        "quell'estrapolazione",
    ),
    MessageSpec(
        "rate.undefined",
        "annual rate of overturning undefined: the collapse fragility median is only a bound",
        "frequenza annua di ribaltamento non definita: la mediana di fragilità al collasso è "
        "solo un limite",
    ),
)
