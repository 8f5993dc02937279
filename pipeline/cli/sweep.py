"""``rockscreen sweep``: run a study file's grid of cases and archive the results."""

from __future__ import annotations

from pathlib import Path

import click

from rockscreen.pipeline.cli.options import (
    folder_option,
    jobs_option,
    path_option,
    scheduler_option,
)


@click.command(name="sweep")
@click.argument("study", type=click.Path(dir_okay=False, path_type=Path))
@path_option(
    "--out",
    as_path=True,
    help="HDF5 archive to write [default: STUDY's name with .h5, in the current folder].",
)
@jobs_option(help="Worker processes [default: 1].")
@scheduler_option(
    "Compute the cases on a running Dask scheduler's workers (--jobs is then ignored)."
)
@folder_option("--figures", help="Also draw the rotation time histories (PNG) into this folder.")
@path_option(
    "--markdown",
    as_path=True,
    help="Also write the results as Markdown tables (rows: friction pairs, columns: frequencies).",
)
@click.option("--overwrite", is_flag=True, help="Replace an existing file at --out.")
@click.option(
    "--dry-run", is_flag=True, help="List the combinations and exit without running them."
)
def cli(
    study: Path,
    out: Path | None,
    jobs: int | None,
    scheduler: str | None,
    figures: Path | None,
    markdown: Path | None,
    overwrite: bool,
    dry_run: bool,
) -> None:
    """Run every combination of a STUDY.toml grid on one tower; write an HDF5 archive.

    The study file names the tower and one or more [[group]] grids (model,
    excitation, amplitudes with units, frequencies, friction pairs, eta); the
    cartesian product of each group's lists is run. The archive holds the study
    text, a /cases table and /histories/<case>; a table is printed at the end.
    See docs/seed_study.md for the format.
    """
    from rockscreen.pipeline.cli.inputs import check_input_files

    check_input_files([study], "study file")  # before the heavy imports
    from rockscreen.pipeline.archive.lock import check_output, claimed_output
    from rockscreen.pipeline.engine.registry import solver_model
    from rockscreen.pipeline.execution.dask_cluster import check_address
    from rockscreen.pipeline.study.sweep import (
        format_cases_table,
        format_markdown_tables,
        load_study,
        read_cases,
        run_study,
        write_sweep_archive,
    )

    parsed = load_study(study)
    cases = parsed.cases()
    if dry_run:
        for case in cases:
            friction = ""
            if solver_model(case.model).takes("mu_s"):
                friction = f" mu_s={case.mu_s:g} mu_k={case.mu_k:g}"
            click.echo(
                f"{case.index:4d}  {case.group}: {case.model} {case.excitation} "
                f"{case.shape} A={case.amplitude_text} f={case.frequency:g} Hz{friction}"
            )
        click.echo(f"{len(cases)} combinations")
        return
    out = Path(study.stem + ".h5") if out is None else out
    # Before any case runs: never the study, never an existing file without --overwrite,
    # one sweep per --out.
    context = click.get_current_context()
    context.with_resource(claimed_output(out, [study], "sweep", overwrite=overwrite))
    if markdown is not None:
        check_output(
            markdown, [study, out], overwrite=True, option="--markdown", keep_archives=True
        )
    total = len(cases)

    def progress(result) -> None:
        c = result.case
        click.echo(
            f"[{c.index + 1}/{total}] {c.group}: A={c.amplitude_text} f={c.frequency:g} Hz "
            f"-> {result.status}, theta_max={result.theta_max:.4g} rad",
            err=True,
        )

    if scheduler:
        check_address(scheduler)  # a malformed address: one line, before anything runs

    def note(line: str) -> None:
        click.echo(line, err=True)

    results = run_study(parsed, jobs=jobs, cases=cases, scheduler=scheduler, notify=note)
    write_sweep_archive(out, parsed, results, on_result=progress)
    rows = read_cases(out)
    click.echo(f"# {parsed.title}")
    click.echo(format_cases_table(rows))
    click.echo(f"archive: {out}")
    if markdown is not None:
        markdown.parent.mkdir(parents=True, exist_ok=True)
        markdown.write_text(format_markdown_tables(rows, parsed.title), encoding="utf-8")
        click.echo(f"tables: {markdown}")
    if figures is not None:
        from rockscreen.pipeline.report.sweep_plots import plot_sweep

        for path in plot_sweep(out, figures):
            click.echo(f"figure: {path}")
