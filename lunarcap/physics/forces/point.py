"""The Moon as a point mass (``gravity: point``): no term beyond the central attraction.

The MEE equations carry the Moon's central attraction in their Kepler part (Song 2011
Eq. A3), so this term adds no acceleration; it names the model and, for an exporter, the
Moon's field with nothing beyond its GM (J2 = 0).
"""

from __future__ import annotations

from lunarcap.physics.forces.term import MoonField, Term, zonal_c20
from lunarcap.physics.frames import moon_pole_radec_deg

#: The ``gravity`` word of a point-mass Moon.
POINT = "point"


class PointMoon(Term):
    """The Moon as a point mass: the central attraction only."""

    name = "point"

    def acts(self, forces) -> bool:
        """True for ``gravity: point``."""
        return forces.gravity == POINT

    def accelerations(self, forces) -> tuple:
        """None: the Kepler part of the MEE equations is the whole of it."""
        return ()

    def words(self, forces) -> str:
        """"point mass"."""
        return "point mass"

    def export(self, forces, model, pole: str):
        """The Moon's GM and radius, J2 = 0 about the pole of the plan's frame."""
        c, s = zonal_c20(0.0)
        return (MoonField(model.mu, model.radius, c, s, "fixed-pole", moon_pole_radec_deg(pole),
                          f"lunar point mass (Song 2011 Sec. 3.1), pole {pole}"),)
