"""One case of the missed-thrust study: a contingency of burn n, recovered, and its row.

Two contingencies (``contingency`` in the table):

* **cut-off** (fraction f, delay d): burn n is flown as planned (its optimal steering,
  re-propagated from its ignition state, :func:`lunarcap.optim.flight.cut_off`) and the
  engine stops after ``f`` of its duration; the spacecraft coasts for ``d`` (the fault
  being cleared).
* **late ignition** (``late_min`` L, as studied for KPLO's LOI burns by Bae et al. 2017,
  JASS 34(4)): burn n ignites L minutes after its planned ignition; nothing of it has been
  flown before.

The recovery from the state the fault leaves is :func:`lunarcap.studies.missed.recovery.
recovery`. The **penalty** is measured on one basis: the delta-V from the state before
burn n to the final orbit, finite burns, same dynamics: (delta-V of the partial burn + the
recovery's) minus (the nominal burns n, n+1, ...; :mod:`lunarcap.studies.missed.nominal`,
which has the recovery's freedoms, except splitting the burn over two perilunes: a
make-up that waits for one may cost less, and its reason says why). The capture's last
burn ends within ``max_days`` of the arrival perilune (``--max-days``). Statuses:
"recovered" (verified), "no recovery" (every place of the make-up refused by physics or
by a limit the reason names, or a re-plan the plan's own checks refuse, with their
message), "failed" (any solver failure, with IPOPT's status: a solver's verdict is not a
physical reason, so it is never reported as "no recovery"). The CasADi and CVODES
warning lines a case's solves write are counted (``solver_warnings``), not printed
(:mod:`lunarcap.studies.missed.messages`).
"""

from __future__ import annotations

import math
import time

from lunarcap.capture.chain import time_to_final_orbit_h
from lunarcap.errors import SolveError
from lunarcap.mission.plan import CapturePlan, PlanError
from lunarcap.mission.targets import PERILUNE
from lunarcap.optim.flight import cut_off
from lunarcap.physics.dynamics import Model
from lunarcap.physics.epochs import calendar_from_seconds
from lunarcap.physics.propagate import propagate
from lunarcap.repro.cache import cached
from lunarcap.studies.missed.makeup import COAST_SLACK_S, ephemeris_fit
from lunarcap.studies.missed.messages import counted
from lunarcap.studies.missed.nominal import DEFAULT_MAX_DAYS, nominal_of
from lunarcap.studies.missed.orbits import classify, period_s
from lunarcap.studies.missed.recovery import recovery

#: A penalty below minus this (m/s) is a recovery cheaper than the nominal, and its row says
#: so (:func:`_below_nominal`): beyond the solver's tolerance, as the tests' bound.
BELOW_NOMINAL_MPS = 0.05
#: Window of the make-up burn's ignition after the fault is cleared, min.
DEFAULT_WINDOW_MIN = (0.0, 30.0)


@cached(ignore=["verbose", "nominal"])
def missed_case(plan: CapturePlan, burn: int, fraction: float, delay_s: float,
                max_period_s: float, window_min: tuple = DEFAULT_WINDOW_MIN,
                version: str = "", verbose: bool = False, nominal: dict | None = None,
                max_days: float = DEFAULT_MAX_DAYS) -> dict:
    """A cut-off case (see the module); pass ``plan.key()``.

    ``nominal``: the nominal of (``plan``, ``burn``, ``max_period_s``) if the caller has
    it (:func:`~lunarcap.studies.missed.nominal.nominal_of`), else solved here; it is a
    function of the cache key, so it is not part of it. ``max_days``: the capture's last
    burn ends within this of the arrival perilune, days (``--max-days``).

    Returns
    -------
    dict
        ``status`` ("recovered", "no recovery", "failed"), ``reason``; the cut-off:
        ``cutoff_epoch``, ``partial_delta_v_mps``, ``cutoff_*`` orbit (see
        :func:`~lunarcap.studies.missed.orbits.classify`), ``captured``; the recovery:
        ``recovery_start_e``, ``recovery_delta_v_mps`` (its burns),
        ``make_up_delta_v_mps`` and its two-body estimate ``make_up_estimate_mps``,
        ``make_up_period_h`` (osculating, at its perilune), ``total_delta_v_mps``
        (partial + recovery), ``penalty_mps``, ``recovery_burns``, ``first_coast_h``,
        ``time_to_final_orbit_h`` and the nominal's
        (:func:`lunarcap.capture.chain.time_to_final_orbit_h`: from the arrival perilune
        to the end of the last burn), ``ipopt_status``, ``all_verified``, ``wall_s``,
        ``solver_warnings`` (:mod:`lunarcap.studies.missed.messages`).
    """
    t_start = time.perf_counter()
    with counted() as tally:
        out = _missed(plan, burn, fraction, delay_s, max_period_s, window_min, nominal,
                      max_days)
    out.update(wall_s=time.perf_counter() - t_start, solver_warnings=tally.count)
    return out


def _missed(plan: CapturePlan, burn: int, fraction: float, delay_s: float,
            max_period_s: float, window_min: tuple, nominal: dict | None,
            max_days: float) -> dict:
    """:func:`missed_case`'s work (its arguments), without its timing and tally."""
    nplan, legs, nom_cols = _nominal_part(plan, burn, max_period_s, nominal)
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
    deadline_s = nplan.nominal_perilunes_s[0] + 86400.0 * max_days
    fit_for = _fits(plan, nplan, burn, t_cut, t_r, max_period_s)
    coast = Model(plan.dynamics, 0.0, plan.engine.isp_s, fit_for(window_min))
    x_r = propagate(coast, t_cut, xc, t_r).final if delay_s > 0 else xc
    out["recovery_start_e"] = float(math.hypot(x_r[1], x_r[2]))
    return _attempt(out, (nplan, legs), burn, t_r, x_r, window_min, max_period_s, fit_for,
                    coast, partial, deadline_s=deadline_s)


@cached(ignore=["verbose", "nominal"])
def late_case(plan: CapturePlan, burn: int, late_s: float, max_period_s: float,
              version: str = "", verbose: bool = False, nominal: dict | None = None,
              max_days: float = DEFAULT_MAX_DAYS) -> dict:
    """A late-ignition case (see the module); pass ``plan.key()``.

    Burn n ignites ``late_s`` after the nominal's ignition, at that epoch exactly (from
    the nominal's state there), its duration and steering re-optimised, the later burns
    re-planned. ``nominal`` and ``max_days`` as :func:`missed_case`'s. Returns the dict
    of :func:`missed_case` (no partial burn: 0 m/s).
    """
    t_start = time.perf_counter()
    with counted() as tally:
        out = _late(plan, burn, late_s, max_period_s, nominal, max_days)
    out.update(wall_s=time.perf_counter() - t_start, solver_warnings=tally.count)
    return out


def _late(plan: CapturePlan, burn: int, late_s: float, max_period_s: float,
          nominal: dict | None, max_days: float) -> dict:
    """:func:`late_case`'s work (its arguments), without its timing and tally."""
    nplan, legs, nom_cols = _nominal_part(plan, burn, max_period_s, nominal)
    i = burn - 1
    prob = legs[i].problem
    t_r = prob.t_ign_s + late_s
    window = (0.0, 0.0)
    deadline_s = nplan.nominal_perilunes_s[0] + 86400.0 * max_days
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
    return _attempt(out, (nplan, legs), burn, t_r, x_r, window, max_period_s, fit_for, coast,
                    0.0, later=False, deadline_s=deadline_s)


def _nominal_part(plan: CapturePlan, burn: int, max_period_s: float,
                  nominal: dict | None = None) -> tuple:
    """The nominal (plan, legs) and the case's nominal columns (``nominal`` if given)."""
    nom = nominal_of(plan, burn, max_period_s) if nominal is None else nominal
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


def _fits(plan: CapturePlan, nplan: CapturePlan, burn: int, t0_s: float, t_r: float,
          max_period_s: float):
    """``fit_for(window, longest=max_period_s)``: the ephemeris fit from ``t0_s`` of a recovery.

    It covers a make-up igniting in ``window`` (min after ``t_r``), its orbit up to
    ``longest`` (s; + 2 h) and the plan's later coasts; one fit per window and bound, made
    once for the case.
    """
    rest = sum(nplan.coast_s(k) for k in range(burn, plan.n_burns))
    made = {}

    def fit_for(window, longest=max_period_s):
        if (window, longest) not in made:
            made[(window, longest)] = ephemeris_fit(
                plan, t0_s, t_r - t0_s + 60 * window[1] + longest + COAST_SLACK_S + rest)
        return made[(window, longest)]
    return fit_for


# ---------------------------------------------------------------------- the outcome
def _attempt(out: dict, nominal_part: tuple, burn: int, t_r: float, x_r, window_min: tuple,
             max_period_s: float, fit_for, coast: Model, partial: float, later: bool = True,
             deadline_s: float = math.inf) -> dict:
    """Recover from ``x_r`` at ``t_r`` (:func:`recovery`) and record the outcome in ``out``.

    ``nominal_part``: (nominal plan, its legs); ``deadline_s``: the epoch by which the
    capture must end (s). A plan the checks refuse is "no recovery" with their message; a
    solver's failure is "failed" with IPOPT's status.
    """
    nplan, legs = nominal_part
    i = burn - 1
    try:
        how, res, est = recovery(nplan, legs, i, t_r, x_r, window_min, max_period_s,
                                 fit_for, coast, later, legs[i].delta_v_mps - partial,
                                 deadline_s=deadline_s)
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
    out["reason"] = "; ".join(r for r in (_why(how, out, est, res, burn),
                                          est.get("doubtful", "") if est else "") if r)
    return out


def _why(how: str, out: dict, est: dict, res, burn: int) -> str:
    """The reason of a recovered row: why the make-up waited, and a penalty below the nominal."""
    below = ""
    if out["penalty_mps"] < -BELOW_NOMINAL_MPS:
        below = _below_nominal(out, burn) if how == "in the window" else _split(out)
    if how == "in the window":
        return below
    wait_h = out["recovery_burns"][0]["ignition_min_after_fault"] / 60.0
    where = f"make-up burn {how} ({wait_h:.1f} h after the fault"
    if est.get("deadline_period_h") is not None:   # the deadline bounds its orbit
        where += (f"; its orbit at most {est['deadline_period_h']:.1f} h, to end the capture "
                  f"within --max-days")
    where += ")"
    if est.get("window_delta_v_mps") is not None:
        why = (f"{where}: its recovery burns need "
               f"{est['window_delta_v_mps'] - res.total_delta_v_mps:.1f} m/s less "
               f"than the verified recovery with it in the window "
               f"({est['window_delta_v_mps']:.1f} m/s, a penalty above the "
               f"nominal burn's own delta-V)")
    elif est.get("window"):
        why = f"{where}: in the window, {est['window']}"
    else:
        why = f"{where}: no verified recovery with it in the window"
    return "; ".join(r for r in (why, below) if r)


def _split(out: dict) -> str:
    """The reason of a make-up at a later perilune cheaper than the nominal.

    The partial burn and the make-up one orbit (or more) later are the nominal burn split
    over two perilunes: each part shorter, flown nearer its perilune, loses less to
    gravity than the one burn of the nominal (Eq. 10's finite-burn loss), a freedom the
    nominal does not have; the price is the time to the final orbit.
    """
    later_h = out["time_to_final_orbit_h"] - out["nominal_time_to_final_orbit_h"]
    return (f"{-out['penalty_mps']:.2f} m/s cheaper than the nominal: the burn split over two "
            f"perilunes loses less to gravity than the nominal's one burn, at the price of "
            f"{later_h:.1f} h more to the final orbit")


def _refused(out: dict, status: str, reason: str, ipopt_status: str = "") -> dict:
    """``out`` with a status that is no recovery: its reason and IPOPT's status."""
    out.update(status=status, reason=reason, ipopt_status=ipopt_status)
    return out


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
    the nominal is not the cheapest such capture (a local optimum, in full dynamics):
    against the cheapest, this penalty would be higher (at least 0).
    """
    return (f"{-out['penalty_mps']:.2f} m/s cheaper than the nominal: the partial burn and "
            f"this recovery are a cheaper capture from burn {burn}'s ignition than the "
            f"nominal's optimum (a local one, or the pause in the burn helps), so against the "
            f"cheapest capture this penalty would be higher")
