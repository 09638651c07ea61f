"""Thrust steering: the unit thrust direction in RTN as a function of the state or of time.

Written over generic operations (numpy or CasADi), so the same laws serve the
transcription (:mod:`lunarcap.optim`), the compiled propagator
(:mod:`lunarcap.physics.propagate`) and the figures. A :class:`Steering` describes one
arc's law and its numeric parameters, which the propagator compiles once per kind.

* ``coast``: no thrust.
* ``constant``: a fixed direction in RTN.
* ``antivelocity``: thrust opposite the velocity, u = -(v_r, v_t, 0)/|v| with
  v_r ~ f sin L - g cos L, v_t ~ 1 + f cos L + g sin L (the factor sqrt(mu/p) cancels).
* ``inertial``: a direction fixed in M-MME2000, u = Q(h, k, L) u_in (Eq. A5).
* ``polynomial``: the interpolating polynomial through d controls at the LGR points of a
  mesh interval (the collocated steering), normalised: u(tau) = U l(tau) / |U l(tau)|,
  with tau in [0, 1] across the interval.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from lunarcap.errors import InputError
from lunarcap.physics._ops import ops
from lunarcap.physics.dynamics import rtn_from_mee

LAWS = ("antivelocity", "inertial")


def law_direction(law: str, x, u_in=None):
    """RTN thrust direction (3 components) of a closed-form law at the MEE state x.

    ``x`` is a sequence of at least 6 (p, f, g, h, k, L), numbers, arrays (one column per
    state) or CasADi symbols; returns a list of three components.
    """
    f, g, h, k, L = x[1], x[2], x[3], x[4], x[5]
    xp = ops(f, g, h, k, L)
    if law == "antivelocity":
        vr = f * xp.sin(L) - g * xp.cos(L)
        vt = 1 + f * xp.cos(L) + g * xp.sin(L)
        n = xp.sqrt(vr * vr + vt * vt)
        return [-vr / n, -vt / n, 0 * n]
    if law == "inertial":
        ir, it, i_n = rtn_from_mee(h, k, L)
        return [sum(a[i] * u_in[i] for i in range(3)) for a in (ir, it, i_n)]
    raise InputError(f"no closed-form steering law {law!r} (known: {LAWS})")


def lagrange_basis(nodes, tau):
    """Lagrange basis polynomials l_j(tau) of the nodes (generic over numpy and CasADi)."""
    out = []
    for j, xj in enumerate(nodes):
        lj = 1.0 + 0 * tau
        for m, xm in enumerate(nodes):
            if m != j:
                lj = lj * (tau - xm) / (xj - xm)
        out.append(lj)
    return out


def polynomial_direction(nodes, U, tau):
    """Unit direction of the polynomial through the columns of U (3, d) at the nodes."""
    ell = lagrange_basis(nodes, tau)
    comps = [sum(U[i][j] * ell[j] for j in range(len(nodes))) for i in range(3)]
    xp = ops(*comps)
    n = xp.sqrt(comps[0] ** 2 + comps[1] ** 2 + comps[2] ** 2)
    return [c / n for c in comps]


@dataclass(frozen=True)
class Steering:
    """The steering of one arc: its kind and numeric parameters.

    Attributes
    ----------
    kind : {"coast", "constant", "antivelocity", "inertial", "polynomial"}
    params : tuple of float
        constant: (u_r, u_t, u_n); inertial: u_in (3, M-MME2000); polynomial: the d
        controls column by column (3 d values); none otherwise.
    nodes : tuple of float
        polynomial only: the d interpolation nodes in [0, 1].
    """

    kind: str = "coast"
    params: tuple = ()
    nodes: tuple = field(default=())

    @property
    def thrusting(self) -> bool:
        """False for a coast."""
        return self.kind != "coast"

    @property
    def shape_key(self) -> tuple:
        """What a compiled propagator depends on (the kind and the parameter count)."""
        return (self.kind, len(self.params), self.nodes)

    def direction(self, x, tau, p):
        """RTN direction at state x and arc fraction tau with parameters p (generic ops)."""
        if self.kind == "coast":
            return [0 * tau, 0 * tau, 0 * tau]
        if self.kind == "constant":
            return [p[0], p[1], p[2]]
        if self.kind in LAWS:
            return law_direction(self.kind, x, [p[0], p[1], p[2]] if p is not None else None)
        if self.kind == "polynomial":
            d = len(self.nodes)
            U = [[p[3 * j + i] for j in range(d)] for i in range(3)]
            return polynomial_direction(self.nodes, U, tau)
        raise InputError(f"unknown steering kind {self.kind!r}")

    def __call__(self, x, tau=0.0) -> np.ndarray:
        """Numeric direction at one state (and arc fraction)."""
        p = np.asarray(self.params, float) if self.params else np.zeros(3)
        return np.array([float(c) for c in self.direction(np.asarray(x, float), tau, p)])


COAST = Steering("coast")


def constant(u) -> Steering:
    """A fixed RTN direction (normalised)."""
    u = np.asarray(u, float)
    return Steering("constant", tuple(u / np.linalg.norm(u)))


def law(kind: str, u_in=None) -> Steering:
    """A closed-form law: "antivelocity", or "inertial" with its M-MME2000 direction."""
    if kind == "antivelocity":
        return Steering("antivelocity", (0.0, 0.0, 0.0))
    if kind == "inertial":
        return Steering("inertial", tuple(float(v) for v in u_in))
    raise InputError(f"no closed-form steering law {kind!r} (known: {LAWS})")


def polynomial(nodes, U) -> Steering:
    """The interpolating polynomial of controls U (3, d) at nodes (d,) in [0, 1]."""
    U = np.asarray(U, float)
    return Steering("polynomial", tuple(U.ravel(order="F")), tuple(float(c) for c in nodes))
