"""Command-line interface: ``lunarcap <command> ...`` (also ``python -m lunarcap``).

Every user error (bad input, a failed solve) prints one line ``lunarcap: error: ...``
to stderr and exits with status 2 (bad input) or 3 (solve failed); nothing already
written is lost.
"""

from __future__ import annotations

import argparse
import json
import math
import sys

from . import constants as C
from .errors import InputError, LunarcapError, SolveError


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
    from .impulsive import impulsive_sequence

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


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of every subcommand."""
    parser = argparse.ArgumentParser(prog="lunarcap", description=__doc__.splitlines()[0])
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("impulsive", help="two-body impulsive capture sequence and Eq. (19)")
    _add_engine(p)
    p.set_defaults(func=cmd_impulsive)
    return parser


def main(argv=None) -> int:
    """Entry point; returns the exit status."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args.func(args)
    except InputError as exc:
        print(f"lunarcap: error: {exc}", file=sys.stderr)
        return 2
    except SolveError as exc:
        print(f"lunarcap: error: {exc}", file=sys.stderr)
        return 3
    except LunarcapError as exc:
        print(f"lunarcap: error: {exc}", file=sys.stderr)
        return 2
