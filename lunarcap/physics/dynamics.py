"""Equations of motion in modified equinoctial elements, Song 2011 Eqs. (2)-(8), (A2)-(A5).

The state is ``x = (p km, f, g, h, k, L rad, m kg)``; the control is the unit thrust
direction ``u = (u_r, u_t, u_n)`` in the radial-tangential-normal (RTN) frame; time
is TDB seconds past J2000. The perturbing acceleration (Eq. 4) is

    Delta = Delta_J2 (Eq. 7) + Q (a_Earth + a_Sun) (Eq. 6, rotated by Eq. A5) + T/m u (Eq. 8)

and the rates are ``dy/dt = A(y) Delta + b(y)`` (Eq. 2, A2-A4), ``dm/dt = -T/(g0 Isp)``
(Eq. 3). Which perturbations act is a :class:`~lunarcap.physics.forces.ForceModel`
(the paper's words ``full``, ``j2``, ``two-body``, or any composition of terms: a
spherical-harmonic field, J2 about the pole of date, ...); its terms' sum is Delta less the
thrust. :func:`mee_rates` is written once over generic operations: it evaluates on numpy
arrays and builds the CasADi expression that the transcription and the propagators share
through :func:`rhs_function`. The terms' own formulas (RTN basis, Eq. 7's J2, Eq. 6's
third bodies) live with the terms (:mod:`lunarcap.physics.forces`) and are re-exported here.

An independent Cartesian formulation (:func:`cartesian_rates`, numpy only, J2 from the
gradient of the potential) exists to check the MEE equations.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

import casadi as ca
import numpy as np

from lunarcap.errors import InputError
from lunarcap.physics import constants as C
from lunarcap.physics._ops import ops
from lunarcap.physics.ephemeris import ChebyshevFit
from lunarcap.physics.forces import (  # noqa: F401  (re-exported: the parameter slots)
    P_MU,
    P_THRUST,
    P_VEX,
    PRESETS,
    ForceModel,
    force_model,
    perturbation_rtn,
    rtn_from_mee,
)
from lunarcap.physics.forces.third_body import (  # noqa: F401  (re-exported)
    third_body_accel,
    third_body_rtn,
)
from lunarcap.physics.forces.zonal_j2 import J2, j2_rtn  # noqa: F401  (j2_rtn re-exported)
from lunarcap.physics.gravity import sh_acceleration


@dataclass
class Model:
    """Physical model: the forces (:mod:`lunarcap.physics.forces`), engine and ephemeris fit.

    Parameters
    ----------
    mode : "full", "j2", "two-body", a ForceModel, or a plan's ``dynamics`` mapping
        Which forces act: the paper's words (lunar J2, Earth and Sun point masses; J2
        only; none), or any composition of terms.
    thrust_N : float
        Engine thrust, N (0 for a coast).
    isp_s : float
        Specific impulse, s.
    fit : ChebyshevFit or None
        Earth/Sun ephemeris fit (with the Moon's orientation when a term turns with it);
        required when the forces need it (:attr:`ForceModel.needs_fit`).
    mu, radius, j2, mu_earth, mu_sun : float
        The Moon's GM (km^3/s^2), radius (km) and J2, the Earth's and the Sun's GM
        (km^3/s^2): Song 2011's values (:mod:`lunarcap.physics.constants`), which the terms
        read (:meth:`~lunarcap.physics.forces.Term.values`).
    """

    mode: str | ForceModel = "full"
    thrust_N: float = 0.0
    isp_s: float = 300.0
    fit: ChebyshevFit | None = None
    mu: float = C.MU_MOON
    radius: float = C.R_MOON
    j2: float = C.J2_MOON
    mu_earth: float = C.MU_EARTH
    mu_sun: float = C.MU_SUN
    forces: ForceModel = field(init=False, repr=False)

    def __post_init__(self):
        self.forces = force_model(self.mode)
        if not isinstance(self.mode, str):   # a mapping: its (hashable) model
            self.mode = self.forces
        if not np.isfinite(self.thrust_N) or self.thrust_N < 0:
            raise InputError(f"thrust must be a non-negative number of newtons, "
                             f"got {self.thrust_N}")
        if not np.isfinite(self.isp_s) or self.isp_s <= 0:
            raise InputError(f"specific impulse must be positive (s), got {self.isp_s}")
        need = self.forces.rotation
        if self.forces.needs_fit and (self.fit is None or self.fit.body_frame != need):
            raise InputError(f"{self.forces.label} dynamics need an ephemeris fit"
                             + (f" with the Moon's {need} orientation" if need else "")
                             + " (Model(fit=ChebyshevFit.fit(..., body_frame=...)))")

    @property
    def exhaust_speed_kmps(self) -> float:
        """Effective exhaust speed g0 Isp, km/s."""
        return C.G0_KMPS2 * self.isp_s

    def params(self, thrust_N: float | None = None) -> np.ndarray:
        """The numeric parameter vector (length ``forces.n_param``) of :func:`rhs_function`.

        GM, thrust and exhaust speed, then each term's values
        (:meth:`~lunarcap.physics.forces.ForceModel.values`: the lunar radius and J2, the
        bodies' GMs, a field's own radius and J2) in the model's layout, then the fit.
        """
        T = self.thrust_N if thrust_N is None else thrust_N
        f = self.forces
        values = {"mu": self.mu, "thrust_kN": T * 1e-3, "vex_mps": self.exhaust_speed_kmps * 1e3,
                  **f.values(self)}
        out = [values[name] for name in f.layout if name != "fit"]
        if f.needs_fit:
            out = np.concatenate([out, self.fit.param_vector()])
        return np.asarray(out, float)


def fit_for(mode, eph, t0_s: float, t1_s: float) -> ChebyshevFit | None:
    """The Chebyshev fit the forces of ``mode`` read over [t0_s, t1_s], or None if none.

    Earth and Sun positions, with the Moon's orientation when a term turns with it
    (:attr:`lunarcap.physics.forces.ForceModel.rotation`), from the ephemeris ``eph``.
    """
    forces = force_model(mode)
    if not forces.needs_fit:
        return None
    return ChebyshevFit.fit(eph, t0_s, t1_s, body_frame=forces.rotation)


def mee_rates(x, u, t, prm, forces="full", a_extra=None):
    """Time derivatives of (p, f, g, h, k, L, m): Eqs. (2)-(8), (A2)-(A4).

    Parameters
    ----------
    x : sequence of 7 (p km, f, g, h, k, L rad, m kg), numpy arrays or CasADi symbols
    u : sequence of 3, unit thrust direction (u_r, u_t, u_n)
    t : epoch, TDB seconds past J2000
    prm : parameter vector of :meth:`Model.params`
    forces : ForceModel or a preset word
        The perturbing terms (:func:`lunarcap.physics.forces.perturbation_rtn`).
    a_extra : sequence of 3, optional
        A further acceleration in RTN, km/s^2, added to the terms' (an outer correction
        of the optimiser carries a field's higher degrees this way).

    Returns
    -------
    list of 7 derivatives (km/s, 1/s, ..., rad/s, kg/s)
    """
    p, f, g, h, k, L, m = (x[i] for i in range(7))
    xp = ops(p, f, g, h, k, L, m, t)
    forces = force_model(forces)
    mu = prm[P_MU]
    cL, sL = xp.cos(L), xp.sin(L)
    q = 1 + f * cL + g * sL
    s2 = 1 + h * h + k * k
    w = h * sL - k * cL
    sq = xp.sqrt(p / mu)

    # the forces' terms (lunar gravity, Earth and Sun point masses: Eqs. 6-7), in RTN
    pert = perturbation_rtn(forces, (p, f, g, h, k, L), t, prm)
    if a_extra is not None:
        pert = tuple(a_extra[i] for i in range(3)) if pert is None else \
            tuple(pert[i] + a_extra[i] for i in range(3))
    # thrust, Eq. (8): T [kN] / m [kg] = km/s^2
    acc = prm[P_THRUST] / m
    if pert is None:
        dr, dt, dn = acc * u[0], acc * u[1], acc * u[2]
    else:
        dr, dt, dn = (pert[i] + acc * u[i] for i in range(3))

    # Eq. (2) with A (A2), b (A3), q, s^2 (A4)
    pdot = 2 * p / q * sq * dt
    fdot = sq * (sL * dr + ((q + 1) * cL + f) * dt / q - w * g * dn / q)
    gdot = sq * (-cL * dr + ((q + 1) * sL + g) * dt / q + w * f * dn / q)
    hdot = sq * s2 * cL / (2 * q) * dn
    kdot = sq * s2 * sL / (2 * q) * dn
    Ldot = xp.sqrt(mu * p) * (q / p) ** 2 + sq * w * dn / q
    # mass flow, Eq. (3): T [N] / (g0 Isp) [m/s] = kg/s
    mdot = -prm[P_THRUST] * 1e3 / prm[P_VEX]
    return [pdot, fdot, gdot, hdot, kdot, Ldot, mdot]


@lru_cache(maxsize=None)
def rhs_function(mode="full", thrust: bool = True, extra: bool = False) -> ca.Function:
    """CasADi Function ``f(x[7], u[3], t, prm[n_param]) -> xdot[7]`` from :func:`mee_rates`.

    ``mode``: a preset word or a ForceModel (:func:`lunarcap.physics.forces.force_model`);
    only its terms enter the graph. With ``thrust=False`` (a coast) the thrust is built in
    as zero (``u`` and the thrust entry of ``prm`` are ignored): the same equations
    without their thrust terms. With ``extra`` a fifth input ``a[3]`` (RTN, km/s^2) is
    added to the perturbation (:func:`mee_rates`'s ``a_extra``).
    """
    forces = force_model(mode)
    n = forces.n_param
    x = ca.SX.sym("x", 7)
    u = ca.SX.sym("u", 3)
    t = ca.SX.sym("t")
    prm = ca.SX.sym("prm", n)
    a = ca.SX.sym("a", 3)
    plist = [prm[i] for i in range(n)]
    if not thrust:
        plist[P_THRUST] = ca.SX(0.0)
    rates = mee_rates([x[i] for i in range(7)], [u[i] for i in range(3)], t, plist, forces,
                      [a[i] for i in range(3)] if extra else None)
    if not forces.third_bodies and not forces.is_field and not extra:
        rates = [ca.simplify(r) for r in rates]
    name = f"mee_rhs_{forces.key}{'' if thrust else '_coast'}{'_extra' if extra else ''}"
    # Common subexpressions merged (the same operations, computed once: e.g. the
    # orbit-plane basis of rv_from_mee and rtn_from_mee): 16 % fewer instructions per node
    # in full dynamics, so smaller NLP derivatives to build and evaluate.
    ins, names = [x, u, t, prm] + ([a] if extra else []), ["x", "u", "t", "prm"] + (
        ["a"] if extra else [])
    return ca.Function(name, ins, [ca.cse(ca.vertcat(*rates))], names, ["xdot"])


# ------------------------------------------------------------------ independent check
#: The terms :func:`cartesian_rates` writes out (by their names in the registry).
CARTESIAN_TERMS = ("point", "zonal-j2", "body-pole-j2", "harmonics", "third-bodies")


def cartesian_rates(t, state, model: Model, u_rtn=(0.0, 0.0, 0.0)):
    """Cartesian equations of motion, written independently of the MEE form (numpy).

    ``state = (r km [3], v km/s [3], m kg)``;
    r'' = -mu r/r^3 + grad(U_J2) + grad(U_field) + a_Earth + a_Sun + T/m Q^T u.
    The J2 term is the gradient of U = -mu J2 R^2 / (2 r^3) (3 z^2/r^2 - 1) with z along
    its axis (the frame's pole, or the body pole from the fit); a field is evaluated
    whole (its C20 too) in the body-fixed frame and rotated back. Written for lunarcap's
    own terms: a model with another term is refused rather than checked without it.
    """
    fm = model.forces
    other = [t.name for t in fm.terms if t.name not in CARTESIAN_TERMS]
    if other:
        raise InputError(f"cartesian_rates: no independent form of the term(s) "
                         f"{', '.join(other)}")
    r = np.asarray(state[:3], float)
    v = np.asarray(state[3:6], float)
    m = state[6]
    mu = model.mu
    rn = np.linalg.norm(r)
    a = -mu * r / rn ** 3
    axes = model.fit.body_axes(t) if fm.rotation else np.eye(3)
    if fm.gravity == J2:
        x, y, z = axes @ r if fm.pole == "of-date" else r
        c = 1.5 * model.j2 * mu * model.radius ** 2 / rn ** 5
        zz = 5 * z * z / rn ** 2
        ab = c * np.array([x * (zz - 1), y * (zz - 1), z * (zz - 3)])
        a = a + (axes.T @ ab if fm.pole == "of-date" else ab)
    if fm.is_field:
        f = fm.field
        ab = sh_acceleration(*(axes @ r), f.C, f.S, f.radius_km, mu, fm.degree, fm.order)
        a = a + axes.T @ np.array(ab)
    if fm.third_bodies:
        re, rs = model.fit(t)
        for name, rj, muj in (("earth", re.ravel(), model.mu_earth),
                              ("sun", rs.ravel(), model.mu_sun)):
            if name in fm.third_bodies:
                d = rj - r
                a = a + muj * (d / np.linalg.norm(d) ** 3 - rj / np.linalg.norm(rj) ** 3)
    mdot = 0.0
    if model.thrust_N > 0:
        ir = r / rn
        hv = np.cross(r, v)
        i_n = hv / np.linalg.norm(hv)
        it = np.cross(i_n, ir)
        dirn = u_rtn[0] * ir + u_rtn[1] * it + u_rtn[2] * i_n
        a = a + model.thrust_N * 1e-3 / m * dirn
        mdot = -model.thrust_N / (model.exhaust_speed_kmps * 1e3)
    return np.concatenate([v, a, [mdot]])
