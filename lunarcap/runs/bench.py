"""Benchmark: every finite-burn case of the paper's Tables 1-5, solved and verified.

``lunarcap bench`` (or ``python -m lunarcap bench``) prints, per case, the wall time of
the whole solve (guess, IPOPT, verification), IPOPT's iterations and the verification
residuals, then medians and the total. Caching is off: every case is computed, through the
paper's capture plans (:func:`lunarcap.mission.plan.paper_plan`). The LOI 2 and 3 cases
start from the paper's best earlier burns (Table B1), as in the paper.
"""

from __future__ import annotations

import os
import statistics
import time

from lunarcap.paper.printed import PAPER_BEST_STARTS_MIN, PAPER_STARTS_MIN

ENGINES = {150.0: 200.0, 300.0: 250.0, 450.0: 300.0}


def paper_cases():
    """The 37 (thrust N, Isp s, LOI, start min, previous starts) cases of Tables 1-5."""
    cases = []
    for (thrust, loi), starts in PAPER_STARTS_MIN.items():
        prev = PAPER_BEST_STARTS_MIN[thrust][:loi - 1]
        for s in starts:
            cases.append((thrust, ENGINES[thrust], loi, s, prev))
    return cases


def run(dynamics: str = "full", out=print, cases=None) -> list[dict]:
    """Solve the cases uncached; print one line each and the medians. Returns the rows."""
    os.environ["LUNARCAP_NO_CACHE"] = "1"
    from lunarcap.repro import cache
    cache.memory.location = None  # make sure nothing is read from disk
    from lunarcap.runs.chain import paper_case

    cases = cases or paper_cases()
    rows = []
    t_all = time.perf_counter()
    out(f"{'case':<28} {'wall s':>7} {'it':>4} {'dV m/s':>9} {'dV diff m/s':>11} "
        f"{'rp err m':>9} {'i err deg':>9} {'gam err deg':>11}")
    for thrust, isp, loi, start, prev in cases:
        sol = paper_case(thrust, isp, loi, start, prev, dynamics)
        s = sol.summary()
        v = s["verification"]
        row = {"thrust_N": thrust, "isp_s": isp, "loi": loi, "start_min": start,
               "solve_wall_s": s["solve_wall_s"], "iterations": s["ipopt_iterations"],
               "delta_v_mps": s["delta_v_mps"], **{f"verification_{k}": x for k, x in v.items()}}
        rows.append(row)
        out(f"{thrust:>4g} N LOI {loi} start {start:+5.1f} min   {s['solve_wall_s']:7.3f} "
            f"{s['ipopt_iterations']:4d} {s['delta_v_mps']:9.3f} {v['delta_v_diff_mps']:11.2e} "
            f"{v['rp_error_m']:9.3f} {v['inc_error_deg']:9.2e} {v['gamma_error_deg']:11.2e}")
    total = time.perf_counter() - t_all
    med = statistics.median(r["solve_wall_s"] for r in rows)
    med_it = statistics.median(r["iterations"] for r in rows)
    out(f"{len(rows)} cases ({dynamics} dynamics): median solve wall {med:.3f} s, median IPOPT "
        f"iterations {med_it:g}, total {total:.1f} s (incl. one NLP build per mesh shape), all "
        f"verified: {all(r['verification_passed'] for r in rows)}")
    return rows
