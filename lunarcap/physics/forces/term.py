"""What a force term is: the hooks a term module fills, the point it is evaluated at, TERMS.

A term (one module each, :mod:`lunarcap.physics.forces`) is an object with

* its **plan keys** (:attr:`Term.keys`): what it reads from a plan's ``dynamics`` mapping
  (:meth:`Term.read`, refusing a bad value with a message that names the key), checks on a
  model (:meth:`Term.check`) and writes back (:meth:`Term.to_plan`);
* whether it **acts** in a model (:meth:`Term.acts`), and its **label** words;
* its **accelerations** in RTN, written once over generic operations (numpy arrays and
  CasADi symbols, :mod:`lunarcap.physics._ops`): :meth:`Term.accelerations` gives the
  pieces (by default the term itself), each with the names of the parameters it reads
  (``params``) and ``rtn(at)``;
* its **parameter values** (:meth:`Term.values`): the numbers of those names for a physical
  model (the Moon's radius and J2, a body's GM, a field's own radius ...);
* what an **exporter** needs of it to fly it elsewhere (:meth:`Term.export`): a part of the
  Moon's gravity field (:class:`MoonField`) or a point mass (:class:`ThirdBody`).

:func:`register` adds a term to :data:`TERMS`; the order of registration is the order of
summation (see :func:`lunarcap.physics.forces.model.perturbation_rtn`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from lunarcap.errors import InputError
from lunarcap.physics._ops import ops
from lunarcap.physics.ephemeris import ChebyshevFit, body_axes_from_params, earth_sun_from_params

#: The registered terms by name, in summation order (:func:`register`).
TERMS: dict = {}


def register(term: "Term") -> "Term":
    """Add ``term`` to :data:`TERMS` (after the others); a second term of a name is refused."""
    if not term.name or term.name in TERMS:
        raise InputError(f"force term {term.name!r}: a term needs a name of its own "
                         f"(registered: {', '.join(TERMS)})")
    TERMS[term.name] = term
    return term


def rtn_from_mee(h, k, L):
    """RTN unit vectors (i_r, i_t, i_n), each a 3-tuple, from MEE (equivalent to Eq. A5)."""
    xp = ops(h, k, L)
    s2 = 1 + h * h + k * k
    fh = ((1 + h * h - k * k) / s2, 2 * h * k / s2, -2 * k / s2)
    gh = (2 * h * k / s2, (1 - h * h + k * k) / s2, 2 * h / s2)
    cL, sL = xp.cos(L), xp.sin(L)
    ir = tuple(cL * a + sL * b for a, b in zip(fh, gh))
    it = tuple(-sL * a + cL * b for a, b in zip(fh, gh))
    i_n = (2 * k / s2, -2 * h / s2, (1 - h * h - k * k) / s2)
    return ir, it, i_n


class At:
    """What the terms share at one state and epoch (each computed once, on first use).

    Parameters
    ----------
    x : 6 MEE (p km, f, g, h, k, L rad), numpy arrays or CasADi symbols
    t : epoch, TDB s past J2000
    prm : the parameter vector (:meth:`lunarcap.physics.dynamics.Model.params`)
    forces : lunarcap.physics.forces.ForceModel
        Whose ``layout`` names the slots of ``prm``.
    """

    def __init__(self, x, t, prm, forces):
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


# ---------------------------------------------------------------------- what exporters get
@dataclass(frozen=True)
class MoonField:
    """The Moon's gravity a term asks an exporter to carry: fully normalised C_nm, S_nm.

    Attributes
    ----------
    mu_km3s2, radius_km : float
        The GM that scales the field (the plan's) and its reference radius.
    c, s : ndarray (n+1, n+1)
        C[n, m], S[n, m] (degrees 0 and 1 ignored).
    frame : {"fixed-pole", "iau2009", "de405"}
        The body-fixed axes: about ``pole_radec_deg`` (right ascension, declination in
        ICRF), fixed in time (all a zonal field needs); the IAU rotation model of date; the
        DE405 principal axes (the libration angles).
    source : str
        Where the coefficients come from, in words (written in exported files).
    """

    mu_km3s2: float
    radius_km: float
    c: np.ndarray = field(repr=False)
    s: np.ndarray = field(repr=False)
    frame: str = "fixed-pole"
    pole_radec_deg: tuple = (0.0, 90.0)
    source: str = ""


def zonal_c20(j2: float) -> tuple:
    """(C, S) of degree 2 with only C20 = -J2 / sqrt(5): an unnormalised J2, fully normalised.

    The inverse of :attr:`lunarcap.physics.gravity.GravityField.j2` (J2 = -sqrt(5) C20; Kaula's
    normalisation, sqrt(2n + 1) for m = 0).
    """
    c = np.zeros((3, 3))
    c[2, 0] = -j2 / math.sqrt(5.0)
    return c, np.zeros((3, 3))


@dataclass(frozen=True)
class ThirdBody:
    """A point mass a term asks an exporter to carry: its name and GM, km^3/s^2."""

    name: str
    mu_km3s2: float


# ---------------------------------------------------------------------- the hooks
class Term:
    """A force term; a module subclasses it, fills the hooks, and :func:`register` s it once.

    The defaults suit a term that is its own (single) acceleration, reads no plan key,
    needs no ephemeris and has no exporter counterpart. A term's own keys (those that are
    not fields of :class:`~lunarcap.physics.forces.ForceModel`) are kept in the model's
    ``extra`` and read back with ``forces.setting(key)``.

    Attributes
    ----------
    name : str
        Its name in :data:`TERMS` and in messages.
    keys : tuple of str
        The plan ``dynamics`` keys it reads (a key may be read by several terms).
    params : tuple of str
        The names of its slots in the parameter vector (a term that is its own acceleration).
    ephemeris : bool
        True if it reads the Earth's or the Sun's position from the fit.
    """

    name: str = ""
    keys: tuple = ()
    params: tuple = ()
    ephemeris: bool = False

    def read(self, d: dict, gravity: str, base_dir=None) -> dict:
        """Its settings from a plan's ``dynamics`` mapping ``d`` (``gravity`` already read).

        A mapping of ForceModel settings (its keys, validated enough to build the model;
        errors name the key: ``dynamics.<key>: ...``); absent keys keep their defaults.
        """
        return {k: d[k] for k in self.keys if k in d}

    def check(self, forces) -> None:
        """Refuse a model whose settings of the term's keys are wrong (InputError, by key)."""

    def acts(self, forces) -> bool:
        """True if the term acts in ``forces``."""
        return False

    def accelerations(self, forces) -> tuple:
        """The pieces summed, in order: objects with ``params`` and ``rtn(at)``."""
        return (self,)

    def rtn(self, at: At):
        """Acceleration (a_r, a_t, a_n), km/s^2, at ``at`` (a term that is its own piece)."""
        raise NotImplementedError(f"force term {self.name}: no acceleration")

    def values(self, forces, model) -> dict:
        """Its parameters' values, by name, for a physical model (``dynamics.Model``)."""
        return {}

    def rotation(self, forces) -> str | None:
        """The Moon orientation it needs ("iau2009", "de405"), or None."""
        return None

    def words(self, forces) -> str:
        """Its words in the model's label ("J2 about the frame pole", "Earth, Sun")."""
        return self.name

    def to_plan(self, forces) -> dict:
        """Its keys of the plan's ``dynamics`` mapping (those that apply to ``forces``)."""
        return {}

    def export(self, forces, model, pole: str):
        """What an exporter must carry to fly it, or None if no exporter has a counterpart.

        A tuple of :class:`MoonField` and :class:`ThirdBody`; None refuses the export,
        naming the term. ``pole``: the plan's lunar pole (the z axis of its frame).
        """
        return None
