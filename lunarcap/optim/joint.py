"""All burns of a capture plan in one NLP, the total delta-V its objective (beyond the paper).

The paper optimises one burn at a time with the proxy objective Eq. (9). Here the single
burn leg (:func:`~lunarcap.optim.transcription.add_leg`) is composed N times, leg k
starting where leg k-1 ends, each with a free ignition and the same target conditions as
alone, so that the comparison isolates what the one-at-a-time approach loses. The optimum
is verified leg by leg like a single burn, each from the previous leg's verified end.

A leg's coast (from the epoch its ignition counts from to the perilune where its target
holds) may be a decision variable instead of the plan's period: the NLP then chooses the
intermediate orbits, within bounds on each coast, an order (no free coast longer than the
free one before it), a limit on the time to the end of the last burn and, optionally, on
each orbit's period. The optimum is returned as the plan with those coasts.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from functools import lru_cache

import casadi as ca
import numpy as np

from lunarcap.errors import SolveError
from lunarcap.mission.plan import CapturePlan
from lunarcap.mission.targets import N_VALUES
from lunarcap.optim.collocation import (
    FIELD_PERILUNE_POWER,
    LU,
    N_PRE,
    N_X,
    TU,
    Mesh,
    node_epochs,
    state_scale,
    sundman_fractions,
)
from lunarcap.optim.correction import (
    MAX_ITERATIONS,
    TOL_KMPS2,
    carried,
    field_difference,
    field_mesh,
    largest_change,
    nlp_shape,
    whole,
)
from lunarcap.optim.flight import BurnPlan
from lunarcap.optim.guess import Guess
from lunarcap.optim.nlp import (
    RawSolution,
    initial_point,
    leg_bounds,
    leg_solution,
    stored,
)
from lunarcap.optim.problem import END_WINDOW_FRACTION, burn_problem
from lunarcap.optim.solution import Solution
from lunarcap.optim.transcription import NLPBuilder, add_leg, dynamics_params
from lunarcap.optim.verify import verify
from lunarcap.physics.dynamics import force_model
from lunarcap.physics.elements import speed_from_mee
from lunarcap.physics.rocket import rocket_delta_v_mps


@dataclass
class JointNLP:
    """A compiled all-burns NLP and its legs' outputs (functions of w, p: LEG_OUTPUTS)."""

    compiled: object
    legs: list


def _of(plan) -> str:
    """' of plan NAME' for a message, or '' for a plan whose name a cache key blanked.

    The caller that knows the name says it (a study's row, the command line).
    """
    return f" of plan {plan.name}" if plan.name else ""


@lru_cache(maxsize=None)
def build_joint_nlp(mesh: Mesh, target_kinds: tuple, mode: str = "full",
                    free_coasts: tuple = (), period_rows: bool = False,
                    expand: bool = False) -> JointNLP:
    """The NLP of N legs (one per target kind), each with a free ignition, linked end to start.

    Built once per machine and loaded by later processes where the optimiser has a store
    (:func:`lunarcap.optim.nlp.stored`), once per process otherwise; see :func:`_build`.
    """
    in_nlp, correction = nlp_shape(mode)  # what the NLP carries keys it, not the whole field
    key = (mesh, tuple(target_kinds), force_model(in_nlp).key, bool(correction),
           tuple(free_coasts), bool(period_rows), bool(expand))
    compiled = stored("joint", key, lambda compile_fn: _build(
        mesh, target_kinds, mode, free_coasts, period_rows, expand, compile_fn))
    return JointNLP(compiled, [compiled.outputs.get(f"leg{k}")
                               for k in range(len(target_kinds))])


def _build(mesh: Mesh, target_kinds: tuple, mode, free_coasts: tuple, period_rows: bool,
           expand: bool, compile_fn=None):
    """The all-burns NLP (a CompiledNLP) of :func:`build_joint_nlp`.

    Parameters (by name): ``x_start`` (the state at the first nominal perilune, physical),
    ``t_ref`` (the N+1 nominal perilune epochs), and per leg ``leg<k>.dynamics``,
    ``leg<k>.mesh_burn``, ``leg<k>.mesh_coast``, ``leg<k>.target``.

    ``free_coasts``: one flag per leg (empty: none free). A free leg k has a variable
    ``leg<k>.coast`` (TU), its coast from t_k to t_{k+1}; the epochs after it are t_k plus
    the coasts (fixed ones from ``t_ref``). Then also the constraint rows ``coast_order``
    (coast_k - coast_{k+1} >= 0 for consecutive free legs; the solver may release them)
    and ``time_limit`` (end of the last burn minus t_0, TU; its upper bound set by the
    solver).

    ``period_rows`` (with free coasts): one more row per free leg, ``energy_limit``, the
    specific orbital energy at the end of its coast, -(1 - f^2 - g^2) / (2 p) (VU^2, the
    osculating orbit at the perilune where its target holds); the solver bounds it above
    to bound that orbit's period.

    ``expand`` (:meth:`NLPBuilder.compile`) applies only where the derivatives are not
    assembled node by node: expanding an all-burns NLP then cost 3-14 s of CPU against
    0.1-1.6 s unexpanded, for solves about 2x faster. ``compile_fn``: the node compiler.

    ``mode`` in a gravity field beyond what the NLP carries: each leg carries the field cut
    as a single burn's NLP does (:func:`lunarcap.optim.correction.nlp_shape`) plus the
    parameters ``leg<k>.accel_pre``, ``leg<k>.accel_burn``, ``leg<k>.accel_coast`` of the
    outer correction; :func:`lunarcap.optim.correction.whole` of a field carries it whole.
    """
    in_nlp, correction = nlp_shape(mode)
    nb, nc = mesh.n_burn, mesh.n_coast
    n = len(target_kinds)
    free = tuple(bool(f) for f in free_coasts) or (False,) * n
    if len(free) != n:
        raise ValueError(f"free_coasts needs one flag per leg ({n}), got {len(free)}")
    nlp = NLPBuilder()
    P_x0 = nlp.param("x_start", N_X)
    P_tref = nlp.param("t_ref", n + 1)
    S = ca.vertcat(LU, 1, 1, 1, 1, 1, P_x0[6])
    x_start, J, legs, coasts = P_x0 / S, 0, [], {}
    t = [P_tref[0]]
    for k, kind in enumerate(target_kinds):
        if free[k]:
            coasts[k] = nlp.var(f"leg{k}.coast", 1)
            t.append(t[k] + coasts[k] * TU)
        elif not any(free[:k]):
            t.append(P_tref[k + 1])
        else:
            t.append(t[k] + (P_tref[k + 1] - P_tref[k]))
    for k, kind in enumerate(target_kinds):
        pre = f"leg{k}."
        leg = add_leg(nlp, pre, mesh, kind, x_start, t[k], t[k + 1],
                      dynamics_params(nlp, pre + "dynamics", in_nlp),
                      nlp.param(pre + "mesh_burn", nb + 1),
                      nlp.param(pre + "mesh_coast", nc + 1), nlp.param(pre + "target", N_VALUES), S,
                      in_nlp, free_start=True, correction=correction)
        legs.append(leg)
        x_start = leg.xf
        J = J + leg.dv
    if any(free):
        for k in range(n - 1):
            if free[k] and free[k + 1]:
                nlp.constrain(coasts[k] - coasts[k + 1], "coast_order", 0.0, np.inf)
        last = legs[-1]
        nlp.constrain((last.t_ign + last.t1 - t[0]) / TU, "time_limit", 0.0, np.inf)
        for k in range(n) if period_rows else ():
            if free[k]:
                xf = legs[k].xf
                nlp.constrain(-(1 - xf[1] ** 2 - xf[2] ** 2) / (2 * xf[0]), "energy_limit",
                              -np.inf, np.inf)
    tag = "" if not any(free) else "_free" + "".join("1" if f else "0" for f in free)
    tag += "_period" if period_rows and any(free) else ""
    tag += "_corr" if correction else ""
    name = f"joint_{n}_{nb}_{nc}_{mesh.degree}_{force_model(in_nlp).key}{tag}".replace("-", "_")
    return nlp.compile(J, name, expand=expand, compile_fn=compile_fn,
                       outputs={f"leg{k}": leg.outputs() for k, leg in enumerate(legs)})


@dataclass
class JointResult:
    """The joint optimum, verified leg by leg."""

    legs: list            # verified Solutions, one per burn
    ipopt_status: str
    iterations: int
    solve_s: float
    plan: CapturePlan | None = None   # the plan solved (with the optimal coasts if free)

    @property
    def total_delta_v_mps(self) -> float:
        """Sum of the burns' delta-V, m/s."""
        return sum(s.delta_v_mps for s in self.legs)


def warm_start(sol: Solution) -> tuple:
    """(problem, Guess, coast mesh fractions) of one leg, from a solved burn."""
    u_fn, burn = BurnPlan.of(sol.raw).direction, sol.flight.burn
    guess = Guess(sol.raw.t1_s, lambda t, u_fn=u_fn, b=burn: u_fn(t, b(t)), burn,
                  sol.flight.coast)
    return sol.problem, guess, sol.raw.mesh_coast


def _legs_start(lay, warm: list, mesh: Mesh, fit, S, vectors: tuple, params: dict,
                corrected: bool = False) -> list:
    """Write each leg's guess, bounds and parameters; return its (burn, coast) meshes.

    ``vectors``: (w0, lbx, ubx, lbg, ubg), filled in place; ``params`` updated in place.
    A warm start's coast mesh of another size is replaced by one uniform in time, or in a
    ``corrected`` field by one spaced in the Sundman variable of the guess's coast,
    weighted towards the perilune (as a single burn's there:
    :data:`~lunarcap.optim.collocation.FIELD_PERILUNE_POWER`).
    """
    w0, lbx, ubx, lbg, ubg = vectors
    meshes = []
    for k, (prob, guess, mc) in enumerate(warm):
        if fit is not None and prob.model.fit is not None:
            from dataclasses import replace

            prob = replace(prob, model=replace(prob.model, fit=fit))
        pre = f"leg{k}."
        mb = np.linspace(0, 1, mesh.n_burn + 1)
        if len(mc) != mesh.n_coast + 1:
            mc = sundman_fractions(guess.coast.t, guess.coast.x, mesh.n_coast,
                                   FIELD_PERILUNE_POWER) if corrected else \
                np.linspace(0, 1, mesh.n_coast + 1)
        meshes.append((mb, mc))
        initial_point(lay, pre, prob, mesh, guess, w0, mb, mc, S)
        leg_bounds(lay, pre, prob, lbx, ubx, lbg, ubg)
        params.update({pre + "dynamics": prob.model.params(), pre + "mesh_burn": mb,
                       pre + "mesh_coast": mc, pre + "target": prob.target.values(LU)})
    return meshes


def solve_joint(plan: CapturePlan, sequential: list, eph, mesh: Mesh = Mesh(8, 16, 5),
                free_coasts: tuple = (), coast_bounds_s: tuple | None = None,
                max_time_s: float | None = None, fit=None, max_period_s: float | None = None,
                warm: list | None = None, expand: bool = False,
                min_period_s: float | None = None, whole_field: bool = False) -> JointResult:
    """Solve all burns of ``plan`` as one NLP, warm-started from a one-at-a-time chain.

    Parameters
    ----------
    plan : CapturePlan
    sequential : list of Solution
        The plan's burns solved one at a time with free ignition (the warm start).
    eph : Ephemeris
    mesh : Mesh
        In a gravity field beyond what the NLP carries (whole or not), each leg has twice
        its coast intervals (:func:`lunarcap.optim.correction.field_mesh`).
    free_coasts : tuple of bool, optional
        Per burn, whether its coast is optimised (see the module docstring; the plan's
        coasts are the initial values). The coast of an ellipse as asked
        (:attr:`lunarcap.mission.targets.Target.free_epoch`) is always free, within
        :data:`lunarcap.optim.problem.END_WINDOW_FRACTION` of its period: it ends at the
        perilune where the orbit holds, and the plan keeps its target.
    coast_bounds_s : (lo, hi), optional
        Bounds of every free coast the caller asked for, s.
    max_time_s : float, optional
        Upper bound of the time from the plan's first epoch to the end of its last burn, s.
    fit : ChebyshevFit, optional
        One ephemeris fit for every leg (required in full dynamics with free coasts: it
        must cover every epoch the coasts allow); default each leg's own.
    max_period_s : float, optional
        With free coasts: the longest osculating period of each free leg's orbit at the
        perilune where its target holds, s (rows ``energy_limit``; default none).
    min_period_s : float, optional
        With ``max_period_s``: the shortest such period, s (default none).
    warm : list of (BurnProblem, Guess, coast mesh fractions), optional
        Per leg, instead of ``sequential`` (then None): the problem (its bounds, ignition
        window, dynamics) and the guess the NLP starts from (:func:`warm_start` of a solved
        burn is one).
    expand : bool, optional
        Expand the NLP to SX (see :func:`build_joint_nlp`): for a shape solved many times.
    whole_field : bool, optional
        Carry the plan's gravity field whole in the NLP, with no outer correction
        (:func:`lunarcap.optim.correction.whole`): the exact optimum, whose build grows
        with the square of the field's terms; what bounds the correction's gap.

    Notes
    -----
    In a gravity field beyond what the NLP carries, the NLP is solved again with the
    field's higher-degree acceleration at every collocation point of every leg, evaluated
    at the previous solution (:mod:`lunarcap.optim.correction`), until it moves by less
    than :data:`~lunarcap.optim.correction.TOL_KMPS2`; each leg is then verified by
    re-flight in the whole field.

    Raises
    ------
    SolveError
        If IPOPT fails, the correction does not converge or a leg fails verification.
    """
    shape = whole(plan.dynamics) if whole_field else carried(plan.dynamics)
    mesh = field_mesh(mesh, plan.dynamics)
    kinds = tuple(t.kind for t in plan.targets)
    asked = tuple(bool(f) for f in free_coasts) or (False,) * plan.n_burns
    orbit = tuple(t.free_epoch for t in plan.targets)
    free = tuple(a or o for a, o in zip(asked, orbit))
    warm = warm if warm is not None else [warm_start(s) for s in sequential]
    period_rows = any(asked) and max_period_s is not None
    nlp = build_joint_nlp(mesh, kinds, shape if shape.correction or whole_field else
                          plan.dynamics, free if any(free) else (), period_rows, expand)
    lay = nlp.compiled.layout
    S = state_scale(warm[0][0].x_ref[6])
    w0 = np.zeros(lay.nv)
    lbx, ubx, lbg, ubg = lay.bounds()
    params = {"x_start": warm[0][0].x_ref, "t_ref": plan.nominal_perilunes_s}
    if any(free):
        _free_coast_bounds(plan, lay, warm, asked, orbit, (w0, lbx, ubx, lbg, ubg),
                           coast_bounds_s, max_time_s,
                           (min_period_s, max_period_s) if period_rows else None)
    meshes = _legs_start(lay, warm, mesh, fit, S, (w0, lbx, ubx, lbg, ubg), params,
                         shape.correction)
    w, stats, solve_s, run = _solve_corrected(plan, nlp, shape, (w0, lbx, ubx, lbg, ubg),
                                              params, meshes, mesh, free, S)
    plan, t_ref = _optimal_coasts(plan, lay, w, free, asked)
    legs = _verified_legs(plan, lay, w, warm, meshes, mesh, S, eph, fit, t_ref,
                          (stats, solve_s, nlp.compiled.build_s, run))
    return JointResult(legs, stats["return_status"], run["iterations"], solve_s, plan)


def _solve_corrected(plan: CapturePlan, nlp: JointNLP, shape, vectors: tuple, params: dict,
                     meshes: list, mesh: Mesh, free: tuple, S) -> tuple:
    """IPOPT on the all-burns NLP; in a corrected field, again until the correction holds.

    Returns (solution vector, IPOPT stats of the last solve, solve time s, run): ``run``
    has ``iterations`` (IPOPT's, summed), ``corrections`` (solves) and ``change`` (the
    correction's last largest change, km/s^2). SolveError if a solve fails or the
    correction moves by more than :data:`~lunarcap.optim.correction.TOL_KMPS2` after
    :data:`~lunarcap.optim.correction.MAX_ITERATIONS` solves.
    """
    w0, lbx, ubx, lbg, ubg = vectors
    lay = nlp.compiled.layout
    accel = _zero_corrections(lay, plan.n_burns) if shape.correction else {}
    solve_s, iterations, change = 0.0, 0, 0.0
    for k in range(1, (MAX_ITERATIONS if shape.correction else 1) + 1):
        t0 = time.perf_counter()
        res = nlp.compiled.solve(x0=w0, p=lay.params(**params, **accel), lbx=lbx, ubx=ubx,
                                 lbg=lbg, ubg=ubg)
        solve_s += time.perf_counter() - t0
        stats = nlp.compiled.stats()
        iterations += int(stats["iter_count"])
        if not stats["success"]:
            after = f" (correction {k})" if shape.correction else ""
            raise SolveError(f"all-burns NLP{_of(plan)}: IPOPT {stats['return_status']}"
                             f"{after}", status=stats["return_status"])
        w0 = np.asarray(res["x"]).ravel()
        if not shape.correction:
            break
        new = _joint_corrections(lay, w0, params, meshes, mesh, free, S,
                                 force_model(plan.dynamics), shape.forces)
        change = largest_change(new, accel)
        accel = new
        if change < TOL_KMPS2:
            break
    if shape.correction and not change < TOL_KMPS2:
        raise SolveError(f"all-burns NLP{_of(plan)}: the field's correction did not converge "
                         f"in {MAX_ITERATIONS} solves (last change {change:.2e} km/s^2, "
                         f"tolerance {TOL_KMPS2:g})", status="Correction_Not_Converged")
    return w0, stats, solve_s, {"iterations": iterations, "corrections": k, "change": change}


def _zero_corrections(lay, n_legs: int) -> dict:
    """The correction parameters of a first solve: none, shaped as the NLP's."""
    return {f"leg{k}.{phase}": np.zeros(lay.par_shapes[f"leg{k}.{phase}"])
            for k in range(n_legs) for phase in ("accel_pre", "accel_burn", "accel_coast")}


def _leg_epochs(lay, w, params: dict, free: tuple) -> list:
    """The N+1 epochs the legs of solution ``w`` start from and end at, s (as the NLP has them).

    :func:`build_joint_nlp`'s: from ``t_ref``, a free leg's coast a variable, a fixed one
    the parameter's (its difference once a free coast came before it).
    """
    t_ref = np.asarray(params["t_ref"], float)
    t = [float(t_ref[0])]
    for k in range(len(t_ref) - 1):
        if free and free[k]:
            t.append(t[k] + float(lay.get(w, f"leg{k}.coast")[0]) * TU)
        elif not any(free[:k]):
            t.append(float(t_ref[k + 1]))
        else:
            t.append(t[k] + float(t_ref[k + 1] - t_ref[k]))
    return t


def _joint_corrections(lay, w, params: dict, meshes: list, mesh: Mesh, free: tuple, S,
                       forces, low) -> dict:
    """Every leg's correction at the collocation points of solution ``w`` (NLP parameters).

    Per leg and phase (pre-ignition coast, burn, coast): the whole field's acceleration
    minus the NLP's, RTN km/s^2, at each point's epoch and state
    (:func:`lunarcap.optim.correction.field_difference`), with the leg's parameters (its
    ephemeris fit: the body frame).
    """
    d = mesh.degree
    t = _leg_epochs(lay, w, params, free)
    out = {}
    for k, (mb, mc) in enumerate(meshes):
        pre = f"leg{k}."
        prm = params[pre + "dynamics"]
        ts = float(lay.get(w, pre + "ts")[0]) * TU
        t1 = float(lay.get(w, pre + "t1")[0]) * TU
        t_ign = t[k] + ts
        phases = {
            "accel_pre": (node_epochs(t[k], ts, np.linspace(0, 1, N_PRE + 1), d)[1:],
                          (lay.get(w, pre + "X0") * S[:, None])[:, 1:]),
            "accel_burn": (node_epochs(t_ign, t1, mb, d)[1:],
                           (lay.get(w, pre + "Xb") * S[:, None])[:, 1:]),
            "accel_coast": (node_epochs(t_ign + t1, t[k + 1] - t_ign - t1, mc, d)[1:],
                            lay.get(w, pre + "Xc") * S[:, None])}
        diff = field_difference(forces, low, prm, phases)
        out.update({pre + name: a for name, a in diff.items()})
    return out


def _optimal_coasts(plan: CapturePlan, lay, w, free: tuple, asked: tuple) -> tuple:
    """(plan, perilune epochs reached s) of the joint optimum ``w``.

    The plan with the coasts the NLP chose where the caller freed them (an ellipse as
    asked keeps its target: its coast ends where the orbit holds), and the N+1 epochs of
    the perilunes each leg starts from and the last one ends at.
    """
    coasts = [float(lay.get(w, f"leg{k}.coast")[0]) * TU if free[k] else None
              for k in range(plan.n_burns)]
    if any(asked):
        plan = plan.with_coasts([c if asked[k] else None for k, c in enumerate(coasts)])
    t_ref = [plan.nominal_perilunes_s[0]]
    for k in range(plan.n_burns):
        t_ref.append(t_ref[k] + (coasts[k] if coasts[k] is not None else plan.coast_s(k)))
    return plan, t_ref


def _free_coast_bounds(plan: CapturePlan, lay, warm: list, asked: tuple, orbit: tuple,
                       vectors: tuple, coast_bounds_s, max_time_s, periods_s) -> None:
    """Initial values and bounds of the free coasts, the time limit and the period rows.

    ``vectors``: (w0, lbx, ubx, lbg, ubg), written in place. A coast the caller freed
    takes ``coast_bounds_s``; an ellipse as asked starts from the perilune its warm start
    reached, within :data:`lunarcap.optim.problem.END_WINDOW_FRACTION` of its period.
    ``periods_s``: (shortest or None, longest) period of each caller-freed leg's orbit,
    bounds of its energy; or None.
    """
    w0, lbx, ubx, lbg, ubg = vectors
    lo, hi = coast_bounds_s if coast_bounds_s is not None else (0.0, np.inf)
    free = [k for k in range(plan.n_burns) if asked[k] or orbit[k]]
    for k in free:
        c = plan.coast_s(k)
        if orbit[k] and not asked[k]:   # from the perilune the warm start reached
            seq = warm[k][0]
            c = seq.t_end_s - seq.t_ref_s
            w = END_WINDOW_FRACTION * plan.targets[k].period_s()
            lo_k, hi_k = c - w, c + w
        else:
            lo_k, hi_k = lo, hi
        lay.put(w0, f"leg{k}.coast", c / TU)
        lay.put(lbx, f"leg{k}.coast", lo_k / TU)
        lay.put(ubx, f"leg{k}.coast", hi_k / TU)
    if max_time_s is not None:
        ubg[lay.rows("time_limit")] = max_time_s / TU
    if periods_s is not None:  # E = -mu / (2 a), a from Kepler's third law, VU^2
        def energy(period_s):
            return -1.0 / (2 * (period_s / (2 * np.pi * TU)) ** (2.0 / 3.0))
        rows = np.flatnonzero(lay.rows("energy_limit"))   # one per free leg, in order
        for row, k in zip(rows, free):
            if asked[k]:
                ubg[row] = energy(periods_s[1])
                if periods_s[0] is not None:
                    lbg[row] = energy(periods_s[0])


def _verified_legs(plan: CapturePlan, lay, w, warm: list, meshes: list, mesh: Mesh, S,
                   eph, fit, t_ref: list, run: tuple) -> list:
    """Each leg of the joint optimum verified by re-propagation, in order (Solutions).

    Leg k is the fixed-ignition problem from the previous leg's verified end state at the
    perilune reached ``t_ref[k]``, its coast ending at ``t_ref[k + 1]``. ``run``: (IPOPT
    stats, solve time s, build time s). SolveError if a leg fails verification, with the
    converged solution (``unverified``: the plan and every leg's RawSolution, those after
    the failed one from the NLP's own state at their perilune). ``run`` ends with the
    correction's record (:func:`_solve_corrected`): each leg's RawSolution carries its
    solves and last change.
    """
    stats, solve_s, build_s, record = run
    legs, raws, x_peri, failure = [], [], warm[0][0].x_ref, None
    for k, (prob0, guess, _) in enumerate(warm):
        pre = f"leg{k}."
        t_ign = t_ref[k] + float(lay.get(w, pre + "ts")[0]) * TU
        prob = burn_problem(plan, k, x_peri, eph, start_min=(t_ign - t_ref[k]) / 60.0,
                            fit=fit if fit is not None else prob0.model.fit,
                            t_perilune_s=t_ref[k], t_end_s=t_ref[k + 1])
        mb, mc = meshes[k]
        fixed = leg_solution(lay, pre, w, prob, mesh, mb, mc, S)
        xf = fixed["x_coast"][:, -1]
        dv = 1e-3 * rocket_delta_v_mps(fixed["x_burn"][6, 0], fixed["x_burn"][6, -1],
                                       prob.model.isp_s)   # km/s
        J_leg = dv + float(speed_from_mee(xf[0], xf[1], xf[2], xf[5], prob.model.mu))
        raw = RawSolution(mesh=mesh, mesh_burn=mb, mesh_coast=mc, objective_kmps=J_leg,
                          status=stats["return_status"], success=True,
                          iterations=int(stats["iter_count"]), solve_s=solve_s,
                          build_s=build_s, max_defect=float("nan"),
                          corrections=record["corrections"] if record["change"] else 0,
                          correction_change=record["change"], **fixed)
        raws.append(raw)
        if failure is not None:   # the rest of the converged solution, unverified
            x_peri = xf
            continue
        ver, flight = verify(raw, return_flight=True)
        legs.append(Solution(raw, ver, flight, [], solve_s, guess.t1_s))
        if not ver.passed:
            failure = (f"all-burns NLP{_of(plan)}: leg {k + 1} failed verification: "
                       + "; ".join(ver.failures()), ver.to_dict())
            x_peri = xf
            continue
        x_peri = flight.end_state
    if failure is not None:
        raise SolveError(failure[0], status="verification failed", details=failure[1],
                         unverified=(plan, raws))
    return legs
