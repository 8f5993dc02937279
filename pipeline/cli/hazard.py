"""``rockscreen hazard``: the NTC 2018 code hazard, spectra and record sets at a site or towers."""

from __future__ import annotations

import json

import click

from rockscreen.pipeline.cli.options import towers_option

#: Largest record set ``--n-records`` asks for [-]: sets are 7 to a few tens; a larger
#: count only generates (embedded suites: two to six times as many candidates) for minutes.
MAX_RECORDS = 100
#: ``--suite`` values naming an embedded suite, and its kind
#: (:data:`rockscreen.pipeline.hazard.suite.SUITE_KINDS`).
EMBEDDED_SUITES = {"stochastic": "stochastic", "synthetic": "stochastic", "matched": "matched"}


def _parse_range(text: str) -> tuple[float, float]:
    try:
        low, high = (float(v) for v in text.split(","))
    except ValueError as exc:
        raise click.BadParameter(f"{text!r}: write LOW,HIGH in s, e.g. 0.15,2.0") from exc
    return low, high


def _record_set(result, suite_arg, suite, n_records, period_range) -> dict:
    from rockscreen.pipeline.hazard import site_record_set

    embedded = {} if suite is not None else {"kind": EMBEDDED_SUITES.get(suite_arg, "stochastic")}
    chosen = site_record_set(
        result.site.lon_deg,
        result.site.lat_deg,
        result.site.return_period_y,
        result.soil_class,
        result.topography,
        suite=suite,
        n_records=n_records,
        period_range_s=period_range,
        damping=result.damping,
        **embedded,
    )
    return {
        "suite": suite_arg,
        "records": [
            {"name": r.name, "scale_factor": float(f), "source": r.source}
            for r, f in zip(chosen.records, chosen.scale_factors, strict=True)
        ],
        "period_range_s": list(period_range),
        "ratio_min": chosen.ratio_min,
        "ratio_max": chosen.ratio_max,
        "meets_tolerance": chosen.meets_tolerance,
        "message": chosen.message,
    }


def _text(entry: dict) -> str:
    if "error" in entry:
        return f"# tower {entry['id']}: {entry['error']}"
    head = f"# tower {entry['id']}  " if "id" in entry else "# "
    state = entry["limit_state"] or "given TR"
    lines = [
        f"{head}lon {entry['lon_deg']:.4f} deg  lat {entry['lat_deg']:.4f} deg  {state}",
        f"  return period      {entry['return_period_y']:10.1f} y",
        f"  ag (rock)          {entry['ag_g']:10.4f} g",
        f"  F0                 {entry['F0']:10.4f} -",
        f"  T*C                {entry['Tc_star_s']:10.4f} s",
        f"  soil / topography  {entry['soil_class']:>6} ({entry['soil_class_source']}) / "
        f"{entry['topography']} ({entry['topography_source']})",
        f"  S = S_S S_T        {entry['S']:10.4f} -  (S_S {entry['S_S']:.4f}, S_T "
        f"{entry['S_T']:.2f}, C_C {entry['C_C']:.4f}, eta {entry['eta']:.4f})",
        f"  TB / TC / TD       {entry['TB_s']:.4f} / {entry['TC_s']:.4f} / {entry['TD_s']:.4f} s",
        f"  PGA = ag S         {entry['pga_g']:10.4f} g",
    ]
    if "periods_s" in entry:
        lines.append(f"  {'period_s':>10}  {'se_g':>10}  {'sve_g':>10}")
        for t, se, sve in zip(entry["periods_s"], entry["se_g"], entry["sve_g"], strict=True):
            lines.append(f"  {t:>10.4g}  {se:>10.5f}  {sve:>10.5f}")
    for text in entry["assumptions"]:
        lines.append(f"  assumption: {text}")
    if "record_set" in entry:
        rs = entry["record_set"]
        lines.append(f"  records ({rs['suite']}): {rs['message']}")
        for record in rs["records"]:
            lines.append(f"    {record['name']:<20} x {record['scale_factor']:.4f}")
    return "\n".join(lines)


@click.command("hazard")
@click.option("--lon", type=float, help="Site longitude, WGS84 [deg].")
@click.option("--lat", type=float, help="Site latitude, WGS84 [deg].")
@towers_option()
@click.option("--return-period", type=float, help="Return period TR [years], 30-2475.")
@click.option(
    "--limit-state",
    type=click.Choice(["SLO", "SLD", "SLV", "SLC"], case_sensitive=False),
    help="Limit state (NTC 2018 §3.2.1); SLV when no --return-period.",
)
@click.option("--nominal-life", type=float, help="Nominal life V_N [years] (default 50).")
@click.option(
    "--use-class",
    type=click.Choice(["I", "II", "III", "IV"], case_sensitive=False),
    help="Use class (NTC 2018 §2.4.2; default III for a church bell tower).",
)
@click.option(
    "--soil",
    type=click.Choice(list("ABCDE"), case_sensitive=False),
    help="Subsoil category (NTC 2018 Tab. 3.2.II; default A, listed as an assumption).",
)
@click.option(
    "--topography",
    type=click.Choice(["T1", "T2", "T3", "T4"], case_sensitive=False),
    help="Topographic category (NTC 2018 Tab. 3.2.III; default T1, listed as an assumption).",
)
@click.option("--damping", type=float, default=0.05, show_default=True, help="Damping ratio [-].")
@click.option("--periods", help="Periods [s] for Se and Sve, e.g. 0,0.1,0.5,1,2.")
@click.option("--json", "as_json", is_flag=True, help="Print JSON.")
@click.option("--plot", type=click.Path(dir_okay=False), help="PNG of the 4 limit states.")
@click.option(
    "--suite",
    help="Record folder, or an embedded suite, for a record set (§3.2.3.6): 'stochastic' "
    "(the default embedded suite; 'synthetic' is the same) or 'matched'.",
)
@click.option(
    "--n-records",
    type=click.IntRange(1, MAX_RECORDS),
    default=None,
    help=f"Records of the set, 1-{MAX_RECORDS} (NTC 2018 §3.2.3.6 asks for at least 7) "
    "[default: 11 for the stochastic suite, 7 otherwise].",
)
@click.option("--period-range", default="0.15,2.0", show_default=True, help="Match range [s].")
def cli(
    lon, lat, towers, return_period, limit_state, nominal_life, use_class, soil, topography,
    damping, periods, as_json, plot, suite, n_records, period_range,
):  # fmt: skip
    """NTC 2018 code hazard (ag, F0, T*C), elastic spectrum and record set at a site.

    Give --lon/--lat or --towers, and --return-period or --limit-state. Values not given
    and absent from the inventory take the tower defaults; each is listed as an
    assumption. Output in g and s, labelled.
    """
    from rockscreen.pipeline.cli.inputs import check_input_files, check_input_paths

    # Before the heavy imports: a mistyped suite or inventory is refused at once.
    check_input_paths([suite if suite and suite not in EMBEDDED_SUITES else None], "suite")
    check_input_files([towers], "inventory")
    from rockscreen.pipeline.cli.spectrum import parse_periods
    from rockscreen.pipeline.hazard.limit_states import LIMIT_STATES
    from rockscreen.pipeline.hazard.site import resolve_hazard, tower_hazard

    if (towers is None) == (lon is None or lat is None):
        raise click.UsageError("give either --lon and --lat, or --towers")
    if return_period is not None and limit_state is not None:
        raise click.UsageError("give --return-period or --limit-state, not both")
    if plot and towers:
        raise click.UsageError("--plot draws one site: use it with --lon/--lat")
    t = parse_periods(periods) if periods else None
    options = {
        "return_period_y": return_period,
        "limit_state": limit_state,
        "nominal_life_y": nominal_life,
        "use_class": use_class.upper() if use_class else None,
        "soil_class": soil,
        "topography": topography,
        "damping": damping,
    }
    match = _parse_range(period_range)
    # The suite is read once, for every tower (None: an embedded suite).
    records = None
    if suite and suite not in EMBEDDED_SUITES:
        from rockscreen.pipeline.hazard import load_suite

        records = load_suite(suite)
    if suite and n_records is None:
        from rockscreen.pipeline.hazard.suite import default_n_records

        n_records = default_n_records(records, EMBEDDED_SUITES.get(suite, "stochastic"))
    entries = []
    if towers:
        from rockscreen.stations.errors import RockscreenError
        from rockscreen.stations.inventory import read_inventory

        for tower in read_inventory(towers):
            try:
                result = tower_hazard(tower, **options)
            except RockscreenError as exc:
                entries.append({"id": tower.id, "error": str(exc)})
                continue
            entries.append({"id": tower.id, **_entry(result, t, suite, records, n_records, match)})
    else:
        result = resolve_hazard(lon, lat, **options)
        entries.append(_entry(result, t, suite, records, n_records, match))
    if plot:
        from rockscreen.pipeline.hazard.plot import plot_limit_state_spectra

        states = [
            resolve_hazard(lon, lat, **{**options, "return_period_y": None, "limit_state": s})
            for s in LIMIT_STATES
        ]
        plot_limit_state_spectra(states, plot)
    if as_json:
        click.echo(json.dumps(entries if towers else entries[0], indent=2))
    else:
        click.echo("\n".join(_text(e) for e in entries))
        if plot:
            click.echo(f"wrote {plot}")


def _entry(result, periods, suite, records, n_records, match) -> dict:
    entry = result.to_dict(periods)
    if suite:
        entry["record_set"] = _record_set(result, suite, records, n_records, match)
    return entry
