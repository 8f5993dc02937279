"""Messages of a record-based campaign's row (``run``): the safety factor, the pairing."""

from __future__ import annotations

from rockscreen.pipeline.verdict.messages import MessageSpec, register

register(
    MessageSpec(
        "run.no_case_solved",
        "no case could be solved (see the failures)",
        "nessun caso risolto (vedi gli errori)",
    ),
    MessageSpec(
        # ``flag``: the record's quality flag as its file stores it (records/quality.py)
        "run.record_flagged",
        "record {record} flagged: {flag}",
        "registrazione {record} segnalata: {flag}",
    ),
    MessageSpec(
        "run.sf_vertical_limit",
        "safety factor >= {sf:.2f}: the search stopped where the scaled vertical acceleration "
        "reaches -g, the rigid-block model's validity limit, not at overturning",
        "fattore di sicurezza >= {sf:.2f}: la ricerca si è fermata dove l'accelerazione "
        "verticale scalata raggiunge -g, limite di validità del modello a blocco rigido, non al "
        "ribaltamento",
    ),
    MessageSpec(
        "run.sf_cap",
        "no overturning up to the search cap {sf:.2f}",
        "nessun ribaltamento fino al limite della ricerca {sf:.2f}",
    ),
    MessageSpec(
        "run.sf_not_monotone",
        "the governing record scaled by {sf:.2f} overturns the tower although the record itself "
        "does not: rocking is not monotone in the amplitude",
        "la registrazione governante scalata per {sf:.2f} ribalta la torre benché la "
        "registrazione stessa non la ribalti: il rocking non è monotono nell'ampiezza",
    ),
    MessageSpec(
        "run.every_station_tower_unlocated",
        "paired with every station: the tower has no coordinates",
        "abbinata a tutte le stazioni: la torre non ha coordinate",
    ),
    MessageSpec(
        "run.every_station_stations_unlocated",
        "paired with every station: no station has coordinates",
        "abbinata a tutte le stazioni: nessuna stazione ha coordinate",
    ),
)
