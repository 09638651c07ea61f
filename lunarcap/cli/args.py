"""What every command does with its parsed arguments: the plan they name, the JSON it prints.

:func:`plan_from_args` reads the plan (a file or a packaged name, or the paper's capture)
and applies the options that override its fields; :func:`print_json` prints a document
with NaN and infinities as null (strict JSON) and numpy scalars as numbers.
"""

from __future__ import annotations

import json
import math
from dataclasses import replace
from pathlib import Path

#: The plan field each overriding option sets, to name the option when the plan refuses it.
_OVERRIDES = {"--thrust": ("thrust", "engine.thrust_N"), "--isp": ("isp", "engine.isp_s"),
              "--mass": ("mass", "arrival.mass_kg"), "--starts": ("starts", "burns[")}


def jsonable(obj):
    """``obj`` with numpy scalars as Python numbers and non-finite floats as None."""
    if isinstance(obj, dict):
        return {k: jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    if hasattr(obj, "item"):
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj


def print_json(doc: dict) -> None:
    """Print a ``--json`` document (2-space indent, strict JSON: see :func:`jsonable`)."""
    print(json.dumps(jsonable(doc), indent=2))


def plan_from_args(args):
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
    """``plan`` (None: the paper's, with the engine asked) with the options' values set."""
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
