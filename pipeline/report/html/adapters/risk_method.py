"""The "Method, references and limits" section of an assess or scenario report, per archive.

:func:`method_paragraphs` describes what was computed in THAT archive, from its root
attributes, the columns of its ``/summary`` and the tables it holds: the hazard and the
record suite, the models solved, how the fragility was fitted (IDA with a censored fit, the
multiple-stripe fit as a check, or a multiple-stripe fit alone in an older archive), which
parts of the tower were modelled (the part models of the registry) for how many towers,
which of the code's checks were made for how many, whether the screening risk was computed
(root attribute ``risk_methods``, with ``risk_priors_source``, ``risk_samples``,
``risk_seed``; RISK_CONTRACT) and the limits that follow. Every sentence is a code of the
catalogue (:mod:`rockscreen.pipeline.verdict.catalogue.method`), so the Italian page holds
no English clause.
"""

from __future__ import annotations

import json
from collections.abc import Collection, Sequence
from pathlib import PurePath
from typing import TYPE_CHECKING

from rockscreen.pipeline.archive.risk_schema import part_model_names
from rockscreen.pipeline.report.added_checks import added_checks
from rockscreen.pipeline.report.html.adapters.common import python_value
from rockscreen.pipeline.report.html.model import MethodParagraph, MethodValue, ModelNames, finite
from rockscreen.pipeline.report.values import Attrs, AttrValue, JSONValue, Row
from rockscreen.pipeline.risk.checks.registry import code_checks
from rockscreen.pipeline.verdict.checks import check_label
from rockscreen.pipeline.verdict.messages import Message, catalogue, message

if TYPE_CHECKING:  # the archive's long tables import h5py
    from rockscreen.pipeline.archive.long_schema import CheckColumns

__all__ = ["method_paragraphs", "risk_methods"]


def _list(value: AttrValue) -> list[JSONValue]:
    """Return an attribute that is a list (stored as JSON text or an array), else ``[]``."""
    value = python_value(value)
    if isinstance(value, str):
        try:
            value = json.loads(value) if value else []
        except json.JSONDecodeError:
            return [value]
    if isinstance(value, (list, tuple)):
        return list(value)
    return [] if value is None else [value]


def risk_methods(attrs: Attrs) -> list[str]:
    """Return the archive's ``risk_methods``: what the screening risk computed.

    ``[]`` when the screening risk was not computed (an older archive, ``assess`` without it).
    """
    return [str(v) for v in _list(attrs.get("risk_methods"))]


def _count(summary: Sequence[Row], key: str) -> int:
    """Return how many rows carry a finite value in ``key``."""
    return sum(finite(row.get(key)) is not None for row in summary)


def _file_name(value: AttrValue) -> str:
    """Return a path's file name (the page shows names, not a machine's folders)."""
    return PurePath(str(value)).name or str(value)


def _sentence(code: str, **params: MethodValue) -> tuple[str, dict[str, MethodValue]]:
    return code, params


def _hazard(kind: str, attrs: Attrs, summary: Sequence[Row]) -> MethodParagraph:
    """Return the hazard and records paragraph of an assess archive."""
    out = MethodParagraph("method.h_hazard")
    periods = ", ".join(f"{float(p):g}" for p in _list(attrs.get("return_periods_y")))
    if periods:
        out.sentences.append(_sentence("method.hazard", periods=periods))
    n = python_value(attrs.get("n_records_per_stripe"))
    if n is not None:
        suite_kind = str(python_value(attrs.get("suite_kind")) or "")
        seed = int(python_value(attrs.get("seed")) or 0)
        if suite_kind in ("stochastic", "matched"):
            out.sentences.append(_sentence(f"method.suite_{suite_kind}", seed=seed, n=int(n)))
        else:
            source = _file_name(attrs.get("suite_source", ""))
            out.sentences.append(_sentence("method.suite_file", source=source, n=int(n)))
    if "basis_compliant" in attrs:
        compliant = bool(python_value(attrs["basis_compliant"]))
        out.sentences.append(
            _sentence("method.basis_compliant" if compliant else "method.basis_noncompliant")
        )
    if "components" in attrs:
        out.sentences.append(_sentence("method.components"))
    return out


def _rocking(attrs: Attrs) -> MethodParagraph:
    """Return the rocking paragraph: the rigid block and the whole tower's models solved."""
    out = MethodParagraph("method.h_rocking", [_sentence("method.rigid_block")])
    parts = set(part_model_names())
    whole = tuple(str(m) for m in _list(attrs.get("models")) if str(m) not in parts)
    if whole:
        out.sentences.append(_sentence("method.models", models=ModelNames(whole)))
    return out


def _fragility(attrs: Attrs, summary: Sequence[Row], columns: Collection[str]) -> MethodParagraph:
    """Return the fragility paragraph: IDA and censored fit, or the stripes' fit alone."""
    out = MethodParagraph("method.h_fragility")
    n_periods = len(_list(attrs.get("return_periods_y")))
    if "collapse_median_g" in columns:
        out.sentences.append(
            _sentence(
                "method.ida",
                ratio=float(python_value(attrs.get("ida_ratio")) or float("nan")),
                tolerance=float(python_value(attrs.get("ida_tolerance")) or float("nan")),
                cap_g=float(python_value(attrs.get("ida_cap_pga_g")) or float("nan")),
                slv=float(python_value(attrs.get("slv_theta_ratio")) or float("nan")),
            )
        )
        bound = sum(bool(str(row.get("collapse_bound") or "")) for row in summary)
        out.sentences.append(_sentence("method.censored_fit", k=bound, n=len(summary)))
        resamples = int(python_value(attrs.get("bootstrap_resamples")) or 0)
        if resamples > 0:
            out.sentences.append(_sentence("method.bootstrap", resamples=resamples))
        if "stripe_median_g" in columns:
            out.sentences.append(_sentence("method.stripes_check", k=n_periods))
    else:
        out.sentences.append(_sentence("method.stripes_fit", k=n_periods))
    out.sentences.append(_sentence("method.hazard_integral"))
    return out


def _parts(summary: Sequence[Row]) -> MethodParagraph:
    """Return the parts paragraph: each part model of the registry, for how many towers."""
    out = MethodParagraph("method.h_parts")
    for part in part_model_names():
        label = check_label(f"{part}.rocking", part)
        k = _count(summary, f"{part}_fragility_median_g")
        if k:
            out.sentences.append(
                _sentence("method.part_modelled", check=label, k=k, n=len(summary))
            )
        else:
            out.sentences.append(_sentence("method.part_not_modelled", check=label))
    return out


def _checks(
    summary: Sequence[Row], columns: Collection[str], stored: Sequence[CheckColumns]
) -> MethodParagraph:
    """Return the code's checks paragraph: each check, for how many towers.

    The registered checks, then those the archive stores that this process has not
    registered (a check added as a module elsewhere: ``stored``, its label from the
    catalogue).
    """
    out = MethodParagraph("method.h_checks")
    for check in code_checks():
        label = check_label(check.id, check.part)
        k = _count(summary, check.keys[1])
        if k:
            out.sentences.append(_sentence("method.check_made", check=label, k=k, n=len(summary)))
        else:
            columns_needed = ", ".join(check.requires) or "-"
            out.sentences.append(
                _sentence("method.check_none", check=label, columns=columns_needed)
            )
    registered = {check.id for check in code_checks()}
    for check in added_checks(stored):
        if check.check not in registered:
            label = check_label(check.check, check.part)
            k = _count(summary, check.keys[1])
            if k:
                made = _sentence("method.check_made", check=label, k=k, n=len(summary))
            else:
                made = _sentence("method.check_none_stored", check=label)
            out.sentences.append(made)
    levels: dict[str, int] = {}
    for row in summary:
        level = str(row.get("knowledge_level") or "")
        if level:
            levels[level] = levels.get(level, 0) + 1
    if levels:
        text = ", ".join(f"{level} ({n})" for level, n in sorted(levels.items()))
        out.sentences.append(_sentence("method.knowledge", levels=text))
    if "governing_check" in columns:
        out.sentences.append(_sentence("method.code_verdict"))
    return out


def _method_message(method: str) -> Message:
    code = f"method.risk.{method}"
    if code in catalogue():
        return message(code)
    return message("method.risk.other", method=method)


def _risk(attrs: Attrs, summary: Sequence[Row]) -> MethodParagraph:
    """Return the screening risk's paragraph: what it computed, or that it was not."""
    out = MethodParagraph("method.h_risk")
    methods = risk_methods(attrs)
    if not methods:
        out.sentences.append(_sentence("method.risk_not_computed"))
        return out
    source = str(python_value(attrs.get("risk_priors_source")) or "default")
    priors = (
        message("method.priors_default")
        if source == "default"
        else message("method.priors_file", source=_file_name(source))
    )
    out.sentences.append(
        _sentence(
            "method.risk_computed",
            samples=int(python_value(attrs.get("risk_samples")) or 0),
            priors=priors,
            seed=int(python_value(attrs.get("risk_seed")) or 0),
        )
    )
    out.sentences.append(
        _sentence("method.risk_methods", methods=tuple(_method_message(m) for m in methods))
    )
    out.sentences.append(_sentence("method.risk_weakest"))
    sources = [str(row.get("risk_beta_source") or "") for row in summary]
    if any(sources):
        out.sentences.append(
            _sentence(
                "method.risk_beta",
                fit=sources.count("ida_fit"),
                judgement=sources.count("judgement_fema_p695"),
            )
        )
    judged = sorted(
        {
            name
            for row in summary
            for name in str(row.get("risk_judgement_inputs") or "").split(";")
            if name
        }
    )
    if judged:
        out.sentences.append(_sentence("method.risk_judgement", inputs=", ".join(judged)))
    top_n = python_value(attrs.get("risk_top_n"))
    if top_n is not None:
        out.sentences.append(_sentence("method.risk_survey", top_n=int(top_n)))
    return out


def _scenario(attrs: Attrs) -> MethodParagraph:
    """Return a scenario's paragraph: the ShakeMap, the fragilities, the ground motion's σ."""
    out = MethodParagraph("method.h_scenario")
    out.sentences.append(
        _sentence(
            "method.scenario_shakemap",
            source=_file_name(attrs.get("shakemap_source", "")),
            event=str(python_value(attrs.get("shakemap_event")) or "-"),
            fragility=_file_name(attrs.get("fragility_source", "")),
        )
    )
    if "gm_uncertainty" in attrs:
        sigma = bool(python_value(attrs["gm_uncertainty"]))
        out.sentences.append(
            _sentence("method.scenario_sigma" if sigma else "method.scenario_sigma_off")
        )
    return out


def _limits(kind: str, attrs: Attrs) -> list[MethodParagraph]:
    limits = MethodParagraph("method.h_limits", [_sentence("method.limits_rigid")])
    computed = kind == "assess" and bool(risk_methods(attrs))
    limits.sentences.append(
        _sentence("method.limits_with_risk" if computed else "method.limits_records_only")
    )
    limits.sentences.append(_sentence("method.limits_rank"))
    references = MethodParagraph("method.h_references", [_sentence("method.references")])
    if computed:
        references.sentences.append(_sentence("method.references_risk"))
    return [limits, references]


def method_paragraphs(
    kind: str,
    attrs: Attrs,
    summary: Sequence[Row],
    columns: Collection[str] = (),
    checks: Sequence[CheckColumns] = (),
) -> list[MethodParagraph]:
    """Return the method section of an assess or scenario archive, from what it holds.

    Parameters
    ----------
    kind : str
        ``"assess"`` or ``"scenario"``.
    attrs : mapping
        The archive's root attributes (``return_periods_y``, ``suite_kind``,
        ``n_records_per_stripe``, ``models``, ``ida_*``, ``bootstrap_resamples``,
        ``risk_methods``, ``risk_priors_source``, ``risk_samples``, ``risk_seed``,
        ``risk_top_n``; a scenario's ``shakemap_*``, ``fragility_source``,
        ``gm_uncertainty``); an attribute absent is a sentence left out.
    summary : sequence of mapping
        The ``/summary`` rows (how many towers had each part modelled, each check made).
    columns : collection of str
        The ``/summary`` columns written (an IDA's ``collapse_median_g``, the stripes'
        ``stripe_median_g``); default: the rows' keys.
    checks : sequence of CheckColumns
        The checks the archive stores (:func:`~rockscreen.pipeline.archive.long_pivot.
        stored_checks`): one it holds that is not registered here is named too.

    Returns
    -------
    list of MethodParagraph
        Headed paragraphs of catalogue sentences, in reading order.
    """
    columns = set(columns) or set().union(*(row.keys() for row in summary))
    if kind == "scenario":
        return [_scenario(attrs), _rocking(attrs), *_limits(kind, attrs)]
    return [
        _hazard(kind, attrs, summary),
        _rocking(attrs),
        _fragility(attrs, summary, columns),
        _parts(summary),
        _checks(summary, columns, checks),
        _risk(attrs, summary),
        *_limits(kind, attrs),
    ]
