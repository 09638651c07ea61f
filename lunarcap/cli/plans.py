"""``lunarcap plans``: the packaged plans, or one of them as YAML."""

from __future__ import annotations


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
