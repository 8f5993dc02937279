"""Geometry and dynamic constants of a rigid rocking block (the tower)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from rockscreen.solver.constants import G
from rockscreen.solver.errors import ParameterError
from rockscreen.solver.validation import check_alpha, check_eta, check_positive


@dataclass(frozen=True)
class RockingBlock:
    """A rigid block rocking about its base corners.

    Build it with :meth:`from_dimensions`, :meth:`from_p_alpha` or :meth:`from_section`.
    """

    #: Slenderness angle between the vertical and the line from a base corner to the centre of mass
    #: [rad], ``0 < alpha < pi/2``.
    alpha: float
    #: Distance R from a base corner to the centre of mass [m].
    radius: float
    #: Polar moment of inertia about a base corner divided by the mass, I_O/m [m^2].
    inertia_per_mass: float
    #: Frequency parameter ``sqrt(g R / (I_O/m))`` [rad/s].
    p: float
    #: Angular-velocity restitution ``theta_dot+ / theta_dot-`` at each impact [-], in (0, 1]. Its
    #: square is the kinetic-energy ratio (Housner's "r").
    eta: float
    #: Full base width 2b and full height 2h [m] when known, else NaN.
    width: float = math.nan
    height: float = math.nan

    @property
    def inertia_ratio(self) -> float:
        """Return m R^2 / I_O [-] (3/4 for a solid rectangle)."""
        return self.radius**2 / self.inertia_per_mass

    @staticmethod
    def housner_eta(alpha: float, inertia_ratio: float = 0.75) -> float:
        """Return Housner's angular-velocity restitution ``1 - 2 (m R^2/I_O) sin^2(alpha)`` [-].

        It follows from conservation of angular momentum about the impacting corner
        (Housner 1963); for a solid rectangle ``m R^2/I_O = 3/4`` and
        ``eta = 1 - 1.5 sin^2(alpha)``.
        """
        return 1.0 - 2.0 * inertia_ratio * math.sin(alpha) ** 2

    @classmethod
    def from_dimensions(cls, width: float, height: float, *, eta: float | None = None):
        """Solid rectangular block from its full base width 2b [m] and full height 2h [m].

        Parameters
        ----------
        width : float
            Full base width 2b [m], > 0.
        height : float
            Full height 2h [m], > 0.
        eta : float, optional
            Angular-velocity restitution [-] in (0, 1]; default ``1 - 1.5 sin^2(alpha)``.
        """
        return cls.from_section(width, height, eta=eta)

    @classmethod
    def from_p_alpha(cls, p: float, alpha: float, *, eta: float | None = None):
        """Solid rectangular block from its frequency parameter p [rad/s] and slenderness [rad].

        Parameters
        ----------
        p : float
            Frequency parameter ``sqrt(3 g / (4 R))`` [rad/s], > 0.
        alpha : float
            Slenderness ``atan(b/h)`` [rad], 0 < alpha < pi/2.
        eta : float, optional
            Angular-velocity restitution [-] in (0, 1]; default ``1 - 1.5 sin^2(alpha)``.
        """
        check_positive("p", p, "rad/s")
        check_alpha(alpha)
        radius = 3.0 * G / (4.0 * p * p)
        width = 2.0 * radius * math.sin(alpha)
        height = 2.0 * radius * math.cos(alpha)
        return cls._build(alpha, radius, 4.0 / 3.0 * radius**2, eta, width, height)

    @classmethod
    def from_section(
        cls,
        width: float,
        height: float,
        *,
        radius: float | None = None,
        inertia_per_mass: float | None = None,
        eta: float | None = None,
    ):
        """Block with a symmetric but not necessarily solid section (a hollow masonry shaft).

        The centre of mass lies on the vertical axis of symmetry, at distance R from
        each base corner, so ``alpha = asin(b/R)``.

        Parameters
        ----------
        width : float
            Full base width 2b [m], > 0.
        height : float
            Full height 2h [m], > 0 (used for the default R only).
        radius : float, optional
            Distance R from a base corner to the centre of mass [m], > b; default
            ``sqrt(b^2 + h^2)`` (centre of mass at mid-height).
        inertia_per_mass : float, optional
            Moment of inertia about a base corner divided by the mass, I_O/m [m^2], > R^2
            (parallel-axis theorem); default ``4/3 R^2`` (solid rectangle).
        eta : float, optional
            Angular-velocity restitution [-] in (0, 1]; default ``1 - 2 (m R^2/I_O) sin^2(alpha)``.
        """
        check_positive("width", width, "m")
        check_positive("height", height, "m")
        b, h = 0.5 * width, 0.5 * height
        if radius is None:
            radius = math.hypot(b, h)
        check_positive("radius", radius, "m")
        if not radius > b:
            raise ParameterError(
                f"radius={radius!r} m must exceed the half-width b={b!r} m "
                "(the centre of mass lies above the base)"
            )
        if inertia_per_mass is None:
            inertia_per_mass = 4.0 / 3.0 * radius**2
        check_positive("inertia_per_mass", inertia_per_mass, "m^2")
        if not inertia_per_mass > radius**2:
            raise ParameterError(
                f"inertia_per_mass={inertia_per_mass!r} m^2 must exceed R^2={radius**2!r} m^2 "
                "(corner inertia = centroidal inertia + m R^2)"
            )
        alpha = math.asin(b / radius)
        return cls._build(alpha, radius, inertia_per_mass, eta, float(width), float(height))

    @classmethod
    def _build(cls, alpha, radius, inertia_per_mass, eta, width, height):
        if eta is None:
            eta = cls.housner_eta(alpha, radius**2 / inertia_per_mass)
            if not eta > 0.0:
                raise ParameterError(
                    f"the default restitution 1 - 2 (m R^2/I_O) sin^2(alpha) = {eta!r} is not "
                    "in (0, 1]; the block is too stocky for Housner's impact law: give eta"
                )
        check_eta(eta)
        p = math.sqrt(G * radius / inertia_per_mass)
        # Every field a float, in the order they are declared.
        return cls(*map(float, (alpha, radius, inertia_per_mass, p, eta, width, height)))
