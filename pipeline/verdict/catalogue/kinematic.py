"""Messages of the kinematic checks (Circolare 2019 §C8.7.1) and what their blocks assume."""

from __future__ import annotations

from rockscreen.pipeline.verdict.messages import MessageSpec, register

register(
    # which block an assumption is of ({part} of kinematic.of)
    MessageSpec("kinematic.whole_tower", "whole-tower kinematic", "cinematismo dell'intera torre"),
    MessageSpec("kinematic.belfry", "belfry kinematic", "cinematismo della cella campanaria"),
    MessageSpec("kinematic.gable", "bell gable", "vela campanaria"),
    MessageSpec("kinematic.of", "{part}: {note}", "{part}: {note}"),
    MessageSpec(
        "kinematic.tower_period",
        "tower period 0.0187 H = {period:.2f} s assumed (no shaft_period_s)",
        "periodo della torre 0,0187 H = {period:.2f} s ipotizzato (nessun shaft_period_s)",
    ),
    MessageSpec(
        "kinematic.church_period",
        "church period 0.0187 H = {period:.2f} s assumed (no building_period_s)",
        "periodo della chiesa 0,0187 H = {period:.2f} s ipotizzato (nessun building_period_s)",
    ),
    MessageSpec("kinematic.church", "church", "chiesa"),
    MessageSpec("kinematic.structure_beneath", "structure beneath", "struttura sottostante"),
    MessageSpec(
        "kinematic.support_period",
        "{beneath} period 0.0187 H = {period:.2f} s assumed",
        "periodo di {beneath} 0,0187 H = {period:.2f} s ipotizzato",
    ),
    MessageSpec(
        "kinematic.masonry_assumed",
        "{masonry} masonry assumed (no masonry_type)",
        "muratura {masonry} ipotizzata (nessun masonry_type)",
    ),
    MessageSpec(
        "kinematic.solid_prism",
        "mass of a solid prism of {weight_kn_m3:g} kN/m3 ({masonry}, Table C8.5.I): no "
        "tower_mass_kg",
        "massa di un prisma pieno di {weight_kn_m3:g} kN/m3 ({masonry}, Tabella C8.5.I): nessun "
        "tower_mass_kg",
    ),
    MessageSpec(
        "kinematic.belfry_t0",
        "T0 = {t0:.3f} s, a solid cantilever of the piers' width ([C8.7.1.7]; openings would "
        "lengthen it)",
        "T0 = {t0:.3f} s, una mensola piena della larghezza dei piedritti ([C8.7.1.7]; le "
        "aperture lo allungherebbero)",
    ),
    MessageSpec(
        "kinematic.belfry_church_ignored",
        "the church beneath the tower not counted in the belfry's demand",
        "la chiesa sotto la torre non è considerata nella domanda della cella campanaria",
    ),
    MessageSpec(
        "kinematic.gable_t0",
        "T0 = {t0:.3f} s ([C8.7.1.7], cracked modulus)",
        "T0 = {t0:.3f} s ([C8.7.1.7], modulo fessurato)",
    ),
    MessageSpec(
        "kinematic.checks",
        "kinematic checks (Circolare 2019 §C8.7.1.2.1: non-linear governs, linear with q = 2 "
        "beside): rigid blocks, no tensile strength, linearised capacity curve",
        "verifiche cinematiche (Circolare 2019 §C8.7.1.2.1: governa la non lineare, la lineare "
        "con q = 2 a fianco): blocchi rigidi, nessuna resistenza a trazione, curva di capacità "
        "linearizzata",
    ),
    MessageSpec(
        # ``error``: why (one line, in English like every error)
        "kinematic.not_made",
        "kinematic checks not made: {error}",
        "verifiche cinematiche non eseguite: {error}",
    ),
    # the bell gable's rocking block (engine/models/gable.py)
    MessageSpec(
        "gable.block_no_axis",
        "bell gable rocking: on its thickness {thickness:.2f} m in every direction (no "
        "gable_axis in the inventory: the safe side, which overstates its response in its plane)",
        "ribaltamento della vela campanaria: sul suo spessore {thickness:.2f} m in ogni "
        "direzione (nessun gable_axis nell'inventario: dalla parte della sicurezza, che ne "
        "sovrastima la risposta nel suo piano)",
    ),
    MessageSpec(
        "gable.block_axis",
        "bell gable rocking: on its thickness {thickness:.2f} m along {axis} (gable_axis, out of "
        "its plane), on its piers' width {width:.2f} m along {across} (in its plane, assumed a "
        "frame of piers: gable_width_m x (1 - gable_opening_ratio))",
        "ribaltamento della vela campanaria: sul suo spessore {thickness:.2f} m lungo {axis} "
        "(gable_axis, fuori dal suo piano), sulla larghezza dei suoi piedritti {width:.2f} m "
        "lungo {across} (nel suo piano, assunta come telaio di piedritti: gable_width_m x "
        "(1 - gable_opening_ratio))",
    ),
)
