"""The lunar J2 about the z axis of the plan's frame, Song 2011 Eq. (7) (``gravity: j2``).

The paper's zonal term: J2 = 0.2027e-3, R = 1738.2 km (:mod:`lunarcap.physics.constants`)
about the z axis of the plan's frame, M-MME2000 of the plan's lunar pole (for the paper's
plans, the Moon's pole at J2000). This module also owns the plan key ``pole`` that chooses
the axis of ``gravity: j2``: ``frame`` (this term) or ``of-date`` (the IAU pole at each
epoch, 0.79 deg from J2000's in 2017: :mod:`lunarcap.physics.forces.body_pole`).
"""

from __future__ import annotations

from lunarcap.errors import InputError
from lunarcap.physics._ops import ops
from lunarcap.physics.forces.point import POINT
from lunarcap.physics.forces.term import MoonField, Term, zonal_c20
from lunarcap.physics.frames import moon_pole_radec_deg

#: The ``gravity`` word of the zonal J2 term.
J2 = "j2"
#: The axes of ``gravity: j2`` (the plan key ``pole``).
POLES = ("frame", "of-date")


def j2_rtn(p, f, g, h, k, L, mu, radius, j2):
    """Lunar J2 acceleration in RTN, km/s^2, Eq. (7) (Kechichian 2000)."""
    xp = ops(p, f, g, h, k, L)
    cL, sL = xp.cos(L), xp.sin(L)
    q = 1 + f * cL + g * sL
    r = p / q
    s2 = 1 + h * h + k * k
    c = mu * j2 * radius ** 2 / r ** 4
    w = h * sL - k * cL
    dr = -1.5 * c * (1 - 12 * w * w / (s2 * s2))
    dt = -12 * c * w * (h * cL + k * sL) / (s2 * s2)
    dn = -6 * c * (1 - h * h - k * k) * w / (s2 * s2)
    return dr, dt, dn


class ZonalJ2(Term):
    """Lunar J2 about the z axis of the plan's frame in RTN, Eq. (7) (Kechichian 2000)."""

    name = "zonal-j2"
    keys = ("pole",)
    params = ("radius", "j2")

    def read(self, d: dict, gravity: str, base_dir=None) -> dict:
        """``pole`` (default ``of-date``), which only ``gravity: j2`` (or point) takes."""
        if gravity in (J2, POINT):
            return {"pole": d.get("pole", "of-date")}
        if "pole" in d:
            raise InputError("dynamics.pole: a gravity field turns with the Moon's body-fixed "
                             "frame (body_frame); pole is the axis of gravity: j2")
        return {}

    def check(self, forces) -> None:
        """``pole``: one of :data:`POLES`."""
        if forces.pole not in POLES:
            raise InputError(f"dynamics.pole: must be one of {', '.join(POLES)}, got "
                             f"{forces.pole!r}")

    def acts(self, forces) -> bool:
        """True for ``gravity: j2`` about the frame's pole."""
        return forces.gravity == J2 and forces.pole == "frame"

    def rtn(self, at):
        """Acceleration (a_r, a_t, a_n), km/s^2: :func:`j2_rtn`."""
        return j2_rtn(at.p, at.f, at.g, at.h, at.k, at.L, at.prm_of("mu"),
                      at.prm_of("radius"), at.prm_of("j2"))

    def values(self, forces, model) -> dict:
        """The model's lunar radius (km) and J2."""
        return {"radius": model.radius, "j2": model.j2}

    def words(self, forces) -> str:
        """"J2 about the frame pole"."""
        return "J2 about the frame pole"

    def to_plan(self, forces) -> dict:
        """``pole``, for ``gravity: j2`` (either axis)."""
        return {"pole": forces.pole} if forces.gravity == J2 else {}

    def export(self, forces, model, pole: str):
        """J2 (C20) about the pole of the plan's frame, fixed in the axes."""
        c, s = zonal_c20(model.j2)
        return (MoonField(model.mu, model.radius, c, s, "fixed-pole", moon_pole_radec_deg(pole),
                          f"lunar point mass + J2 (Song 2011 Sec. 3.1), pole {pole}"),)
