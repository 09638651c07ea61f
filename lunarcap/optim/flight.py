"""One flight: a solved or planned burn and its coasts, re-flown by the propagator.

Every study that flies a burn flies it here: the verification (:mod:`lunarcap.optim.verify`),
the dispersions (execution errors, the coast to the next perilune), the missed-thrust
cut-off, the export (states at any epochs) and the figures.

* :class:`BurnPlan` is what is flown: the ignition epoch, the duration, the mesh
  intervals and the steering of each (:func:`interval_steering`: the interpolating
  polynomial of its collocated controls, or the closed-form law), in a dynamics model.
  It is read from a solution (:meth:`BurnPlan.of`), moved to another ignition
  (:meth:`BurnPlan.moved`) or spoilt by :class:`ExecutionErrors`
  (:meth:`BurnPlan.with_errors`: thrust and Isp factors, a pointing tilt, an ignition
  offset).
* :func:`fly` flies it from a state (coasting first to its ignition), interval by
  interval with CVODES (rtol 1e-13, :func:`lunarcap.physics.propagate.propagate`), to its
  planned cut-off or an earlier one, densely or not; :func:`coast` and
  :func:`coast_to_perilune` fly what follows, to an epoch or to the next perilune.
  Each returns a :class:`Flown` record: the states (epoch, MEE, mass; a
  :class:`~lunarcap.physics.state.State`) where it starts and ends, the delta-V flown
  (the quadrature of T/m, m/s) and the arc if asked.
* :func:`fly_solution` is the verification's flight of a solution (:class:`Flight`: burn,
  then coast to the end epoch); :func:`cut_off` its burn stopped early; :class:`Arc`
  re-flies pieces of a flight to report states at any epochs (the export).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from lunarcap.errors import InputError
from lunarcap.optim.collocation import radau_matrices
from lunarcap.optim.guess import Guess
from lunarcap.physics import constants as C
from lunarcap.physics.dynamics import Model
from lunarcap.physics.elements import mean_motion_and_anomaly, rv_from_mee
from lunarcap.physics.propagate import N_X, Trajectory, propagate
from lunarcap.physics.state import MASS, State
from lunarcap.physics.steering import COAST, Steering, law, polynomial

#: Output points per mesh interval of a dense burn (the Hermite knots of its arc).
BURN_DENSE_POINTS = 24


# ====================================================================== what is flown
@dataclass(frozen=True)
class ExecutionErrors:
    """How a burn is flown wrong: thrust and Isp factors, tilt (rad, 2), ignition offset (s).

    ``tilt_rad``: two angles about the axes perpendicular to the burn's mean thrust
    direction (:func:`tilt_matrix`); ``ignition_s``: late (> 0) or early, the steering
    following the time since the actual ignition.
    """

    thrust_factor: float = 1.0
    isp_factor: float = 1.0
    tilt_rad: tuple = (0.0, 0.0)
    ignition_s: float = 0.0


NO_ERRORS = ExecutionErrors()


def interval_steering(raw, j: int) -> Steering:
    """The steering flown over burn interval ``j`` of a solution (a RawSolution).

    The polynomial through its collocated controls (optimal law), or the closed-form law
    with its parameters.
    """
    if raw.prob.steering == "optimal":
        c, _ = radau_matrices(raw.mesh.degree)
        d = raw.mesh.degree
        return polynomial(c, raw.u[:, j * d:(j + 1) * d])
    return law(raw.prob.steering, raw.u_inertial)


def rotation(axis_angle) -> np.ndarray:
    """Rotation matrix of a rotation vector (rad), Rodrigues."""
    w = np.asarray(axis_angle, float)
    th = float(np.linalg.norm(w))
    if th == 0.0:
        return np.eye(3)
    k = w / th
    K = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + math.sin(th) * K + (1 - math.cos(th)) * K @ K


def tilt_matrix(controls, tilt_rad) -> np.ndarray:
    """The RTN rotation tilting a burn's thrust by ``tilt_rad`` (two angles, rad).

    ``controls`` (3, n): the burn's collocated thrust directions. The rotation vector lies
    perpendicular to their mean direction: e1 = mean x n / |.|, e2 = mean x e1 with n the
    orbit normal (or the radial axis if the mean is nearly normal); its length is the tilt.
    """
    if not any(tilt_rad):
        return np.eye(3)
    u = np.asarray(controls, float)
    u = u / np.linalg.norm(u, axis=0)
    m = u.mean(axis=1)
    m /= np.linalg.norm(m)
    ref = np.array([0.0, 0.0, 1.0]) if abs(m[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
    e1 = np.cross(m, ref)
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(m, e1)
    return rotation(tilt_rad[0] * e1 + tilt_rad[1] * e2)


def _controls(s: Steering) -> np.ndarray:
    """The (3, d) controls of a polynomial steering."""
    return np.asarray(s.params, float).reshape(3, len(s.nodes), order="F")


@dataclass(frozen=True)
class BurnPlan:
    """A burn to fly: ignition, duration, mesh intervals and their steering, dynamics.

    Attributes
    ----------
    t_ign_s : float
        Ignition epoch, TDB s past J2000.
    duration_s : float
        Planned duration (the timer's cut-off), s.
    fractions : ndarray, shape (n+1,)
        Mesh-interval bounds as fractions of the duration (0 ... 1).
    pieces : tuple of Steering
        The steering of each interval, over tau in [0, 1] across it.
    model : Model
        Dynamics and engine (its thrust and Isp are those flown).
    label : str
        "burn k", for messages.
    """

    t_ign_s: float
    duration_s: float
    fractions: np.ndarray
    pieces: tuple
    model: Model
    label: str = "burn"

    @classmethod
    def of(cls, raw) -> "BurnPlan":
        """The burn of a solution (RawSolution) as the verification flies it."""
        n = len(raw.mesh_burn) - 1
        return cls(raw.prob.t_ign_s, raw.t1_s, raw.mesh_burn,
                   tuple(interval_steering(raw, j) for j in range(n)), raw.prob.model,
                   f"burn {raw.prob.index}")

    @property
    def rel_s(self) -> np.ndarray:
        """Interval bounds in time since ignition, s (full precision: no epoch differences)."""
        return self.duration_s * self.fractions

    @property
    def bounds_s(self) -> np.ndarray:
        """Epochs of the interval bounds, TDB s past J2000."""
        return self.t_ign_s + self.rel_s

    @property
    def end_s(self) -> float:
        """Epoch of the planned cut-off, TDB s past J2000."""
        return float(self.t_ign_s + self.duration_s)

    def direction(self, t_s: float, x) -> np.ndarray:
        """The thrust direction (RTN) at epoch ``t_s`` and state ``x`` (7,)."""
        bounds = self.bounds_s
        j = int(np.clip(np.searchsorted(bounds, t_s, side="right") - 1, 0,
                        len(self.pieces) - 1))
        tau = (t_s - bounds[j]) / (bounds[j + 1] - bounds[j])
        return self.pieces[j](x, tau)

    def moved(self, t_ign_s: float, model: Model | None = None) -> "BurnPlan":
        """The same steering and duration igniting at ``t_ign_s`` (in ``model``)."""
        return replace(self, t_ign_s=t_ign_s, model=model or self.model)

    def with_errors(self, errors: ExecutionErrors) -> "BurnPlan":
        """The burn as flown with execution errors (the plan itself if there are none)."""
        if errors == NO_ERRORS:
            return self
        model = replace(self.model, thrust_N=self.model.thrust_N * errors.thrust_factor,
                        isp_s=self.model.isp_s * errors.isp_factor)
        R = np.eye(3)
        if any(errors.tilt_rad):
            if any(s.kind != "polynomial" for s in self.pieces):
                law_kind = self.pieces[0].kind
                raise InputError(f"pointing errors need the optimal steering (a polynomial "
                                 f"per mesh interval); {self.label} uses {law_kind!r}")
            R = tilt_matrix(np.column_stack([_controls(s) for s in self.pieces]),
                            errors.tilt_rad)
        pieces = self.pieces
        if not np.array_equal(R, np.eye(3)):   # (R U) l / |R U l| = R (U l / |U l|)
            pieces = tuple(polynomial(s.nodes, R @ _controls(s)) for s in pieces)
        return replace(self, t_ign_s=self.t_ign_s + errors.ignition_s, model=model,
                       pieces=pieces)


# ====================================================================== flying
@dataclass
class Flown:
    """A flown arc: its first and last states, the delta-V flown, the arc if asked.

    Attributes
    ----------
    start, end : State
        Epoch (TDB s past J2000), MEE and mass where the arc starts and ends.
    delta_v_mps : float
        The quadrature of T/m along the arc, m/s (0 on a coast).
    arc : Trajectory or None
        The states along the arc (dense: evaluable anywhere on it); for a burn its rows
        are the state and, eighth, the delta-V so far (km/s).
    """

    start: State
    end: State
    delta_v_mps: float = 0.0
    arc: Trajectory | None = None

    @property
    def propellant_kg(self) -> float:
        """Mass spent, kg."""
        return self.start.mass_kg - self.end.mass_kg


def fly(burn: BurnPlan, start: State, until_s: float | None = None, dense: bool = False
        ) -> Flown:
    """Fly ``burn`` from ``start``: the coast to its ignition, then the burn.

    The burn is flown interval by interval of its mesh (within an interval the steering
    is smooth) for its duration (a timer cut-off), or for ``until_s`` after ignition (a
    cut-off before the planned one: 0 <= until_s <= duration).

    Returns
    -------
    Flown
        ``start``: the state at ignition; ``end``: at the cut-off; ``arc``: the burn,
        dense with ``dense`` (else its last interval only).
    """
    x_ign = np.asarray(start.x, float)[:MASS + 1]
    if start.t_s != burn.t_ign_s:
        x_ign = propagate(burn.model, start.t_s, x_ign, burn.t_ign_s).final
    x, arcs = np.append(x_ign, 0.0), []
    rel = burn.rel_s
    for j in range(len(rel) - 1):
        if until_s is not None and until_s <= rel[j]:
            break
        stop = rel[j + 1] if until_s is None else min(rel[j + 1], until_s)
        arcs.append(propagate(burn.model, burn.t_ign_s + rel[j], x[:MASS + 1], None,
                              u=burn.pieces[j], dense=dense, dense_points=BURN_DENSE_POINTS,
                              delta_v=True, dv0_kmps=x[MASS + 1], duration_s=stop - rel[j]))
        x = arcs[-1].final
    t_end = burn.t_ign_s + (burn.duration_s if until_s is None else until_s)
    arc = None
    if arcs:
        arc = Trajectory.join(arcs) if dense else arcs[-1]
    return Flown(State(burn.t_ign_s, x_ign), State(t_end, x[:MASS + 1].copy()),
                 float(x[MASS + 1]) * 1e3, arc)


def coast(model: Model, start: State, t1_s: float, **kw) -> Flown:
    """Coast from ``start`` to the epoch ``t1_s`` (either direction).

    ``kw``: :func:`lunarcap.physics.propagate.propagate`'s options (``dense``,
    ``t_eval``, ``rtol``, ``atol``). The arc is always returned.
    """
    tr = propagate(model, start.t_s, np.asarray(start.x, float)[:MASS + 1], t1_s, u=None, **kw)
    return Flown(start, State(float(tr.t[-1]), tr.final), 0.0, tr)


def coast_to_perilune(model: Model, start: State, t_guess_s: float, tol_s: float = 1e-3
                      ) -> State:
    """The perilune nearest ``t_guess_s`` on the coast from ``start``.

    Propagates to the guess, jumps by the osculating mean anomaly, then Newton on
    r.v = 0 (rate v^2 - mu/r), in the model's dynamics.
    """
    t, xx = float(start.t_s), np.asarray(start.x, float)[:MASS + 1]
    target = float(t_guess_s)
    xx = propagate(model, t, xx, target).final
    t = target
    n, M = mean_motion_and_anomaly(xx, C.MU_MOON)
    dt = -float(M) / float(n)
    for _ in range(8):
        if abs(dt) < tol_s:
            break
        xx = propagate(model, t, xx, t + dt).final
        t += dt
        r, v = (np.array(a, float) for a in rv_from_mee(*xx[:6], C.MU_MOON))
        rv = float(r @ v)
        rate = float(v @ v) - C.MU_MOON / float(np.linalg.norm(r))
        dt = -rv / rate
    return State(t, xx)


def flown_guess(raw, prob) -> Guess:
    """A solved burn's steering flown from another problem's ignition state: its guess.

    The solution's duration and steering (shifted to ``prob``'s ignition, in its
    dynamics), the burn and the coast to the problem's end propagated from the problem's
    initial state: a guess that is the solution where the two problems agree.
    """
    burn = BurnPlan.of(raw).moved(prob.t_ign_s, prob.model)
    flown = fly(burn, State(prob.t_ign_s, prob.x0), dense=True)
    after = coast(prob.model, flown.end, prob.t_end_s, dense=True, rtol=1e-8, atol=1e-10)
    arc = flown.arc
    return Guess(burn.duration_s, lambda t: burn.direction(t, arc(t)[:N_X]), arc, after.arc)


# ====================================================================== a solution's flight
@dataclass
class Flight:
    """The re-propagated flight of a solution: the burn (piecewise) and the coast."""

    burn: Trajectory
    coast: Trajectory
    delta_v_mps: float

    @property
    def end_state(self) -> np.ndarray:
        """State (p, f, g, h, k, L, m) at the end of the coast."""
        return self.coast.final

    @property
    def cutoff(self) -> State:
        """The state at the burn's cut-off."""
        return State(float(self.coast.t[0]), self.coast.x[:, 0])

    @property
    def nfev(self) -> int:
        """Right-hand-side evaluations of the whole flight."""
        return self.burn.nfev + self.coast.nfev


def fly_solution(raw) -> Flight:
    """Re-propagate a solution's steering from its initial state: the burn, then the coast.

    The burn densely (:data:`BURN_DENSE_POINTS` per mesh interval), the coast to the
    problem's end epoch densely: the flight the verification gates.
    """
    prob = raw.prob
    burn = fly(BurnPlan.of(raw), State(prob.t_ign_s, prob.x0), dense=True)
    after = coast(prob.model, burn.end, prob.t_end_s, dense=True)
    return Flight(burn.arc, after.arc, burn.delta_v_mps)


def cut_off(raw, duration_s: float) -> Flown:
    """A solution's burn flown from its initial state and stopped after ``duration_s``.

    ``0 <= duration_s <=`` the burn's duration, else ValueError.
    """
    prob = raw.prob
    if not 0.0 <= duration_s <= raw.t1_s * (1 + 1e-12):
        raise ValueError(f"a cut-off after {duration_s} s is outside the burn's "
                         f"{raw.t1_s} s")
    return fly(BurnPlan.of(raw), State(prob.t_ign_s, prob.x0), until_s=duration_s)


# ====================================================================== states at any epochs
@dataclass
class Arc:
    """An arc re-flown on demand: pieces ``(t0, x0 (7,), duration, steering)`` in ``model``."""

    name: str
    model: Model
    pieces: list
    thrust_N: float = 0.0

    @property
    def span(self) -> tuple:
        """(first, last) epoch, s."""
        ends = [p[0] for p in self.pieces] + [p[0] + p[2] for p in self.pieces]
        return min(ends), max(ends)

    def states(self, t) -> np.ndarray:
        """(7, M) states (p, f, g, h, k, L, m) at increasing epochs ``t`` within the arc.

        Each piece is propagated from its first state to the epochs in it (CVODES, rtol
        1e-13): nothing is interpolated.
        """
        t = np.asarray(t, float)
        out = np.full((MASS + 1, t.size), np.nan)
        for t0, x0, dur, steer in self.pieces:
            lo, hi = min(t0, t0 + dur), max(t0, t0 + dur)
            sel = np.flatnonzero((t >= lo - 1e-9) & (t <= hi + 1e-9) & np.isnan(out[0]))
            if not sel.size:
                continue
            order = sel if dur > 0 else sel[::-1]   # in the direction of integration
            tt = np.clip(t[order], lo, hi)
            exact = tt == t0
            if exact.all():
                out[:, order] = np.asarray(x0)[:, None]
                continue
            tr = propagate(self.model, t0, x0, None, u=steer, duration_s=dur,
                           thrust_N=self.thrust_N if steer.thrusting else 0.0,
                           t_eval=tt[~exact])
            out[:, order[~exact]] = tr.x
            out[:, order[exact]] = np.asarray(x0)[:, None]
        return out


def burn_arc(name: str, raw, flight: Flight) -> Arc:
    """A solution's burn as an :class:`Arc`: each interval from the flight's state there."""
    plan = BurnPlan.of(raw)
    bounds, burn = plan.bounds_s, flight.burn
    pieces = []
    for j, steer in enumerate(plan.pieces):
        k = int(np.argmin(np.abs(burn.t - bounds[j])))
        pieces.append((burn.t[k], burn.x[:MASS + 1, k], bounds[j + 1] - bounds[j], steer))
    return Arc(name, plan.model, pieces, plan.model.thrust_N)


def coast_arc(name: str, model: Model, start: State, duration_s: float) -> Arc:
    """A coast of ``duration_s`` (negative: backward) from ``start`` as an :class:`Arc`."""
    return Arc(name, model, [(start.t_s, start.x, duration_s, COAST)])
