"""Legendre-Gauss-Radau collocation: meshes, the differentiation matrix, phase defects.

Nondimensional units of every NLP: LU = 1738.2 km (the paper's lunar unit), TU =
sqrt(LU^3 / mu_Moon), VU = LU / TU; masses are divided by the mass at the start of the
phase chain. A phase of ``n`` intervals of LGR degree ``d`` carries its start state and
``d`` states per interval; the state polynomial of an interval interpolates its start and
its ``d`` Radau points, and its derivative there must equal the dynamics (the defects).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import casadi as ca
import numpy as np

from lunarcap.physics import constants as C
from lunarcap.physics.dynamics import rhs_function

LU = C.LU_KM
TU = float(np.sqrt(LU ** 3 / C.MU_MOON))
VU = LU / TU

#: Number of states: (p, f, g, h, k, L, m).
N_X = 7

#: Box bounds of the scaled states (p LU, f, g, h, k, L rad, m / m_ref): wide, only to keep
#: IPOPT away from nonsense (p > 0, a finite mass). h and k, tan(i/2) times the cosine and
#: sine of the node, are widened per problem to admit its inclination (:func:`hk_bound`).
STATE_LB = np.array([0.2, -3, -3, -3, -3, -np.inf, 0.05])
STATE_UB = np.array([200.0, 3, 3, 3, 3, np.inf, 1.0 + 1e-9])


def hk_bound(*tan_half_inclinations) -> float:
    """Bound of |h| and |k| for orbits of these tan(i/2): 3, or 1.5 times the largest + 1.

    3 (the bound of every plan up to i = 90 deg, kept so that their optima are unchanged)
    admits i <= 2 atan(3) = 143 deg only for some nodes; 1.5 tan(i/2) + 1 leaves room for
    the inclination to move during a burn.
    """
    return max(3.0, 1.5 * max(tan_half_inclinations) + 1.0)


@dataclass(frozen=True)
class Mesh:
    """Collocation mesh: intervals in the burn and coast phases and the LGR degree."""

    n_burn: int = 8
    n_coast: int = 16
    degree: int = 5

    def label(self) -> str:
        """'8x16 LGR-5'."""
        return f"{self.n_burn}x{self.n_coast} LGR-{self.degree}"


#: Meshes tried in turn until verification passes.
DEFAULT_MESHES = (Mesh(8, 16, 5), Mesh(12, 24, 5), Mesh(18, 36, 6))

#: Intervals of the pre-ignition coast when the ignition time is free.
N_PRE = 4


def state_scale(m_ref_kg: float) -> np.ndarray:
    """Scale of each state (LU for p, the reference mass for m, 1 otherwise)."""
    return np.array([LU, 1.0, 1.0, 1.0, 1.0, 1.0, m_ref_kg])


@lru_cache(maxsize=None)
def radau_matrices(d: int):
    """LGR points c (d,), differentiation matrix D (d+1, d) for [0, 1] intervals.

    The state polynomial on an interval interpolates X_0 (start) and X_1..X_d (at c_k);
    its derivative at c_k is sum_r D[r, k-1] X_r / h.
    """
    c = np.concatenate([[0.0], ca.collocation_points(d, "radau")])
    D = np.zeros((d + 1, d))
    for r in range(d + 1):
        coeff = np.array([1.0])
        for s in range(d + 1):
            if s != r:
                coeff = np.convolve(coeff, [1.0, -c[s]]) / (c[r] - c[s])
        dpoly = np.polyder(coeff)
        for k in range(1, d + 1):
            D[r, k - 1] = np.polyval(dpoly, c[k])
    return c[1:], D


def taus(frac, c) -> np.ndarray:
    """Phase fractions of the collocation points of every interval (boundaries ``frac``)."""
    return np.concatenate([frac[j] + (frac[j + 1] - frac[j]) * c for j in range(len(frac) - 1)])


def node_epochs(t_start: float, duration: float, frac, d: int) -> np.ndarray:
    """Epochs of a phase's start and its collocation points, s."""
    c, _ = radau_matrices(d)
    return t_start + duration * np.concatenate([[0.0], taus(frac, c)])


def collocation_defects(Xall, U, mesh_frac, t_start, dur, prm, n, d, S, mode="full",
                        thrust: bool = True, accel=None):
    """LGR collocation defects of one phase (CasADi expressions).

    Parameters
    ----------
    Xall : (7, n*d+1) scaled states: the phase's start, then the d points of each interval
    U : (3, n*d) RTN thrust directions at the collocation points
    mesh_frac : (n+1,) interval boundaries as fractions of the phase
    t_start, dur : phase start epoch (s past J2000) and duration (s; may be negative)
    prm : dynamics parameter vector (thrust 0 for a coast)
    n, d : intervals and LGR degree
    S : (7,) state scales (:func:`state_scale`)
    mode : the forces built into the right-hand side (a preset word or a ForceModel)
    thrust : False for a coast (the right-hand side without its thrust terms)
    accel : (3, n*d) or None
        A further acceleration at each collocation point, RTN km/s^2 (an outer
        correction: :mod:`lunarcap.optim.correction`).
    """
    c, D = radau_matrices(d)
    f = rhs_function(mode, thrust, accel is not None)
    tau = ca.horzcat(*[mesh_frac[j] + (mesh_frac[j + 1] - mesh_frac[j]) * c[k]
                       for j in range(n) for k in range(d)])
    tpts = t_start + dur * tau
    Sm = ca.repmat(S, 1, n * d)
    args = [Xall[:, 1:] * Sm, U, tpts, ca.repmat(prm, 1, n * d)]
    F = f.map(n * d)(*args, *([accel] if accel is not None else []))
    Fnd = F / Sm * dur  # d x / d tau
    defects = []
    for j in range(n):
        h = mesh_frac[j + 1] - mesh_frac[j]
        dX = ca.mtimes(Xall[:, j * d: j * d + d + 1], D)   # (7, d)
        defects.append(ca.vec(dX - h * Fnd[:, j * d: j * d + d]))
    return ca.vertcat(*defects)


#: Power of the perilune weight of a coast mesh in a gravity field (see
#: :func:`sundman_fractions`): twice Sundman's node density at the perilune, 19 % more
#: 20 % higher up. A field's terms of degree n fall off as (R/r)^(n+2), so near a 100 km
#: perilune they change over minutes (degree 20: a wavelength in 4 min) and higher up
#: they hardly act.
FIELD_PERILUNE_POWER = 10.0


def sundman_fractions(traj_t, traj_x, n: int, perilune_power: float = 0.0) -> np.ndarray:
    """Interval boundaries (fractions of a phase) equally spaced in s = int dt / r.

    On a Kepler orbit s is the eccentric anomaly over sqrt(mu a): equal steps in it put
    the nodes close together near perilune, where the state changes fastest. With
    ``perilune_power`` k > 0 (a coast in a gravity field: :data:`FIELD_PERILUNE_POWER`)
    the density 1/r gains (r_min/r)^k / r_min, r_min the lowest radius of the arc: twice
    as many nodes per unit of s at the lowest point, as many as Sundman's far above it.
    """
    p, f, g, L = traj_x[0], traj_x[1], traj_x[2], traj_x[5]
    r = p / (1 + f * np.cos(L) + g * np.sin(L))
    density = 1 / r
    if perilune_power > 0:
        density = density + (r.min() / r) ** perilune_power / r.min()
    s = np.concatenate([[0.0], np.cumsum(0.5 * (density[1:] + density[:-1])
                                         * np.diff(traj_t))])
    s /= s[-1]
    tau = (traj_t - traj_t[0]) / (traj_t[-1] - traj_t[0])
    frac = np.interp(np.linspace(0, 1, n + 1), s, tau)
    frac[0], frac[-1] = 0.0, 1.0
    return frac
