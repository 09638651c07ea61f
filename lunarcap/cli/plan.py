"""``lunarcap plan``: solve and verify every burn of a capture plan, print or export it.

Each burn's row is printed as soon as it is verified (``on_burn``), then the totals; with
``--json`` one document at the end, written even when a solve fails (what was done is
kept, ``complete`` false). ``--after-days`` propagates the final orbit; ``--export``
writes the verified capture for other tools (refused before any solve if the directory
cannot be written, and not written if a burn failed verification: status 3).
"""

from __future__ import annotations

import sys

from lunarcap.cli.args import plan_from_args
from lunarcap.physics.constants import R_MOON


def _fmt(v, spec: str, width: int) -> str:
    """``v`` formatted in ``width`` columns, a dash if None (a burn with no impulsive limit)."""
    return f"{'—':>{width}}" if v is None else f"{v:{width}{spec}}"


def _target_width(plan) -> int:
    """Columns of the target column: the longest of the plan's orbits in words."""
    return max(6, *(len(b.describe()) for b in plan.burns))


def print_plan_header(plan) -> None:
    """The plan's line (engine, dynamics, arrival, frame) and the burn table's header."""
    a = plan.arrival
    print(f"Plan {plan.name}: {plan.engine.thrust_N:g} N / {plan.engine.isp_s:g} s, "
          f"{plan.dynamics} dynamics, {plan.n_burns} burn(s); arrival {a.epoch}, perilune "
          f"{a.perilune_altitude_km:g} km, inclination {a.inclination_deg:g} deg, "
          f"v_inf {a.v_inf_kmps:.5f} km/s, {a.mass_kg:g} kg; M-MME2000 pole {plan.lunar_pole}")
    print(f"{'burn':>4}  {'target':<{_target_width(plan)}} {'ignition (TDB)':<27} {'start min':>9} "
          f"{'dur min':>7} {'dV m/s':>9} {'imp m/s':>9} {'loss m/s':>8} {'loss %':>6} "
          f"{'m start kg':>10} {'m end kg':>9}  verification", flush=True)


def print_burn_row(plan, r: dict) -> None:
    """One burn's row (``r``: its :meth:`BurnResult.row`) and its verification's residuals."""
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


def print_totals(tot: dict) -> None:
    """The plan's totals (``tot``: :meth:`PlanResult.totals`), its final orbit in altitudes."""
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
    from lunarcap.api import CaptureResult, solve

    plan = plan_from_args(args)
    if args.export:   # before any solve: a directory that cannot be written is refused
        from lunarcap.capture.export import check_export_dir

        check_export_dir(args.export, "--export")
    done, res = [], None

    def on_burn(b):
        done.append(b)
        if not args.json:
            print_burn_row(plan, b.row())

    if not args.json:
        print_plan_header(plan)
    try:
        res = solve(plan, impulsive=not args.no_impulsive, after_days=args.after_days,
                    verbose=not args.quiet, on_burn=on_burn)
    finally:
        if args.json:   # what was done, even if a solve failed
            print(res.to_json() if res is not None else
                  CaptureResult(plan, done, None, args.after_days).to_json())
    if not args.json:
        print_totals(res.totals())
        if res.after is not None:
            _print_after(res.after)
    if args.export:
        if all(b.solution.verification.passed for b in res.burns):
            _export_plan(res, args)
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


def _export_plan(res, args) -> None:
    """Write the plan's OEM, SPK, attitude and maneuver files (``--export DIR``).

    With ``--after-days``, the OEM and the SPK go on to the evolution's end.
    """
    ex = res.export(args.export, time_system=args.time_system, object_id=args.spk_id)
    out = sys.stderr if args.json else sys.stdout
    print(f"Exported in {ex.seconds:.2f} s ({ex.time_system}, SPK object ID {ex.object_id}; "
          f"OEM interpolation within {ex.max_interpolation_error_m:.2g} m):", file=out)
    for kind, path in ex.files.items():
        print(f"  {path}  {ex.sizes_bytes[kind]:,} bytes", file=out)
    for line in ex.reference:   # also at the head of every file
        print(f"  {line}", file=out)
