"""Benchmark: every finite-burn case of the paper's Tables 1-5, solved and verified.

``lunarcap bench`` (or ``python -m lunarcap bench``) prints, per case, the wall time of
the whole solve (guess, IPOPT, verification), IPOPT's iterations and the verification
residuals, then medians and the total. The disk cache is off: every case is computed,
through the paper's capture plans (:func:`lunarcap.mission.plan.paper_plan`). The LOI 2
and 3 cases start from the paper's best earlier burns (Table B1), as in the paper; each
distinct earlier burn is solved once per run (in memory,
:func:`lunarcap.capture.chain.reuse_earlier_burns`), or again for every case with
``reuse=False``. NLP builds (once per shape and process) are part of the total.

``lunarcap bench --studies`` (:func:`studies`) prints where the time goes instead: the
build of each NLP shape with the size and call time of IPOPT's derivative functions,
cold and cached ``lunarcap plan`` in fresh processes, one trade-study engine split into
NLP builds, NLP solves and the rest, and the last logged wall of each study.

Why NLPs are built per process and not loaded from disk (measured with CasADi 3.8.2 on
the 2-core machine): the expanded IPOPT solver of the 8x16 LGR-5 shape serialises to
103 MB and loads in 1.4 s, no faster than building it (1.0-1.5 s of CPU); the
non-expanded one loads in 0.3 s but solves 3x slower (its derivatives run in the MX
virtual machine), and compiling its generated C takes 27 s at -O0. So the build is made
cheaper instead (a smaller expression graph: 32 % fewer Hessian instructions) and is
never paid for a result already in the disk cache.
"""

from __future__ import annotations

import os
import statistics
import time

from lunarcap.mission.scenario import paper_engines
from lunarcap.paper.printed import PAPER_BEST_STARTS_MIN, PAPER_STARTS_MIN

#: The paper's engines, thrust N -> Isp s (its packaged plans).
ENGINES = paper_engines()


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

    from lunarcap.capture.chain import paper_case, reuse_earlier_burns
    from lunarcap.optim.solve import prebuild
    from lunarcap.repro.cache import caching

    t0 = time.perf_counter()
    # the two NLP shapes of the paper's cases (ellipse and circle targets, fixed ignition),
    # built at once on the machine's two cores; their time is part of the total
    prebuild([(kind, False, "optimal", dynamics) for kind in ("perilune", "circular")])
    with caching(False), (reuse_earlier_burns() if reuse else contextlib.nullcontext()):
        return _run(dynamics, out, cases, reuse, paper_case, t0)  # nothing read or written


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

    from lunarcap.capture.chain import arrival_for
    from lunarcap.mission.plan import paper_plan
    from lunarcap.optim.collocation import DEFAULT_MESHES
    from lunarcap.optim.guess import make_guess
    from lunarcap.optim.nlp import solve_nlp
    from lunarcap.optim.problem import burn_problem
    from lunarcap.optim.verify import verify

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


# ====================================================================== --studies
def _median_wall(cmd, env, repeats: int) -> float:
    import subprocess

    walls = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        r = subprocess.run(cmd, env=env, capture_output=True, text=True)
        walls.append(time.perf_counter() - t0)
        if r.returncode:
            raise RuntimeError(f"{' '.join(cmd)} exited {r.returncode}: {r.stderr[-500:]}")
    return statistics.median(walls)


def _eval_ms(fun, repeats: int = 20) -> float:
    """Median wall (ms) of one call of ``fun`` at a fixed random point."""
    import numpy as np

    rng = np.random.default_rng(0)
    args = [rng.random(fun.size1_in(i)) for i in range(fun.n_in())]
    fun(*args)
    walls = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fun(*args)
        walls.append(time.perf_counter() - t0)
    return 1e3 * statistics.median(walls)


def nlp_builds(dynamics: str = "full", out=print) -> list[dict]:
    """Build each NLP shape of the paper's plans afresh; print its build time and sizes.

    The shapes: ellipse (``perilune``) and ``circular`` targets, fixed and free ignition,
    on the first default mesh. Per shape: build wall (s), instructions of IPOPT's two
    derivative functions (Hessian of the Lagrangian, constraint Jacobian) and the median
    wall of one call of each (ms).
    """
    from lunarcap.optim.collocation import DEFAULT_MESHES
    from lunarcap.optim.nlp import build_burn_nlp, clear_nlps

    mesh, rows = DEFAULT_MESHES[0], []
    out(f"{'NLP shape':<44} {'build s':>7} {'vars':>5} {'hess_l instr':>12} "
        f"{'hess_l ms':>9} {'jac_g instr':>11} {'jac_g ms':>8}")
    for kind in ("perilune", "circular"):
        for free in (False, True):
            clear_nlps()
            nlp = build_burn_nlp(mesh, kind, free, "optimal", dynamics)
            s = nlp.compiled.solver
            h, j = s.get_function("nlp_hess_l"), s.get_function("nlp_jac_g")
            row = {"shape": f"{mesh.n_burn}x{mesh.n_coast} LGR-{mesh.degree} {kind}"
                            f"{' free start' if free else ''} {dynamics}",
                   "build_s": nlp.compiled.build_s, "n_vars": nlp.compiled.layout.nv,
                   "hess_l_instructions": h.n_instructions(), "hess_l_ms": _eval_ms(h),
                   "jac_g_instructions": j.n_instructions(), "jac_g_ms": _eval_ms(j)}
            rows.append(row)
            out(f"{row['shape']:<44} {row['build_s']:7.2f} {row['n_vars']:5d} "
                f"{row['hess_l_instructions']:12,d} {row['hess_l_ms']:9.2f} "
                f"{row['jac_g_instructions']:11,d} {row['jac_g_ms']:8.2f}")
    clear_nlps()
    return rows


def plan_walls(plan: str = "song2011-150N", repeats: int = 3, cold: bool = True,
               out=print) -> list[dict]:
    """Wall of ``lunarcap plan PLAN`` (and with free starts) in fresh processes.

    Cold: an empty cache directory (every burn and impulsive limit solved, every NLP shape
    built); cached: the same command again (median of ``repeats``). Also the wall of
    importing the CLI and the heavy packages its import pulls in (none should be).
    """
    import subprocess
    import sys
    import tempfile

    py = sys.executable
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        env = {**os.environ, "LUNARCAP_CACHE_DIR": tmp}
        env.pop("LUNARCAP_NO_CACHE", None)
        imp = _median_wall([py, "-c", "import lunarcap.cli, lunarcap.capture.chain"], env,
                           repeats)
        heavy = subprocess.run(
            [py, "-c", "import sys, lunarcap.cli, lunarcap.capture.chain; print(' '.join("
                       "m for m in ('dask', 'distributed', 'pandas', 'matplotlib', "
                       "'papermill') if m in sys.modules))"],
            env=env, capture_output=True, text=True).stdout.strip()
        out(f"import of the CLI and the chain: {imp:.2f} s (median of {repeats}); heavy "
            f"packages imported: {heavy or 'none'}")
        for extra in ([], ["--starts", "free,free,free"]):
            cmd = [py, "-m", "lunarcap", "plan", plan, *extra]
            label = " ".join(["lunarcap plan", plan, *extra])
            c = _median_wall(cmd, env, 1) if cold else None
            w = _median_wall(cmd, env, repeats)
            rows.append({"command": label, "cold_s": c, "cached_s": w})
            out(f"{label:<52} cold {'-' if c is None else f'{c:.1f}':>5} s   cached "
                f"{w:.2f} s (median of {repeats})")
    return rows


def engine_profile(engines=((300.0, 250.0), (420.0, 250.0)), dynamics: str = "full",
                   out=print) -> list[dict]:
    """Where one trade-study engine's time goes (:func:`.trade.solve_engine`).

    Each engine is solved in this process with an empty temporary cache: NLP builds (the
    first engine builds the study's four shapes), the NLP solves (``solve_in_model``: initial
    point and IPOPT, of which its Hessian and Jacobian evaluations are shown; the rest is
    MUMPS and IPOPT's own work), and everything else (guesses, verification by
    re-propagation, ephemeris fits, cache I/O).
    """
    import tempfile

    import joblib

    import lunarcap.optim.solve as solve_mod
    from lunarcap.optim.correction import nlp_of
    from lunarcap.optim.nlp import n_built
    from lunarcap.repro import cache
    from lunarcap.studies.engine_trade.trade import solve_engine

    acc: dict = {}
    plain = solve_mod.solve_in_model

    def counted(prob, mesh, guess):
        before = n_built()
        t0 = time.perf_counter()
        nlp = nlp_of(prob, mesh)  # the NLP solve_in_model solves
        if n_built() > before:
            acc["build_s"] = acc.get("build_s", 0.0) + time.perf_counter() - t0
        t0 = time.perf_counter()
        raw = plain(prob, mesh, guess)
        acc["ipopt_s"] = acc.get("ipopt_s", 0.0) + time.perf_counter() - t0
        st = nlp.compiled.solver.stats()
        for k in ("nlp_hess_l", "nlp_jac_g"):
            acc[k] = acc.get(k, 0.0) + st.get(f"t_wall_{k}", 0.0)
        acc["solves"] = acc.get("solves", 0) + 1
        acc["iterations"] = acc.get("iterations", 0) + raw.iterations
        return raw

    rows = []
    old_memory = cache.memory
    out(f"{'engine':<16} {'wall s':>7} {'solves':>6} {'it':>4} {'builds s':>8} "
        f"{'NLP s':>7} {'hess_l s':>8} {'jac_g s':>7} {'other s':>7}")
    with tempfile.TemporaryDirectory() as tmp:
        cache.memory = joblib.Memory(tmp, verbose=0)
        solve_mod.solve_in_model = counted
        try:
            for thrust, isp in engines:
                acc.clear()
                t0 = time.perf_counter()
                solve_engine(thrust, isp, dynamics)
                wall = time.perf_counter() - t0
                row = {"thrust_N": thrust, "isp_s": isp, "wall_s": wall, **acc}
                rows.append(row)
                b, ip = acc.get("build_s", 0.0), acc.get("ipopt_s", 0.0)
                out(f"{thrust:5g} N / {isp:3g} s {wall:7.2f} {acc.get('solves', 0):6d} "
                    f"{acc.get('iterations', 0):4d} {b:8.2f} {ip:7.2f} "
                    f"{acc.get('nlp_hess_l', 0):8.2f} {acc.get('nlp_jac_g', 0):7.2f} "
                    f"{wall - b - ip:7.2f}")
        finally:
            solve_mod.solve_in_model = plain
            cache.memory = old_memory
    return rows


def study_walls(out=print) -> list[dict]:
    """The last recorded run of each study table (every ``*.runs.json`` of the study dir)."""
    import json

    from lunarcap.studies.engine_trade import trade as study

    rows = []
    for path in sorted(study.STUDY.default_table_path().parent.glob("*.runs.json")):
        try:
            runs = json.loads(path.read_text())
        except (OSError, ValueError):
            continue
        if not runs:
            continue
        r = runs[-1]
        rows.append({"table": path.name, **r})
        out(f"{path.name.removesuffix('.runs.json'):<16} {r.get('started_utc', '?'):<24} "
            f"wall {r.get('wall_s', float('nan')):7.1f} s, {r.get('computed', '?')} of "
            f"{r.get('cases', '?')} cases computed ({r.get('reused', 0)} reused), "
            f"{r.get('workers', '?')} workers, load {r.get('load_avg_1min_start', '?')}"
            f" -> {r.get('load_avg_1min_end', '?')}")
    if not rows:   # the registered studies' commands, each of which records its runs
        from lunarcap.studies.registry import studies as registered

        out(f"no study run recorded yet (lunarcap {' / '.join(registered())} write "
            f"<table>.runs.json)")
    return rows


def studies(out=print, cold: bool = True, repeats: int = 3) -> dict:
    """``lunarcap bench --studies``: figures on where the time goes (not a timed test).

    NLP build per shape, cold and cached ``lunarcap plan`` walls, one trade-study engine
    profiled, and the last recorded wall of each study. Wall times on a shared machine are
    noisy: compare ratios, rerun for medians.
    """
    out(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f} (1 min)")
    out("\n== NLP build per shape (this process, full dynamics)")
    builds = nlp_builds(out=out)
    out("\n== lunarcap plan in fresh processes")
    plans = plan_walls(repeats=repeats, cold=cold, out=out)
    out("\n== one trade-study engine (engine_trade.trade.solve_engine), empty cache")
    engines = engine_profile(out=out)
    out("\n== studies, as last recorded")
    walls = study_walls(out=out)
    return {"builds": builds, "plans": plans, "engines": engines, "studies": walls}
