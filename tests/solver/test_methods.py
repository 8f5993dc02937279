"""The table of solver methods (``solver/methods.py``)."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest

from rockscreen import solver
from rockscreen.solver.constants import G
from rockscreen.solver.methods import DEFAULT_METHOD, METHOD_NAMES, get_method


def test_the_compiled_method_is_the_default_and_its_solvers_are_the_public_ones():
    assert DEFAULT_METHOD == "compiled" and DEFAULT_METHOD in METHOD_NAMES
    method = get_method()
    assert method.name == "compiled"
    assert method.rocking is solver.solve_rocking
    assert method.double_block is solver.solve_double_block
    assert method.sliding is solver.solve_sliding


def test_an_unknown_method_names_the_allowed_ones():
    with pytest.raises(ValueError, match="'nope'.*compiled"):
        get_method("nope")


def test_importing_the_table_loads_no_numba():
    code = (
        "import sys, rockscreen.solver.methods; "
        "print('numba' in sys.modules, 'rockscreen.solver.kernel' in sys.modules)"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["False", "False"]


# ------------------------------------------------------------------ the reference method

DT = 0.0025


def _harmonic(amplitude_g: float, frequency_hz: float, duration_s: float) -> np.ndarray:
    t = np.arange(int(round(duration_s / DT)) + 1) * DT
    return amplitude_g * G * np.cos(2.0 * np.pi * frequency_hz * t)


def test_the_reference_method_is_the_oracle_with_the_compiled_api():
    # A slender tower under 3 cycles: it rocks without overturning (test_reference's setting).
    block = solver.RockingBlock.from_dimensions(1.0, 8.0, eta=0.98)
    acc = _harmonic(0.2, 2.0, 1.5)
    reference, compiled = get_method("reference"), get_method("compiled")
    ref = reference.rocking(block, acc, DT, history=True)
    res = compiled.rocking(block, acc, DT, history=True)
    assert isinstance(ref, solver.Response)
    assert ref.status == res.status and ref.overturned == res.overturned
    assert ref.theta_max == pytest.approx(res.theta_max, rel=5e-3)
    assert (ref.alpha, ref.p, ref.eta) == (block.alpha, block.p, block.eta)
    # What the oracle does not compute is NaN, and the message names the oracle.
    assert np.isnan(ref.friction_demand_max) and "reference" in ref.message
    # Histories on the input grid k*dt up to t_end, as the compiled solvers give them.
    assert ref.t[0] == 0.0 and np.allclose(np.diff(ref.t), DT)
    assert ref.t[-1] <= ref.t_end < ref.t[-1] + DT
    assert len(ref.theta) == len(ref.regime) == len(ref.t) and ref.regime.dtype == np.int8
    assert np.max(np.abs(ref.theta)) == pytest.approx(ref.theta_max, rel=1e-2)


def test_the_reference_method_scales_like_the_compiled_one():
    block = solver.RockingBlock.from_dimensions(1.0, 8.0, eta=0.98)
    acc = _harmonic(0.1, 2.0, 1.5)
    method = get_method("reference")
    scaled = method.rocking(block, acc, DT, scale=2.0, history=False)
    plain = method.rocking(block, 2.0 * acc, DT, history=False)
    assert scaled.theta_max == plain.theta_max and scaled.t is None


def test_the_reference_method_refuses_the_compiled_controls():
    block = solver.RockingBlock.from_dimensions(1.0, 8.0)
    with pytest.raises(TypeError, match="rest_tolerance"):
        get_method("reference").rocking(block, np.zeros(4), DT, rest_tolerance=1e-6)
