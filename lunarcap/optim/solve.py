"""Solve one burn with automatic mesh refinement behind the verification gate.

:func:`solve_burn` tries the meshes of :data:`lunarcap.optim.collocation.DEFAULT_MESHES` in turn:
build (cached per mesh shape), guess, IPOPT, independent re-propagation. The first
solution that converges *and* passes verification is returned; otherwise a
:class:`~lunarcap.errors.SolveError` carries IPOPT's status and the residuals of every
attempt. A converged IPOPT status alone is never accepted.
"""

from __future__ import annotations

import time

from lunarcap.errors import SolveError
from lunarcap.optim.collocation import DEFAULT_MESHES
from lunarcap.optim.guess import make_guess
from lunarcap.optim.nlp import solve_nlp
from lunarcap.optim.problem import BurnProblem
from lunarcap.optim.solution import Solution
from lunarcap.optim.verify import verify


def solve_burn(prob: BurnProblem, meshes=DEFAULT_MESHES, guess=None, progress=None) -> Solution:
    """Optimal finite burn for ``prob``, verified by re-propagation.

    Parameters
    ----------
    prob : BurnProblem
    meshes : sequence of Mesh
        Meshes tried in order until one passes the gate.
    guess : Guess or None
        Initial guess (default: :func:`lunarcap.optim.guess.make_guess`).
    progress : callable(str) or None
        Receives one line per attempt.

    Raises
    ------
    SolveError
        If no mesh gives a converged, verified solution.
    """
    t0 = time.perf_counter()
    guess = guess or make_guess(prob)
    attempts = []
    for mesh in meshes:
        raw = solve_nlp(prob, mesh, guess)
        rec = {"mesh": mesh.label(), "ipopt_status": raw.status,
               "iterations": raw.iterations, "nlp_solve_s": raw.solve_s,
               "delta_v_mps": raw.delta_v_mps}
        if not raw.success:
            rec["verified"] = False
            attempts.append(rec)
            if progress:
                progress(f"  mesh {rec['mesh']}: IPOPT {raw.status} after {raw.iterations} it")
            continue
        ver, flight = verify(raw, return_flight=True)
        rec.update({"verified": ver.passed, "rp_error_m": ver.rp_error_m,
                    "inc_error_deg": ver.inc_error_deg, "gamma_error_deg": ver.gamma_error_deg,
                    "delta_v_diff_mps": ver.delta_v_diff_mps, "failures": ver.failures()})
        attempts.append(rec)
        if progress:
            progress(f"  mesh {rec['mesh']}: {raw.status}, {raw.iterations} it, verification "
                     f"{'passed' if ver.passed else 'FAILED: ' + '; '.join(ver.failures())}")
        if ver.passed:
            return Solution(raw, ver, flight, attempts, time.perf_counter() - t0, guess.t1_s)
    last = attempts[-1]
    start = "free" if prob.free_start else f"{prob.start_min:g} min"
    what = (f"burn {prob.index} ({prob.model.thrust_N:g} N, {prob.model.isp_s:g} s, start "
            f"{start}, {prob.model.mode} dynamics)")
    detail = "; ".join(
        f"{a['mesh']}: IPOPT {a['ipopt_status']}"
        + (f", verification failed: rp error {a['rp_error_m']:.3g} m, "
           + ", ".join(a["failures"]) if "failures" in a else "")
        for a in attempts)
    raise SolveError(f"{what} failed on every mesh: {detail}", status=last["ipopt_status"],
                     details={"attempts": attempts})
