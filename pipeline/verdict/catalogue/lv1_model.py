"""Messages of the LV1 tower model (DPCM 9/2/2011 §5.4.4) and of a capacity on the site."""

from __future__ import annotations

from rockscreen.pipeline.verdict.messages import MessageSpec, register

register(
    MessageSpec(
        # {source}: lv1model.t1_*; {strength}: lv1model.fm_*; {shaft}: lv1model.shaft_*
        "lv1model.model",
        "LV1 tower model (DPCM 9/2/2011 §5.4.4, formulas to be verified): T1 = {t1:.2f} s "
        "({source}), q = {q:g}, gamma_M = 2, {masonry}, {strength}, {shaft}, critical section "
        "at {z:.1f} m",
        "modello LV1 per le torri (DPCM 9/2/2011 §5.4.4, formule da verificare): T1 = {t1:.2f} s "
        "({source}), q = {q:g}, gamma_M = 2, muratura {masonry}, {strength}, {shaft}, sezione "
        "critica a {z:.1f} m",
    ),
    MessageSpec("lv1model.t1_measured", "measured", "misurato"),
    MessageSpec(
        "lv1model.t1_assumed",
        "0.0187 H of the whole tower, assumed",
        "0,0187 H dell'intera torre, ipotizzato",
    ),
    MessageSpec(
        "lv1model.fm_measured",
        "f_m = {fm_mpa:g} MPa measured (masonry_strength_mpa, {level})",
        "f_m = {fm_mpa:g} MPa misurata (masonry_strength_mpa, {level})",
    ),
    MessageSpec(
        "lv1model.fm_table_min",
        "f_m = {fm_mpa:g} MPa (Table C8.5.I, {level}: the range's lower end)",
        "f_m = {fm_mpa:g} MPa (Tabella C8.5.I, {level}: estremo inferiore dell'intervallo)",
    ),
    MessageSpec(
        "lv1model.fm_table_mean",
        "f_m = {fm_mpa:g} MPa (Table C8.5.I, {level}: the range's mean)",
        "f_m = {fm_mpa:g} MPa (Tabella C8.5.I, {level}: media dell'intervallo)",
    ),
    MessageSpec(
        "lv1model.shaft_prismatic",
        "prismatic shaft, walls {wall_m:.2f} m",
        "fusto prismatico, pareti di {wall_m:.2f} m",
    ),
    MessageSpec(
        "lv1model.shaft_tapered",
        "shaft walls tapering from {base_m:.2f} m at the base to {top_m:.2f} m at the top "
        "({n} segments)",
        "pareti del fusto rastremate da {base_m:.2f} m alla base a {top_m:.2f} m in sommità "
        "({n} tratti)",
    ),
    MessageSpec(
        # {period_source}: lv1model.tk_*
        "lv1model.church_demand",
        "LV1 demand: the Circolare 2019 floor spectrum S_eZ(T1, z) of the church beneath "
        "(§C7.2.3, [C7.2.5]-[C7.2.10]): church H = {h_m:g} m, T_k = {tk:.2f} s ({period_source}), "
        "elastic (xi_k = 5 %), at the tower's springing z = {z_m:g} m (base_height_m), read at "
        "the tower's T1 = {t1:.2f} s, never below the ground's Se(T1)",
        "domanda LV1: lo spettro di piano della Circolare 2019 S_eZ(T1, z) della chiesa "
        "sottostante (§C7.2.3, [C7.2.5]-[C7.2.10]): chiesa H = {h_m:g} m, T_k = {tk:.2f} s "
        "({period_source}), in campo elastico (xi_k = 5 %), all'imposta della torre z = {z_m:g} m "
        "(base_height_m), letto al T1 della torre = {t1:.2f} s, mai inferiore a Se(T1) del suolo",
    ),
    MessageSpec("lv1model.tk_given", "building_period_s", "building_period_s"),
    MessageSpec(
        "lv1model.tk_assumed",
        "0.0187 H of the church, assumed: no building_period_s",
        "0,0187 H della chiesa, ipotizzato: nessun building_period_s",
    ),
    MessageSpec(
        "lv1model.crushed",
        "LV1: the shaft's own weight alone crushes its section at {z_m:.1f} m by the code's "
        "design strength (sigma_0 / (0.85 f_d) = {ratio:.2f}, f_d = f_m / (gamma_M F_C), "
        "gamma_M = 2 of Circolare 2019 §C8.7.1, F_C = {fc:g}): the section has no flexural "
        "capacity left and the check fails at every return period. A tower that stands carries "
        "its weight, so its masonry is stronger than f_d: a measured f_m (knowledge level LC3, "
        "masonry_strength_mpa) would change this verdict",
        "LV1: il solo peso proprio del fusto schiaccia la sua sezione a {z_m:.1f} m con la "
        "resistenza di progetto della norma (sigma_0 / (0,85 f_d) = {ratio:.2f}, f_d = f_m / "
        "(gamma_M F_C), gamma_M = 2 della Circolare 2019 §C8.7.1, F_C = {fc:g}): la sezione non "
        "ha più capacità flessionale e la verifica non è soddisfatta per alcun periodo di "
        "ritorno. Una torre che sta in piedi porta il proprio peso, quindi la sua muratura è più "
        "resistente di f_d: una f_m misurata (livello di conoscenza LC3, masonry_strength_mpa) "
        "cambierebbe questo giudizio",
    ),
    MessageSpec(
        "lv1model.compression",
        "LV1: the shaft's own weight takes {share} % of its section's design strength at "
        "{z_m:.1f} m (sigma_0 / (0.85 f_d) = {ratio:.2f}, f_d = f_m / (gamma_M F_C), gamma_M = 2 "
        "of Circolare 2019 §C8.7.1, F_C = {fc:g}): the capacity is cut to {rest} % of the "
        "uncrushed block's, so the masonry's strength data (type, knowledge level) drive this "
        "result",
        "LV1: il peso proprio del fusto impegna il {share} % della resistenza di progetto della "
        "sua sezione a {z_m:.1f} m (sigma_0 / (0,85 f_d) = {ratio:.2f}, f_d = f_m / "
        "(gamma_M F_C), gamma_M = 2 della Circolare 2019 §C8.7.1, F_C = {fc:g}): la capacità si "
        "riduce al {rest} % di quella del blocco non schiacciato, quindi sono i dati di "
        "resistenza della muratura (tipo, livello di conoscenza) a determinare questo risultato",
    ),
    # a check's capacity on the tabulated hazard (checks/site_capacity.py)
    MessageSpec("lv1model.capacity", "LV1: {notes}", "LV1: {notes}"),
    MessageSpec(
        "capacity.holds_longest",
        "the check holds at {tr:g} y, the longest tabulated return period: T_R,C, a_C, I_S and "
        "f_a are lower bounds",
        "la verifica è soddisfatta a {tr:g} anni, il periodo di ritorno tabulato più lungo: "
        "T_R,C, a_C, I_S e f_a sono limiti inferiori",
    ),
    MessageSpec(
        "capacity.fails_shortest",
        "the check fails at {tr:g} y, the shortest tabulated return period: T_R,C, a_C, I_S and "
        "f_a are upper bounds",
        "la verifica non è soddisfatta già a {tr:g} anni, il periodo di ritorno tabulato più "
        "breve: T_R,C, a_C, I_S e f_a sono limiti superiori",
    ),
    MessageSpec(
        "capacity.slv_clamped",
        "T_R,SLV={tr:.0f} y is outside the table: clamped",
        "T_R,SLV={tr:.0f} anni è fuori dalla tabella: limitato ai suoi estremi",
    ),
)
