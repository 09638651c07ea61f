"""The forces on the spacecraft, as terms composed per plan (Song 2011 Eqs. 4, 6, 7, and more).

A :class:`ForceModel` says which terms act besides the Moon's central attraction (which
the MEE equations carry in their Kepler part, Eq. A3) and the thrust:

``gravity``
    ``point`` (none), ``j2`` (the paper's zonal J2 term, Eq. 7: J2 = 0.2027e-3,
    R = 1738.2 km), or a spherical-harmonic **field** (the packaged ``LP165P``, or the
    path of a ``.cof`` or PDS SHADR file; :mod:`lunarcap.physics.gravity`) of ``degree``
    and ``order`` in the Moon's body-fixed frame ``body_frame`` (``de405``: the DE405
    libration angles, the principal-axis frame GMAT's ``Luna`` uses; ``iau2009``: the IAU
    rotation model; the two frames are 92-109 arcsec apart over 2017, 0.82-0.97 km at 100
    km altitude, measured). A field's C20 acts as the zonal J2 term about the body's pole
    (J2 = -sqrt(5) C20, its radius); its other terms by the Cunningham recursion.
``pole`` (J2 only)
    ``frame``: J2 about the z axis of the plan's frame (M-MME2000 of the plan's lunar
    pole: for the paper's plans, the Moon's pole at J2000); ``of-date``: about the IAU
    pole at each epoch (0.79 deg from J2000's in 2017).
``third_bodies``
    Earth and/or Sun point masses from the ephemeris (Eq. 6).

The central GM of every model is the plan's (Song 2011's 4902.800 km^3/s^2), and a field's
harmonics are scaled by it too (not by the field's own GM, 4902.801 for LP165P: one GM
acts, as in GMAT, whose field file then carries lunarcap's; the 2e-7 relative difference
would move the spacecraft 91 m along track per 12 h orbit).

The paper's words are models: ``full`` (J2 about the frame's pole, Earth, Sun), ``j2``
and ``two-body``; their right-hand sides are the paper's, operation for operation.

Each term is a small class with the parameters it reads, whether it needs the Chebyshev
fit of the ephemeris (and of the Moon's orientation), and its acceleration in RTN,
written over generic operations. :func:`perturbation_rtn` sums them (last first, so the
paper's models add J2 + (Earth + Sun) as they always did); :mod:`lunarcap.physics.
dynamics` turns the sum into element rates. Adding a force is adding a term here.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field, fields, replace
from functools import cached_property

from lunarcap.errors import InputError
from lunarcap.physics._ops import ops
from lunarcap.physics.ephemeris import (
    BODY_FRAMES,
    ChebyshevFit,
    body_axes_from_params,
    earth_sun_from_params,
)
from lunarcap.physics.gravity import PACKAGED, GravityField, load_field, sh_acceleration

POINT, J2 = "point", "j2"
POLES = ("frame", "of-date")
THIRD_BODIES = ("earth", "sun")
#: The paper's dynamics by their words (the one list of them).
PRESETS = ("full", "j2", "two-body")
#: Base slots of every parameter vector: GM (km^3/s^2), thrust (kN), exhaust speed (m/s).
P_MU, P_THRUST, P_VEX = 0, 1, 2
N_BASE = 3


@dataclass(frozen=True)
class ForceModel:
    """Which forces act (see the module docstring); hashable, so functions are cached per model.

    Attributes
    ----------
    gravity : "point", "j2", or a field (packaged name or absolute path)
    degree, order : int
        Of a field (ignored otherwise).
    pole : {"frame", "of-date"}
        Axis of the J2 term (``gravity: j2``).
    third_bodies : tuple of {"earth", "sun"}
    body_frame : {"de405", "iau2009"}
        The frame a field is evaluated in.
    name : str
        The paper's word for a preset (``full``, ``j2``, ``two-body``), else "".
    """

    gravity: str = J2
    degree: int = 0
    order: int = 0
    pole: str = "of-date"
    third_bodies: tuple = THIRD_BODIES
    body_frame: str = "de405"
    name: str = ""
    #: SHA-256 of a field's file (set on construction): a model is its file's content too.
    field_sha: str = field(default="", repr=False)

    def __getstate__(self):   # the fields only: cached properties are not the model
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def __setstate__(self, state):
        for k, v in state.items():
            object.__setattr__(self, k, v)

    def __post_init__(self):
        object.__setattr__(self, "third_bodies", tuple(self.third_bodies))
        where = "dynamics"
        if self.pole not in POLES:
            raise InputError(f"{where}.pole: must be one of {', '.join(POLES)}, got "
                             f"{self.pole!r}")
        bad = [b for b in self.third_bodies if b not in THIRD_BODIES]
        if bad or len(set(self.third_bodies)) != len(self.third_bodies):
            raise InputError(f"{where}.third_bodies: a list of distinct names among "
                             f"{', '.join(THIRD_BODIES)}, got {list(self.third_bodies)}")
        if self.body_frame not in BODY_FRAMES:
            raise InputError(f"{where}.body_frame: must be one of {', '.join(BODY_FRAMES)}, "
                             f"got {self.body_frame!r}")
        if self.is_field:
            f = self.field
            _integer(f"{where}.degree", self.degree, 2, f.degree,
                     f"the field {f.name} goes to degree {f.degree}")
            _integer(f"{where}.order", self.order, 0, min(self.degree, f.order),
                     f"at most the degree, and the field's order {f.order}")
            object.__setattr__(self, "field_sha", f.sha256)

    # ------------------------------------------------------------------ what it is
    @property
    def is_field(self) -> bool:
        """True for a spherical-harmonic field."""
        return self.gravity not in (POINT, J2)

    @property
    def perturbed(self) -> bool:
        """True if any force acts beyond a point Moon (an orbit's perilune then moves)."""
        return self.gravity != POINT or bool(self.third_bodies)

    @cached_property
    def field(self) -> GravityField:
        """The gravity field (a field model only)."""
        if not self.is_field:
            raise InputError(f"dynamics {self.label}: no gravity field")
        return load_field(self.gravity)

    @property
    def rotation(self) -> str | None:
        """The Moon orientation a term needs ("iau2009", "de405") or None."""
        if self.is_field:
            return self.body_frame
        if self.gravity == J2 and self.pole == "of-date":
            return "iau2009"
        return None

    @property
    def needs_fit(self) -> bool:
        """True if a term reads the Chebyshev fit (Earth/Sun positions or the Moon's axes)."""
        return bool(self.third_bodies) or self.rotation is not None

    @cached_property
    def terms(self) -> tuple:
        """The perturbing terms, in summation order (see :func:`perturbation_rtn`)."""
        out = []
        if self.gravity == J2:
            out.append(ZonalJ2() if self.pole == "frame" else ZonalJ2Axis())
        elif self.is_field:
            out.append(ZonalJ2Axis())
            if (self.degree, self.order) != (2, 0):
                out.append(Harmonics(self.field, self.degree, self.order))
        out += [PointMass(b) for b in THIRD_BODIES if b in self.third_bodies]
        return tuple(out)

    @cached_property
    def layout(self) -> dict:
        """Slot of each named parameter: mu, thrust_kN, vex_mps, then the terms', then fit."""
        slots = {"mu": P_MU, "thrust_kN": P_THRUST, "vex_mps": P_VEX}
        for term in self.terms:
            for name in term.params:
                slots.setdefault(name, len(slots))
        if self.needs_fit:
            slots["fit"] = len(slots)
        return slots

    @property
    def n_param(self) -> int:
        """Length of the parameter vector (:meth:`lunarcap.physics.dynamics.Model.params`)."""
        n = len(self.layout) - (1 if self.needs_fit else 0)
        return n + (ChebyshevFit.n_params(self.rotation is not None) if self.needs_fit else 0)

    # ------------------------------------------------------------------ names
    @property
    def label(self) -> str:
        """A few words: 'full', or 'LP165P 20x20 (de405), Earth, Sun'."""
        if self.name:
            return self.name
        if self.is_field:
            g = f"{self.field.name} {self.degree}x{self.order} ({self.body_frame})"
        elif self.gravity == J2:
            g = f"J2 about the {'pole of date' if self.pole == 'of-date' else 'frame pole'}"
        else:
            g = "point mass"
        return ", ".join([g] + [b.capitalize() for b in self.third_bodies])

    def __str__(self) -> str:
        return self.label

    @property
    def key(self) -> str:
        """An identifier for compiled functions: the preset word, else a digest of the model."""
        if self.name:
            return self.name.replace("-", "_")
        text = repr((self.gravity, self.degree, self.order, self.pole, self.third_bodies,
                     self.body_frame, self.field_sha))
        return "forces_" + hashlib.sha256(text.encode()).hexdigest()[:12]

    def to_plan(self):
        """The plan file's ``dynamics`` value: the word, or a mapping."""
        if self.name:
            return self.name
        out = {"gravity": self.gravity}
        if self.is_field:
            out.update(degree=self.degree, order=self.order, body_frame=self.body_frame)
        if self.gravity == J2:
            out["pole"] = self.pole
        out["third_bodies"] = list(self.third_bodies)
        return out

    def truncated(self, degree: int, order: int) -> "ForceModel":
        """The same model with the field cut to ``degree`` x ``order`` (at most its own)."""
        if not self.is_field:
            return self
        d = min(degree, self.degree)
        return replace(self, degree=d, order=min(order, self.order, d), name="")


def _integer(where: str, v, lo: int, hi: int, why: str) -> None:
    if isinstance(v, bool) or not isinstance(v, int) or not lo <= v <= hi:
        raise InputError(f"{where}: an integer from {lo} to {hi} ({why}), got {v!r}")


_PRESETS = {
    "full": ForceModel(J2, pole="frame", third_bodies=THIRD_BODIES, name="full"),
    "j2": ForceModel(J2, pole="frame", third_bodies=(), name="j2"),
    "two-body": ForceModel(POINT, pole="frame", third_bodies=(), name="two-body"),
}

#: Keys of a plan's ``dynamics`` mapping.
KEYS = ("gravity", "degree", "order", "pole", "third_bodies", "body_frame")


def force_model(spec) -> ForceModel:
    """The ForceModel of a preset word, a mapping (a plan's ``dynamics``) or a ForceModel."""
    if isinstance(spec, ForceModel):
        return spec
    if isinstance(spec, str) and spec in _PRESETS:
        return _PRESETS[spec]
    if isinstance(spec, dict):
        return from_mapping(spec)
    raise InputError(f"dynamics: must be one of {', '.join(PRESETS)}, or a mapping of "
                     f"{', '.join(KEYS)}; got {spec!r}")


def from_mapping(d: dict, base_dir=None) -> ForceModel:
    """A model from a plan's ``dynamics`` mapping (paths relative to ``base_dir``).

    Defaults: gravity j2, pole of date, Earth and Sun, a field's order its degree, frame
    de405. Every error names its key (``dynamics.degree: ...``).
    """
    unknown = sorted(set(d) - set(KEYS))
    if unknown:
        raise InputError(f"dynamics.{unknown[0]}: unknown key (known: {', '.join(KEYS)})")
    gravity = d.get("gravity", J2)
    if not isinstance(gravity, str) or not gravity.strip():
        raise InputError(f"dynamics.gravity: point, j2, a packaged field (LP165P) or the "
                         f"path of a .cof or SHADR file, got {gravity!r}")
    bodies = d.get("third_bodies", list(THIRD_BODIES))
    if not isinstance(bodies, (list, tuple)):
        raise InputError(f"dynamics.third_bodies: a list (earth, sun or both), got {bodies!r}")
    kw = dict(pole=d.get("pole", "of-date"), third_bodies=tuple(bodies),
              body_frame=d.get("body_frame", "de405"))
    if gravity in (POINT, J2):
        extra = sorted({"degree", "order", "body_frame"} & set(d))
        if extra:
            raise InputError(f"dynamics.{extra[0]}: only a gravity field takes it "
                             f"(gravity is {gravity})")
        return ForceModel(gravity, **kw)
    if "pole" in d:
        raise InputError("dynamics.pole: a gravity field turns with the Moon's body-fixed "
                         "frame (body_frame); pole is the axis of gravity: j2")
    try:
        field = load_field(gravity, base_dir)
    except InputError as exc:
        raise InputError(f"dynamics.gravity: {exc}") from None
    if "degree" not in d:
        raise InputError(f"dynamics.degree: missing (the field {field.name} goes to "
                         f"{field.degree})")
    name = gravity if gravity in PACKAGED else field.source
    return ForceModel(name, degree=d["degree"], order=d.get("order", d["degree"]), **kw)


# ---------------------------------------------------------------------- the terms
class _Point:
    """What the terms share at one state and epoch (computed once, on first use)."""

    def __init__(self, x, t, prm, forces: ForceModel):
        self.p, self.f, self.g, self.h, self.k, self.L = x
        self.t, self.prm, self.forces = t, prm, forces
        self.xp = ops(*x, t)

    def prm_of(self, name):
        """The parameter ``name`` of the model's layout."""
        return self.prm[self.forces.layout[name]]

    @cached_property
    def r(self):
        """Radius, km."""
        cL, sL = self.xp.cos(self.L), self.xp.sin(self.L)
        return self.p / (1 + self.f * cL + self.g * sL)

    @cached_property
    def rtn(self):
        """RTN unit vectors (i_r, i_t, i_n) in the plan's frame."""
        from lunarcap.physics.dynamics import rtn_from_mee

        return rtn_from_mee(self.h, self.k, self.L)

    @cached_property
    def fit(self):
        """The fit's block of the parameter vector."""
        i = self.forces.layout["fit"]
        n = ChebyshevFit.n_params(self.forces.rotation is not None)
        return [self.prm[i + j] for j in range(n)]

    @cached_property
    def earth_sun(self):
        """Earth and Sun positions, km (from the fit)."""
        return earth_sun_from_params(self.fit, self.t)

    @cached_property
    def body_rtn(self):
        """RTN unit vectors in body-fixed components: rows M i_r, M i_t, M i_n."""
        m = body_axes_from_params(self.fit, self.t)
        return tuple(tuple(m[a][0] * i[0] + m[a][1] * i[1] + m[a][2] * i[2] for a in range(3))
                     for i in self.rtn)


class ZonalJ2:
    """Lunar J2 about the z axis of the plan's frame in RTN, Eq. (7) (Kechichian 2000)."""

    params = ("radius", "j2")

    def rtn(self, pt: _Point):
        """Acceleration (a_r, a_t, a_n), km/s^2."""
        from lunarcap.physics.dynamics import j2_rtn

        return j2_rtn(pt.p, pt.f, pt.g, pt.h, pt.k, pt.L, pt.prm_of("mu"),
                      pt.prm_of("radius"), pt.prm_of("j2"))


class ZonalJ2Axis:
    """J2 about the Moon's body pole (the IAU pole of date, or a field's body frame).

    With e the pole, (e_r, e_t, e_n) its RTN components and c = mu J2 R^2 / r^4:
    a = -3/2 c (1 - 3 e_r^2) i_r - 3 c e_r (e_t i_t + e_n i_n), the gradient of
    U = -mu J2 R^2 / (2 r^3) (3 (r.e)^2 / r^2 - 1); Eq. (7) is its case e = z.
    """

    params = ("radius", "j2")

    def rtn(self, pt: _Point):
        """Acceleration (a_r, a_t, a_n), km/s^2."""
        er, et, en = (b[2] for b in pt.body_rtn)
        r = pt.r
        c = pt.prm_of("mu") * pt.prm_of("j2") * pt.prm_of("radius") ** 2 / r ** 4
        return (-1.5 * c * (1 - 3 * er * er), -3 * c * er * et, -3 * c * er * en)


class Harmonics:
    """A field's terms other than C20, in the body-fixed frame (:func:`sh_acceleration`)."""

    params = ()

    def __init__(self, field: GravityField, degree: int, order: int):
        self.field, self.degree, self.order = field, degree, order

    def rtn(self, pt: _Point):
        """Acceleration (a_r, a_t, a_n), km/s^2."""
        br, bt, bn = pt.body_rtn
        xb, yb, zb = (pt.r * br[a] for a in range(3))
        f = self.field
        ab = sh_acceleration(xb, yb, zb, f.C, f.S, f.radius_km, pt.prm_of("mu"), self.degree,
                             self.order, skip_c20=True)
        return tuple(b[0] * ab[0] + b[1] * ab[1] + b[2] * ab[2] for b in (br, bt, bn))


class PointMass:
    """The Earth's or the Sun's point-mass attraction in RTN, Eq. (6) rotated by Eq. (A5)."""

    def __init__(self, body: str):
        self.body = body
        self.params = (f"mu_{body}",)

    def rtn(self, pt: _Point):
        """Acceleration (a_r, a_t, a_n), km/s^2."""
        from lunarcap.physics.dynamics import third_body_rtn

        rj = pt.earth_sun[THIRD_BODIES.index(self.body)]
        return third_body_rtn(pt.r, pt.rtn, rj, pt.prm_of(f"mu_{self.body}"))


def perturbation_rtn(forces: ForceModel, mee, t, prm):
    """The sum of the model's accelerations in RTN (km/s^2), or None if it has no term.

    Summed from the last term to the first (a1 + (a2 + (a3 + ...))): the paper's full
    dynamics add J2 + (Earth + Sun), the order of its right-hand side.
    """
    pt = _Point(tuple(mee[i] for i in range(6)), t, prm, forces)
    total = None
    for term in reversed(forces.terms):
        a = term.rtn(pt)
        total = a if total is None else tuple(a[i] + total[i] for i in range(3))
    return total
