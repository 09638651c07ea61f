"""Command-line interface: ``lunarcap <command> ...`` (also ``python -m lunarcap``).

Every user error (bad input, a failed solve) prints one line ``lunarcap: error: ...``
to stderr and exits with status 2 (bad input) or 3 (solve failed); nothing already
written is lost.
"""

from __future__ import annotations

import argparse
import json
import math
import re
import sys

from lunarcap.physics import constants as C
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


def _add_engine(p: argparse.ArgumentParser) -> None:
    p.add_argument("--thrust", type=_positive("thrust", "N"), default=150.0, help="thrust, N")
    p.add_argument("--isp", type=_positive("Isp", "s"), default=200.0, help="specific impulse, s")
    p.add_argument("--mass", type=_positive("mass", "kg"), default=C.ARRIVAL_MASS_KG,
                   help="mass at the first perilune, kg")
    p.add_argument("--json", action="store_true", help="print JSON instead of a table")


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


def cmd_impulsive(args) -> int:
    """Print the two-body impulsive capture sequence and Eq. (19) estimates."""
    from lunarcap.mission.impulsive import impulsive_sequence

    burns = impulsive_sequence(args.thrust, args.isp, args.mass)
    rows = [{"loi": b.loi, "delta_v_mps": b.delta_v_mps,
             "period_before_h": b.period_before_h, "period_after_h": b.period_after_h,
             "v_perilune_before_kmps": b.v_before_kmps, "v_perilune_after_kmps": b.v_after_kmps,
             "m_before_kg": b.m_before_kg, "m_after_kg": b.m_after_kg, "fuel_kg": b.fuel_kg,
             "eq19_burn_duration_min": b.eq19_duration_min} for b in burns]
    if args.json:
        out = {"thrust_N": args.thrust, "isp_s": args.isp, "mass_kg": args.mass,
               "total_delta_v_mps": sum(r["delta_v_mps"] for r in rows), "burns": rows}
        print(json.dumps(_jsonable(out), indent=2))
        return 0
    print(f"Two-body impulsive capture, {args.thrust:g} N / {args.isp:g} s, "
          f"{args.mass:g} kg at arrival")
    print(f"{'LOI':>3} {'dV m/s':>9} {'P after h':>9} {'m before kg':>11} {'m after kg':>10} "
          f"{'fuel kg':>8} {'Eq.19 min':>9}")
    for r in rows:
        print(f"{r['loi']:>3} {r['delta_v_mps']:9.3f} {r['period_after_h']:9.3f} "
              f"{r['m_before_kg']:11.3f} {r['m_after_kg']:10.3f} {r['fuel_kg']:8.3f} "
              f"{r['eq19_burn_duration_min']:9.2f}")
    return 0


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


def _start(text: str) -> float:
    vals = _starts(text)
    if len(vals) != 1:
        raise argparse.ArgumentTypeError(f"one start offset (min) expected, got {text!r}")
    return vals[0]


def _add_solver_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--dynamics", choices=["full", "j2", "two-body"], default="full",
                   help="perturbations: full (J2, Earth, Sun), j2, or two-body")
    p.add_argument("--ephemeris", default=None, metavar="BSP",
                   help="SPK file (.bsp) instead of the bundled DE405")
    p.add_argument("--hemisphere", choices=["north", "south"], default="north",
                   help="lunar hemisphere of the arrival perilune")
    p.add_argument("--no-cache", action="store_true", help="recompute, ignoring the disk cache")
    p.add_argument("--quiet", action="store_true", help="no progress lines on stderr")


def default_previous_starts(thrust_N: float, isp_s: float, loi: int) -> tuple:
    """Ignition offsets of the LOIs before ``loi``: the paper's best for its engines, else
    the free-ignition optima ("free")."""
    from lunarcap.runs.sweeps import default_previous

    return default_previous(thrust_N, loi, isp_s)


def _case_kwargs(args) -> dict:
    from lunarcap.mission.arrival import ArrivalSpec

    kw = {"dynamics": args.dynamics,
          "arrival": ArrivalSpec(mass_kg=args.mass, hemisphere=args.hemisphere),
          "ephemeris": args.ephemeris, "verbose": not args.quiet}
    if getattr(args, "steering", "optimal") != "optimal":
        kw["steering"] = args.steering
    return kw


def _solver(args):
    from lunarcap.runs.chain import solve_case

    return solve_case.uncached if args.no_cache else solve_case


def _print_summary_line(s: dict) -> None:
    v = s["verification"]
    print(f"LOI {s['loi']}  start {s['start_min']:+.3f} min  burn {s['burn_duration_min']:.2f} min  "
          f"dV {s['delta_v_mps']:.3f} m/s  impulsive {s['impulsive_delta_v_mps']:.3f} m/s  "
          f"loss {s['loss_mps']:.3f} m/s ({s['loss_percent']:.2f} %)  mass "
          f"{s['m_start_kg']:.3f} -> {s['m_end_kg']:.3f} kg  v_end {s['v_end_kmps']:.5f} km/s  "
          f"Eq.19 {s['eq19_duration_min']:.2f} min")
    print(f"      IPOPT {s['ipopt_status']} ({s['ipopt_iterations']} it, {s['mesh']}), "
          f"wall {s['solve_wall_s']:.2f} s; verified: dV diff {v['delta_v_diff_mps']:.2e} m/s, "
          f"rp {v['rp_error_m']:.3f} m, i {v['inc_error_deg']:.1e} deg, "
          f"gamma {v['gamma_error_deg']:.1e} deg")


def cmd_solve(args) -> int:
    """Solve one LOI (the earlier LOIs of the chain are solved or fetched first)."""
    from lunarcap.mission.arrival import check_loi

    loi = check_loi(args.loi)
    prev = args.previous_starts
    if prev is None:
        prev = default_previous_starts(args.thrust, args.isp, loi)
    if len(prev) != loi - 1:
        raise InputError(f"--previous-starts needs {loi - 1} offset(s) for LOI {loi}, got {prev}")
    sol = _solver(args)(args.thrust, args.isp, loi, args.start, tuple(prev), **_case_kwargs(args))
    s = sol.to_dict()
    s["previous_starts_min"] = list(prev)
    if args.json:
        print(json.dumps(_jsonable(s), indent=2))
    else:
        _print_summary_line(s)
    return 0


def cmd_sequence(args) -> int:
    """Solve the three LOIs in chain order; completed LOIs are printed even if a later fails."""
    if len(args.starts) != 3:
        raise InputError(f"--starts needs three offsets (LOI 1, 2, 3), got {args.starts}")
    solve = _solver(args)
    done = []
    try:
        for i in range(3):
            sol = solve(args.thrust, args.isp, i + 1, args.starts[i], tuple(args.starts[:i]),
                        **_case_kwargs(args))
            done.append(sol.to_dict())
            if not args.json:
                _print_summary_line(done[-1])
    finally:
        if args.json:
            tot = {"total_delta_v_mps": sum(d["delta_v_mps"] for d in done),
                   "total_impulsive_delta_v_mps": sum(d["impulsive_delta_v_mps"] for d in done),
                   "total_burn_duration_min": sum(d["burn_duration_min"] for d in done),
                   "final_mass_kg": done[-1]["m_end_kg"] if done else None,
                   "complete": len(done) == 3}
            tot["total_loss_mps"] = tot["total_delta_v_mps"] - tot["total_impulsive_delta_v_mps"]
            print(json.dumps(_jsonable({"thrust_N": args.thrust, "isp_s": args.isp,
                                        "starts_min": list(args.starts), **tot, "lois": done}),
                             indent=2))
    if not args.json:
        tot_dv = sum(d["delta_v_mps"] for d in done)
        tot_imp = sum(d["impulsive_delta_v_mps"] for d in done)
        print(f"total: dV {tot_dv:.3f} m/s, loss {tot_dv - tot_imp:.3f} m/s "
              f"({100 * (tot_dv - tot_imp) / tot_imp:.2f} % of {tot_imp:.3f}), burn "
              f"{sum(d['burn_duration_min'] for d in done):.2f} min, final mass "
              f"{done[-1]['m_end_kg']:.3f} kg")
    return 0


def cmd_bench(args) -> int:
    """Solve and verify all 37 paper cases uncached; print timings and residuals."""
    from lunarcap.runs.bench import run

    rows = run(args.dynamics)
    return 0 if all(r["verification_passed"] for r in rows) else 3


def cmd_study(args) -> int:
    """Engine trade study on Dask: loss against thrust-to-weight, free ignition, per Isp."""
    from lunarcap.runs.study import StudySpec, format_summary, run_study

    spec = StudySpec(args.thrust_min, args.thrust_max, args.points, args.isp, args.dynamics)
    try:
        res = run_study(spec, out=args.out, workers=args.workers, scheduler=args.scheduler,
                        retry_failed=args.retry_failed, progress=not args.no_progress)
    except KeyboardInterrupt:
        print("lunarcap: interrupted; finished engines are in the table, run the same command "
              "again to resume", file=sys.stderr)
        return 130
    print(format_summary(res))
    return 0 if res.failures.empty else 3


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of every subcommand."""
    parser = argparse.ArgumentParser(prog="lunarcap", description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("impulsive", help="two-body impulsive capture sequence and Eq. (19)")
    _add_engine(p)
    p.set_defaults(func=cmd_impulsive)

    p = sub.add_parser("solve", help="optimal finite burn of one LOI, verified by re-propagation")
    _add_engine(p)
    p.add_argument("--loi", type=int, choices=[1, 2, 3], default=1, help="LOI number")
    p.add_argument("--start", type=_start, default=-10.0,
                   help="ignition, minutes from the nominal perilune (negative: before), or "
                        "'free' to optimise it within +-2 Eq. (19) durations")
    p.add_argument("--previous-starts", type=_starts, default=None, metavar="S1[,S2]",
                   help="ignition offsets of the earlier LOIs (default: the paper's best for "
                        "its engines, else the free-ignition optima)")
    p.add_argument("--steering", choices=["optimal", "inertial", "antivelocity"],
                   default="optimal", help="steering law of this LOI (earlier LOIs: optimal)")
    _add_solver_options(p)
    p.set_defaults(func=cmd_solve)

    p = sub.add_parser("sequence", help="the three LOIs of the capture chain")
    _add_engine(p)
    p.add_argument("--starts", type=_starts, default=(-10.0, -6.0, -5.0), metavar="S1,S2,S3",
                   help="ignition offsets of LOI 1, 2, 3 in minutes from perilune")
    _add_solver_options(p)
    p.set_defaults(func=cmd_sequence)

    p = sub.add_parser("bench", help="solve and verify all 37 paper cases, print timings")
    p.add_argument("--dynamics", choices=["full", "j2", "two-body"], default="full")
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
    return parser


_LIST_OPTIONS = ("--starts", "--previous-starts", "--start")


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


def main(argv=None) -> int:
    """Entry point; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(_join_negative_lists(sys.argv[1:] if argv is None else list(argv)))
    try:
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
