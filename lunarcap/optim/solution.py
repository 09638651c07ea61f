"""The result of one verified burn optimisation: histories, summary, diagnostics."""

from __future__ import annotations

import json
from dataclasses import dataclass, field

import numpy as np

from lunarcap.optim.flight import BurnPlan, Flight
from lunarcap.optim.nlp import RawSolution
from lunarcap.optim.verify import Verification
from lunarcap.physics import constants as C
from lunarcap.physics.dynamics import rtn_from_mee
from lunarcap.physics.elements import orbit_summary, period_from_semi_major_axis, rv_from_mee
from lunarcap.physics.epochs import calendar_from_seconds
from lunarcap.physics.frames import thrust_angles_deg
from lunarcap.physics.propagate import N_X


@dataclass
class Solution:
    """A verified finite-burn solution.

    Attributes
    ----------
    raw : RawSolution
        Collocation solution and IPOPT diagnostics (accepted mesh).
    verification : Verification
        Residuals of the independent re-propagation.
    flight : Flight
        The verified re-propagation (burn and coast trajectories, delta-V).
    attempts : list of dict
        Every mesh tried: mesh, IPOPT status, iterations, verification verdict.
    wall_s : float
        Wall time of the whole solve (guess, NLP build if new, solve, verification), s.
    """

    raw: RawSolution
    verification: Verification
    flight: Flight
    attempts: list = field(default_factory=list)
    wall_s: float = 0.0
    guess_t1_s: float = 0.0

    # ------------------------------------------------------------------ summary
    @property
    def problem(self):
        """The BurnProblem solved."""
        return self.raw.prob

    @property
    def delta_v_mps(self) -> float:
        """Burn delta-V (collocation), m/s."""
        return self.raw.delta_v_mps

    @property
    def burn_end_s(self) -> float:
        """Epoch of the burn's cut-off, TDB s past J2000 (ignition + duration)."""
        return float(self.problem.t_ign_s + self.raw.t1_s)

    @property
    def end_state(self) -> np.ndarray:
        """Verified state (p, f, g, h, k, L, m) at the end of the coast."""
        return self.flight.end_state

    def summary(self) -> dict:
        """Flat summary with units in the keys (the CLI's JSON).

        ``impulsive_delta_v_two_body_mps`` is the closed-form two-body impulse of this burn
        (vis-viva,
        tangential at perilune) from which Eq. (19) estimates ``eq19_duration_min``; the
        impulsive limit in the same dynamics, and the loss against it, are computed by
        :mod:`lunarcap.capture.chain`.
        """
        prob, raw = self.problem, self.raw
        tv = orbit_summary(self.end_state, C.MU_MOON)
        return {
            "burn": prob.index, "thrust_N": prob.model.thrust_N, "isp_s": prob.model.isp_s,
            "dynamics": str(prob.model.forces), "steering": prob.steering,
            "target_kind": prob.target.kind,
            "free_start": prob.free_start, "start_min": prob.start_min,
            "ignition_epoch": calendar_from_seconds(prob.t_ign_s),
            "end_epoch": calendar_from_seconds(prob.t_end_s),
            "burn_duration_min": raw.t1_s / 60.0, "delta_v_mps": raw.delta_v_mps,
            "impulsive_delta_v_two_body_mps": prob.dv_impulsive_mps,
            "m_start_kg": prob.x0[6], "m_end_kg": float(raw.x_burn[6, -1]),
            "fuel_kg": prob.x0[6] - float(raw.x_burn[6, -1]),
            "v_end_kmps": tv["v_kmps"], "rp_end_km": tv["rp_km"], "ra_end_km": tv["ra_km"],
            "inc_end_deg": tv["inc_deg"], "period_end_h": _period_h(tv),
            "eq19_duration_min": prob.eq19_duration_s / 60.0,
            "objective_j_mps": raw.objective_kmps * 1e3,
            "ipopt_status": raw.status, "ipopt_iterations": raw.iterations,
            "mesh": raw.mesh.label(), "nlp_solve_s": raw.solve_s, "solve_wall_s": self.wall_s,
            "u_inertial": None if raw.u_inertial is None else list(raw.u_inertial),
            "verification": self.verification.to_dict(),
        }

    def to_dict(self) -> dict:
        """Summary plus the mesh attempts, JSON-ready."""
        d = self.summary()
        d["attempts"] = self.attempts
        return _plain(d)

    def to_json(self, **kw) -> str:
        """JSON text of :meth:`to_dict`."""
        return json.dumps(self.to_dict(), **kw)

    # ------------------------------------------------------------------ histories
    def history(self, n_burn: int = 121, n_coast: int = 400):
        """Time histories of the verified flight.

        Columns: t_s (TDB s past J2000), minutes from ignition, phase, MEE (p_km, f, g, h,
        k, L_rad), m_kg, Cartesian state (x_km..., vx_kmps...; M-MME2000), u_r, u_t, u_n,
        alpha_deg, beta_deg (NaN while coasting), thrust acceleration (km/s^2, M-MME2000).
        """
        import pandas as pd

        burn, coast = self.flight.burn, self.flight.coast
        prob = self.problem
        plan = BurnPlan.of(self.raw)
        bounds = plan.bounds_s
        tb = np.linspace(bounds[0], bounds[-1], n_burn)
        xb = burn(tb)[:N_X]
        ub = np.column_stack([plan.direction(t, xb[:, i]) for i, t in enumerate(tb)])
        tc = np.linspace(coast.t[0], coast.t[-1], n_coast)[1:]
        xc = coast(tc)
        t = np.concatenate([tb, tc])
        x = np.column_stack([xb, xc])
        u = np.column_stack([ub, np.full((3, tc.size), np.nan)])
        r, v = rv_from_mee(*x[:6], C.MU_MOON)
        r, v = np.array(r), np.array(v)
        alpha, beta = thrust_angles_deg(u)
        df = pd.DataFrame({
            "t_s": t, "min_from_ignition": (t - prob.t_ign_s) / 60.0,
            "phase": ["burn"] * tb.size + ["coast"] * tc.size,
            "p_km": x[0], "f": x[1], "g": x[2], "h": x[3], "k": x[4], "L_rad": x[5], "m_kg": x[6],
            "x_km": r[0], "y_km": r[1], "z_km": r[2], "vx_kmps": v[0], "vy_kmps": v[1],
            "vz_kmps": v[2], "u_r": u[0], "u_t": u[1], "u_n": u[2],
            "alpha_deg": alpha, "beta_deg": beta})
        # thrust acceleration in M-MME2000 (km/s^2): T/m (u_r i_r + u_t i_t + u_n i_n)
        ir, it, i_n = (np.array(a) for a in rtn_from_mee(x[3], x[4], x[5]))
        acc = prob.model.thrust_N * 1e-3 / x[6]
        for j, ax in enumerate("xyz"):
            df[f"a{ax}_thrust_kmps2"] = acc * (u[0] * ir[j] + u[1] * it[j] + u[2] * i_n[j])
        return df

    def dataframe(self):
        """One-row summary DataFrame (verification flattened)."""
        import pandas as pd

        d = self.summary()
        ver = d.pop("verification")
        d.update({f"verification_{k}": v for k, v in ver.items()})
        return pd.DataFrame([d])


def _period_h(tv: dict) -> float:
    """Kepler period (h) of an orbit summary, inf for an open orbit."""
    if tv["e"] >= 1:
        return float("inf")
    a = 0.5 * (tv["rp_km"] + tv["ra_km"])
    return float(period_from_semi_major_axis(a, C.MU_MOON) / 3600.0)


def _plain(obj):
    if isinstance(obj, dict):
        return {k: _plain(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_plain(v) for v in obj]
    if isinstance(obj, (np.floating, np.integer, np.bool_)):
        obj = obj.item()
    if isinstance(obj, float) and not np.isfinite(obj):
        return None
    return obj
