"""Adaptive-step propagation of coasts and burns (scipy DOP853), forward or backward.

The right-hand side is the CasADi Function of :func:`lunarcap.physics.dynamics.rhs_function`,
called numerically, so propagation and the transcription use the same equations.
:class:`Trajectory` is the one container of propagated states in lunarcap: epochs,
states, and (when asked) dense output between them, possibly piecewise.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np
from scipy.integrate import solve_ivp

from lunarcap.errors import InputError
from lunarcap.physics.dynamics import Model, rhs_function

#: Default tolerances: relative 1e-12, absolute per state (p km, f, g, h, k, L rad, m kg).
RTOL = 1e-12
ATOL = np.array([1e-9, 1e-13, 1e-13, 1e-13, 1e-13, 1e-13, 1e-10])


@dataclass
class Trajectory:
    """Propagated states: epochs ``t`` (N,) TDB s past J2000 and states ``x`` (n, N).

    With dense output, calling the trajectory at epochs evaluates the interpolant of the
    integrator (piecewise, for a trajectory joined from several arcs):
    ``traj(t)`` -> (n,) for a scalar epoch, (n, M) for M epochs.
    """

    t: np.ndarray
    x: np.ndarray
    nfev: int = 0
    pieces: tuple = field(default=(), repr=False)  # (t_lo, t_hi, t_origin, scipy dense)

    @property
    def final(self) -> np.ndarray:
        """State at the last epoch."""
        return self.x[:, -1]

    @property
    def dense(self) -> bool:
        """True if the trajectory can be evaluated between its epochs."""
        return bool(self.pieces)

    def __call__(self, t):
        """States at epochs ``t`` (s past J2000) from the dense output."""
        if not self.pieces:
            raise ValueError("this trajectory was propagated without dense output")
        scalar = np.ndim(t) == 0
        tt = np.atleast_1d(np.asarray(t, float))
        los = np.array([min(p[0], p[1]) for p in self.pieces])
        order = np.argsort(los)
        j = np.clip(np.searchsorted(los[order], tt, side="right") - 1, 0, len(order) - 1)
        out = np.empty((self.x.shape[0], tt.size))
        for k in np.unique(j):
            lo, hi, t0, sol = self.pieces[order[k]]
            sel = j == k
            out[:, sel] = sol(tt[sel] - t0)
        return out[:, 0] if scalar else out

    @classmethod
    def join(cls, arcs) -> "Trajectory":
        """One trajectory from consecutive arcs (each arc's first epoch = previous last)."""
        arcs = list(arcs)
        t = np.concatenate([arcs[0].t] + [a.t[1:] for a in arcs[1:]])
        x = np.column_stack([arcs[0].x] + [a.x[:, 1:] for a in arcs[1:]])
        return cls(t, x, sum(a.nfev for a in arcs), tuple(p for a in arcs for p in a.pieces))


Steering = Callable[[float, np.ndarray], np.ndarray]


def propagate(model: Model, t0_s: float, x0, t1_s: float | None,
              u: Steering | np.ndarray | None = None, thrust_N: float | None = None,
              rtol: float = RTOL, atol=ATOL, t_eval=None, dense: bool = False,
              events=None, delta_v: bool = False, dv0_kmps: float = 0.0,
              duration_s: float | None = None) -> Trajectory:
    """Propagate ``x0 = (p, f, g, h, k, L, m)`` from t0_s to t1_s (either direction).

    Parameters
    ----------
    model : Model
        Dynamics; its ``thrust_N`` applies unless ``thrust_N`` is given (0 for a coast).
    u : callable (t, x) -> (3,), or (3,) array, or None
        Thrust direction in RTN (unit vector), a constant or a function of the epoch and
        the state (a feedback law). ``None`` means a coast.
    t_eval : array_like or None
        Epochs at which to report the state.
    delta_v : bool
        Also integrate the delta-V of the thrust, int T/m dt (km/s), as an eighth state,
        starting from ``dv0_kmps``.
    duration_s : float, optional
        The span to integrate, s (then ``t1_s`` is ignored). Epochs past J2000 (~5e8 s)
        carry only ~6e-8 s of resolution, so a short arc given by two epochs would be
        shortened or lengthened by that much; a 2 s burn at 180 m/s^2 would change its
        delta-V by 1e-5 m/s.
    """
    x0 = np.asarray(x0, dtype=float)
    t0_s = float(t0_s)
    span = float(t1_s) - t0_s if duration_s is None else float(duration_s)
    t1_s = t0_s + span
    if x0.shape != (7,) or not np.all(np.isfinite(x0)):
        raise InputError(f"initial state must be 7 finite numbers (p,f,g,h,k,L,m), got {x0}")
    if x0[0] <= 0 or x0[6] <= 0:
        raise InputError("initial state needs p > 0 km and m > 0 kg")
    if u is None:
        thrust = 0.0
        ufun = lambda t, x: _ZERO  # noqa: E731
    else:
        thrust = model.thrust_N if thrust_N is None else thrust_N
        ufun = u if callable(u) else (lambda t, x, _u=np.asarray(u, float): _u)
    if model.fit is not None:
        lo, hi = min(t0_s, t1_s), max(t0_s, t1_s)
        if lo < model.fit.t0_s - 1e-6 or hi > model.fit.t1_s + 1e-6:
            raise InputError("propagation leaves the ephemeris-fit window "
                             f"[{model.fit.t0_s}, {model.fit.t1_s}] s")
    f = rhs_function(model.mode)
    prm = model.params(thrust)
    thrust_kN = thrust * 1e-3
    # Integrate in time elapsed since t0_s: epochs past J2000 (~5e8 s) carry only ~6e-8 s
    # of resolution, which would blur short high-thrust arcs.

    if delta_v:
        def rhs(s, y):
            t = t0_s + s
            xd = np.asarray(f(y[:7], ufun(t, y[:7]), t, prm)).ravel()
            return np.append(xd, thrust_kN / y[6])
        y0 = np.append(x0, float(dv0_kmps))
        atol = np.append(np.broadcast_to(atol, 7), 1e-13)
    else:
        def rhs(s, y):
            t = t0_s + s
            return np.asarray(f(y, ufun(t, y), t, prm)).ravel()
        y0 = x0

    if span == 0.0:
        return Trajectory(np.array([t0_s]), y0[:, None].copy(), 0)
    s_eval = None if t_eval is None else np.asarray(t_eval, float) - t0_s
    res = solve_ivp(rhs, (0.0, span), y0, method="DOP853", rtol=rtol, atol=atol,
                    t_eval=s_eval, dense_output=dense, events=events)
    if not res.success:
        raise RuntimeError(f"propagation failed: {res.message}")
    pieces = ((t0_s, t1_s, t0_s, res.sol),) if dense else ()
    return Trajectory(t0_s + res.t, res.y, res.nfev, pieces)


_ZERO = np.zeros(3)
