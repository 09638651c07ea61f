"""Sweeps of the paper's capture plans, beside the paper's printed values (pandas).

Each function solves (or fetches from the cache) what it needs through the paper's capture
plans (:func:`lunarcap.mission.plan.paper_plan`, :mod:`lunarcap.capture.chain`) and returns a
DataFrame whose column names carry units. No plotting, no file I/O.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from lunarcap.capture.chain import burn_loss, impulsive_limit, paper_case
from lunarcap.mission.plan import paper_plan
from lunarcap.mission.scenario import paper_scenario
from lunarcap.paper.printed import (
    PAPER_BEST_STARTS_MIN,
    PAPER_IMPULSIVE_DV_MPS,
    PAPER_STARTS_MIN,
    paper_best,
    paper_table,
)


def _paper_row(thrust_N, loi, start):
    try:
        t = paper_table(thrust_N, loi)
    except Exception:  # not one of the paper's engines
        return None
    hit = t[np.isclose(t.start_min.astype(float), float(start))]
    return None if hit.empty else hit.iloc[0]


def default_previous(thrust_N: float, loi: int, isp_s: float) -> tuple:
    """Ignition offsets of the burns before ``loi`` in the paper's plan for this engine.

    The paper's best (Table B1) for its engines; for any other engine the free-ignition
    optima of the earlier burns (``"free"``), as :func:`lunarcap.mission.plan.paper_plan`.
    """
    return tuple(b.start_min for b in paper_plan(thrust_N, isp_s).burns[:loi - 1])


def _paper_loss_percent(dv_mps: float, loi: int) -> float:
    """Delta-V above the paper's impulsive value of that LOI, in % of it (as Tables 1-5)."""
    imp = PAPER_IMPULSIVE_DV_MPS[loi - 1]
    return 100.0 * (dv_mps - imp) / imp


def paper_impulsive_case(thrust_N, isp_s, loi, previous_starts=(), dynamics="full") -> dict:
    """The impulsive limit (same dynamics) of burn ``loi`` of the paper's plan."""
    plan = paper_plan(thrust_N, isp_s, dynamics=dynamics)
    for j, s in enumerate(previous_starts):
        plan = plan.with_start(j, s)
    return impulsive_limit(plan.key(loi))


def sweep_table(thrust_N: float, isp_s: float, loi: int, starts, previous_starts=None,
                dynamics: str = "full", verbose: bool = False, **kw) -> pd.DataFrame:
    """One LOI for several ignition offsets, shaped like the paper's Tables 1-5.

    Solves (or fetches) burn ``loi`` of the paper's plan at each offset of ``starts``
    (min, or "free"), the earlier burns at ``previous_starts`` (default
    :func:`default_previous`), and shapes the solutions with :func:`sweep_frame`.
    """
    if previous_starts is None:
        previous_starts = default_previous(thrust_N, loi, isp_s)
    solutions = [paper_case(thrust_N, isp_s, loi, s, tuple(previous_starts), dynamics,
                            verbose=verbose, **kw) for s in starts]
    return sweep_frame(solutions, thrust_N, isp_s, loi, previous_starts, dynamics)


def sweep_frame(solutions, thrust_N: float, isp_s: float, loi: int, previous_starts=(),
                dynamics: str = "full") -> pd.DataFrame:
    """Solutions of one LOI at several ignitions beside the paper's rows (Tables 1-5).

    ``solutions``: one :class:`~lunarcap.optim.solution.Solution` per ignition offset, of
    burn ``loi`` (1-3) of the paper's plan with the ``thrust_N`` (N) / ``isp_s`` (s)
    engine, the earlier burns igniting at ``previous_starts`` (min, or "free") in
    ``dynamics`` (as :func:`sweep_table` or ``lunarcap.solve_burn(...).solution`` give
    them). The one shaping of a sweep, whoever solved it.

    Columns: start_min; burn duration (paper, ours, difference, min); delta-V (paper, ours,
    difference m/s and %); loss relative to the paper's impulsive delta-V (paper's
    printed %, ours %); best flags; the verification verdict and residuals.
    """
    rows = []
    for sol in solutions:
        sm = sol.summary()
        free = bool(sm["free_start"])
        p = _paper_row(thrust_N, loi, sm["start_min"]) if not free else None
        ver = sm["verification"]
        rows.append({
            "start_min": sm["start_min"], "free_start": free,
            "paper_burn_duration_min": np.nan if p is None else p.burn_duration_min,
            "burn_duration_min": sm["burn_duration_min"],
            "paper_delta_v_mps": np.nan if p is None else p.delta_v_mps,
            "delta_v_mps": sm["delta_v_mps"],
            "paper_delta_v_loss_percent": np.nan if p is None else p.diff_percent,
            "loss_vs_paper_impulse_percent": _paper_loss_percent(sm["delta_v_mps"], loi),
            "eq19_duration_min": sm["eq19_duration_min"],
            "m_start_kg": sm["m_start_kg"], "m_end_kg": sm["m_end_kg"],
            "verified": ver["passed"], "rp_error_m": ver["rp_error_m"],
            "inc_error_deg": ver["inc_error_deg"], "gamma_error_deg": ver["gamma_error_deg"],
            "ipopt_iterations": sm["ipopt_iterations"], "solve_wall_s": sm["solve_wall_s"],
        })
    df = pd.DataFrame(rows)
    df["burn_duration_diff_min"] = df.burn_duration_min - df.paper_burn_duration_min
    df["delta_v_diff_mps"] = df.delta_v_mps - df.paper_delta_v_mps
    df["delta_v_diff_percent"] = 100 * df.delta_v_diff_mps / df.paper_delta_v_mps
    fixed = df[~df.free_start]
    df["best"] = False
    if not fixed.empty:
        df.loc[fixed.delta_v_mps.idxmin(), "best"] = True
    df["paper_best"] = False
    try:
        pb = paper_best(thrust_N, loi)["start_min"]
        df.loc[np.isclose(df.start_min, pb) & ~df.free_start, "paper_best"] = True
    except Exception:
        pass
    df.attrs.update({"thrust_N": thrust_N, "isp_s": isp_s, "loi": loi, "dynamics": dynamics,
                     "previous_starts_min": tuple(previous_starts),
                     "impulsive_delta_v_mps": PAPER_IMPULSIVE_DV_MPS[loi - 1]})
    return df


def sequence_table(thrust_N: float, isp_s: float, starts=None, dynamics: str = "full",
                   with_impulsive_model: bool = True, verbose: bool = False, **kw) -> pd.DataFrame:
    """The best chain of one engine (Table B1 rows) with our model-to-model impulsive loss.

    One row per LOI: start, duration, delta-V (paper, ours), loss vs the paper's impulsive
    values (m/s, %), and, with ``with_impulsive_model``, the impulsive delta-V in the same
    dynamics from the same pre-burn orbit and the loss against it, by delta-V
    (``model_loss_*``) and by the objective of Eq. (9) (``objective_loss_*``, see
    :func:`lunarcap.capture.chain.burn_loss`).
    """
    starts = tuple(starts or PAPER_BEST_STARTS_MIN[float(thrust_N)])
    rows = []
    for i, s in enumerate(starts):
        loi = i + 1
        sol = paper_case(thrust_N, isp_s, loi, s, starts[:i], dynamics, verbose=verbose, **kw)
        sm = sol.summary()
        try:
            pb = paper_best(thrust_N, loi)
        except Exception:
            pb = None
        row = {"loi": loi, "start_min": sm["start_min"],
               "paper_start_min": np.nan if pb is None else pb["start_min"],
               "burn_duration_min": sm["burn_duration_min"],
               "paper_burn_duration_min": np.nan if pb is None else pb["burn_duration_min"],
               "delta_v_mps": sm["delta_v_mps"],
               "paper_delta_v_mps": np.nan if pb is None else pb["delta_v_mps"],
               "paper_impulsive_delta_v_mps": PAPER_IMPULSIVE_DV_MPS[i],
               "loss_vs_paper_impulse_mps": sm["delta_v_mps"] - PAPER_IMPULSIVE_DV_MPS[i],
               "loss_vs_paper_impulse_percent": _paper_loss_percent(sm["delta_v_mps"], loi),
               "paper_delta_v_loss_percent": np.nan if pb is None else pb["diff_percent"],
               "m_start_kg": sm["m_start_kg"], "m_end_kg": sm["m_end_kg"],
               "fuel_kg": sm["fuel_kg"], "v_end_kmps": sm["v_end_kmps"],
               "verified": sm["verification"]["passed"]}
        if with_impulsive_model:
            imp = paper_impulsive_case(thrust_N, isp_s, loi, starts[:i], dynamics)
            loss = burn_loss(sm, imp)
            row["impulsive_limit_mps"] = imp["delta_v_mps"]
            row["delta_v_loss_mps"] = loss["delta_v_loss_mps"]
            row["delta_v_loss_percent"] = loss["delta_v_loss_percent"]
            row["objective_loss_mps"] = loss["objective_loss_mps"]
            row["objective_loss_percent"] = loss["objective_loss_percent"]
        rows.append(row)
    df = pd.DataFrame(rows)
    df.attrs.update({"thrust_N": thrust_N, "isp_s": isp_s, "starts_min": starts,
                     "dynamics": dynamics})
    return df


def sequence_totals(df: pd.DataFrame, mass0_kg: float = paper_scenario().mass_kg) -> dict:
    """Totals of a :func:`sequence_table`: delta-V, loss, fuel, burn time, final mass.

    The loss in m/s and in % of the impulsive total, and the paper's way of quoting it (the
    mean of the per-burn percentages).
    """
    imp = df.paper_impulsive_delta_v_mps.sum()
    out = {"total_delta_v_mps": df.delta_v_mps.sum(), "total_paper_impulsive_delta_v_mps": imp,
           "total_loss_vs_paper_impulse_mps": df.loss_vs_paper_impulse_mps.sum(),
           "total_loss_vs_paper_impulse_percent": 100 * df.loss_vs_paper_impulse_mps.sum() / imp,
           "mean_of_burn_loss_percent": df.loss_vs_paper_impulse_percent.mean(),
           "total_fuel_kg": mass0_kg - df.m_end_kg.iloc[-1],
           "total_burn_duration_min": df.burn_duration_min.sum(),
           "final_mass_kg": df.m_end_kg.iloc[-1]}
    if "delta_v_loss_mps" in df:
        out["total_delta_v_loss_mps"] = df.delta_v_loss_mps.sum()
        out["total_impulsive_limit_mps"] = df.impulsive_limit_mps.sum()
        out["total_delta_v_loss_percent"] = 100 * df.delta_v_loss_mps.sum() / \
            df.impulsive_limit_mps.sum()
        out["total_objective_loss_mps"] = df.objective_loss_mps.sum()
        out["total_objective_loss_percent"] = 100 * df.objective_loss_mps.sum() / \
            df.impulsive_limit_mps.sum()
    return out


def verification_table(solutions) -> pd.DataFrame:
    """Verification residuals of a list of Solutions, one row each."""
    rows = []
    for sol in solutions:
        s = sol.summary()
        v = s["verification"]
        rows.append({"thrust_N": s["thrust_N"], "isp_s": s["isp_s"], "loi": s["burn"],
                     "start_min": s["start_min"], "dynamics": s["dynamics"], "mesh": s["mesh"],
                     "ipopt_status": s["ipopt_status"], "iterations": s["ipopt_iterations"],
                     "delta_v_mps": s["delta_v_mps"],
                     "verified_delta_v_diff_mps": v["delta_v_diff_mps"],
                     "objective_diff_mps": v["objective_diff_mps"],
                     "rp_error_m": v["rp_error_m"], "ra_error_m": v["ra_error_m"],
                     "inc_error_deg": v["inc_error_deg"], "gamma_error_deg": v["gamma_error_deg"],
                     "final_position_diff_m": v["final_position_diff_m"],
                     "end_speed_diff_mps": v["end_speed_diff_mps"], "passed": v["passed"],
                     "solve_wall_s": s["solve_wall_s"]})
    return pd.DataFrame(rows)


def free_vs_grid_table(thrust_N: float, isp_s: float, dynamics: str = "full",
                       verbose: bool = False) -> pd.DataFrame:
    """Free-ignition optimum beside the best point of the paper's grid, per LOI.

    Both chains start each LOI from the previous LOI's best (grid chain: the paper's best
    offsets; free chain: the free optima). What the grid "left on the table" is measured
    in the paper's performance index J = delta-V + end speed (Eq. 9), which the free
    optimum cannot exceed, and in delta-V. ``free_loss_*``: the free optimum's loss against
    the impulsive limit from the same orbit in the same dynamics, by J
    (:func:`lunarcap.capture.chain.burn_loss`), m/s and % of the impulsive delta-V.
    """
    grid_starts = PAPER_BEST_STARTS_MIN.get(float(thrust_N))
    rows = []
    for loi in (1, 2, 3):
        prev_free = ("free",) * (loi - 1)
        free = paper_case(thrust_N, isp_s, loi, "free", prev_free, dynamics, verbose=verbose)
        fs = free.summary()
        loss = burn_loss(fs, paper_impulsive_case(thrust_N, isp_s, loi, prev_free, dynamics))
        row = {"loi": loi, "free_start_min": fs["start_min"],
               "free_burn_duration_min": fs["burn_duration_min"],
               "free_delta_v_mps": fs["delta_v_mps"], "free_objective_mps": fs["objective_j_mps"],
               "free_impulsive_limit_mps": loss["impulsive_limit_mps"],
               "free_objective_loss_mps": loss["objective_loss_mps"],
               "free_objective_loss_percent": loss["objective_loss_percent"],
               "eq19_half_duration_min":
               0.5 * fs["eq19_duration_min"], "free_verified": fs["verification"]["passed"]}
        if grid_starts is not None:
            # the grid point on the same pre-burn orbit as the free optimum
            starts = PAPER_STARTS_MIN[(float(thrust_N), loi)]
            grid = [paper_case(thrust_N, isp_s, loi, s, prev_free, dynamics, verbose=verbose)
                    for s in starts]
            best = min(grid, key=lambda s: s.raw.objective_kmps)
            gs = best.summary()
            row.update({"grid_start_min": gs["start_min"], "grid_delta_v_mps": gs["delta_v_mps"],
                        "grid_objective_mps": gs["objective_j_mps"],
                        "objective_gain_mps": gs["objective_j_mps"] - fs["objective_j_mps"],
                        "delta_v_gain_mps": gs["delta_v_mps"] - fs["delta_v_mps"]})
        rows.append(row)
    df = pd.DataFrame(rows)
    df.attrs.update({"thrust_N": thrust_N, "isp_s": isp_s, "dynamics": dynamics})
    return df


#: The steering laws :func:`steering_table` compares, the paper's optimal one first.
STEERING_LAWS = ("optimal", "inertial", "antivelocity")


def steering_table(thrust_N: float, isp_s: float, dynamics: str = "full",
                   verbose: bool = False) -> pd.DataFrame:
    """Delta-V penalty of simple steering laws against the optimal steering, per LOI.

    Laws (each with its ignition time optimised): "optimal" (the paper's), "inertial"
    (one fixed inertial direction, optimised), "antivelocity" (thrust opposite the
    velocity). Each LOI starts from the free-ignition optimal chain's previous orbit.
    Solves (or fetches) each burn of the paper's plan so and shapes the solutions with
    :func:`steering_frame`.
    """
    solutions = [paper_case(thrust_N, isp_s, loi, "free", ("free",) * (loi - 1), dynamics,
                            verbose=verbose, steering=law)
                 for loi in (1, 2, 3) for law in STEERING_LAWS]
    return steering_frame(solutions, thrust_N, isp_s, dynamics)


def steering_frame(solutions, thrust_N: float, isp_s: float,
                   dynamics: str = "full") -> pd.DataFrame:
    """Burns flown with several steering laws, each beside the optimal steering's.

    ``solutions``: :class:`~lunarcap.optim.solution.Solution` of burns of one engine's
    plan (``thrust_N`` N / ``isp_s`` s, in ``dynamics``), each LOI's optimal steering
    before its other laws (as :func:`steering_table` or ``lunarcap.solve_burn(...,
    steering=law).solution`` give them). The one shaping of a steering comparison. The
    antivelocity law cannot meet every target; the released targets and how far it
    misses them are reported (perilune radius error in km, inclination error in deg).
    """
    rows, ref = [], {}
    for sol in solutions:
        s = sol.summary()
        v = s["verification"]
        loi, law = int(s["burn"]), s["steering"]
        if law == "optimal":
            ref[loi] = s
        r = ref[loi]   # KeyError: no optimal steering of this LOI before it
        rows.append({"loi": loi, "steering": law, "start_min": s["start_min"],
                     "burn_duration_min": s["burn_duration_min"],
                     "delta_v_mps": s["delta_v_mps"], "objective_j_mps": s["objective_j_mps"],
                     "delta_v_penalty_mps": s["delta_v_mps"] - r["delta_v_mps"],
                     "objective_penalty_mps": s["objective_j_mps"] - r["objective_j_mps"],
                     "released_targets": ", ".join(v["released"]) or "none",
                     "rp_miss_km": v["rp_error_m"] / 1e3 if "rp" in v["released"] or
                     "p" in v["released"] else 0.0,
                     "inc_miss_deg": v["inc_error_deg"] if "inc" in v["released"] else 0.0,
                     "verified": v["passed"]})
    df = pd.DataFrame(rows)
    df.attrs.update({"thrust_N": thrust_N, "isp_s": isp_s, "dynamics": dynamics})
    return df
