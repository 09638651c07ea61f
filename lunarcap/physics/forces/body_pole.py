"""The lunar J2 about the Moon's body pole (``gravity: j2, pole: of-date``, and a field's C20).

With e the body pole, (e_r, e_t, e_n) its RTN components and c = mu J2 R^2 / r^4, the
acceleration is the gradient of U = -mu J2 R^2 / (2 r^3) (3 (r.e)^2 / r^2 - 1):

    a = -3/2 c (1 - 3 e_r^2) i_r - 3 c e_r (e_t i_t + e_n i_n);

Song 2011 Eq. (7) is its case e = z. The pole is the IAU pole of date (the IAU 2009
rotation model, from the ephemeris fit); a spherical-harmonic field carries its own C20 as
this term in the field's body frame (:mod:`lunarcap.physics.forces.harmonics`).
"""

from __future__ import annotations

from dataclasses import replace

from lunarcap.physics.forces.term import Term
from lunarcap.physics.forces.zonal_j2 import J2, ZonalJ2


class BodyPoleJ2(Term):
    """J2 about the Moon's body pole: the IAU pole of date, or a field's body frame."""

    name = "body-pole-j2"
    params = ("radius", "j2")

    def acts(self, forces) -> bool:
        """True for ``gravity: j2`` about the pole of date (a field carries it itself)."""
        return forces.gravity == J2 and forces.pole == "of-date"

    def rtn(self, at):
        """Acceleration (a_r, a_t, a_n), km/s^2 (the module docstring's formula)."""
        er, et, en = (b[2] for b in at.body_rtn)
        r = at.r
        c = at.prm_of("mu") * at.prm_of("j2") * at.prm_of("radius") ** 2 / r ** 4
        return (-1.5 * c * (1 - 3 * er * er), -3 * c * er * et, -3 * c * er * en)

    def values(self, forces, model) -> dict:
        """The model's lunar radius (km) and J2."""
        return {"radius": model.radius, "j2": model.j2}

    def rotation(self, forces) -> str:
        """The IAU (2009) orientation of the Moon."""
        return "iau2009"

    def words(self, forces) -> str:
        """"J2 about the pole of date"."""
        return "J2 about the pole of date"

    def export(self, forces, model, pole: str):
        """J2 (C20) in the IAU body frame of date."""
        (frame_j2,) = ZonalJ2().export(forces, model, pole)
        return (replace(frame_j2, frame="iau2009",
                        source=frame_j2.source + " (J2 about the pole of date)"),)
