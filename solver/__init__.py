"""Rocking, sliding and double-block dynamics of rigid blocks on a moving base.

Pure numerics: arrays of base acceleration [m/s^2] with their sampling step
``dt`` [s] go in, result objects come out. This package never imports
``pipeline``, ``stations``, ObsPy or h5py.

Public API::

    RockingBlock.from_dimensions(width, height, *, eta=None)
    RockingBlock.from_p_alpha(p, alpha, *, eta=None)
    RockingBlock.from_section(width, height, *, radius=None, inertia_per_mass=None, eta=None)
    solve_rocking(block, acc, dt, *, linearized=False, acc_v=None, theta0=0.0, ...)
    solve_sliding(acc, dt, *, mu_s, mu_k, acc_v=None, history=True)
    solve_double_block(block, acc, dt, *, tower_mass, building_mass, mu_s, mu_k, ...)
    critical_friction_for_rocking(accel_ratio, alpha)

The numerical core (:mod:`solver.kernel`) is compiled by numba on first use and
cached on disk (:mod:`solver.cache`: a per-user folder, never site-packages), so only
the first call of a fresh installation pays the compile time.
"""

# First: importing solver.cache points numba's cache away from site-packages.
from solver import cache as _cache  # noqa: F401
from solver.lazy import lazy_exports

#: The public names and the modules that define them, loaded on first use (PEP 562), so
#: that ``solver.constants`` or ``solver.errors`` can be imported without numba.
_EXPORTS = {
    "ParameterError": "solver.errors",
    "Response": "solver.response",
    "RockingBlock": "solver.block",
    "critical_friction_for_rocking": "solver.sliding",
    "solve_double_block": "solver.double_block",
    "solve_rocking": "solver.rocking",
    "solve_sliding": "solver.sliding",
}

__all__ = sorted(_EXPORTS)


__getattr__, __dir__ = lazy_exports("solver", _EXPORTS, globals())
