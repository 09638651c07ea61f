"""Dispersions: the capture's delta-V budget under execution and navigation errors.

A Monte Carlo of the whole capture, corrected in closed loop. In one **sample**:

1. **Arrival.** The arrival perilune state is dispersed: its B-plane target (B.R, B.T
   and the time of closest approach, from a 2x2 or 3x3 covariance, on the osculating
   hyperbola of the nominal arrival perilune: :mod:`lunarcap.physics.bplane`), and/or a
   position and velocity error in the arrival frame (RTN at the arrival perilune:
   radial, transverse, normal), isotropic (``arrival_sigma_km``, ``arrival_sigma_mps``
   per axis) or from a 6x6 covariance (km, km/s). Burn 1 is not re-planned for it: it
   is the trajectory delivered, flown open loop.
2. **Burn 1** is flown open loop: the nominal optimal steering (the collocated polynomial
   of each mesh interval, :func:`lunarcap.optim.flight.interval_steering`), re-propagated
   from the dispersed state with the burn's own errors: thrust scaled by (1 + dT), Isp by
   (1 + dIsp), the thrust direction tilted by a fixed random rotation in the local RTN
   frame (two angles perpendicular to the burn's mean direction, each of standard
   deviation ``pointing_sigma_deg``), and the ignition late or early by ``dt_ign`` (the
   steering follows the time since ignition); and the Gates errors (proportional and
   fixed magnitude and pointing, :func:`lunarcap.studies.dispersions.model.gates_errors`).
   The engine is cut off on the timer: the burn lasts its planned duration, so a weak
   engine delivers less delta-V.
3. **Correction.** The orbit reached is classified (open, or an apolune beyond the Moon's
   sphere of influence: *not captured*); the spacecraft coasts to its actual next
   perilune (found by Newton on r.v in the plan's dynamics), and the next burn is
   re-planned to the plan's target from the orbit-determination **estimate** of that
   state (the true state plus a knowledge error in its RTN frame, per axis or from a
   6x6 covariance; :func:`lunarcap.studies.dispersions.model.knowledge_error`):
   :meth:`CapturePlan.resumed`, then the burn's optimal-control problem, verified by
   re-propagation, warm-started from the nominal burn's steering. The burn is flown from
   the **true** state: the next coast shows the difference, and the final orbit keeps
   it. The paper's formulation keeps the plan's timeline (each coast ends at the plan's
   nominal perilune); the orbit formulation targets the orbit asked.
   A burn of fixed ignition offset ignites at that offset from the perilune actually
   reached; a free one within its nominal window. The re-planned burn is flown with its
   own errors, and so on. Burns are solved one at a time, as the plan is (each burn's
   optimum depends on its own state only, so re-solving the later burns at every step
   would be discarded work).
4. **Final orbit and trim.** After the last burn, the coast to the plan's end is flown
   and the final orbit compared with the target (perilune and apolune radius,
   inclination: the target's own error functions,
   :meth:`lunarcap.mission.targets.Target.errors`): the errors *before* the trim. Then
   the **trim** returns it to the plan's final orbit: two impulses of least total
   delta-V placed within two revolutions, corrected in the plan's dynamics until the
   trimmed orbit passes the verification gate on the re-flown state
   (:mod:`lunarcap.studies.dispersions.trim`, where the choice of impulses over a
   re-planned finite burn is argued). Its delta-V is counted in the sample's total and
   its propellant in the propellant, so a sample that delivered less than planned does
   not count as cheaper than the nominal by what it left undone; an orbit already
   within the gate needs none (a trim of exactly 0).

**Not modelled**: errors of the dynamics (gravity field, ephemeris, solar pressure), an
attitude that wanders during a burn, correlations between burns or error sources, the
estimate's error in mass, thrust or Isp, a knowledge error before burn 1 (its
re-plan), and the execution and knowledge errors of the trim itself (a 1 % error of a
5 m/s trim is 5 cm/s).

A sample that cannot be corrected (the re-plan has no verified solution, a re-plan that
the plan's rules refuse, a trim that does not reach the gate) or that is not captured is
a row with the reason in physical terms, counted in the failure probability; it is never
dropped.

**Common random numbers.** Sample ``k`` of seed ``s`` draws a fixed block of
:data:`BLOCK` standard normals from ``numpy.random.default_rng([s, k])`` (PCG64, seeded
by the pair), then scales them by the sigmas: the same seed gives the same numbers for
any sigmas (doubling a sigma doubles every error), locally and on a cluster, whatever the
order samples run in. ``antithetic`` pairs sample 2j+1 with the negated numbers of 2j.

The **budget** is what the tanks must hold: the delta-V flown (the quadrature of T/m
along every re-propagated burn, plus the trim's impulses) and the propellant used,
summarised by percentiles and a distribution-free confidence interval on the 99 %
quantile from order statistics (:func:`quantile_ci`); the burns alone
(``burns_delta_v_mps``) and the trim (``trim_delta_v_mps``) are kept apart in the table.

The error model and the draws are in :mod:`lunarcap.studies.dispersions.model`, the answer
from a table in :mod:`lunarcap.studies.dispersions.summary`; their public names are imported
here, so ``dispersions.ErrorModel`` or ``dispersions.summarise`` keep working.
"""

from __future__ import annotations

import json
import math
import time

import numpy as np

from lunarcap.errors import InputError, SolveError, integer
from lunarcap.mission.plan import CapturePlan, PlanError
from lunarcap.optim.flight import (
    BurnPlan,
    ExecutionErrors,
    Flown,
    coast,
    coast_to_perilune,
    flown_guess,
    fly,
)
from lunarcap.optim.problem import burn_problem
from lunarcap.optim.solve import solve_burn_problem
from lunarcap.physics import constants as C
from lunarcap.physics.bplane import bplane_from_rv, perilune_from_bplane
from lunarcap.physics.elements import (
    mean_motion_and_anomaly,
    mee_from_rv,
    orbit_summary,
    rv_from_mee,
)
from lunarcap.physics.state import State
from lunarcap.repro.cache import enabled, position
from lunarcap.studies.campaign import TableFormat
from lunarcap.studies.dispersions.model import (  # noqa: F401
    BLOCK,
    MAX_BURNS,
    PER_BURN,
    SIGMAS,
    ErrorModel,
    arrival_factor,
    bplane_error,
    covariance_factor,
    draws,
    gates_errors,
    knowledge_error,
    read_covariance,
    realise,
    sample_draws,
)
from lunarcap.studies.dispersions.summary import (  # noqa: F401
    PERCENTILES,
    convergence,
    format_summary,
    quantile_ci,
    samples_needed,
    settled_after,
    summarise,
)
from lunarcap.studies.dispersions.trim import TrimFailed, trim_orbit
from lunarcap.studies.study import Study, check_workers, json_list, plan_columns

#: Mean Earth-Moon distance, km (IAU 2009 / JPL: 384,400 km), for the Moon's sphere of
#: influence (Laplace's radius a (m_Moon/m_Earth)^(2/5) = 66,200 km).
EARTH_MOON_KM = 384400.0
SOI_RADIUS_KM = EARTH_MOON_KM * (C.MU_MOON / C.MU_EARTH) ** 0.4

#: Share of a revolution by which the nominal steering's coast may miss the plan's perilune
#: epoch before a re-plan starts from the burn timed to it (:func:`replan_guesses`).
TIMING_MISS_REV = 0.05
#: Whether a re-plan starts IPOPT from the nominal's multipliers too (:func:`_replan`).
WARM_MULTIPLIERS = True
#: IPOPT statuses meaning "no solution within the bounds".
INFEASIBLE = ("Infeasible_Problem_Detected", "Restoration_Failed")

STATUSES = ("ok", "not captured", "correction failed", "error")
#: Statuses of a sample computed as it should be (the failures are physical outcomes).
OK_STATUSES = ("ok", "not captured", "correction failed")


#: The study's modules, relative to the package: its tables' and cached cases' code
#: version is :func:`lunarcap.repro.cache.code_version` of the numerical code and these.
_MODULES = ("studies/dispersions/samples.py", "studies/dispersions/model.py",
            "studies/dispersions/summary.py", "studies/dispersions/trim.py")


# ====================================================================== the orbit reached
def orbit_check(x) -> str:
    """'' if the orbit of state ``x`` is captured, else why not (physical terms)."""
    o = orbit_summary(np.asarray(x, float), C.MU_MOON)
    energy = o["v_kmps"] ** 2 / 2 - C.MU_MOON / o["r_km"]
    if energy >= 0:
        return f"the orbit is open (e = {o['e']:.3f}): the spacecraft escapes the Moon"
    if o["ra_km"] > SOI_RADIUS_KM:
        return (f"apolune {o['ra_km']:.0f} km lies beyond the Moon's sphere of influence "
                f"({SOI_RADIUS_KM:.0f} km)")
    if o["rp_km"] < C.R_MOON:
        return (f"perilune {o['rp_km'] - C.R_MOON:.0f} km below the surface: the spacecraft "
                "would hit the Moon")
    return ""


# ====================================================================== nominal
_NOMINAL: dict = {}


def nominal(plan: CapturePlan) -> list:
    """The plan's verified burns (solved in order, :func:`lunarcap.capture.chain.solve_plan`).

    Memoised per process and cache switch position (a worker solves or loads it once for
    all its samples).
    """
    from lunarcap.capture.chain import solve_plan

    key = (plan.key(), enabled())
    if key not in _NOMINAL:
        _NOMINAL[key] = solve_plan(plan)
    return _NOMINAL[key]


def nominal_totals(plan: CapturePlan) -> dict:
    """Nominal delta-V (m/s), propellant (kg) and the two-body impulsive delta-V (m/s)."""
    sols = nominal(plan)
    return {"nominal_delta_v_mps": float(sum(s.delta_v_mps for s in sols)),
            "nominal_propellant_kg": float(plan.initial_mass_kg - sols[-1].end_state[6]),
            "impulsive_delta_v_two_body_mps": float(sum(b.delta_v_mps for b in plan.impulsive()))}


# ====================================================================== one sample
def displaced(x, d) -> np.ndarray:
    """The state ``x`` (7,) moved by ``d`` (6,: km, km/s) in its own RTN frame.

    ``x`` itself (the same array) when ``d`` is zero; the true longitude keeps ``x``'s
    revolution.
    """
    if not np.any(d):
        return x
    r, v = (np.array(a, float) for a in rv_from_mee(*x[:6], C.MU_MOON))
    ir = r / np.linalg.norm(r)
    i_n = np.cross(r, v)
    i_n /= np.linalg.norm(i_n)
    Q = np.column_stack([ir, np.cross(i_n, ir), i_n])   # RTN axes (Song 2011 Eq. A5)
    mee = mee_from_rv(r + Q @ d[:3], v + Q @ d[3:6], C.MU_MOON)
    out = np.array([*np.asarray(mee, float).ravel()[:6], x[6]])
    out[5] = x[5] + math.remainder(out[5] - x[5], 2 * math.pi)
    return out


def _arrival_state(plan: CapturePlan, d_arr, d_bplane=None) -> tuple:
    """(epoch, state) of the arrival perilune, dispersed (see :func:`fly_sample`).

    ``d_bplane`` (3,): B.R (km), B.T (km) and the time of closest approach (s) moved on
    the osculating hyperbola of the nominal arrival perilune (B-plane axes about the
    M-MME2000 pole, asymptote and v_inf kept), the state taken at the nominal epoch (a
    perilune ``dt`` later is ``dt`` before it there, flown in the burn's dynamics); then
    ``d_arr`` (6,: RTN, km and km/s) added.
    """
    from lunarcap.capture.chain import perilune_epoch_state

    t0, x0 = perilune_epoch_state(plan, 0)
    x = np.array(x0, float)
    if d_bplane is not None and np.any(d_bplane):
        r, v = (np.array(a, float) for a in rv_from_mee(*x[:6], C.MU_MOON))
        b = bplane_from_rv(r, v, C.MU_MOON)
        r1, v1 = perilune_from_bplane(b.b_r_km + d_bplane[0], b.b_t_km + d_bplane[1],
                                      b.v_inf_kmps, b.s_hat, C.MU_MOON)
        x1 = np.array([*np.asarray(mee_from_rv(r1, v1, C.MU_MOON), float).ravel()[:6], x[6]])
        x1[5] = x[5] + math.remainder(x1[5] - x[5], 2 * math.pi)
        if d_bplane[2]:
            x1 = coast(nominal(plan)[0].problem.model, State(t0 + float(d_bplane[2]), x1),
                       t0).end.x
        x = x1
    return t0, displaced(x, d_arr)


def _replan(plan: CapturePlan, i: int, t_p: float, x_p, nom) -> object:
    """Burn ``i`` (0-based) re-planned from the perilune reached (t_p, x_p): a Solution.

    Each guess of :func:`replan_guesses` is solved with IPOPT warm-started from the
    nominal burn's multipliers as well (:data:`WARM_MULTIPLIERS`; on the mesh where the
    nominal solved the same NLP): the re-plan is a small perturbation of the nominal, so
    its constraints' multipliers are nearly the nominal's. Measured on 10-12 samples of
    each paper engine (full dynamics, the book's sigmas): 13-15 IPOPT iterations per
    re-plan -> 3.6-3.8, the same optima (total delta-V within 3e-9 m/s).
    """
    b = plan.burns[i]
    if plan.formulation == "song2011":
        first_coast = None   # the plan's timeline: the coast ends at its nominal perilune
        left = plan.nominal_perilunes_s[i + 1] - t_p
        if left < 0.5 * plan.coast_s(i):
            raise Uncorrectable(
                f"the perilune before burn {i + 1} is reached "
                f"{(t_p - plan.nominal_perilunes_s[i]) / 60:+.1f} min off the plan's, leaving "
                f"{left / 60:.1f} min to the epoch where the plan's next orbit must hold "
                f"(less than half its {plan.coast_s(i) / 60:.1f} min period)")
    else:
        first_coast = plan.coast_s(i)   # the orbit asked, one period (or the circle's coast)
    window = nom.problem.start_bounds_min if b.free_start else (b.start_min, b.start_min)
    try:
        rp = plan.resumed(i, t_p, x_p, first_coast_s=first_coast, window_min=window)
        if not b.free_start:
            rp = rp.with_start(0, b.start_min)
    except PlanError as exc:
        why = str(exc)
        if "too weak" in why:
            why = "the engine is too weak for the orbit reached: " + why.split(": ", 2)[-1]
        raise Uncorrectable(f"the plan's rules refuse a re-plan from the orbit reached ({why})"
                            ) from None
    prob = burn_problem(rp, 0, x_p, rp.ephemeris_model())
    first = None
    for guess in replan_guesses(nom.raw, prob):
        # IPOPT starts from the nominal's multipliers too (same NLP: see same_nlp)
        warm = nom.raw if WARM_MULTIPLIERS else None
        try:
            return solve_burn_problem(prob, guess=guess, multipliers=warm)
        except SolveError as exc:
            first = first or exc
    raise first


def replan_guesses(nominal_raw, prob) -> list:
    """The guesses a re-plan tries in turn: the nominal steering, or the timed burn first.

    The nominal burn's steering (:func:`lunarcap.optim.flight.flown_guess`) is the natural
    start, except when the plan's timeline makes it the wrong one: with the paper's target
    (a perilune at the plan's fixed epoch) a burn error of a few m/s moves the perilune
    reached by tens of minutes, and the next orbit must then have another period to bring
    its perilune back onto the plan's epoch. The nominal steering's coast then misses that
    epoch by more than :data:`TIMING_MISS_REV` of a revolution, and IPOPT started from it
    stalls or ends on a costlier branch (one more revolution in a smaller orbit); the
    anti-velocity burn whose duration is tuned to reach perilune at the epoch (``None``: the
    solver's own :func:`lunarcap.optim.guess.make_guess`) goes first. The other guess is the
    fallback.
    """
    warm = flown_guess(nominal_raw, prob)
    if prob.free_end or prob.circular:
        return [warm, None]
    _, mean_anomaly = mean_motion_and_anomaly(warm.coast.x[:, -1], C.MU_MOON)
    if abs(float(mean_anomaly)) > 2 * math.pi * TIMING_MISS_REV:
        return [None, warm]
    return [warm, None]


class Uncorrectable(Exception):
    """A re-plan that the plan's rules or timeline cannot accept (its message says why)."""


def _fail(out: dict, status: str, reason: str) -> dict:
    out.update(status=status, reason=reason)
    out["sample_wall_s"] = time.perf_counter() - out.pop("_t0")
    out["sample_cpu_s"] = time.process_time() - out.pop("_c0")
    return out


def _corrected(plan: CapturePlan, i: int, t_ref: float, x_ref, nom) -> tuple:
    """(Solution, "") of burn ``i`` re-planned from (t_ref, x_ref), or (None, why not)."""
    try:
        return _replan(plan, i, t_ref, x_ref, nom), ""
    except SolveError as exc:
        status = getattr(exc, "status", "") or "no status"
        what = ("no burn meets the target from the orbit reached"
                if status in INFEASIBLE else "no verified solution")
        return None, (f"burn {i + 1} cannot be re-planned: {what} (IPOPT {status} on the "
                      f"last of {len(exc.details.get('attempts', [])) or 'its'} meshes)")
    except Uncorrectable as exc:
        return None, f"burn {i + 1} cannot be re-planned: {exc}"
    except InputError as exc:
        return None, f"burn {i + 1} cannot be re-planned from the orbit reached: {exc}"
    except RuntimeError as exc:   # a guess propagation that fails (p -> 0)
        return None, (f"burn {i + 1}: no trajectory to start the re-plan from ({exc})"
                      .split("\n")[0])


def _burn_record(i: int, sol, flown: Flown, e: ExecutionErrors, t_ref: float,
                 d_know) -> dict:
    """One flown burn of a sample, as stored in its row's ``burns_json``.

    The knowledge error (the estimate less the truth of the state the burn was
    re-planned from, km and m/s) is written only when it is not zero, so a sample without
    knowledge errors keeps its record as it was.
    """
    rec = {"burn": i + 1, "delta_v_mps": flown.delta_v_mps,
           "planned_delta_v_mps": sol.delta_v_mps,
           "ignition_min": (flown.start.t_s - t_ref) / 60.0,
           "duration_min": sol.raw.t1_s / 60.0,
           "thrust_error_pct": 100 * (e.thrust_factor - 1),
           "isp_error_pct": 100 * (e.isp_factor - 1),
           "pointing_error_deg": math.degrees(math.hypot(*e.tilt_rad)),
           "ignition_error_s": e.ignition_s}
    if np.any(d_know):
        rec["knowledge_dr_km"] = float(np.linalg.norm(d_know[:3]))
        rec["knowledge_dv_mps"] = float(np.linalg.norm(d_know[3:6])) * 1e3
    return rec


def _final_orbit(sol, flown: Flown) -> tuple:
    """(errors, state): the final orbit at the end of the plan's last coast, before a trim."""
    end = coast(sol.problem.model, flown.end, sol.problem.t_end_s).end
    err = sol.problem.target.errors(end.mee)
    o = orbit_summary(end.x, C.MU_MOON)
    return {"final_rp_error_km": err["rp_error_m"] / 1e3,
            "final_ra_error_km": (err["ra_error_m"] / 1e3 if err["ra_error_m"] is not None
                                  else math.nan),
            "final_inc_error_deg": err["inc_error_deg"],
            "final_rp_altitude_km": o["rp_km"] - C.R_MOON,
            "final_ra_altitude_km": o["ra_km"] - C.R_MOON}, end


# ====================================================================== the trim
_TRIM_MODELS: dict = {}


def trim_model(plan: CapturePlan):
    """(model, reference): the plan's coast dynamics for a trim and its final orbit.

    ``model``: the plan's forces with an ephemeris fit from 6 h before the nominal's end
    to 6 h after four final-orbit periods (a trim and its check lie within two);
    ``reference(t_s)``: (t_c, state): the nominal's final state flown on to the first
    whole number of final-orbit periods after its end at or after ``t_s``
    (:mod:`lunarcap.studies.dispersions.trim`). Memoised per process and plan.
    """
    from lunarcap.physics.dynamics import Model, fit_for

    key = (plan.key(), enabled())
    if key not in _TRIM_MODELS:
        last = nominal(plan)[-1]
        t_end, x_end = last.problem.t_end_s, np.asarray(last.end_state, float)
        period = plan.coast_s(plan.n_burns - 1)
        fit = fit_for(plan.dynamics, plan.ephemeris_model(), t_end - 6 * 3600.0,
                      t_end + 4 * period + 6 * 3600.0)
        model = Model(plan.dynamics, 0.0, plan.engine.isp_s, fit)
        flown: dict = {}

        def reference(t_s: float) -> tuple:
            n = max(0, math.ceil((t_s - t_end) / period - 1e-9))
            if n not in flown:
                t_c = t_end + n * period
                flown[n] = (t_c, coast(model, State(t_end, x_end), t_c).end.x if n else x_end)
            return flown[n]

        _TRIM_MODELS[key] = (model, reference)
    return _TRIM_MODELS[key]


def _trimmed(plan: CapturePlan, sol, end: State) -> dict:
    """The trim's columns of a sample whose final orbit at the plan's end is ``end``.

    ``trimmed_*``: the trimmed orbit against the plan's final orbit at the trim's check
    epoch (no trim needed: the orbit as reached against the plan's target). TrimFailed
    (its message the residuals) if the trim does not pass the gate.
    """
    model, reference = trim_model(plan)
    tr = trim_orbit(model, sol.problem.target, end.t_s, end.x, reference, plan.engine.isp_s)
    ra = tr.errors["ra_error_m"]
    return {"trim_delta_v_mps": tr.delta_v_mps, "trim_propellant_kg": tr.propellant_kg,
            "trim_json": json.dumps(tr.record(end.t_s)),
            "trimmed_rp_error_m": tr.errors["rp_error_m"],
            "trimmed_ra_error_m": math.nan if ra is None else ra,
            "trimmed_inc_error_deg": tr.errors["inc_error_deg"]}


def fly_sample(plan: CapturePlan, z, model: ErrorModel) -> dict:
    """One sample of the capture with the errors of the draws ``z`` (see the module).

    Returns a dict: status ("ok", "not captured", "correction failed"), reason, the total
    delta-V flown (m/s) and propellant (kg), per-burn delta-Vs and errors, the final
    orbit's errors, its wall and CPU time (s; the nominal, solved or loaded once per
    process, is left out).
    """
    noms = nominal(plan)
    t_start, c_start = time.perf_counter(), time.process_time()
    d_arr, errs = realise(z, model, plan.n_burns)
    d_b = bplane_error(z, model, plan)
    out = {"status": "ok", "reason": "", "burns_flown": 0, "_t0": t_start, "_c0": c_start,
           "arrival_dr_km": float(np.linalg.norm(d_arr[:3])),
           "arrival_dv_mps": float(np.linalg.norm(d_arr[3:6])) * 1e3,
           "arrival_db_km": float(np.hypot(d_b[0], d_b[1])), "arrival_dt_s": float(d_b[2])}
    burns = []
    t_ref, x_ref = _arrival_state(plan, d_arr, d_b)
    sol = noms[0]
    for i in range(plan.n_burns):
        d_know = np.zeros(6)
        if i > 0:   # re-planned from the estimate of the true state (t_ref, x_ref)
            d_know = knowledge_error(z, model, i)
            sol, why = _corrected(plan, i, t_ref, displaced(x_ref, d_know), noms[i])
            if sol is None:
                out["burns_json"] = json.dumps(burns)
                return _fail(out, "correction failed", why)
        try:
            e = gates_errors(z, model, i, sol.delta_v_mps, errs[i],
                             plan.engine.exhaust_speed_mps)
        except InputError as exc:
            out["burns_json"] = json.dumps(burns)
            return _fail(out, "not captured", f"burn {i + 1} is not flown: {exc}")
        flown = fly(BurnPlan.of(sol.raw).with_errors(e), State(t_ref, x_ref))   # the truth
        burns.append(_burn_record(i, sol, flown, e, t_ref, d_know))
        out["burns_flown"] = i + 1
        out["propellant_kg"] = float(plan.initial_mass_kg - flown.end.mass_kg)
        out["total_delta_v_mps"] = float(sum(b["delta_v_mps"] for b in burns))
        out["burns_delta_v_mps"] = out["total_delta_v_mps"]
        out["burns_json"] = json.dumps(burns)
        why = orbit_check(flown.end.x)
        if why:
            return _fail(out, "not captured", f"after burn {i + 1}, {why}")
        if i < plan.n_burns - 1:
            try:
                peri = coast_to_perilune(sol.problem.model, flown.end,
                                         sol.problem.t_end_s + e.ignition_s)
                t_ref, x_ref = peri.t_s, peri.x
            except InputError as exc:   # beyond the burn's ephemeris fit (+-6 h)
                return _fail(out, "correction failed",
                             f"the perilune after burn {i + 1} is not found within 6 h of the "
                             f"plan's ({exc})")
        else:   # the final orbit, at the end of the plan's last coast, and its trim
            errors, end = _final_orbit(sol, flown)
            out.update(errors)
            try:
                out.update(_trimmed(plan, sol, end))
            except TrimFailed as exc:
                return _fail(out, "correction failed", f"after burn {i + 1}, {exc}")
            out["total_delta_v_mps"] += out["trim_delta_v_mps"]
            out["propellant_kg"] += out["trim_propellant_kg"]
    out["sample_wall_s"] = time.perf_counter() - out.pop("_t0")
    out["sample_cpu_s"] = time.process_time() - out.pop("_c0")
    return out


# ====================================================================== the study on Dask
COLUMNS = ("plan", "plan_id", "thrust_N", "isp_s", "dynamics", "seed", "sample",
           "antithetic", "thrust_sigma_pct", "isp_sigma_pct", "pointing_sigma_deg",
           "ignition_sigma_s", "arrival_sigma_km", "arrival_sigma_mps", "arrival_cov",
           "status", "reason", "burns_flown", "total_delta_v_mps", "propellant_kg",
           "nominal_delta_v_mps", "nominal_propellant_kg", "delta_v_above_nominal_mps",
           "final_rp_error_km", "final_ra_error_km", "final_inc_error_deg",
           "final_rp_altitude_km", "final_ra_altitude_km", "arrival_dr_km", "arrival_dv_mps",
           "burns_json", "task_wall_s", "task_cpu_s", "worker", "code_version",
           "completed_utc", "error",
           "knowledge_sigma_km", "knowledge_sigma_mps", "knowledge_cov",
           "gates_magnitude_pct", "gates_magnitude_mps", "gates_pointing_deg",
           "gates_pointing_mps", "bplane_cov", "arrival_db_km", "arrival_dt_s",
           "burns_delta_v_mps", "trim_delta_v_mps", "trim_propellant_kg",
           "trimmed_rp_error_m", "trimmed_ra_error_m", "trimmed_inc_error_deg", "trim_json")
KEY = ("plan_id", "seed", "sample", "antithetic", "thrust_sigma_pct", "isp_sigma_pct",
       "pointing_sigma_deg", "ignition_sigma_s", "arrival_sigma_km", "arrival_sigma_mps",
       "arrival_cov", "knowledge_sigma_km", "knowledge_sigma_mps", "knowledge_cov",
       "gates_magnitude_pct", "gates_magnitude_mps", "gates_pointing_deg",
       "gates_pointing_mps", "bplane_cov")


def sample_row(plan: CapturePlan, seed: int, index: int, model: ErrorModel,
               antithetic: bool = False) -> dict:
    """Dask task: one sample as a row of the table (a failure is a status, not raised)."""
    r = fly_sample(plan, sample_draws(seed, index, antithetic), model)
    r.update(nominal_totals(plan))
    if "total_delta_v_mps" in r:
        r["delta_v_above_nominal_mps"] = r["total_delta_v_mps"] - r["nominal_delta_v_mps"]
    row = {k: v for k, v in r.items() if k in COLUMNS}
    row["task_wall_s"] = r.get("sample_wall_s")
    row["task_cpu_s"] = r.get("sample_cpu_s")
    row["error"] = ""
    return row


def check_samples(samples, seed) -> tuple:
    """(samples, seed) as integers (samples >= 1, seed >= 0), else InputError."""
    return integer("--samples", samples, 1), integer("--seed", seed, 0)


def run_dispersions(plan: CapturePlan, samples: int, seed: int, model: ErrorModel,
                    out=None, workers=2, scheduler=None, progress: bool = True,
                    use_cache: bool | None = None, processes: bool = True,
                    antithetic: bool = False,
                    first: int = 0, task=None):
    """Run (or resume) ``samples`` samples (indices ``first``...) of the capture on Dask.

    ``plan`` may be a list of plans, ``model`` a list of error models (a sensitivity,
    :mod:`lunarcap.studies.dispersions.sensitivity`): their samples run as one campaign (one
    cluster), plan by plan, model by model.
    Returns a :class:`lunarcap.studies.campaign.CampaignResult` (one row per sample, in
    index order, plan by plan). InputError (a bad count, seed or sigma, a plan with more than
    :data:`MAX_BURNS` burns, an unusable ``out``, an unreachable scheduler) before any
    sample.
    """
    use_cache = position(use_cache)   # None: the switch's current position
    samples, seed = check_samples(samples, seed)
    plans = list(plan) if isinstance(plan, (list, tuple)) else [plan]
    models = list(model) if isinstance(model, (list, tuple)) else [model]
    for p, model in ((p, m) for p in plans for m in models):
        if p.n_burns > MAX_BURNS:
            raise InputError(f"plan {p.name} has {p.n_burns} burns; the dispersions study "
                             f"draws errors for at most {MAX_BURNS}")
        for name in ("pointing_sigma_deg", "gates_pointing_deg", "gates_pointing_mps"):
            if getattr(model, name) and any(b.steering != "optimal" for b in p.burns):
                raise InputError(f"--{name.replace('_', '-')} needs every burn's steering "
                                 f"optimal (a polynomial per mesh interval to tilt)")
    workers = check_workers(workers)
    cases = []
    for p, model in ((p, m) for p in plans for m in models):   # one campaign: one cluster,
        base = {**plan_columns(p), "seed": seed, "antithetic": bool(antithetic),
                **model.key()}   # whose workers build each NLP shape once
        cases += [(dict(base, sample=k), (p, seed, k, model, bool(antithetic)))
                  for k in range(int(first), int(first) + samples)]
    return STUDY.run(cases, out, task=task, workers=workers, scheduler=scheduler,
                     progress=progress, processes=processes, use_cache=use_cache,
                     describe={"study": "dispersions", "seed": seed, "samples": samples,
                               "error_model": "; ".join(m.describe() for m in models)})


def format_report(result, plan: CapturePlan, model: ErrorModel) -> str:
    """The study's text: the error model, the budget, failures, final orbit, the run."""
    return "\n".join([format_summary(plan, model, summarise(result.table.to_dict("records"))),
                      *STUDY.run_lines(result)])


#: The study, declared once (:class:`lunarcap.studies.study.Study`).
STUDY = Study(
    "dispersions", TableFormat(KEY, COLUMNS, text_columns=(
        "plan", "plan_id", "dynamics", "reason", "arrival_cov", "knowledge_cov", "bplane_cov",
        "burns_json", "trim_json"), name="dispersions table"),
    sample_row, STATUSES, OK_STATUSES, "sample", "dispersions", _MODULES,
    decoders=(("burns_json", "burns", json_list), ("trim_json", "trim", json_list)),
    rows_key="samples", text=format_report)
