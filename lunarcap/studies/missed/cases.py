"""Missed thrust and late ignition: a capture burn goes wrong; the rest of the capture, re-planned.

Two contingencies of burn n of a plan (``contingency`` in the table):

* **cut-off** (fraction f, delay d): burn n is flown as planned (its optimal steering,
  re-propagated from its ignition state, :func:`lunarcap.optim.flight.cut_off`)
  and the engine stops after ``f`` of its duration; the spacecraft coasts for ``d`` (the
  fault being cleared).
* **late ignition** (``late_min`` L, as studied for KPLO's LOI burns by Bae et al. 2017,
  JASS 34(4)): burn n ignites L minutes after its planned ignition; nothing of it has been
  flown before.

The **nominal** is the plan's all-burns optimum (:func:`lunarcap.optim.joint.solve_joint`)
with every ignition free and the orbit after burn n free (its coast a decision variable)
up to the same longest period ``max_period_h`` the recovery has, whatever the plan's
formulation (:func:`freed`: an ellipse asked by period or apolune becomes the Eq. 17
target at a free coast, as the paper's formulation already is): the same freedoms, so a
penalty measures the contingency and not a difference of bounds. It is solved from the
plan's own orbit and from the longest allowed, and the cheaper verified optimum kept. The
last burn's orbit is the final one (a circle or an ellipse as asked): nothing to free.

**Recovery** (:mod:`lunarcap.studies.missed.recovery`, one function for both
contingencies): from the state at the end of the delay (cut-off) or at the late ignition,
either nothing to make up (the orbit left, coasting, meets burn n's target within the
verification gate: no make-up burn is flown, the recovery is the nominal's later burns;
a cut-off at the planned end, f = 1), or a make-up burn with burn n's target, igniting
within ``window_min`` after that epoch (late ignition: exactly then), whose orbit is free
up to ``max_period_h`` (osculating period at its perilune, where its target holds;
default :data:`DEFAULT_MAX_PERIOD_H`; the last burn's: the final orbit), then burns n+1,
... with the nominal's periods and free ignitions, to the same final orbit, re-optimised
as one NLP (total delta-V) and verified leg by leg. A cut-off whose window gives no
verified recovery is re-planned with the make-up at the next perilune (the final orbit
passes only through radii between its perilune and apolune: after a cut-off of the last
burn and a delay the spacecraft is above them until it comes back); a make-up whose
penalty in the window exceeds the nominal burn's own delta-V is tried there too, and the
cheaper kept (family-4 of the seed-24 family, 201 N, full dynamics, a quarter of the last
burn and 30 min: +828.7 m/s in the window, +0.36 m/s at the next perilune, 6.6 h later).
That row's ``reason`` says so, and its penalty may be negative (the nominal flies each
burn in one piece, and a burn completed one orbit later loses less).

Before any solve, a recovery that physics forbids is answered as **no recovery**, with
the reason (:func:`physical_bound`, for every kind of target): the spacecraft has left
the Moon's sphere of influence when the window opens, or every orbit through its position
with the target's perilune radius is longer than ``max_period_h`` (an orbit through
radius r with perilune radius rp has a semi-major axis of at least (r + rp) / 2).

The **penalty** is measured on one basis: the delta-V from the state before burn n to the
final orbit, finite burns, same dynamics: (delta-V of the partial burn + the
recovery's) minus (the nominal burns n, n+1, ...). Statuses: "recovered" (verified),
"no recovery" (the physical bound above, or a re-plan the plan's own checks refuse, with
their message), "failed" (any solver failure, with IPOPT's status: a solver's verdict is
not a physical reason, so it is never reported as "no recovery").
"""

from __future__ import annotations

import math
import time

import numpy as np

from lunarcap.capture.chain import solve_plan, time_to_final_orbit_h
from lunarcap.errors import InputError, SolveError, number_list
from lunarcap.mission.plan import CapturePlan, PlanError
from lunarcap.mission.targets import PERILUNE
from lunarcap.optim.collocation import DEFAULT_MESHES, sundman_fractions
from lunarcap.optim.flight import cut_off
from lunarcap.optim.joint import solve_joint, warm_start
from lunarcap.physics.dynamics import Model, force_model
from lunarcap.physics.ephemeris import ChebyshevFit
from lunarcap.physics.epochs import calendar_from_seconds
from lunarcap.physics.propagate import propagate
from lunarcap.repro.cache import cached, caching, code_version, position
from lunarcap.studies.burn_count.counts import MAX_FIT_SPAN_S
from lunarcap.studies.campaign import TableFormat
from lunarcap.studies.missed.orbits import (  # noqa: F401  (this module's API too)
    after_free_orbit,
    classify,
    make_up_estimate,
    period_s,
    physical_bound,
    shortest_free_period_s,
    soi_radius_km,
    time_to_perilune_after_impulse_s,
)
from lunarcap.studies.missed.recovery import (  # noqa: F401  (this module's API too)
    MIN_FIRST_COAST_S,
    MIN_MAKE_UP_S,
    nothing_to_make_up,
    on_meshes,
    recover,
    recovery,
)
from lunarcap.studies.study import Study, check_workers, json_list, plan_columns

#: Longest period of the orbit after burn n, in the recovery and in the nominal alike, h.
#: About twice the paper's 12.235 h. For the paper's 150 N plan the nominal's own optimum
#: lies inside it in two-body dynamics (22.6 h: a longer first ellipse shares the capture's
#: delta-V more evenly between burns 1 and 2), and presses against it in full dynamics
#: (coast 23.8 h), as do the recoveries: both sides carry the same bound, so the penalty
#: compares like with like. Its apolune (about 17,700 km at 100 km perilune) stays far
#: inside the Moon's sphere of influence (about 63,000 km). Known limitation: in full
#: dynamics that nominal (935.8 m/s, coast 23.8 h) is a local optimum costlier than the
#: paper's 12.235 h plan (872.6 m/s), which the bound allows (see the README).
DEFAULT_MAX_PERIOD_H = 24.0
#: A penalty below minus this (m/s) is a recovery cheaper than the nominal, and its row says
#: so (:func:`_below_nominal`): beyond the solver's tolerance, as the tests' bound.
BELOW_NOMINAL_MPS = 0.05
#: Window of the make-up burn's ignition after the fault is cleared, min.
DEFAULT_WINDOW_MIN = (0.0, 30.0)
#: The contingencies of a case.
CONTINGENCIES = ("cut-off", "late ignition")

STATUSES = ("recovered", "no recovery", "failed", "error")


#: The study's modules, relative to the package: its tables' and cached cases' code
#: version is :func:`lunarcap.repro.cache.code_version` of the numerical code and these.
_MODULES = ("studies/missed/cases.py", "studies/missed/orbits.py", "studies/missed/recovery.py")


# ---------------------------------------------------------------------- the nominal
def _fit_for(plan: CapturePlan, t0_s: float, span_s: float):
    """One Earth/Sun fit from ``t0_s`` - 1 h over ``span_s`` + 6 h for every leg and coast.

    (Made in every dynamics: a model's epochs are checked against its fit's window.)
    """
    if span_s + 7 * 3600.0 > MAX_FIT_SPAN_S:
        raise InputError(f"the recovery would span {span_s / 3600:.0f} h, more than the 4 "
                         f"days an ephemeris fit covers: shorten the delay or --max-period-h")
    return ChebyshevFit.fit(plan.ephemeris_model(), t0_s - 3600.0, t0_s + span_s + 6 * 3600.0,
                            body_frame=force_model(plan.dynamics).rotation)


def freed(plan: CapturePlan, i: int) -> CapturePlan:
    """The plan with every ignition free and the orbit after burn ``i`` (0-based) free.

    The orbit after an intermediate burn is the paper's perilune target (Eq. 17) at the
    end of a coast the all-burns NLP chooses (:meth:`CapturePlan.with_coasts`), whether
    the plan asks for it by period or apolune (``formulation: orbit``) or by timing
    (``song2011``): the recovery re-plans from that burn with this freedom, so the
    nominal it is measured against has it too. The last burn's target (the final orbit,
    a circle or an ellipse as asked) is kept.
    """
    free_plan = plan.with_starts(["free"] * plan.n_burns)
    if i + 1 < plan.n_burns and free_plan.targets[i].kind != PERILUNE:
        free_plan = free_plan.with_coasts([free_plan.coast_s(i) if k == i else None
                                           for k in range(plan.n_burns)])
    return free_plan


@cached
def nominal(plan: CapturePlan, burn: int = 1, max_period_s: float = DEFAULT_MAX_PERIOD_H *
            3600.0, version: str = "") -> dict:
    """The plan's all-burns optimum, the orbit after ``burn`` free up to ``max_period_s``.

    Pass ``plan.key()``. Every ignition free; burn n's coast (from the perilune before it
    to the one after) a decision variable between the next orbit's coast and
    ``max_period_s`` + 2 h, the osculating period at that perilune at most
    ``max_period_s`` (the recovery's bounds), whatever the plan's formulation
    (:func:`freed`). The last burn (the final orbit) has no orbit to free. Returns
    ``{"plan": CapturePlan (free ignitions, the optimal coasts), "legs": [Solution]}``.
    """
    i = burn - 1
    free_plan = freed(plan, i)
    if free_plan.targets[i].kind != PERILUNE:   # the final orbit: nothing to free
        res = _final_orbit_nominal(free_plan)
        return {"plan": res.plan, "legs": res.legs}
    # from the plan's own orbit and from the longest one allowed: the total depends
    # little on that orbit (two-body: only through the finite burns' losses), and from the
    # plan's alone IPOPT may stop where it started (family-0 of the missed family, seed
    # 24: 813.121 m/s on the plan's 17.3 h orbit, 812.999 m/s on the 24 h bound from 12,
    # 20 or 23.5 h; recoveries found the cheaper one, penalties -0.10 m/s)
    starts, middle = [free_plan], None
    if plan.dynamics == "two-body":   # (a plan the checks refuse is no start)
        starts.append(_coasted(free_plan, i, max_period_s))
    else:
        # also from the two-body optimum's orbit: a long free coast needs its mesh spaced
        # for the orbit it ends on, not for the plan's. The full-dynamics problem has
        # several local optima (from that start alone the 150 N plan's nominal ended on a
        # 23.8 h orbit at 935.8 m/s, 63 m/s above the plan's own 12.235 h orbit, which its
        # bounds allow): every start is solved and the cheapest verified optimum kept,
        # each on every mesh up to the finest (the plan's start passed verification only
        # there: 869.96 m/s, a 23.8 h orbit, gamma off by 2e-4 deg on the coarser ones).
        two = nominal(plan.with_dynamics("two-body"), burn, max_period_s, version)["plan"]
        starts.append(_coasted(free_plan, i, two.coast_s(i)))
        middle = _coasted(free_plan, i, math.sqrt(free_plan.coast_s(i) * two.coast_s(i)))
    found, error = _solved_from([s for s in starts if s is not None], i, max_period_s)
    # And from halfway between the two (geometric mean), where they end on different
    # orbits (or one fails): family-2 of the seed-24 family (141 N, 1,145 kg, four burns)
    # from 10.73 h stopped at 949.64 m/s on a 10.01 h orbit and from 24.0 h failed
    # verification, and 9 of its 20 missed cases were cheaper than that nominal (a 5 min
    # late ignition by 7.64 m/s, on a 16.5 h orbit); from 16.05 h: 942.07 m/s. (The 150 N
    # paper plan's two end on 23.8 h orbits: the middle start, 909.44 m/s, is not solved.)
    periods = [r.plan.coast_s(i) for r in found]
    if middle is not None and (len(periods) < 2 or abs(periods[0] / periods[1] - 1) > 0.01):
        more, error = _solved_from([middle], i, max_period_s, error)
        found += more
    if not found:
        raise error
    best = min(found, key=lambda r: r.total_delta_v_mps)
    return {"plan": best.plan, "legs": best.legs}


def _coasted(free_plan: CapturePlan, i: int, coast_s: float) -> CapturePlan | None:
    """``free_plan`` with the coast after burn ``i`` (0-based) ``coast_s`` (s); None if refused."""
    try:
        return free_plan.with_coasts([coast_s if k == i else None
                                      for k in range(free_plan.n_burns)])
    except PlanError:
        return None


def _solved_from(starts: list, i: int, max_period_s: float, error=None) -> tuple:
    """(the verified :func:`_nominal_from` of each start, the last error or ``error``)."""
    found = []
    for start in starts:
        try:
            found.append(_nominal_from(start, i, max_period_s))
        except (SolveError, PlanError) as exc:
            error = exc
    return found, error


def _final_orbit_nominal(free_plan: CapturePlan):
    """:func:`nominal` of the last burn: the all-burns optimum of the plan's own orbits.

    On each mesh until one passes verification, as every other nominal (family-2 of the
    seed-24 family, 141 N, four burns, full dynamics: on the first mesh alone leg 2 missed
    the flight-path angle by 3.3e-4 deg, and every case of its last burn was an error).
    """
    return _joint_on_meshes(free_plan, solve_plan(free_plan))


def _joint_on_meshes(free_plan: CapturePlan, seq: list, widen=None, **bounds):
    """The all-burns NLP of ``free_plan`` from the chain ``seq``, mesh after mesh.

    Each mesh of :data:`~lunarcap.optim.collocation.DEFAULT_MESHES` until one passes
    verification. ``widen(warm, k)``: leg ``k``'s warm start as the NLP should have it (default as
    solved); ``bounds``: :func:`~lunarcap.optim.joint.solve_joint`'s free coasts and bounds.
    """
    eph = free_plan.ephemeris_model()
    return on_meshes(meshes=DEFAULT_MESHES, solve=lambda mesh: solve_joint(
        free_plan, None, eph, mesh, **bounds,
        warm=[_remeshed(warm_start(s) if widen is None else widen(warm_start(s), k),
                        s.flight.coast, mesh) for k, s in enumerate(seq)]))


def _nominal_from(free_plan: CapturePlan, i: int, max_period_s: float):
    """:func:`nominal`'s all-burns optimum from one warm start (the plan's coasts)."""
    seq = solve_plan(free_plan)
    flags = tuple(k == i for k in range(free_plan.n_burns))
    hi = max_period_s + 7200.0
    t = free_plan.nominal_perilunes_s
    span = (t[-1] - t[0]) - free_plan.coast_s(i) + hi
    lo = free_plan.coast_s(i + 1) if i + 1 < free_plan.n_burns else MIN_FIRST_COAST_S
    fit = _fit_for(free_plan, t[0], span)
    return _joint_on_meshes(free_plan, seq, lambda w, k: _widened(w, k, free_plan, i, max_period_s),
                      free_coasts=flags, coast_bounds_s=(lo, hi), max_period_s=max_period_s,
                      fit=fit, min_period_s=shortest_free_period_s(free_plan, i))


def _widened(warm: tuple, k: int, free_plan: CapturePlan, i: int, max_period_s: float) -> tuple:
    """Leg ``k``'s warm start; burn i + 1's with room for any orbit after burn ``i``.

    The recovery's bound (:func:`lunarcap.studies.missed.orbits.after_free_orbit`), so that
    the nominal keeps the same freedom.
    """
    if k != i + 1:
        return warm
    prob, guess, mc = warm
    return after_free_orbit(prob, free_plan, i, max_period_s), guess, mc


#: In-process memo of nominals: (plan key, burn, max period s) -> :func:`nominal`'s dict.
_NOMINALS: dict = {}


def nominal_of(plan: CapturePlan, burn: int, max_period_s: float) -> dict:
    """:func:`nominal` of ``plan``, solved once per process (memo).

    Cached on disk as the cache switch says (:func:`lunarcap.repro.cache.caching`).
    """
    key = (plan.key(), int(burn), float(max_period_s))
    if key not in _NOMINALS:
        _NOMINALS[key] = nominal(plan.key(), int(burn), float(max_period_s),
                                 code_version(*_MODULES))
    return _NOMINALS[key]


def _remeshed(warm: tuple, coast, mesh) -> tuple:
    """A leg's warm start with its coast mesh made for ``mesh`` (Sundman-spaced)."""
    prob, guess, mc = warm
    if len(mc) != mesh.n_coast + 1:
        mc = sundman_fractions(coast.t, coast.x, mesh.n_coast)
    return prob, guess, mc


# ---------------------------------------------------------------------- one case
def _nominal_part(plan: CapturePlan, burn: int, max_period_s: float) -> tuple:
    """The nominal (plan, legs) and the case's nominal columns."""
    nom = nominal_of(plan, burn, max_period_s)
    nplan, legs = nom["plan"], nom["legs"]
    i = burn - 1
    last = legs[-1]
    t_ref = nplan.nominal_perilunes_s
    cols = {"nominal_burn_duration_min": legs[i].raw.t1_s / 60.0,
            "nominal_burn_delta_v_mps": legs[i].delta_v_mps,
            "nominal_remaining_delta_v_mps": sum(s.delta_v_mps for s in legs[i:]),
            "nominal_time_to_final_orbit_h": time_to_final_orbit_h(t_ref[0], last),
            "nominal_period_after_burn_h": (nplan.coast_s(i) / 3600.0
                                            if i < plan.n_burns - 1 else None)}
    return nplan, legs, cols


def _burn_rows(legs: list, burns: list, burn: int, t_r: float) -> list[dict]:
    """One row per recovery burn (verified Solutions ``legs``, plan ``burns``), from ``burn``."""
    rows = []
    for k, (s, b) in enumerate(zip(legs, burns)):
        sm = s.summary()
        rows.append({"burn": burn + k, "target_orbit": b.describe(),
                     "ignition_epoch": sm["ignition_epoch"],
                     "ignition_min_after_fault": (s.problem.t_ign_s - t_r) / 60.0,
                     "burn_duration_min": sm["burn_duration_min"],
                     "delta_v_mps": sm["delta_v_mps"], "verified": s.verification.passed})
    return rows


def _solved(out: dict, res, est, burn: int, t_r: float, t_arrival_s: float,
            partial: float, free: bool) -> dict:
    """Fill ``out`` with a verified recovery (its JointResult ``res``).

    ``free``: the make-up orbit was free (an intermediate burn's).
    """
    rows = _burn_rows(res.legs, res.plan.burns, burn, t_r)
    period = None
    if free:
        xf = res.legs[0].end_state
        a = xf[0] / (1 - xf[1] ** 2 - xf[2] ** 2)
        period = period_s(a) / 3600.0 if a > 0 else math.inf
        rows[0]["target_orbit"] = f"ellipse, {period:.6g} h (free)"
    _recovered(out, rows, partial, time_to_final_orbit_h(t_arrival_s, res.legs[-1]))
    out.update(make_up_delta_v_mps=rows[0]["delta_v_mps"],
               make_up_estimate_mps=None if est is None else est["delta_v_mps"],
               make_up_estimate_h=None if est is None else est["first_coast_guess_s"] / 3600,
               first_coast_h=res.plan.coast_s(0) / 3600.0 if free else None,
               make_up_period_h=period, ipopt_status=res.ipopt_status)
    return out


def _recovered(out: dict, rows: list, partial: float, final_h: float) -> None:
    """The totals of a recovery of burns ``rows`` after a partial burn (m/s) into ``out``."""
    rec_dv = sum(r["delta_v_mps"] for r in rows)
    out.update(status="recovered", recovery_delta_v_mps=rec_dv,
               total_delta_v_mps=partial + rec_dv,
               penalty_mps=partial + rec_dv - out["nominal_remaining_delta_v_mps"],
               recovery_burns=rows, time_to_final_orbit_h=final_h,
               all_verified=all(r["verified"] for r in rows))


def _nothing_made_up(out: dict, nplan: CapturePlan, legs: list, i: int, t_r: float,
                     partial: float) -> dict:
    """Fill ``out`` for a fault that left nothing to make up: the nominal's later burns."""
    rows = _burn_rows(legs[i + 1:], nplan.burns[i + 1:], i + 2, t_r)
    _recovered(out, rows, partial, out["nominal_time_to_final_orbit_h"])
    out.update(reason="nothing to make up: coasting, the orbit the fault left meets burn "
                      f"{i + 1}'s target within the verification gate (no make-up burn)",
               make_up_delta_v_mps=0.0, make_up_estimate_mps=0.0, ipopt_status="")
    return out


def _below_nominal(out: dict, burn: int) -> str:
    """The reason of a recovery cheaper than the nominal (its penalty below -0.05 m/s).

    The partial burn and the recovery are a capture from burn ``burn``'s ignition state to
    the final orbit with the nominal's freedoms (and one more, the pause in the burn), so
    the nominal is not the cheapest such capture: against the cheapest, this penalty would
    be higher (at least 0). In two-body dynamics the generated families never show one (the
    tests); in full dynamics family-3 of the seed-24 family (194 N) does, -1.5 to -2.2 m/s
    for burn 1: its nominal, 861.744 m/s, is a local optimum (859.368 m/s from a 10 h orbit
    after burn 1).
    """
    return (f"{-out['penalty_mps']:.2f} m/s cheaper than the nominal: the partial burn and "
            f"this recovery are a cheaper capture from burn {burn}'s ignition than the "
            f"nominal's optimum (a local one, or the pause in the burn helps), so against the "
            f"cheapest capture this penalty would be higher")


def _refused(out: dict, status: str, reason: str, ipopt_status: str = "") -> dict:
    out.update(status=status, reason=reason, ipopt_status=ipopt_status)
    return out


def _attempt(out: dict, nominal_part: tuple, burn: int, t_r: float, x_r, window_min: tuple,
             max_period_s: float, fit_for, coast: Model, partial: float,
             later: bool = True) -> dict:
    """Recover from ``x_r`` at ``t_r`` (:func:`recovery`) and record the outcome in ``out``.

    ``nominal_part``: (nominal plan, its legs). A plan the checks refuse is "no recovery"
    with their message; a solver's failure is "failed" with IPOPT's status.
    """
    nplan, legs = nominal_part
    i = burn - 1
    try:
        how, res, est = recovery(nplan, legs, i, t_r, x_r, window_min, max_period_s,
                                 fit_for, coast, later, legs[i].delta_v_mps - partial)
    except PlanError as exc:
        return _refused(out, "no recovery", f"no plan from this state: {exc}")
    except SolveError as exc:
        return _refused(out, "failed", str(exc).split("\n")[0], exc.status)
    except RuntimeError as exc:  # a guess's propagation failed (e.g. p -> 0)
        return _refused(out, "failed", f"no initial guess: {exc}".split("\n")[0])
    if how == "no recovery":
        return _refused(out, "no recovery", res)
    if how == "none":
        return _nothing_made_up(out, nplan, legs, i, t_r, partial)
    out = _solved(out, res, est, burn, t_r, nplan.nominal_perilunes_s[0], partial,
                  nplan.targets[i].kind == PERILUNE)
    if how == "next perilune" and est.get("window_delta_v_mps") is not None:
        out["reason"] = (f"make-up burn at the next perilune: its recovery burns need "
                         f"{est['window_delta_v_mps'] - res.total_delta_v_mps:.1f} m/s less "
                         f"than the verified recovery with it in the window "
                         f"({est['window_delta_v_mps']:.1f} m/s, a penalty above the "
                         f"nominal burn's own delta-V)")
    elif how == "next perilune":
        out["reason"] = ("make-up burn at the next perilune: no verified recovery with it "
                         "in the window")
    elif out["penalty_mps"] < -BELOW_NOMINAL_MPS:
        out["reason"] = "; ".join(r for r in (out["reason"], _below_nominal(out, burn)) if r)
    if est and est.get("doubtful"):
        out["reason"] = "; ".join(r for r in (out["reason"], est["doubtful"]) if r)
    return out


@cached(ignore=["verbose"])
def missed_case(plan: CapturePlan, burn: int, fraction: float, delay_s: float,
                max_period_s: float, window_min: tuple = DEFAULT_WINDOW_MIN,
                version: str = "", verbose: bool = False) -> dict:
    """A cut-off case (see the module docstring); pass ``plan.key()``.

    Returns
    -------
    dict
        ``status`` ("recovered", "no recovery", "failed"), ``reason``; the cut-off:
        ``cutoff_epoch``, ``partial_delta_v_mps``, ``cutoff_*`` orbit (see
        :func:`classify`), ``captured``; the recovery: ``recovery_start_e``,
        ``recovery_delta_v_mps`` (its burns), ``make_up_delta_v_mps`` and its two-body
        estimate ``make_up_estimate_mps``, ``make_up_period_h`` (osculating, at its
        perilune), ``total_delta_v_mps`` (partial + recovery), ``penalty_mps``,
        ``recovery_burns``, ``first_coast_h``, ``time_to_final_orbit_h`` and the
        nominal's (:func:`lunarcap.capture.chain.time_to_final_orbit_h`: from the arrival
        perilune to the end of the last burn),
        ``ipopt_status``, ``all_verified``, ``wall_s``.
    """
    t_start = time.perf_counter()
    nplan, legs, nom_cols = _nominal_part(plan, burn, max_period_s)
    i = burn - 1
    raw = legs[i].raw
    t_cut_rel = fraction * raw.t1_s
    flown = cut_off(raw, t_cut_rel)
    t_cut, xc = flown.end.t_s, flown.end.x
    partial = flown.delta_v_mps
    cut = classify(xc, t_cut, plan.ephemeris)
    out = {"contingency": "cut-off", "status": "recovered", "reason": "",
           "cutoff_epoch": calendar_from_seconds(t_cut),
           "cutoff_min_after_ignition": t_cut_rel / 60.0, "partial_delta_v_mps": partial,
           **nom_cols, "captured": cut["orbit"] != "escape",
           **{f"cutoff_{k}": v for k, v in cut.items()}}
    t_r = t_cut + delay_s
    fit_for = _fits(plan, nplan, burn, t_cut, t_r, max_period_s)
    coast = Model(plan.dynamics, 0.0, plan.engine.isp_s, fit_for(window_min))
    x_r = propagate(coast, t_cut, xc, t_r).final if delay_s > 0 else xc
    out["recovery_start_e"] = float(math.hypot(x_r[1], x_r[2]))
    out = _attempt(out, (nplan, legs), burn, t_r, x_r, window_min, max_period_s, fit_for,
                   coast, partial)
    out["wall_s"] = time.perf_counter() - t_start
    return out


def _fits(plan: CapturePlan, nplan: CapturePlan, burn: int, t0_s: float, t_r: float,
          max_period_s: float):
    """``fit_for(window)``: the ephemeris fit from ``t0_s`` of a recovery from ``t_r``.

    It covers a make-up igniting in ``window`` (min after ``t_r``), its orbit up to
    ``max_period_s`` (+ 2 h) and the plan's later coasts; one fit per window, reused.
    """
    rest = sum(nplan.coast_s(k) for k in range(burn, plan.n_burns))
    memo = {}

    def fit_for(window):
        if window not in memo:
            memo[window] = _fit_for(plan, t0_s, t_r - t0_s + 60 * window[1] + max_period_s
                                    + 7200.0 + rest)
        return memo[window]
    return fit_for


@cached(ignore=["verbose"])
def late_case(plan: CapturePlan, burn: int, late_s: float, max_period_s: float,
              version: str = "", verbose: bool = False) -> dict:
    """A late-ignition case (see the module docstring); pass ``plan.key()``.

    Burn n ignites ``late_s`` after the nominal's ignition, at that epoch exactly (from
    the nominal's state there), its duration and steering re-optimised, the later burns
    re-planned. Returns the dict of :func:`missed_case` (no partial burn: 0 m/s).
    """
    t_start = time.perf_counter()
    nplan, legs, nom_cols = _nominal_part(plan, burn, max_period_s)
    i = burn - 1
    prob = legs[i].problem
    t_r = prob.t_ign_s + late_s
    window = (0.0, 0.0)
    fit_for = _fits(plan, nplan, burn, prob.t_ign_s, t_r, max_period_s)
    coast = Model(plan.dynamics, 0.0, plan.engine.isp_s, fit_for(window))
    x_r = propagate(coast, prob.t_ign_s, prob.x0, t_r).final if late_s > 0 else prob.x0
    cut = classify(x_r, t_r, plan.ephemeris)
    out = {"contingency": "late ignition", "status": "recovered", "reason": "",
           "late_min": late_s / 60.0, "cutoff_epoch": calendar_from_seconds(t_r),
           "cutoff_min_after_ignition": late_s / 60.0, "partial_delta_v_mps": 0.0,
           **nom_cols, "captured": cut["orbit"] != "escape",
           **{f"cutoff_{k}": v for k, v in cut.items()},
           "recovery_start_e": cut["e"]}
    out = _attempt(out, (nplan, legs), burn, t_r, x_r, window, max_period_s, fit_for, coast,
                   0.0, later=False)
    out["wall_s"] = time.perf_counter() - t_start
    return out


def case_result(plan: CapturePlan, burn: int, fraction: float | None = None,
                delay_min: float = 0.0, max_period_h: float = DEFAULT_MAX_PERIOD_H,
                window_min: tuple = DEFAULT_WINDOW_MIN, verbose: bool = False,
                late_min: float | None = None) -> dict:
    """One case with checked inputs (InputError) in the CLI's units.

    A cut-off (``fraction``, ``delay_min``), or with ``late_min`` a late ignition. Cached
    as the cache switch says (:func:`lunarcap.repro.cache.caching`); the cached case is
    the plan's physics (:meth:`CapturePlan.key`, its name blanked), so its ``reason``
    names the plan here.
    """
    if late_min is not None:
        check_case(plan, burn, 1.0, late_min, "a late ignition")
        r = late_case(plan.key(), int(burn), float(late_min) * 60.0,
                      float(max_period_h) * 3600.0, code_version(*_MODULES), verbose=verbose)
    else:
        check_case(plan, burn, fraction, delay_min)
        r = missed_case(plan.key(), int(burn), float(fraction), float(delay_min) * 60.0,
                        float(max_period_h) * 3600.0, tuple(float(w) for w in window_min),
                        code_version(*_MODULES), verbose=verbose)
    return {**r, "reason": r["reason"].replace("plan ''", f"plan {plan.name!r}")}


def check_case(plan: CapturePlan, burn, fraction, delay_min, what: str = "a delay") -> None:
    """InputError for a burn the plan lacks, a fraction outside (0, 1], a negative delay."""
    if isinstance(burn, bool) or not isinstance(burn, (int, np.integer)) or \
            not 1 <= burn <= plan.n_burns:
        raise InputError(f"--burn {burn!r}: plan {plan.name} has burns 1 to {plan.n_burns}")
    if not isinstance(fraction, (int, float)) or not math.isfinite(fraction) or \
            not 0 < fraction <= 1:
        raise InputError(f"a fraction of the burn must lie in (0, 1], got {fraction!r}")
    if not isinstance(delay_min, (int, float)) or not math.isfinite(delay_min) or delay_min < 0:
        raise InputError(f"{what} must be a non-negative number of minutes, got "
                         f"{delay_min!r}")


# ====================================================================== the study on Dask
#: Columns of the study's table (one row per case; units in the names). ``contingency``:
#: "cut-off" (``fraction``, ``delay_min``; ``late_min`` 0) or "late ignition"
#: (``late_min``; ``fraction`` and ``delay_min`` 0).
COLUMNS = ("plan", "plan_id", "thrust_N", "isp_s", "dynamics", "burn", "contingency",
           "fraction", "delay_min", "late_min", "max_period_h", "status", "reason",
           "captured", "cutoff_orbit",
           "cutoff_epoch", "cutoff_min_after_ignition", "nominal_burn_duration_min",
           "partial_delta_v_mps", "nominal_burn_delta_v_mps", "cutoff_energy_km2ps2",
           "cutoff_e", "cutoff_rp_km", "cutoff_ra_km", "cutoff_period_h",
           "cutoff_soi_radius_km", "recovery_start_e", "recovery_delta_v_mps",
           "total_delta_v_mps", "nominal_remaining_delta_v_mps", "penalty_mps",
           "make_up_delta_v_mps", "make_up_estimate_mps", "make_up_period_h",
           "nominal_period_after_burn_h",
           "first_coast_h", "make_up_estimate_h", "time_to_final_orbit_h",
           "nominal_time_to_final_orbit_h",
           "all_verified", "ipopt_status", "recovery_burns_json", "task_wall_s", "worker",
           "code_version", "completed_utc", "error")
KEY = ("plan_id", "burn", "contingency", "fraction", "delay_min", "late_min", "max_period_h")


def case_row(plan: CapturePlan, burn: int, fraction: float, delay_min: float,
             max_period_h: float, late_min: float | None = None,
             nominal_result: dict | None = None) -> dict:
    """Dask task: one case as a row of the study's table (a failure is a status, not raised).

    ``nominal_result``: the nominal computed once by the caller (kept in this process's
    memo, so no worker solves it again, with or without the disk cache).
    """
    import json

    if nominal_result is not None:
        _NOMINALS[(plan.key(), int(burn), float(max_period_h) * 3600.0)] = nominal_result
    r = case_result(plan, burn, fraction, delay_min, max_period_h, late_min=late_min)
    row = {k: v for k, v in r.items() if k in COLUMNS}
    row["recovery_burns_json"] = json.dumps(r.get("recovery_burns", []))
    row["task_wall_s"] = r.get("wall_s")
    row["error"] = ""
    return row


def _cases(plan: CapturePlan, burn: int, fractions, delays, late, max_period_h: float,
           nom: dict) -> list:
    """The campaign's (key, args) of every case: cut-offs (fractions major), then late."""
    base = {**plan_columns(plan), "burn": int(burn)}
    h = float(max_period_h)
    cases = [({**base, "contingency": "cut-off", "fraction": f, "delay_min": d,
               "late_min": 0.0, "max_period_h": h},
              (plan, int(burn), f, d, h, None, nom))
             for f in fractions for d in delays]
    cases += [({**base, "contingency": "late ignition", "fraction": 0.0, "delay_min": 0.0,
                "late_min": m, "max_period_h": h},
               (plan, int(burn), None, 0.0, h, m, nom)) for m in late]
    return cases


def run_missed(plan: CapturePlan, burn: int, fractions, delays_min,
               max_period_h: float = DEFAULT_MAX_PERIOD_H, out=None, workers=2,
               scheduler=None, progress: bool = True, use_cache: bool | None = None,
               processes: bool = True, task=None, late_min=None):
    """Run (or resume) the study on Dask (see the module): cut-offs and late ignitions.

    ``fractions`` x ``delays_min`` cut-off cases (none if ``fractions`` is None or
    empty) and one late-ignition case per ``late_min``. The nominal is solved once, here,
    before the cases. Returns a :class:`lunarcap.studies.campaign.CampaignResult` (one row
    per case). InputError (a burn the plan lacks, fractions outside (0, 1], negative
    delays, an unusable ``out``, an unreachable scheduler) before any solve.
    """
    fractions = number_list("--fractions", fractions, "", positive=True, maximum=1.0,
                            distinct=True) if fractions not in (None, "", []) else ()
    delays = number_list("--delays-min", delays_min, "min", minimum=0.0, distinct=True)
    late = number_list("--late-min", late_min, "min", minimum=0.0, distinct=True) \
        if late_min not in (None, "", []) else ()
    if not fractions and not late:
        raise InputError("no case: give --fractions or --late-min")
    check_case(plan, burn, fractions[0] if fractions else 1.0, delays[0])
    if isinstance(max_period_h, bool) or not isinstance(max_period_h, (int, float)) or \
            not math.isfinite(max_period_h) or max_period_h <= 0:
        raise InputError(f"--max-period-h must be a positive number of hours, got "
                         f"{max_period_h!r}")
    workers = check_workers(workers)
    use_cache = position(use_cache)   # None: the switch's current position
    nom = None
    if task is None:   # the real study: its nominal, once, in this process
        with caching(use_cache):
            nom = nominal_of(plan, int(burn), float(max_period_h) * 3600.0)
    return STUDY.run(_cases(plan, burn, fractions, delays, late, max_period_h, nom),
                     out, task=task, workers=workers, scheduler=scheduler, progress=progress,
                     processes=processes, use_cache=use_cache,
                     describe={"study": "missed", "burn": int(burn),
                               "fractions": list(fractions), "delays_min": list(delays),
                               "late_min": list(late), "max_period_h": float(max_period_h)})


def format_rows(result, plan: CapturePlan, burn: int) -> str:
    """The study's text: one line per case, then the run."""
    rows = result.table.to_dict("records")
    h = rows[0]["max_period_h"] if rows else DEFAULT_MAX_PERIOD_H
    lines = [f"Burn {burn} of plan {plan.name} ({plan.engine.thrust_N:g} N / "
             f"{plan.engine.isp_s:g} s, {plan.dynamics} dynamics) cut off (the engine stops "
             f"after a fraction of the burn, the fault lasts the delay) or ignited late; the "
             f"rest of the capture re-optimised to the same final orbit, the orbit after "
             f"burn {burn} at most {h:g} h in the recovery and the nominal alike; "
             f"penalty = partial + recovery delta-V minus the nominal burns "
             f"{burn}..{plan.n_burns}",
             f"{'contingency':<13} {'fraction':>8} {'delay min':>9} {'late min':>8} | "
             f"{'orbit at cut-off':<16} {'e':>6} {'apolune km':>10} | {'recovery m/s':>12} "
             f"{'penalty m/s':>11} {'final orbit h':>13} | status"]
    for r in rows:
        ra = r["cutoff_ra_km"]
        ra_txt = f"{ra:10.0f}" if isinstance(ra, float) and math.isfinite(ra) else f"{'inf':>10}"
        ok = r["status"] == "recovered"
        lines.append(
            f"{str(r['contingency']):<13} {r['fraction']:8.3g} {r['delay_min']:9.4g} "
            f"{r['late_min']:8.4g} | {str(r['cutoff_orbit']):<16} {r['cutoff_e']:6.3f} "
            f"{ra_txt} | "
            + (f"{r['recovery_delta_v_mps']:12.3f} {r['penalty_mps']:z11.3f} "
               f"{r['time_to_final_orbit_h']:13.2f} | recovered" if ok else
               f"{'—':>12} {'—':>11} {'—':>13} | {r['status']}: {r['reason'] or r['error']}"))
    if rows:
        r0 = rows[0]
        lines.append(f"nominal: burns {burn}..{plan.n_burns} need "
                     f"{r0['nominal_remaining_delta_v_mps']:.3f} m/s; burn {burn} lasts "
                     f"{r0['nominal_burn_duration_min']:.2f} min; final orbit "
                     f"{r0['nominal_time_to_final_orbit_h']:.2f} h after the arrival "
                     f"perilune")
    return "\n".join(lines + STUDY.run_lines(result))

#: The study, declared once (:class:`lunarcap.studies.study.Study`).
STUDY = Study(
    "missed", TableFormat(KEY, COLUMNS, text_columns=(
        "plan", "plan_id", "dynamics", "contingency", "reason", "cutoff_orbit", "cutoff_epoch",
        "ipopt_status", "recovery_burns_json")),
    case_row, STATUSES, ("recovered", "no recovery"), "case", "missed-thrust study", _MODULES,
    decoders=(("recovery_burns_json", "recovery_burns", json_list),), rows_key="cases",
    text=format_rows)
