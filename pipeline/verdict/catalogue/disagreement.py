"""Messages of a note's disagreement clause: rocking against the code's checks.

:func:`rockscreen.pipeline.verdict.rules.disagreement` returns them; the row's
``checks_disagree`` column and the note's clause are both rendered from them.
"""

from __future__ import annotations

from rockscreen.pipeline.verdict.messages import MessageSpec, register

_KINEMATIC_WHY = (
    "the kinematic checks ignore rocking's size effect: a large block outlasts accelerations "
    "above alpha0 g too brief to overturn it (Makris & Konstantinidis 2003), while the IDA "
    "sees the records' pulses, their vertical motion and (belfry) the shaft's amplification"
)
_LV1_WHY = (
    "the LV1 model checks the shaft's masonry sections in flexure under their own weight, "
    "which rigid rocking takes as infinitely strong: a tall shaft cracks at its critical "
    "section long before it could overturn as one block"
)

register(
    # the safety classes as the sentence names them (English: the class's identifier)
    MessageSpec("safety_class.meets", "meets", "soddisfa la norma"),
    MessageSpec("safety_class.moderate", "moderate", "moderato"),
    MessageSpec("safety_class.high", "high", "alto"),
    MessageSpec("safety_class.very_high", "very_high", "molto alto"),
    MessageSpec(
        # {rocking_class}, {other_class}: safety_class.*
        "disagree.kinematic",
        "rocking (I_S {rocking:.2f}, {rocking_class}) and the kinematic checks (I_S {other:.2f}, "
        "{other_class}) disagree: " + _KINEMATIC_WHY,
        "ribaltamento dinamico (I_S {rocking:.2f}, {rocking_class}) e verifiche cinematiche "
        "(I_S {other:.2f}, {other_class}) non concordano: le verifiche cinematiche ignorano "
        "l'effetto scala del ribaltamento, per cui un blocco grande resiste ad accelerazioni "
        "oltre alpha0 g troppo brevi per ribaltarlo (Makris & Konstantinidis 2003), mentre "
        "l'analisi dinamica incrementale vede gli impulsi degli accelerogrammi, la componente "
        "verticale e (cella campanaria) l'amplificazione del fusto",
    ),
    MessageSpec(
        "disagree.lv1",
        "rocking (I_S {rocking:.2f}, {rocking_class}) and the LV1 model (I_S {other:.2f}, "
        "{other_class}) disagree: " + _LV1_WHY,
        "il ribaltamento (I_S {rocking:.2f}, {rocking_class}) e il modello LV1 (I_S {other:.2f}, "
        "{other_class}) divergono: il modello LV1 verifica a flessione le sezioni in muratura "
        "del fusto sotto il peso proprio, che il ribaltamento rigido considera infinitamente "
        "resistenti: un fusto alto si fessura nella sezione critica molto prima di poter "
        "ribaltare come un solo blocco",
    ),
)
