"""Adaptive-step propagation of coasts and burns in compiled code (CVODES), either direction.

The right-hand side is :func:`lunarcap.physics.dynamics.rhs_function`, the same CasADi
Function the transcription uses; the steering is a :class:`~lunarcap.physics.steering.Steering`
(a coast, a constant direction, a closed-form law of the state, or the interpolating
polynomial of collocated controls). For each kind of arc CasADi's interface to SUNDIALS
CVODES (variable-order Adams steps, relative tolerance 1e-13) is built once per process
and then called with the arc's numbers: the whole integration runs in compiled code,
with its own error control, independently of the collocation.

The integration variable is the fraction of the arc, tau in [0, 1] (time elapsed since
the start over the arc's duration, which may be negative): epochs past J2000 (~5e8 s)
carry only ~6e-8 s of resolution, so durations are passed exactly and never formed as
differences of epochs. The states are scaled (p by its initial value, the mass by its
initial value) so that one absolute tolerance fits them all.

:class:`Trajectory` is the one container of propagated states in lunarcap: epochs,
states and, when asked, a piecewise cubic Hermite interpolant (values and derivatives at
the output points, clustered near both ends of an arc, where it passes a perilune) for
evaluation between them.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import lru_cache

import casadi as ca
import numpy as np

from lunarcap.errors import InputError
from lunarcap.physics.dynamics import P_THRUST, Model, force_model, rhs_function
from lunarcap.physics.steering import COAST, Steering, constant

#: Default relative tolerance, and absolute tolerance of the scaled states. At 1e-13 a
#: two-body 12.235 h ellipse closes to 1e-9 rad in L after one period (at 1e-12: 7e-9);
#: the cost is ~10 % more steps.
RTOL = 1e-13
ATOL = 1e-13

#: Turns an arc's DAE (a dict of SX: x, t, p, ode) into a compiled function of the same bits,
#: or returns it; set with the optimiser's store (:func:`lunarcap.optim.nlp.use_store`).
ARC_COMPILER = None

#: Output points of a dense arc (the Hermite interpolant's knots), per arc.
DENSE_POINTS = 240

N_X = 7


@dataclass
class Trajectory:
    """Propagated states: epochs ``t`` (N,) TDB s past J2000 and states ``x`` (n, N).

    With dense output, calling the trajectory at epochs evaluates its interpolant
    (piecewise, for a trajectory joined from several arcs):
    ``traj(t)`` -> (n,) for a scalar epoch, (n, M) for M epochs.
    """

    t: np.ndarray
    x: np.ndarray
    nfev: int = 0
    pieces: tuple = field(default=(), repr=False)  # (t_lo, t_hi, t_origin, callable(s))

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


class Hermite:
    """Piecewise cubic Hermite interpolant through values and derivatives at knots.

    ``Hermite(s, x, dx)(s_query)`` with knots ``s`` (N,) monotonic (either direction),
    values ``x`` (n, N) and derivatives ``dx`` (n, N) with respect to s; it reproduces a
    cubic exactly and is C1 across knots. Outside the knots the end pieces extrapolate.
    """

    def __init__(self, s, x, dx):
        s = np.asarray(s, float)
        order = np.argsort(s)
        self.s, self.x, self.dx = s[order], np.asarray(x)[:, order], np.asarray(dx)[:, order]

    def __call__(self, q):
        """Values at ``q`` (n, M)."""
        q = np.atleast_1d(np.asarray(q, float))
        j = np.clip(np.searchsorted(self.s, q, side="right") - 1, 0, len(self.s) - 2)
        s0, s1 = self.s[j], self.s[j + 1]
        h = s1 - s0
        u = (q - s0) / h
        h00 = (1 + 2 * u) * (1 - u) ** 2
        h10 = u * (1 - u) ** 2
        h01 = u * u * (3 - 2 * u)
        h11 = u * u * (u - 1)
        return (h00 * self.x[:, j] + h10 * h * self.dx[:, j] + h01 * self.x[:, j + 1]
                + h11 * h * self.dx[:, j + 1])


# ---------------------------------------------------------------------- compiled arcs
def _arc_rhs(mode: str, steering: Steering, quadrature: bool):
    """Symbols and the scaled right-hand side dy/dtau of an arc.

    Parameters of the arc: the dynamics parameters (``n_param`` of the model), the start
    epoch t0 (s), the duration span (s), the scales of p (km) and m (kg), and the
    steering's numbers.
    """
    n_s = len(steering.params)
    y = ca.SX.sym("y", N_X + (1 if quadrature else 0))
    tau = ca.SX.sym("tau")
    prm = ca.SX.sym("prm", force_model(mode).n_param)
    t0, span, sp, sm = ca.SX.sym("t0"), ca.SX.sym("span"), ca.SX.sym("sp"), ca.SX.sym("sm")
    ps = ca.SX.sym("ps", n_s)
    scale = ca.vertcat(sp, 1, 1, 1, 1, 1, sm)
    x = y[:N_X] * scale
    u = steering.direction([x[i] for i in range(N_X)], tau, [ps[i] for i in range(n_s)])
    xdot = rhs_function(mode, steering.thrusting)(x, ca.vertcat(*u), t0 + span * tau, prm)
    rates = [span * xdot / scale]
    if quadrature:  # delta-V of the thrust, int T/m dt (km/s): T in kN / m in kg
        rates.append(span * prm[P_THRUST] / x[6])
    p = ca.vertcat(prm, t0, span, sp, sm, ps)
    return y, tau, p, ca.vertcat(*rates)


@lru_cache(maxsize=128)
def _integrator(mode: str, steering: Steering, quadrature: bool, grid: tuple, rtol: float,
                atol: float) -> tuple:
    """The CVODES integrator of one kind of arc with outputs at ``grid`` (tau values).

    ``steering`` has zeroed parameters (:func:`_shape`): one compiled integrator per
    dynamics mode, steering kind, quadrature and output grid.
    """
    y, tau, p, ode = _arc_rhs(mode, steering, quadrature)
    opts = {"abstol": atol, "reltol": rtol, "max_num_steps": 200000,
            "linear_multistep_method": "adams", "nonlinear_solver_iteration": "functional"}
    dae = {"x": y, "t": tau, "p": p, "ode": ode}
    integ = ca.integrator("arc", "cvodes", ARC_COMPILER(dae) if ARC_COMPILER else dae, 0.0,
                          list(grid), opts)
    rhs = ca.Function("arc_rhs", [y, tau, p], [ode])
    return integ, rhs.map(len(grid) + 1)


def _nfev(integ) -> int:
    """Right-hand-side evaluations of the integrator's last call (0 if not reported)."""
    try:
        st = integ.stats()
    except Exception:  # stats unavailable in this CasADi build
        return 0
    return int(st.get("nfevals", st.get("nfevals_total", 0)) or 0)


def _steering_of(u) -> Steering:
    if u is None:
        return COAST
    if isinstance(u, Steering):
        return u
    return constant(u)


def _shape(steering: Steering) -> Steering:
    """The steering with zeroed parameters: what a compiled integrator is keyed by."""
    return Steering(steering.kind, (0.0,) * len(steering.params), steering.nodes)


def _output_grid(t0_s: float, span: float, t_eval, dense: bool, dense_points: int) -> tuple:
    """(output fractions of the arc after its start, whether the start is an output)."""
    if t_eval is not None:
        taus = (np.asarray(t_eval, float) - t0_s) / span
        # an epoch past J2000 carries ~6e-8 s of resolution: the arc's end epoch t0 + span
        # may round to a tau a few ulps of t0 beyond 1 (8e-12 for a 2 h arc)
        tol = 1e-12 + 4.0 * float(np.spacing(abs(t0_s))) / abs(span)
        if np.any(taus < -tol) or np.any(taus > 1 + tol) or np.any(np.diff(taus) <= 0):
            raise InputError("t_eval must be epochs within the arc, in the direction of "
                             "integration")
        taus = np.clip(taus, 0.0, 1.0)
        return tuple(float(v) for v in taus if v > 0.0) or (1.0,), bool(taus[0] == 0.0)
    if dense:  # knots clustered at both ends, where arcs pass their perilunes
        k = np.arange(1, dense_points + 1)
        return tuple(float(v) for v in 0.5 * (1.0 - np.cos(np.pi * k / dense_points))), True
    return (1.0,), True


def propagate(model: Model, t0_s: float, x0, t1_s: float | None,
              u: Steering | np.ndarray | None = None, thrust_N: float | None = None,
              rtol: float = RTOL, atol: float = ATOL, t_eval=None, dense: bool = False,
              delta_v: bool = False, dv0_kmps: float = 0.0,
              duration_s: float | None = None, dense_points: int = DENSE_POINTS
              ) -> Trajectory:
    """Propagate ``x0 = (p, f, g, h, k, L, m)`` from t0_s to t1_s (either direction).

    Parameters
    ----------
    model : Model
        Dynamics; its ``thrust_N`` applies unless ``thrust_N`` is given (0 for a coast).
    u : Steering, or (3,) array (a constant RTN direction), or None (a coast)
    rtol, atol : relative tolerance, absolute tolerance of the scaled states
    t_eval : array_like, optional
        Epochs at which to report the state (between t0 and t1, in order).
    dense : bool
        Keep a Hermite interpolant through ``dense_points`` outputs, for evaluation
        anywhere on the arc (``traj(t)``).
    delta_v : bool
        Also integrate the delta-V of the thrust, int T/m dt (km/s), as an eighth state,
        starting from ``dv0_kmps``.
    duration_s : float, optional
        The span to integrate, s (then ``t1_s`` is ignored): a short arc given by two
        epochs would be off by their resolution.

    Returns
    -------
    Trajectory
        States at t0 and at the output epochs (``t_eval``, else the dense knots, else the
        end only).
    """
    x0 = np.asarray(x0, dtype=float)
    t0_s = float(t0_s)
    span = float(t1_s) - t0_s if duration_s is None else float(duration_s)
    t1_s = t0_s + span
    if x0.shape != (7,) or not np.all(np.isfinite(x0)):
        raise InputError(f"initial state must be 7 finite numbers (p,f,g,h,k,L,m), got {x0}")
    if x0[0] <= 0 or x0[6] <= 0:
        raise InputError("initial state needs p > 0 km and m > 0 kg")
    steering = _steering_of(u)
    thrust = 0.0 if not steering.thrusting else (model.thrust_N if thrust_N is None
                                                 else thrust_N)
    if model.fit is not None:
        lo, hi = min(t0_s, t1_s), max(t0_s, t1_s)
        if lo < model.fit.t0_s - 1e-6 or hi > model.fit.t1_s + 1e-6:
            raise InputError("propagation leaves the ephemeris-fit window "
                             f"[{model.fit.t0_s}, {model.fit.t1_s}] s")
    y0 = x0 / np.array([x0[0], 1, 1, 1, 1, 1, x0[6]])
    if delta_v:
        y0 = np.append(y0, float(dv0_kmps))
    if span == 0.0:
        return Trajectory(np.array([t0_s]), (np.append(x0, dv0_kmps) if delta_v
                                             else x0)[:, None].copy(), 0)
    grid, with_start = _output_grid(t0_s, span, t_eval, dense, dense_points)
    integ, rhs_map = _integrator(model.mode, _shape(steering), bool(delta_v), grid,
                                 float(rtol), float(atol))
    pvec = np.concatenate([model.params(thrust), [t0_s, span, x0[0], x0[6]],
                           np.asarray(steering.params, float)])
    try:
        res = integ(x0=y0, p=pvec)
    except RuntimeError as exc:  # CVODES failed (too many steps, a singular state)
        raise RuntimeError(f"propagation failed: {exc}") from None
    ys = np.column_stack([y0, np.asarray(res["xf"])])
    scale = np.array([x0[0], 1, 1, 1, 1, 1, x0[6]] + ([1.0] if delta_v else []))
    xs = ys * scale[:, None]
    taus_all = np.concatenate([[0.0], grid])
    ts = t0_s + span * taus_all
    if not with_start:   # t_eval: exactly the epochs asked for
        return Trajectory(ts[1:], xs[:, 1:], _nfev(integ))
    nfev = _nfev(integ)
    pieces = ()
    if dense:
        dydtau = np.asarray(rhs_map(ys, taus_all, np.tile(pvec[:, None], len(taus_all))))
        dx_ds = dydtau * scale[:, None] / span   # per second of elapsed time
        pieces = ((t0_s, t1_s, t0_s, Hermite(span * taus_all, xs, dx_ds)),)
    return Trajectory(ts, xs, nfev, pieces)
