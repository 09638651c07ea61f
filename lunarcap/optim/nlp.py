"""Direct transcription of one LOI's optimal-control problem (Song 2011, Sec. 2.2).

Problem (Eqs. 9-18): phase 1 burns for a free duration ``t1`` (0 < t1 <= t1_max, Eq. 10)
with a free unit thrust direction ``u = (u_r, u_t, u_n)`` (bounds +-1.01, |u| = 1,
Eqs. 12-13); phase 2 coasts to a fixed epoch; states (MEE and mass) are continuous
across the phases (Eq. 16). The objective is J = Delta-V of the burn + speed at the end
of phase 2 (Eq. 9). Terminal conditions at the end of phase 2 (Eqs. 17-18): perilune
radius, inclination and flight-path angle. Two refinements of the literal statement:

* gamma = 0 also holds at apolune; we add ``e cos(nu) = f cos L + g sin L >= 0``, which
  keeps only the perilune branch;
* for a circular target (LOI 3) gamma is undefined; we impose r_p = r_a = r_target, i.e.
  ``p = r_target`` and ``f = g = 0``, with the inclination condition.

Transcription: Legendre-Gauss-Radau collocation of degree ``d`` on ``n`` intervals per
phase, in nondimensional units (LU = 1738.2 km, TU = sqrt(LU^3/mu_Moon), mass over the
ignition mass). The coast mesh is not uniform in time: its interval boundaries are
equally spaced in the Sundman variable s = int dt / r of the initial guess (the
eccentric anomaly on a Kepler orbit), which concentrates nodes near the perilunes. The
mesh fractions are NLP parameters, so one compiled NLP (per mesh shape and target
kind) serves every engine, ignition time and LOI. IPOPT with MUMPS and exact second
derivatives from CasADi solves it.
"""

from __future__ import annotations

import os
import time
from dataclasses import dataclass, replace
from functools import lru_cache

import casadi as ca
import numpy as np

from lunarcap.physics import constants as C
from lunarcap.physics.dynamics import N_PARAM, P_THRUST, Model, rhs_function
from lunarcap.physics.elements import rv_from_mee
from lunarcap.errors import InputError
from lunarcap.physics.rocket import burn_duration_estimate_s, check_engine
from lunarcap.physics.propagate import propagate

LU = C.LU_KM
TU = float(np.sqrt(LU ** 3 / C.MU_MOON))
VU = LU / TU


@dataclass(frozen=True)
class Mesh:
    """Collocation mesh: intervals in the burn and coast phases and the LGR degree."""

    n_burn: int = 10
    n_coast: int = 24
    degree: int = 5

    def refined(self) -> "Mesh":
        """The next, finer mesh of the automatic refinement."""
        return Mesh(int(self.n_burn * 1.5), int(self.n_coast * 1.5), self.degree)


#: Meshes tried in turn until verification passes.
DEFAULT_MESHES = (Mesh(8, 16, 5), Mesh(12, 24, 5), Mesh(18, 36, 6))


@dataclass
class LOIProblem:
    """One LOI: initial state at ignition, engine, fixed end epoch, targets.

    Attributes
    ----------
    x0 : ndarray (7,)
        (p km, f, g, h, k, L rad, m kg) at ignition (with ``free_start``: at the guessed
        ignition).
    t_ign_s, t_end_s : float
        Ignition epoch and end of the coast, TDB s past J2000.
    model : Model
        Dynamics (mode, engine thrust and Isp, ephemeris fit).
    rp_target_km, inc_target_deg : float
        Terminal perilune radius and inclination.
    circular : bool
        Target a circular orbit (r_p = r_a = rp_target_km).
    dv_impulsive_mps : float or None
        Impulsive delta-V this burn is compared with.
    free_start : bool
        The ignition epoch is a decision variable, bounded by ``start_bounds_min``
        (minutes from ``t_perilune_s``); ``x_ref`` at ``t_ref_s`` is the known state the
        pre-ignition coast starts from.
    """

    x0: np.ndarray
    t_ign_s: float
    t_end_s: float
    model: Model
    rp_target_km: float = C.R_MOON + C.PERILUNE_ALTITUDE_KM
    inc_target_deg: float = 90.0
    circular: bool = False
    dv_impulsive_mps: float | None = None
    t1_max_s: float | None = None
    loi: int = 0
    start_min: float = float("nan")
    t_perilune_s: float = float("nan")
    free_start: bool = False
    x_ref: np.ndarray | None = None
    t_ref_s: float = float("nan")
    start_bounds_min: tuple = (-60.0, 30.0)
    steering: str = "optimal"

    def __post_init__(self):
        self.x0 = np.asarray(self.x0, float)
        check_engine(self.model.thrust_N, self.model.isp_s, self.x0[6])
        if not self.t_end_s > self.t_ign_s:
            raise InputError("the coast must end after ignition (t_end > t_ign)")
        if self.rp_target_km <= C.R_MOON:
            raise InputError(f"target perilune radius {self.rp_target_km} km is below the surface")
        if self.steering not in STEERING_LAWS:
            raise InputError(f"steering must be one of {STEERING_LAWS}, got {self.steering!r}")

    @property
    def released_targets(self) -> frozenset:
        """Terminal conditions a closed-form steering law cannot meet and therefore leaves free.

        Thrust opposite the velocity is in-plane and has only the ignition time and the
        duration free: it keeps the perilune timing (gamma = 0 at the end epoch; for LOI 3
        the circularity f = g = 0) and releases the inclination and the perilune radius (the
        radius, for a circle). A fixed inertial direction (two more parameters) meets every
        target except, for LOI 3, the circle's radius. What is released is reported, not
        gated.
        """
        if self.steering == "antivelocity":
            return frozenset({"inc", "p"}) if self.circular else frozenset({"inc", "rp"})
        if self.steering == "inertial" and self.circular:
            return frozenset({"p"})
        return frozenset()

    @property
    def eq19_duration_s(self) -> float | None:
        """Eq. (19) burn-duration estimate from the impulsive delta-V, s."""
        if self.dv_impulsive_mps is None:
            return None
        return burn_duration_estimate_s(self.x0[6], self.dv_impulsive_mps, self.model.thrust_N,
                                        self.model.isp_s)


# ------------------------------------------------------------------ collocation algebra
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


def lagrange_eval(nodes: np.ndarray, values: np.ndarray, x) -> np.ndarray:
    """Evaluate the interpolating polynomial through (nodes, values[:, j]) at x."""
    x = np.atleast_1d(np.asarray(x, float))
    out = np.zeros((values.shape[0], x.size))
    for j, xj in enumerate(nodes):
        lj = np.ones_like(x)
        for m, xm in enumerate(nodes):
            if m != j:
                lj *= (x - xm) / (xj - xm)
        out += values[:, [j]] * lj
    return out


# ------------------------------------------------------------------ the NLP
N_X = 7
N_PRE = 4  # intervals of the pre-ignition coast when the ignition time is free

#: IPOPT settings (MUMPS, exact Hessian). The strict tolerances are on the scaled NLP;
#: acceptance of a solution is decided by the verification gate, not by these.
IPOPT_OPTIONS = {
    "print_level": int(os.environ.get("LUNARCAP_IPOPT_PRINT", "0")), "sb": "yes",
    "tol": 1e-10, "constr_viol_tol": 1e-10, "acceptable_tol": 1e-7, "acceptable_iter": 3,
    "acceptable_constr_viol_tol": 1e-9, "acceptable_obj_change_tol": 1e-10, "max_iter": 400,
    "linear_solver": "mumps", "mu_strategy": "adaptive", "nlp_scaling_method": "gradient-based"}


@dataclass
class _NLP:
    solver: ca.Function
    mesh: Mesh
    circular: bool
    nv: int
    idx: dict
    ng: int
    g_kinds: list
    build_s: float


def collocation_defects(Xall, U, mesh_frac, t_start, dur, prm, n, d, S, mode=None):
    """LGR collocation defects of one phase (CasADi expressions).

    Parameters
    ----------
    Xall : (7, n*d+1) scaled states: the phase's start, then the d points of each interval
    U : (3, n*d) RTN thrust directions at the collocation points
    mesh_frac : (n+1,) interval boundaries as fractions of the phase
    t_start, dur : phase start epoch (s past J2000) and duration (s; may be negative)
    prm : dynamics parameter vector (thrust 0 for a coast)
    n, d : intervals and LGR degree
    S : (7,) state scales (LU for p, the reference mass for m, 1 otherwise)
    mode : dynamics mode built into the right-hand side (None: switches read from prm)
    """
    c, D = radau_matrices(d)
    f = rhs_function(mode)
    tau = ca.horzcat(*[mesh_frac[j] + (mesh_frac[j + 1] - mesh_frac[j]) * c[k]
                       for j in range(n) for k in range(d)])
    tpts = t_start + dur * tau
    Sm = ca.repmat(S, 1, n * d)
    F = f.map(n * d)(Xall[:, 1:] * Sm, U, tpts, ca.repmat(prm, 1, n * d))
    Fnd = F / Sm * dur  # d x / d tau
    defects = []
    for j in range(n):
        h = mesh_frac[j + 1] - mesh_frac[j]
        dX = ca.mtimes(Xall[:, j * d: j * d + d + 1], D)   # (7, d)
        defects.append(ca.vec(dX - h * Fnd[:, j * d: j * d + d]))
    return ca.vertcat(*defects)


def _scale_vec(mref):
    return [LU, 1.0, 1.0, 1.0, 1.0, 1.0, mref]


#: Steering laws: the optimal time-varying direction (the paper's), a direction fixed in
#: inertial space (optimised), and thrust opposite the velocity.
STEERING_LAWS = ("optimal", "inertial", "antivelocity")


def steering_law_expr(steering: str, X, u_in=None):
    """RTN thrust directions (3, N) of a steering law at states X (7, N), generic ops.

    "antivelocity": u = -(v_r, v_t, 0)/|v| with v_r ~ f sin L - g cos L, v_t ~ 1 + f cos L +
    g sin L (the common factor sqrt(mu/p) cancels); "inertial": u = Q(h, k, L) u_in, the
    fixed inertial unit vector u_in expressed in the local RTN frame (Eq. A5).
    """
    from lunarcap.physics._ops import ops
    from lunarcap.physics.dynamics import rtn_from_mee

    f, g, h, k, L = X[1, :], X[2, :], X[3, :], X[4, :], X[5, :]
    xp = ops(X)
    if steering == "antivelocity":
        vr = f * xp.sin(L) - g * xp.cos(L)
        vt = 1 + f * xp.cos(L) + g * xp.sin(L)
        n = xp.sqrt(vr * vr + vt * vt)
        rows = [-vr / n, -vt / n, 0 * n]
    elif steering == "inertial":
        ir, it, i_n = rtn_from_mee(h, k, L)
        rows = [sum(a[i] * u_in[i] for i in range(3)) for a in (ir, it, i_n)]
    else:
        raise InputError(f"no closed-form steering law {steering!r}")
    return ca.vertcat(*rows) if xp.casadi else np.vstack(rows)


@lru_cache(maxsize=None)
def build_nlp(mesh: Mesh, circular: bool, free_start: bool = False,
              steering: str = "optimal", mode: str = "full") -> _NLP:
    """Build (once per mesh shape, target kind, start mode, steering law) the LOI's IPOPT solver.

    NLP parameters (in order): x0 (7, physical), t_ign, t_end, model parameters (N_PARAM),
    burn-mesh fractions (n_burn+1), coast-mesh fractions (n_coast+1), r_p target (LU),
    tan^2(i_target/2).

    With ``free_start`` the ignition epoch is a decision variable: x0 and t_ign are then
    the reference state and epoch (the nominal perilune), and a pre-coast phase of
    ``N_PRE`` intervals links them to the ignition.
    """
    t0 = time.perf_counter()
    d = mesh.degree
    nb, nc = mesh.n_burn, mesh.n_coast

    # parameters
    P_x0 = ca.MX.sym("x0", N_X)
    P_tign = ca.MX.sym("t_ign")
    P_tend = ca.MX.sym("t_end")
    P_prm = ca.MX.sym("prm", N_PARAM)
    P_mb = ca.MX.sym("mesh_b", nb + 1)
    P_mc = ca.MX.sym("mesh_c", nc + 1)
    P_rp = ca.MX.sym("rp_tar")
    P_tan2 = ca.MX.sym("tan2")
    params = ca.vertcat(P_x0, P_tign, P_tend, P_prm, P_mb, P_mc, P_rp, P_tan2)

    # decision variables
    V_t1 = ca.MX.sym("t1")                      # burn duration, TU
    V_Xb = ca.MX.sym("Xb", N_X, nb * d + 1)     # burn states incl. the initial one
    V_Ub = ca.MX.sym("Ub", 3, nb * d)           # controls at burn collocation points
    V_Xc = ca.MX.sym("Xc", N_X, nc * d)         # coast states (start shared with the burn end)
    parts = [V_t1, ca.vec(V_Xb), ca.vec(V_Ub), ca.vec(V_Xc)]
    if free_start:
        V_ts = ca.MX.sym("ts")                      # ignition minus reference epoch, TU
        V_X0 = ca.MX.sym("X0", N_X, N_PRE * d + 1)  # pre-coast states incl. the reference one
        parts += [V_ts, ca.vec(V_X0)]
    if steering == "inertial":
        V_uin = ca.MX.sym("u_in", 3)                # fixed thrust direction, M-MME2000
        parts += [V_uin]
    w = ca.vertcat(*parts)
    nv = w.numel()
    o = 0
    idx = {"t1": slice(0, 1)}
    o = 1
    idx["Xb"] = slice(o, o + N_X * (nb * d + 1))
    o = idx["Xb"].stop
    idx["Ub"] = slice(o, o + 3 * nb * d)
    o = idx["Ub"].stop
    idx["Xc"] = slice(o, o + N_X * nc * d)
    o = idx["Xc"].stop
    if free_start:
        idx["ts"] = slice(o, o + 1)
        o += 1
        idx["X0"] = slice(o, o + N_X * (N_PRE * d + 1))
        o = idx["X0"].stop
    if steering == "inertial":
        idx["u_in"] = slice(o, o + 3)
        o += 3

    mref = P_x0[6]
    S = ca.vertcat(LU, 1, 1, 1, 1, 1, mref)
    prm_coast = ca.vertcat(P_prm[:P_THRUST], 0, P_prm[P_THRUST + 1:])
    t1_s = V_t1 * TU
    t_ign = P_tign + V_ts * TU if free_start else P_tign
    t_burn_end = t_ign + t1_s
    dur_c = P_tend - t_burn_end

    def phase_defects(Xall, U, mesh_frac, t_start, dur, prm, n):
        return collocation_defects(Xall, U, mesh_frac, t_start, dur, prm, n, d, S, mode)

    g_list, kinds = [], []
    # burn: initial state fixed through an equality (scaled)
    if free_start:
        g_list.append(V_X0[:, 0] - P_x0 / S)
        kinds += ["x0"] * N_X
        g0 = phase_defects(V_X0, ca.DM.zeros(3, N_PRE * d), ca.DM(np.linspace(0, 1, N_PRE + 1)),
                           P_tign, V_ts * TU, prm_coast, N_PRE)
        g_list.append(g0)
        kinds += ["defect_pre"] * g0.numel()
        g_list.append(V_Xb[:, 0] - V_X0[:, -1])
        kinds += ["link_pre"] * N_X
    else:
        g_list.append(V_Xb[:, 0] - P_x0 / S)
        kinds += ["x0"] * N_X
    gb = phase_defects(V_Xb, V_Ub, P_mb, t_ign, t1_s, P_prm, nb)
    g_list.append(gb)
    kinds += ["defect_burn"] * gb.numel()
    Xc_all = ca.horzcat(V_Xb[:, -1], V_Xc)
    gc = phase_defects(Xc_all, ca.DM.zeros(3, nc * d), P_mc, t_burn_end, dur_c, prm_coast, nc)
    g_list.append(gc)
    kinds += ["defect_coast"] * gc.numel()
    # |u| = 1, Eq. (13)
    if steering == "optimal":
        gu = ca.sum1(V_Ub ** 2).T - 1
        g_list.append(gu)
        kinds += ["unit_u"] * gu.numel()
    else:  # the controls follow the law at every collocation point
        law = steering_law_expr(steering, V_Xb[:, 1:], V_uin if steering == "inertial" else None)
        gl = ca.vec(V_Ub - law)
        g_list.append(gl)
        kinds += ["law"] * gl.numel()
        if steering == "inertial":
            g_list.append(ca.sumsqr(V_uin) - 1)
            kinds += ["unit_u_in"]
    # terminal conditions, Eqs. (17)-(18)
    xf = V_Xc[:, -1]
    p, fe, ge, he, ke, Le = (xf[i] for i in range(6))
    if circular:
        term = ca.vertcat(p - P_rp, fe, ge, he ** 2 + ke ** 2 - P_tan2)
        kinds += ["p", "f", "g", "inc"]
    else:
        e = ca.sqrt(fe ** 2 + ge ** 2)
        term = ca.vertcat(p / (1 + e) - P_rp, he ** 2 + ke ** 2 - P_tan2,
                          fe * ca.sin(Le) - ge * ca.cos(Le))
        kinds += ["rp", "inc", "gamma"]
    g_list.append(term)
    # perilune branch: e cos(nu) >= 0 (inequality), and a positive coast duration
    branch = fe * ca.cos(Le) + ge * ca.sin(Le)
    g_list.append(branch)
    kinds += ["branch"]
    g_list.append(dur_c / TU)
    kinds += ["coast_duration"]
    g = ca.vertcat(*g_list)

    # objective, Eq. (9): Delta-V (exact for constant thrust) + speed at the end, in VU
    vex = P_prm[6] * 1e-3 / VU  # exhaust speed, m/s -> km/s -> VU
    dv = vex * ca.log(V_Xb[6, 0] / V_Xb[6, -1])
    mu_nd = 1.0
    v2 = mu_nd / p * (1 + fe ** 2 + ge ** 2 + 2 * (fe * ca.cos(Le) + ge * ca.sin(Le)))
    J = dv + ca.sqrt(v2)

    nlp = {"x": w, "p": params, "f": J, "g": g}
    opts = {"expand": True, "print_time": False,
                    "ipopt": IPOPT_OPTIONS}
    solver = ca.nlpsol(f"loi_{nb}_{nc}_{d}_{int(circular)}{'_free' if free_start else ''}"
                       f"_{steering}_{mode}".replace("-", "_"), "ipopt", nlp, opts)
    return _NLP(solver, mesh, circular, nv, idx, g.numel(), kinds, time.perf_counter() - t0)


# ------------------------------------------------------------------ guess and mesh
def anti_velocity_u(x) -> np.ndarray:
    """Unit RTN direction opposite the velocity for MEE state(s) x (the initial-guess steering)."""
    p, f, g, h, k, L = x[:6]
    vr = f * np.sin(L) - g * np.cos(L)
    vt = 1 + f * np.cos(L) + g * np.sin(L)
    n = np.hypot(vr, vt)
    return -np.array([vr / n, vt / n, 0.0 * n])


def _sundman_fractions(traj_t, traj_x, mu, n):
    """Interval boundaries (fractions of the phase) equally spaced in s = int dt / r."""
    p, f, g, L = traj_x[0], traj_x[1], traj_x[2], traj_x[5]
    r = p / (1 + f * np.cos(L) + g * np.sin(L))
    s = np.concatenate([[0.0], np.cumsum(0.5 * (1 / r[1:] + 1 / r[:-1]) * np.diff(traj_t))])
    s /= s[-1]
    tau = (traj_t - traj_t[0]) / (traj_t[-1] - traj_t[0])
    frac = np.interp(np.linspace(0, 1, n + 1), s, tau)
    frac[0], frac[-1] = 0.0, 1.0
    return frac


@dataclass
class Guess:
    """Initial guess: burn duration (s), steering u(t) and the propagated arcs."""

    t1_s: float
    burn_u: object  # callable t -> (3,)
    burn: object    # Trajectory with dense output
    coast: object


def make_guess(prob: LOIProblem, t1_s: float | None = None, burn_u=None,
               tune: bool = True) -> Guess:
    """Initial guess: anti-velocity steering, then a coast to t_end (propagated).

    The burn duration starts from Eq. (19) (or ``t1_s``); with ``tune`` it is adjusted by
    a secant search so that the guess coast ends at a perilune (e sin(nu) = 0 at t_end),
    which removes most of the initial infeasibility of the NLP.
    """
    t1 = t1_s or prob.eq19_duration_s or 600.0
    t1 = min(t1, 0.9 * (prob.t_end_s - prob.t_ign_s))
    if tune and burn_u is None and not prob.circular:
        t1, arc = _tune_duration(prob, t1)
        if arc is not None:
            return arc
    return _guess_arcs(prob, t1, burn_u, rtol=GUESS_RTOL)


def _mean_motion_and_anomaly(x, mu=C.MU_MOON):
    """Osculating mean motion (rad/s) and mean anomaly (rad, in (-pi, pi]) of MEE state(s)."""
    p, f, g, L = x[0], x[1], x[2], x[5]
    e = np.hypot(f, g)
    a = p / (1 - e * e)
    nu = np.angle(np.exp(1j * (L - np.arctan2(g, f))))  # wrapped to (-pi, pi]
    E = 2 * np.arctan2(np.sqrt(1 - e) * np.sin(nu / 2), np.sqrt(1 + e) * np.cos(nu / 2))
    return np.sqrt(mu / a ** 3), E - e * np.sin(E)


#: Tolerance of the guess propagations (the guess need not be exact: IPOPT corrects it).
GUESS_RTOL = 1e-8


def _tune_duration(prob: LOIProblem, t1: float, revs: int = 1):
    """Burn duration for which the anti-velocity guess reaches perilune at t_end.

    The total mean anomaly swept from the burn end to t_end, M(t1) + n(t1) (t_end - t_b),
    is continuous in t1; on the osculating Kepler orbit after the burn it must equal
    2 pi revs. Its root is bracketed on a dense grid of the propagated burn, then
    corrected with numerical coasts (the Earth and Sun shift the timing by minutes).
    Returns the duration and the guess arcs propagated for it (None if not found).
    """
    span = prob.t_end_s - prob.t_ign_s
    tmax = min(2.0 * t1, 0.9 * span)
    g = _guess_arcs(prob, tmax, None, rtol=GUESS_RTOL, coast=False)
    ts = np.linspace(0.3 * t1, tmax, 600)
    xs = g.burn.sol(prob.t_ign_s + ts)
    ok = np.hypot(xs[1], xs[2]) < 1
    ts = ts[ok]
    n, M = _mean_motion_and_anomaly(xs[:, ok])
    tot = M + n * (span - ts) - 2 * np.pi * revs
    sign = np.nonzero(np.diff(np.sign(tot)) != 0)[0]
    if sign.size == 0:
        return t1, None
    i = sign[0]
    tk = ts[i] - tot[i] * (ts[i + 1] - ts[i]) / (tot[i + 1] - tot[i])
    slope = (tot[i + 1] - tot[i]) / (ts[i + 1] - ts[i])
    for _ in range(4):  # numerical correction of the Kepler root
        arc = _guess_arcs(prob, tk, None, rtol=GUESS_RTOL)
        _, Mend = _mean_motion_and_anomaly(arc.coast.x[:, -1])
        if abs(Mend) < 1e-5:  # ~0.1 s from perilune on a 12 h orbit: ample for a guess
            return float(tk), arc
        tk = tk - Mend / slope
    return float(tk), None


def _guess_arcs(prob: LOIProblem, t1: float, burn_u, rtol: float = 1e-10,
                coast: bool = True) -> Guess:
    model = prob.model
    if burn_u is None:
        # anti-velocity: u depends on the state, so propagate with a state feedback
        f = rhs_function(model.mode)
        prm = model.params()
        from scipy.integrate import solve_ivp

        def rhs(t, x):
            return np.asarray(f(x, anti_velocity_u(x), t, prm)).ravel()
        res = solve_ivp(rhs, (prob.t_ign_s, prob.t_ign_s + t1), prob.x0, method="DOP853",
                        rtol=rtol, atol=1e-10, dense_output=True)
        burn = _Traj(res.t, res.y, res.sol)
        u_of_t = lambda t: anti_velocity_u(burn.sol(t))  # noqa: E731
    else:
        tr = propagate(model, prob.t_ign_s, prob.x0, prob.t_ign_s + t1, u=burn_u, dense=True,
                       rtol=rtol, atol=1e-10)
        burn = _Traj(tr.t, tr.x, tr.sol)
        u_of_t = burn_u
    if not coast:
        return Guess(t1, u_of_t, burn, None)
    arc = propagate(model, burn.t[-1], burn.x[:, -1], prob.t_end_s, u=None, dense=True,
                    rtol=rtol, atol=1e-10)
    return Guess(t1, u_of_t, burn, _Traj(arc.t, arc.x, arc.sol))


@dataclass
class _Traj:
    t: np.ndarray
    x: np.ndarray
    sol: object


# ------------------------------------------------------------------ solve
@dataclass
class RawSolution:
    """Collocation solution in physical units plus IPOPT's diagnostics."""

    prob: LOIProblem
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

    @property
    def delta_v_mps(self) -> float:
        """Delta-V of the burn, Eq. (11): g0 Isp ln(m0/m1), m/s."""
        return self.prob.model.exhaust_speed_kmps * 1e3 * np.log(self.x_burn[6, 0] /
                                                                  self.x_burn[6, -1])


def _taus(frac, c):
    return np.concatenate([frac[j] + (frac[j + 1] - frac[j]) * c for j in range(len(frac) - 1)])


def solve_nlp(prob: LOIProblem, mesh: Mesh, guess: Guess) -> RawSolution:
    """Solve the LOI NLP on one mesh from a guess; no verification here."""
    nlp = build_nlp(mesh, prob.circular, prob.free_start, prob.steering, prob.model.mode)
    d = mesh.degree
    c, _ = radau_matrices(d)
    nb, nc = mesh.n_burn, mesh.n_coast
    # meshes: burn uniform in time, coast equally spaced in the Sundman variable
    mb = np.linspace(0.0, 1.0, nb + 1)
    mc = _sundman_fractions(guess.coast.t, guess.coast.x, C.MU_MOON, nc)
    S = np.array(_scale_vec(prob.x0[6]))
    t1 = guess.t1_s
    tb = prob.t_ign_s + t1 * np.concatenate([[0.0], _taus(mb, c)])
    tcoast_start = prob.t_ign_s + t1
    tc = tcoast_start + (prob.t_end_s - tcoast_start) * _taus(mc, c)
    Xb = guess.burn.sol(tb) / S[:, None]
    Xb[:, 0] = prob.x0 / S
    Ub = np.array([guess.burn_u(t) for t in tb[1:]]).T
    Xc = guess.coast.sol(tc) / S[:, None]
    w0 = [[t1 / TU], Xb.ravel(order="F"), Ub.ravel(order="F"), Xc.ravel(order="F")]
    if prob.free_start:
        m0 = np.linspace(0.0, 1.0, N_PRE + 1)
        pre = propagate(prob.model, prob.t_ref_s, prob.x_ref, prob.t_ign_s, dense=True,
                        rtol=1e-10, atol=1e-10)
        t0s = prob.t_ref_s + (prob.t_ign_s - prob.t_ref_s) * np.concatenate([[0.0], _taus(m0, c)])
        X0 = (pre.sol(t0s) if pre.sol is not None else np.tile(prob.x_ref[:, None], t0s.size))
        X0 = X0 / S[:, None]
        w0 += [[(prob.t_ign_s - prob.t_ref_s) / TU], X0.ravel(order="F")]
    if prob.steering == "inertial":  # anti-velocity direction at mid-burn, M-MME2000
        xm = guess.burn.sol(prob.t_ign_s + 0.5 * t1)
        _, vm = rv_from_mee(*xm[:6], C.MU_MOON)
        w0 += [-np.array(vm) / np.linalg.norm(vm)]
    w0 = np.concatenate(w0)
    # bounds
    lbw = -np.inf * np.ones(nlp.nv)
    ubw = np.inf * np.ones(nlp.nv)
    t1max = prob.t1_max_s or min(3.0 * (prob.eq19_duration_s or t1), 0.9 * (prob.t_end_s - prob.t_ign_s))
    lbw[0], ubw[0] = 1.0 / TU, t1max / TU
    for key, ncols in (("Xb", nb * d + 1), ("Xc", nc * d)):
        sl = nlp.idx[key]
        lo = np.tile([0.2, -3, -3, -3, -3, -np.inf, 0.05], ncols)
        hi = np.tile([200.0, 3, 3, 3, 3, np.inf, 1.0 + 1e-9], ncols)
        lbw[sl], ubw[sl] = lo, hi
    lbw[nlp.idx["Ub"]], ubw[nlp.idx["Ub"]] = -1.01, 1.01   # Eq. (12)
    if prob.steering == "inertial":
        lbw[nlp.idx["u_in"]], ubw[nlp.idx["u_in"]] = -1.01, 1.01
    if prob.free_start:
        lo, hi = (prob.t_perilune_s + 60.0 * np.array(prob.start_bounds_min) - prob.t_ref_s) / TU
        lbw[nlp.idx["ts"]], ubw[nlp.idx["ts"]] = lo, hi
        sl = nlp.idx["X0"]
        lbw[sl] = np.tile([0.2, -3, -3, -3, -3, -np.inf, 0.05], N_PRE * d + 1)
        ubw[sl] = np.tile([200.0, 3, 3, 3, 3, np.inf, 1.0 + 1e-9], N_PRE * d + 1)
    lbg = np.zeros(nlp.ng)
    ubg = np.zeros(nlp.ng)
    kinds = np.array(nlp.g_kinds)
    ubg[kinds == "branch"] = np.inf
    if prob.circular:  # f = g = 0 makes e cos(nu) identically 0: drop it (LICQ)
        lbg[kinds == "branch"] = -np.inf
    ubg[kinds == "coast_duration"] = np.inf
    lbg[kinds == "coast_duration"] = 1e-3
    for kind in prob.released_targets:
        lbg[kinds == kind], ubg[kinds == kind] = -np.inf, np.inf
    tan2 = np.tan(np.radians(prob.inc_target_deg) / 2) ** 2
    xp, tp = (prob.x_ref, prob.t_ref_s) if prob.free_start else (prob.x0, prob.t_ign_s)
    pvec = np.concatenate([xp, [tp, prob.t_end_s], prob.model.params(), mb, mc,
                           [prob.rp_target_km / LU, tan2]])
    t0 = time.perf_counter()
    res = nlp.solver(x0=w0, p=pvec, lbx=lbw, ubx=ubw, lbg=lbg, ubg=ubg)
    solve_s = time.perf_counter() - t0
    stats = nlp.solver.stats()
    w = np.asarray(res["x"]).ravel()
    gval = np.asarray(res["g"]).ravel()
    t1 = w[0] * TU
    if prob.free_start:
        # the ignition found; the verified flight starts from x_ref propagated to it
        t_ign = prob.t_ref_s + float(w[nlp.idx["ts"]][0]) * TU
        x0 = propagate(prob.model, prob.t_ref_s, prob.x_ref, t_ign).final
        prob = replace(prob, x0=x0, t_ign_s=t_ign,
                       start_min=(t_ign - prob.t_perilune_s) / 60.0)
    Xb = w[nlp.idx["Xb"]].reshape((N_X, nb * d + 1), order="F") * S[:, None]
    Ub = w[nlp.idx["Ub"]].reshape((3, nb * d), order="F")
    Xc = w[nlp.idx["Xc"]].reshape((N_X, nc * d), order="F") * S[:, None]
    tb = prob.t_ign_s + t1 * np.concatenate([[0.0], _taus(mb, c)])
    tcs = prob.t_ign_s + t1
    tc = tcs + (prob.t_end_s - tcs) * np.concatenate([[0.0], _taus(mc, c)])
    defect_mask = np.char.startswith(kinds.astype(str), "defect")
    u_in = None
    if prob.steering == "inertial":
        u_in = w[nlp.idx["u_in"]] / np.linalg.norm(w[nlp.idx["u_in"]])
    return RawSolution(prob, mesh, t1, tb, Xb, tb[1:], Ub, tc, np.column_stack([Xb[:, -1], Xc]),
                       mb, mc, float(res["f"]) * VU, stats["return_status"], bool(stats["success"]),
                       int(stats["iter_count"]), solve_s, nlp.build_s,
                       float(np.max(np.abs(gval[defect_mask]))), u_in)


def steering_function(raw: RawSolution):
    """u(t, x): the solution's thrust direction in RTN at epoch t and state x.

    For the optimal law, the collocated controls interpolated in time (``x`` unused); for
    the closed-form laws, the law evaluated on the state (state feedback).
    """
    steering = raw.prob.steering
    if steering == "optimal":
        u_of_t, _ = control_function(raw)
        return lambda t, x: u_of_t(t)
    u_in = raw.u_inertial

    def law(t, x):
        return steering_law_expr(steering, np.asarray(x, float)[:, None], u_in)[:, 0]
    return law


def control_function(raw: RawSolution):
    """u(t): the collocated steering interpolated per interval (Lagrange), normalised to unit."""
    d = raw.mesh.degree
    c, _ = radau_matrices(d)
    nb = raw.mesh.n_burn
    bounds = raw.prob.t_ign_s + raw.t1_s * raw.mesh_burn

    def u_of_t(t):
        j = int(np.clip(np.searchsorted(bounds, t, side="right") - 1, 0, nb - 1))
        tau = (t - bounds[j]) / (bounds[j + 1] - bounds[j])
        u = lagrange_eval(c, raw.u[:, j * d:(j + 1) * d], tau)[:, 0]
        return u / np.linalg.norm(u)
    return u_of_t, bounds


def terminal_values(x) -> dict:
    """Perilune radius (km), inclination (deg), flight-path angle (deg), speed (km/s) of x."""
    from lunarcap.physics.elements import eccentricity, flight_path_angle, inclination, perilune_radius
    p, f, g, h, k, L = x[:6]
    e = eccentricity(f, g)
    r, v = rv_from_mee(p, f, g, h, k, L, C.MU_MOON)
    return {"rp_km": float(perilune_radius(p, f, g)), "ra_km": float(p / (1 - e)) if e < 1 else np.inf,
            "inc_deg": float(np.degrees(inclination(h, k))),
            "gamma_deg": float(np.degrees(flight_path_angle(p, f, g, L))),
            "e": float(e), "p_km": float(p), "v_kmps": float(np.linalg.norm(v)),
            "r_km": float(np.linalg.norm(r))}
