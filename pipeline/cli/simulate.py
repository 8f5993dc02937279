"""``rockscreen simulate``: one tower (or sliding block), one excitation, one outcome.

The command parses options, builds the excitation with :mod:`pipeline.motion.excitations` or
reads a record with :func:`pipeline.records.io.read_stream`, calls the solver and prints the
result. It holds no physics.
"""

from __future__ import annotations

import json
import math

import click
import numpy as np

from rockscreen.pipeline.cli.traces import read_trace, stations_option, units_option
from rockscreen.pipeline.engine.registry import (
    SIMULATE,
    TowerModel,
    model_names,
    models,
    solver_model,
)
from rockscreen.pipeline.errors import UnitsError
from rockscreen.pipeline.units import parse_acceleration
from rockscreen.pipeline.vocabulary import PULSE_SHAPES

#: Sampling step of free rocking from an initial rotation when --dt is not given [s].
FREE_ROCKING_DT = 1e-3


def _amplitude(ctx, param, value):
    """Click callback: an acceleration with its unit, to m/s^2 (a bare number is refused)."""
    if value is None:
        return None
    try:
        return parse_acceleration(value, name="--amplitude")
    except UnitsError as exc:
        raise click.BadParameter(str(exc), ctx=ctx, param=param) from exc


def _given(**options) -> list[str]:
    return [name for name, value in options.items() if value is not None and value is not False]


def _single_block(model: TowerModel) -> bool:
    """Whether ``model`` is the tower rocking alone (a block, no building parameters)."""
    return model.has_block and not model.parameters


def _inferred(geometry, building, friction) -> TowerModel:
    """Return the model the given options describe: masses, else geometry, else friction."""
    if building:
        wanted = lambda m: m.takes("tower_mass")  # noqa: E731
    elif geometry:
        wanted = _single_block
    elif friction:
        wanted = lambda m: not m.has_block  # noqa: E731
    else:
        raise click.UsageError(
            "give the tower geometry (--width/--height or --p/--alpha), or --mu-s/--mu-k "
            "for a sliding block"
        )
    return next(m for m in models(SIMULATE) if wanted(m))


def _resolve_model(name, geometry, building, friction) -> TowerModel:
    """Return the model of ``--model`` or the one the given options describe.

    ``geometry``, ``building`` (the masses) and ``friction`` list the option names given.
    """
    model = _inferred(geometry, building, friction) if name is None else solver_model(name)
    if model.takes("tower_mass"):
        missing = [
            name
            for name in ("--tower-mass", "--building-mass", "--mu-s", "--mu-k")
            if name not in building + friction
        ]
        if missing:
            raise click.UsageError(
                f"the double block needs all building options; missing: {', '.join(missing)}"
            )
        if not geometry:
            raise click.UsageError("the double block needs the tower geometry")
    elif _single_block(model):
        extra = building + friction
        if extra:
            raise click.UsageError(
                f"{', '.join(extra)} describe the building: give all of --tower-mass, "
                "--building-mass, --mu-s, --mu-k (double block) or none (rocking)"
            )
        if not geometry:
            raise click.UsageError("the rocking model needs --width/--height or --p/--alpha")
    else:
        if building or geometry:
            raise click.UsageError(
                "the sliding block takes only --mu-s and --mu-k, not "
                + ", ".join(building + geometry)
            )
        if len(friction) != 2:
            raise click.UsageError("the sliding block needs --mu-s and --mu-k")
    return model


def _block(width, height, p, alpha, eta):
    from rockscreen.solver import RockingBlock

    if width is not None or height is not None:
        if p is not None or alpha is not None:
            raise click.UsageError("give --width/--height or --p/--alpha, not both")
        if width is None or height is None:
            raise click.UsageError("--width and --height go together")
        return RockingBlock.from_dimensions(width, height, eta=eta)
    if p is None or alpha is None:
        raise click.UsageError("--p and --alpha go together")
    return RockingBlock.from_p_alpha(p, alpha, eta=eta)


def _excitation(pulse, harmonic, record, rotation, amplitude, frequency, duration, dt, opts):
    """Return ``(acc [m/s^2], dt [s], description, free_time [s] or None)``."""
    from rockscreen.pipeline.motion.excitations import harmonic as harmonic_motion
    from rockscreen.pipeline.motion.excitations import pulse as pulse_motion

    chosen = _given(
        **{
            "--pulse": pulse,
            "--harmonic": harmonic or None,
            "--record": record,
            "--initial-rotation": rotation,
        }
    )
    if len(chosen) != 1:
        raise click.UsageError(
            "give exactly one excitation: --pulse, --harmonic, --record or --initial-rotation"
            + (f" (got {', '.join(chosen)})" if chosen else "")
        )
    if pulse is not None or harmonic:
        need = {"--amplitude": amplitude, "--frequency": frequency}
        if harmonic:
            need["--duration"] = duration
        missing = [name for name, value in need.items() if value is None]
        if missing:
            raise click.UsageError(f"{chosen[0]} needs {', '.join(missing)}")
        if pulse is not None:
            acc, step = pulse_motion(pulse, amplitude, frequency, dt=dt)
            return acc, step, f"{pulse} pulse {amplitude:g} m/s2 at {frequency:g} Hz", None
        acc, step = harmonic_motion(amplitude, frequency, duration, dt=dt)
        text = f"harmonic {amplitude:g} m/s2 at {frequency:g} Hz for {duration:g} s"
        return acc, step, text, None
    if amplitude is not None or frequency is not None:
        raise click.UsageError(f"--amplitude/--frequency do not apply to {chosen[0]}")
    if rotation is not None:
        if duration is None:
            raise click.UsageError("--initial-rotation needs --duration (free rocking time)")
        step = FREE_ROCKING_DT if dt is None else dt
        return np.zeros(1), step, f"free rocking from {rotation:g} rad", duration
    return _record(record, opts)


def _record(path, opts):
    if opts["dt"] is not None:
        raise click.UsageError("--dt does not apply to --record (the record has its own step)")
    trace, note = read_trace(
        path, units=opts["units"], stations=opts["stations"], channel=opts["channel"]
    )
    acc = np.asarray(trace.data, dtype=np.float64) * opts["scale"]
    fmt = trace.stats.rockscreen["format"]
    text = f"record {trace.id} read as {fmt} from {path}: {note}, scale {opts['scale']:g}"
    return acc, float(trace.stats.delta), text, None


def _nan_to_none(value):
    return None if isinstance(value, float) and math.isnan(value) else value


def _as_dict(model, res, description, dt):
    return {
        "model": model,
        "excitation": description,
        "dt_s": dt,
        "status": res.status,
        "overturned": res.overturned,
        "uplifted": res.uplifted,
        "slipped": res.slipped,
        "theta_max_rad": _nan_to_none(res.theta_max),
        "theta_max_over_alpha": _nan_to_none(res.theta_max_over_alpha),
        "n_impacts": res.n_impacts,
        "impact_times_s": [float(x) for x in res.impact_times],
        "t_overturn_s": _nan_to_none(res.t_overturn),
        "alpha_rad": _nan_to_none(res.alpha),
        "p_rad_s": _nan_to_none(res.p),
        "eta": _nan_to_none(res.eta),
        "sliding_max_m": res.slip_max,
        "sliding_residual_m": res.slip_residual,
        "friction_demand_max": _nan_to_none(res.friction_demand_max),
        "t_end_s": res.t_end,
        "message": res.message,
    }


def _summary(out: dict) -> str:
    lines = [
        f"model        {out['model']}"
        + (
            f" ({out['formulation']})"
            if out.get("formulation", "consistent") != "consistent"
            else ""
        ),
        f"excitation   {out['excitation']} (dt = {out['dt_s']:g} s)",
        f"status       {out['status']}: {out['message']}",
    ]
    if out["alpha_rad"] is not None:
        lines += [
            f"block        alpha = {out['alpha_rad']:.5f} rad, p = {out['p_rad_s']:.5f} rad/s, "
            f"eta = {out['eta']:.4f}",
            f"theta_max    {out['theta_max_rad']:.6g} rad = "
            f"{out['theta_max_over_alpha']:.4f} alpha"
            + (" (before overturning became certain)" if out["overturned"] else ""),
            f"impacts      {out['n_impacts']}"
            + (f" (first at {out['impact_times_s'][0]:.4f} s)" if out["n_impacts"] else ""),
        ]
        if out["friction_demand_max"] is not None:
            lines.append(
                "friction     largest |f_x/f_z| at the tower's base = "
                f"{out['friction_demand_max']:.4f}"
            )
        if out["overturned"]:
            lines.append(f"overturned   outcome certain at t = {out['t_overturn_s']:.4f} s")
    if solver_model(out["model"]).parameters:
        lines.append(
            f"sliding      max |u| = {out['sliding_max_m']:.6g} m, "
            f"residual u = {out['sliding_residual_m']:.6g} m"
        )
    lines.append(f"end          t = {out['t_end_s']:.4f} s")
    return "\n".join(lines)


@click.command("simulate")
@click.option("--width", type=float, metavar="M", help="Full base width 2b of the block [m].")
@click.option("--height", type=float, metavar="M", help="Full height 2h of the block [m].")
@click.option("--p", "p", type=float, metavar="RAD_PER_S", help="Frequency parameter p [rad/s].")
@click.option("--alpha", type=float, metavar="RAD", help="Slenderness atan(b/h) [rad].")
@click.option(
    "--eta", type=float, metavar="X", help="Restitution theta'+/theta'- (default 1 - 1.5 sin²α)."
)
@click.option("--linearized", is_flag=True, help="Small-angle equations, uplift at α·g.")
@click.option("--tower-mass", type=float, metavar="KG", help="Tower mass m [kg] (double block).")
@click.option("--building-mass", type=float, metavar="KG", help="Building mass M [kg].")
@click.option("--mu-s", type=float, metavar="X", help="Static friction of the building [-].")
@click.option("--mu-k", type=float, metavar="X", help="Kinetic friction of the building [-].")
@click.option(
    "--model", type=click.Choice(model_names(SIMULATE)), help="Model; inferred when omitted."
)
@click.option("--pulse", type=click.Choice(PULSE_SHAPES), help="Single-pulse excitation shape.")
@click.option("--harmonic", is_flag=True, help="Harmonic excitation A·cos(2πft).")
@click.option(
    "--record", type=click.Path(dir_okay=False), metavar="FILE", help="Record file to apply."
)
@click.option("--initial-rotation", type=float, metavar="RAD", help="Free rocking from θ0 [rad].")
@click.option(
    "--amplitude",
    metavar="A",
    callback=_amplitude,
    help="Peak acceleration with its unit: 0.4g, 3.92m/s2 or 392cm/s2.",
)
@click.option("--frequency", type=float, metavar="HZ", help="Pulse or harmonic frequency [Hz].")
@click.option("--duration", type=float, metavar="S", help="Harmonic or free-rocking duration [s].")
@click.option("--dt", type=float, metavar="S", help="Sampling step of synthetic input [s].")
@click.option("--channel", metavar="CHA", help="Trace of --record (default first horizontal).")
@click.option("--scale", type=float, default=1.0, show_default=True, help="Record scale factor.")
@units_option("Units of record files that carry none: g, m/s2, cm/s2.")
@stations_option("StationXML for --record: sensitivities of files in counts.")
@click.option(
    "--max-free-time",
    type=float,
    default=60.0,
    show_default=True,
    metavar="S",
    help="Longest free motion after the excitation while the outcome is undecided [s].",
)
@click.option(
    "--formulation",
    default="consistent",
    show_default=True,
    metavar="NAME",
    help="Double block only: consistent (rockscreen's), di-gennaro-2023 (the paper's eqs. "
    "(20)-(24) as printed), di-gennaro-2023-eq20, or NAME+switch=value (docs/theory.md §5).",
)
@click.option("--json", "as_json", is_flag=True, help="Print one JSON object.")
def cli(
    width, height, p, alpha, eta, linearized, tower_mass, building_mass, mu_s, mu_k, model,
    pulse, harmonic, record, initial_rotation, amplitude, frequency, duration, dt, channel,
    scale, units, stations, max_free_time, formulation, as_json,
):  # fmt: skip
    """Simulate one tower (or sliding block) under one excitation.

    Geometry by --width/--height or --p/--alpha; the double block needs all of
    --tower-mass, --building-mass, --mu-s, --mu-k; the sliding block only --mu-s/--mu-k.
    Exactly one excitation: --pulse, --harmonic, --record or --initial-rotation.
    Amplitudes always carry their unit (0.4g, 3.92m/s2).
    """
    geometry = _given(**{"--width": width, "--height": height, "--p": p, "--alpha": alpha})
    building = _given(**{"--tower-mass": tower_mass, "--building-mass": building_mass})
    friction = _given(**{"--mu-s": mu_s, "--mu-k": mu_k})
    tower_model = _resolve_model(model, geometry, building, friction)
    model = tower_model.solver_name
    if formulation != "consistent":
        from rockscreen.solver.paper_formulation import parse_formulation

        if not tower_model.paper_formulations:
            raise click.UsageError(
                f"--formulation {formulation} applies to the double block only (model is {model})"
            )
        if initial_rotation is not None:
            raise click.UsageError("--formulation other than consistent needs a base excitation")
        parse_formulation(formulation)
    if not _single_block(tower_model) and linearized:
        raise click.UsageError("--linearized applies to the rocking model only")
    if not tower_model.has_block and (eta is not None or initial_rotation is not None):
        raise click.UsageError("--eta and --initial-rotation need a rocking tower")
    opts = {"units": units, "stations": stations, "channel": channel, "scale": scale, "dt": dt}
    acc, step, description, free_time = _excitation(
        pulse, harmonic, record, initial_rotation, amplitude, frequency, duration, dt, opts
    )
    free_time = max_free_time if free_time is None else free_time
    theta0 = 0.0 if initial_rotation is None else initial_rotation
    given = {"tower_mass": tower_mass, "building_mass": building_mass, "mu_s": mu_s, "mu_k": mu_k}
    parameters = {keyword: given[keyword] for keyword in tower_model.parameters}
    if not tower_model.has_block:
        res = tower_model.solve(None, acc, step, parameters, max_free_time=free_time)
    elif formulation != "consistent":
        from rockscreen.solver.paper_formulation import solve_paper_double_block

        block = _block(width, height, p, alpha, eta)
        res = solve_paper_double_block(
            block, acc, step, **parameters, formulation=formulation, history=False,
            free_time=max(free_time, 1e-9),
        )  # fmt: skip
    else:
        block = _block(width, height, p, alpha, eta)
        extra = {"linearized": linearized} if _single_block(tower_model) else {}
        res = tower_model.solve(
            block, acc, step, parameters, theta0=theta0, max_free_time=free_time,
            history=False, **extra,
        )  # fmt: skip
    out = _as_dict(model, res, description, step)
    if tower_model.paper_formulations:
        out["formulation"] = formulation
    click.echo(json.dumps(out, indent=2) if as_json else _summary(out))
