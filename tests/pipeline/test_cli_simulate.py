"""``rockscreen simulate`` reproduces REFERENCES R1, R3, R4, R5 and R6 through --json."""

from __future__ import annotations

import json
import math

import pytest
from click.testing import CliRunner

from rockscreen.pipeline.cli import main

ALPHA_15 = repr(math.radians(15.0))


def simulate(line, *args):
    """``rockscreen simulate`` with the options of ``line`` (split at spaces) and ``args``."""
    return CliRunner().invoke(main, ["simulate", *line.split(), *args])


def _run(line, *args):
    result = simulate(line, *args, "--json")
    assert result.exit_code == 0, result.output
    return json.loads(result.output)


def test_r1_free_rocking_period():
    # Housner 1963 / REFERENCES R1: p = 2, alpha = 0.25, theta0 = 0.5 alpha, no loss:
    # T = 2.63875 s (5 digits); the first impact comes after T/4.
    out = _run("--p 2 --alpha 0.25 --eta 1 --initial-rotation 0.125 --duration 6")
    assert 4 * out["impact_times_s"][0] == pytest.approx(2.63875, rel=2e-5)
    assert out["status"] == "moving_at_end" and out["t_end_s"] == pytest.approx(6.0)
    expected_keys = {
        "overturned",
        "status",
        "theta_max_rad",
        "theta_max_over_alpha",
        "n_impacts",
        "impact_times_s",
        "alpha_rad",
        "p_rad_s",
        "eta",
        "sliding_max_m",
        "sliding_residual_m",
        "t_end_s",
    }
    assert expected_keys <= set(out)


@pytest.mark.parametrize(
    ("amplitude", "overturns"), [("0.310g", False), ("0.315g", False), ("0.316g", True)]
)
def test_r3_one_cosine(amplitude, overturns):
    # Makris & Konstantinidis 2003 (REFERENCES R3): 0.310 g and 0.315 g survive, 0.316 g
    # overturns; p = 2, alpha = 15 deg, default eta = 0.8995, f = 0.5 Hz.
    out = _run(
        f"--p 2 --alpha {ALPHA_15} --pulse one-cosine --amplitude {amplitude} --frequency 0.5"
    )
    assert out["overturned"] is overturns
    assert out["eta"] == pytest.approx(0.8995, abs=1e-4)


@pytest.mark.parametrize(("factor", "overturns"), [(0.998, False), (1.002, True)])
def test_r4_one_sine_mode2_linearized(factor, overturns):
    # Zhang & Makris 2001 eq. 47 (REFERENCES R4): w_p/p = 8, a_p/(alpha g) = 14.871 is the
    # minimum overturning amplitude (eta = 0.9); tested 0.2 % either side.
    alpha, p = 0.1, 2.0
    freq = 8 * p / (2 * math.pi)
    amplitude = f"{factor * 14.871 * alpha!r}g"
    out = _run(
        f"--p {p} --alpha {alpha} --eta 0.9 --linearized"
        f" --pulse one-sine --amplitude {amplitude} --frequency {freq!r}"
    )
    assert out["overturned"] is overturns


@pytest.mark.parametrize(("factor", "overturns"), [(0.995, False), (1.005, True)])
def test_r5_rectangular_pulse(factor, overturns):
    # Housner rectangular pulse (REFERENCES R5): A = 2, p = 2, alpha = 0.2, critical
    # duration 0.346574 s; the pulse lasts 1/(2f). Tested 0.5 % either side at dt = 0.1 ms.
    duration = factor * 0.346574
    out = _run(
        "--p 2 --alpha 0.2 --linearized --pulse rectangular --amplitude 0.4g --dt 1e-4",
        "--frequency",
        repr(0.5 / duration),
    )
    assert out["overturned"] is overturns


def test_r6_newmark_sliding():
    # Newmark 1965 (REFERENCES R6): A = 0.5, N = 0.2, t0 = 0.5 s -> u = 0.919687 m.
    out = _run("--mu-s 0.2 --mu-k 0.2 --pulse rectangular --amplitude 0.5g --frequency 1")
    assert out["model"] == "sliding"
    assert abs(out["sliding_residual_m"]) == pytest.approx(0.919687, rel=1e-6)
    assert out["sliding_max_m"] == pytest.approx(0.919687, rel=1e-6)


def test_double_block_inferred_and_text_summary():
    result = simulate(
        "--width 2.06 --height 5.80 --eta 0.9 --tower-mass 34557 --building-mass 9871628"
        " --mu-s 1 --mu-k 0.7 --harmonic --amplitude 0.4g --frequency 3 --duration 2"
    )
    assert result.exit_code == 0, result.output
    assert "double-block" in result.output and "rad" in result.output and " m" in result.output


@pytest.mark.parametrize(
    ("args", "message"),
    [
        ("--p 2 --alpha 0.2 --pulse one-sine --amplitude 0.4 --frequency 1", "has no unit"),
        ("--p 2 --alpha 0.2 --mu-s 0.5", "building"),
        (
            "--p 2 --alpha 0.2 --tower-mass 1 --pulse one-sine --amplitude 1g --frequency 1",
            "missing",
        ),
        (
            "--p 2 --alpha 0.2 --pulse one-sine --harmonic --amplitude 1g --frequency 1",
            "exactly one excitation",
        ),
        (
            "--p 2 --alpha 0.2 --width 1 --height 3 --initial-rotation 0.1 --duration 1",
            "not both",
        ),
        (
            "--p 2 --alpha 0.2 --harmonic --amplitude 1g --frequency 1",
            "--duration",
        ),
        (
            "--mu-s 0.2 --mu-k 0.2 --linearized --pulse one-sine --amplitude 1g --frequency 1",
            "--linearized",
        ),
    ],
)
def test_usage_errors(args, message):
    result = simulate(args)
    assert result.exit_code == 2
    assert message in result.output


def test_solver_parameter_error_is_one_line():
    result = simulate("--p 2 --alpha 0.2 --eta 1.5 --initial-rotation 0.1 --duration 1")
    assert result.exit_code == 1
    assert result.output.strip().count("\n") == 0 and "eta=1.5" in result.output


@pytest.mark.data
def test_real_record(shared_data):
    folder = shared_data / "laquila2009"
    out = _run(
        "--width 3 --height 20",
        "--record",
        str(folder / "IT.AQV..HNE.mseed"),
        "--stations",
        str(folder / "stations.xml"),
    )
    assert out["status"] in ("came_to_rest", "overturned", "no_motion")
    assert "MSEED" in out["excitation"]
    assert out["dt_s"] == pytest.approx(0.005)


def test_formulation_runs_the_papers_equations_for_the_double_block():
    args = (
        "--width 2.06 --height 5.80 --eta 0.9 --tower-mass 34568 --building-mass 9875000"
        " --mu-s 1 --mu-k 0.7 --harmonic --amplitude 0.5g --frequency 3 --duration 1"
    )
    consistent = _run(args)
    paper = _run(args, "--formulation", "di-gennaro-2023-eq20")
    assert consistent["formulation"] == "consistent" and consistent["theta_max_rad"] > 0.005
    assert paper["formulation"] == "di-gennaro-2023-eq20" and paper["theta_max_rad"] == 0.0
    result = simulate(args, "--formulation", "nope")
    assert result.exit_code != 0 and "is not one of" in result.output
    rocking = "--width 2.06 --height 5.80 --harmonic --amplitude 0.4g --frequency 3"
    result = simulate(rocking, "--formulation", "di-gennaro-2023")
    assert result.exit_code == 2 and "double block only" in result.output
