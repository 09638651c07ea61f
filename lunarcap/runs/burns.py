"""How many capture burns: a plan's capture in N burns, the intermediate orbits optimised.

For a count N, the capture goes from the plan's arrival to its final orbit (its last
burn's target) through N-1 intermediate ellipses with the plan's perilune radius and
inclination. Their periods are chosen to minimise the total delta-V of the finite burns:

1. a start: the periods that share the two-body impulsive total equally among the burns
   (:func:`lunarcap.mission.impulsive.equal_split_periods_s`; the first ellipse no longer
   than the longest period allowed);
2. that plan solved burn by burn, every ignition free (:func:`lunarcap.runs.chain.solve_plan`,
   cached), the warm start of
3. the all-burns NLP with the N-1 coasts free (:func:`lunarcap.optim.joint.solve_joint`):
   objective the total delta-V; each period between the circle's (+1 min) and
   ``max_period_s``, each no longer than the one before, and the end of the last burn at
   most ``max_time_s`` after the arrival perilune. Its optimum is verified leg by leg.

Each burn's loss is measured against its impulsive limit in the same dynamics from the
same (verified) pre-burn state at its nominal perilune
(:func:`lunarcap.runs.chain.impulsive_limit` of the plan resumed from that state,
:meth:`lunarcap.mission.plan.CapturePlan.resumed`).

What the impulsive limit predicts: in two-body dynamics, tangential perilune impulses from
the hyperbola to the circle cost ``sqrt(v_inf^2 + 2 mu/r_p) - sqrt(mu/r_p)`` in total
whatever N and the periods (:func:`lunarcap.mission.impulsive.capture_total_mps`), so any
difference between counts is the finite burns' loss (and, in full dynamics, the Earth's
and Sun's pull on the longer orbits).

A count for which no plan exists is reported as such (``status`` "infeasible" with the
reason: for example a burn longer than half the orbit around it), and a count whose NLP
fails as "failed" with IPOPT's status; neither is an error of the study.
"""

from __future__ import annotations

import hashlib
import math
import time
from functools import lru_cache
from pathlib import Path

import numpy as np

from lunarcap.errors import InputError, SolveError
from lunarcap.mission.impulsive import capture_total_mps, equal_split_periods_s
from lunarcap.mission.plan import CapturePlan, PlanError, plan_ephemeris
from lunarcap.mission.targets import CIRCULAR
from lunarcap.optim.joint import solve_joint
from lunarcap.physics import constants as C
from lunarcap.physics.ephemeris import ChebyshevFit
from lunarcap.physics.epochs import calendar_from_seconds
from lunarcap.repro.cache import cached
from lunarcap.runs.chain import impulsive_limit, solve_plan

#: Longest intermediate period allowed by default, h (the paper's first ellipse: longer
#: orbits are strongly perturbed by the Earth).
DEFAULT_MAX_PERIOD_H = 12.235
#: Longest time from the arrival perilune to the end of the last burn, by default, days.
DEFAULT_MAX_DAYS = 3.0
#: Shortest intermediate period allowed: the circle's at the perilune radius plus this, s.
MIN_PERIOD_MARGIN_S = 60.0
#: Margin of the ephemeris fit around the capture, s; a fit spans at most 4 days.
FIT_MARGIN_S = 6 * 3600.0
MAX_FIT_SPAN_S = 4 * 86400.0

STATUSES = ("ok", "infeasible", "failed")


@lru_cache(maxsize=1)
def module_version() -> str:
    """Hash of this module's source: part of the cache key of :func:`solve_count`."""
    return hashlib.sha256(Path(__file__).read_bytes()).hexdigest()[:16]


def circle_period_s(r_km: float) -> float:
    """Period of the circle of radius r about the Moon, s."""
    return 2 * math.pi * math.sqrt(r_km ** 3 / C.MU_MOON)


def check_bounds(max_period_s: float, max_time_s: float) -> None:
    """InputError unless both bounds are positive finite numbers."""
    for name, v, unit in (("the longest period", max_period_s / 3600.0, "h"),
                          ("the longest time to the final orbit", max_time_s / 86400.0,
                           "days")):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) \
                or v <= 0:
            raise InputError(f"{name} must be a positive number of {unit}, got {v!r}")


def count_guess(plan: CapturePlan, n: int, max_period_s: float) -> CapturePlan:
    """The plan in ``n`` burns with the equal-share periods (the search's start).

    Raises PlanError (the count is infeasible: no such plan) or InputError.
    """
    if n > 1 and max_period_s <= circle_period_s(plan.perilune_radius_km) + MIN_PERIOD_MARGIN_S:
        raise PlanError(f"the longest period {max_period_s / 3600:g} h leaves no room for an "
                        f"ellipse above the {circle_period_s(plan.perilune_radius_km) / 3600:.3f}"
                        f" h circle")
    periods = equal_split_periods_s(plan.perilune_radius_km, plan.arrival.v_inf_kmps, n,
                                    max_period_s)
    return plan.with_burn_count(periods)


def _fit_for(plan: CapturePlan, n: int, max_period_s: float, max_time_s: float):
    """One Earth/Sun fit covering every epoch the free coasts allow (None if not needed)."""
    if plan.dynamics != "full":
        return None
    t0 = plan.nominal_perilunes_s[0]
    horizon = min(max_time_s, (n - 1) * max_period_s) + plan.coast_s(plan.n_burns - 1)
    span = horizon + 2 * FIT_MARGIN_S
    if span > MAX_FIT_SPAN_S:
        raise InputError(f"the capture may last {horizon / 86400:.2f} days: an ephemeris fit "
                         f"covers at most {MAX_FIT_SPAN_S / 86400 - 0.5:g} days; lower "
                         f"--max-days or --max-period-h")
    return ChebyshevFit.fit(plan_ephemeris(plan.ephemeris), t0 - FIT_MARGIN_S, t0 + span
                            - FIT_MARGIN_S)


def _burn_rows(plan: CapturePlan, legs: list, imps: list | None) -> list[dict]:
    t = plan.nominal_perilunes_s
    rows = []
    for k, sol in enumerate(legs):
        s = sol.summary()
        b = plan.burns[k]
        imp = None if imps is None else imps[k]["delta_v_mps"]
        rows.append({
            "burn": k + 1, "target": b.describe(),
            "period_after_h": (b.period_s / 3600.0 if b.target != CIRCULAR
                               else circle_period_s(plan.perilune_radius_km) / 3600.0),
            "nominal_perilune_epoch": calendar_from_seconds(t[k]),
            "ignition_epoch": s["ignition_epoch"], "start_min": s["start_min"],
            "burn_duration_min": s["burn_duration_min"], "delta_v_mps": s["delta_v_mps"],
            "impulsive_delta_v_mps": imp,
            "loss_mps": None if imp is None else s["delta_v_mps"] - imp,
            "m_start_kg": s["m_start_kg"], "m_end_kg": s["m_end_kg"],
            "fuel_kg": s["fuel_kg"], "rp_end_km": s["rp_end_km"], "ra_end_km": s["ra_end_km"],
            "verified": bool(sol.verification.passed),
            "impulsive_verified": None if imps is None else imps[k]["verification_passed"]})
    return rows


@cached(ignore=["verbose"])
def solve_count(plan: CapturePlan, n: int, max_period_s: float, max_time_s: float,
                impulsive: bool = True, version: str = "", verbose: bool = False) -> dict:
    """The capture of ``plan`` (pass ``plan.key()``) in ``n`` burns, periods optimised.

    See the module docstring. ``version`` is :func:`module_version` (part of the cache key).

    Returns
    -------
    dict
        ``n_burns``, ``status`` ("ok", "infeasible" or "failed"), ``reason`` (why not ok),
        ``periods_h`` (the optimal intermediate periods), ``burns`` (one row per burn:
        target, ignition, duration, delta-V, impulsive limit, loss, masses, verdicts),
        ``total_delta_v_mps``, ``total_impulsive_delta_v_mps`` (sum of the limits),
        ``total_loss_mps``, ``two_body_impulsive_total_mps`` (the closed form),
        ``fuel_kg``, ``final_mass_kg``, ``time_to_final_orbit_h`` (arrival perilune to
        the end of the last burn), ``ipopt_status``, ``iterations``, ``wall_s``.
    """
    t_start = time.perf_counter()
    n = int(n)
    out = {"n_burns": n, "status": "ok", "reason": "", "periods_h": [], "burns": [],
           "two_body_impulsive_total_mps": capture_total_mps(plan.perilune_radius_km,
                                                             plan.arrival.v_inf_kmps),
           "ipopt_status": "", "iterations": None}
    try:
        guess = count_guess(plan, n, max_period_s)
        fit = _fit_for(guess, n, max_period_s, max_time_s)
    except PlanError as exc:
        out.update(status="infeasible", reason=str(exc), wall_s=time.perf_counter() - t_start)
        return out
    eph = plan_ephemeris(plan.ephemeris)
    try:
        seq = solve_plan(guess, verbose=verbose)
        lo = circle_period_s(plan.perilune_radius_km) + MIN_PERIOD_MARGIN_S
        res = solve_joint(guess, seq, eph, free_coasts=(True,) * (n - 1) + (False,),
                          coast_bounds_s=(lo, max_period_s), max_time_s=max_time_s, fit=fit)
    except SolveError as exc:
        out.update(status="failed", reason=str(exc), ipopt_status=exc.status,
                   wall_s=time.perf_counter() - t_start)
        return out
    opt = res.plan
    imps = None
    if impulsive:
        imps, t = [], opt.nominal_perilunes_s
        x = [seq[0].problem.x_ref] + [leg.end_state for leg in res.legs[:-1]]
        try:
            for k in range(n):
                rest = opt.resumed(k, t[k], x[k], window_min=(-10.0, 10.0))
                imps.append(impulsive_limit(rest.key(1), verbose=verbose))
        except (SolveError, PlanError) as exc:
            out["reason"] = f"impulsive limit of burn {len(imps) + 1}: {exc}"
            imps = None
    rows = _burn_rows(opt, res.legs, imps)
    dv = sum(r["delta_v_mps"] for r in rows)
    imp_total = None if imps is None else sum(r["impulsive_delta_v_mps"] for r in rows)
    last = res.legs[-1]
    t0 = opt.nominal_perilunes_s[0]
    out.update(
        periods_h=[b.period_s / 3600.0 for b in opt.burns[:-1]], burns=rows,
        total_delta_v_mps=dv, total_impulsive_delta_v_mps=imp_total,
        total_loss_mps=None if imp_total is None else dv - imp_total,
        fuel_kg=rows[0]["m_start_kg"] - rows[-1]["m_end_kg"],
        final_mass_kg=rows[-1]["m_end_kg"],
        total_burn_duration_min=sum(r["burn_duration_min"] for r in rows),
        time_to_final_orbit_h=(last.problem.t_ign_s + last.raw.t1_s - t0) / 3600.0,
        all_verified=all(r["verified"] for r in rows),
        ipopt_status=res.ipopt_status, iterations=res.iterations, nlp_solve_s=res.solve_s,
        wall_s=time.perf_counter() - t_start)
    if not out["all_verified"]:
        out.update(status="failed", reason="a burn failed verification")
    return out


def count_result(plan: CapturePlan, n: int, max_period_h: float = DEFAULT_MAX_PERIOD_H,
                 max_days: float = DEFAULT_MAX_DAYS, impulsive: bool = True,
                 use_cache: bool = True, verbose: bool = False) -> dict:
    """:func:`solve_count` of ``plan`` in ``n`` burns with bounds in hours and days."""
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise InputError(f"a number of burns is an integer >= 1, got {n!r}")
    check_bounds(max_period_h * 3600.0, max_days * 86400.0)
    fn = solve_count if use_cache else solve_count.uncached
    return fn(plan.key(), int(n), float(max_period_h) * 3600.0, float(max_days) * 86400.0,
              impulsive, module_version(), verbose=verbose)
