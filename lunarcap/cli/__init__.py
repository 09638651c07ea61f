"""Command-line interface: ``lunarcap <command> ...`` (also ``python -m lunarcap``).

Every user error (bad input, a failed solve) prints one line ``lunarcap: error: ...``
to stderr and exits with status 2 (bad input) or 3 (solve failed); nothing already
written is lost.
"""

from __future__ import annotations

import contextlib
import json
import math
import sys

from lunarcap.cli import parser as cli_parser
from lunarcap.errors import InputError, LunarcapError, SolveError, integer, number, number_list
from lunarcap.physics.constants import R_MOON


def _jsonable(obj):
    if isinstance(obj, dict):
        return {k: _jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [_jsonable(v) for v in obj]
    if hasattr(obj, "item"):
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj


#: The plan field each overriding option sets, to name the option when the plan refuses it.
_OVERRIDES = {"--thrust": ("thrust", "engine.thrust_N"), "--isp": ("isp", "engine.isp_s"),
              "--mass": ("mass", "arrival.mass_kg"), "--starts": ("starts", "burns[")}


def _plan_from_args(args):
    """The plan named by the arguments, with their overrides applied.

    A value the plan refuses because of an option is reported with the option first:
    ``--mass (arrival.mass_kg): 700000 kg is above ...``.
    """
    from lunarcap.mission.plan import PlanError, load_plan

    source = getattr(args, "plan", None)
    plan = None if source is None else load_plan(source)
    try:
        return _with_overrides(plan, args)
    except PlanError as exc:
        msg = str(exc)
        for opt, (dest, field) in _OVERRIDES.items():
            if getattr(args, dest, None) is not None and msg.startswith(field):
                raise PlanError(f"{opt} ({msg.split(': ', 1)[0]}): {msg.split(': ', 1)[1]}") \
                    from None
        raise


def _with_overrides(plan, args):
    from dataclasses import replace
    from pathlib import Path

    from lunarcap.mission.plan import paper_plan

    if plan is None:
        plan = paper_plan(args.thrust or 150.0, args.isp or 200.0)
    elif args.thrust is not None or args.isp is not None:
        plan = plan.with_engine(args.thrust or plan.engine.thrust_N,
                                args.isp or plan.engine.isp_s, name=plan.name)
    arrival = plan.arrival
    if args.mass is not None:
        arrival = replace(arrival, mass_kg=args.mass)
    if args.hemisphere is not None:
        arrival = replace(arrival, hemisphere=args.hemisphere)
    if arrival != plan.arrival:
        plan = replace(plan, arrival=arrival)
    if args.dynamics is not None:
        plan = plan.with_dynamics(args.dynamics)
    if args.ephemeris is not None:
        plan = replace(plan, ephemeris=str(Path(args.ephemeris).expanduser().resolve()))
    if args.lunar_pole is not None:
        plan = plan.with_lunar_pole(args.lunar_pole)
    if getattr(args, "starts", None) is not None:
        plan = plan.with_starts(args.starts)
    return plan


def cmd_impulsive(args) -> int:
    """Print the plan's two-body impulsive chain and Eq. (19) estimates."""
    plan = _plan_from_args(args)
    burns = plan.impulsive()
    rows = [{"burn": b.burn, "impulsive_delta_v_two_body_mps": b.delta_v_mps,
             "period_before_h": b.period_before_h, "period_after_h": b.period_after_h,
             "v_perilune_before_kmps": b.v_before_kmps, "v_perilune_after_kmps": b.v_after_kmps,
             "m_before_kg": b.m_before_kg, "m_after_kg": b.m_after_kg, "fuel_kg": b.fuel_kg,
             "eq19_duration_min": b.eq19_duration_min} for b in burns]
    if args.json:
        out = {"plan": plan.name, "thrust_N": plan.engine.thrust_N, "isp_s": plan.engine.isp_s,
               "mass_kg": plan.arrival.mass_kg, "v_inf_kmps": plan.arrival.v_inf_kmps,
               "total_impulsive_delta_v_two_body_mps":
                   sum(r["impulsive_delta_v_two_body_mps"] for r in rows), "burns": rows}
        print(json.dumps(_jsonable(out), indent=2))
        return 0
    print(f"Two-body impulsive capture of plan {plan.name}: {plan.engine.thrust_N:g} N / "
          f"{plan.engine.isp_s:g} s, {plan.arrival.mass_kg:g} kg at arrival, v_inf "
          f"{plan.arrival.v_inf_kmps:.5f} km/s")
    print(f"{'burn':>4} {'dV m/s':>9} {'P after h':>9} {'m before kg':>11} {'m after kg':>10} "
          f"{'fuel kg':>8} {'Eq.19 min':>9}")
    for r in rows:
        print(f"{r['burn']:>4} {r['impulsive_delta_v_two_body_mps']:9.3f} "
              f"{r['period_after_h']:9.3f} "
              f"{r['m_before_kg']:11.3f} {r['m_after_kg']:10.3f} {r['fuel_kg']:8.3f} "
              f"{r['eq19_duration_min']:9.2f}")
    print(f"total {sum(r['impulsive_delta_v_two_body_mps'] for r in rows):.3f} m/s")
    return 0



def _fmt(v, spec: str, width: int) -> str:
    return f"{'—':>{width}}" if v is None else f"{v:{width}{spec}}"


def _target_width(plan) -> int:
    return max(6, *(len(b.describe()) for b in plan.burns))


def _print_plan_header(plan) -> None:
    a = plan.arrival
    print(f"Plan {plan.name}: {plan.engine.thrust_N:g} N / {plan.engine.isp_s:g} s, "
          f"{plan.dynamics} dynamics, {plan.n_burns} burn(s); arrival {a.epoch}, perilune "
          f"{a.perilune_altitude_km:g} km, inclination {a.inclination_deg:g} deg, "
          f"v_inf {a.v_inf_kmps:.5f} km/s, {a.mass_kg:g} kg; M-MME2000 pole {plan.lunar_pole}")
    print(f"{'burn':>4}  {'target':<{_target_width(plan)}} {'ignition (TDB)':<27} {'start min':>9} "
          f"{'dur min':>7} {'dV m/s':>9} {'imp m/s':>9} {'loss m/s':>8} {'loss %':>6} "
          f"{'m start kg':>10} {'m end kg':>9}  verification", flush=True)


def _print_burn_row(plan, r: dict) -> None:
    b = plan.burns[r["burn"] - 1]
    ver = ("passed" if r["verification_passed"] else "FAILED") + \
        f" (rp {r['verification_rp_error_m']:.2g} m, i {r['verification_inc_error_deg']:.1g} deg"
    if r["verification_gamma_error_deg"] is not None:
        ver += f", gamma {r['verification_gamma_error_deg']:.1g} deg"
    if r["verification_ra_error_m"] is not None:
        ver += f", ra {r['verification_ra_error_m']:.2g} m"
    if r.get("verification_period_error_s") is not None:
        ver += f", period {r['verification_period_error_s']:.2g} s"
    ver += ")"
    print(f"{r['burn']:>4}  {b.describe():<{_target_width(plan)}} {r['ignition_epoch']:<27} "
          f"{r['start_min']:9.3f} "
          f"{r['burn_duration_min']:7.2f} {r['delta_v_mps']:9.3f} "
          f"{_fmt(r['impulsive_limit_mps'], '.3f', 9)} {_fmt(r['delta_v_loss_mps'], '.3f', 8)} "
          f"{_fmt(r['delta_v_loss_percent'], '.2f', 6)} {r['m_start_kg']:10.3f} "
          f"{r['m_end_kg']:9.3f}  "
          f"{ver}", flush=True)


def _print_totals(tot: dict) -> None:
    loss = "" if tot["total_delta_v_loss_mps"] is None else \
        (f", impulsive {tot['total_impulsive_limit_mps']:.3f} m/s, loss "
         f"{tot['total_delta_v_loss_mps']:.3f} m/s ({tot['total_delta_v_loss_percent']:.2f} %)")
    print(f"total: dV {tot['total_delta_v_mps']:.3f} m/s{loss}; burns "
          f"{tot['total_burn_duration_min']:.2f} min; fuel {tot['total_fuel_kg']:.3f} kg, final "
          f"mass {tot['final_mass_kg']:.3f} kg; final orbit {tot['final_rp_km'] - R_MOON:.1f} x "
          f"{tot['final_ra_km'] - R_MOON:.1f} km altitude, {tot['final_inc_deg']:.4f} deg, "
          f"reached "
          f"{tot['final_orbit_epoch']} (end of the last burn, {tot['time_to_final_orbit_h']:.2f} h "
          f"after the arrival perilune)")


def cmd_plan(args) -> int:
    """Solve and verify every burn of a capture plan; print each burn and the totals."""
    from lunarcap.capture.chain import PlanResult, after_capture, plan_result

    plan = _plan_from_args(args)
    if args.export:   # before any solve: a directory that cannot be written is refused
        from lunarcap.capture.export import check_export_dir

        check_export_dir(args.export, "--export")
    done, after = [], None

    def on_burn(b):
        done.append(b)
        if not args.json:
            _print_burn_row(plan, b.row())

    if not args.json:
        _print_plan_header(plan)
    try:
        res = plan_result(plan, impulsive=not args.no_impulsive, verbose=not args.quiet,
                          on_burn=on_burn)
        if args.after_days and res.totals()["all_verified"]:
            after = after_capture(res, args.after_days)
    finally:
        if args.json:
            partial = PlanResult(plan, done)
            out = {"plan": plan.to_dict(), "complete": len(done) == plan.n_burns,
                   "burns": [b.row() | {"target_orbit": plan.burns[i].describe()}
                             for i, b in enumerate(done)],
                   "totals": partial.totals() if done else None}
            if args.after_days:
                out["after"] = after.to_dict() if after is not None else None
            print(json.dumps(_jsonable(out), indent=2))
    if not args.json:
        _print_totals(res.totals())
        if after is not None:
            _print_after(after)
    if args.export:
        if all(b.solution.verification.passed for b in res.burns):
            _export_plan(res, args, after)
        else:
            print("lunarcap: error: not exported: a burn failed verification", file=sys.stderr)
            return 3
    return 0 if res.totals()["all_verified"] else 3


def _print_after(after) -> None:
    """The final orbit's evolution (``--after-days``): its extremes and first and last turns."""
    s = after.summary()
    print(f"\nAfter the capture: {after.days:g} days in {after.forces} dynamics, "
          f"{s['after_revolutions']} revolutions")
    print(f"  lowest perilune {s['after_min_perilune_altitude_km']:.3f} km, highest apolune "
          f"{s['after_max_apolune_altitude_km']:.3f} km, inclination change "
          f"{s['after_inclination_change_deg']:+.4f} deg")
    for label, j in (("first", 0), ("last", -1)):
        print(f"  {label} revolution: {after.perilune_altitude_km[j]:.3f} x "
              f"{after.apolune_altitude_km[j]:.3f} km, inclination "
              f"{after.inclination_deg[j]:.4f} deg")


def _export_plan(res, args, after=None) -> None:
    """Write the plan's OEM, SPK, attitude and maneuver files (``--export DIR``).

    With ``after`` (``--after-days``), the OEM and the SPK go on to its end.
    """
    from lunarcap.capture.export import export_plan

    ex = export_plan(res, args.export, time_system=args.time_system, object_id=args.spk_id,
                     after=after)
    out = sys.stderr if args.json else sys.stdout
    print(f"Exported in {ex.seconds:.2f} s ({ex.time_system}, SPK object ID {ex.object_id}; "
          f"OEM interpolation within {ex.max_interpolation_error_m:.2g} m):", file=out)
    for kind, path in ex.files.items():
        print(f"  {path}  {ex.sizes_bytes[kind]:,} bytes", file=out)
    for line in ex.reference:   # also at the head of every file
        print(f"  {line}", file=out)


def cmd_solve(args) -> int:
    """Solve one burn of a plan (its earlier burns are solved or fetched first)."""
    from lunarcap.capture.chain import (
        BurnResult,
        impulsive_limit,
        labelled,
        prebuild_for,
        reuse_earlier_burns,
        solve_burn,
    )

    plan = _plan_from_args(args)
    n = args.burn
    if n > plan.n_burns:
        raise InputError(f"--burn {n}: plan {plan.name} has burns 1 to {plan.n_burns}")
    prev = args.previous_starts
    if prev is not None:
        if len(prev) != n - 1:
            raise InputError(f"--previous-starts needs {n - 1} offset(s) for burn {n}, "
                             f"got {len(prev)}")
        for j, s in enumerate(prev):
            plan = plan.with_start(j, s)
    if args.start is not None:
        plan = plan.with_start(n - 1, args.start)
    if args.steering != "optimal":
        plan = plan.with_steering(n - 1, args.steering)
    key = plan.key(n)
    verbose = not args.quiet
    prebuild_for(key, [n], impulsive=not args.no_impulsive, verbose=verbose)
    with reuse_earlier_burns(), labelled(plan):
        sol = solve_burn(key, verbose=verbose)
        imp = None if args.no_impulsive else impulsive_limit(key, verbose=verbose)
    r = BurnResult(sol, imp)
    if args.json:
        out = sol.to_dict()
        row = r.row()
        for k in ("impulsive_limit_mps", "delta_v_loss_mps", "delta_v_loss_percent",
                  "objective_loss_mps"):
            out[k] = row[k]
        out["target_orbit"] = plan.burns[n - 1].describe()
        out["plan"] = plan.name
        out["previous_starts_min"] = [b.start_min for b in plan.burns[:n - 1]]
        print(json.dumps(_jsonable(out), indent=2))
    else:
        _print_plan_header(plan)
        _print_burn_row(plan, r.row())
    return 0 if sol.verification.passed else 3


def cmd_bench(args) -> int:
    """Solve and verify all 37 paper cases uncached; print timings and residuals."""
    from lunarcap.studies.bench import run, warm_solves

    if args.studies:
        from lunarcap.studies.bench import studies

        studies(cold=not args.no_cold)
        return 0
    if args.warm:
        rows = warm_solves(args.dynamics or "two-body", args.repeats)
        return 0 if all(r["verified"] for r in rows) else 3
    rows = run(args.dynamics or "full", reuse=not args.resolve_earlier)
    return 0 if all(r["verification_passed"] for r in rows) else 3


def cmd_plans(args) -> int:
    """List the packaged plans, or print one as YAML."""
    from lunarcap.mission.plan import available_plans, load_plan

    if args.name is None:
        for name in available_plans():
            plan = load_plan(name)
            print(f"{name:<16} {plan.description or plan.name}")
        return 0
    print(load_plan(args.name).to_yaml(), end="")
    return 0


def _resumable(run, unit: str):
    """``(run(), None)``, or ``(None, 130)`` after Ctrl-C.

    On Ctrl-C one line says that the finished ``unit`` are in the study's table, which
    keeps every finished case, so running the same command again resumes.
    """
    try:
        return run(), None
    except KeyboardInterrupt:
        print(f"lunarcap: interrupted; finished {unit} are in the table, run the same command "
              "again to resume", file=sys.stderr)
        return None, 130


def run_study(args, study, run, head: dict | None = None, extra=None, **context) -> int:
    """Run any study (a :class:`lunarcap.studies.study.Study`) and report it; the exit status.

    ``run()``: the study's run (resumable: Ctrl-C is one line, status 130); then its
    ``--json`` document (``head``, the table and run, ``extra(result)``, the decoded rows)
    or its text (``study.text(result, **context)``). Status 0 when every case has an
    answer (a status of ``study.ok_statuses``), 3 otherwise.
    """
    res, status = _resumable(run, study.units)
    if status:
        return status
    if getattr(args, "json", False):
        doc = study.to_json(res, head or {}, extra(res) if extra else None)
        print(json.dumps(_jsonable(doc), indent=2))
    else:
        print(study.text(res, **context))
    return 0 if study.answered(res.table.to_dict("records")) else 3


def cmd_study(args) -> int:
    """Engine trade study on Dask: loss against thrust-to-weight, free ignition, per Isp."""
    from lunarcap.studies.engine_trade import trade as study

    spec = study.StudySpec(args.thrust_min, args.thrust_max, args.points, args.isp,
                           args.dynamics)
    return run_study(args, study.STUDY, lambda: study.run_study(
        spec, out=args.out, workers=args.workers, scheduler=args.scheduler,
        retry_failed=args.retry_failed, progress=not args.no_progress))


def cmd_burns(args) -> int:
    """How many capture burns: the plan's capture in N burns, the periods optimised."""
    from lunarcap.studies.burn_count import counts as burns

    plan = _plan_from_args(args)
    counts = burns.parse_counts(args.counts)
    max_period_h = number("--max-period-h", args.max_period_h, "h", positive=True)
    max_days = number("--max-days", args.max_days, "days", positive=True)
    return run_study(args, burns.STUDY, lambda: burns.run_burns(
        [plan], counts, max_period_h, max_days, out=args.out, workers=args.workers,
        scheduler=args.scheduler, progress=not args.no_progress),
        {"plan": plan.to_dict(), "max_period_h": max_period_h, "max_days": max_days},
        plan=plan)


def cmd_missed(args) -> int:
    """Missed thrust: the engine stops during a burn; the rest re-planned and re-optimised."""
    from lunarcap.studies.missed import cases as missed

    plan = _plan_from_args(args)
    burn = integer("--burn", args.burn, minimum=1)
    max_period_h = number("--max-period-h", args.max_period_h, "h", positive=True)
    fractions = args.fractions
    if fractions is None:   # the default cut-offs, unless only late ignitions are asked
        fractions = None if args.late_min else "0.25,0.5,0.75,0.9"
    if fractions is not None:
        fractions = number_list("--fractions", fractions, "", positive=True, maximum=1.0,
                                distinct=True)
    delays = number_list("--delays-min", args.delays_min, "min", minimum=0.0, distinct=True)
    late = None if args.late_min is None else \
        number_list("--late-min", args.late_min, "min", minimum=0.0, distinct=True)
    return run_study(args, missed.STUDY, lambda: missed.run_missed(
        plan, burn, fractions, delays, max_period_h, out=args.out,
        workers=args.workers, scheduler=args.scheduler, progress=not args.no_progress,
        late_min=late), {"plan": plan.to_dict(), "burn": burn, "max_period_h": max_period_h},
        plan=plan, burn=burn)


def cmd_dispersions(args) -> int:
    """Dispersions: the capture flown with errors, re-planned after each burn; the budget."""
    from lunarcap.studies.dispersions import samples as disp

    plan = _plan_from_args(args)
    if args.formulation is not None and args.formulation != plan.formulation:
        from dataclasses import replace

        plan = replace(plan, formulation=args.formulation)
    samples = integer("--samples", args.samples, minimum=1)
    seed = integer("--seed", args.seed, minimum=0)
    covs = {name: disp.read_covariance(getattr(args, name), name)
            for name in ("arrival_cov", "knowledge_cov", "bplane_cov")
            if getattr(args, name) is not None}
    model = disp.ErrorModel(**{name: number("--" + name.replace("_", "-"), getattr(args, name),
                                              "", minimum=0.0) for name in disp.SIGMAS},
                            **covs)
    if args.sensitivity:
        return _dispersion_sensitivity(args, plan, samples, seed, model)
    return run_study(args, disp.STUDY, lambda: disp.run_dispersions(
        plan, samples, seed, model, out=args.out, workers=args.workers,
        scheduler=args.scheduler, progress=not args.no_progress),
        {"plan": plan.to_dict(),
         "error_model": model.key() | {"description": model.describe()}, "seed": seed},
        lambda res: {"summary": disp.summarise(res.table.to_dict("records"))},
        plan=plan, model=model)


def _dispersion_sensitivity(args, plan, samples: int, seed: int, model) -> int:
    """``lunarcap dispersions --sensitivity``: each sigma alone at 0.5, 1, 2 times its value."""
    from lunarcap.studies.dispersions import samples as disp
    from lunarcap.studies.dispersions import sensitivity as sens

    out, status = _resumable(lambda: sens.run_sensitivity(
        plan, samples, seed, model, out=args.out, workers=args.workers,
        scheduler=args.scheduler, progress=not args.no_progress), "samples")
    if status:
        return status
    models, res = out
    rows = sens.sensitivity_rows(res.table, models)
    if args.json:
        print(json.dumps(_jsonable({"plan": plan.to_dict(), "seed": seed,
                                    "table": str(res.path), "run": res.run,
                                    "sensitivity": rows, "laws": sens.slopes(rows)}),
                         indent=2))
    else:
        print(sens.format_sensitivity(plan, rows, res))
    return 0 if all(s in disp.OK_STATUSES for s in res.table.status) else 3


def build_parser():
    """The argument parser of every subcommand (:func:`lunarcap.cli.parser.build_parser`)."""
    return cli_parser.build_parser(_commands(), __doc__.splitlines()[0])


def _commands() -> dict:
    return {"plan": cmd_plan, "solve": cmd_solve, "impulsive": cmd_impulsive,
            "plans": cmd_plans, "bench": cmd_bench, "study": cmd_study, "burns": cmd_burns,
            "missed": cmd_missed, "dispersions": cmd_dispersions}


@contextlib.contextmanager
def _interrupt_outside_casadi():
    """Within the block, Ctrl-C raises KeyboardInterrupt, but never inside a CasADi call.

    CasADi checks for Ctrl-C during IPOPT and CVODES, and turns the KeyboardInterrupt it
    finds into a solver status (``NonIpopt_Exception_Thrown``) and a ``CasADi - WARNING``
    line; the command then carried on with the next mesh, or ended in a "failed solve".
    Here a SIGINT that arrives within a CasADi call (the handler's frame is CasADi's
    Python wrapper) is raised 0.1 s after the call returns (SIGALRM rechecks). Main
    thread only; the previous handlers are restored at the end.
    """
    import os
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def handler(signum, frame):
        if frame is not None and f"{os.sep}casadi{os.sep}" in frame.f_code.co_filename:
            signal.setitimer(signal.ITIMER_REAL, 0.1)  # again once the call has returned
            return
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        raise KeyboardInterrupt

    old = {s: signal.signal(s, handler) for s in (signal.SIGINT, signal.SIGALRM)}
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0.0)
        for s, h in old.items():
            signal.signal(s, h)


def main(argv=None) -> int:
    """Entry point; returns the exit status."""
    args = cli_parser.parse_args(_commands(), __doc__.splitlines()[0], argv)
    code = _run(args)
    if code == 130:
        _leave_abandoned_calls()
    return code


def _leave_abandoned_calls() -> None:
    """After Ctrl-C, exit at once (status 130) if a CasADi call still runs in a thread.

    Such a call (an NLP build, an IPOPT solve: :mod:`lunarcap.optim.interrupt`) may last
    seconds more, and tearing the interpreter down under it crashes (a segmentation fault
    instead of status 130): the streams are flushed and the process leaves with
    ``os._exit``; every ``finally`` of the command has run.
    """
    import os

    from lunarcap.optim.interrupt import busy

    if busy():
        for stream in (sys.stdout, sys.stderr):
            with contextlib.suppress(Exception):
                stream.flush()
        os._exit(130)


def _run(args) -> int:
    """The command of ``args``, its errors turned into one line and an exit status."""
    from lunarcap.repro.cache import caching

    # --no-cache: the one cache switch, off for the whole command (studies ship its
    # position to their workers); without it the environment decides (LUNARCAP_NO_CACHE)
    no_cache = getattr(args, "no_cache", False)
    try:
        with _interrupt_outside_casadi(), caching(False) if no_cache else contextlib.nullcontext():
            return args.func(args)
    except BrokenPipeError:  # e.g. `lunarcap impulsive --json | head`
        import os
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0
    except InputError as exc:
        print(f"lunarcap: error: {exc}", file=sys.stderr)
        return 2
    except SolveError as exc:
        print(f"lunarcap: error: {exc}", file=sys.stderr)
        return 3
    except LunarcapError as exc:
        print(f"lunarcap: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:  # Ctrl-C (a study's says how to resume: _resumable)
        print("lunarcap: interrupted", file=sys.stderr)
        return 130
