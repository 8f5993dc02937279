"""The double block: a tower rocking on a building that sticks or slides on its foundation."""

from __future__ import annotations

import math

from rockscreen.solver.block import RockingBlock
from rockscreen.solver.docstrings import fill_doc
from rockscreen.solver.errors import ParameterError
from rockscreen.solver.response import Response
from rockscreen.solver.rocking import TOWER_DOCS, RunOptions, check_base_motion, run_kernel
from rockscreen.solver.validation import check_friction, check_positive

#: Parameter descriptions of the double-block solvers (also
#: :func:`solver.paper_formulation.solve_paper_double_block`'s): the tower solvers' and the
#: building's.
DOUBLE_BLOCK_DOCS = {
    **TOWER_DOCS,
    "building": """\
tower_mass, building_mass : float
    Masses m and M [kg], > 0.
mu_s, mu_k : float
    Static and kinetic friction of the building on its foundation [-],
    ``0 <= mu_k <= mu_s``.""",
}


def check_building(*, tower_mass: float, building_mass: float, mu_s: float, mu_k: float) -> float:
    """Check the building's masses [kg] and friction [-] (its keywords); return m / (M + m) [-]."""
    check_positive("tower_mass", tower_mass, "kg")
    check_positive("building_mass", building_mass, "kg")
    check_friction(mu_s, mu_k)
    return tower_mass / (tower_mass + building_mass)


def check_coupling(block: RockingBlock, mass_ratio: float, mu_k: float) -> None:
    """Raise if the coupled sliding-rocking equations can lose their unique solution.

    The determinant of the regime-3 system is
    ``1 - r (m R^2/I_O) cos(phi) (cos(phi) + mu_k s_u sin(phi))`` with ``r = m/(M+m)``;
    its smallest value over all angles is ``1 - r (m R^2/I_O) (1 + sqrt(1 + mu_k^2))/2``.
    When that is not positive the Coulomb model is inconsistent (Painleve's paradox).
    """
    worst = 1.0 - mass_ratio * block.inertia_ratio * 0.5 * (1.0 + math.sqrt(1.0 + mu_k * mu_k))
    if not worst > 0.0:
        raise ParameterError(
            f"tower_mass/(tower_mass+building_mass)={mass_ratio!r} with mu_k={mu_k!r}: the "
            "rocking-sliding equations have no unique solution (Painleve paradox); the "
            "building must be heavier relative to the tower, or mu_k smaller"
        )


@fill_doc(DOUBLE_BLOCK_DOCS)
def solve_double_block(
    block: RockingBlock,
    acc,
    dt: float,
    *,
    tower_mass: float,
    building_mass: float,
    mu_s: float,
    mu_k: float,
    **options,
) -> Response:
    """Integrate a tower rocking on a building that slides on its foundation (docs/theory.md).

    Parameters
    ----------
    block : RockingBlock
        The tower.
    %(motion)s
    %(building)s
    %(options)s

    Returns
    -------
    Response
        Tower rotation, building slip ``u`` relative to the ground, regimes (0 rest,
        1 tower rocking, 2 building sliding, 3 both).
    """
    run = RunOptions.from_keywords("solve_double_block", options)
    motion = check_base_motion(block, acc, dt, run.acc_v, run.scale)
    mass_ratio = check_building(
        tower_mass=tower_mass, building_mass=building_mass, mu_s=mu_s, mu_k=mu_k
    )
    check_coupling(block, mass_ratio, mu_k)
    return run_kernel(
        block, motion, run, mass_ratio=mass_ratio, mu_s=mu_s, mu_k=mu_k, can_slide=True
    )
