"""Missed thrust and late ignition, the study: its cases, its table and its declaration.

A capture burn goes wrong (burn n of a plan cut off after a fraction of its duration and
a delay to clear the fault, or ignited late: :mod:`lunarcap.studies.missed.contingency`)
and the rest of the capture is re-planned to the same final orbit
(:mod:`lunarcap.studies.missed.recovery`); the penalty is measured against the plan's
all-burns optimum with the same freedoms (:mod:`lunarcap.studies.missed.nominal`). Each
case is one row of the study's table, computed by a Dask task (:func:`case_row`);
:func:`run_missed` runs a grid of them through :data:`STUDY`.
"""

from __future__ import annotations

import json
import math

import numpy as np

from lunarcap.errors import InputError, number_list
from lunarcap.mission.plan import MAX_START_MIN, CapturePlan
from lunarcap.repro.cache import caching, code_version, position
from lunarcap.studies.burn_count.counts import MAX_FIT_SPAN_S
from lunarcap.studies.campaign import TableFormat
from lunarcap.studies.missed import MODULES
from lunarcap.studies.missed.contingency import DEFAULT_WINDOW_MIN, late_case, missed_case
from lunarcap.studies.missed.makeup import COAST_SLACK_S
from lunarcap.studies.missed.messages import counted
from lunarcap.studies.missed.nominal import DEFAULT_MAX_DAYS, DEFAULT_MAX_PERIOD_H, nominal_of
from lunarcap.studies.study import Study, check_workers, json_list, plan_columns

#: The contingencies of a case.
CONTINGENCIES = ("cut-off", "late ignition")
STATUSES = ("recovered", "no recovery", "failed", "error")


def case_result(plan: CapturePlan, burn: int, fraction: float | None = None,
                delay_min: float = 0.0, max_period_h: float = DEFAULT_MAX_PERIOD_H,
                window_min: tuple = DEFAULT_WINDOW_MIN, verbose: bool = False,
                late_min: float | None = None, nominal: dict | None = None,
                max_days: float = DEFAULT_MAX_DAYS) -> dict:
    """One case with checked inputs (InputError) in the CLI's units.

    A cut-off (``fraction``, ``delay_min``), or with ``late_min`` a late ignition. Cached
    as the cache switch says (:func:`lunarcap.repro.cache.caching`); the cached case is
    the plan's physics (:meth:`CapturePlan.key`, its name blanked), so its ``reason``
    names the plan here. ``nominal``: the nominal of (``plan``, ``burn``,
    ``max_period_h``) if the caller has it (:func:`lunarcap.studies.missed.nominal.
    nominal_of`: a caller running several cases of one burn solves it once), else solved
    for this case. ``max_days``: the capture ends within this of the arrival perilune.
    """
    check_max_days(plan, burn, max_period_h, max_days)
    if late_min is not None:
        check_case(plan, burn, 1.0, late_min, "a late ignition")
        r = late_case(plan.key(), int(burn), float(late_min) * 60.0,
                      float(max_period_h) * 3600.0, code_version(*MODULES), verbose=verbose,
                      nominal=nominal, max_days=float(max_days))
    else:
        check_case(plan, burn, fraction, delay_min)
        r = missed_case(plan.key(), int(burn), float(fraction), float(delay_min) * 60.0,
                        float(max_period_h) * 3600.0, tuple(float(w) for w in window_min),
                        code_version(*MODULES), verbose=verbose, nominal=nominal,
                        max_days=float(max_days))
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


def check_max_days(plan: CapturePlan, burn, max_period_h, max_days) -> None:
    """InputError for a ``--max-days`` that is not a positive number, or outside what it may be.

    At least the longest nominal capture (the orbit after ``burn`` at ``max_period_h``,
    + 2 h, the plan's other coasts to its last burn): the penalty compares a recovery with
    a nominal that meets the same deadline. At most what one ephemeris fit covers (4 days:
    from an hour before the arrival perilune to the deadline, a make-up window's 2 h, the
    make-up coast's 2 h of slack, the final coast and the fit's 7 h of margins).
    """
    if isinstance(max_days, bool) or not isinstance(max_days, (int, float)) or \
            not math.isfinite(max_days) or max_days <= 0:
        raise InputError(f"--max-days must be a positive number of days, got {max_days!r}")
    if isinstance(max_period_h, bool) or not isinstance(max_period_h, (int, float)) or \
            not math.isfinite(max_period_h) or max_period_h <= 0:
        raise InputError(f"--max-period-h must be a positive number of hours, got "
                         f"{max_period_h!r}")
    if not isinstance(burn, (int, np.integer)) or not 1 <= burn <= plan.n_burns:
        return   # check_case names it
    i, t = burn - 1, plan.nominal_perilunes_s
    nominal_s = t[plan.n_burns - 1] - t[0]
    if i < plan.n_burns - 1:
        nominal_s += 3600.0 * max_period_h + 7200.0 - plan.coast_s(i)
    last_s = plan.coast_s(plan.n_burns - 1)   # the fit's 7 h, an hour before the arrival,
    most = (MAX_FIT_SPAN_S - 8 * 3600.0 - 60.0 * MAX_START_MIN - COAST_SLACK_S   # a window,
            - last_s) / 86400.0                                    # the slack, the circle
    if max_days * 86400.0 < nominal_s:
        raise InputError(f"--max-days {max_days:g}: plan {plan.name}'s capture, the orbit after "
                         f"burn {burn} up to {max_period_h:g} h (--max-period-h), may last "
                         f"{nominal_s / 86400:.2f} days; give at least that")
    if max_days > most:
        raise InputError(f"--max-days {max_days:g}: at most {math.floor(most * 100) / 100:g} "
                         f"days for plan {plan.name} (a recovery is solved with one Earth/Sun "
                         f"ephemeris fit, which spans at most 4 days with its margins)")


# ====================================================================== the study on Dask
#: Columns of the study's table (one row per case; units in the names). ``contingency``:
#: "cut-off" (``fraction``, ``delay_min``; ``late_min`` 0) or "late ignition"
#: (``late_min``; ``fraction`` and ``delay_min`` 0).
COLUMNS = ("plan", "plan_id", "thrust_N", "isp_s", "dynamics", "burn", "contingency",
           "fraction", "delay_min", "late_min", "max_period_h", "max_days", "status", "reason",
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
           "all_verified", "ipopt_status", "recovery_burns_json", "solver_warnings",
           "task_wall_s", "worker", "code_version", "completed_utc", "error")
KEY = ("plan_id", "burn", "contingency", "fraction", "delay_min", "late_min", "max_period_h",
       "max_days")


def case_row(plan: CapturePlan, burn: int, fraction: float, delay_min: float,
             max_period_h: float, late_min: float | None = None,
             nominal_result: dict | None = None, max_days: float = DEFAULT_MAX_DAYS) -> dict:
    """Dask task: one case as a row of the study's table (a failure is a status, not raised).

    ``nominal_result``: the nominal computed once by the caller, passed to the case (no
    worker solves it again, and nothing is kept in the worker between cases).
    """
    r = case_result(plan, burn, fraction, delay_min, max_period_h, late_min=late_min,
                    nominal=nominal_result, max_days=max_days)
    row = {k: v for k, v in r.items() if k in COLUMNS}
    row["recovery_burns_json"] = json.dumps(r.get("recovery_burns", []))
    row["task_wall_s"] = r.get("wall_s")
    row["error"] = ""
    return row


def _cases(plan: CapturePlan, burn: int, fractions, delays, late, max_period_h: float,
           nom: dict, max_days: float = DEFAULT_MAX_DAYS) -> list:
    """The campaign's (key, args) of every case: cut-offs (fractions major), then late."""
    base = {**plan_columns(plan), "burn": int(burn)}
    h, days = float(max_period_h), float(max_days)
    cases = [({**base, "contingency": "cut-off", "fraction": f, "delay_min": d,
               "late_min": 0.0, "max_period_h": h, "max_days": days},
              (plan, int(burn), f, d, h, None, nom, days))
             for f in fractions for d in delays]
    cases += [({**base, "contingency": "late ignition", "fraction": 0.0, "delay_min": 0.0,
                "late_min": m, "max_period_h": h, "max_days": days},
               (plan, int(burn), None, 0.0, h, m, nom, days)) for m in late]
    return cases


def run_missed(plan: CapturePlan, burn: int, fractions, delays_min,
               max_period_h: float = DEFAULT_MAX_PERIOD_H, out=None, workers=2,
               scheduler=None, progress: bool = True, use_cache: bool | None = None,
               processes: bool = True, task=None, late_min=None,
               max_days: float = DEFAULT_MAX_DAYS):
    """Run (or resume) the study on Dask (see the module): cut-offs and late ignitions.

    ``fractions`` x ``delays_min`` cut-off cases (none if ``fractions`` is None or
    empty) and one late-ignition case per ``late_min``; every capture ends within
    ``max_days`` of the arrival perilune. The nominal is solved once, here, before the
    cases; the solver lines it writes are counted (the run's
    ``nominal_solver_warnings``), not printed. Returns a
    :class:`lunarcap.studies.campaign.CampaignResult` (one row per case). InputError (a
    burn the plan lacks, fractions outside (0, 1], negative delays, a ``max_days`` out of
    range, an unusable ``out``, an unreachable scheduler) before any solve.
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
    check_max_days(plan, burn, max_period_h, max_days)
    workers = check_workers(workers)
    use_cache = position(use_cache)   # None: the switch's current position
    nom, tally = None, None
    if task is None:   # the real study: its nominal, once, in this process
        with caching(use_cache), counted() as tally:
            nom = nominal_of(plan, int(burn), float(max_period_h) * 3600.0)
    return STUDY.run(_cases(plan, burn, fractions, delays, late, max_period_h, nom, max_days),
                     out, task=task, workers=workers, scheduler=scheduler, progress=progress,
                     processes=processes, use_cache=use_cache,
                     describe={"study": "missed", "burn": int(burn),
                               "fractions": list(fractions), "delays_min": list(delays),
                               "late_min": list(late), "max_period_h": float(max_period_h),
                               "max_days": float(max_days),
                               "nominal_solver_warnings": tally.count if tally else 0})


def format_rows(result, plan: CapturePlan, burn: int) -> str:
    """The study's text: one line per case, then the run."""
    rows = result.table.to_dict("records")
    h = rows[0]["max_period_h"] if rows else DEFAULT_MAX_PERIOD_H
    days = rows[0].get("max_days") if rows else DEFAULT_MAX_DAYS
    deadline = (f", the capture's last burn within {days:g} days of the arrival perilune"
                if isinstance(days, (int, float)) and math.isfinite(days) else "")
    lines = [f"Burn {burn} of plan {plan.name} ({plan.engine.thrust_N:g} N / "
             f"{plan.engine.isp_s:g} s, {plan.dynamics} dynamics) cut off (the engine stops "
             f"after a fraction of the burn, the fault lasts the delay) or ignited late; the "
             f"rest of the capture re-optimised to the same final orbit, the orbit after "
             f"burn {burn} at most {h:g} h in the recovery and the nominal alike{deadline}; "
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
    lines += solver_line(rows, result.run)
    return "\n".join(lines + STUDY.run_lines(result))


def solver_line(rows: list, run: dict) -> list:
    """The one line that counts the solver warnings kept off the terminal (none if none).

    The cases' ``solver_warnings`` and the nominal's (the run's
    ``nominal_solver_warnings``): see :mod:`lunarcap.studies.missed.messages`.
    """
    cases = [int(r["solver_warnings"]) for r in rows
             if isinstance(r.get("solver_warnings"), (int, float))
             and math.isfinite(r["solver_warnings"])]
    nominal = int(run.get("nominal_solver_warnings") or 0)
    if not sum(cases) + nominal:
        return []
    return [f"solver warnings: {sum(cases) + nominal} CasADi/CVODES lines kept off the "
            f"terminal ({nominal} in the nominal, {sum(cases)} in {sum(c > 0 for c in cases)} "
            f"case(s): guesses whose propagation met an infinite state and failed; the "
            f"table's solver_warnings, the text at DEBUG on the logger lunarcap.studies.missed)"]

#: The study, declared once (:class:`lunarcap.studies.study.Study`).
STUDY = Study(
    "missed", TableFormat(KEY, COLUMNS, text_columns=(
        "plan", "plan_id", "dynamics", "contingency", "reason", "cutoff_orbit", "cutoff_epoch",
        "ipopt_status", "recovery_burns_json")),
    case_row, STATUSES, ("recovered", "no recovery"), "case", "missed-thrust study", MODULES,
    decoders=(("recovery_burns_json", "recovery_burns", json_list),), rows_key="cases",
    text=format_rows)
