"""A force model: the registered terms that act in a plan's dynamics, and their sum.

A :class:`ForceModel` holds a plan's ``dynamics`` settings; each registered term
(:data:`~lunarcap.physics.forces.term.TERMS`) says from them whether it acts, what it
reads and writes of the plan, its parameters, its label words and what an exporter needs
of it. The model adds what the terms share: the parameter layout, the label, the key of
compiled functions, the plan mapping, and :func:`perturbation_rtn`, their sum.

The settings are the keys of the terms lunarcap carries (``gravity``, ``degree``,
``order``, ``pole``, ``third_bodies``, ``body_frame``), each a field; the keys of a term
registered later are kept in ``extra``. The central GM of every model is the plan's (Song
2011's 4902.800 km^3/s^2).

The paper's words are models: ``full`` (J2 about the frame's pole, Earth, Sun), ``j2``
and ``two-body``; their right-hand sides are the paper's, operation for operation.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass, field, fields, replace
from functools import cached_property

import lunarcap.physics.forces.registry  # noqa: F401  (the terms lunarcap carries)
from lunarcap.errors import InputError
from lunarcap.physics.ephemeris import ChebyshevFit
from lunarcap.physics.forces.point import POINT
from lunarcap.physics.forces.term import TERMS, At
from lunarcap.physics.forces.third_body import THIRD_BODIES
from lunarcap.physics.forces.zonal_j2 import J2
from lunarcap.physics.gravity import GravityField, load_field

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
    extra : tuple of (key, value)
        Settings of the plan keys of terms registered outside lunarcap, sorted by key.
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
    extra: tuple = ()

    def __getstate__(self):   # the fields only: cached properties are not the model
        return {f.name: getattr(self, f.name) for f in fields(self)}

    def __setstate__(self, state):
        for k, v in state.items():
            object.__setattr__(self, k, v)

    def __post_init__(self):
        object.__setattr__(self, "third_bodies", tuple(self.third_bodies))
        object.__setattr__(self, "extra", tuple(sorted(
            (k, tuple(v) if isinstance(v, list) else v) for k, v in dict(self.extra).items())))
        for k, _ in self.extra:
            if k not in plan_keys() or k in _FIELDS:
                raise InputError(f"dynamics.{k}: unknown key (known: "
                                 f"{', '.join(plan_keys())})")
        for term in TERMS.values():
            term.check(self)
        if self.is_field:
            object.__setattr__(self, "field_sha", self.field.sha256)

    def setting(self, key: str, default=None):
        """The value of a plan key: a field's, else the ``extra`` setting, else ``default``."""
        if key in _FIELDS:
            return getattr(self, key)
        return dict(self.extra).get(key, default)

    # ------------------------------------------------------------------ what it is
    @property
    def is_field(self) -> bool:
        """True for a spherical-harmonic field."""
        return self.gravity not in (POINT, J2)

    @cached_property
    def field(self) -> GravityField:
        """The gravity field (a field model only)."""
        if not self.is_field:
            raise InputError(f"dynamics {self.label}: no gravity field")
        return load_field(self.gravity)

    @cached_property
    def terms(self) -> tuple:
        """The registered terms that act, in summation order."""
        return tuple(t for t in TERMS.values() if t.acts(self))

    @cached_property
    def accelerations(self) -> tuple:
        """The acceleration pieces of the terms, in summation order (:func:`perturbation_rtn`)."""
        return tuple(a for t in self.terms for a in t.accelerations(self))

    @property
    def perturbed(self) -> bool:
        """True if any force acts beyond a point Moon (an orbit's perilune then moves)."""
        return bool(self.accelerations)

    @property
    def rotation(self) -> str | None:
        """The Moon orientation a term needs ("iau2009", "de405") or None."""
        return next((r for t in self.terms if (r := t.rotation(self)) is not None), None)

    @property
    def needs_fit(self) -> bool:
        """True if a term reads the Chebyshev fit (Earth/Sun positions or the Moon's axes)."""
        return any(t.ephemeris for t in self.terms) or self.rotation is not None

    @cached_property
    def layout(self) -> dict:
        """Slot of each named parameter: mu, thrust_kN, vex_mps, then the terms', then fit."""
        slots = {"mu": P_MU, "thrust_kN": P_THRUST, "vex_mps": P_VEX}
        for piece in self.accelerations:
            for name in piece.params:
                slots.setdefault(name, len(slots))
        if self.needs_fit:
            slots["fit"] = len(slots)
        return slots

    @property
    def n_param(self) -> int:
        """Length of the parameter vector (:meth:`lunarcap.physics.dynamics.Model.params`)."""
        n = len(self.layout) - (1 if self.needs_fit else 0)
        return n + (ChebyshevFit.n_params(self.rotation is not None) if self.needs_fit else 0)

    def values(self, model) -> dict:
        """The terms' parameter values for a physical model (``dynamics.Model``), by name."""
        out = {}
        for t in self.terms:
            out.update(t.values(self, model))
        return out

    # ------------------------------------------------------------------ names
    @property
    def label(self) -> str:
        """A few words: 'full', or 'LP165P 20x20 (de405), Earth, Sun'."""
        if self.name:
            return self.name
        return ", ".join(w for t in self.terms if (w := t.words(self)))

    def __str__(self) -> str:
        return self.label

    @property
    def key(self) -> str:
        """An identifier for compiled functions: the preset word, else a digest of the model."""
        if self.name:
            return self.name.replace("-", "_")
        parts = (self.gravity, self.degree, self.order, self.pole, self.third_bodies,
                 self.body_frame, self.field_sha) + ((self.extra,) if self.extra else ())
        return "forces_" + hashlib.sha256(repr(parts).encode()).hexdigest()[:12]

    def to_plan(self):
        """The plan file's ``dynamics`` value: the word, or a mapping."""
        if self.name:
            return self.name
        out = {"gravity": self.gravity}
        for term in TERMS.values():
            out.update(term.to_plan(self))
        return out

    def truncated(self, degree: int, order: int) -> "ForceModel":
        """The same model with the field cut to ``degree`` x ``order`` (at most its own)."""
        if not self.is_field:
            return self
        d = min(degree, self.degree)
        return replace(self, degree=d, order=min(order, self.order, d), name="")

    def beyond(self, degree: int, order: int) -> bool:
        """True if the model's field has terms beyond ``degree`` x ``order``."""
        return self.is_field and (self.degree > degree or self.order > order)


#: The settings that are fields of a ForceModel (the plan keys of lunarcap's own terms).
_FIELDS = ("gravity", "degree", "order", "pole", "third_bodies", "body_frame")

def plan_keys() -> tuple:
    """The keys of a plan's ``dynamics`` mapping: ``gravity``, then the registered terms'."""
    return tuple(dict.fromkeys(("gravity",) + tuple(k for t in TERMS.values() for k in t.keys)))


_PRESETS = {
    "full": ForceModel(J2, pole="frame", third_bodies=THIRD_BODIES, name="full"),
    "j2": ForceModel(J2, pole="frame", third_bodies=(), name="j2"),
    "two-body": ForceModel(POINT, pole="frame", third_bodies=(), name="two-body"),
}


def force_model(spec) -> ForceModel:
    """The ForceModel of a preset word, a mapping (a plan's ``dynamics``) or a ForceModel."""
    if isinstance(spec, ForceModel):
        return spec
    if isinstance(spec, str) and spec in _PRESETS:
        return _PRESETS[spec]
    if isinstance(spec, dict):
        return from_mapping(spec)
    raise InputError(f"dynamics: must be one of {', '.join(PRESETS)}, or a mapping of "
                     f"{', '.join(plan_keys())}; got {spec!r}")


def from_mapping(d: dict, base_dir=None) -> ForceModel:
    """A model from a plan's ``dynamics`` mapping (paths relative to ``base_dir``).

    ``gravity`` (default ``j2``) is read here; each registered term reads its own keys
    (:meth:`~lunarcap.physics.forces.term.Term.read`), with its defaults (lunarcap's: pole
    of date, Earth and Sun, a field's order its degree, frame de405). Every error names its
    key (``dynamics.degree: ...``).
    """
    known = plan_keys()
    unknown = sorted(set(d) - set(known))
    if unknown:
        raise InputError(f"dynamics.{unknown[0]}: unknown key (known: {', '.join(known)})")
    gravity = d.get("gravity", J2)
    if not isinstance(gravity, str) or not gravity.strip():
        raise InputError(f"dynamics.gravity: point, j2, a packaged field (LP165P) or the "
                         f"path of a .cof or SHADR file, got {gravity!r}")
    settings = {"gravity": gravity}
    for term in TERMS.values():
        settings.update(term.read(d, gravity, base_dir))
    extra = tuple((k, v) for k, v in settings.items() if k not in _FIELDS)
    return ForceModel(**{k: v for k, v in settings.items() if k in _FIELDS}, extra=extra)


def perturbation_rtn(forces: ForceModel, mee, t, prm):
    """The sum of the model's accelerations in RTN (km/s^2), or None if it has no term.

    Summed from the last term to the first (a1 + (a2 + (a3 + ...))): the paper's full
    dynamics add J2 + (Earth + Sun), the order of its right-hand side.
    """
    at = At(tuple(mee[i] for i in range(6)), t, prm, forces)
    total = None
    for piece in reversed(forces.accelerations):
        a = piece.rtn(at)
        total = a if total is None else tuple(a[i] + total[i] for i in range(3))
    return total
