"""Messages of the screening risk (issue 31): judgement priors, bounds, limits, no risk."""

from __future__ import annotations

from rockscreen.pipeline.verdict.messages import MessageSpec, register

register(
    MessageSpec(
        "risk.judgement_prior",
        "the prior of {input} is a judgement, not a fit of data ({source})",
        "la distribuzione a priori di {input} è un giudizio, non un adattamento a dati ({source})",
    ),
    MessageSpec(
        "risk.source_masonry_uniform",
        "uniform over the seven historic types of Circolare 2019 Table C8.5.I, semi_solid_brick "
        "with cement mortar left out",
        "uniforme sui sette tipi storici della Tabella C8.5.I della Circolare 2019, esclusa "
        "semi_solid_brick con malta cementizia",
    ),
    MessageSpec(
        "risk.source_belfry_judgement",
        "judgement: docs/uncertainty.md, belfry priors",
        "giudizio: docs/uncertainty.md, distribuzioni a priori della cella campanaria",
    ),
    MessageSpec(
        "risk.source_belfry_presence",
        "judgement for an inventory of bell towers: docs/uncertainty.md, belfry priors",
        "giudizio per un inventario di campanili: docs/uncertainty.md, distribuzioni a priori "
        "della cella campanaria",
    ),
    MessageSpec(
        "risk.belfry_sampled",
        "the row has no belfry columns: a belfry is sampled from the priors (present with "
        "probability {presence:.2f}; its height, openings, bells' mass and height drawn), "
        "checked by its kinematic mechanism in every sample that has one; its rocking is not "
        "in the IDA, and the shaft and the whole tower do not carry its mass",
        "la riga non ha le colonne della cella campanaria: una cella è campionata dalle "
        "distribuzioni a priori (presente con probabilità {presence:.2f}; altezza, aperture, "
        "massa e quota delle campane estratte), verificata con il suo meccanismo cinematico "
        "in ogni campione che la ha; il suo ribaltamento non è nell'IDA, e il fusto e la torre "
        "intera non ne portano la massa",
    ),
    MessageSpec(
        "risk.belfry_in_gable",
        "the row has a bell gable, where its bells are checked: no belfry is sampled",
        "la riga ha una vela campanaria, dove sono verificate le sue campane: nessuna cella "
        "campanaria è campionata",
    ),
    MessageSpec(
        "risk.belfry_too_low",
        "the tower ({height:.1f} m) is too low for the belfry prior (its shortest belfry, "
        "{shortest:.2f} m, is below an inventory's {minimum:.1f} m): no belfry is sampled",
        "la torre ({height:.1f} m) è troppo bassa per la distribuzione a priori della cella "
        "campanaria (la cella più bassa, {shortest:.2f} m, è sotto i {minimum:.1f} m di un "
        "inventario): nessuna cella è campionata",
    ),
    MessageSpec(
        "risk.belfry_not_sampled",
        "the row has no belfry columns and the priors file samples none ([belfry] sampled = "
        "false): no belfry is in the risk",
        "la riga non ha le colonne della cella campanaria e il file delle distribuzioni a "
        "priori non ne campiona ([belfry] sampled = false): nessuna cella è nel rischio",
    ),
    MessageSpec(
        "risk.sampled_inputs",
        "sampled (epistemic inputs): {inputs}; not sampled: the rocking IDA's block, restitution "
        "and friction (the row's values, else Housner's restitution: at the ends of their "
        "ranges in the literature they moved the P50 of the 31 towers measured by at most "
        "0.01 % of its 90 % interval; docs/risk.md)",
        "campionati (dati epistemici): {inputs}; non campionati: il blocco, la restituzione e "
        "l'attrito dell'IDA del ribaltamento (i valori della riga, altrimenti la restituzione di "
        "Housner: agli estremi dei loro intervalli in letteratura hanno spostato la P50 delle 31 "
        "torri misurate al più dello 0,01 % del suo intervallo al 90 %; docs/risk.md)",
    ),
    MessageSpec(
        "risk.beta_judgement",
        "aleatory beta = {beta:.2f} by judgement: FEMA P-695 (2009) §7.3.1 record-to-record "
        "beta for a mechanism the IDA does not fit",
        "beta aleatoria = {beta:.2f} per giudizio: beta record-to-record di FEMA P-695 (2009) "
        "§7.3.1 per un meccanismo che l'IDA non stima",
    ),
    MessageSpec(
        "risk.beta_ida",
        "aleatory beta = {beta:.2f} from the IDA fit of {mechanism}, which governs",
        "beta aleatoria = {beta:.2f} dalla stima IDA di {mechanism}, che governa",
    ),
    MessageSpec(
        "risk.rocking_at_row",
        "{mechanism} taken at the row's inputs (IDA median {ag:.3f} g), the same in every "
        "sample: its capacity does not follow the sampled inputs",
        "{mechanism} preso con i dati della riga (mediana IDA {ag:.3f} g), uguale in ogni "
        "campione: la sua capacità non segue i dati campionati",
    ),
    MessageSpec(
        "risk.rocking_left_out",
        "{mechanism} not in the risk: {reason}",
        "{mechanism} escluso dal rischio: {reason}",
    ),
    MessageSpec(
        "risk.no_ida_fit",
        "the IDA gave no median",
        "l'IDA non ha dato una mediana",
    ),
    MessageSpec(
        "risk.no_ida_run",
        "the IDA was not run (the tower's record set was not made or not compliant)",
        "l'IDA non è stata eseguita (la terna di accelerogrammi del sito non è stata creata o "
        "non è conforme)",
    ),
    MessageSpec(
        "risk.bounded_samples",
        "{k} of {n} samples have a capacity that is a bound (holds at 2475 y or fails at 30 y): "
        "the statistics they can move are printed as bounds",
        "{k} campioni su {n} hanno una capacità che è un limite (regge a 2475 anni o cede a 30 "
        "anni): le statistiche che possono spostare sono indicate come limiti",
    ),
    MessageSpec(
        "risk.extrapolated_samples",
        "{k} of {n} samples have a capacity beyond the NTC 2018 table (the check holds at "
        "2475 y or fails at 30 y), continued with the spectral shape held at the table's end "
        "(docs/uncertainty.md): a value, not a bound; {share:.0f} % of the best estimate's "
        "lambda comes from the hazard curve extrapolated beyond the table",
        "{k} campioni su {n} hanno una capacità oltre la tabella delle NTC 2018 (la verifica "
        "regge a 2475 anni o cede a 30 anni), prolungata con la forma spettrale tenuta a "
        "quella dell'estremo della tabella (docs/uncertainty.md): un valore, non un limite; "
        "il {share:.0f} % della lambda della stima migliore proviene dalla curva di "
        "pericolosità estrapolata oltre la tabella",
    ),
    MessageSpec(
        "risk.no_location",
        "no screening risk: the tower has no site hazard ({reason})",
        "nessun rischio di screening: la torre non ha pericolosità di sito ({reason})",
    ),
    MessageSpec(
        "risk.no_geometry",
        "no screening risk: {missing} not given (needed: lat, lon, width_m, depth_m, height_m)",
        "nessun rischio di screening: {missing} non dato (servono: lat, lon, width_m, depth_m, "
        "height_m)",
    ),
    MessageSpec(
        "risk.failed",
        "no screening risk: {error}",
        "nessun rischio di screening: {error}",
    ),
    MessageSpec(
        "risk.not_computed",
        "screening risk not computed in this run",
        "rischio di screening non calcolato in questa esecuzione",
    ),
)
