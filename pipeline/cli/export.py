"""``rockscreen export``: the per-tower risk summary of an archive as CSV or GeoJSON."""

from __future__ import annotations

from pathlib import Path

import click

from rockscreen.pipeline.cli.options import path_option


@click.command("export")
@click.argument("archive", type=click.Path(path_type=Path))
@path_option(
    "--csv",
    "csv_out",
    metavar="OUT",
    as_path=True,
    help="Write a CSV table (units in the column names) for spreadsheets.",
)
@path_option(
    "--geojson",
    "geojson_out",
    metavar="OUT",
    as_path=True,
    help="Write a GeoJSON FeatureCollection of tower points for GIS (QGIS, ...).",
)
@click.option(
    "--locale",
    "locale",
    type=click.Choice(["c", "it"]),
    default="c",
    show_default=True,
    help="CSV dialect: c = comma and decimal point; it = Italian Excel (';', decimal comma, "
    "UTF-8 with BOM).",
)
@click.option("--excel-it", is_flag=True, help="Same as --locale it.")
@click.option(
    "--by",
    "area",
    type=click.Choice(["comune", "provincia"]),
    default=None,
    help="CSV: towers per class per area of this inventory column instead of one row per tower.",
)
@click.option(
    "--order",
    type=click.Choice(["risk", "inventory"]),
    default="risk",
    show_default=True,
    help="Rows riskiest first, or in the inventory's order.",
)
@click.option(
    "--digits",
    type=click.IntRange(min=1, max=17),
    default=None,
    metavar="N",
    help="CSV: N significant digits for the numbers (coordinates stay whole); "
    "default full precision.",
)
def cli(
    archive: Path,
    csv_out: Path | None,
    geojson_out: Path | None,
    locale: str,
    excel_it: bool,
    order: str,
    digits: int | None,
    area: str | None,
) -> None:
    """Export the per-tower summary of ARCHIVE: exactly one of --csv OUT or --geojson OUT.

    One row (or point) per tower, riskiest first (--order inventory: the inventory's
    order): id, name, lat_deg, lon_deg,
    theta_max_over_alpha, theta_max_rad, overturned, safety_factor, risk_class,
    governing record, model and component, number of records, ... GeoJSON leaves out
    towers without coordinates (a warning on stderr lists them) and writes NaN and
    infinity as null. In the CSV, a text cell starting with =, +, -, @, tab or carriage
    return gets a leading apostrophe, so that no spreadsheet runs it as a formula
    (numbers stay numbers). --excel-it (--locale it) writes the CSV as Italian Excel
    reads it: ';' separator, decimal comma, UTF-8 with BOM; --digits N rounds its numbers
    to N significant digits; --by comune|provincia writes the towers per class per area
    instead (those optional inventory columns). A value that is only a bound is written
    with its relation (>1.67: at least), never as a plain number. Beside a GeoJSON,
    NAME.qml: a QGIS style (towers by risk class in the report's colours) that QGIS loads
    with the layer. OUT is replaced atomically.
    """
    if (csv_out is None) == (geojson_out is None):
        raise click.UsageError("give exactly one of --csv OUT or --geojson OUT")
    locale = "it" if excel_it else locale
    if geojson_out is not None and (locale != "c" or digits is not None or area is not None):
        raise click.UsageError("--locale, --excel-it, --digits and --by apply to --csv only")
    from rockscreen.pipeline.cli.inputs import check_archive_path

    check_archive_path(archive)  # before the heavy imports: a typo is refused at once
    from rockscreen.pipeline.archive.kinds import open_archive
    from rockscreen.pipeline.archive.lock import check_output
    from rockscreen.pipeline.report.export import (
        summary_feature_collection,
        write_summary_csv,
        write_summary_geojson,
    )
    from rockscreen.pipeline.report.presenters import face
    from rockscreen.pipeline.report.qgis_style import class_style_path, write_risk_style
    from rockscreen.pipeline.text import printable

    # Never the archive itself, never another archive (an existing CSV/GeoJSON is replaced).
    target, option = (csv_out, "--csv") if csv_out is not None else (geojson_out, "--geojson")
    check_output(target, [archive], overwrite=True, option=option, keep_archives=True)
    # One writer for every archive kind (the CSV formula guard included).
    reader = open_archive(archive)
    rows = face(reader, "export")(reader, order=order)
    if csv_out is not None and area is not None:
        from rockscreen.pipeline.archive.atomic import write_text_atomic
        from rockscreen.pipeline.report.areas import area_columns
        from rockscreen.pipeline.report.export import area_csv_text

        if area not in area_columns(rows):
            raise click.UsageError(
                f"--by {area}: the archive's towers have no {area} (an optional inventory "
                "column of assess and scenario)"
            )
        write_text_atomic(csv_out, area_csv_text(rows, area, locale))
        done = f"rockscreen: wrote towers per class by {area} to {printable(str(csv_out))}"
        click.echo(done, err=True)
        return
    if csv_out is not None:
        written = write_summary_csv(rows, csv_out, locale=locale, digits=digits)
        click.echo(f"rockscreen: wrote {written} tower(s) to {printable(str(csv_out))}", err=True)
        return
    style = geojson_out.with_suffix(".qml")
    for path in (style, class_style_path(geojson_out)):
        check_output(path, [archive], overwrite=True, option="--geojson", keep_archives=True)
    written, skipped = write_summary_geojson(rows, geojson_out)
    features = summary_feature_collection(rows)[0]["features"]
    write_risk_style(features, geojson_out)
    click.echo(f"rockscreen: QGIS style written to {printable(str(style))}", err=True)
    by_class = class_style_path(geojson_out)
    if any(f.get("properties", {}).get("risk_band") for f in features):
        click.echo(
            f"rockscreen: coloured by the screening risk's band; the code's classes in "
            f"{printable(str(by_class))}",
            err=True,
        )
    if skipped:
        shown = ", ".join(printable(i) for i in skipped[:10])
        shown += ", ..." if len(skipped) > 10 else ""
        click.echo(
            f"rockscreen: warning: {len(skipped)} tower(s) without coordinates left out "
            f"of {printable(str(geojson_out))}: {shown}",
            err=True,
        )
    click.echo(f"rockscreen: wrote {written} tower(s) to {printable(str(geojson_out))}", err=True)
