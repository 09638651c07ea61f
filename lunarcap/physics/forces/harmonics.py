"""A spherical-harmonic gravity field of the Moon (``gravity: LP165P`` or a file's path).

A field (:mod:`lunarcap.physics.gravity`: the packaged ``LP165P``, or a ``.cof`` or PDS
SHADR file) of ``degree`` and ``order`` in the Moon's body-fixed frame ``body_frame``
(``de405``: the DE405 libration angles, the principal-axis frame GMAT's ``Luna`` uses;
``iau2009``: the IAU rotation model; the two frames are 92-109 arcsec apart over 2017,
0.82-0.97 km at 100 km altitude, measured). Its C20 acts as the J2 term about the body's
pole (J2 = -sqrt(5) C20, with the field's radius:
:class:`~lunarcap.physics.forces.body_pole.BodyPoleJ2`); its other terms by the Cunningham
recursion (:func:`lunarcap.physics.gravity.sh_acceleration`), projected on RTN.

The central GM is the plan's (Song 2011's 4902.800 km^3/s^2), and the harmonics are scaled
by it too, not by the field's own GM (4902.801 for LP165P): one GM acts, as in GMAT, whose
field file then carries lunarcap's; the 2e-7 relative difference would move the spacecraft
91 m along track per 12 h orbit.
"""

from __future__ import annotations

from lunarcap.errors import InputError
from lunarcap.physics.ephemeris import BODY_FRAMES
from lunarcap.physics.forces.body_pole import BodyPoleJ2
from lunarcap.physics.forces.point import POINT
from lunarcap.physics.forces.term import MoonField, Term
from lunarcap.physics.forces.zonal_j2 import J2
from lunarcap.physics.gravity import PACKAGED, GravityField, load_field, sh_acceleration

#: The plan keys only a field takes.
FIELD_KEYS = ("degree", "order", "body_frame")


class Cunningham:
    """A field's terms other than C20, in the body-fixed frame (:func:`sh_acceleration`)."""

    params = ()

    def __init__(self, field: GravityField, degree: int, order: int):
        self.field, self.degree, self.order = field, degree, order

    def rtn(self, at):
        """Acceleration (a_r, a_t, a_n), km/s^2."""
        br, bt, bn = at.body_rtn
        xb, yb, zb = (at.r * br[a] for a in range(3))
        f = self.field
        ab = sh_acceleration(xb, yb, zb, f.C, f.S, f.radius_km, at.prm_of("mu"), self.degree,
                             self.order, skip_c20=True)
        return tuple(b[0] * ab[0] + b[1] * ab[1] + b[2] * ab[2] for b in (br, bt, bn))


def _integer(where: str, v, lo: int, hi: int, why: str) -> None:
    if isinstance(v, bool) or not isinstance(v, int) or not lo <= v <= hi:
        raise InputError(f"{where}: an integer from {lo} to {hi} ({why}), got {v!r}")


class Harmonics(Term):
    """A spherical-harmonic field: its C20 as J2 about the body pole, then Cunningham's terms."""

    name = "harmonics"
    keys = FIELD_KEYS

    def read(self, d: dict, gravity: str, base_dir=None) -> dict:
        """The field named by ``gravity``, its ``degree``, ``order`` and ``body_frame``.

        The field is loaded (a packaged name, or a path relative to ``base_dir``); the
        degree is required, the order defaults to it, the frame to ``de405``. These keys
        are refused for ``gravity: point`` or ``j2``.
        """
        if gravity in (POINT, J2):
            extra = sorted(set(FIELD_KEYS) & set(d))
            if extra:
                raise InputError(f"dynamics.{extra[0]}: only a gravity field takes it "
                                 f"(gravity is {gravity})")
            return {}
        try:
            field = load_field(gravity, base_dir)
        except InputError as exc:
            raise InputError(f"dynamics.gravity: {exc}") from None
        if "degree" not in d:
            raise InputError(f"dynamics.degree: missing (the field {field.name} goes to "
                             f"{field.degree})")
        return {"gravity": gravity if gravity in PACKAGED else field.source,
                "degree": d["degree"], "order": d.get("order", d["degree"]),
                "body_frame": d.get("body_frame", "de405")}

    def check(self, forces) -> None:
        """``body_frame`` one of the Moon's frames; a field's ``degree`` and ``order`` its own."""
        if forces.body_frame not in BODY_FRAMES:
            raise InputError(f"dynamics.body_frame: must be one of {', '.join(BODY_FRAMES)}, "
                             f"got {forces.body_frame!r}")
        if forces.is_field:
            f = forces.field
            _integer("dynamics.degree", forces.degree, 2, f.degree,
                     f"the field {f.name} goes to degree {f.degree}")
            _integer("dynamics.order", forces.order, 0, min(forces.degree, f.order),
                     f"at most the degree, and the field's order {f.order}")

    def acts(self, forces) -> bool:
        """True for a field."""
        return forces.is_field

    def accelerations(self, forces) -> tuple:
        """C20 as J2 about the body pole, then (above 2 x 0) the other terms."""
        if (forces.degree, forces.order) == (2, 0):
            return (BodyPoleJ2(),)
        return (BodyPoleJ2(), Cunningham(forces.field, forces.degree, forces.order))

    def values(self, forces, model) -> dict:
        """The field's radius (km) and J2 (-sqrt(5) C20): its C20 term's parameters."""
        return {"radius": forces.field.radius_km, "j2": forces.field.j2}

    def rotation(self, forces) -> str:
        """The field's body frame."""
        return forces.body_frame

    def words(self, forces) -> str:
        """"LP165P 20x20 (de405)"."""
        return f"{forces.field.name} {forces.degree}x{forces.order} ({forces.body_frame})"

    def to_plan(self, forces) -> dict:
        """``degree``, ``order``, ``body_frame`` of a field."""
        if not forces.is_field:
            return {}
        return {"degree": forces.degree, "order": forces.order, "body_frame": forces.body_frame}

    def export(self, forces, model, pole: str):
        """The whole field (its C20 too) to its degree and order, the orders above zeroed."""
        f, n = forces.field, forces.degree
        c, s = f.C[:n + 1, :n + 1].copy(), f.S[:n + 1, :n + 1].copy()
        c[:, forces.order + 1:], s[:, forces.order + 1:] = 0.0, 0.0
        return (MoonField(model.mu, f.radius_km, c, s, forces.body_frame,
                          source=f"{forces.label} ({f.name}, Konopliv et al. 2001 for "
                                 f"LP165P); GM lunarcap's"),)
