"""The single-burn NLP: one leg transcribed by LGR collocation, solved by IPOPT.

The problem (:class:`~lunarcap.optim.problem.BurnProblem`) is transcribed by
:func:`~lunarcap.optim.transcription.add_leg` in nondimensional units; the coast mesh is
not uniform in time: its interval boundaries are equally spaced in the Sundman variable
of the initial guess (:func:`~lunarcap.optim.collocation.sundman_fractions`). The mesh
fractions, the initial state, the epochs, the dynamics parameters and the target values
are NLP parameters, so one compiled NLP per (mesh shape, target kind, start mode,
steering law, dynamics) serves every engine, ignition time and burn. The objective is
Eq. (9): the burn's delta-V plus the speed at the end of the coast.
"""

from __future__ import annotations

import time
from contextlib import contextmanager
from dataclasses import dataclass, replace

import numpy as np

from lunarcap.mission.targets import N_VALUES
from lunarcap.optim.collocation import (
    FIELD_PERILUNE_POWER,
    LU,
    N_PRE,
    N_X,
    TU,
    VU,
    Mesh,
    hk_bound,
    node_epochs,
    state_scale,
    sundman_fractions,
)
from lunarcap.optim.guess import Guess
from lunarcap.optim.interrupt import map_in_threads
from lunarcap.optim.problem import BurnProblem
from lunarcap.optim.transcription import CompiledNLP, NLPBuilder, add_leg
from lunarcap.physics import constants as C
from lunarcap.physics.dynamics import force_model
from lunarcap.physics.elements import rv_from_mee
from lunarcap.physics.propagate import propagate
from lunarcap.physics.rocket import rocket_delta_v_mps


@dataclass
class BurnNLP:
    """A compiled single-burn NLP and its leg's outputs (a function of w, p: LEG_OUTPUTS)."""

    compiled: CompiledNLP
    leg: object


#: The NLPs built or loaded in this process, by shape (the arguments of :func:`build_burn_nlp`).
_NLPS: dict = {}

#: Where NLPs and compiled node functions are kept between processes (None: nowhere, every
#: process builds its own): set by the layer above the optimiser (:func:`use_store`).
_STORE = None
#: The node compiler of that store (:class:`lunarcap.optim.derivatives.NodeCompiler`).
_COMPILER = None


def use_store(store) -> None:
    """Keep NLPs in ``store`` (or None): built once per machine, loaded by later processes.

    ``store`` has ``load(parts, decode)``, ``save(parts, data)``, ``locked(parts)`` and
    ``file(name, suffix)`` (:class:`lunarcap.repro.cache.NLPStore`, keyed there by the
    code's version as well). With a C compiler (:func:`lunarcap.optim.derivatives.compiler`)
    the node functions of the NLPs' derivatives are compiled into it too, and so are the
    propagators' right-hand sides (:data:`lunarcap.physics.propagate.ARC_COMPILER`). The
    optimiser caches nothing itself: the capture service installs the store.
    """
    global _STORE, _COMPILER
    from lunarcap.optim.derivatives import NodeCompiler, compiler
    from lunarcap.physics import propagate as prop

    cc = compiler() if store is not None else None
    _STORE, _COMPILER = store, (NodeCompiler(store, cc) if cc else None)
    prop.ARC_COMPILER = _COMPILER.arc if _COMPILER is not None else None


def stored(kind: str, shape: tuple, build) -> CompiledNLP:
    """The compiled NLP of ``shape``: loaded from the store, else ``build()`` and saved.

    ``kind`` ("burn", "joint") and ``shape`` key it, with how its node functions run. Two
    processes asking for the same shape at once: one builds and saves it under the
    store's lock, the other waits and loads it. ``build(compile_fn)`` returns the
    CompiledNLP; a store that fails to read or write leaves the NLP built in memory.
    """
    store, cc = _STORE, _COMPILER
    compile_fn = cc if cc is not None else None
    if store is None:
        return build(compile_fn)
    from lunarcap.optim import transcription

    parts = (kind, repr(shape), ca_version(), cc.tag if cc is not None else "vm",
             "nodes" if transcription.NODE_DERIVATIVES else "casadi")
    t0 = time.perf_counter()
    decode = lambda data: CompiledNLP.from_bytes(data, time.perf_counter() - t0)  # noqa: E731
    hit = store.load(parts, decode)
    if hit is None:
        with store.locked(parts):
            hit = store.load(parts, decode)   # saved by another process meanwhile
            if hit is None:
                nlp = build(compile_fn)
                store.save(parts, nlp.to_bytes())
                return nlp
    hit.build_s = time.perf_counter() - t0
    return hit


@contextmanager
def node_derivatives(on: bool):
    """Within the block, NLPs built take their derivatives node by node (``on``) or not.

    Not: CasADi's AD of the expanded NLP, what ``lunarcap bench --studies`` compares.
    """
    from lunarcap.optim import transcription

    old, transcription.NODE_DERIVATIVES = transcription.NODE_DERIVATIVES, bool(on)
    try:
        yield
    finally:
        transcription.NODE_DERIVATIVES = old


def ca_version() -> str:
    """CasADi's version (a serialized NLP is read by the version that wrote it)."""
    import casadi

    return casadi.__version__


def build_burn_nlp(mesh: Mesh, target_kind: str, free_start: bool = False,
                   steering: str = "optimal", mode: str = "full",
                   free_end: bool = False, correction: bool = False) -> BurnNLP:
    """The NLP of one shape: built (or loaded, :func:`stored`) on first use in a process."""
    shape = (mesh, target_kind, free_start, steering, mode, free_end, correction)
    if shape not in _NLPS:
        key = (mesh, target_kind, free_start, steering, force_model(mode).key, free_end,
               correction)
        compiled = stored("burn", key, lambda compile_fn: _build(*shape, compile_fn))
        _NLPS[shape] = BurnNLP(compiled, compiled.outputs.get("leg"))
    return _NLPS[shape]


def _build(mesh: Mesh, target_kind: str, free_start: bool, steering: str, mode: str,
           free_end: bool, correction: bool = False, compile_fn=None) -> CompiledNLP:
    """Build (once per mesh shape, target kind, start mode, steering law, dynamics) the NLP.

    Parameters (by name): ``x_start`` (7, physical: the state at ignition, or at the
    nominal perilune with a free start), ``t_ref`` (its epoch), ``t_end``, ``dynamics``
    (the model's ``n_param``), ``mesh_burn`` and ``mesh_coast`` (interval fractions), ``target``
    (:meth:`lunarcap.mission.targets.Target.values` in LU).

    With ``free_end`` the coast ends at ``t_end`` plus a variable ``te`` (TU): the
    epoch of the perilune where an ellipse target holds is optimised. With ``correction``
    the parameters ``accel_pre``, ``accel_burn``, ``accel_coast`` add an acceleration at
    each collocation point (:mod:`lunarcap.optim.correction`). ``compile_fn``: the node
    compiler of the derivatives (:meth:`NLPBuilder.compile`).
    """
    nb, nc = mesh.n_burn, mesh.n_coast
    nlp = NLPBuilder()
    P_x0 = nlp.param("x_start", N_X)
    P_tref = nlp.param("t_ref", 1)
    P_tend = nlp.param("t_end", 1)
    P_prm = nlp.param("dynamics", force_model(mode).n_param)
    P_mb = nlp.param("mesh_burn", nb + 1)
    P_mc = nlp.param("mesh_coast", nc + 1)
    P_tar = nlp.param("target", N_VALUES)
    import casadi as ca

    S = ca.vertcat(LU, 1, 1, 1, 1, 1, P_x0[6])
    t_end = P_tend + nlp.var("te", 1) * TU if free_end else P_tend
    leg = add_leg(nlp, "", mesh, target_kind, P_x0 / S, P_tref, t_end, P_prm, P_mb, P_mc,
                  P_tar, S, mode, free_start, steering, correction)
    name = (f"burn_{nb}_{nc}_{mesh.degree}_{target_kind}{'_free' if free_start else ''}"
            f"{'_end' if free_end else ''}_{steering}_{force_model(mode).key}"
            f"{'_corr' if correction else ''}").replace("-", "_")
    return nlp.compile(leg.dv + leg.v_end, name, compile_fn=compile_fn,
                       outputs={"leg": leg.outputs()})


def describe_shape(mesh: Mesh, target_kind: str, free_start: bool = False,
                   steering: str = "optimal", mode: str = "full", free_end: bool = False,
                   correction: bool = False) -> str:
    """An NLP shape (the arguments of :func:`build_burn_nlp`) in words."""
    return (f"{target_kind} target, {'free' if free_start else 'fixed'} ignition"
            f"{', free perilune epoch' if free_end else ''}"
            f"{'' if steering == 'optimal' else f', {steering} steering'}, "
            f"{force_model(mode)} dynamics{' + corrections' if correction else ''}, "
            f"mesh {mesh.label()}")


def is_built(mesh: Mesh, prob: BurnProblem, mode=None, correction: bool = False) -> bool:
    """True if this process holds the NLP of ``prob``'s shape on ``mesh`` (built or loaded)."""
    return shape_of(mesh, prob, mode, correction) in _NLPS


def shape_of(mesh: Mesh, prob: BurnProblem, mode=None, correction: bool = False) -> tuple:
    """The NLP shape of ``prob`` on ``mesh``: the arguments of :func:`build_burn_nlp`.

    ``mode`` and ``correction``: the forces the NLP carries, if not the problem's, and
    whether it takes outer corrections (:func:`lunarcap.optim.correction.nlp_shape`).
    """
    return (mesh, prob.target.kind, prob.free_start, prob.steering,
            prob.model.mode if mode is None else mode, prob.free_end, correction)


def clear_nlps() -> None:
    """Forget every NLP this process holds (the next use builds or loads it again)."""
    _NLPS.clear()


def n_built() -> int:
    """How many NLP shapes this process holds (built or loaded)."""
    return len(_NLPS)


def prebuild(shapes, progress=None) -> None:
    """Build several NLP shapes before the first solve, one after the other.

    ``shapes``: iterable of (mesh, target kind, free start, steering, dynamics[, free end])
    tuples, the arguments of :func:`build_burn_nlp`; each is built once per machine (or
    per process without a store, :func:`use_store`) and loaded by later processes, here or
    later. The builds run off the main thread so that Ctrl-C acts at once
    (:func:`lunarcap.optim.interrupt.map_in_threads`), but never two at once: creating
    CasADi's symbolic expressions is not thread-safe (shared reference counts; concurrent
    builds can crash the process). ``progress(str)``: a line before the builds, one per
    shape (what, built or loaded, how long) and the total.
    """
    shapes = [s for s in dict.fromkeys(_normal(*s) for s in shapes) if s not in _NLPS]
    if not shapes:
        return
    if progress:
        progress(f"building {len(shapes)} NLP{'s' * (len(shapes) > 1)} (once per "
                 f"{'machine, loaded if built before' if _STORE is not None else 'process'}):")
    t0 = time.perf_counter()

    def build(shape):
        t = time.perf_counter()
        origin = build_burn_nlp(*shape).compiled.origin
        if progress:
            progress(f"  {describe_shape(*shape)}: {origin} in {time.perf_counter() - t:.1f} s")

    map_in_threads(build, shapes, workers=1)
    if progress and len(shapes) > 1:
        progress(f"  NLPs built in {time.perf_counter() - t0:.1f} s")


def _normal(mesh: Mesh, target_kind: str, free_start: bool = False, steering: str = "optimal",
            mode: str = "full", free_end: bool = False, correction: bool = False) -> tuple:
    return (mesh, target_kind, free_start, steering, mode, free_end, correction)


@dataclass
class RawSolution:
    """Collocation solution in physical units plus IPOPT's diagnostics."""

    prob: BurnProblem
    mesh: Mesh
    t1_s: float
    t_burn: np.ndarray   # epochs of burn states (start + points), s
    x_burn: np.ndarray   # (7, nb*d+1)
    t_u: np.ndarray      # epochs of the controls (collocation points), s
    u: np.ndarray        # (3, nb*d)
    t_coast: np.ndarray
    x_coast: np.ndarray  # (7, nc*d+1) incl. the burn end
    mesh_burn: np.ndarray
    mesh_coast: np.ndarray
    objective_kmps: float
    status: str
    success: bool
    iterations: int
    solve_s: float
    build_s: float
    max_defect: float
    u_inertial: np.ndarray | None = None
    w: np.ndarray | None = None        # the NLP's solution vector (a warm start)
    lam_x: np.ndarray | None = None    # its multipliers of the variables' bounds
    lam_g: np.ndarray | None = None    # and of the constraints (a warm start's too)
    nlp_shape: tuple | None = None     # the NLP solved (shape_of), whose multipliers these are
    t_pre: np.ndarray | None = None    # epochs of the pre-ignition coast (start + points), s
    x_pre: np.ndarray | None = None    # (7, N_PRE*d+1), free start only
    corrections: int = 0               # outer corrections of a field (optim.correction)
    correction_change: float = 0.0     # their last largest change, km/s^2

    @property
    def delta_v_mps(self) -> float:
        """Delta-V of the burn, Eq. (11): g0 Isp ln(m0/m1), m/s."""
        return rocket_delta_v_mps(self.x_burn[6, 0], self.x_burn[6, -1], self.prob.model.isp_s)


def initial_point(layout, prefix: str, prob: BurnProblem, mesh: Mesh, guess: Guess,
                  w0: np.ndarray, mb: np.ndarray, mc: np.ndarray, S: np.ndarray) -> None:
    """Write the guess of one leg into ``w0`` (scaled; names with ``prefix``)."""
    d = mesh.degree
    t1 = guess.t1_s
    t_end = prob.t_end_s
    if prob.free_end and prefix + "te" in layout.var_slices:   # the guess's perilune
        t_end = float(guess.coast.t[-1])
        layout.put(w0, prefix + "te", (t_end - prob.t_end_s) / TU)
    tb = node_epochs(prob.t_ign_s, t1, mb, d)
    tc = node_epochs(prob.t_ign_s + t1, t_end - prob.t_ign_s - t1, mc, d)[1:]
    Xb = guess.burn(tb)[:N_X] / S[:, None]
    Xb[:, 0] = prob.x0 / S
    layout.put(w0, prefix + "t1", t1 / TU)
    layout.put(w0, prefix + "Xb", Xb)
    layout.put(w0, prefix + "Ub", np.array([guess.burn_u(t) for t in tb[1:]]).T)
    layout.put(w0, prefix + "Xc", guess.coast(tc)[:N_X] / S[:, None])
    if prob.free_start:
        t0s = node_epochs(prob.t_ref_s, prob.t_ign_s - prob.t_ref_s, np.linspace(0, 1, N_PRE + 1),
                          d)
        pre = propagate(prob.model, prob.t_ref_s, prob.x_ref, prob.t_ign_s, dense=True,
                        rtol=1e-10, atol=1e-10)
        X0 = pre(t0s) if pre.dense else np.tile(prob.x_ref[:, None], t0s.size)
        layout.put(w0, prefix + "ts", (prob.t_ign_s - prob.t_ref_s) / TU)
        layout.put(w0, prefix + "X0", X0 / S[:, None])
    if prob.steering == "inertial":  # anti-velocity direction at mid-burn, M-MME2000
        xm = guess.burn(prob.t_ign_s + 0.5 * t1)
        _, vm = rv_from_mee(*xm[:6], C.MU_MOON)
        layout.put(w0, prefix + "u_in", -np.array(vm) / np.linalg.norm(vm))


def leg_bounds(layout, prefix: str, prob: BurnProblem, lbx, ubx, lbg, ubg) -> None:
    """Problem-dependent bounds of one leg: burn duration, ignition window, released rows."""
    lo, hi = prob.burn_bounds_s
    layout.put(lbx, prefix + "t1", lo / TU)
    layout.put(ubx, prefix + "t1", hi / TU)
    if prob.free_start:
        lo, hi = (prob.t_perilune_s + 60.0 * np.array(prob.start_bounds_min) - prob.t_ref_s) / TU
        layout.put(lbx, prefix + "ts", lo)
        layout.put(ubx, prefix + "ts", hi)
    if prob.free_end and prefix + "te" in layout.var_slices:
        layout.put(lbx, prefix + "te", prob.end_window_s[0] / TU)
        layout.put(ubx, prefix + "te", prob.end_window_s[1] / TU)
    for kind in prob.released_targets:
        rows = layout.rows(prefix + kind)
        lbg[rows], ubg[rows] = -np.inf, np.inf
    x = prob.x_ref if prob.free_start else prob.x0
    bound = hk_bound(float(np.sqrt(prob.target.values()[1])), float(np.hypot(x[3], x[4])))
    for name in ("Xb", "Xc", "X0"):
        if prefix + name in layout.var_slices:
            _state_rows(layout, lbx, prefix + name, (3, 4), -bound)
            _state_rows(layout, ubx, prefix + name, (3, 4), bound)


def _state_rows(layout, vec: np.ndarray, name: str, rows: tuple, value: float) -> None:
    """Set rows ``rows`` of the (7 x n) state variable ``name`` to ``value`` in ``vec``."""
    arr = layout.get(vec, name).copy()
    arr[list(rows), :] = value
    layout.put(vec, name, arr)


def leg_solution(layout, prefix: str, w: np.ndarray, prob: BurnProblem, mesh: Mesh,
                 mb, mc, S) -> dict:
    """Physical burn and coast histories of one leg from a solution vector."""
    d = mesh.degree
    t1 = float(layout.get(w, prefix + "t1")[0]) * TU
    if prob.free_end and prefix + "te" in layout.var_slices:
        # the perilune where the orbit asked holds: the coast ends there, now fixed
        t_end = prob.t_end_s + float(layout.get(w, prefix + "te")[0]) * TU
        prob = replace(prob, t_end_s=t_end, end_window_s=None)
    pre = {}
    if prob.free_start:
        # the ignition found; the verified flight starts from x_ref propagated to it
        ts = float(layout.get(w, prefix + "ts")[0]) * TU
        t_ign = prob.t_ref_s + ts
        x0 = propagate(prob.model, prob.t_ref_s, prob.x_ref, t_ign).final
        pre = {"t_pre": node_epochs(prob.t_ref_s, ts, np.linspace(0, 1, N_PRE + 1), d),
               "x_pre": layout.get(w, prefix + "X0") * S[:, None]}
        prob = replace(prob, x0=x0, t_ign_s=t_ign, start_min=(t_ign - prob.t_perilune_s) / 60.0)
    Xb = layout.get(w, prefix + "Xb") * S[:, None]
    Xc = layout.get(w, prefix + "Xc") * S[:, None]
    tb = node_epochs(prob.t_ign_s, t1, mb, d)
    tc = node_epochs(prob.t_ign_s + t1, prob.t_end_s - prob.t_ign_s - t1, mc, d)
    u_in = None
    if prob.steering == "inertial":
        u_in = layout.get(w, prefix + "u_in")
        u_in = u_in / np.linalg.norm(u_in)
    return {"prob": prob, "t1_s": t1, "t_burn": tb, "x_burn": Xb, "t_u": tb[1:],
            "u": layout.get(w, prefix + "Ub"), "t_coast": tc,
            "x_coast": np.column_stack([Xb[:, -1], Xc]), "u_inertial": u_in, **pre}


def nlp_for(prob: BurnProblem, mesh: Mesh, mode=None, correction: bool = False) -> BurnNLP:
    """The compiled NLP of this burn problem's shape on ``mesh`` (built on first use).

    ``mode``: the forces the NLP carries (default the problem's); ``correction``: with
    the parameters of an outer correction (:mod:`lunarcap.optim.correction`).
    """
    return build_burn_nlp(*shape_of(mesh, prob, mode, correction))


def solve_nlp(prob: BurnProblem, mesh: Mesh, guess: Guess, mode=None, accel: dict | None = None,
              w0: np.ndarray | None = None, fractions: tuple | None = None,
              multipliers: RawSolution | None = None) -> RawSolution:
    """Solve the burn's NLP on one mesh from a guess; no verification here.

    ``mode`` and ``accel`` (the per-phase corrections, ``{"accel_burn": (3, N), ...}``):
    an NLP carrying other forces than the problem's plus a tabulated acceleration
    (:mod:`lunarcap.optim.correction`); ``w0`` and ``fractions`` (burn and coast mesh
    fractions): start from a previous solution of the same NLP. ``multipliers``: a
    solution of the same NLP whose multipliers IPOPT starts from (:func:`same_nlp`;
    ignored otherwise), the primal point still the guess's.
    """
    nlp = nlp_for(prob, mesh, mode, accel is not None)
    lay = nlp.compiled.layout
    # meshes: burn uniform in time, coast equally spaced in the Sundman variable (in a
    # field carried by corrections, weighted towards the perilune)
    power = FIELD_PERILUNE_POWER if accel is not None else 0.0
    mb, mc = fractions or (np.linspace(0.0, 1.0, mesh.n_burn + 1),
                           sundman_fractions(guess.coast.t, guess.coast.x, mesh.n_coast,
                                             power))
    S = state_scale(prob.x0[6])
    if w0 is None:
        w0 = np.zeros(lay.nv)
        initial_point(lay, "", prob, mesh, guess, w0, mb, mc, S)
    lbx, ubx, lbg, ubg = lay.bounds()
    leg_bounds(lay, "", prob, lbx, ubx, lbg, ubg)
    xs, ts = (prob.x_ref, prob.t_ref_s) if prob.free_start else (prob.x0, prob.t_ign_s)
    pvec = lay.params(x_start=xs, t_ref=ts, t_end=prob.t_end_s, dynamics=prob.model.params(),
                      mesh_burn=mb, mesh_coast=mc, target=prob.target.values(LU),
                      **(accel or {}))
    warm = None
    if multipliers is not None and same_nlp(multipliers, prob, mesh, mode, accel is not None):
        warm = (multipliers.lam_x, multipliers.lam_g)
    t0 = time.perf_counter()
    res = nlp.compiled.solve(warm, x0=w0, p=pvec, lbx=lbx, ubx=ubx, lbg=lbg, ubg=ubg)
    solve_s = time.perf_counter() - t0
    stats = nlp.compiled.stats()
    w = np.asarray(res["x"]).ravel()
    gval = np.asarray(res["g"]).ravel()
    defect = np.char.startswith(np.array(lay.g_kinds, dtype=str), "defect")
    return RawSolution(mesh=mesh, mesh_burn=mb, mesh_coast=mc,
                       objective_kmps=float(res["f"]) * VU, status=stats["return_status"],
                       success=bool(stats["success"]), iterations=int(stats["iter_count"]),
                       solve_s=solve_s, build_s=nlp.compiled.build_s,
                       max_defect=float(np.max(np.abs(gval[defect]))), w=w,
                       lam_x=np.asarray(res["lam_x"]).ravel(),
                       lam_g=np.asarray(res["lam_g"]).ravel(),
                       nlp_shape=shape_of(mesh, prob, mode, accel is not None),
                       **leg_solution(lay, "", w, prob, mesh, mb, mc, S))


def same_nlp(raw: RawSolution, prob: BurnProblem, mesh: Mesh, mode=None,
             correction: bool = False) -> bool:
    """Whether ``raw`` solved the NLP that ``prob`` on ``mesh`` solves (with its multipliers).

    The same shape (:func:`shape_of`: mesh, target, start and end modes, steering,
    forces), so its multipliers are a starting point of the same length and meaning.
    """
    return (raw.lam_x is not None and raw.lam_g is not None
            and raw.nlp_shape == shape_of(mesh, prob, mode, correction))
