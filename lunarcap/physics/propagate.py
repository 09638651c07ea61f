"""Adaptive-step propagation of coasts and burns (scipy DOP853), forward or backward.

The right-hand side is the CasADi Function of :func:`lunarcap.physics.dynamics.rhs_function`,
called numerically, so propagation and the transcription use the same equations.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np
from scipy.integrate import solve_ivp

from lunarcap.physics.dynamics import Model, rhs_function
from lunarcap.errors import InputError

#: Default tolerances: relative 1e-12, absolute per state (p km, f, g, h, k, L rad, m kg).
RTOL = 1e-12
ATOL = np.array([1e-9, 1e-13, 1e-13, 1e-13, 1e-13, 1e-13, 1e-10])


@dataclass
class Trajectory:
    """Propagated states: ``t`` (N,) TDB s past J2000; ``x`` (7, N) MEE + mass."""

    t: np.ndarray
    x: np.ndarray
    nfev: int
    sol: object | None = None  # scipy dense output, if asked

    @property
    def final(self) -> np.ndarray:
        """State at the last epoch."""
        return self.x[:, -1]


def propagate(model: Model, t0_s: float, x0, t1_s: float,
              u: Callable[[float], np.ndarray] | np.ndarray | None = None,
              thrust_N: float | None = None, rtol: float = RTOL, atol=ATOL,
              t_eval=None, dense: bool = False, events=None) -> Trajectory:
    """Propagate ``x0 = (p, f, g, h, k, L, m)`` from t0_s to t1_s (either direction).

    Parameters
    ----------
    model : Model
        Dynamics; its ``thrust_N`` applies unless ``thrust_N`` is given (0 for a coast).
    u : callable t -> (3,), or (3,) array, or None
        Thrust direction in RTN (unit vector). ``None`` means a coast.
    t_eval : array_like or None
        Epochs at which to report the state.
    """
    x0 = np.asarray(x0, dtype=float)
    if x0.shape != (7,) or not np.all(np.isfinite(x0)):
        raise InputError(f"initial state must be 7 finite numbers (p,f,g,h,k,L,m), got {x0}")
    if x0[0] <= 0 or x0[6] <= 0:
        raise InputError("initial state needs p > 0 km and m > 0 kg")
    if u is None:
        thrust = 0.0
        ufun = lambda t: np.zeros(3)  # noqa: E731
    else:
        thrust = model.thrust_N if thrust_N is None else thrust_N
        ufun = u if callable(u) else (lambda t, _u=np.asarray(u, float): _u)
    if model.fit is not None:
        lo, hi = min(t0_s, t1_s), max(t0_s, t1_s)
        if lo < model.fit.t0_s - 1e-6 or hi > model.fit.t1_s + 1e-6:
            raise InputError("propagation leaves the ephemeris-fit window "
                             f"[{model.fit.t0_s}, {model.fit.t1_s}] s")
    f = rhs_function(model.mode)
    prm = model.params(thrust)
    # Integrate in time elapsed since t0_s: epochs past J2000 (~5e8 s) carry only ~6e-8 s
    # of resolution, which would blur short high-thrust arcs.
    t0_s = float(t0_s)

    def rhs(s, x):
        t = t0_s + s
        return np.asarray(f(x, ufun(t), t, prm)).ravel()

    if t1_s == t0_s:
        return Trajectory(np.array([t0_s]), x0[:, None].copy(), 0)
    s_eval = None if t_eval is None else np.asarray(t_eval, float) - t0_s
    res = solve_ivp(rhs, (0.0, t1_s - t0_s), x0, method="DOP853", rtol=rtol, atol=atol,
                    t_eval=s_eval, dense_output=dense, events=events)
    if not res.success:
        raise RuntimeError(f"propagation failed: {res.message}")
    sol = _Shifted(res.sol, t0_s) if dense else None
    return Trajectory(t0_s + res.t, res.y, res.nfev, sol)


class _Shifted:
    """Dense output evaluated at epochs (s past J2000) though integrated in elapsed time."""

    def __init__(self, sol, t0_s: float):
        self.sol, self.t0_s = sol, t0_s

    def __call__(self, t):
        return self.sol(np.asarray(t, float) - self.t0_s)
