"""Run a seeded family of generated plans through the missed-thrust study; print pass rates.

Usage (from the repository root)::

    .venv/bin/python tools/missed_family.py --seed 24 --count 12 --dynamics two-body \
        --out /tmp/family.jsonl

Each accepted plan (lunarcap.studies.families: 2-5 burns, 100-600 N, 400-2,000 kg,
20-170 deg, every target kind) is run for each burn asked (``--burns first,last``):
cut-offs of 0.25, 0.5, 0.9 and 1.0 of the burn at 0 and 30 min, late ignitions of 1 and
5 min. One JSON line per case (plan, burn, case, status, reason, penalty, wall time); the
summary counts the cases answered (recovered and verified, or "no recovery" with a
reason) against all, and the penalties below -0.05 m/s.
"""

from __future__ import annotations

import argparse
import json
import sys
import time

from lunarcap.repro.cache import caching
from lunarcap.studies.families import plan_family
from lunarcap.studies.missed.cases import case_result
from lunarcap.studies.missed.nominal import DEFAULT_MAX_PERIOD_H, nominal_of

FRACTIONS = (0.25, 0.5, 0.9, 1.0)
DELAYS_MIN = (0.0, 30.0)
LATE_MIN = (1.0, 5.0)


def cases():
    """(fraction, delay_min, late_min) of every case of one burn."""
    return [(f, d, None) for f in FRACTIONS for d in DELAYS_MIN] + \
        [(None, 0.0, m) for m in LATE_MIN]


def run_plan(plan, burn: int) -> list[dict]:
    """Every case of ``burn`` of ``plan`` (a failure of the study is a row, not raised).

    The burn's nominal is solved once, by the first case that needs it, and passed to the
    others (a nominal that fails is tried again by the next case).
    """
    rows, nominal = [], None
    for f, d, late in cases():
        t0 = time.perf_counter()
        try:
            nominal = nominal or nominal_of(plan, burn, DEFAULT_MAX_PERIOD_H * 3600.0)
            r = case_result(plan, burn, f, d, late_min=late, nominal=nominal)
            row = {"status": r["status"], "reason": r.get("reason", ""),
                   "penalty_mps": r.get("penalty_mps"), "all_verified": r.get("all_verified")}
        except Exception as exc:   # a crash is counted as a failure of the study
            row = {"status": "error", "reason": f"{type(exc).__name__}: {exc}".split("\n")[0]}
        row.update(plan=plan.name, burn=burn, n_burns=plan.n_burns,
                   kinds=[t.kind for t in plan.targets], thrust_N=plan.engine.thrust_N,
                   mass_kg=plan.arrival.mass_kg, inc_deg=plan.arrival.inclination_deg,
                   dynamics=plan.dynamics, fraction=f, delay_min=d, late_min=late,
                   wall_s=time.perf_counter() - t0)
        rows.append(row)
    return rows


def main(argv=None) -> int:
    """Run the family (see the module docstring) and print its pass rate."""
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--seed", type=int, default=24)
    ap.add_argument("--count", type=int, default=12)
    ap.add_argument("--dynamics", default="two-body")
    ap.add_argument("--burns", default="first", help="first, last or first,last")
    ap.add_argument("--out", default=None, help="JSON lines, one per case")
    ap.add_argument("--one-per-kind", action="store_true",
                    help="only the first plan of each formulation and final orbit")
    ap.add_argument("--only", default=None, help="plan names, comma-separated (default all)")
    args = ap.parse_args(argv)
    plans, refused = plan_family(args.seed, args.count, dynamics=args.dynamics,
                                 mass_kg=(400, 2000), formulations=("orbit", "song2011"))
    if args.one_per_kind:
        firsts = {}
        for p in plans:
            firsts.setdefault((p.formulation, p.targets[-1].kind), p)
        plans = list(firsts.values())
    if args.only:
        plans = [p for p in plans if p.name in args.only.split(",")]
    print(f"{len(plans)} plans accepted, {len(refused)} refused at load", flush=True)
    out = open(args.out, "w") if args.out else None
    rows = []
    with caching(False):
        for plan in plans:
            for which in args.burns.split(","):
                burn = 1 if which == "first" else plan.n_burns
                for row in run_plan(plan, burn):
                    rows.append(row)
                    print(f"{row['plan']} burn {burn}/{plan.n_burns} f={row['fraction']} "
                          f"d={row['delay_min']} late={row['late_min']}: {row['status']} "
                          f"{row.get('penalty_mps')} {row['wall_s']:.1f}s {row['reason'][:140]}",
                          flush=True)
                    if out:
                        out.write(json.dumps(row) + "\n")
                        out.flush()
    ok = [r for r in rows if r["status"] in ("recovered", "no recovery")]
    neg = [r for r in rows if r["status"] == "recovered" and r["penalty_mps"] < -0.05]
    print(f"answered {len(ok)}/{len(rows)}; penalties < -0.05 m/s: {len(neg)}; wall "
          f"{sum(r['wall_s'] for r in rows):.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
