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
ways of computing IPOPT's derivatives on one solve, the build and load of each NLP shape
with the size and call time of IPOPT's derivative functions, cold, NLPs-stored and
cached ``lunarcap plan`` in fresh processes, one trade-study engine split into NLP builds,
NLP solves and the rest, dispersion samples per CPU second with and without warm
multipliers, and the last logged wall of each study.

What was measured before the NLP store (CasADi 3.8.2, the 2-core machine): the expanded
IPOPT solver of the 8x16 LGR-5 shape, its derivatives made by CasADi's AD, serialised to
88-103 MB and loaded in 1.1-1.4 s, no faster than building it (1.7 s); its generated C
compiled in 242 s at -O1. Assembling the derivatives node by node
(:mod:`lunarcap.optim.derivatives`) makes the same NLP in 0.4-0.6 s, stored in 0.5 MB
and loaded in 0.2-0.4 s, and its one node function compiles in seconds.
"""

from __future__ import annotations

import contextlib
import os
import statistics
import time
from pathlib import Path

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
    """Median CPU time (ms) of one call of ``fun`` at a fixed random point.

    CPU, not wall: on a machine shared with other work, a call's wall time is mostly the
    time the process waits for a core.
    """
    import numpy as np

    rng = np.random.default_rng(0)
    args = [rng.random(fun.size1_in(i)) for i in range(fun.n_in())]
    fun(*args)
    cpus = []
    for _ in range(repeats):
        t0 = time.process_time()
        fun(*args)
        cpus.append(time.process_time() - t0)
    return 1e3 * statistics.median(cpus)


@contextlib.contextmanager
def _nlp_store(directory):
    """The optimiser's NLP store at ``directory`` (None: none) for the block; then the old."""
    from lunarcap.optim import nlp as N
    from lunarcap.repro.cache import NLPStore

    old = N._STORE
    N.use_store(NLPStore(directory) if directory is not None else None)
    N.clear_nlps()
    try:
        yield N
    finally:
        N.use_store(old)
        N.clear_nlps()


def nlp_builds(dynamics: str = "full", out=print) -> list[dict]:
    """Build each NLP shape of the paper's plans in an empty store, then load it from there.

    The shapes: ellipse (``perilune``) and ``circular`` targets, fixed and free ignition,
    on the first default mesh. Per shape: build wall and CPU (s; the first shape's wall
    includes compiling the node functions it needs, once per machine, in a compiler
    process whose CPU is not this one's), the wall and CPU of loading it from the store
    in this process (s), the stored file's size, IPOPT's two derivative
    functions (Hessian of the Lagrangian, constraint Jacobian): instructions of their
    outer graph and the median CPU time of one call (ms).
    """
    import tempfile

    from lunarcap.optim.collocation import DEFAULT_MESHES

    mesh, rows = DEFAULT_MESHES[0], []
    out(f"{'NLP shape':<40} {'build s':>7} {'CPU':>5} {'load s':>6} {'CPU':>5} {'kB':>5} "
        f"{'vars':>5} {'hess_l instr':>12} {'hess_l ms':>9} {'jac_g instr':>11} "
        f"{'jac_g ms':>8}  derivatives")
    with tempfile.TemporaryDirectory() as tmp, _nlp_store(tmp) as N:
        for kind in ("perilune", "circular"):
            for free in (False, True):
                N.clear_nlps()
                c0 = time.process_time()
                nlp = N.build_burn_nlp(mesh, kind, free, "optimal", dynamics)
                c1 = time.process_time()
                N.clear_nlps()
                loaded = N.build_burn_nlp(mesh, kind, free, "optimal", dynamics)
                c2 = time.process_time()
                s = loaded.compiled.solver
                h, j = s.get_function("nlp_hess_l"), s.get_function("nlp_jac_g")
                row = {"shape": f"{mesh.n_burn}x{mesh.n_coast} LGR-{mesh.degree} {kind}"
                                f"{' free start' if free else ''} {dynamics}",
                       "build_s": nlp.compiled.build_s, "load_s": loaded.compiled.build_s,
                       "build_cpu_s": c1 - c0, "load_cpu_s": c2 - c1,
                       "loaded": loaded.compiled.origin == "loaded",
                       "stored_kB": sum(f.stat().st_size for f in Path(tmp).glob("*/*.nlp"))
                       / 1e3 - sum(r["stored_kB"] for r in rows),
                       "n_vars": nlp.compiled.layout.nv,
                       "derivatives": nlp.compiled.derivatives,
                       "hess_l_instructions": h.n_instructions(), "hess_l_ms": _eval_ms(h),
                       "jac_g_instructions": j.n_instructions(), "jac_g_ms": _eval_ms(j)}
                rows.append(row)
                out(f"{row['shape']:<40} {row['build_s']:7.2f} {row['build_cpu_s']:5.2f} "
                    f"{row['load_s']:6.2f} {row['load_cpu_s']:5.2f} "
                    f"{row['stored_kB']:5.0f} {row['n_vars']:5d} "
                    f"{row['hess_l_instructions']:12,d} {row['hess_l_ms']:9.2f} "
                    f"{row['jac_g_instructions']:11,d} {row['jac_g_ms']:8.2f}  "
                    f"{row['derivatives']}")
    return rows


def derivative_options(out=print) -> list[dict]:
    """What each way of computing IPOPT's derivatives gives on one solve, built afresh.

    The first burn of ``song2011-150N`` (full dynamics, ignition 10 min before perilune,
    mesh 8x16 LGR-5) solved from the same guess with the NLP built three ways: CasADi's AD
    of the expanded NLP (what lunarcap did before), the node-by-node assembly with the
    node function in CasADi's virtual machine, and with it compiled to C (built in an empty
    store: the compilation is part of that build). Per way: build wall (s), one call of
    the Hessian and of the Jacobian (CPU ms), IPOPT's iterations, the solve's CPU (s) and
    its CPU per iteration (ms), and the optimum (m/s).
    """
    import tempfile

    from lunarcap.capture.chain import arrival_for
    from lunarcap.mission.plan import load_plan
    from lunarcap.optim.collocation import DEFAULT_MESHES
    from lunarcap.optim.derivatives import compiler
    from lunarcap.optim.guess import make_guess
    from lunarcap.optim.problem import burn_problem

    plan = load_plan("song2011-150N")
    x = arrival_for(plan.arrival, plan.ephemeris, plan.lunar_pole).state
    prob = burn_problem(plan, 0, x, plan.ephemeris_model())
    guess, mesh, rows = make_guess(prob), DEFAULT_MESHES[0], []
    out(f"{'derivatives':<28} {'build s':>7} {'hess_l ms':>9} {'jac_g ms':>8} {'it':>3} "
        f"{'solve CPU s':>11} {'ms/it':>6} {'dV m/s':>12}")
    ways = [("CasADi's AD, expanded NLP", False, None), ("node by node, VM", True, None)]
    if compiler():
        ways.append(("node by node, compiled C", True, "store"))
    for label, nodes, store in ways:
        with tempfile.TemporaryDirectory() as tmp, \
                _nlp_store(tmp if store else None) as N:
            with N.node_derivatives(nodes):
                t0 = time.perf_counter()
                nlp = N.nlp_for(prob, mesh)
                build = time.perf_counter() - t0
                N.solve_nlp(prob, mesh, guess)          # once, so that nothing is first
                c0 = time.process_time()
                raw = N.solve_nlp(prob, mesh, guess)
                cpu = time.process_time() - c0
            s = nlp.compiled.solver
            row = {"derivatives": label, "build_s": build,
                   "hess_l_ms": _eval_ms(s.get_function("nlp_hess_l")),
                   "jac_g_ms": _eval_ms(s.get_function("nlp_jac_g")),
                   "iterations": raw.iterations, "solve_cpu_s": cpu,
                   "ms_per_iteration": 1e3 * cpu / max(raw.iterations, 1),
                   "delta_v_mps": raw.delta_v_mps}
            rows.append(row)
            out(f"{label:<28} {build:7.2f} {row['hess_l_ms']:9.2f} {row['jac_g_ms']:8.2f} "
                f"{raw.iterations:3d} {cpu:11.3f} {row['ms_per_iteration']:6.2f} "
                f"{raw.delta_v_mps:12.6f}")
    return rows


def dispersion_rate(plan: str = "song2011-150N", samples: int = 8, out=print) -> list[dict]:
    """Dispersion samples per second of one core, with and without warm multipliers.

    The nominal solved first (not counted), one sample flown to build or load the NLPs,
    then ``samples`` samples of the book's error model (seed 2011) in this process: CPU
    seconds per sample, samples per CPU second, IPOPT iterations per re-plan, and the
    largest difference in total delta-V between the two (m/s).
    """
    import lunarcap.optim.nlp as N
    from lunarcap.mission.plan import load_plan
    from lunarcap.studies.dispersions import samples as disp

    p = load_plan(plan)
    model = disp.ErrorModel(thrust_sigma_pct=1.0, isp_sigma_pct=0.5, pointing_sigma_deg=0.3,
                            ignition_sigma_s=1.0, arrival_sigma_km=1.0,
                            arrival_sigma_mps=1.0, knowledge_sigma_km=0.1,
                            knowledge_sigma_mps=0.1)
    disp.nominal(p)
    disp.sample_row(p, 2011, 0, model)
    rows, totals, old = [], {}, disp.WARM_MULTIPLIERS
    plain = N.solve_nlp
    iters = []

    def counted(*args, **kwargs):
        raw = plain(*args, **kwargs)
        iters.append(raw.iterations)
        return raw

    out(f"{'re-plans':<34} {'CPU s/sample':>12} {'samples/CPU s':>13} {'it/re-plan':>10}")
    import lunarcap.optim.correction as correction
    import lunarcap.optim.solve as solve

    try:
        solve.solve_nlp, correction.solve_nlp = counted, counted
        for warm in (False, True):
            disp.WARM_MULTIPLIERS = warm
            iters.clear()
            c0 = time.process_time()
            got = [disp.sample_row(p, 2011, k, model) for k in range(1, samples + 1)]
            cpu = (time.process_time() - c0) / samples
            totals[warm] = [r.get("total_delta_v_mps", float("nan")) for r in got]
            label = "warm (nominal's multipliers)" if warm else "cold (primal guess only)"
            rows.append({"plan": plan, "warm": warm, "cpu_s_per_sample": cpu,
                         "samples_per_cpu_s": 1.0 / cpu,
                         "iterations_per_replan": statistics.mean(iters) if iters else 0.0})
            out(f"{label:<34} {cpu:12.3f} {1.0 / cpu:13.2f} "
                f"{rows[-1]['iterations_per_replan']:10.2f}")
    finally:
        disp.WARM_MULTIPLIERS = old
        solve.solve_nlp, correction.solve_nlp = plain, plain
    diff = max(abs(a - b) for a, b in zip(totals[False], totals[True]))
    out(f"{plan}, {samples} samples: total delta-V warm vs cold within {diff:.1e} m/s")
    return rows


def plan_walls(plan: str = "song2011-150N", repeats: int = 3, cold: bool = True,
               out=print) -> list[dict]:
    """Wall of ``lunarcap plan PLAN`` (and with free starts) in fresh processes.

    Cold: an empty cache directory (every burn and impulsive limit solved, every NLP shape
    built, the node functions compiled); NLPs stored: the results deleted, the NLP store
    kept (every burn solved again, every NLP loaded: what a process after the first one of
    a machine pays); cached: the same command again (median of ``repeats``). Also the wall
    of importing the CLI and the heavy packages its import pulls in (none should be).
    """
    import shutil
    import subprocess
    import sys
    import tempfile

    py = sys.executable
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        env = {**os.environ, "LUNARCAP_CACHE_DIR": tmp}
        env.pop("LUNARCAP_NO_CACHE", None)
        env.pop("LUNARCAP_NLP_CACHE", None)
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
        with tempfile.TemporaryDirectory() as tmp:
            env = {**os.environ, "LUNARCAP_CACHE_DIR": tmp}
            env.pop("LUNARCAP_NO_CACHE", None)
            env.pop("LUNARCAP_NLP_CACHE", None)
            cmd = [py, "-m", "lunarcap", "plan", plan, *extra]
            label = " ".join(["lunarcap plan", plan, *extra])
            c = stored = None
            if cold:
                c = _median_wall(cmd, env, 1)
                shutil.rmtree(Path(tmp) / "joblib", ignore_errors=True)
                stored = _median_wall(cmd, env, 1)
            w = _median_wall(cmd, env, repeats)
            rows.append({"command": label, "cold_s": c, "nlps_stored_s": stored,
                         "cached_s": w})
            out(f"{label:<52} cold {'-' if c is None else f'{c:.1f}':>5} s   NLPs stored "
                f"{'-' if stored is None else f'{stored:.1f}':>5} s   cached {w:.2f} s "
                f"(median of {repeats})")
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
        st = nlp.compiled.stats()
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

    The ways of computing IPOPT's derivatives on one solve, NLP build against load per
    shape, cold / NLPs-stored / cached ``lunarcap plan`` walls, one trade-study engine
    profiled, dispersion samples per CPU second, and the last recorded wall of each study.
    Wall times on a shared machine are noisy: compare ratios, rerun for medians.
    """
    out(f"machine: {os.cpu_count()} cores, load average {os.getloadavg()[0]:.2f} (1 min)")
    out("\n== IPOPT's derivatives, three ways (LOI 1 of song2011-150N, full dynamics)")
    options = derivative_options(out=out)
    out("\n== NLP build and load per shape (full dynamics, an empty store)")
    builds = nlp_builds(out=out)
    out("\n== lunarcap plan in fresh processes")
    plans = plan_walls(repeats=repeats, cold=cold, out=out)
    out("\n== one trade-study engine (engine_trade.trade.solve_engine), empty cache")
    engines = engine_profile(out=out)
    out("\n== dispersion samples (song2011-150N, full dynamics, the book's sigmas)")
    rate = dispersion_rate(out=out)
    out("\n== studies, as last recorded")
    walls = study_walls(out=out)
    out(f"load average at the end {os.getloadavg()[0]:.2f} (1 min)")
    return {"derivatives": options, "builds": builds, "plans": plans, "engines": engines,
            "dispersions": rate, "studies": walls}
