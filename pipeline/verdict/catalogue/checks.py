"""Messages about a tower's checks (:mod:`rockscreen.pipeline.verdict.checks`).

Their labels and families, why one was not made, the marks of a printed class. Where
rocking and the code's checks disagree is :mod:`.disagreement`'s (``disagree.*``, with the
safety classes as the sentence names them).

The English texts are the ones the terminal, the CSV and the archives printed before the
typed verdict (``governing``, ``governing_kind``, ``checks_not_made``, ``checks_disagree``);
the Italian ones are the report's (``strings.json``, ``notes.py``).
"""

from __future__ import annotations

from rockscreen.pipeline.verdict.messages import MessageSpec, register

register(
    # the checks' labels (the ``governing`` column)
    MessageSpec("check.tower.rocking", "whole-tower rocking", "ribaltamento della torre intera"),
    MessageSpec("check.belfry.rocking", "belfry rocking", "ribaltamento della cella campanaria"),
    MessageSpec("check.gable.rocking", "gable rocking", "ribaltamento della vela campanaria"),
    MessageSpec("check.part.rocking", "{part} rocking", "ribaltamento della parte {part}"),
    # a check without its label's entry (``check.<id>``): its id
    MessageSpec("check.unlabelled", "{check}", "{check}"),
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
    # a check's details on the report's sheet (a check added as a module: its declared
    # details, each with its units)
    MessageSpec("check.detail", "{name} {value:.3g}{units}", "{name} {value:.3g}{units}"),
    MessageSpec("check.details", "{items}", "{items}"),
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
    # a registered code check (risk.checks.registry) without its result in the row
    MessageSpec(
        "not_made.code_check_columns",
        "{check} not made (no {columns} in the inventory)",
        "{check} non eseguita ({columns} assenti nell'inventario)",
    ),
    MessageSpec(
        "not_made.code_check_error",
        "{check} failed ({error})",
        "{check} non riuscita ({error})",
    ),
    MessageSpec(
        "not_made.code_check_result",
        "{check} not made (no result)",
        "{check} non eseguita (nessun risultato)",
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
)
