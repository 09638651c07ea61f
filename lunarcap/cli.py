"""Command-line interface: ``lunarcap <command> ...`` (also ``python -m lunarcap``).

Every user error (bad input, a failed solve) prints one line ``lunarcap: error: ...``
to stderr and exits with status 2 (bad input) or 3 (solve failed); nothing already
written is lost.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import re
import sys

from lunarcap.errors import InputError, LunarcapError, SolveError


def _positive(kind: str, unit: str):
    def conv(text: str) -> float:
        try:
            val = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{kind} must be a number of {unit}, got {text!r}")
        if not math.isfinite(val) or val <= 0:
            raise argparse.ArgumentTypeError(f"{kind} must be positive ({unit}), got {text!r}")
        return val
    return conv


def _burn_number(text: str) -> int:
    try:
        val = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"a burn number is an integer from 1, got {text!r}")
    if val < 1:
        raise argparse.ArgumentTypeError(f"a burn number is an integer from 1, got {text!r}")
    return val


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


def _starts(text: str) -> tuple:
    """Comma-separated ignition offsets (min) or 'free'."""
    try:
        vals = tuple("free" if s.strip() == "free" else float(s)
                     for s in text.split(",") if s.strip())
    except ValueError:
        raise argparse.ArgumentTypeError(f"start offsets must be numbers of minutes (or 'free') "
                                         f"separated by commas, got {text!r}")
    if not vals or not all(v == "free" or math.isfinite(v) for v in vals):
        raise argparse.ArgumentTypeError(f"start offsets must be finite numbers, got {text!r}")
    return vals


def _start(text: str):
    vals = _starts(text)
    if len(vals) != 1:
        raise argparse.ArgumentTypeError(f"one start offset (min) expected, got {text!r}")
    return vals[0]


# ---------------------------------------------------------------------- plans
def _add_plan_options(p: argparse.ArgumentParser, plan_positional: bool) -> None:
    if plan_positional:
        p.add_argument("plan", metavar="PLAN",
                       help="a plan file (YAML) or the name of a packaged plan (list them "
                            "with `lunarcap plans`)")
    else:
        p.add_argument("--plan", default=None, metavar="PLAN",
                       help="a plan file (YAML) or packaged plan name (default: the paper's "
                            "capture with the engine of --thrust and --isp)")
    p.add_argument("--thrust", type=_positive("thrust", "N"), default=None,
                   help="engine thrust, N (overrides the plan's; default 150)")
    p.add_argument("--isp", type=_positive("Isp", "s"), default=None,
                   help="specific impulse, s (overrides the plan's; default 200)")
    p.add_argument("--mass", type=_positive("mass", "kg"), default=None,
                   help="mass at the first perilune, kg (overrides the plan's)")
    p.add_argument("--dynamics", choices=["full", "j2", "two-body"], default=None,
                   help="perturbations: full (J2, Earth, Sun), j2, or two-body (overrides the "
                        "plan's)")
    p.add_argument("--hemisphere", choices=["north", "south"], default=None,
                   help="lunar hemisphere of the arrival perilune (overrides the plan's)")
    p.add_argument("--ephemeris", default=None, metavar="BSP",
                   help="SPK file (.bsp) instead of the plan's (default: the bundled DE405)")
    p.add_argument("--lunar-pole", choices=["iau2009-j2000", "iau-constant"], default=None,
                   help="the pole fixing M-MME2000: the IAU (2009) expression at J2000 "
                        "(default) or its constant terms only (overrides the plan's)")
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")


def _plan_from_args(args):
    """The plan named by the arguments, with their overrides applied."""
    from dataclasses import replace

    from lunarcap.mission.plan import load_plan, paper_plan

    source = getattr(args, "plan", None)
    if source is None:
        plan = paper_plan(args.thrust or 150.0, args.isp or 200.0)
    else:
        plan = load_plan(source)
        if args.thrust is not None or args.isp is not None:
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
        from pathlib import Path
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
          f"mass {tot['final_mass_kg']:.3f} kg; final orbit {tot['final_rp_km']:.1f} x "
          f"{tot['final_ra_km']:.1f} km, {tot['final_inc_deg']:.4f} deg, reached "
          f"{tot['final_orbit_epoch']} (end of the last burn, {tot['time_to_final_orbit_h']:.2f} h "
          f"after the arrival perilune)")


def cmd_plan(args) -> int:
    """Solve and verify every burn of a capture plan; print each burn and the totals."""
    from lunarcap.runs.chain import PlanResult, plan_result

    plan = _plan_from_args(args)
    done = []

    def on_burn(b):
        done.append(b)
        if not args.json:
            _print_burn_row(plan, b.row())

    if not args.json:
        _print_plan_header(plan)
    try:
        res = plan_result(plan, impulsive=not args.no_impulsive, verbose=not args.quiet,
                          use_cache=not args.no_cache, on_burn=on_burn)
    finally:
        if args.json:
            partial = PlanResult(plan, done)
            out = {"plan": plan.to_dict(), "complete": len(done) == plan.n_burns,
                   "burns": [b.row() | {"target_orbit": plan.burns[i].describe()}
                             for i, b in enumerate(done)],
                   "totals": partial.totals() if done else None}
            print(json.dumps(_jsonable(out), indent=2))
    if not args.json:
        _print_totals(res.totals())
    if args.export:
        if all(b.solution.verification.passed for b in res.burns):
            _export_plan(res, args)
        else:
            print("lunarcap: error: not exported: a burn failed verification", file=sys.stderr)
            return 3
    return 0 if res.totals()["all_verified"] else 3


def _export_plan(res, args) -> None:
    """Write the plan's OEM, SPK, attitude and maneuver files (``--export DIR``)."""
    from lunarcap.runs.export import export_plan

    ex = export_plan(res, args.export, time_system=args.time_system, object_id=args.spk_id)
    out = sys.stderr if args.json else sys.stdout
    print(f"Exported in {ex.seconds:.2f} s ({ex.time_system}, SPK object ID {ex.object_id}; "
          f"OEM interpolation within {ex.max_interpolation_error_m:.2g} m):", file=out)
    for kind, path in ex.files.items():
        print(f"  {path}  {ex.sizes_bytes[kind]:,} bytes", file=out)


def cmd_solve(args) -> int:
    """Solve one burn of a plan (its earlier burns are solved or fetched first)."""
    from lunarcap.runs.chain import BurnResult, impulsive_limit, prebuild_for, solve_burn

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
    prebuild_for(key, [n], impulsive=not args.no_impulsive, use_cache=not args.no_cache)
    sol = (solve_burn.uncached if args.no_cache else solve_burn)(key, verbose=verbose)
    imp = None
    if not args.no_impulsive:
        imp = impulsive_limit(key, verbose=verbose, use_cache=not args.no_cache)
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
    from lunarcap.runs.bench import run, warm_solves

    if args.studies:
        from lunarcap.runs.bench import studies

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


def cmd_study(args) -> int:
    """Engine trade study on Dask: loss against thrust-to-weight, free ignition, per Isp."""
    from lunarcap.runs.study import StudySpec, format_summary, run_study

    spec = StudySpec(args.thrust_min, args.thrust_max, args.points, args.isp, args.dynamics)
    res, status = _resumable(lambda: run_study(
        spec, out=args.out, workers=args.workers, scheduler=args.scheduler,
        retry_failed=args.retry_failed, progress=not args.no_progress), "engines")
    if status:
        return status
    print(format_summary(res))
    return 0 if res.failures.empty else 3


def _number_arg(option: str, text: str, unit: str) -> float:
    """A positive finite number from an option's text, else InputError naming the option."""
    try:
        val = float(text)
    except (TypeError, ValueError):
        raise InputError(f"{option} must be a positive number of {unit}, got {text!r}") \
            from None
    if not math.isfinite(val) or val <= 0:
        raise InputError(f"{option} must be a positive number of {unit}, got {text!r}")
    return val


def _periods_h(text) -> list:
    """The intermediate periods (h) of a burns-table cell ("8.365;3.5", empty or NaN)."""
    return [float(p) for p in text.split(";") if p] if isinstance(text, str) else []


def cmd_burns(args) -> int:
    """How many capture burns: the plan's capture in N burns, the periods optimised."""
    from lunarcap.runs import burns

    plan = _plan_from_args(args)
    counts = burns.parse_counts(args.counts)
    max_period_h = _number_arg("--max-period-h", args.max_period_h, "hours")
    max_days = _number_arg("--max-days", args.max_days, "days")
    res, status = _resumable(lambda: burns.run_burns(
        [plan], counts, max_period_h, max_days, out=args.out, workers=args.workers,
        scheduler=args.scheduler, progress=not args.no_progress, use_cache=not args.no_cache),
        "counts")
    if status:
        return status
    rows = res.table.to_dict("records")
    if args.json:
        out = {"plan": plan.to_dict(), "max_period_h": max_period_h, "max_days": max_days,
               "table": str(res.path), "run": res.run,
               "counts": [dict({k: v for k, v in r.items() if k != "burns_json"},
                               periods_h=_periods_h(r["periods_h"]), burns=burns.burns_of(r))
                          for r in rows]}
        print(json.dumps(_jsonable(out), indent=2))
    else:
        print(burns.format_rows(plan, rows, res))
    return 0 if all(r["status"] in ("ok", "infeasible") for r in rows) else 3


def cmd_missed(args) -> int:
    """Missed thrust: the engine stops during a burn; the rest re-planned and re-optimised."""
    from lunarcap.runs import missed

    plan = _plan_from_args(args)
    try:
        burn = int(args.burn)
    except ValueError:
        raise InputError(f"--burn must be a burn number from 1, got {args.burn!r}") from None
    max_period_h = _number_arg("--max-period-h", args.max_period_h, "hours")
    fractions = args.fractions
    if fractions is None:   # the default cut-offs, unless only late ignitions are asked
        fractions = None if args.late_min else "0.25,0.5,0.75,0.9"
    res, status = _resumable(lambda: missed.run_missed(
        plan, burn, fractions, args.delays_min, max_period_h, out=args.out,
        workers=args.workers, scheduler=args.scheduler, progress=not args.no_progress,
        use_cache=not args.no_cache, late_min=args.late_min), "cases")
    if status:
        return status
    rows = res.table.to_dict("records")
    if args.json:
        out = {"plan": plan.to_dict(), "burn": burn, "max_period_h": max_period_h,
               "table": str(res.path), "run": res.run,
               "cases": [dict({k: v for k, v in r.items() if k != "recovery_burns_json"},
                              recovery_burns=missed.recovery_burns_of(r)) for r in rows]}
        print(json.dumps(_jsonable(out), indent=2))
    else:
        print(missed.format_rows(plan, burn, rows, res))
    return 0 if all(r["status"] in ("recovered", "no recovery") for r in rows) else 3


def _sigma_arg(option: str, text) -> float:
    """A non-negative finite number from an option's text, else InputError naming it."""
    try:
        val = float(text)
    except (TypeError, ValueError):
        raise InputError(f"{option} must be a non-negative number, got {text!r}") from None
    if not math.isfinite(val) or val < 0:
        raise InputError(f"{option} must be a non-negative number, got {text!r}")
    return val


def cmd_dispersions(args) -> int:
    """Dispersions: the capture flown with errors, re-planned after each burn; the budget."""
    from lunarcap.runs import dispersions as disp

    plan = _plan_from_args(args)
    if args.formulation is not None and args.formulation != plan.formulation:
        from dataclasses import replace

        plan = replace(plan, formulation=args.formulation)
    samples, seed = disp.check_samples(args.samples, args.seed)
    cov = None
    if args.arrival_cov is not None:
        cov = disp.read_covariance(args.arrival_cov)
    model = disp.ErrorModel(**{name: _sigma_arg("--" + name.replace("_", "-"),
                                                 getattr(args, name))
                               for name in ("thrust_sigma_pct", "isp_sigma_pct",
                                            "pointing_sigma_deg", "ignition_sigma_s",
                                            "arrival_sigma_km", "arrival_sigma_mps")},
                            arrival_cov=cov)
    res, status = _resumable(lambda: disp.run_dispersions(
        plan, samples, seed, model, out=args.out, workers=args.workers,
        scheduler=args.scheduler, progress=not args.no_progress,
        use_cache=not args.no_cache), "samples")
    if status:
        return status
    rows = res.table.to_dict("records")
    summary = disp.summarise(rows)
    if args.json:
        out = {"plan": plan.to_dict(), "error_model": model.key() | {
                   "description": model.describe()},
               "seed": seed, "table": str(res.path), "run": res.run, "summary": summary,
               "samples": [dict({k: v for k, v in r.items() if k != "burns_json"},
                                burns=disp.burns_of(r)) for r in rows]}
        print(json.dumps(_jsonable(out), indent=2))
    else:
        print(disp.format_summary(plan, model, summary, res))
    return 0 if all(r["status"] in disp.OK_STATUSES for r in rows) else 3


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of every subcommand."""
    parser = argparse.ArgumentParser(prog="lunarcap", description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)

    p = sub.add_parser("plan", help="solve and verify every burn of a capture plan")
    _add_plan_options(p, plan_positional=True)
    p.add_argument("--starts", type=_starts, default=None, metavar="S1,S2,...",
                   help="ignition offsets of every burn, min from perilune (or 'free'), "
                        "overriding the plan's")
    p.add_argument("--no-impulsive", action="store_true",
                   help="skip the impulsive limits in the same dynamics (no loss column)")
    p.add_argument("--no-cache", action="store_true", help="recompute, ignoring the disk cache")
    p.add_argument("--quiet", action="store_true", help="no progress lines on stderr")
    p.add_argument("--export", default=None, metavar="DIR",
                   help="write the verified capture to DIR for other tools: <name>.oem (CCSDS "
                        "OEM), <name>.bsp (SPICE SPK), <name>_attitude.csv, "
                        "<name>_maneuvers.csv (Moon-centred ICRF)")
    p.add_argument("--time-system", choices=["TDB", "UTC"], default="TDB",
                   type=str.upper, help="time scale of the exported epochs (default TDB; "
                                        "the SPK is always in ET = TDB)")
    p.add_argument("--spk-id", type=int, default=-310001, metavar="ID",
                   help="NAIF ID of the spacecraft in the exported SPK and OEM (default "
                        "-310001)")
    p.set_defaults(func=cmd_plan)

    p = sub.add_parser("solve", help="optimal finite burn of one burn of a plan, verified")
    _add_plan_options(p, plan_positional=False)
    p.add_argument("--burn", "--loi", dest="burn", type=_burn_number, default=1,
                   help="burn number, from 1 (--loi is the same)")
    p.add_argument("--start", type=_start, default=None,
                   help="ignition, minutes from the nominal perilune (negative: before), or "
                        "'free' to optimise it (default: the plan's)")
    p.add_argument("--previous-starts", type=_starts, default=None, metavar="S1[,S2...]",
                   help="ignition offsets of the earlier burns (default: the plan's)")
    p.add_argument("--steering", choices=["optimal", "inertial", "antivelocity"],
                   default="optimal", help="steering law of this burn (earlier burns: the plan's)")
    p.add_argument("--no-impulsive", action="store_true",
                   help="skip the impulsive limit in the same dynamics (no loss)")
    p.add_argument("--no-cache", action="store_true", help="recompute, ignoring the disk cache")
    p.add_argument("--quiet", action="store_true", help="no progress lines on stderr")
    p.set_defaults(func=cmd_solve)

    p = sub.add_parser("impulsive", help="a plan's two-body impulsive chain and Eq. (19)")
    _add_plan_options(p, plan_positional=False)
    p.set_defaults(func=cmd_impulsive)

    p = sub.add_parser("plans", help="list the packaged plans, or print one as YAML")
    p.add_argument("name", nargs="?", default=None, help="a packaged plan to print")
    p.set_defaults(func=cmd_plans)

    p = sub.add_parser("bench", help="solve and verify all 37 paper cases, print timings")
    p.add_argument("--dynamics", choices=["full", "j2", "two-body"], default=None,
                   help="dynamics (default: full; with --warm, two-body)")
    p.add_argument("--warm", action="store_true",
                   help="instead: warm verified solves of the dymos peer benchmark's cases")
    p.add_argument("--repeats", type=int, default=5, help="warm solves per case (--warm)")
    p.add_argument("--studies", action="store_true",
                   help="instead: figures on where the time goes (NLP builds per shape, cold "
                        "and cached `lunarcap plan`, a trade-study engine, study walls)")
    p.add_argument("--no-cold", action="store_true",
                   help="with --studies: skip the cold `lunarcap plan` runs")
    p.add_argument("--resolve-earlier", action="store_true",
                   help="solve each case's earlier burns again (default: once per run)")
    p.set_defaults(func=cmd_bench)

    p = sub.add_parser("study", help="engine trade study: loss vs thrust-to-weight on Dask")
    p.add_argument("--thrust-min", default="50", metavar="N", help="lowest thrust, N (50)")
    p.add_argument("--thrust-max", default="2000", metavar="N", help="highest thrust, N (2000)")
    p.add_argument("--points", default="30", metavar="K", help="log-spaced thrusts (30)")
    p.add_argument("--isp", default="200,250,300", metavar="S1,S2,...",
                   help="specific impulses, s (200,250,300)")
    p.add_argument("--workers", default="2", metavar="W",
                   help="local Dask worker processes, one thread each (2)")
    p.add_argument("--scheduler", default=None, metavar="ADDR",
                   help="address of an existing Dask scheduler instead of a local cluster")
    p.add_argument("--out", default=None, metavar="PATH",
                   help="CSV table, appended as engines finish and resumed on rerun "
                        "(default .cache/study/engine_trade.csv)")
    p.add_argument("--dynamics", choices=["full", "j2", "two-body"], default="full")
    p.add_argument("--retry-failed", action="store_true",
                   help="recompute engines that failed in an earlier run")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.set_defaults(func=cmd_study)

    p = sub.add_parser("burns", help="how many capture burns: N burns, periods optimised")
    _add_plan_options(p, plan_positional=True)
    p.add_argument("--counts", default="1,2,3,4,5", metavar="N1,N2,...",
                   help="numbers of burns to try (1,2,3,4,5)")
    p.add_argument("--max-period-h", default="12.235", metavar="H",
                   help="longest intermediate period, h (12.235)")
    p.add_argument("--max-days", default="3", metavar="D",
                   help="longest time from the arrival perilune to the end of the last burn, "
                        "days (3)")
    _add_dask_options(p, "count")
    p.set_defaults(func=cmd_burns)

    p = sub.add_parser("missed", help="missed thrust or late ignition: a burn gone wrong, "
                                      "the capture re-planned")
    _add_plan_options(p, plan_positional=True)
    p.add_argument("--burn", default="1", metavar="N", help="the burn cut short (1)")
    p.add_argument("--fractions", default=None, metavar="F1,F2,...",
                   help="fractions of the burn flown before the engine stops, in (0, 1] "
                        "(0.25,0.5,0.75,0.9; none if only --late-min is given)")
    p.add_argument("--delays-min", default="0,30,120,720", metavar="D1,D2,...",
                   help="minutes from the cut-off to the recovery window (0,30,120,720)")
    p.add_argument("--late-min", default=None, metavar="L1,L2,...",
                   help="late ignition: the burn ignites these minutes after its planned "
                        "ignition, is re-optimised from there and the later burns re-planned")
    p.add_argument("--max-period-h", default="24", metavar="H",
                   help="longest period of the orbit after the burn, in the recovery and "
                        "in the nominal it is compared with, h (24)")
    _add_dask_options(p, "case")
    p.set_defaults(func=cmd_missed)

    p = sub.add_parser("dispersions", help="the capture's delta-V budget under execution and "
                                           "arrival errors (Monte Carlo, closed loop)")
    _add_plan_options(p, plan_positional=True)
    p.add_argument("--samples", default="100", metavar="N", help="samples (100)")
    p.add_argument("--seed", default="0", metavar="S",
                   help="seed: sample k draws its errors from numpy's generator seeded by "
                        "(S, k), the same whatever the sigmas (0)")
    for opt, unit, what in (
            ("--thrust-sigma-pct", "%", "thrust, per burn"),
            ("--isp-sigma-pct", "%", "specific impulse, per burn"),
            ("--pointing-sigma-deg", "deg", "each of two tilt angles of the thrust "
                                            "direction, fixed over a burn"),
            ("--ignition-sigma-s", "s", "ignition epoch, per burn"),
            ("--arrival-sigma-km", "km", "arrival position, per RTN axis"),
            ("--arrival-sigma-mps", "m/s", "arrival velocity, per RTN axis")):
        p.add_argument(opt, default="0", metavar=unit.upper().replace("/", "").replace("%",
                                                                                        "PCT"),
                       help=f"1-sigma error of the {what}, {unit} (0)")
    p.add_argument("--arrival-cov", default=None, metavar="FILE",
                   help="instead of --arrival-sigma-*: a 6x6 covariance of the arrival state "
                        "in its RTN frame, km and km/s (36 numbers, whitespace or commas)")
    p.add_argument("--formulation", choices=["orbit", "song2011"], default=None,
                   help="how the re-planned burns meet a period: orbit (the orbit asked, its "
                        "perilune epoch free) or song2011 (the paper's: at the plan's nominal "
                        "perilune epochs, a fixed timeline); default the plan's")
    _add_dask_options(p, "sample")
    p.set_defaults(func=cmd_dispersions)
    return parser


def _add_dask_options(p: argparse.ArgumentParser, what: str) -> None:
    p.add_argument("--workers", default="2", metavar="W",
                   help="local Dask worker processes, one thread each (2)")
    p.add_argument("--scheduler", default=None, metavar="ADDR",
                   help="address of an existing Dask scheduler instead of a local cluster")
    p.add_argument("--out", default=None, metavar="PATH",
                   help=f"CSV table, appended as each {what} finishes and resumed on rerun "
                        f"(default below .cache/study/)")
    p.add_argument("--no-cache", action="store_true",
                   help="recompute every case, ignoring the disk cache and the table")
    p.add_argument("--no-progress", action="store_true", help="no progress bar")


_LIST_OPTIONS = ("--starts", "--previous-starts", "--start", "--counts", "--fractions",
                 "--delays-min", "--max-period-h", "--max-days", "--burn", "--workers",
                 "--samples", "--seed", "--thrust-sigma-pct", "--isp-sigma-pct",
                 "--pointing-sigma-deg", "--ignition-sigma-s", "--arrival-sigma-km",
                 "--arrival-sigma-mps")


def _join_negative_lists(argv: list) -> list:
    """Let ``--starts -10,-6,-5`` work: argparse would take '-10,-6,-5' for an option."""
    out = []
    i = 0
    while i < len(argv):
        a = argv[i]
        if a in _LIST_OPTIONS and i + 1 < len(argv) and re.match(r"^-\d", argv[i + 1]):
            out.append(f"{a}={argv[i + 1]}")
            i += 2
            continue
        out.append(a)
        i += 1
    return out


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
    parser = build_parser()
    args = parser.parse_args(_join_negative_lists(sys.argv[1:] if argv is None else list(argv)))
    try:
        with _interrupt_outside_casadi():
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
