"""The answer a reader needs first: one or two sentences per archive kind, and the class counts.

The page opens with them (issue 23: a regional civil-protection officer reads the first
screen and must know which towers to inspect):

- **run**: how many towers need an inspection (class ``collapse`` or ``high``) and which;
- **assess**: how many towers do not meet the code (``I_S < 1``) and which, with their I_S
  (written as a bound, with the words "upper bound" or "lower bound", where the archive
  marks one); how many of those that meet it do so on a lower bound only;
- **scenario**: the expected number of overturned towers (the sum of the towers'
  probabilities) and the towers with ``P >= 0.2`` (the lower limit of the ``high`` class);
- **sweep**: how many cases overturn the tower.

Towers that could not be screened or assessed are named after that. Everything is read from
the report model (:class:`~rockscreen.pipeline.report.html.model.ReportModel`), so the answer
cannot disagree with the table below it.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from rockscreen.pipeline.report.html.i18n import STRINGS, number, tr, trn
from rockscreen.pipeline.report.html.model import ReportModel, TowerCell
from rockscreen.pipeline.report.html.notes import translate_note
from rockscreen.pipeline.verdict.labels import ClassLabel, marks_of, not_made_reasons
from rockscreen.pipeline.verdict.scales import INCOMPLETE, ClassBound, Completeness

__all__ = [
    "INSPECT_CLASSES",
    "MAX_NAMED",
    "SCENARIO_HIGH_FROM",
    "answer_lines",
    "class_counts",
    "class_text",
]

#: Run classes that call for an inspection.
INSPECT_CLASSES = ("collapse", "high")
#: Assess classes of towers that do not meet the code (``I_S < 1``).
_BELOW_CODE = ("very_high", "high", "moderate")
#: Scenario probability from which a tower is named in the answer (the ``high`` class) [-].
SCENARIO_HIGH_FROM = 0.2
#: Towers named in one sentence; the others are counted ("and 4 more").
MAX_NAMED = 12


def _class(tower: Mapping[str, object]) -> str:
    """Return the class a tower is counted under (its label's typed marks)."""
    return marks_of(tower.get("risk_class", "")).counted


def class_text(label: object, lang: str) -> str:
    """Return a risk-class label in ``lang``, its marks translated too.

    The marks are read from the label's types (:class:`~rockscreen.pipeline.verdict.labels.
    ClassLabel`), never from its text: the non-compliant basis, a scenario class read on a
    bound of P, the checks not made beside a ``meets`` (``rocking only`` when they leave
    only rigid overturning), rendered from their messages in ``lang`` (only an archive written
    before ``checks_not_made_codes`` goes through the older archives' adapter,
    :func:`~rockscreen.pipeline.report.html.notes.translate_note`).

    Parameters
    ----------
    label : str or ClassLabel
        A class word (``"high"``) or a label of
        :func:`rockscreen.pipeline.verdict.labels.class_label`.
    lang : str
        ``"en"`` or ``"it"``.
    """
    marks = marks_of(label)
    name = marks.counted
    key = f"class_{name}"
    text = tr(key, lang) if key in STRINGS else name
    if not marks.basis_compliant:
        text += f" ({tr('class_mark_noncompliant', lang)})"
    if marks.bound is not ClassBound.NONE:  # a scenario class from a bound of P
        text += f" ({tr('n_rel_' + marks.bound.value, lang)})"
    not_made = label.not_made if isinstance(label, ClassLabel) else ""
    if not_made and marks.cls == "meets" and isinstance(label, ClassLabel):
        # the reasons' messages in the page's language; text only in an older archive
        details = label.reasons_text(lang)
        if marks.completeness is Completeness.ROCKING_ONLY:  # which checks were not made
            if details is None:
                details = translate_note(not_made_reasons(label), lang)
            text += f" ({tr('class_mark_rocking_only', lang)}: {details})"
        else:  # other checks not made (a meets with its belfry unchecked, ...)
            text += f" ({translate_note(not_made, lang) if details is None else details})"
    return text


def class_counts(model: ReportModel) -> list[tuple[str, int]]:
    """Return (class, number of towers) for every class of the model, worst first.

    Marked classes (``"meets (basis not code-compliant)"``) count under their class; a class
    the model does not list is appended. Classes without towers are kept (count 0).
    """
    counts: dict[str, int] = {name: 0 for name in model.classes}
    for tower in model.towers:
        name = _class(tower)
        counts[name] = counts.get(name, 0) + 1
    return list(counts.items())


def _named(items: Sequence[str], lang: str) -> str:
    """Join tower ids (with their annotation) and count those beyond :data:`MAX_NAMED`."""
    shown = ", ".join(items[:MAX_NAMED])
    if len(items) > MAX_NAMED:
        shown += " " + tr("ans_more", lang, n=len(items) - MAX_NAMED)
    return shown


def _bound_words(bound: str, lang: str) -> str:
    return {">": tr("ans_lower_bound", lang), "<": tr("ans_upper_bound", lang)}.get(bound, "")


def _value(tower: Mapping[str, TowerCell], key: str, lang: str, digits: int = 2) -> tuple[str, str]:
    """Return the value text of a row's cell (with its bound sign) and the bound."""
    bound = (tower.get("bounds") or {}).get(key, "")
    return number(tower.get(key), lang, digits, bound=bound), bound


def _index_key(tower: Mapping[str, TowerCell]) -> str:
    """Return the column of the I_S a tower's class comes from.

    The governing check's (``governing_safety_index``) when the archive has it and the
    governing check is not whole-tower rocking, else whole-tower rocking's ``safety_index``.
    """
    if tower.get("governing_safety_index") is None or tower.get("governing_check") == (
        "tower.rocking"
    ):
        return "safety_index"
    return "governing_safety_index"


def _run(model: ReportModel, lang: str) -> list[str]:
    towers, m = model.towers, len(model.towers)
    inspect = [t for t in towers if _class(t) in INSPECT_CLASSES]
    lines = []
    if inspect:
        inspect.sort(key=lambda t: INSPECT_CLASSES.index(_class(t)))
        items = [f"{t['id']} ({class_text(t['risk_class'], lang)})" for t in inspect]
        lines.append(trn("ans_run_inspect", len(inspect), lang, m=m, ids=_named(items, lang)))
    else:
        lines.append(trn("ans_run_none", m, lang))
    unknown = [t["id"] for t in towers if _class(t) == "unknown"]
    if unknown:
        lines.append(trn("ans_run_unknown", len(unknown), lang, ids=_named(unknown, lang)))
    return lines


def _assess(model: ReportModel, lang: str) -> list[str]:
    towers, m = model.towers, len(model.towers)
    below = [t for t in towers if _class(t) in _BELOW_CODE]
    meets = [t for t in towers if _class(t) == "meets"]
    incomplete = [t["id"] for t in towers if _class(t) == INCOMPLETE]
    undefined = [t["id"] for t in towers if _class(t) == "undefined"]
    lines = []
    if below:
        items = []
        for t in below:
            text, bound = _value(t, _index_key(t), lang)
            words = _bound_words(bound, lang)
            items.append(f"{t['id']} (I_S {text}{', ' + words if words else ''})")
        lines.append(trn("ans_assess_below", len(below), lang, m=m, ids=_named(items, lang)))
    if meets and len(meets) == m:
        lines.append(trn("ans_assess_meets", len(meets), lang))
    elif meets and not below:
        lines.append(trn("ans_assess_meets_some", len(meets), lang, m=m))
    lower = [t for t in meets if (t.get("bounds") or {}).get(_index_key(t)) == ">"]
    by_rocking = [t["id"] for t in lower if _index_key(t) == "safety_index"]
    by_check = [t["id"] for t in lower if _index_key(t) != "safety_index"]
    if by_rocking:  # the IDA's search ended with no record at the level
        lines.append(trn("ans_assess_lower", len(by_rocking), lang, ids=_named(by_rocking, lang)))
    if by_check:  # a code check (or a part's rocking) still holds at 2475 y
        lines.append(trn("ans_assess_lower_check", len(by_check), lang, ids=_named(by_check, lang)))
    if incomplete:  # a meets on rigid overturning alone is no meets (issue 22)
        lines.append(
            trn("ans_assess_incomplete", len(incomplete), lang, m=m, ids=_named(incomplete, lang))
        )
    if undefined:
        lines.append(trn("ans_undefined", len(undefined), lang, ids=_named(undefined, lang)))
    noncompliant = [t for t in towers if not marks_of(t["risk_class"]).basis_compliant]
    if noncompliant:
        lines.append(trn("ans_noncompliant", len(noncompliant), lang))
    return lines


def _scenario(model: ReportModel, lang: str) -> list[str]:
    towers = model.towers
    with_p = [t for t in towers if isinstance(t.get("p_overturning"), (int, float))]
    lines = []
    if with_p:
        expected = sum(float(t["p_overturning"]) for t in with_p)
        lines.append(trn("ans_scenario_expected", len(with_p), lang, e=number(expected, lang, 2)))
        high = sorted(
            (t for t in with_p if t["p_overturning"] >= SCENARIO_HIGH_FROM),
            key=lambda t: -t["p_overturning"],
        )
        limit = number(SCENARIO_HIGH_FROM, lang)
        if high:
            items = [f"{t['id']} (P = {number(t['p_overturning'], lang, 2)})" for t in high]
            lines.append(
                trn("ans_scenario_high", len(high), lang, p=limit, ids=_named(items, lang))
            )
        else:
            lines.append(tr("ans_scenario_high_none", lang, p=limit))
    without = [t["id"] for t in towers if t not in with_p]
    if without:
        lines.append(trn("ans_scenario_without", len(without), lang, ids=_named(without, lang)))
    return lines


def _sweep(model: ReportModel, lang: str) -> list[str]:
    n = sum(1 for t in model.towers if _class(t) == "collapse")
    return [trn("ans_sweep", n, lang, total=len(model.towers))]


def answer_lines(model: ReportModel, lang: str = "en") -> list[str]:
    """Return the sentences that answer the reader first (module docstring), in ``lang``.

    Parameters
    ----------
    model : ReportModel
        The report model of any archive kind.
    lang : str
        ``"en"`` or ``"it"``.

    Returns
    -------
    list of str
        One to four sentences (raw text: escape them before putting them into HTML); none
        for a model without towers.
    """
    if not model.towers:
        return [tr("ans_empty", lang)]
    build = {"run": _run, "assess": _assess, "scenario": _scenario, "sweep": _sweep}
    return build.get(model.kind, _run)(model, lang)
