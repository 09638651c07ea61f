"""Run a seeded family of generated plans in a lunar gravity field through missed and burns.

Usage (from the repository root)::

    .venv/bin/python tools/field_family.py --seed 37 --count 8 --out /tmp/field.jsonl

Each accepted plan (:func:`lunarcap.studies.families.plan_family` with ``degrees=(4, 8)``
and ``burns=(2, 3)``: LP165P of degree 4 to 8 with the Earth and the Sun, two or three
burns, intermediate ellipses asked by period or apolune, a circle or a 100 x 150-600 km
ellipse last, 300-1,500 kg, 100-600 N, 20-170 deg) goes through what ``lunarcap missed``
and ``lunarcap burns`` compute for one case: burn 1 cut off at 0.5 and 0.9 of its duration
with a 0 and a 30 min delay, burn 1 ignited 2 min late, and the capture in 2 and in 3
burns. One JSON line per case (plan, study, case, status, reason, delta-V, wall time);
the summary counts the answered cases (missed: recovered and verified, or "no recovery"
with a reason; burns: "ok" or "infeasible" with a reason) against all, per study, with
the wall times (solved afresh: the cache switch off).
"""

from __future__ import annotations

import argparse
import json
import sys
import time

from lunarcap.repro.cache import caching
from lunarcap.studies.burn_count.counts import count_result
from lunarcap.studies.families import plan_family
from lunarcap.studies.missed.cases import case_result
from lunarcap.studies.missed.nominal import DEFAULT_MAX_PERIOD_H, nominal_of

#: The missed-thrust cases of burn 1: (fraction, delay_min, late_min).
MISSED = [(f, d, None) for f in (0.5, 0.9) for d in (0.0, 30.0)] + [(None, 0.0, 2.0)]
#: The counts of the burns study.
COUNTS = (2, 3)
#: What answers a case, per study.
ANSWERS = {"missed": ("recovered", "no recovery"), "burns": ("ok", "infeasible")}


def _guarded(study: str, plan, case: dict, run) -> dict:
    """``run()`` as one row (a crash of the study is a row with status "error")."""
    t0 = time.perf_counter()
    try:
        row = run()
    except Exception as exc:   # a crash is counted as a failure of the study
        row = {"status": "error", "reason": f"{type(exc).__name__}: {exc}".split("\n")[0]}
    row.update(plan=plan.name, study=study, n_burns=plan.n_burns,
               kinds=[t.kind for t in plan.targets], thrust_N=plan.engine.thrust_N,
               mass_kg=plan.arrival.mass_kg, inc_deg=plan.arrival.inclination_deg,
               degree=plan.dynamics.degree, wall_s=time.perf_counter() - t0, **case)
    return row


def run_plan(plan):
    """The plan's missed-thrust cases and counts, one row at a time (a generator)."""
    nominal = []

    def missed(f, d, late):
        if not nominal:
            nominal.append(nominal_of(plan, 1, DEFAULT_MAX_PERIOD_H * 3600.0))
        r = case_result(plan, 1, f, d, late_min=late, nominal=nominal[0])
        return {"status": r["status"], "reason": r.get("reason", ""),
                "penalty_mps": r.get("penalty_mps"), "all_verified": r.get("all_verified")}

    def burns(n):
        r = count_result(plan, n)
        return {"status": r["status"], "reason": r.get("reason", ""),
                "total_delta_v_mps": r.get("total_delta_v_mps"),
                "all_verified": r.get("all_verified")}

    for f, d, late in MISSED:
        yield _guarded("missed", plan, {"fraction": f, "delay_min": d, "late_min": late},
                       lambda f=f, d=d, late=late: missed(f, d, late))
    for n in COUNTS:
        yield _guarded("burns", plan, {"count": n}, lambda n=n: burns(n))


def main(argv=None) -> int:
    """Run the family (see the module docstring) and print its pass rates."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seed", type=int, default=37)
    ap.add_argument("--count", type=int, default=8)
    ap.add_argument("--out", default=None, help="JSON lines, one per case")
    ap.add_argument("--only", default=None, help="plan names, comma-separated (default all)")
    args = ap.parse_args(argv)
    plans, refused = plan_family(args.seed, args.count, mass_kg=(300, 1500), burns=(2, 3),
                                 degrees=(4, 8))
    if args.only:
        plans = [p for p in plans if p.name in args.only.split(",")]
    print(f"{len(plans)} plans accepted, {len(refused)} refused at load", flush=True)
    for why in refused:
        print(f"  refused: {why}", flush=True)
    out = open(args.out, "w") if args.out else None
    rows = []
    with caching(False):
        for plan in plans:
            for row in run_plan(plan):
                rows.append(row)
                case = {k: row[k] for k in ("fraction", "delay_min", "late_min", "count")
                        if row.get(k) is not None}
                print(f"{row['plan']} ({plan.n_burns} burns, {row['degree']}x{row['degree']}, "
                      f"{row['thrust_N']:g} N, {row['mass_kg']:g} kg) {row['study']} {case}: "
                      f"{row['status']} {row['wall_s']:.0f} s {row['reason'][:160]}",
                      flush=True)
                if out:
                    out.write(json.dumps(row) + "\n")
                    out.flush()
    for study, ok in ANSWERS.items():
        mine = [r for r in rows if r["study"] == study]
        answered = [r for r in mine if r["status"] in ok]
        wall = sorted(r["wall_s"] for r in mine)
        print(f"{study}: answered {len(answered)}/{len(mine)}; wall per case "
              f"{wall[0] if wall else 0:.0f}-{wall[-1] if wall else 0:.0f} s, total "
              f"{sum(wall):.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
