"""Benchmark: every finite-burn case of the paper's Tables 1-5, solved and verified.

``lunarcap bench`` (or ``python -m lunarcap bench``) prints, per case, the wall time of
the whole solve (guess, IPOPT, verification), IPOPT's iterations and the verification
residuals, then medians and the total. The disk cache is off: every case is computed,
through the paper's capture plans (:func:`lunarcap.mission.plan.paper_plan`). The LOI 2
and 3 cases start from the paper's best earlier burns (Table B1), as in the paper; each
distinct earlier burn is solved once per run (in memory,
:func:`lunarcap.runs.chain.reuse_earlier_burns`), or again for every case with
``reuse=False``. NLP builds (once per shape and process) are part of the total.
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


def _e(v, width: int) -> str:
    """A residual in exponent notation, or a dash where it does not apply."""
    return f"{'—':>{width}}" if v is None else f"{v:{width}.2e}"


def run(dynamics: str = "full", out=print, cases=None, reuse: bool = True) -> list[dict]:
    """Solve the cases uncached; print one line each and the medians. Returns the rows."""
    import contextlib

    os.environ["LUNARCAP_NO_CACHE"] = "1"  # nothing read from or written to disk
    from lunarcap.optim.collocation import DEFAULT_MESHES
    from lunarcap.optim.nlp import prebuild
    from lunarcap.runs.chain import paper_case, reuse_earlier_burns

    t0 = time.perf_counter()
    # the two NLP shapes of the paper's cases (ellipse and circle targets, fixed ignition),
    # built at once on the machine's two cores; their time is part of the total
    prebuild([(DEFAULT_MESHES[0], kind, False, "optimal", dynamics)
              for kind in ("perilune", "circular")])
    with reuse_earlier_burns() if reuse else contextlib.nullcontext():
        return _run(dynamics, out, cases, reuse, paper_case, t0)


def _run(dynamics, out, cases, reuse, paper_case, t_all) -> list[dict]:
    cases = cases or paper_cases()
    rows = []
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
            f"{v['rp_error_m']:9.3f} {v['inc_error_deg']:9.2e} {_e(v['gamma_error_deg'], 11)}")
    total = time.perf_counter() - t_all
    med = statistics.median(r["solve_wall_s"] for r in rows)
    med_it = statistics.median(r["iterations"] for r in rows)
    out(f"{len(rows)} cases ({dynamics} dynamics): median solve wall {med:.3f} s, median IPOPT "
        f"iterations {med_it:g}, total {total:.1f} s (incl. the NLP builds, two at once; "
        f"earlier burns {'solved once per run' if reuse else 'solved again for each case'}), "
        f"all verified: {all(r['verification_passed'] for r in rows)}")
    return rows


#: The cases of the dymos peer benchmark (thrust N, Isp s, LOI-1 ignition min).
PEER_CASES = ((150.0, 200.0, -6.0), (150.0, 200.0, -10.0), (150.0, 200.0, -14.0),
              (450.0, 300.0, -3.0))


def warm_solves(dynamics: str = "two-body", repeats: int = 5, out=print,
                cases=PEER_CASES) -> list[dict]:
    """Warm verified first-burn solves of the peer cases: guess + IPOPT + verification.

    For each case the NLP is built and solved once (warm-up, not timed), then solved
    ``repeats`` times from scratch (problem, guess, IPOPT, re-propagation), nothing cached;
    the medians of each part are printed, with the optimum (to compare with the peer's).
    """
    import statistics as st

    from lunarcap.mission.plan import paper_plan
    from lunarcap.optim.collocation import DEFAULT_MESHES
    from lunarcap.optim.guess import make_guess
    from lunarcap.optim.nlp import solve_nlp
    from lunarcap.optim.problem import burn_problem
    from lunarcap.optim.verify import verify
    from lunarcap.runs.chain import arrival_for

    rows = []
    out(f"{'case':<26} {'problem s':>9} {'guess s':>8} {'IPOPT s':>8} {'verify s':>8} "
        f"{'total s':>8} {'it':>3} {'dV m/s':>10} gate")
    for thrust, isp, start in cases:
        plan = paper_plan(thrust, isp, dynamics=dynamics).with_start(0, start)
        x = arrival_for(plan.arrival, plan.ephemeris, plan.lunar_pole).state
        eph = plan.ephemeris_model()
        times = []
        for rep in range(repeats + 1):
            t0 = time.perf_counter()
            prob = burn_problem(plan, 0, x, eph)
            t1 = time.perf_counter()
            guess = make_guess(prob)
            t2 = time.perf_counter()
            raw = solve_nlp(prob, DEFAULT_MESHES[0], guess)
            t3 = time.perf_counter()
            ver = verify(raw)
            t4 = time.perf_counter()
            if rep:  # the first solve builds the NLP and the integrators
                times.append((t1 - t0, t2 - t1, t3 - t2, t4 - t3, t4 - t0))
        med = [st.median(t[i] for t in times) for i in range(5)]
        row = {"thrust_N": thrust, "isp_s": isp, "start_min": start, "dynamics": dynamics,
               "problem_s": med[0], "guess_s": med[1], "ipopt_s": med[2], "verify_s": med[3],
               "total_s": med[4], "iterations": raw.iterations,
               "delta_v_mps": raw.delta_v_mps, "verified": ver.passed}
        rows.append(row)
        out(f"{thrust:>4g} N / {isp:g} s start {start:+5.1f} min {med[0]:9.4f} {med[1]:8.4f} "
            f"{med[2]:8.4f} {med[3]:8.4f} {med[4]:8.4f} {raw.iterations:3d} "
            f"{raw.delta_v_mps:10.4f} {'passed' if ver.passed else 'FAILED'}")
    out(f"median of the cases' medians: total {st.median(r['total_s'] for r in rows):.4f} s "
        f"(IPOPT {st.median(r['ipopt_s'] for r in rows):.4f} s), {dynamics} dynamics, "
        f"{repeats} warm solves per case")
    return rows
