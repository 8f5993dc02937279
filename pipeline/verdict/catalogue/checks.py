"""Messages about a tower's checks (:mod:`rockscreen.pipeline.verdict.checks`).

Their labels and families, why one was not made, where rocking and the code's checks
disagree.

The English texts are the ones the terminal, the CSV and the archives printed before the
typed verdict (``governing``, ``governing_kind``, ``checks_not_made``, ``checks_disagree``);
the Italian ones are the report's (``strings.json``, ``notes.py``).
"""

from __future__ import annotations

from rockscreen.pipeline.verdict.messages import MessageSpec, register

#: Why the kinematic checks and the rocking dynamics can disagree (docs/code_checks.md §5).
_SIZE_EFFECT_EN = (
    "the kinematic checks ignore rocking's size effect: a large block outlasts accelerations "
    "above alpha0 g too brief to overturn it (Makris & Konstantinidis 2003), while the IDA "
    "sees the records' pulses, their vertical motion and (belfry) the shaft's amplification"
)
_SIZE_EFFECT_IT = (
    "le verifiche cinematiche ignorano l'effetto scala del ribaltamento, per cui un blocco "
    "grande resiste ad accelerazioni oltre alpha0 g troppo brevi per ribaltarlo (Makris & "
    "Konstantinidis 2003), mentre l'analisi dinamica incrementale vede gli impulsi degli "
    "accelerogrammi, la componente verticale e (cella campanaria) l'amplificazione del fusto"
)
#: Why the LV1 model and the rocking dynamics can disagree (docs/code_checks.md §5).
_LV1_EN = (
    "the LV1 model checks the shaft's masonry sections in flexure under their own weight, "
    "which rigid rocking takes as infinitely strong: a tall shaft cracks at its critical "
    "section long before it could overturn as one block"
)
_LV1_IT = (
    "il modello LV1 verifica a flessione le sezioni in muratura del fusto sotto il peso "
    "proprio, che il ribaltamento rigido considera infinitamente resistenti: un fusto alto si "
    "fessura nella sezione critica molto prima di poter ribaltare come un solo blocco"
)

register(
    # the checks' labels (the ``governing`` column)
    MessageSpec("check.tower.rocking", "whole-tower rocking", "ribaltamento della torre intera"),
    MessageSpec("check.belfry.rocking", "belfry rocking", "ribaltamento della cella campanaria"),
    MessageSpec("check.gable.rocking", "gable rocking", "ribaltamento della vela campanaria"),
    MessageSpec("check.part.rocking", "{part} rocking", "ribaltamento della parte {part}"),
    MessageSpec(
        "check.tower.kinematic_nonlinear",
        "whole-tower kinematic (non-linear)",
        "cinematica non lineare: torre intera",
    ),
    MessageSpec(
        "check.belfry.kinematic_nonlinear",
        "belfry kinematic (non-linear)",
        "cinematica non lineare: cella campanaria",
    ),
    MessageSpec(
        "check.gable.kinematic_nonlinear",
        "bell gable kinematic (non-linear)",
        "cinematica non lineare: vela campanaria",
    ),
    MessageSpec("check.lv1", "shaft flexure (LV1)", "flessione del fusto (LV1)"),
    MessageSpec(
        "check.not_shown_to_govern",
        "{label} (a lower bound: not shown to govern)",
        "{label} (un limite inferiore: non è dimostrato che governi)",
    ),
    # the checks' families (the ``governing_kind`` column)
    MessageSpec("family.shaft_flexure", "shaft flexure", "flessione del fusto"),
    MessageSpec("family.tower_rocking", "tower rocking", "ribaltamento della torre"),
    MessageSpec("family.part_rocking", "{part} rocking", "ribaltamento della parte {part}"),
    MessageSpec("family.kinematic", "kinematic", "cinematica"),
    MessageSpec("family.gable", "gable", "vela campanaria"),
    # why a check that can fail earlier was not made (the ``checks_not_made`` column)
    MessageSpec(
        "not_made.belfry",
        "belfry not checked (no belfry columns in the inventory)",
        "cella campanaria non verificata (nessuna colonna della cella nell'inventario)",
    ),
    MessageSpec(
        "not_made.lv1_column",
        "LV1 not made (no {column} in the inventory)",
        "LV1 non eseguita ({column} assente nell'inventario)",
    ),
    MessageSpec(
        "not_made.lv1_columns",
        "LV1 not made (no {a} and {b} in the inventory)",
        "LV1 non eseguita ({a} e {b} assenti nell'inventario)",
    ),
    MessageSpec(
        "not_made.lv1_measured_strength",
        "LV1 not made ({level} rests on a measured f_m: no {column} in the inventory)",
        "LV1 non eseguita ({level} richiede una f_m misurata: {column} assente nell'inventario)",
    ),
    MessageSpec("not_made.lv1_error", "LV1 not made: {error}", "LV1 non eseguita: {error}"),
    MessageSpec("completeness.rocking_only", "rocking only", "solo ribaltamento rigido"),
    # the marks a printed class carries (:mod:`rockscreen.pipeline.verdict.labels`)
    MessageSpec(
        "class.mark.noncompliant", "basis not code-compliant", "base non conforme alla norma"
    ),
    MessageSpec("class.bound.at_most", "at most", "al più"),
    MessageSpec("class.bound.at_least", "at least", "almeno"),
    # where rocking and the code's checks disagree (the ``checks_disagree`` column)
    MessageSpec(
        "disagree.kinematic",
        "rocking (I_S {a:.2f}, {ca}) and the kinematic checks (I_S {b:.2f}, {cb}) disagree: "
        + _SIZE_EFFECT_EN,
        "ribaltamento dinamico (I_S {a:.2f}, {ca}) e verifiche cinematiche (I_S {b:.2f}, {cb}) "
        "non concordano: " + _SIZE_EFFECT_IT,
    ),
    MessageSpec(
        "disagree.lv1",
        "rocking (I_S {a:.2f}, {ca}) and the LV1 model (I_S {b:.2f}, {cb}) disagree: " + _LV1_EN,
        "il ribaltamento (I_S {a:.2f}, {ca}) e il modello LV1 (I_S {b:.2f}, {cb}) divergono: "
        + _LV1_IT,
    ),
)
