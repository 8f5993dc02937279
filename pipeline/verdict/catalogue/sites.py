"""Messages of a tower's site: its defaults, its knowledge level, a failed hazard or tower."""

from __future__ import annotations

from rockscreen.pipeline.verdict.messages import MessageSpec, register

register(
    MessageSpec(
        "knowledge.inventory",
        "knowledge level {level} (F_C = {fc:.2f} divides the SLV capacity) (inventory)",
        "livello di conoscenza {level} (F_C = {fc:.2f} divide la capacità allo SLV) (inventario)",
    ),
    MessageSpec(
        "knowledge.run",
        "knowledge level {level} (F_C = {fc:.2f} divides the SLV capacity) (--knowledge-level)",
        "livello di conoscenza {level} (F_C = {fc:.2f} divide la capacità allo SLV) "
        "(--knowledge-level)",
    ),
    MessageSpec(
        "knowledge.assumed",
        "knowledge level {level} (F_C = {fc:.2f} divides the SLV capacity) assumed: not in the "
        "inventory (--knowledge-level)",
        "livello di conoscenza {level} (F_C = {fc:.2f} divide la capacità allo SLV) ipotizzato: "
        "assente nell'inventario (--knowledge-level)",
    ),
    # ``defaults``: site.default messages, joined by ", "
    MessageSpec("site.assumed", "assumed {defaults:, }", "ipotizzati {defaults:, }"),
    MessageSpec("site.default", "{name}={value} (default)", "{name}={value} (predefinito)"),
    MessageSpec(
        "site.no_coordinates",
        "no coordinates: the site hazard is unknown, the tower is not assessed",
        "nessuna coordinata: la pericolosità del sito è ignota, la torre non è valutata",
    ),
    MessageSpec(
        # ``error``: the hazard stage's error (one line, in English like every error)
        "site.hazard_failed",
        "site hazard: {error}",
        "pericolosità del sito: {error}",
    ),
    MessageSpec(
        # ``error``: the exception's type and text (one line, in English like every error)
        "site.tower_error",
        "not assessed: an unexpected error in its computation ({error}); in /failures "
        "(rockscreen inspect)",
        "non valutata: errore imprevisto nel suo calcolo ({error}); in /failures "
        "(rockscreen inspect)",
    ),
    MessageSpec(
        # ``error``: why the site's record set failed (one line, in English like every error)
        "site.records_failed",
        "record set at lon={lon:g} lat={lat:g} TR={tr:g} y: {error}",
        "insieme di registrazioni a lon={lon:g} lat={lat:g} TR={tr:g} anni: {error}",
    ),
)
