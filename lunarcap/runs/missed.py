"""Missed thrust: the engine stops during a capture burn; the rest of the capture, re-planned.

The **nominal** capture is the plan's all-burns optimum with every ignition free and the
plan's periods (:func:`lunarcap.runs.joint.solve_plan_jointly`, verified leg by leg).
In a case (burn n, fraction f, delay d):

1. **Cut-off.** Burn n is flown as planned (its optimal steering, re-propagated from its
   ignition state, :func:`lunarcap.optim.verify.fly_burn_until`) and the engine stops
   after ``f`` of its duration. The orbit at cut-off is classified: an **escape**
   (hyperbola, specific energy >= 0), a **capture** (ellipse) whose apolune lies inside
   the Moon's sphere of influence (Laplace's radius a (m_Moon/m_Earth)^(2/5), a the
   Earth-Moon distance at that epoch from the ephemeris), or a **weak capture** beyond it.
2. **Delay.** The spacecraft coasts for ``d`` (the fault being cleared), in the plan's
   dynamics.
3. **Recovery.** The rest of the capture is re-planned from that state
   (:meth:`lunarcap.mission.plan.CapturePlan.resumed`) and re-optimised as one NLP
   (:func:`lunarcap.optim.joint.solve_joint`, objective the total delta-V, verified leg by
   leg): a make-up burn with burn n's target, igniting within ``window_min`` after the
   fault is cleared, whose coast to its perilune is free (between 10 min and
   ``max_period_h``: the orbit it reaches is chosen, and the capture's timeline moves with
   it), then burns n+1, ... with the plan's periods and free ignition, to the same final
   orbit. Its warm start is the same plan solved burn by burn. If the cut-off comes within
   the last second of the burn (f = 1 included), nothing is made up: the recovery is the
   plan's later burns from the cut-off state, at their nominal perilunes.

The **penalty** is measured on one basis: the delta-V from the state before burn n to the
final orbit, finite burns, same dynamics: (delta-V of the partial burn + the recovery's)
minus (the nominal burns n, n+1, ...). A recovery whose NLP IPOPT reports infeasible, or
whose make-up orbit would need a coast longer than ``max_period_h``, is "no recovery
within the plan's bounds"; any other solver failure is "failed" with IPOPT's status.
Neither is an error of the study.
"""

from __future__ import annotations

import hashlib
import math
import time
from functools import lru_cache
from pathlib import Path

import numpy as np

from lunarcap.errors import InputError, SolveError
from lunarcap.mission.plan import CapturePlan, PlanError, plan_ephemeris
from lunarcap.mission.targets import PERILUNE
from lunarcap.optim.guess import mean_motion_and_anomaly
from lunarcap.optim.joint import solve_joint
from lunarcap.optim.verify import fly_burn_until
from lunarcap.physics import constants as C
from lunarcap.physics.dynamics import Model
from lunarcap.physics.elements import mee_from_rv, orbit_summary, rv_from_mee
from lunarcap.physics.ephemeris import ChebyshevFit
from lunarcap.physics.epochs import calendar_from_seconds
from lunarcap.physics.propagate import propagate
from lunarcap.repro.cache import cached
from lunarcap.runs.burns import DEFAULT_MAX_PERIOD_H, MAX_FIT_SPAN_S
from lunarcap.runs.chain import solve_plan
from lunarcap.runs.joint import solve_plan_jointly

#: Window of the make-up burn's ignition after the fault is cleared, min.
DEFAULT_WINDOW_MIN = (0.0, 30.0)
#: A cut-off this close to the planned end of the burn leaves nothing to make up, s.
NOTHING_LEFT_S = 1.0
#: Shortest coast from the fault's end to the make-up orbit's perilune, s.
MIN_FIRST_COAST_S = 600.0
#: IPOPT statuses that mean "no solution exists within the bounds".
INFEASIBLE = ("Infeasible_Problem_Detected", "Restoration_Failed")

STATUSES = ("recovered", "no recovery", "failed", "error")


@lru_cache(maxsize=1)
def module_version() -> str:
    """Hash of this module's source: part of the cache keys of this study."""
    return hashlib.sha256(Path(__file__).read_bytes()).hexdigest()[:16]


# ---------------------------------------------------------------------- the nominal
@cached
def nominal(plan: CapturePlan, version: str = "") -> dict:
    """The plan's all-burns optimum (free ignition), verified: legs and the plan solved.

    Pass ``plan.key()``. Returns ``{"plan": CapturePlan (free ignitions), "legs": [Solution]}``.
    """
    r = solve_plan_jointly(plan)
    return {"plan": plan.with_starts(["free"] * plan.n_burns), "legs": r.joint.legs}


# ---------------------------------------------------------------------- orbits
def classify(x, t_s: float, ephemeris: str | None = None) -> dict:
    """The orbit of state ``x`` (p, f, g, h, k, L, m) at epoch ``t_s`` about the Moon.

    Returns energy (km^2/s^2), eccentricity, perilune and apolune radii (km, inf if open),
    period (h, inf if open), the sphere-of-influence radius at that epoch (km) and
    ``orbit``: "escape" (energy >= 0), "captured" (apolune inside the sphere of influence)
    or "weakly captured".
    """
    o = orbit_summary(np.asarray(x, float), C.MU_MOON)
    energy = o["v_kmps"] ** 2 / 2 - C.MU_MOON / o["r_km"]
    rm, _ = plan_ephemeris(ephemeris).moon_geocentric_state(t_s)
    soi = float(np.linalg.norm(rm[:, 0])) * (C.MU_MOON / C.MU_EARTH) ** 0.4
    if energy >= 0:
        kind, period_h = "escape", math.inf
    else:
        a = -C.MU_MOON / (2 * energy)
        period_h = 2 * math.pi * math.sqrt(a ** 3 / C.MU_MOON) / 3600.0
        kind = "captured" if o["ra_km"] < soi else "weakly captured"
    return {"orbit": kind, "energy_km2ps2": energy, "e": o["e"], "rp_km": o["rp_km"],
            "ra_km": o["ra_km"], "period_h": period_h, "r_km": o["r_km"],
            "soi_radius_km": soi}


def time_to_perilune_after_impulse_s(x, dv_mps: float, after_s: float = 0.0,
                                     mu: float = C.MU_MOON) -> float:
    """Two-body time to the first perilune later than ``after_s``, after an impulse ``dv``.

    The impulse is opposite the velocity at the state ``x``; inf if the orbit after it is
    open. Seeds the make-up burn's free coast (``after_s``: the end of the burn, whose
    target is the perilune after it).
    """
    r, v = (np.array(a, float) for a in rv_from_mee(*np.asarray(x, float)[:6], mu))
    vn = np.linalg.norm(v)
    if dv_mps * 1e-3 >= vn:   # the impulse would stop the spacecraft: no such orbit
        return math.inf
    v2 = v * (vn - dv_mps * 1e-3) / vn
    mee = mee_from_rv(r, v2, mu)
    if math.hypot(mee[1], mee[2]) >= 1:
        return math.inf
    n, M = mean_motion_and_anomaly(mee, mu)
    t = float((-M if M < 0 else 2 * math.pi - M) / n)
    while t <= after_s:
        t += 2 * math.pi / n
    return t


# ---------------------------------------------------------------------- one case
@cached(ignore=["verbose"])
def missed_case(plan: CapturePlan, burn: int, fraction: float, delay_s: float,
                max_period_s: float, window_min: tuple = DEFAULT_WINDOW_MIN,
                version: str = "", verbose: bool = False) -> dict:
    """One case of the study (see the module docstring); pass ``plan.key()``.

    Returns
    -------
    dict
        ``status`` ("recovered", "no recovery", "failed"), ``reason``; the cut-off:
        ``cutoff_epoch``, ``partial_delta_v_mps``, ``cutoff_*`` orbit (see
        :func:`classify`), ``captured``; the recovery: ``recovery_start_e`` (eccentricity
        of the state it starts from), ``recovery_delta_v_mps`` (its burns),
        ``total_delta_v_mps`` (partial + recovery), ``nominal_remaining_delta_v_mps``,
        ``penalty_mps``, ``recovery_burns`` (per burn: ignition, duration, delta-V),
        ``first_coast_h`` (the make-up orbit's coast to its perilune, optimised) and
        ``make_up_estimate_h`` (its two-body estimate, the NLP's start; inf: none),
        ``time_to_final_orbit_h`` and the nominal's
        (``nominal_time_to_final_orbit_h``), both from the nominal perilune before burn n
        to the end of the last burn; ``ipopt_status``, ``all_verified``.
    """
    t_start = time.perf_counter()
    nom = nominal(plan, module_version())
    nplan, legs = nom["plan"], nom["legs"]
    i = burn - 1
    leg = legs[i]
    raw = leg.raw
    t_ref = nplan.nominal_perilunes_s
    t_cut_rel = fraction * raw.t1_s
    xc = fly_burn_until(raw, t_cut_rel)
    t_cut = leg.problem.t_ign_s + t_cut_rel
    partial = float(xc[7]) * 1e3
    nominal_rest = sum(s.delta_v_mps for s in legs[i:])
    last = legs[-1]
    nominal_time = last.problem.t_ign_s + last.raw.t1_s - t_ref[i]
    cut = classify(xc[:7], t_cut, plan.ephemeris)
    out = {"status": "recovered", "reason": "", "cutoff_epoch": calendar_from_seconds(t_cut),
           "cutoff_min_after_ignition": t_cut_rel / 60.0,
           "nominal_burn_duration_min": raw.t1_s / 60.0, "partial_delta_v_mps": partial,
           "nominal_burn_delta_v_mps": leg.delta_v_mps,
           "nominal_remaining_delta_v_mps": nominal_rest,
           "nominal_time_to_final_orbit_h": nominal_time / 3600.0,
           "captured": cut["orbit"] != "escape",
           **{f"cutoff_{k}": v for k, v in cut.items()}}
    remaining_s = raw.t1_s - t_cut_rel
    eph = plan_ephemeris(plan.ephemeris)
    t_r = t_cut + delay_s
    # one Earth/Sun fit over the fault and the whole recovery (full dynamics)
    horizon = delay_s + max_period_s + sum(nplan.coast_s(k) for k in range(burn, plan.n_burns))
    fit = None
    if plan.dynamics == "full":
        if horizon + 7 * 3600.0 > MAX_FIT_SPAN_S:
            raise InputError(f"a delay of {delay_s / 3600:g} h leaves the recovery more than "
                             f"the 4 days an ephemeris fit covers")
        fit = ChebyshevFit.fit(eph, t_cut - 3600.0, t_cut + horizon + 6 * 3600.0)
    coast = Model(plan.dynamics, 0.0, plan.engine.isp_s, fit)
    if remaining_s < NOTHING_LEFT_S:
        if i == plan.n_burns - 1:   # the last burn ended: the capture is done
            out.update(recovery_start_e=cut["e"], recovery_delta_v_mps=0.0,
                       total_delta_v_mps=partial, penalty_mps=partial - nominal_rest,
                       recovery_burns=[], first_coast_h=None,
                       time_to_final_orbit_h=(t_cut - t_ref[i]) / 3600.0,
                       all_verified=True, ipopt_status="")
            out["wall_s"] = time.perf_counter() - t_start
            return out
        t_next = t_ref[i + 1]
        if t_r >= t_next - 0.4 * (t_next - t_ref[i]):
            out.update(status="no recovery",
                       reason="the fault outlasts the time to the next burn's perilune")
            out["wall_s"] = time.perf_counter() - t_start
            return out
        x_next = propagate(coast, t_cut, xc[:7], t_next).final
        rec_plan = nplan.resumed(i + 1, t_next, x_next, window_min=_window(nplan, i + 1))
        free = ()
    else:
        x_r = propagate(coast, t_cut, xc[:7], t_r).final if delay_s > 0 else xc[:7]
        probe = nplan.resumed(i, t_r, x_r, first_coast_s=max_period_s, window_min=window_min)
        first = nplan.burns[i]
        if first.target == PERILUNE:
            est = probe.impulsive()[0]
            burn_end = (window_min[1] + 2 * est.eq19_duration_min) * 60.0
            guess = time_to_perilune_after_impulse_s(x_r, est.delta_v_mps, burn_end)
            out["make_up_estimate_h"] = guess / 3600.0
            if not math.isfinite(guess) or guess > max_period_s:
                guess = max_period_s
            first_coast = max(guess, window_min[1] * 60.0 + MIN_FIRST_COAST_S)
        else:  # a circle: any coast; one circle period after the window
            first_coast = window_min[1] * 60.0 + 2 * probe.impulsive()[0].eq19_duration_min \
                * 60.0 + nplan.coast_s(i)
        try:
            rec_plan = nplan.resumed(i, t_r, x_r, first_coast_s=first_coast,
                                     window_min=window_min)
        except PlanError as exc:
            out.update(status="no recovery", reason=f"no plan from the cut-off state: {exc}")
            out["wall_s"] = time.perf_counter() - t_start
            return out
        free = (first.target == PERILUNE,) + (False,) * (rec_plan.n_burns - 1)
    out["recovery_start_e"] = float(math.hypot(rec_plan.start.state[1],
                                               rec_plan.start.state[2]))
    try:
        seq = solve_plan(rec_plan, verbose=verbose)
        res = solve_joint(rec_plan, seq, eph, free_coasts=free if any(free) else (),
                          coast_bounds_s=(MIN_FIRST_COAST_S, max_period_s), fit=fit)
    except RuntimeError as exc:  # the guess's propagation failed (e.g. p -> 0)
        if not isinstance(exc, SolveError):
            out.update(status="failed", reason=f"no initial guess: {exc}".split("\n")[0])
            out["wall_s"] = time.perf_counter() - t_start
            return out
        infeasible = exc.status in INFEASIBLE
        hint = ""
        if not math.isfinite(out.get("make_up_estimate_h", 0.0)):
            hint = (" (two-body estimate: no make-up orbit, a tangential impulse of the "
                    "estimated size would stop the spacecraft or leave it unbound)")
        out.update(status="no recovery" if infeasible else "failed",
                   reason=("IPOPT found no recovery within the plan's bounds "
                           f"({exc.status})" if infeasible else str(exc)) + hint,
                   ipopt_status=exc.status)
        out["wall_s"] = time.perf_counter() - t_start
        return out
    rec = res.plan
    rows = []
    for k, s in enumerate(res.legs):
        sm = s.summary()
        rows.append({"burn": burn + k, "target": rec.burns[k].describe(),
                     "ignition_epoch": sm["ignition_epoch"],
                     "ignition_min_after_fault": (s.problem.t_ign_s - t_r) / 60.0,
                     "burn_duration_min": sm["burn_duration_min"],
                     "delta_v_mps": sm["delta_v_mps"], "verified": s.verification.passed})
    rec_dv = sum(r["delta_v_mps"] for r in rows)
    end = res.legs[-1]
    out.update(recovery_delta_v_mps=rec_dv, total_delta_v_mps=partial + rec_dv,
               penalty_mps=partial + rec_dv - nominal_rest, recovery_burns=rows,
               first_coast_h=rec.coast_s(0) / 3600.0 if any(free) else None,
               time_to_final_orbit_h=(end.problem.t_ign_s + end.raw.t1_s - t_ref[i]) / 3600.0,
               all_verified=all(r["verified"] for r in rows), ipopt_status=res.ipopt_status,
               wall_s=time.perf_counter() - t_start)
    return out


def _window(plan: CapturePlan, i: int) -> tuple:
    """The free-ignition window of burn ``i`` around its nominal perilune, min.

    The plan's default: +-2 Eq. (19) durations, within 120 min and 0.4 of the orbit before.
    """
    t19 = plan.impulsive()[i].eq19_duration_min
    t = plan.nominal_perilunes_s
    lim = min(120.0, 0.4 * (t[i] - t[i - 1]) / 60.0) if i else 120.0
    return (max(-2 * t19, -lim), min(2 * t19, lim))


def case_result(plan: CapturePlan, burn: int, fraction: float, delay_min: float,
                max_period_h: float = DEFAULT_MAX_PERIOD_H,
                window_min: tuple = DEFAULT_WINDOW_MIN, use_cache: bool = True,
                verbose: bool = False) -> dict:
    """:func:`missed_case` with checked inputs (InputError) in the CLI's units."""
    check_case(plan, burn, fraction, delay_min)
    fn = missed_case if use_cache else missed_case.uncached
    return fn(plan.key(), int(burn), float(fraction), float(delay_min) * 60.0,
              float(max_period_h) * 3600.0, tuple(float(w) for w in window_min),
              module_version(), verbose=verbose)


def check_case(plan: CapturePlan, burn, fraction, delay_min) -> None:
    """InputError for a burn the plan lacks, a fraction outside (0, 1], a negative delay."""
    if isinstance(burn, bool) or not isinstance(burn, (int, np.integer)) or \
            not 1 <= burn <= plan.n_burns:
        raise InputError(f"--burn {burn!r}: plan {plan.name} has burns 1 to {plan.n_burns}")
    if not isinstance(fraction, (int, float)) or not math.isfinite(fraction) or \
            not 0 < fraction <= 1:
        raise InputError(f"a fraction of the burn must lie in (0, 1], got {fraction!r}")
    if not isinstance(delay_min, (int, float)) or not math.isfinite(delay_min) or delay_min < 0:
        raise InputError(f"a delay must be a non-negative number of minutes, got "
                         f"{delay_min!r}")


# ====================================================================== the study on Dask
#: Columns of the study's table (one row per (burn, fraction, delay); units in the names).
COLUMNS = ("plan", "plan_id", "thrust_N", "isp_s", "dynamics", "burn", "fraction",
           "delay_min", "max_period_h", "status", "reason", "captured", "cutoff_orbit",
           "cutoff_epoch", "cutoff_min_after_ignition", "nominal_burn_duration_min",
           "partial_delta_v_mps", "nominal_burn_delta_v_mps", "cutoff_energy_km2ps2",
           "cutoff_e", "cutoff_rp_km", "cutoff_ra_km", "cutoff_period_h",
           "cutoff_soi_radius_km", "recovery_start_e", "recovery_delta_v_mps",
           "total_delta_v_mps", "nominal_remaining_delta_v_mps", "penalty_mps",
           "first_coast_h", "make_up_estimate_h", "time_to_final_orbit_h",
           "nominal_time_to_final_orbit_h",
           "all_verified", "ipopt_status", "recovery_burns_json", "task_wall_s", "worker",
           "code_version", "completed_utc", "error")
KEY = ("plan_id", "burn", "fraction", "delay_min", "max_period_h")


def table_format():
    """The campaign table format of this study."""
    from lunarcap.runs.campaign import TableFormat

    return TableFormat(KEY, COLUMNS, text_columns=("plan", "plan_id", "dynamics", "reason",
                                                   "cutoff_orbit", "cutoff_epoch",
                                                   "ipopt_status", "recovery_burns_json"))


def default_table_path():
    """``<cache>/study/missed.csv``."""
    from lunarcap.repro import paths

    return paths.CACHE / "study" / "missed.csv"


def case_row(plan: CapturePlan, burn: int, fraction: float, delay_min: float,
             max_period_h: float, use_cache: bool = True) -> dict:
    """Dask task: one case as a row of the study's table (a failure is a status, not raised)."""
    import json

    from lunarcap.runs import campaign

    r, error = campaign.guarded(
        lambda: case_result(plan, burn, fraction, delay_min, max_period_h), use_cache)
    if error:
        return error
    row = {k: v for k, v in r.items() if k in COLUMNS}
    row["recovery_burns_json"] = json.dumps(r.get("recovery_burns", []))
    row["task_wall_s"] = r.get("wall_s")
    row["error"] = ""
    return row


def run_missed(plan: CapturePlan, burn: int, fractions, delays_min,
               max_period_h: float = DEFAULT_MAX_PERIOD_H, out=None, workers=2,
               scheduler=None, progress: bool = True, use_cache: bool = True,
               processes: bool = True, task=None):
    """Run (or resume) the study over fractions x delays on Dask (see the module).

    Returns a :class:`lunarcap.runs.campaign.CampaignResult` (one row per case, fractions
    major). InputError (a burn the plan lacks, fractions outside (0, 1], negative delays,
    an unusable ``out``, an unreachable scheduler) before any solve.
    """
    from lunarcap.repro.cache import code_version
    from lunarcap.runs.burns import plan_id
    from lunarcap.runs.campaign import parse_numbers, run_campaign
    from lunarcap.runs.study import check_workers

    fractions = parse_numbers("--fractions", fractions, 0.0, False, 1.0)
    delays = parse_numbers("--delays-min", delays_min, 0.0, True)
    check_case(plan, burn, fractions[0], delays[0])
    if isinstance(max_period_h, bool) or not isinstance(max_period_h, (int, float)) or \
            not math.isfinite(max_period_h) or max_period_h <= 0:
        raise InputError(f"--max-period-h must be a positive number of hours, got "
                         f"{max_period_h!r}")
    workers = check_workers(workers)
    pid = plan_id(plan)
    cases = [({"plan": plan.name, "plan_id": pid, "thrust_N": plan.engine.thrust_N,
               "isp_s": plan.engine.isp_s, "dynamics": plan.dynamics, "burn": int(burn),
               "fraction": f, "delay_min": d, "max_period_h": float(max_period_h)},
              (plan, int(burn), f, d, float(max_period_h), use_cache))
             for f in fractions for d in delays]
    return run_campaign(cases, task or case_row, out or default_table_path(), table_format(),
                        f"{code_version()}:{module_version()}", workers=workers,
                        scheduler=scheduler, progress=progress, processes=processes,
                        desc="missed-thrust study", unit="case", recompute=not use_cache,
                        ok_statuses=("recovered", "no recovery"),
                        describe={"study": "missed", "burn": int(burn),
                                  "fractions": list(fractions), "delays_min": list(delays)})


def recovery_burns_of(row) -> list:
    """The recovery's burns of a table row (decoded ``recovery_burns_json``)."""
    import json

    text = row["recovery_burns_json"] if isinstance(row, dict) else row.recovery_burns_json
    return json.loads(text) if isinstance(text, str) and text else []


def format_rows(plan: CapturePlan, burn: int, rows: list, result) -> str:
    """The CLI's text: one line per case, then the run."""
    lines = [f"Missed thrust in burn {burn} of plan {plan.name} ({plan.engine.thrust_N:g} N / "
             f"{plan.engine.isp_s:g} s, {plan.dynamics} dynamics): the engine stops after a "
             f"fraction of the burn, the fault lasts the delay, the rest of the capture is "
             f"re-optimised to the same final orbit; penalty = partial + recovery delta-V "
             f"minus the nominal burns {burn}..{plan.n_burns}",
             f"{'fraction':>8} {'delay min':>9} | {'orbit at cut-off':<16} {'e':>6} "
             f"{'apolune km':>10} | {'recovery m/s':>12} {'penalty m/s':>11} "
             f"{'final orbit h':>13} | status"]
    for r in rows:
        ra = r["cutoff_ra_km"]
        ra_txt = f"{ra:10.0f}" if isinstance(ra, float) and math.isfinite(ra) else f"{'inf':>10}"
        ok = r["status"] == "recovered"
        lines.append(
            f"{r['fraction']:8.3g} {r['delay_min']:9.4g} | {str(r['cutoff_orbit']):<16} "
            f"{r['cutoff_e']:6.3f} {ra_txt} | "
            + (f"{r['recovery_delta_v_mps']:12.3f} {r['penalty_mps']:11.3f} "
               f"{r['time_to_final_orbit_h']:13.2f} | recovered" if ok else
               f"{'—':>12} {'—':>11} {'—':>13} | {r['status']}: {r['reason'] or r['error']}"))
    if rows:
        r0 = rows[0]
        lines.append(f"nominal: burns {burn}..{plan.n_burns} need "
                     f"{r0['nominal_remaining_delta_v_mps']:.3f} m/s; burn {burn} lasts "
                     f"{r0['nominal_burn_duration_min']:.2f} min; final orbit "
                     f"{r0['nominal_time_to_final_orbit_h']:.2f} h after the perilune "
                     f"before burn {burn}")
    run = result.run
    lines.append(f"{run['computed']} case(s) computed, {run['reused']} taken from the table; "
                 f"wall time {run['wall_s']:.1f} s ({run['scheduler']}, {run['workers']} "
                 f"worker(s), cache: {run['cache']})")
    lines.append(f"table: {result.path}")
    return "\n".join(lines)
