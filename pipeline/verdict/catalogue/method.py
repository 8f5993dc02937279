"""Sentences of the report's "Method, references and limits" section, per archive.

The HTML report builds that section from what an assess or scenario archive holds (its
attributes, the columns and tables written): which models ran, how the fragility was
fitted, which parts were modelled, which code checks were made, whether the screening
risk was computed (``rockscreen.pipeline.report.html.adapters.risk_method``). Each
sentence is one entry here, so that a page in Italian holds no English clause.
"""

from __future__ import annotations

from rockscreen.pipeline.verdict.messages import MessageSpec, register

register(
    # headings of the section's paragraphs
    MessageSpec("method.h_hazard", "Hazard and records.", "Pericolosità e accelerogrammi."),
    MessageSpec("method.h_rocking", "Rocking.", "Ribaltamento rigido."),
    MessageSpec("method.h_fragility", "Fragility.", "Fragilità."),
    MessageSpec("method.h_parts", "Parts of the tower.", "Parti della torre."),
    MessageSpec("method.h_checks", "The code's checks.", "Le verifiche di norma."),
    MessageSpec("method.h_risk", "The screening risk.", "Il rischio di screening."),
    MessageSpec("method.h_scenario", "Scenario.", "Scenario."),
    MessageSpec("method.h_limits", "Limits.", "Limiti."),
    MessageSpec("method.h_references", "References.", "Riferimenti."),
    # hazard and records
    MessageSpec(
        "method.hazard",
        "The site hazard is the code hazard (NTC 2018 §3.2, Allegato A/B) at each tower's site, "
        "at the return periods {periods} y.",
        "La pericolosità di sito è quella di norma (NTC 2018 §3.2, Allegati A/B) nel sito di "
        "ogni torre, ai periodi di ritorno {periods} anni.",
    ),
    MessageSpec(
        "method.suite_stochastic",
        "Records: the embedded stochastic suite (Rezaeian & Der Kiureghian 2010 records with "
        "velocity pulses, selected and scaled to the site's spectrum, never matched; seed "
        "{seed}), {n} per return period.",
        "Accelerogrammi: la raccolta stocastica interna (accelerogrammi di Rezaeian & Der "
        "Kiureghian 2010 con impulsi di velocità, selezionati e scalati sullo spettro del sito, "
        "mai modificati; seme {seed}), {n} per periodo di ritorno.",
    ),
    MessageSpec(
        "method.suite_matched",
        "Records: the embedded suite of spectrum-matched synthetic records (seed {seed}), {n} "
        "per return period.",
        "Accelerogrammi: la raccolta interna di accelerogrammi sintetici spettro-compatibili "
        "(seme {seed}), {n} per periodo di ritorno.",
    ),
    MessageSpec(
        "method.suite_file",
        "Records: the user's suite {source}, {n} per return period.",
        "Accelerogrammi: la raccolta dell'utente {source}, {n} per periodo di ritorno.",
    ),
    MessageSpec(
        "method.basis_compliant",
        "Every record set meets NTC 2018 §3.2.3.6 and §7.3.5.",
        "Ogni insieme di accelerogrammi rispetta NTC 2018 §3.2.3.6 e §7.3.5.",
    ),
    MessageSpec(
        "method.basis_noncompliant",
        "Not every record set meets NTC 2018 §3.2.3.6 and §7.3.5: the towers were assessed with "
        "--allow-noncompliant and their verdicts are marked so.",
        "Non tutti gli insiemi di accelerogrammi rispettano NTC 2018 §3.2.3.6 e §7.3.5: le torri "
        "sono state valutate con --allow-noncompliant e i loro esiti sono marcati.",
    ),
    MessageSpec(
        "method.components",
        "A record's x component acts along the tower's width, its y component along the plan "
        "depth (the records carry no orientation).",
        "La componente x di un accelerogramma agisce lungo la larghezza della torre, la "
        "componente y lungo la profondità in pianta (gli accelerogrammi non hanno orientamento).",
    ),
    # rocking
    MessageSpec(
        "method.rigid_block",
        "Each block is a rigid block rocking on its base (Housner 1963): it stays at rest until "
        "the base acceleration exceeds g·tan α (α = atan(b/h), the slenderness), then rotates "
        "about a base corner; at each impact its angular velocity is multiplied by the "
        "restitution η (by default 1 − 1.5 sin²α). Overturning is decided with the energy "
        "barrier in free motion, not when θ first reaches α (Zhang & Makris 2001).",
        "Ogni blocco è un blocco rigido che oscilla sulla base (Housner 1963): resta fermo "
        "finché l'accelerazione alla base non supera g·tan α (α = atan(b/h), la snellezza), poi "
        "ruota attorno a uno spigolo di base; a ogni urto la velocità angolare è moltiplicata "
        "per il coefficiente di restituzione η (per default 1 − 1,5 sin²α). Il ribaltamento è "
        "deciso con la barriera energetica nel moto libero, non quando θ raggiunge α per la "
        "prima volta (Zhang & Makris 2001).",
    ),
    MessageSpec(
        "method.models",
        "Models of the whole tower solved for every record and component: {models}.",
        "Modelli della torre intera risolti per ogni accelerogramma e componente: {models}.",
    ),
    # fragility
    MessageSpec(
        "method.ida",
        "The fragility comes from an incremental dynamic analysis (IDA): each record of the "
        "site's set at the tower's T_R,SLV is scaled up by a factor {ratio:g} per step and "
        "bisected to {tolerance:.0%} until it overturns the tower, up to {cap_g:g} g of ag on "
        "rock; the SLV level is θ/α ≥ {slv:g}.",
        "La fragilità deriva da un'analisi dinamica incrementale (IDA): ogni accelerogramma "
        "dell'insieme del sito al T_R,SLV della torre è scalato di un fattore {ratio:g} a ogni "
        "passo e bisecato con tolleranza {tolerance:.0%} finché ribalta la torre, fino a "
        "{cap_g:g} g di ag su roccia; il livello SLV è θ/α ≥ {slv:g}.",
    ),
    MessageSpec(
        "method.censored_fit",
        "A lognormal curve (median, dispersion β) is fitted to the records' overturning "
        "intensities by maximum likelihood; a record that did not overturn the tower up to the "
        "cap enters as censored (the tower holds at least that intensity). Towers whose "
        "collapse median is only a bound: {k} of {n}.",
        "Una curva lognormale (mediana, dispersione β) è adattata alle intensità di "
        "ribaltamento degli accelerogrammi con la massima verosimiglianza; un accelerogramma "
        "che non ha ribaltato la torre fino al limite entra come censurato (la torre regge "
        "almeno quell'intensità). Torri la cui mediana di collasso è solo un limite: {k} su "
        "{n}.",
    ),
    MessageSpec(
        "method.bootstrap",
        "Its 90 % intervals come from {resamples} bootstrap resamples of the records.",
        "I suoi intervalli al 90 % derivano da {resamples} ricampionamenti bootstrap degli "
        "accelerogrammi.",
    ),
    MessageSpec(
        "method.stripes_check",
        "The multiple-stripe fit of the overturning counts at the {k} return periods is kept "
        "beside as a check.",
        "L'adattamento a strisce multiple dei conteggi di ribaltamento ai {k} periodi di "
        "ritorno è riportato accanto come controllo.",
    ),
    MessageSpec(
        "method.stripes_fit",
        "The fragility comes from multiple-stripe analysis: the records are scaled to the "
        "{k} return periods' intensities, the records that overturn the tower are counted at "
        "each and a lognormal curve (median, dispersion β) is fitted to the counts by maximum "
        "likelihood.",
        "La fragilità deriva da un'analisi a strisce multiple: gli accelerogrammi sono scalati "
        "alle intensità dei {k} periodi di ritorno, a ognuna si contano quelli che ribaltano la "
        "torre e si adatta ai conteggi una curva lognormale (mediana, dispersione β) con la "
        "massima verosimiglianza.",
    ),
    MessageSpec(
        "method.hazard_integral",
        "Integrating the fragility over the site's hazard curve gives the annual rate of "
        "overturning λ_C and the probability in 50 years; as in the MiC 2011 Guidelines, the "
        "capacity acceleration a_C (the SLV median over F_C), its return period, the safety "
        "index I_S and the acceleration factor f_a are given beside.",
        "Integrando la fragilità sulla curva di pericolosità del sito si ottengono la "
        "frequenza annua di ribaltamento λ_C e la probabilità in 50 anni; come nelle Linee "
        "Guida MiC 2011, accanto si riportano l'accelerazione di capacità a_C (la mediana SLV "
        "divisa per F_C), il suo periodo di ritorno, l'indice di sicurezza I_S e il fattore di "
        "accelerazione f_a.",
    ),
    # parts of the tower
    MessageSpec(
        "method.part_modelled",
        "{check}: its own rigid block on its support, with its own IDA (towers: {k} of {n}).",
        "{check}: un proprio blocco rigido sul suo appoggio, con una propria IDA (torri: {k} "
        "su {n}).",
    ),
    MessageSpec(
        "method.part_not_modelled",
        "{check}: not modelled (no tower of the inventory gives its data).",
        "{check}: non modellato (nessuna torre dell'inventario ne fornisce i dati).",
    ),
    # the code's checks
    MessageSpec(
        "method.check_made",
        "{check}: made (towers: {k} of {n}).",
        "{check}: eseguita (torri: {k} su {n}).",
    ),
    MessageSpec(
        "method.check_none",
        "{check}: made for no tower (it needs {columns} in the inventory).",
        "{check}: non eseguita per alcuna torre (richiede {columns} nell'inventario).",
    ),
    MessageSpec(
        "method.check_none_stored",
        "{check}: made for no tower (each tower's sheet says why).",
        "{check}: non eseguita per alcuna torre (la scheda di ogni torre dice perché).",
    ),
    MessageSpec(
        "method.knowledge",
        "Knowledge levels (confidence factor F_C, Circolare 2019 §C8.5.4): {levels}.",
        "Livelli di conoscenza (fattore di confidenza F_C, Circolare 2019 §C8.5.4): {levels}.",
    ),
    MessageSpec(
        "method.code_verdict",
        "The code's verdict (the class) is the I_S of the check of lowest capacity among those "
        "made (the governing check), at the code's strengths with F_C and γ_M; a tower with "
        "rocking checked only is incomplete.",
        "L'esito di norma (la classe) è l'I_S della verifica di capacità minima tra quelle "
        "eseguite (la verifica governante), con le resistenze di norma, F_C e γ_M; una torre "
        "verificata solo al ribaltamento rigido è incompleta.",
    ),
    # the screening risk
    MessageSpec(
        "method.risk_computed",
        "A second question, apart from the code's verdict: how likely the tower is to "
        "collapse, and how sure that is. Best estimates (mean strengths, no partial or "
        "confidence factor) over {samples} epistemic samples of what the inventory does not "
        "say (priors: {priors}; seed {seed}); each tower's P(collapse) in 50 years is the "
        "median over the samples with its 90 % interval, and the towers are ranked by it.",
        "Una seconda domanda, distinta dall'esito di norma: quanto è probabile che la torre "
        "crolli, e con quale certezza. Stime migliori (resistenze medie, nessun fattore "
        "parziale o di confidenza) su {samples} campioni epistemici di ciò che l'inventario "
        "non dice (distribuzioni a priori: {priors}; seme {seed}); la P(crollo) in 50 anni di "
        "ogni torre è la mediana sui campioni con il suo intervallo al 90 %, e le torri sono "
        "ordinate secondo essa.",
    ),
    MessageSpec(
        "method.priors_default",
        "the defaults of docs/uncertainty.md",
        "quelle predefinite di docs/uncertainty.md",
    ),
    MessageSpec("method.priors_file", "the file {source}", "il file {source}"),
    MessageSpec(
        "method.risk_methods",
        "Computed: {methods:; }.",
        "Calcolato: {methods:; }.",
    ),
    MessageSpec(
        "method.risk.shaft_lv1_mean",
        "the shaft in compression and flexure with the LV1 mechanics at mean strength",
        "il fusto a pressoflessione con la meccanica LV1 alla resistenza media",
    ),
    MessageSpec(
        "method.risk.kinematic_mean",
        "the kinematic mechanisms at mean values",
        "i meccanismi cinematici ai valori medi",
    ),
    MessageSpec(
        "method.risk.rocking_ida",
        "whole-tower and part rocking from the records' IDA intensities",
        "il ribaltamento della torre e delle parti dalle intensità IDA degli accelerogrammi",
    ),
    MessageSpec(
        "method.risk.hazard_integral",
        "the fragility integrated over the site's hazard curve",
        "la fragilità integrata sulla curva di pericolosità del sito",
    ),
    MessageSpec(
        "method.risk.belfry_sampled",
        "a belfry sampled from its priors (presence, height and openings, bells) where the "
        "inventory gives none: its kinematic checks, not its rocking",
        "una cella campanaria campionata dalle sue distribuzioni a priori (presenza, altezza e "
        "aperture, campane) dove l'inventario non la descrive: i suoi meccanismi cinematici, "
        "non il suo ribaltamento",
    ),
    MessageSpec("method.risk.other", "{method}", "{method}"),
    MessageSpec(
        "method.risk_weakest",
        "Under each sample the tower's capacity is that of its weakest mechanism; the "
        "fragility combines the record-to-record (aleatory) and the input (epistemic) "
        "uncertainty, kept apart: the interval is over the epistemic samples.",
        "Per ogni campione la capacità della torre è quella del suo meccanismo più debole; la "
        "fragilità combina l'incertezza tra accelerogrammi (aleatoria) e quella dei dati "
        "(epistemica), tenute distinte: l'intervallo è sui campioni epistemici.",
    ),
    MessageSpec(
        "method.risk_beta",
        "Aleatory dispersion β: from the IDA fit (towers: {fit}), a judgement (FEMA P-695; "
        "towers: {judgement}).",
        "Dispersione aleatoria β: dall'adattamento IDA (torri: {fit}), un giudizio (FEMA "
        "P-695; torri: {judgement}).",
    ),
    MessageSpec(
        "method.risk_judgement",
        'Priors that are a judgement, not a fit of data (labelled "judgement" wherever '
        "shown): {inputs}.",
        "Distribuzioni a priori che sono un giudizio e non un adattamento a dati (indicate "
        '"giudizio" ovunque compaiano): {inputs}.',
    ),
    MessageSpec(
        "method.risk_survey",
        "For each tower, the input whose exact value would narrow its interval most (a "
        "first-order Sobol' index over the epistemic inputs) is named with the expected "
        "narrowing; the region's list names the measurements that change the top {top_n} "
        "most.",
        "Per ogni torre si indica il dato il cui valore esatto restringerebbe di più il suo "
        "intervallo (un indice di Sobol' del primo ordine sui dati epistemici), con il "
        "restringimento atteso; l'elenco della regione indica le misure che cambiano di più "
        "le prime {top_n}.",
    ),
    MessageSpec(
        "method.risk_not_computed",
        "The screening risk (a best estimate of the probability of collapse with its 90 % "
        "interval, the rank, what to survey first) was not computed for this archive: only "
        "the code's verdict is shown.",
        "Il rischio di screening (una stima migliore della probabilità di crollo con il suo "
        "intervallo al 90 %, la posizione in graduatoria, cosa rilevare per primo) non è "
        "stato calcolato per questo archivio: è riportato solo l'esito di norma.",
    ),
    # scenario
    MessageSpec(
        "method.scenario_shakemap",
        "The shaking at each tower is the PGA of the ShakeMap {source} (event {event}); the "
        "towers' fragilities are those of the assessment {fragility}, converted to the "
        "tower's soil.",
        "Lo scuotimento a ogni torre è la PGA della ShakeMap {source} (evento {event}); le "
        "fragilità delle torri sono quelle della valutazione {fragility}, riportate al suolo "
        "della torre.",
    ),
    MessageSpec(
        "method.scenario_sigma",
        "The ShakeMap's uncertainty of ln PGA is combined with the fragility's β (β_total).",
        "L'incertezza di ln PGA della ShakeMap è combinata con la β della fragilità (β_total).",
    ),
    MessageSpec(
        "method.scenario_sigma_off",
        "The event's PGA is taken as known (no ground-motion uncertainty).",
        "La PGA dell'evento è considerata nota (nessuna incertezza del moto del suolo).",
    ),
    # limits
    MessageSpec(
        "method.limits_rigid",
        "The tower moves as one rigid body, or as the parts modelled above: cracking, "
        "flexibility, soil–structure interaction and out-of-plane interaction with the church "
        "are not modelled. A scaled vertical acceleration reaching −g ends the validity of the "
        "model and is counted as failure.",
        "La torre si muove come un unico corpo rigido, o come le parti modellate sopra: "
        "fessurazione, deformabilità, interazione terreno-struttura e interazione fuori piano "
        "con la chiesa non sono modellate. Un'accelerazione verticale scalata che raggiunge −g "
        "pone fine alla validità del modello ed è considerata crisi.",
    ),
    MessageSpec(
        "method.limits_records_only",
        "The probabilities include the record-to-record variability only, not the uncertainty "
        "of the geometry, the masonry, the restitution or the hazard model.",
        "Le probabilità includono solo la variabilità tra accelerogrammi, non l'incertezza "
        "della geometria, della muratura, della restituzione o del modello di pericolosità.",
    ),
    MessageSpec(
        "method.limits_with_risk",
        "The code's probabilities (λ_C, P(50 y)) include the record-to-record variability "
        "only; the screening risk adds the uncertainty of the inputs that have priors, not "
        "that of the hazard model.",
        "Le probabilità di norma (λ_C, P(50 anni)) includono solo la variabilità tra "
        "accelerogrammi; il rischio di screening aggiunge l'incertezza dei dati che hanno una "
        "distribuzione a priori, non quella del modello di pericolosità.",
    ),
    MessageSpec(
        "method.limits_rank",
        "The results rank towers for closer study; they do not replace the assessment "
        "required by the code.",
        "I risultati ordinano le torri per approfondimenti; non sostituiscono la valutazione "
        "richiesta dalla norma.",
    ),
    MessageSpec(
        "method.references",
        "G. W. Housner (1963), BSSA 53(2):403–417. · J. Zhang, N. Makris (2001), J. Eng. Mech. "
        "127(5):473–483. · N. Makris, D. Konstantinidis (2003), Earthq. Eng. Struct. Dyn. "
        "32:265–289. · R. Di Gennaro, M. Guadagnuolo, M. Monaco (2023), Buildings 13:762. · "
        "D'Angela et al. (2026), Procedia Structural Integrity 78:1617–1624. · Ministero delle "
        "Infrastrutture e dei Trasporti (2018), NTC 2018, and Circolare 2019. · Ministero per "
        "i Beni e le Attività Culturali (2011), Guidelines for the seismic risk of the cultural "
        "heritage.",
        "G. W. Housner (1963), BSSA 53(2):403–417. · J. Zhang, N. Makris (2001), J. Eng. Mech. "
        "127(5):473–483. · N. Makris, D. Konstantinidis (2003), Earthq. Eng. Struct. Dyn. "
        "32:265–289. · R. Di Gennaro, M. Guadagnuolo, M. Monaco (2023), Buildings 13:762. · "
        "D'Angela et al. (2026), Procedia Structural Integrity 78:1617–1624. · Ministero delle "
        "Infrastrutture e dei Trasporti (2018), NTC 2018, e Circolare 2019. · Ministero per i "
        "Beni e le Attività Culturali (2011), Linee Guida per la valutazione e riduzione del "
        "rischio sismico del patrimonio culturale.",
    ),
    MessageSpec(
        "method.references_risk",
        "A. Montabert et al. (2023), TURRIS, Buildings. · FEMA P-695 (2009), Quantification "
        "of building seismic performance factors. · I. M. Sobol' (2001), Math. Comput. Simul. "
        "55:271–280.",
        "A. Montabert et al. (2023), TURRIS, Buildings. · FEMA P-695 (2009), Quantification "
        "of building seismic performance factors. · I. M. Sobol' (2001), Math. Comput. Simul. "
        "55:271–280.",
    ),
)
