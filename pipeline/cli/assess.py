"""``rockscreen assess``: pre-event fragility, annual rate of overturning and LV1 indices."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path
from typing import Any

import click

from rockscreen.pipeline.cli.options import (
    example_option,
    jobs_option,
    out_option,
    scheduler_option,
    towers_option,
)


def _floats(text: str | None, option: str) -> tuple[float, ...]:
    if not text:
        return ()
    try:
        return tuple(float(v) for v in text.split(","))
    except ValueError:
        raise click.BadParameter(
            f"{text!r}: expected numbers separated by commas", param_hint=option
        ) from None


def _check_return_periods(text: str | None) -> None:
    """Refuse return periods outside the NTC 2018 hazard table (30-2475 y), before any work."""
    from rockscreen.pipeline.hazard.grid import RETURN_PERIODS_Y

    low, high = float(RETURN_PERIODS_Y[0]), float(RETURN_PERIODS_Y[-1])
    bad = [v for v in _floats(text, "--return-periods") if not low <= v <= high]
    if bad:
        raise click.BadParameter(
            f"{text!r}: {', '.join(f'{v:g}' for v in bad)} outside the allowed range "
            f"{low:g}-{high:g} years (NTC 2018 hazard table, not extrapolated)",
            param_hint="--return-periods",
        )


@click.command("assess", context_settings={"show_default": True})
@towers_option()
@example_option("Assess the embedded example inventory with the embedded record suite.")
@click.option(
    "--suite",
    "suite_paths",
    multiple=True,
    type=click.Path(exists=True),
    help="Record suite: a folder or files (repeatable); default the embedded suite (--suite-kind).",
)
@click.option(
    "--suite-kind",
    type=click.Choice(["stochastic", "matched"], case_sensitive=False),
    default="stochastic",
    help="Embedded suite when no --suite: 'stochastic' (Rezaeian & Der Kiureghian 2010 "
    "records with velocity pulses, each keeping its own shape: record-to-record scatter) or "
    "'matched' (spectrum-matched synthetics). See docs/hazard.md.",
)
@click.option("--units", help="Units of suite files that state none: g, m/s2 or cm/s2.")
@click.option(
    "--return-periods",
    metavar="TR,...",
    help="Stripes' return periods [y] (default the nine of NTC 2018: 30,50,...,2475).",
)
@click.option(
    "--records",
    "n_records",
    type=click.IntRange(min=1),
    default=None,
    help="Records per stripe [default: 11 for the embedded stochastic suite, 7 otherwise].",
)
@click.option(
    "--models",
    default="ground,floor,double,belfry,gable",
    help="Models to run (those the tower's data allow).",
)
@click.option(
    "--damage-levels",
    default="0.01,0.2,0.5",
    help="theta_max/alpha levels counted per stripe [-].",
)
@click.option(
    "--site-resolution",
    type=click.FloatRange(min=0.0),
    default=0.01,
    help="Rounding of tower locations into shared sites [deg].",
)
@click.option(
    "--class-limits",
    default="1,0.6,0.3",
    help="Lower I_S limits of the classes meets, moderate, high [-].",
)
@click.option("--seed", type=int, default=0, help="Seed of the embedded suite.")
@click.option(
    "--scale-limits",
    metavar="LOW,HIGH",
    default="0.25,4",
    help="Smallest and largest scale factor of a suite record [-].",
)
@click.option(
    "--allow-noncompliant",
    is_flag=True,
    help="Assess the towers whose record sets fail NTC 2018 §3.2.3.6 (fewer than 7 records, "
    "mean spectrum outside -10 %/+30 % of the code's); each verdict built on them is marked "
    "'basis not code-compliant'. Default: those towers are not solved but listed in /failures "
    "with the measured values and the fix; every other tower is assessed.",
)
@click.option(
    "--skip-invalid",
    is_flag=True,
    help="Assess the inventory's valid towers and list its invalid rows in /failures (kind "
    "'inventory') instead of refusing the inventory. Default: every invalid row named in one "
    "error, nothing assessed.",
)
@click.option(
    "--knowledge-level",
    type=click.Choice(["LC1", "LC2", "LC3"], case_sensitive=False),
    default=None,
    help="Knowledge level of every tower (Circolare 2019 §C8.5.4): F_C = 1.35/1.20/1.00 "
    "divides the SLV capacity. Default LC1, written in every row's note as an assumption.",
)
@click.option(
    "--bootstrap",
    "bootstrap_resamples",
    type=click.IntRange(min=0),
    default=200,
    help="Resamples of the record bootstrap (90 % intervals of the collapse median, lambda_C "
    "and I_S; seeded with --seed); 0 = none.",
)
@click.option(
    "--priors",
    "priors_path",
    type=click.Path(exists=True, dir_okay=False),
    default=None,
    help="A region's priors file (TOML; docs/uncertainty.md) for what the inventory does not "
    "say (wall, taper, masonry type, period) in the screening risk. Default: the built-in "
    "priors (TURRIS; the masonry type uniform, a judgement).",
)
@click.option(
    "--risk-samples",
    type=int,
    default=1000,
    help="Epistemic samples per tower of the screening risk (>= 100; seeded with --seed and "
    "the tower's id).",
)
@out_option("Archive (default rockscreen-assess.h5; with --example rockscreen-assess-example.h5).")
@click.option(
    "--overwrite",
    is_flag=True,
    help="Replace an existing file at --out, and discard a work file OUT.part of other inputs "
    "(one of the same inputs is always resumed).",
)
@jobs_option()
@scheduler_option(
    "Compute on a running Dask scheduler's workers (--jobs is then ignored).",
)
def cli(
    towers,
    example,
    suite_paths,
    suite_kind,
    units,
    return_periods,
    n_records,
    models,
    damage_levels,
    site_resolution,
    class_limits,
    seed,
    scale_limits,
    allow_noncompliant,
    skip_invalid,
    knowledge_level,
    bootstrap_resamples,
    priors_path,
    risk_samples,
    out,
    overwrite,
    jobs,
    scheduler,
) -> None:
    """Multiple-stripe fragility, annual rate of overturning and LV1 safety index per tower.

    At each return period of the site's code hazard (NTC 2018) a spectrum-compatible record
    set is selected and every tower is solved under every record, both horizontal
    components and every model its data allow. A lognormal fragility in the site's ag is
    fitted by maximum likelihood (record-to-record variability only), integrated over the
    site's hazard curve (annual rate of overturning, probability in 50 years) and read as
    the Guidelines' capacity acceleration a_C, its return period T_R,C, the safety index
    I_S = T_R,C / T_R,SLV and the acceleration factor f_a. A tower whose site's record set
    fails NTC 2018 §3.2.3.6 (at least 7 records, mean spectrum within -10 %/+30 % of the
    code's), whose site has no hazard or no set is not assessed but listed in /failures with
    the reason and the fix (--allow-noncompliant assesses it, marked); the others are.

    Exit status: 0 the archive is written (a last line on stderr counts the towers not
    assessed, if any: rockscreen inspect OUT lists them); 1 an error, nothing written
    (an invalid inventory names every invalid row; no tower could be assessed); 2 a usage
    error; 129/130/143 interrupted, finished towers kept in OUT.part. See docs/risk.md.

    Finished towers are kept in OUT.part as they come: after an interruption (Ctrl-C,
    kill, a lost worker, a full disk) the same command resumes from it; other inputs are
    refused with the difference named (--overwrite discards it).
    """
    from rockscreen.pipeline.cli.inputs import check_input_files

    # Before the heavy imports: a mistyped inventory is refused at once (click checked
    # that every --suite exists).
    if towers and not example:
        check_input_files([towers], "inventory")
    from rockscreen.pipeline.archive.lock import claimed_output
    from rockscreen.pipeline.risk.assess.batch import AssessInputs, assess_to_archive

    inventory = _inventory_path(towers, example)
    _check_return_periods(return_periods)
    risk = _risk_options(priors_path, risk_samples)
    out_path = Path(out or ("rockscreen-assess-example.h5" if example else "rockscreen-assess.h5"))
    # Before any work: never an input, never an existing file without --overwrite, a
    # writable folder; one assess per --out (released when the command ends).
    claim = claimed_output(out_path, [towers, *suite_paths], "assess", overwrite=overwrite)
    click.get_current_context().with_resource(claim)
    chosen = _models(models)
    notify = _notify
    tower_list, skipped = _read_towers(inventory, skip_invalid, notify)
    suite, suite_label = _read_suite(suite_paths, units, suite_kind.lower())
    options = _assess_options(
        suite,
        suite_kind.lower(),
        chosen,
        return_periods=return_periods,
        n_records=n_records,
        damage_levels=damage_levels,
        site_resolution=site_resolution,
        class_limits=class_limits,
        seed=seed,
        scale_limits=scale_limits,
        allow_noncompliant=allow_noncompliant,
        knowledge_level=knowledge_level,
        bootstrap_resamples=bootstrap_resamples,
        risk=risk,
    )
    inputs = AssessInputs(
        inventory=inventory, suite=suite, suite_label=suite_label, seed=seed, skipped_rows=skipped
    )
    result = assess_to_archive(
        tower_list,
        options,
        out_path,
        inputs,
        scheduler=scheduler,
        jobs=jobs,
        notify=notify,
        discard_other=overwrite,
    )
    _print_result(result, len(tower_list) + len(skipped), out_path)


def _notify(text: str) -> None:
    """Print one line of the run's progress or notes on stderr."""
    click.echo(f"rockscreen: {text}", err=True)


def _inventory_path(towers: str | None, example: bool) -> Path:
    """Return the inventory to read: ``--towers`` or, with ``--example``, the embedded one."""
    from rockscreen.stations.inventory import example_inventory_path

    if example and towers:
        raise click.UsageError("give --towers CSV or --example, not both")
    if not example and not towers:
        raise click.UsageError("give --towers CSV (or --example)")
    return example_inventory_path() if example else Path(towers)


def _read_towers(
    inventory: Path, skip_invalid: bool, notify: Callable[[str], None]
) -> tuple[list[Any], tuple[dict[str, Any], ...]]:
    """Return the inventory's towers and the ``/failures`` rows of its rows skipped.

    Raises
    ------
    InventoryError
        Every invalid row named at once, unless ``--skip-invalid`` and some row is valid.
    """
    from rockscreen.pipeline.risk.assess.batch import inventory_failures
    from rockscreen.stations.inventory import read_inventory_rows

    reading = read_inventory_rows(inventory)
    if reading.invalid and (not skip_invalid or not reading.towers):
        raise reading.error()  # every invalid row named at once
    skipped = inventory_failures(reading.invalid)
    if skipped:
        notify(f"skipping {len(skipped)} invalid row(s) of {inventory} (--skip-invalid)")
    return reading.towers, skipped


def _read_suite(suite_paths: Sequence[str], units: str | None, kind: str) -> tuple[Any, str]:
    """Return the ``--suite`` records (None for the embedded suite of ``kind``) and their label."""
    from rockscreen.pipeline.risk.assess.batch import EMBEDDED_SUITE_LABELS

    if not suite_paths:
        return None, EMBEDDED_SUITE_LABELS[kind]
    from rockscreen.pipeline.hazard.suite_io import load_suite

    paths = list(suite_paths)
    suite = load_suite(paths[0] if len(paths) == 1 else paths, units=units)
    return suite, ", ".join(paths)


def _assess_options(
    suite: Any,
    suite_kind: str,
    models: tuple[str, ...],
    *,
    return_periods: str | None,
    n_records: int | None,
    damage_levels: str,
    site_resolution: float,
    class_limits: str,
    seed: int,
    scale_limits: str,
    allow_noncompliant: bool,
    knowledge_level: str | None,
    bootstrap_resamples: int,
    risk: Any,
) -> Any:
    """Return the :class:`rockscreen.pipeline.risk.assess.run.AssessOptions` of the options given.

    The record selection takes ``--records`` (default per suite:
    :func:`rockscreen.pipeline.hazard.suite.default_n_records`) and ``--scale-limits``; the
    embedded suite (``suite`` None) also its kind and ``--seed``.
    """
    from rockscreen.pipeline.hazard.suite import default_n_records
    from rockscreen.pipeline.risk.assess.run import AssessOptions
    from rockscreen.pipeline.risk.assess.stripes import StripeOptions
    from rockscreen.pipeline.risk.measures.classes import parse_limits

    limits = _scale_limits(scale_limits)
    if n_records is None:
        n_records = default_n_records(suite, suite_kind)
    selection = {"n_records": n_records, "scale_limits": limits}
    return AssessOptions(
        return_periods_y=_floats(return_periods, "--return-periods"),
        stripe=StripeOptions(
            models=models, damage_levels=_floats(damage_levels, "--damage-levels")
        ),
        selection={
            **selection,
            **({} if suite is not None else {"seed": seed, "kind": suite_kind}),
        },
        site_resolution_deg=site_resolution,
        class_limits=parse_limits(class_limits),
        allow_noncompliant=allow_noncompliant,
        knowledge_level=knowledge_level.upper() if knowledge_level else None,
        bootstrap_resamples=bootstrap_resamples,
        seed=seed,
        risk=risk,
    )


def _risk_options(priors_path: str | None, risk_samples: int) -> Any:
    """Return the screening risk's options: ``--risk-samples`` checked, ``--priors`` read.

    Raises
    ------
    click.BadParameter
        For fewer than :data:`~rockscreen.pipeline.risk.assess.screening_risk.MIN_RISK_SAMPLES`.
    ConfigError
        For a priors file rockscreen does not read (one line naming the key).
    """
    from rockscreen.pipeline.risk.assess.screening_risk import MIN_RISK_SAMPLES, RiskOptions
    from rockscreen.pipeline.risk.uncertainty.region import read_region_priors

    if risk_samples < MIN_RISK_SAMPLES:
        raise click.BadParameter(
            f"{risk_samples}: too few for the 5 % and 95 % ends of the risk's interval; "
            f"allowed: an integer >= {MIN_RISK_SAMPLES}",
            param_hint="--risk-samples",
        )
    if priors_path is None:
        return RiskOptions(samples=risk_samples)
    region = read_region_priors(priors_path)
    return RiskOptions(samples=risk_samples, region=region, priors_source=Path(priors_path).name)


def _models(models: str) -> tuple[str, ...]:
    """Return the ``--models`` names, each a registered model (else a usage error)."""
    from rockscreen.pipeline.engine.registry import model_names

    chosen = tuple(m.strip() for m in models.split(",") if m.strip())
    if not chosen or any(m not in model_names() for m in chosen):
        raise click.BadParameter(
            f"{models!r}: allowed models {', '.join(model_names())}", param_hint="--models"
        )
    return chosen


def _scale_limits(text: str) -> list[float]:
    """Return ``--scale-limits`` LOW,HIGH with 0 < LOW <= 1 <= HIGH (else a usage error)."""
    limits = _floats(text, "--scale-limits")
    if len(limits) != 2 or not 0 < limits[0] <= 1 <= limits[1]:
        raise click.BadParameter(
            f"{text!r}: expected LOW,HIGH with 0 < LOW <= 1 <= HIGH (e.g. 0.25,4)",
            param_hint="--scale-limits",
        )
    return limits


def _print_result(result, n_towers: int, out_path: Path) -> None:
    """Print the ranked towers, the legend, the counts per area, the screening risk, the rest.

    The screening risk's ranked list: the riskiest ten, beside the code verdict.

    What was not assessed is one line on stderr, the last.
    """
    from rockscreen.pipeline.report.areas import area_lines
    from rockscreen.pipeline.report.risk_ranking import RANKING_LEGEND, ranking_lines
    from rockscreen.pipeline.report.risk_summary import (
        ASSESS_LEGEND,
        assess_lines,
        not_assessed_line,
    )
    from rockscreen.pipeline.risk.checks.governing import check_columns
    from rockscreen.pipeline.risk.measures.classes import PRINTED_CLASSES

    rows = list(result.summary)  # read once (from the archive, after a work file)
    # every registered check beside the built-in columns (a check added as a module)
    for line in assess_lines(rows, check_columns()):
        click.echo(line)
    click.echo(ASSESS_LEGEND)
    for line in area_lines(rows, PRINTED_CLASSES):
        click.echo(line)
    ranking = ranking_lines(rows)
    if ranking:
        click.echo("")
        for line in ranking:
            click.echo(line)
        click.echo(RANKING_LEGEND)
    line = not_assessed_line(result.failures, n_towers, str(out_path))
    if line:
        click.echo(f"rockscreen: {line}", err=True)
