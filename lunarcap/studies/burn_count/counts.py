"""How many capture burns: a plan's capture in N burns, the intermediate orbits optimised.

For a count N, the capture goes from the plan's arrival to its final orbit (its last
burn's target) through N-1 intermediate ellipses with the plan's perilune radius and
inclination. Their periods are chosen to minimise the total delta-V of the finite burns:

1. a start: the periods that share the two-body impulsive total equally among the burns
   (:func:`lunarcap.mission.impulsive.equal_split_periods_s`; the first ellipse no longer
   than the longest period allowed);
2. that plan solved burn by burn, every ignition free (:func:`lunarcap.capture.chain.solve_plan`,
   cached), the warm start of
3. the all-burns NLP with the N-1 coasts free (:func:`lunarcap.optim.joint.solve_joint`):
   objective the total delta-V; each period between the final orbit's (+1 min) and
   ``max_period_s``, each no longer than the one before, and the end of the last burn at
   most ``max_time_s`` after the arrival perilune. Its optimum is verified leg by leg.

Each burn's loss is measured against its impulsive limit in the same dynamics from the
same (verified) pre-burn state at its nominal perilune
(:func:`lunarcap.capture.chain.impulsive_limit` of the plan resumed from that state,
:meth:`lunarcap.mission.plan.CapturePlan.resumed`).

What the impulsive limit predicts: in two-body dynamics, tangential perilune impulses from
the hyperbola to the final orbit cost ``sqrt(v_inf^2 + 2 mu/r_p) - v_p(final)`` in total
(``v_p = sqrt(mu/r_p)`` for the circle, the perilune speed of the final ellipse asked
otherwise) whatever N and the periods (:func:`two_body_total_mps`, the sum of ``lunarcap
impulsive --plan``'s burns), so any difference between counts is the finite burns' loss
(and, in full dynamics, the Earth's and Sun's pull on the longer orbits).

A count for which no plan exists is reported as such (``status`` "infeasible" with the
reason: for example a burn longer than half the orbit around it), and a count whose NLP
fails as "failed" with IPOPT's status; neither is an error of the study.
"""

from __future__ import annotations

import math
import re
import time

import numpy as np

from lunarcap.capture.chain import impulsive_limit, solve_plan, time_to_final_orbit_h
from lunarcap.errors import InputError, SolveError, integer, number_list
from lunarcap.mission.impulsive import capture_total_mps, equal_split_periods_s
from lunarcap.mission.plan import CapturePlan, PlanError
from lunarcap.mission.targets import CIRCULAR
from lunarcap.optim.joint import solve_joint
from lunarcap.physics import constants as C
from lunarcap.physics.dynamics import fit_for, force_model
from lunarcap.physics.elements import period_from_semi_major_axis
from lunarcap.physics.epochs import calendar_from_seconds
from lunarcap.repro.cache import cached, code_version, position
from lunarcap.studies.campaign import TableFormat
from lunarcap.studies.study import Study, check_workers, json_list, plan_columns

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

#: This module, relative to the package: its tables' and cached cases' code version is
#: :func:`lunarcap.repro.cache.code_version` of the numerical code and this file.
_MODULE = "studies/burn_count/counts.py"


def circle_period_s(r_km: float) -> float:
    """Period of the circle of radius r about the Moon, s."""
    return float(period_from_semi_major_axis(r_km, C.MU_MOON))


def check_bounds(max_period_s: float, max_time_s: float) -> None:
    """InputError unless both bounds are positive finite numbers."""
    for name, v, unit in (("the longest period", max_period_s / 3600.0, "h"),
                          ("the longest time to the final orbit", max_time_s / 86400.0,
                           "days")):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) \
                or v <= 0:
            raise InputError(f"{name} must be a positive number of {unit}, got {v!r}")


def final_period_s(plan: CapturePlan) -> float | None:
    """Period of the plan's final orbit if it is an ellipse (s); None for the circle."""
    last = plan.burns[-1]
    return None if last.target == CIRCULAR else last.period_s


def shortest_period_s(plan: CapturePlan) -> float:
    """Shortest intermediate period: the final orbit's (+ :data:`MIN_PERIOD_MARGIN_S`), s."""
    final = final_period_s(plan)
    return (circle_period_s(plan.perilune_radius_km) if final is None else final) + \
        MIN_PERIOD_MARGIN_S


def two_body_total_mps(plan: CapturePlan) -> float:
    """The two-body impulsive total into the plan's final orbit, any N and periods, m/s.

    :func:`lunarcap.mission.impulsive.capture_total_mps` to the circle or to the final
    ellipse asked: the sum of ``lunarcap impulsive --plan``'s burns, whatever the count.
    """
    return capture_total_mps(plan.perilune_radius_km, plan.arrival.v_inf_kmps,
                             final_period_s=final_period_s(plan))


def count_guess(plan: CapturePlan, n: int, max_period_s: float) -> CapturePlan:
    """The plan in ``n`` burns with the equal-share periods (the search's start).

    The periods share the impulsive total into the plan's final orbit (circle or
    ellipse). Raises PlanError (the count is infeasible: no such plan) or InputError.
    """
    final = final_period_s(plan)
    if n > 1 and max_period_s <= shortest_period_s(plan):
        what = (f"{circle_period_s(plan.perilune_radius_km) / 3600:.3f} h circle"
                if final is None else f"{final / 3600:.3f} h final orbit")
        raise PlanError(f"the longest period {max_period_s / 3600:g} h leaves no room for an "
                        f"ellipse above the {what}")
    periods = equal_split_periods_s(plan.perilune_radius_km, plan.arrival.v_inf_kmps, n,
                                    max_period_s, final_period_s=final)
    return plan.with_burn_count(periods)


def fit_span_s(plan: CapturePlan, n: int, max_period_s: float, max_time_s: float) -> float:
    """The span (s) of the fit a count needs, InputError beyond what one fit covers.

    Only dynamics that read the ephemeris (the Earth and the Sun, a field's body frame)
    need a fit: 0 for the others (see :func:`_without_fit`). The span depends on the
    bounds and the plan's last coast alone, so the command checks every count before any
    solve (:func:`check_counts`).
    """
    if not force_model(plan.dynamics).needs_fit:
        return 0.0
    horizon = min(max_time_s, (n - 1) * max_period_s) + plan.coast_s(plan.n_burns - 1)
    span = horizon + 2 * FIT_MARGIN_S
    if span > MAX_FIT_SPAN_S:
        raise InputError(f"the capture in {n} burns may last {horizon / 86400:.2f} days: an "
                         f"ephemeris fit covers at most {MAX_FIT_SPAN_S / 86400 - 0.5:g} days; "
                         f"lower --max-days or --max-period-h")
    return span


def check_counts(plan: CapturePlan, counts, max_period_s: float, max_time_s: float) -> None:
    """InputError (before any solve) if a count's capture could outlast an ephemeris fit."""
    for n in counts:
        fit_span_s(plan, n, max_period_s, max_time_s)


def _fit_for(plan: CapturePlan, n: int, max_period_s: float, max_time_s: float):
    """One Earth/Sun fit covering every epoch the free coasts allow (None if not needed)."""
    span = fit_span_s(plan, n, max_period_s, max_time_s)
    if not span:
        return None
    t0 = plan.nominal_perilunes_s[0]
    return fit_for(plan.dynamics, plan.ephemeris_model(), t0 - FIT_MARGIN_S,
                   t0 + span - FIT_MARGIN_S)


def _without_fit(sol):
    """``sol`` with its problem's ephemeris fit dropped (two-body and J2 dynamics).

    :func:`lunarcap.capture.chain.solve_plan` builds every burn with a fit of its own orbit
    (unused outside full dynamics); :func:`lunarcap.optim.joint.solve_joint` keeps a warm
    start's fit for each leg when it is given none, and the propagation then checks the
    optimised legs' epochs against that window. Free coasts shortened by a binding
    ``max_time_s`` move the epochs out of it ("propagation leaves the ephemeris-fit
    window"), although no ephemeris is used. Without a fit, each leg gets its own.
    """
    from dataclasses import replace

    prob = sol.raw.prob
    if prob.model.fit is None:
        return sol
    return replace(sol, raw=replace(sol.raw, prob=replace(
        prob, model=replace(prob.model, fit=None))))


def _burn_rows(plan: CapturePlan, legs: list, imps: list | None) -> list[dict]:
    t = plan.nominal_perilunes_s
    rows = []
    for k, sol in enumerate(legs):
        s = sol.summary()
        b = plan.burns[k]
        imp = None if imps is None else imps[k]["delta_v_mps"]
        rows.append({
            "burn": k + 1, "target_orbit": b.describe(),
            "period_after_h": (b.period_s / 3600.0 if b.target != CIRCULAR
                               else circle_period_s(plan.perilune_radius_km) / 3600.0),
            "nominal_perilune_epoch": calendar_from_seconds(t[k]),
            "ignition_epoch": s["ignition_epoch"], "start_min": s["start_min"],
            "burn_duration_min": s["burn_duration_min"], "delta_v_mps": s["delta_v_mps"],
            "impulsive_limit_mps": imp,
            "delta_v_loss_mps": None if imp is None else s["delta_v_mps"] - imp,
            "m_start_kg": s["m_start_kg"], "m_end_kg": s["m_end_kg"],
            "fuel_kg": s["fuel_kg"], "rp_end_km": s["rp_end_km"], "ra_end_km": s["ra_end_km"],
            "verified": bool(sol.verification.passed),
            "impulsive_verified": None if imps is None else imps[k]["verification_passed"]})
    return rows


@cached(ignore=["verbose"])
def solve_count(plan: CapturePlan, n: int, max_period_s: float, max_time_s: float,
                impulsive: bool = True, version: str = "", verbose: bool = False) -> dict:
    """The capture of ``plan`` (pass ``plan.key()``) in ``n`` burns, periods optimised.

    See the module docstring. ``version`` is ``code_version(_MODULE)`` (part of the cache key).
    Never raises for a count without a plan (status "infeasible", also when the optimum
    found is no valid ``n``-burn plan, see :func:`_not_a_plan`) or a failed solve
    ("failed").

    Returns
    -------
    dict
        ``n_burns``, ``status`` ("ok", "infeasible" or "failed"), ``reason`` (why not ok),
        ``periods_h`` (the optimal intermediate periods), ``burns`` (one row per burn:
        target, ignition, duration, delta-V, impulsive limit, loss, masses, verdicts),
        ``total_delta_v_mps``, ``total_impulsive_limit_mps`` (sum of the limits),
        ``total_delta_v_loss_mps``, ``total_impulsive_delta_v_two_body_mps`` (the closed form),
        ``total_fuel_kg``, ``final_mass_kg``, ``time_to_final_orbit_h`` (arrival perilune to
        the end of the last burn), ``ipopt_status``, ``total_ipopt_iterations``, ``wall_s``.
    """
    t_start = time.perf_counter()
    n = int(n)
    out = {"n_burns": n, "status": "ok", "reason": "", "periods_h": [], "burns": [],
           "total_impulsive_delta_v_two_body_mps": two_body_total_mps(plan),
           "ipopt_status": "", "total_ipopt_iterations": None}
    try:
        guess = count_guess(plan, n, max_period_s)
        fit = _fit_for(guess, n, max_period_s, max_time_s)
    except PlanError as exc:
        out.update(status="infeasible", reason=str(exc), wall_s=time.perf_counter() - t_start)
        return out
    try:
        seq, res = _optimum(plan, guess, n, max_period_s, max_time_s, fit, verbose)
    except PlanError as exc:  # raised by the optimum's plan, after IPOPT succeeded
        out.update(status="infeasible", reason=_not_a_plan(n, exc),
                   wall_s=time.perf_counter() - t_start)
        return out
    except SolveError as exc:
        out.update(status="failed", reason=str(exc), ipopt_status=exc.status,
                   wall_s=time.perf_counter() - t_start)
        return out
    except RuntimeError as exc:  # a guess's propagation failed
        out.update(status="failed", reason=f"no initial guess: {exc}".split("\n")[0],
                   wall_s=time.perf_counter() - t_start)
        return out
    imps = None
    if impulsive:
        imps, out["reason"] = _impulsive_limits(res, seq[0].problem.x_ref, verbose)
    out.update(_totals(res, imps))
    out["wall_s"] = time.perf_counter() - t_start
    if not out["all_verified"]:
        out.update(status="failed", reason="a burn failed verification")
    return out


def _optimum(plan: CapturePlan, guess: CapturePlan, n: int, max_period_s: float,
             max_time_s: float, fit, verbose: bool):
    """The chain solved burn by burn (the warm start) and the all-burns optimum from it.

    Returns ``(seq, res)``: the list of Solution and the
    :class:`lunarcap.optim.joint.JointResult`. Raises SolveError, PlanError (the
    optimum's coasts make no valid plan) or RuntimeError (a guess's propagation).
    """
    seq = solve_plan(guess, verbose=verbose)
    if not force_model(plan.dynamics).needs_fit:
        seq = [_without_fit(sol) for sol in seq]
    lo = shortest_period_s(plan)
    res = solve_joint(guess, seq, plan.ephemeris_model(),
                      free_coasts=(True,) * (n - 1) + (False,),
                      coast_bounds_s=(lo, max_period_s), max_time_s=max_time_s, fit=fit)
    return seq, res


#: The plan checker's words for a burn of (next to) no delta-V: "burn 3 (0.0 m/s)".
_VANISHED_BURN = re.compile(r"burn (\d+) \((-?\d+(?:\.\d+)?) m/s\)")


def _not_a_plan(n: int, exc: PlanError) -> str:
    """Why the all-burns optimum is no ``n``-burn plan (the reason of status "infeasible").

    The NLP bounds each period below by the previous one and the circle's (+1 min), not
    strictly: an optimum may put two consecutive periods on the same bound, so that the
    burn between them does nothing (e.g. 4 burns within 0.29 days in two-body: both last
    periods at the shortest allowed, burn 3 of 0.0 m/s). The plan checker then refuses the
    optimum's plan, naming the engine ("too strong") or the period ("not shorter"); the
    culprit is the count, one burn too many within the bounds.
    """
    m = _VANISHED_BURN.search(str(exc))
    if m and abs(float(m.group(2))) < 0.05:
        return (f"burn {m.group(1)} vanishes at the optimum ({m.group(2)} m/s: the orbits "
                f"before and after it have the same period): within these bounds {n} burns "
                f"do no better than {n - 1}; plan check: {exc}")
    if "is not shorter than the orbit before" in str(exc):
        return (f"two consecutive periods coincide at the optimum: within these bounds {n} "
                f"burns do no better than {n - 1}; plan check: {exc}")
    return f"the all-burns optimum is no valid {n}-burn plan: {exc}"


def _impulsive_limits(res, x_arrival, verbose: bool) -> tuple:
    """Each burn's impulsive limit from its verified pre-burn state at its nominal perilune.

    Returns ``(limits, reason)``: the list of :func:`lunarcap.capture.chain.impulsive_limit`
    dicts and "", or None and why one of them could not be computed. In a gravity field a
    burn may have no limit (no impulse reaches its orbit): its dict's delta-V is None, and
    the reason says which burn and why (the count's totals then have no loss).
    """
    opt, imps = res.plan, []
    t = opt.nominal_perilunes_s
    x = [x_arrival] + [leg.end_state for leg in res.legs[:-1]]
    try:
        for k in range(opt.n_burns):
            rest = opt.resumed(k, t[k], x[k], window_min=(-10.0, 10.0))
            imps.append(impulsive_limit(rest.key(1), verbose=verbose))
    except (SolveError, PlanError) as exc:
        return None, f"impulsive limit of burn {len(imps) + 1}: {exc}"
    none = [f"burn {k + 1}: {imp['reason']}" for k, imp in enumerate(imps)
            if imp["delta_v_mps"] is None]
    return imps, "; ".join(none)


def _totals(res, imps: list | None) -> dict:
    """The count's burn rows and totals (the keys of :func:`solve_count` after a solve)."""
    opt = res.plan
    rows = _burn_rows(opt, res.legs, imps)
    dv = sum(r["delta_v_mps"] for r in rows)
    limits = [r["impulsive_limit_mps"] for r in rows]
    imp_total = None if imps is None or None in limits else sum(limits)
    last = res.legs[-1]
    t0 = opt.nominal_perilunes_s[0]
    return dict(
        periods_h=[b.period_s / 3600.0 for b in opt.burns[:-1]], burns=rows,
        total_delta_v_mps=dv, total_impulsive_limit_mps=imp_total,
        total_delta_v_loss_mps=None if imp_total is None else dv - imp_total,
        total_fuel_kg=rows[0]["m_start_kg"] - rows[-1]["m_end_kg"],
        final_mass_kg=rows[-1]["m_end_kg"],
        total_burn_duration_min=sum(r["burn_duration_min"] for r in rows),
        time_to_final_orbit_h=time_to_final_orbit_h(t0, last),
        all_verified=all(r["verified"] for r in rows),
        ipopt_status=res.ipopt_status, total_ipopt_iterations=res.iterations,
        nlp_solve_s=res.solve_s)


def count_result(plan: CapturePlan, n: int, max_period_h: float = DEFAULT_MAX_PERIOD_H,
                 max_days: float = DEFAULT_MAX_DAYS, impulsive: bool = True,
                 verbose: bool = False) -> dict:
    """:func:`solve_count` of ``plan`` in ``n`` burns with bounds in hours and days.

    Cached as the cache switch says (:func:`lunarcap.repro.cache.caching`).
    """
    if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
        raise InputError(f"a number of burns is an integer >= 1, got {n!r}")
    check_bounds(max_period_h * 3600.0, max_days * 86400.0)
    return solve_count(plan.key(), int(n), float(max_period_h) * 3600.0, float(max_days) * 86400.0,
              impulsive, code_version(_MODULE), verbose=verbose)


# ====================================================================== the study on Dask
#: Columns of the study's table (one row per plan and count; units in the names).
COLUMNS = ("plan", "plan_id", "thrust_N", "isp_s", "dynamics", "n_burns", "max_period_h",
           "max_days", "status", "reason", "periods_h", "total_delta_v_mps",
           "total_impulsive_limit_mps", "total_delta_v_loss_mps",
           "total_impulsive_delta_v_two_body_mps",
           "total_fuel_kg", "final_mass_kg", "total_burn_duration_min", "time_to_final_orbit_h",
           "all_verified", "ipopt_status", "total_ipopt_iterations", "burns_json", "task_wall_s",
           "worker", "code_version", "completed_utc", "error")
KEY = ("plan_id", "n_burns", "max_period_h", "max_days")


def parse_counts(text) -> tuple:
    """Counts of burns from ``"1,2,3"`` (or a sequence): distinct integers >= 1, sorted."""
    counts = number_list("--counts", text, "", distinct=True)
    return tuple(sorted(integer("--counts", n, 1) for n in counts))


def count_row(plan: CapturePlan, n: int, max_period_h: float, max_days: float) -> dict:
    """Dask task: one plan in ``n`` burns, as a row of the study's table.

    Never raises for a solver failure (status "failed" with IPOPT's status); the campaign
    records any other exception as status "error" (:func:`lunarcap.studies.campaign.guarded`).
    """
    import json

    r = count_result(plan, n, max_period_h, max_days)
    row = {k: r.get(k) for k in COLUMNS if k in r and k not in ("burns_json",)}
    row["periods_h"] = ";".join(f"{p:.6f}" for p in r["periods_h"])
    row["burns_json"] = json.dumps(r["burns"])
    row["task_wall_s"] = r.get("wall_s")
    row["error"] = ""
    return row


def run_burns(plans, counts, max_period_h: float = DEFAULT_MAX_PERIOD_H,
              max_days: float = DEFAULT_MAX_DAYS, out=None, workers=2, scheduler=None,
              progress: bool = True, use_cache: bool | None = None, processes: bool = True,
              task=None):
    """Run (or resume) the study for every plan and count on Dask (see the module).

    Returns a :class:`lunarcap.studies.campaign.CampaignResult` whose table has one row per
    (plan, count), in the order given. ``use_cache``: the cache switch for the tasks (None:
    its current position, :func:`lunarcap.repro.cache.position`). InputError (bad counts or
    bounds, an unusable ``out``, an unreachable scheduler) before any solve.
    """
    use_cache = position(use_cache)
    counts = parse_counts(counts)
    check_bounds(_hours(max_period_h) * 3600.0, _days(max_days) * 86400.0)
    workers = check_workers(workers)
    for plan in plans:
        check_counts(plan, counts, _hours(max_period_h) * 3600.0, _days(max_days) * 86400.0)
    cases = []
    for plan in plans:
        for n in counts:
            key = {**plan_columns(plan), "n_burns": n, "max_period_h": float(max_period_h),
                   "max_days": float(max_days)}
            cases.append((key, (plan, n, float(max_period_h), float(max_days))))
    return STUDY.run(cases, out, task=task, workers=workers, scheduler=scheduler,
                     progress=progress, processes=processes, use_cache=use_cache,
                     describe={"study": "burns", "counts": list(counts),
                               "max_period_h": max_period_h, "max_days": max_days})


def _nlp_shapes(key: dict) -> tuple:
    """Cases that solve NLPs of the same shapes (count and dynamics): one worker builds them.

    An all-burns NLP of n legs takes 1.6 s of CPU to build for one leg and 14 s for five
    (full dynamics); built by every worker that meets it, the builds were half of the
    book's burns study.
    """
    return key["n_burns"], key["dynamics"]


def _hours(v) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
        raise InputError(f"--max-period-h must be a positive number of hours, got {v!r}")
    return float(v)


def _days(v) -> float:
    if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or v <= 0:
        raise InputError(f"--max-days must be a positive number of days, got {v!r}")
    return float(v)


def periods_of(text) -> list:
    """The intermediate periods (h) of a ``periods_h`` cell ("8.365;3.5", empty or NaN)."""
    return [float(p) for p in text.split(";") if p] if isinstance(text, str) else []


def format_rows(result, plan: CapturePlan) -> str:
    """The study's text: one block per count (its burns), then the run."""
    rows = result.table.to_dict("records")
    lines = [f"Plan {plan.name} in N burns: {plan.engine.thrust_N:g} N / "
             f"{plan.engine.isp_s:g} s, {plan.dynamics} dynamics, final orbit "
             f"{plan.burns[-1].describe()}; intermediate periods optimised (longest "
             f"{rows[0]['max_period_h']:g} h, all burns within {rows[0]['max_days']:g} days); "
             f"loss against the impulsive limit in the same dynamics"
             if rows else f"Plan {plan.name}: no counts"]
    if rows:
        lines.append(f"two-body impulsive total (any N, any periods): "
                     f"{two_body_total_mps(plan):.3f}"
                     f" m/s")
    for r in rows:
        n = int(r["n_burns"])
        if r["status"] != "ok":
            lines.append(f"N = {n}: {r['status']}: {r['reason'] or r['error']}")
            continue
        periods = r["periods_h"] if isinstance(r["periods_h"], str) else ""
        lines.append(
            f"N = {n}: total dV {r['total_delta_v_mps']:.3f} m/s, impulsive "
            f"{_num(r['total_impulsive_limit_mps'])} m/s, loss {_num(r['total_delta_v_loss_mps'])} "
            f"m/s; fuel {r['total_fuel_kg']:.2f} kg; final orbit {r['time_to_final_orbit_h']:.2f} "
            f"h "
            f"after arrival; periods "
            + (", ".join(f"{float(p):.3f}" for p in periods.split(";")) + " h" if periods
               else "none"))
        if isinstance(r["reason"], str) and r["reason"]:   # an impulsive limit in a field
            lines.append(f"    no loss where a burn has no impulsive limit: {r['reason']}")
        for b in STUDY.decode(r, "burns"):
            lines.append(f"    burn {b['burn']}: {b['target_orbit']:<20} ignition "
                         f"{b['ignition_epoch']}"
                         f" ({b['start_min']:+.2f} min), {b['burn_duration_min']:6.2f} min, "
                         f"dV {b['delta_v_mps']:8.3f} m/s, impulsive "
                         f"{_num(b['impulsive_limit_mps'])}, loss {_num(b['delta_v_loss_mps'])} m/s"
                         f"{'' if b['verified'] else ', NOT VERIFIED'}")
    return "\n".join(lines + STUDY.run_lines(result))


def _num(v, fmt: str = ".3f") -> str:
    return "—" if v is None or (isinstance(v, float) and not math.isfinite(v)) else \
        f"{v:{fmt}}"


#: The study, declared once (:class:`lunarcap.studies.study.Study`).
STUDY = Study(
    "burns", TableFormat(KEY, COLUMNS, text_columns=("plan", "plan_id", "dynamics", "reason",
                                                     "periods_h", "ipopt_status",
                                                     "burns_json")),
    count_row, STATUSES, ("ok", "infeasible"), "count", "burns study", (_MODULE,),
    decoders=(("periods_h", "periods_h", periods_of), ("burns_json", "burns", json_list)),
    rows_key="counts", text=format_rows,
    longest=lambda key: key["n_burns"],  # an NLP of n legs
    affinity=_nlp_shapes)
