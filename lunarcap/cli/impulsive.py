"""``lunarcap impulsive``: a plan's two-body impulsive chain and its Eq. (19) durations."""

from __future__ import annotations

from lunarcap.cli.args import plan_from_args, print_json


def cmd_impulsive(args) -> int:
    """Print the plan's two-body impulsive chain and Eq. (19) estimates."""
    plan = plan_from_args(args)
    burns = plan.impulsive()
    rows = [{"burn": b.burn, "impulsive_delta_v_two_body_mps": b.delta_v_mps,
             "period_before_h": b.period_before_h, "period_after_h": b.period_after_h,
             "v_perilune_before_kmps": b.v_before_kmps, "v_perilune_after_kmps": b.v_after_kmps,
             "m_before_kg": b.m_before_kg, "m_after_kg": b.m_after_kg, "fuel_kg": b.fuel_kg,
             "eq19_duration_min": b.eq19_duration_min} for b in burns]
    if args.json:
        print_json({"plan": plan.name, "thrust_N": plan.engine.thrust_N,
                    "isp_s": plan.engine.isp_s, "mass_kg": plan.arrival.mass_kg,
                    "v_inf_kmps": plan.arrival.v_inf_kmps,
                    "total_impulsive_delta_v_two_body_mps":
                        sum(r["impulsive_delta_v_two_body_mps"] for r in rows), "burns": rows})
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
