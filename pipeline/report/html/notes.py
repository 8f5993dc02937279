"""The archives' notes in the page's language.

A tower's note is stored twice in its archive's summary row: ``note``, English clauses joined
by ``"; "`` (what a CSV and a terminal show), and ``note_codes``, the same clauses as messages
(codes and parameters, :mod:`rockscreen.pipeline.verdict.messages`). :func:`note_text` renders
the note in a language from ``note_codes`` and the message catalogue: no clause is parsed, and
a code this rockscreen's catalogue does not know is refused (:class:`ReportError`), never shown
as an English clause on an Italian page.

**Adapter of older archives.** An archive written before notes were stored as codes has no
``note_codes`` column: its note is English text only. For those, and only those,
:func:`translate_note` splits the note into its clauses, writes every clause it recognises
(:data:`PATTERNS`, the ``n_*`` keys of ``assets/strings.json``) in the page's language with its
numbers in that language's notation, and leaves any other clause as it is (in English). New
archives never reach it; it is kept so that the archives written before stay readable
(``docs/report.md``). The failure notes of a ``run`` sheet (``kind: reason``) are text too
and go through it.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping

from rockscreen.pipeline.errors import ReportError
from rockscreen.pipeline.report.html.i18n import DECIMAL, STRINGS, tr
from rockscreen.pipeline.verdict.messages import loads, render_all

__all__ = ["PATTERNS", "note_text", "stored_codes", "translate_note"]


def stored_codes(row: Mapping[str, object]) -> str | None:
    """Return a summary row's ``note_codes`` as text, or None when the archive has none."""
    codes = row.get("note_codes")
    if codes is None or (isinstance(codes, float) and math.isnan(codes)):
        return None
    return codes.decode("utf-8") if isinstance(codes, bytes) else str(codes)


def note_text(text: str, codes: str | bytes | float | None, lang: str) -> str:
    """Return a stored note in ``lang``: from its codes when stored, else its English text.

    Parameters
    ----------
    text : str
        The row's ``note`` (English).
    codes : str, bytes, float or None
        The row's ``note_codes`` (:func:`rockscreen.pipeline.verdict.messages.dumps`); None
        (or NaN) for an archive written before it: the note then goes through the adapter of
        older archives (:func:`translate_note`).
    lang : str
        ``"en"`` or ``"it"``.

    Returns
    -------
    str
        The note (raw text).

    Raises
    ------
    ReportError
        For stored codes that are not this rockscreen's catalogue's (a newer archive, or a
        damaged one): a note is never shown in another language than the page's.
    """
    if codes is None or (isinstance(codes, float) and math.isnan(codes)):
        return translate_note(str(text or ""), lang)
    try:
        messages = loads(codes)
    except ValueError as exc:
        raise ReportError(
            f"a tower's note_codes: {exc} (a newer rockscreen wrote this archive; report it "
            "with that version)"
        ) from None
    return render_all(messages, lang)


_NUM = r"[-+]?\d+(?:\.\d+)?(?:e[-+]?\d+)?"
#: The head of the LV1 model's clause (period, q, masonry, f_m and its source ``sub``).
_LV1_MODEL = (
    r"LV1 tower model \(DPCM 9/2/2011 §5\.4\.4, formulas to be verified\): T1 = "
    rf"(?P<t1>{_NUM}) s \((?P<src>measured|0\.0187 H of the whole tower, assumed)\), "
    rf"q = (?P<q>{_NUM}), gamma_M = 2, (?P<kind>\w+), f_m = (?P<fm>{_NUM}) MPa (?P<sub>.+?)"
)
#: (compiled clause pattern, translation key): the key's template takes the named groups.
PATTERNS: list[tuple[re.Pattern[str], str]] = [
    (
        re.compile(
            rf"safety factor >= (?P<sf>{_NUM}): the search stopped where the scaled vertical "
            r"acceleration reaches -g, the rigid-block model's validity limit, not at overturning"
        ),
        "n_sf_vertical",
    ),
    (re.compile(rf"no overturning up to the search cap (?P<sf>{_NUM})"), "n_sf_cap"),
    (re.compile(r"safety factor: no overturning up to the cap"), "n_sf_cap_old"),
    (
        re.compile(
            rf"the governing record scaled by (?P<sf>{_NUM}) overturns the tower although the "
            r"record itself does not: rocking is not monotone in the amplitude"
        ),
        "n_sf_not_monotone",
    ),
    (re.compile(r"paired with every station: (?P<rest>.*)"), "n_every_station"),
    (
        re.compile(
            rf"no record overturned the tower up to ag = (?P<ag>{_NUM}) g: the median is above "
            r"it \(lower bound\)"
        ),
        "n_no_overturn",
    ),
    (re.compile(r"beta undetermined"), "n_beta_undetermined"),
    (
        re.compile(
            r"lower bounds: the tower never overturned up to the largest stripe, so a_C, T_R,C, "
            r"I_S and f_a are at least these values"
        ),
        "n_lower_bounds",
    ),
    (
        re.compile(r"annual rate of overturning undefined: the fragility median is only a bound"),
        "n_rate_undefined",
    ),
    (re.compile(r"assumed (?P<rest>.*\(default\).*)"), "n_assumed"),
    (
        re.compile(r"basis not code-compliant \(run with --allow-noncompliant\): (?P<rest>.*)"),
        "n_noncompliant",
    ),
    (
        re.compile(r"no coordinates: the site hazard is unknown, the tower is not assessed"),
        "n_no_coordinates_assess",
    ),
    (re.compile(r"tower without coordinates"), "n_no_coordinates"),
    (
        re.compile(
            rf"TR=(?P<tr>{_NUM}) y: (?P<n>\d+) records "
            r"\((?P<required>\d+) required, (?P<ref>[^)]*)\)"
        ),
        "n_records_short",
    ),
    (
        re.compile(
            rf"fragility median is only a lower bound \((?P<median>{_NUM}) g\); the event's "
            rf"ag_equiv (?P<ag>{_NUM}) g is (?P<where>below it|at or above it): no probability "
            r"computed"
        ),
        "n_scenario_bound",
    ),
    (
        re.compile(
            rf"(?P<share>{_NUM}) % of lambda_C comes from the hazard curve extrapolated beyond "
            rf"TR = 2475 y \((?P<over>{_NUM}) %\) or below TR = 30 y \((?P<under>{_NUM}) %\), "
            r"where the code defines no hazard: lambda_C and P50 rest mostly on that extrapolation"
        ),
        "n_extrapolated",
    ),
    (
        re.compile(
            rf"P\(overturning\) (?P<rel>at most|at least) (?P<p>{_NUM}): the collapse median is "
            rf"only a (?P<side>lower|upper) bound \((?P<median>{_NUM}) g, ag_equiv (?P<ag>{_NUM}) "
            rf"g\), beta taken as its largest plausible value (?P<beta>{_NUM})"
        ),
        "n_scenario_p_bound",
    ),
    (re.compile(r"belfry not checked \(no belfry columns in the inventory\)"), "n_no_belfry"),
    (re.compile(r"LV1 not made \(no (?P<a>\w+) and (?P<b>\w+) in the inventory\)"), "n_no_lv1_two"),
    (re.compile(r"LV1 not made \(no (?P<cols>[\w ]+?) in the inventory\)"), "n_no_lv1"),
    (
        re.compile(
            r"LV1 not made \(LC3 rests on a measured f_m: no masonry_strength_mpa in the "
            r"inventory\)"
        ),
        "n_no_lv1_lc3",
    ),
    (
        re.compile(r"I_S and f_a from the SLV fragility: (?P<sub>.*)"),
        "n_from_slv",
    ),
    (
        re.compile(
            r"T_R,C extrapolated outside the tabulated 30-2475 y along the end power law of the "
            r"site's hazard curve"
        ),
        "n_tr_extrapolated",
    ),
    (
        re.compile(
            rf"knowledge level (?P<lc>LC\d) \(F_C = (?P<fc>{_NUM}) divides the SLV capacity\) "
            r"assumed: not in the inventory \(--knowledge-level\)"
        ),
        "n_knowledge_assumed",
    ),
    (
        re.compile(
            rf"knowledge level (?P<lc>LC\d) \(F_C = (?P<fc>{_NUM}) divides the SLV capacity\) "
            r"\((?P<src>inventory|--knowledge-level)\)"
        ),
        "n_knowledge_given",
    ),
    # the LV1 model's clause: with the shaft's walls (prismatic or tapering), and without
    # them (archives written before wall_thickness_top_m); the first two are tried first
    (
        re.compile(
            rf"{_LV1_MODEL}, prismatic shaft, walls (?P<wall>{_NUM}) m, critical section at "
            rf"(?P<z>{_NUM}) m"
        ),
        "n_lv1_model_prismatic",
    ),
    (
        re.compile(
            rf"{_LV1_MODEL}, shaft walls tapering from (?P<wb>{_NUM}) m at the base to "
            rf"(?P<wt>{_NUM}) m at the top \((?P<n>\d+) segments\), critical section at "
            rf"(?P<z>{_NUM}) m"
        ),
        "n_lv1_model_tapered",
    ),
    (re.compile(rf"{_LV1_MODEL}, critical section at (?P<z>{_NUM}) m"), "n_lv1_model"),
    # the source of f_m inside the LV1 model's clause (its ``sub``)
    (re.compile(r"\(Table C8\.5\.I, (?P<lc>LC\d): the range's lower end\)"), "n_fm_table_min"),
    (re.compile(r"\(Table C8\.5\.I, (?P<lc>LC\d): the range's mean\)"), "n_fm_table_mean"),
    (re.compile(r"measured \(masonry_strength_mpa, (?P<lc>LC\d)\)"), "n_fm_measured"),
    (
        re.compile(
            r"LV1 demand: the Circolare 2019 floor spectrum S_eZ\(T1, z\) of the church beneath "
            rf"\(§C7\.2\.3, \[C7\.2\.5\]-\[C7\.2\.10\]\): church H = (?P<h>{_NUM}) m, "
            rf"T_k = (?P<tk>{_NUM}) s \((?P<tsrc>building_period_s|0\.0187 H of the church, "
            r"assumed: no building_period_s)\), elastic \(xi_k = 5 %\), at the tower's "
            rf"springing z = (?P<z>{_NUM}) m \(base_height_m\), read at the tower's T1 = "
            rf"(?P<t1>{_NUM}) s, never below the ground's Se\(T1\)"
        ),
        "n_lv1_church",
    ),
    (
        re.compile(
            rf"LV1: the shaft's own weight alone crushes its section at (?P<z>{_NUM}) m by the "
            rf"code's design strength \(sigma_0 / \(0\.85 f_d\) = (?P<ratio>{_NUM}), f_d = f_m / "
            r"\(gamma_M F_C\), gamma_M = 2 of Circolare 2019 §C8\.7\.1, "
            rf"F_C = (?P<fc>{_NUM})\): the section has no flexural capacity left and the check "
            r"fails at every return period\. A tower that stands carries its weight, so its "
            r"masonry is stronger than f_d: a measured f_m \(knowledge level LC3, "
            r"masonry_strength_mpa\) would change this verdict"
        ),
        "n_lv1_crushed",
    ),
    (
        re.compile(
            rf"LV1: the shaft's own weight takes (?P<share>{_NUM}) % of its section's design "
            rf"strength at (?P<z>{_NUM}) m \(sigma_0 / \(0\.85 f_d\) = (?P<ratio>{_NUM}), "
            r"f_d = f_m / \(gamma_M F_C\), gamma_M = 2 of Circolare 2019 §C8\.7\.1, "
            rf"F_C = (?P<fc>{_NUM})\): the capacity is cut to (?P<rest>{_NUM}) % of the "
            r"uncrushed block's, so the masonry's strength data \(type, knowledge level\) "
            r"drive this result"
        ),
        "n_lv1_compression",
    ),
    (
        re.compile(
            rf"bell gable rocking: on its thickness (?P<t>{_NUM}) m in every direction \(no "
            r"gable_axis in the inventory: the safe side, which overstates its response in its "
            r"plane\)"
        ),
        "n_gable_block_no_axis",
    ),
    (
        re.compile(
            rf"bell gable rocking: on its thickness (?P<t>{_NUM}) m along (?P<ax>[xy]) "
            rf"\(gable_axis, out of its plane\), on its piers' width (?P<w>{_NUM}) m along "
            r"(?P<across>[xy]) \(in its plane, assumed a frame of piers: gable_width_m x "
            r"\(1 - gable_opening_ratio\)\)"
        ),
        "n_gable_block_axis",
    ),
    # the LV1 model's period source (its ``src``) and its bounds on the tabulated hazard
    (re.compile(r"0\.0187 H of the whole tower, assumed"), "n_t1_assumed"),
    (re.compile(r"measured"), "n_t1_measured"),
    (
        re.compile(
            rf"LV1: the check holds at (?P<tr>{_NUM}) y, the longest tabulated return period: "
            r"T_R,C, a_C, I_S and f_a are lower bounds"
        ),
        "n_lv1_holds_longest",
    ),
    (
        re.compile(
            rf"LV1: the check fails at (?P<tr>{_NUM}) y, the shortest tabulated return period: "
            r"T_R,C, a_C, I_S and f_a are upper bounds"
        ),
        "n_lv1_fails_shortest",
    ),
    (re.compile(r"collapse fit: no record overturned the tower"), "n_collapse_fit_none"),
    (
        re.compile(
            rf"SLV fit \(theta_max/alpha >= (?P<ratio>{_NUM})\): no record reached the SLV level"
        ),
        "n_slv_fit_none",
    ),
    (re.compile(r"collapse fit: one record overturned the tower"), "n_collapse_fit_one"),
    (
        re.compile(
            rf"SLV fit \(theta_max/alpha >= (?P<ratio>{_NUM})\): one record reached the SLV level"
        ),
        "n_slv_fit_one",
    ),
    (
        re.compile(
            rf"(?P<k>\d+) of (?P<n>\d+) records stand at (?P<ag>{_NUM}) g, the smallest censoring "
            r"intensity: the median is above it \(lower bound\)"
        ),
        "n_censored_all",
    ),
    (
        re.compile(
            r"lower bounds: the fragility median is a lower bound \(no record reached the limit "
            r"state up to its censoring intensity\), so a_C, T_R,C, I_S and f_a are at least "
            r"these values"
        ),
        "n_lower_bounds_censored",
    ),
    (
        re.compile(
            r"annual rate of overturning undefined: the collapse fragility median is only a bound"
        ),
        "n_rate_undefined",
    ),
    (
        re.compile(
            rf"rocking \(I_S (?P<a>{_NUM}), (?P<ca>[\w ]+)\) and the kinematic checks \(I_S "
            rf"(?P<b>{_NUM}), (?P<cb>[\w ]+)\) disagree: the kinematic checks ignore rocking's "
            r"size effect: a large block outlasts accelerations above alpha0 g too brief to "
            r"overturn it \(Makris & Konstantinidis 2003\), while the IDA sees the records' "
            r"pulses, their vertical motion and \(belfry\) the shaft's amplification"
        ),
        "n_disagree_size_effect",
    ),
    (
        re.compile(
            rf"rocking \(I_S (?P<a>{_NUM}), (?P<ca>[\w ]+)\) and the LV1 model \(I_S "
            rf"(?P<b>{_NUM}), (?P<cb>[\w ]+)\) disagree: the LV1 model checks the shaft's "
            r"masonry sections in flexure under their own weight, which rigid rocking takes as "
            r"infinitely strong: a tall shaft cracks at its critical section long before it "
            r"could overturn as one block"
        ),
        "n_disagree_lv1",
    ),
]
_NUMBER = re.compile(r"(?<![\w.])(\d+)\.(\d+)(?![\w.])")


def _localise(text: str, lang: str) -> str:
    """Write the decimal numbers of ``text`` with the decimal separator of ``lang``."""
    sep = DECIMAL.get(lang, ".")
    return text if sep == "." else _NUMBER.sub(rf"\1{sep}\2", text)


def _clause(text: str, lang: str, *, joined: bool = False) -> str | None:
    """Return a clause in ``lang``, or None when no pattern knows it.

    ``joined``: ``text`` is two clauses joined by ``"; "``; only the patterns that hold
    ``"; "`` themselves are tried (a pattern ending in ``.*`` would swallow the next clause).
    """
    for pattern, key in PATTERNS:
        if joined and "; " not in pattern.pattern:
            continue
        match = pattern.fullmatch(text.strip())
        if match:
            values = {name: _localise(value, lang) for name, value in match.groupdict().items()}
            if "where" in values:
                side = "below" if "below" in values["where"] else "above"
                values["where"] = tr(f"n_where_{side}", lang)
            if key == "n_assumed":
                values["rest"] = values["rest"].replace("(default)", tr("n_default", lang))
            if "rel" in values:
                values["rel"] = tr(f"n_rel_{values['rel'].replace(' ', '_')}", lang)
                values["side"] = tr(f"n_side_{values['side']}", lang)
            for name in ("ca", "cb"):  # risk classes
                if name in values and f"class_{values[name]}" in STRINGS:
                    values[name] = tr(f"class_{values[name]}", lang)
            for name in ("sub", "rest", "src"):  # a clause inside a clause
                inner = _clause(match.group(name), lang) if name in values else None
                if inner is not None:
                    values[name] = inner
            return tr(key, lang, **values)
    return None


def translate_note(note: str, lang: str) -> str:
    """Return an archive note in ``lang`` (module docstring); English is returned unchanged.

    Parameters
    ----------
    note : str
        The note: clauses joined by ``"; "``.
    lang : str
        ``"en"`` or ``"it"``.

    Returns
    -------
    str
        The note with every known clause translated (raw text).
    """
    if lang == "en" or not note:
        return note
    parts, out, i = note.split("; "), [], 0
    while i < len(parts):  # a clause may hold "; " itself: try it joined with the next first
        pair = "; ".join(parts[i : i + 2])
        joined = _clause(pair, lang, joined=True) if i + 1 < len(parts) else None
        if joined is not None:
            out.append(joined)
            i += 2
            continue
        single = _clause(parts[i], lang)
        out.append(parts[i] if single is None else single)
        i += 1
    return "; ".join(out)
