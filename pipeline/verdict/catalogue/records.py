"""Messages of a record set's compliance with NTC 2018 (§3.2.3.6 spectrum, §7.3.5 count)."""

from __future__ import annotations

from rockscreen.pipeline.verdict.messages import MessageSpec, register

register(
    # one set's problems (records.too_few, records.mean_off, records.capped): the {detail}
    # of basis.noncompliant
    MessageSpec("records.set_problems", "TR={tr:g} y: {problems}", "TR={tr:g} anni: {problems}"),
    # a tower whose record sets fail the code and that was not assessed (its row's note; the
    # set and the fix are in /failures)
    MessageSpec(
        "records.not_assessed",
        "not assessed: its record sets do not meet the code ({detail}); the sets and the fix "
        "are in /failures (rockscreen inspect)",
        "non valutata: i suoi gruppi di accelerogrammi non rispettano la norma ({detail}); i "
        "gruppi e la correzione sono in /failures (rockscreen inspect)",
    ),
    MessageSpec(
        "records.too_few",
        "{n} records ({required} required, NTC 2018 §7.3.5)",
        "{n} accelerogrammi ({required} richiesti, NTC 2018 §7.3.5)",
    ),
    MessageSpec(
        "records.mean_off",
        "mean/target {ratio_min:.{min_digits}f}-{ratio_max:.{max_digits}f} over "
        "{t_from_s:g}-{t_to_s:g} s (allowed {low:.2f}-{high:.2f}, NTC 2018 §3.2.3.6)",
        "media/obiettivo {ratio_min:.{min_digits}f}-{ratio_max:.{max_digits}f} su "
        "{t_from_s:g}-{t_to_s:g} s (ammessi {low:.2f}-{high:.2f}, NTC 2018 §3.2.3.6)",
    ),
    MessageSpec(
        "records.capped",
        "{capped} of {n} scale factors at the limits {low:g}-{high:g} (records too weak or too "
        "strong for the target)",
        "{capped} fattori di scala su {n} ai limiti {low:g}-{high:g} (accelerogrammi troppo "
        "deboli o troppo forti per l'obiettivo)",
    ),
)
