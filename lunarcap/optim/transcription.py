"""Transcription of burn legs into an NLP: named slots, and one leg written once.

A *leg* is what one burn of a capture plan contributes to an NLP: an optional
pre-ignition coast (free ignition time), the burn, the coast to the next nominal perilune,
and the burn's target at the end (:mod:`lunarcap.mission.targets`). :func:`add_leg` writes
its variables, defects and conditions into an :class:`NLPBuilder`; the single-burn NLP
(:mod:`lunarcap.optim.nlp`) adds one leg, the all-burns NLP (:mod:`lunarcap.optim.joint`)
adds one per burn and links each to the previous one's end.

Every decision variable, parameter and constraint row has a name (``"leg0.t1"``,
``"leg1.defect_burn"``, ``"x_start"``): solvers fill bounds and parameters by name
through the :class:`Layout`, never by position.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from lunarcap.errors import InputError
from lunarcap.mission.targets import CONDITIONS, conditions
from lunarcap.optim.collocation import (
    N_PRE,
    N_X,
    STATE_LB,
    STATE_UB,
    TU,
    VU,
    Mesh,
    collocation_defects,
)
from lunarcap.optim.derivatives import exact_derivatives
from lunarcap.optim.interrupt import off_main_thread
from lunarcap.optim.problem import steering_law_expr
from lunarcap.physics.dynamics import P_THRUST, P_VEX, force_model
from lunarcap.physics.elements import speed_from_mee

#: IPOPT settings (MUMPS, exact Hessian). The strict tolerances are on the scaled NLP;
#: acceptance of a solution is decided by the verification gate, not by these.
#: ``max_hessian_perturbation``: an iterate whose KKT matrix needs a regularisation above
#: 1e8 is treated as singular (IPOPT then restores feasibility or gives up) rather than
#: pushed towards the default 1e20, where MUMPS asks for ever more memory and an iteration
#: takes minutes: a hopeless start then fails in seconds and the next start is tried.
IPOPT_OPTIONS = {
    "print_level": 0, "sb": "yes",
    "tol": 1e-10, "constr_viol_tol": 1e-10, "acceptable_tol": 1e-7, "acceptable_iter": 3,
    "acceptable_constr_viol_tol": 1e-9, "acceptable_obj_change_tol": 1e-10, "max_iter": 400,
    "linear_solver": "mumps", "mu_strategy": "adaptive", "nlp_scaling_method": "gradient-based",
    "max_hessian_perturbation": 1e8}

#: IPOPT's warm start (:meth:`CompiledNLP.warm_solver`): the initial point's multipliers
#: as given, and the primal point and multipliers pushed inside their bounds by little.
WARM_START_OPTIONS = {"warm_start_init_point": "yes", "warm_start_bound_push": 1e-9,
                      "warm_start_bound_frac": 1e-9, "warm_start_slack_bound_push": 1e-9,
                      "warm_start_slack_bound_frac": 1e-9, "warm_start_mult_bound_push": 1e-9}


@dataclass
class Layout:
    """Where every named variable, parameter and constraint sits in the NLP's vectors."""

    var_slices: dict = field(default_factory=dict)
    var_shapes: dict = field(default_factory=dict)
    var_lb: list = field(default_factory=list)
    var_ub: list = field(default_factory=list)
    par_slices: dict = field(default_factory=dict)
    par_shapes: dict = field(default_factory=dict)
    g_kinds: list = field(default_factory=list)
    g_lb: list = field(default_factory=list)
    g_ub: list = field(default_factory=list)
    nv: int = 0
    np_: int = 0

    @property
    def ng(self) -> int:
        """Number of constraint rows."""
        return len(self.g_kinds)

    def bounds(self) -> tuple:
        """Default (lbx, ubx, lbg, ubg) arrays."""
        return (np.array(self.var_lb, float), np.array(self.var_ub, float),
                np.array(self.g_lb, float), np.array(self.g_ub, float))

    def rows(self, kind: str) -> np.ndarray:
        """Boolean mask of the constraint rows of one kind."""
        return np.array(self.g_kinds) == kind

    def put(self, vec: np.ndarray, name: str, value) -> None:
        """Write a variable's value (scalar, or an array of its shape, column-major)."""
        sl = self.var_slices[name]
        shape = self.var_shapes[name]
        v = np.asarray(value, float)
        v = v.reshape(shape, order="F") if v.size == sl.stop - sl.start else \
            np.broadcast_to(v, shape)
        vec[sl] = np.ravel(v, order="F")

    def get(self, vec: np.ndarray, name: str) -> np.ndarray:
        """A variable's value from a solution vector, in its shape."""
        rows, cols = self.var_shapes[name]
        v = np.asarray(vec, float)[self.var_slices[name]]
        return v.reshape((rows, cols), order="F") if cols > 1 else v

    def params(self, **values) -> np.ndarray:
        """The parameter vector from named values (every slot exactly once)."""
        missing = sorted(set(self.par_slices) - set(values))
        extra = sorted(set(values) - set(self.par_slices))
        if missing or extra:
            raise InputError(f"NLP parameters: missing {missing}, unknown {extra}")
        out = np.zeros(self.np_)
        for name, sl in self.par_slices.items():
            v = np.ravel(np.asarray(values[name], float), order="F")
            if v.size != sl.stop - sl.start:
                raise InputError(f"NLP parameter {name!r}: {sl.stop - sl.start} values "
                                 f"expected, got {v.size}")
            out[sl] = v
        return out


class NLPBuilder:
    """Collects named variables, parameters and constraints, then compiles an IPOPT solver."""

    def __init__(self):
        self.layout = Layout()
        self._w, self._p, self._g = [], [], []

    def var(self, name: str, rows: int, cols: int = 1, lb=-np.inf, ub=np.inf) -> ca.MX:
        """A decision variable (rows x cols) with default bounds (broadcast)."""
        sym = ca.MX.sym(name, rows, cols)
        lay = self.layout
        lay.var_slices[name] = slice(lay.nv, lay.nv + rows * cols)
        lay.var_shapes[name] = (rows, cols)
        lay.var_lb += list(np.ravel(np.broadcast_to(lb, (rows, cols)), order="F"))
        lay.var_ub += list(np.ravel(np.broadcast_to(ub, (rows, cols)), order="F"))
        lay.nv += rows * cols
        self._w.append(ca.vec(sym))
        return sym

    def param(self, name: str, rows: int, cols: int = 1) -> ca.MX:
        """A parameter (rows x cols), set at solve time by :meth:`Layout.params`."""
        sym = ca.MX.sym(name, rows, cols)
        lay = self.layout
        lay.par_slices[name] = slice(lay.np_, lay.np_ + rows * cols)
        lay.par_shapes[name] = (rows, cols)
        lay.np_ += rows * cols
        self._p.append(ca.vec(sym))
        return sym

    def constrain(self, expr, kind: str, lb: float = 0.0, ub: float = 0.0) -> None:
        """Constraint rows lb <= expr <= ub, all of one kind."""
        expr = ca.vec(expr)
        n = expr.numel()
        self._g.append(expr)
        self.layout.g_kinds += [kind] * n
        self.layout.g_lb += [lb] * n
        self.layout.g_ub += [ub] * n

    def compile(self, objective, name: str, expand: bool = True, compile_fn=None,
                outputs: dict | None = None) -> "CompiledNLP":
        """The IPOPT solver of everything added.

        Its derivatives are assembled node by node (:mod:`lunarcap.optim.derivatives`),
        the node function compiled by ``compile_fn`` (None: CasADi's virtual machine);
        where that does not apply, CasADi's own: ``expand`` then rewrites the graph in
        SX before differentiating it (evaluations about 2x faster, construction several
        times slower). ``outputs``: named lists of expressions of the variables and
        parameters, made functions of (w, p) (:attr:`CompiledNLP.outputs`).
        """
        t0 = time.perf_counter()
        w, p, g = ca.vertcat(*self._w), ca.vertcat(*self._p), ca.vertcat(*self._g)
        derivatives = off_main_thread(exact_derivatives, w, p, objective, g, compile_fn) \
            if NODE_DERIVATIVES else None
        opts = {"expand": expand, "print_time": False, "ipopt": IPOPT_OPTIONS}
        if derivatives is not None:
            opts.update(expand=False, hess_lag=derivatives[0], jac_g=derivatives[1])
        solver = off_main_thread(   # seconds in C++: Ctrl-C must not wait for it
            ca.nlpsol, name, "ipopt", {"x": w, "p": p, "f": objective, "g": g}, opts)
        g_fun = ca.Function(f"{name}_g", [w, p], [g])
        funs = {key: ca.Function(f"{name}_{key}", [w, p], list(exprs))
                for key, exprs in (outputs or {}).items()}
        how = "node by node" if derivatives is None or compile_fn is None else "compiled nodes"
        return CompiledNLP(solver, self.layout, g_fun, time.perf_counter() - t0, funs,
                           "CasADi's" if derivatives is None else how)


#: Whether :meth:`NLPBuilder.compile` assembles the derivatives node by node (False: CasADi's
#: own AD of the expanded NLP, as ``lunarcap bench --studies`` compares).
NODE_DERIVATIVES = True

#: Version of the serialized form of a :class:`CompiledNLP` (:meth:`CompiledNLP.to_bytes`).
SERIAL_VERSION = 1


@dataclass
class CompiledNLP:
    """A compiled solver with its layout, the constraint function and its build time.

    ``build_s``: what making it took, built or loaded (``origin``: "built" or "loaded");
    ``outputs``: named functions of (w, p) (a leg's delta-V, end speed, ...);
    ``derivatives``: how IPOPT's derivatives are computed ("compiled nodes", "node by
    node" in the virtual machine, or "CasADi's" own).
    """

    solver: ca.Function
    layout: Layout
    g: ca.Function
    build_s: float
    outputs: dict = field(default_factory=dict)
    derivatives: str = "CasADi's"
    origin: str = "built"
    _warm: ca.Function | None = field(default=None, repr=False, compare=False)
    _last: ca.Function | None = field(default=None, repr=False, compare=False)

    def solve(self, multipliers: tuple | None = None, **args) -> dict:
        """``solver(**args)`` (IPOPT), off the main thread so that Ctrl-C acts at once.

        ``multipliers``: (lam_x0, lam_g0) of a neighbouring solution of this NLP: IPOPT
        then starts from them as well as from ``x0`` (:meth:`warm_solver`).
        """
        solver = self.solver
        if multipliers is not None:
            solver = self.warm_solver()
            args = {**args, "lam_x0": multipliers[0], "lam_g0": multipliers[1]}
        self._last = solver
        return off_main_thread(solver, **args)

    def stats(self) -> dict:
        """IPOPT's statistics of the last :meth:`solve`."""
        return (self._last or self.solver).stats()

    def warm_solver(self) -> ca.Function:
        """The same NLP's solver with IPOPT warm-started from given multipliers.

        Made once from this solver's functions (no derivative is built again): IPOPT's
        ``warm_start_init_point`` with :data:`WARM_START_OPTIONS`; the caller passes
        ``lam_x0`` and ``lam_g0``.
        """
        if self._warm is None:
            s = self.solver
            opts = {"expand": False, "print_time": False,
                    "ipopt": {**IPOPT_OPTIONS, **WARM_START_OPTIONS}}
            for opt, fun in (("hess_lag", "nlp_hess_l"), ("jac_g", "nlp_jac_g"),
                             ("grad_f", "nlp_grad_f")):
                opts[opt] = s.get_function(fun)
            self._warm = off_main_thread(ca.nlpsol, f"{s.name()}_warm", "ipopt", s.oracle(),
                                         opts)
        return self._warm

    def to_bytes(self) -> bytes:
        """The NLP serialized (CasADi's serialization of each function, the layout)."""
        import pickle

        return pickle.dumps({"version": SERIAL_VERSION, "solver": self.solver.serialize(),
                             "g": self.g.serialize(), "layout": self.layout,
                             "outputs": {k: f.serialize() for k, f in self.outputs.items()},
                             "derivatives": self.derivatives}, protocol=5)

    @classmethod
    def from_bytes(cls, data: bytes, load_s: float = 0.0) -> "CompiledNLP":
        """The NLP of :meth:`to_bytes` (``origin`` "loaded", ``build_s`` ``load_s``)."""
        import pickle

        d = pickle.loads(data)
        if d.get("version") != SERIAL_VERSION:
            raise ValueError(f"serialized NLP of version {d.get('version')}, not "
                             f"{SERIAL_VERSION}")
        load = ca.Function.deserialize
        return cls(load(d["solver"]), d["layout"], load(d["g"]), load_s,
                   {k: load(v) for k, v in d["outputs"].items()}, d["derivatives"], "loaded")


@dataclass
class Leg:
    """The symbols of one leg in an NLP (names in the layout start with ``prefix``)."""

    prefix: str
    mesh: Mesh
    free_start: bool
    steering: str
    target_kind: str
    dv: ca.MX          # delta-V of the burn, VU
    xf: ca.MX          # scaled state at the end of the coast
    v_end: ca.MX       # speed at the end of the coast, VU
    t_ign: ca.MX       # ignition epoch, s
    t1: ca.MX          # burn duration, s

    def name(self, part: str) -> str:
        """Layout name of one of the leg's variables or constraint kinds."""
        return f"{self.prefix}{part}"

    def outputs(self) -> list:
        """What the leg yields, in the order of :data:`LEG_OUTPUTS` (see there)."""
        return [self.dv, self.v_end, self.xf, self.t_ign, self.t1]


#: The outputs of a leg as a function of the NLP's (w, p) (:meth:`Leg.outputs`): the burn's
#: delta-V (VU), the speed at the end of the coast (VU), the scaled state there (7), the
#: ignition epoch (s past J2000) and the burn's duration (s).
LEG_OUTPUTS = ("dv", "v_end", "xf", "t_ign", "t1")


def add_leg(nlp: NLPBuilder, prefix: str, mesh: Mesh, target_kind: str, x_start, t_ref,
            t_end, prm, mesh_b, mesh_c, target_values, S, mode: str,
            free_start: bool = False, steering: str = "optimal",
            correction: bool = False) -> Leg:
    """Write one burn leg into ``nlp`` and return its symbols.

    Parameters
    ----------
    nlp : NLPBuilder
    prefix : str
        Name prefix of the leg's variables and constraint kinds (``"leg0."``).
    mesh : Mesh
    target_kind : {"perilune", "circular"}
    x_start : (7,) scaled state at ``t_ref`` (a parameter, or the previous leg's end)
    t_ref : epoch of ``x_start``, s past J2000: the ignition (fixed start) or the nominal
        perilune the pre-ignition coast starts from (free start)
    t_end : end of the coast, s past J2000
    prm : dynamics parameters (:meth:`lunarcap.physics.dynamics.Model.params`)
    mesh_b, mesh_c : interval boundaries of the burn and coast (fractions)
    target_values : (r_target LU, tan^2(i/2))
    S : (7,) state scales
    mode : the forces built into the right-hand side (a preset word or a ForceModel)
    free_start : bool
        Optimise the ignition epoch (variable ``ts``, TU from ``t_ref``).
    steering : {"optimal", "inertial", "antivelocity"}
    correction : bool
        Add parameters ``accel_pre``, ``accel_burn``, ``accel_coast`` (3 x points of each
        phase, RTN km/s^2): an acceleration added at each collocation point
        (:mod:`lunarcap.optim.correction`).

    Notes
    -----
    Variables, in order: ``t1`` (TU), ``Xb`` (7 x n_b d+1), ``Ub`` (3 x n_b d), ``Xc``
    (7 x n_c d), then with a free start ``ts`` and ``X0`` (7 x N_PRE d+1), with the inertial
    law ``u_in`` (3). Constraint kinds: ``start``, [``defect_pre``, ``link_pre``],
    ``defect_burn``, ``defect_coast``, ``unit_u`` or ``law`` [+ ``unit_u_in``], the target's
    equalities and inequalities (:data:`lunarcap.mission.targets.CONDITIONS`), and
    ``coast_duration``.
    """
    d, nb, nc = mesh.degree, mesh.n_burn, mesh.n_coast
    n = lambda part: prefix + part  # noqa: E731
    V_t1, V_Xb, V_Ub, V_Xc, V_ts, V_X0, V_uin = _leg_variables(nlp, prefix, mesh, free_start,
                                                                steering)
    prm_coast = ca.vertcat(prm[:P_THRUST], 0, prm[P_THRUST + 1:])
    t1_s = V_t1 * TU
    t_ign = t_ref + V_ts * TU if free_start else t_ref
    t_burn_end = t_ign + t1_s
    dur_c = t_end - t_burn_end

    def defects(Xall, U, frac, t_start, dur, p, nint, phase, thrust=False):
        accel = nlp.param(n("accel_" + phase), 3, nint * d) if correction else None
        return collocation_defects(Xall, U, frac, t_start, dur, p, nint, d, S, mode, thrust,
                                   accel)

    if free_start:
        nlp.constrain(V_X0[:, 0] - x_start, n("start"))
        nlp.constrain(defects(V_X0, ca.DM.zeros(3, N_PRE * d), ca.DM(np.linspace(0, 1, N_PRE + 1)),
                              t_ref, V_ts * TU, prm_coast, N_PRE, "pre"), n("defect_pre"))
        nlp.constrain(V_Xb[:, 0] - V_X0[:, -1], n("link_pre"))
    else:
        nlp.constrain(V_Xb[:, 0] - x_start, n("start"))
    nlp.constrain(defects(V_Xb, V_Ub, mesh_b, t_ign, t1_s, prm, nb, "burn", thrust=True),
                  n("defect_burn"))
    nlp.constrain(defects(ca.horzcat(V_Xb[:, -1], V_Xc), ca.DM.zeros(3, nc * d), mesh_c,
                          t_burn_end, dur_c, prm_coast, nc, "coast"), n("defect_coast"))
    _steering_rows(nlp, prefix, steering, V_Ub, V_Xb, V_uin)
    xf = V_Xc[:, -1]
    _target_rows(nlp, prefix, target_kind, xf, target_values)
    nlp.constrain(dur_c / TU, n("coast_duration"), 1e-3, np.inf)
    # delta-V of a constant-thrust burn (Eq. 11 integrated), VU
    vex = prm[P_VEX] * 1e-3 / VU
    dv = vex * ca.log(V_Xb[6, 0] / V_Xb[6, -1])
    v_end = speed_from_mee(xf[0], xf[1], xf[2], xf[5], 1.0)
    return Leg(prefix, mesh, free_start, steering, target_kind, dv, xf, v_end, t_ign, t1_s)


def _leg_variables(nlp: NLPBuilder, prefix: str, mesh: Mesh, free_start: bool,
                   steering: str) -> tuple:
    """A leg's decision variables, declared in their layout order (see :func:`add_leg`).

    (t1, Xb, Ub, Xc, ts, X0, u_in): ``ts`` and ``X0`` None without a free start, ``u_in``
    None but for the inertial law. States within the collocation's bounds, the controls
    within +-1.01 (Eq. 12).
    """
    d, nb, nc = mesh.degree, mesh.n_burn, mesh.n_coast
    lb, ub = STATE_LB[:, None], STATE_UB[:, None]
    V_t1 = nlp.var(prefix + "t1", 1)
    V_Xb = nlp.var(prefix + "Xb", N_X, nb * d + 1, lb, ub)
    V_Ub = nlp.var(prefix + "Ub", 3, nb * d, -1.01, 1.01)
    V_Xc = nlp.var(prefix + "Xc", N_X, nc * d, lb, ub)
    V_ts = nlp.var(prefix + "ts", 1) if free_start else None
    V_X0 = nlp.var(prefix + "X0", N_X, N_PRE * d + 1, lb, ub) if free_start else None
    V_uin = nlp.var(prefix + "u_in", 3, 1, -1.01, 1.01) if steering == "inertial" else None
    return V_t1, V_Xb, V_Ub, V_Xc, V_ts, V_X0, V_uin


def _steering_rows(nlp: NLPBuilder, prefix: str, steering: str, V_Ub, V_Xb, V_uin) -> None:
    """The steering's constraints of a leg: unit controls (optimal) or the law's."""
    if steering == "optimal":
        nlp.constrain(ca.sum1(V_Ub ** 2).T - 1, prefix + "unit_u")           # Eq. (13)
        return
    # the controls follow the law at every collocation point
    nlp.constrain(V_Ub - steering_law_expr(steering, V_Xb[:, 1:], V_uin), prefix + "law")
    if steering == "inertial":
        nlp.constrain(ca.sumsqr(V_uin) - 1, prefix + "unit_u_in")


def _target_rows(nlp: NLPBuilder, prefix: str, target_kind: str, xf, target_values) -> None:
    """The target at the end of the coast (Eqs. 17-18), written once in mission.targets."""
    eqs, ineqs = conditions(target_kind, [xf[i] for i in range(6)], target_values)
    _, eq_names, ineq_names = CONDITIONS[target_kind]
    for expr, name in zip(eqs, eq_names):
        nlp.constrain(expr, prefix + name)
    for expr, name in zip(ineqs, ineq_names):
        nlp.constrain(expr, prefix + name, 0.0, np.inf)


def dynamics_params(nlp: NLPBuilder, name: str, mode="full") -> ca.MX:
    """The dynamics parameter vector of a leg as an NLP parameter (the model's ``n_param``)."""
    return nlp.param(name, force_model(mode).n_param)
