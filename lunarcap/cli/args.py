"""What every command does with its parsed arguments: the plan they name, the JSON it prints.

:func:`plan_from_args` reads the plan (a file or a packaged name, or the paper's capture)
and applies the options that override its fields, through the public API's
:func:`lunarcap.api.load_plan`; :func:`print_json` prints a document as the API's results
write it (:func:`lunarcap.api.results.dumps`: NaN and infinities as null, numpy scalars as
numbers).
"""

from __future__ import annotations

from lunarcap.api.results import dumps

#: The plan field each overriding option sets, to name the option when the plan refuses it.
_OVERRIDES = {"--thrust": ("thrust", "engine.thrust_N"), "--isp": ("isp", "engine.isp_s"),
              "--mass": ("mass", "arrival.mass_kg"), "--starts": ("starts", "burns[")}


def print_json(doc: dict) -> None:
    """Print a ``--json`` document (2-space indent, strict JSON)."""
    print(dumps(doc))


def plan_from_args(args):
    """The plan named by the arguments, with their overrides applied.

    A value the plan refuses because of an option is reported with the option first:
    ``--mass (arrival.mass_kg): 700000 kg is above ...``.
    """
    from lunarcap.api import load_plan, paper_plan
    from lunarcap.mission.plan import PlanError

    source = getattr(args, "plan", None)
    plan = None if source is None else load_plan(source)
    try:
        if plan is None:   # the paper's capture, with the engine asked
            plan, thrust, isp = paper_plan(args.thrust or 150.0, args.isp or 200.0), None, None
        else:
            thrust, isp = args.thrust, args.isp
        return load_plan(plan, thrust_N=thrust, isp_s=isp, mass_kg=args.mass,
                         hemisphere=args.hemisphere, dynamics=args.dynamics,
                         ephemeris=args.ephemeris, lunar_pole=args.lunar_pole,
                         starts=getattr(args, "starts", None))
    except PlanError as exc:
        msg = str(exc)
        for opt, (dest, field) in _OVERRIDES.items():
            if getattr(args, dest, None) is not None and msg.startswith(field):
                raise PlanError(f"{opt} ({msg.split(': ', 1)[0]}): {msg.split(': ', 1)[1]}") \
                    from None
        raise
