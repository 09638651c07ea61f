"""``lunarcap solve``: the optimal finite burn of one burn of a plan, verified.

The earlier burns are solved (or fetched from the cache) first, at their plan's starts or
those of ``--previous-starts``; the row printed is ``lunarcap plan``'s.
"""

from __future__ import annotations

from lunarcap.cli.args import plan_from_args, print_json
from lunarcap.cli.plan import print_burn_row, print_plan_header
from lunarcap.errors import InputError


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

    plan = plan_from_args(args)
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
        print_json(out)
    else:
        print_plan_header(plan)
        print_burn_row(plan, r.row())
    return 0 if sol.verification.passed else 3
