"""``lunarcap solve``: the optimal finite burn of one burn of a plan, verified.

The earlier burns are solved (or fetched from the cache) first, at their plan's starts or
those of ``--previous-starts``; the row printed is ``lunarcap plan``'s. The solve is the
public API's :func:`lunarcap.api.solve_burn`, its ``--json`` document the result's.
"""

from __future__ import annotations

from lunarcap.cli.args import plan_from_args
from lunarcap.cli.plan import print_burn_row, print_plan_header


def cmd_solve(args) -> int:
    """Solve one burn of a plan (its earlier burns are solved or fetched first)."""
    from lunarcap.api import solve_burn

    res = solve_burn(plan_from_args(args), args.burn, start=args.start,
                     previous_starts=args.previous_starts, steering=args.steering,
                     impulsive=not args.no_impulsive, verbose=not args.quiet)
    if args.json:
        print(res.to_json())
    else:
        print_plan_header(res.plan)
        print_burn_row(res.plan, res.row())
    return 0 if res.verified else 3
