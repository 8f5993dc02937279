"""Reference (oracle) integration of the rocking, sliding and double-block equations.

An independent, plain-Python implementation of the equations agreed for rockscreen
(``docs/theory.md``) with :func:`scipy.integrate.solve_ivp` and events. It is slow on
purpose-built terms: every sample interval of the record is integrated by its own
``solve_ivp`` call (DOP853, ``rtol=1e-10``, ``atol=1e-12``) so that the piecewise-linear
base acceleration is smooth inside every call, and every event (uplift, impact, rest,
stick/slip, overturning) is located by the integrator's root finder, never snapped to a
sample. Rest phases are not integrated: the next onset of motion is found exactly on
the piecewise-linear record.

It serves two purposes: the accuracy oracle for the compiled solver (``tests/solver``)
and the speed baseline of ``benchmarks/solver_bench.py``. It shares no code with the
compiled solver (only :mod:`rockscreen.solver.constants`, :mod:`rockscreen.solver.errors`,
:func:`rockscreen.solver.docstrings.fill_doc` and the outcome fields of
:class:`rockscreen.solver.response.Outcome`).

Conventions
-----------
- ``acc``, ``acc_v``: base acceleration [m/s^2] at ``t_k = k*dt``, linear between
  samples, **zero from the last sample on** (the excitation ends at ``(n-1)*dt``).
- theta > 0: tower tilted about its right corner; ``s = sgn(theta)``,
  ``phi = alpha*s - theta``; ``g_e = g + acc_v``.
- Rocking: ``theta'' = -(p^2/g) [g_e sin(phi) + a_b cos(phi)]``; linearized
  ``theta'' = p^2 [(g_e/g)(theta - alpha s) - a_b/g]``. Uplift from rest when
  ``|a_b| > g_e tan(alpha)`` (linearized ``g_e alpha``); ``a_b > 0`` starts ``theta < 0``.
- Impact at ``theta = 0``: ``theta'+ = eta theta'-`` (``eta`` is the angular-velocity
  ratio), building velocity unchanged. **Rest (Zeno)**: after an impact with
  ``|theta'+| < rest_fraction * p * alpha`` the tower is at rest (theta = theta' = 0)
  and waits for a new uplift test; with the default ``rest_fraction = 1e-4`` the next
  swing would reach less than about 1e-8 alpha.
- Overturning: during the excitation only when ``|theta| >= pi/2``. In free motion
  (excitation over, building stuck) the energy barrier decides: a swing moving outward
  (or leaving an impact) with ``theta'^2 >= 2 p^2 (1 - cos(alpha - |theta|))``
  (linearized ``theta'^2 >= p^2 (alpha - |theta|)^2``), or ``|theta| > alpha`` while
  moving outward, overturns. After the excitation the integration goes on until rest,
  overturning, or ``t_free`` seconds, whichever comes first.
- Double block: building mass ``M``, tower mass ``m``, corner inertia
  ``I_O = m g R / p^2``; regimes 0 rest, 1 tower rocking on the stuck building,
  2 building sliding with the tower at rest, 3 both. Equations as in ``docs/theory.md``.
"""

from rockscreen.solver.reference.api import (
    reference_double_block,
    reference_rocking,
    reference_sliding,
)
from rockscreen.solver.reference.model import ATOL, REST_FRACTION, RTOL, T_FREE, ReferenceResult

__all__ = [
    "ATOL",
    "REST_FRACTION",
    "RTOL",
    "T_FREE",
    "ReferenceResult",
    "reference_double_block",
    "reference_rocking",
    "reference_sliding",
]
