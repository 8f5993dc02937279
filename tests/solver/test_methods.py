"""The table of solver methods (``solver/methods.py``)."""

from __future__ import annotations

import subprocess
import sys

import pytest

from rockscreen import solver
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
