"""Rocking, sliding and double-block dynamics of rigid blocks on a moving base.

Pure numerics: arrays of base acceleration [m/s^2] with their sampling step
``dt`` [s] go in, result objects come out. This package never imports
``rockscreen.pipeline``, ``rockscreen.stations``, ObsPy or h5py.

Public API::

    RockingBlock.from_dimensions(width, height, *, eta=None)
    RockingBlock.from_p_alpha(p, alpha, *, eta=None)
    RockingBlock.from_section(width, height, *, radius=None, inertia_per_mass=None, eta=None)
    solve_rocking(block, acc, dt, *, linearized=False, acc_v=None, theta0=0.0, ...)
    solve_sliding(acc, dt, *, mu_s, mu_k, acc_v=None, history=True)
    solve_double_block(block, acc, dt, *, tower_mass, building_mass, mu_s, mu_k, ...)
    critical_friction_for_rocking(accel_ratio, alpha)

The numerical core (:mod:`rockscreen.solver.kernel`) is compiled by numba on first use and
cached on disk (:mod:`rockscreen.solver.cache`: a per-user folder, never site-packages), so only
the first call of a fresh installation pays the compile time.
"""

# First: importing rockscreen.solver.cache points numba's cache away from site-packages.
from rockscreen.solver import cache as _cache  # noqa: F401
from rockscreen.solver.lazy import lazy_exports

#: The public names and the modules that define them, loaded on first use (PEP 562), so
#: that ``solver.constants`` or ``solver.errors`` can be imported without numba.
_EXPORTS = {
    "ParameterError": "rockscreen.solver.errors",
    "Response": "rockscreen.solver.response",
    "RockingBlock": "rockscreen.solver.block",
    "critical_friction_for_rocking": "rockscreen.solver.sliding",
    "solve_double_block": "rockscreen.solver.double_block",
    "solve_rocking": "rockscreen.solver.rocking",
    "solve_sliding": "rockscreen.solver.sliding",
}

__all__ = sorted(_EXPORTS)


__getattr__, __dir__ = lazy_exports("rockscreen.solver", _EXPORTS, globals())
