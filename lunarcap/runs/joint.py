"""All three burns of the capture in one NLP (beyond the paper).

The paper optimises one LOI at a time with the proxy objective Eq. (9) (burn delta-V +
perilune speed at the end of the coast) and a grid of ignition times. Here the three
burns, their free ignition times and the linked coasts form one NLP whose objective is
the total delta-V of the capture (the final circular orbit fixes the last speed). The
intermediate orbits keep the paper's conditions (perilune radius, inclination and
gamma = 0 at the nominal perilune epochs), so the comparison isolates what the
one-burn-at-a-time approach and its proxy objective lose.

Leg k: a pre-ignition coast from the nominal perilune epoch t_ref,k (where the previous
leg ends; for leg 1 the arrival perilune) to the ignition, the burn, and the coast to
t_ref,k+1. The joint solution is verified leg by leg exactly like a single LOI: each
leg's steering is flown from the previous leg's *verified* end state.
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from functools import lru_cache

import casadi as ca
import numpy as np

from lunarcap.repro.cache import cached
from lunarcap.physics.dynamics import N_PARAM, P_THRUST
from lunarcap.errors import SolveError
from lunarcap.optim.nlp import (
    IPOPT_OPTIONS,
    LU,
    N_PRE,
    N_X,
    TU,
    VU,
    Mesh,
    RawSolution,
    _taus,
    collocation_defects,
    radau_matrices,
    steering_function,
    terminal_values,
)
from lunarcap.physics.propagate import propagate
from lunarcap.runs.chain import ArrivalSpec, loi_problem, mission_for, solve_sequence
from lunarcap.optim.solution import Solution, _arc_eval
from lunarcap.optim.verify import verify

N_LEGS = 3


@dataclass
class _ChainNLP:
    solver: ca.Function
    mesh: Mesh
    nv: int
    idx: list
    kinds: list
    ng: int
    build_s: float


@lru_cache(maxsize=None)
def build_chain_nlp(mesh: Mesh, mode: str = "full") -> _ChainNLP:
    """The joint NLP of the three LOIs (legs 1-2 elliptic targets, leg 3 circular)."""
    t0 = time.perf_counter()
    d = mesh.degree
    nb, nc = mesh.n_burn, mesh.n_coast
    P_x0 = ca.MX.sym("x_arr", N_X)
    P_tref = ca.MX.sym("t_ref", N_LEGS + 1)   # nominal perilune epochs, s past J2000
    P_prm = ca.MX.sym("prm", N_PARAM)
    P_mb = ca.MX.sym("mesh_b", nb + 1, N_LEGS)
    P_mc = ca.MX.sym("mesh_c", nc + 1, N_LEGS)
    P_rp = ca.MX.sym("rp_tar")
    P_tan2 = ca.MX.sym("tan2")
    params = ca.vertcat(P_x0, P_tref, P_prm, ca.vec(P_mb), ca.vec(P_mc), P_rp, P_tan2)
    S = ca.vertcat(LU, 1, 1, 1, 1, 1, P_x0[6])
    prm_coast = ca.vertcat(P_prm[:P_THRUST], 0, P_prm[P_THRUST + 1:])
    pre_mesh = ca.DM(np.linspace(0, 1, N_PRE + 1))

    parts, idx, g, kinds = [], [], [], []
    offset = 0
    vex = P_prm[6] * 1e-3 / VU
    J = 0
    prev_end = None
    for k in range(N_LEGS):
        V = {"ts": ca.MX.sym(f"ts{k}"), "X0": ca.MX.sym(f"X0{k}", N_X, N_PRE * d + 1),
             "t1": ca.MX.sym(f"t1{k}"), "Xb": ca.MX.sym(f"Xb{k}", N_X, nb * d + 1),
             "Ub": ca.MX.sym(f"Ub{k}", 3, nb * d), "Xc": ca.MX.sym(f"Xc{k}", N_X, nc * d)}
        sl = {}
        for name, sym in V.items():
            parts.append(ca.vec(sym))
            sl[name] = slice(offset, offset + sym.numel())
            offset += sym.numel()
        idx.append(sl)
        t_ref, t_end = P_tref[k], P_tref[k + 1]
        t_ign = t_ref + V["ts"] * TU
        t1 = V["t1"] * TU
        start = P_x0 / S if k == 0 else prev_end
        g.append(V["X0"][:, 0] - start)
        kinds += [f"link{k}"] * N_X
        gd = collocation_defects(V["X0"], ca.DM.zeros(3, N_PRE * d), pre_mesh, t_ref,
                                 V["ts"] * TU, prm_coast, N_PRE, d, S, mode)
        g.append(gd)
        kinds += [f"defect_pre{k}"] * gd.numel()
        g.append(V["Xb"][:, 0] - V["X0"][:, -1])
        kinds += [f"link_pre{k}"] * N_X
        gb = collocation_defects(V["Xb"], V["Ub"], P_mb[:, k], t_ign, t1, P_prm, nb, d, S, mode)
        g.append(gb)
        kinds += [f"defect_burn{k}"] * gb.numel()
        Xc_all = ca.horzcat(V["Xb"][:, -1], V["Xc"])
        gc = collocation_defects(Xc_all, ca.DM.zeros(3, nc * d), P_mc[:, k], t_ign + t1,
                                 t_end - t_ign - t1, prm_coast, nc, d, S, mode)
        g.append(gc)
        kinds += [f"defect_coast{k}"] * gc.numel()
        gu = ca.sum1(V["Ub"] ** 2).T - 1
        g.append(gu)
        kinds += [f"unit_u{k}"] * gu.numel()
        xf = V["Xc"][:, -1]
        p, fe, ge, he, ke, Le = (xf[i] for i in range(6))
        if k == N_LEGS - 1:
            g.append(ca.vertcat(p - P_rp, fe, ge, he ** 2 + ke ** 2 - P_tan2))
            kinds += ["p", "f", "g", "inc"]
        else:
            e = ca.sqrt(fe ** 2 + ge ** 2)
            g.append(ca.vertcat(p / (1 + e) - P_rp, he ** 2 + ke ** 2 - P_tan2,
                                fe * ca.sin(Le) - ge * ca.cos(Le),
                                fe * ca.cos(Le) + ge * ca.sin(Le)))
            kinds += ["rp", "inc", "gamma", "branch"]
        g.append((t_end - t_ign - t1) / TU)
        kinds += ["coast_duration"]
        J = J + vex * ca.log(V["Xb"][6, 0] / V["Xb"][6, -1])
        prev_end = xf
    w = ca.vertcat(*parts)
    gv = ca.vertcat(*g)
    solver = ca.nlpsol(f"chain_{nb}_{nc}_{d}_{mode}".replace("-", "_"), "ipopt", {"x": w, "p": params, "f": J, "g": gv},
                       {"expand": True, "print_time": False, "ipopt": IPOPT_OPTIONS})
    return _ChainNLP(solver, mesh, w.numel(), idx, kinds, gv.numel(), time.perf_counter() - t0)


@dataclass
class ChainResult:
    """The joint optimum, verified leg by leg, beside the one-at-a-time chain it started from."""

    legs: list            # three verified Solutions (joint optimum)
    sequential: list      # three Solutions of the one-at-a-time free-ignition chain
    ipopt_status: str
    iterations: int
    solve_s: float

    @property
    def total_delta_v_mps(self) -> float:
        """Sum of the three burns' delta-V of the joint optimum, m/s."""
        return sum(s.delta_v_mps for s in self.legs)

    @property
    def sequential_total_delta_v_mps(self) -> float:
        """Sum of the one-at-a-time chain's delta-Vs, m/s."""
        return sum(s.delta_v_mps for s in self.sequential)


def solve_chain(thrust_N: float, isp_s: float, dynamics: str = "full", mesh: Mesh = Mesh(8, 16, 5),
                arrival: ArrivalSpec = ArrivalSpec(), ephemeris: str | None = None) -> ChainResult:
    """Solve the three LOIs as one NLP, warm-started from the one-at-a-time free chain.

    Raises
    ------
    SolveError
        If IPOPT fails or a leg fails verification.
    """
    seq = solve_sequence(thrust_N, isp_s, ("free", "free", "free"), dynamics=dynamics,
                         arrival=arrival, ephemeris=ephemeris)
    mission = mission_for(arrival, ephemeris)
    nlp = build_chain_nlp(mesh, dynamics)
    d = mesh.degree
    c, _ = radau_matrices(d)
    nb, nc = mesh.n_burn, mesh.n_coast
    S = np.array([LU, 1, 1, 1, 1, 1, seq[0].problem.x_ref[6]])
    tref = np.array(mission.perilune_epochs_s)
    w0 = np.zeros(nlp.nv)
    lbw = -np.inf * np.ones(nlp.nv)
    ubw = np.inf * np.ones(nlp.nv)
    mbs, mcs = [], []
    for k, sol in enumerate(seq):
        raw, prob = sol.raw, sol.problem
        arcs, coast = sol.flight
        sl = nlp.idx[k]
        u_fn = steering_function(raw)
        mb = np.linspace(0, 1, nb + 1)
        mc = raw.mesh_coast if len(raw.mesh_coast) == nc + 1 else np.linspace(0, 1, nc + 1)
        mbs.append(mb), mcs.append(mc)
        # pre-coast from the nominal perilune to the ignition
        x_ref = prob.x_ref
        t_pre = tref[k] + (prob.t_ign_s - tref[k]) * np.concatenate([[0], _taus(np.linspace(0, 1, N_PRE + 1), c)])
        pre = propagate(prob.model, tref[k], x_ref, prob.t_ign_s, dense=True, rtol=1e-10, atol=1e-12)
        X0 = pre.sol(t_pre) if pre.sol is not None else np.tile(x_ref[:, None], len(t_pre))
        tb = prob.t_ign_s + raw.t1_s * np.concatenate([[0], _taus(mb, c)])
        bnd = prob.t_ign_s + raw.t1_s * raw.mesh_burn
        Xb = np.column_stack([_arc_eval(arcs, bnd, t)[:7] for t in tb])
        Ub = np.column_stack([u_fn(t, Xb[:, i + 1]) for i, t in enumerate(tb[1:])])
        tcs = prob.t_ign_s + raw.t1_s
        tc = tcs + (prob.t_end_s - tcs) * _taus(mc, c)
        Xc = coast.sol(tc)
        w0[sl["ts"]] = (prob.t_ign_s - tref[k]) / TU
        w0[sl["X0"]] = (X0 / S[:, None]).ravel(order="F")
        w0[sl["t1"]] = raw.t1_s / TU
        w0[sl["Xb"]] = (Xb / S[:, None]).ravel(order="F")
        w0[sl["Ub"]] = Ub.ravel(order="F")
        w0[sl["Xc"]] = (Xc / S[:, None]).ravel(order="F")
        lo, hi = prob.start_bounds_min
        lbw[sl["ts"]] = (prob.t_perilune_s + 60 * lo - tref[k]) / TU
        ubw[sl["ts"]] = (prob.t_perilune_s + 60 * hi - tref[k]) / TU
        lbw[sl["t1"]], ubw[sl["t1"]] = 1.0 / TU, 3 * raw.t1_s / TU
        lbw[sl["Ub"]], ubw[sl["Ub"]] = -1.01, 1.01
        for key in ("X0", "Xb", "Xc"):
            ncol = (sl[key].stop - sl[key].start) // N_X
            lbw[sl[key]] = np.tile([0.2, -3, -3, -3, -3, -np.inf, 0.05], ncol)
            ubw[sl[key]] = np.tile([200.0, 3, 3, 3, 3, np.inf, 1.0 + 1e-9], ncol)
    kinds = np.array(nlp.kinds)
    lbg = np.zeros(nlp.ng)
    ubg = np.zeros(nlp.ng)
    ubg[kinds == "branch"] = np.inf
    lbg[kinds == "coast_duration"], ubg[kinds == "coast_duration"] = 1e-3, np.inf
    model = seq[0].problem.model
    x_arr = seq[0].problem.x_ref
    pvec = np.concatenate([x_arr, tref, model.params(), np.concatenate(mbs), np.concatenate(mcs),
                           [seq[0].problem.rp_target_km / LU, np.tan(np.radians(90.0) / 2) ** 2]])
    t0 = time.perf_counter()
    res = nlp.solver(x0=w0, p=pvec, lbx=lbw, ubx=ubw, lbg=lbg, ubg=ubg)
    solve_s = time.perf_counter() - t0
    stats = nlp.solver.stats()
    if not stats["success"]:
        raise SolveError(f"joint three-burn NLP ({thrust_N:g} N, {isp_s:g} s): IPOPT "
                         f"{stats['return_status']}", status=stats["return_status"])
    w = np.asarray(res["x"]).ravel()
    legs = []
    x_peri = x_arr
    for k, sol in enumerate(seq):
        sl = nlp.idx[k]
        prob0 = sol.problem
        t_ign = tref[k] + float(w[sl["ts"]][0]) * TU
        t1 = float(w[sl["t1"]][0]) * TU
        # the leg as a fixed-ignition problem from the previous leg's verified end state
        prob = loi_problem(mission, k + 1, thrust_N, isp_s, (t_ign - tref[k]) / 60.0, x_peri,
                           dynamics, dv_impulsive_mps=prob0.dv_impulsive_mps)
        Xb = w[sl["Xb"]].reshape((N_X, nb * d + 1), order="F") * S[:, None]
        Ub = w[sl["Ub"]].reshape((3, nb * d), order="F")
        Xc = w[sl["Xc"]].reshape((N_X, nc * d), order="F") * S[:, None]
        tb = t_ign + t1 * np.concatenate([[0], _taus(mbs[k], c)])
        tc = t_ign + t1 + (prob.t_end_s - t_ign - t1) * np.concatenate([[0], _taus(mcs[k], c)])
        dv = prob.model.exhaust_speed_kmps * np.log(Xb[6, 0] / Xb[6, -1])
        J_leg = dv + terminal_values(Xc[:, -1])["v_kmps"]  # Eq. (9) of this leg, km/s
        raw = RawSolution(prob, mesh, t1, tb, Xb, tb[1:], Ub, tc, np.column_stack([Xb[:, -1], Xc]),
                          mbs[k], mcs[k], J_leg, stats["return_status"], True,
                          int(stats["iter_count"]), solve_s, nlp.build_s, 0.0)
        ver, flight = verify(raw, return_flight=True)
        if not ver.passed:
            raise SolveError(f"joint three-burn NLP: leg {k + 1} failed verification: "
                             + "; ".join(ver.failures()), status="verification failed",
                             details=ver.to_dict())
        legs.append(Solution(raw, ver, flight, [], solve_s, sol.raw.t1_s))
        x_peri = flight[1].final
    return ChainResult(legs, seq, stats["return_status"], int(stats["iter_count"]), solve_s)




@cached
def chain_summary(thrust_N: float, isp_s: float, dynamics: str = "full") -> dict:
    """Cached plain-dict form of :func:`solve_chain` (summaries of the legs)."""
    r = solve_chain(thrust_N, isp_s, dynamics)
    return {"legs": [s.summary() for s in r.legs],
            "sequential": [s.summary() for s in r.sequential],
            "ipopt_status": r.ipopt_status, "iterations": r.iterations, "solve_s": r.solve_s,
            "total_delta_v_mps": r.total_delta_v_mps,
            "sequential_total_delta_v_mps": r.sequential_total_delta_v_mps}
