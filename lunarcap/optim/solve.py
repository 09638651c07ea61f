"""Solve one burn with automatic mesh refinement behind the verification gate.

:func:`solve_burn_problem` tries the meshes of
:data:`lunarcap.optim.collocation.DEFAULT_MESHES` in turn (in a gravity field,
:data:`lunarcap.optim.correction.FIELD_MESHES`): build (cached per mesh shape),
guess, IPOPT, independent re-propagation. The first solution that converges *and* passes
verification is returned; otherwise a :class:`~lunarcap.errors.SolveError` carries
IPOPT's status and the residuals of every attempt. A converged IPOPT status alone is never accepted.
"""

from __future__ import annotations

import time
from dataclasses import replace

import numpy as np

from lunarcap.errors import SolveError
from lunarcap.optim.correction import meshes_for, nlp_shape, solve_in_model
from lunarcap.optim.guess import make_guess
from lunarcap.optim.nlp import describe_shape, is_built, shape_of, solve_nlp
from lunarcap.optim.nlp import prebuild as _prebuild_nlps
from lunarcap.optim.nlp import use_store as use_nlp_store  # noqa: F401  (for the capture service)
from lunarcap.optim.problem import BurnProblem
from lunarcap.optim.solution import Solution
from lunarcap.optim.verify import verify
from lunarcap.physics.elements import period


def solve_burn_problem(prob: BurnProblem, meshes=None, guess=None,
                       progress=None, multipliers=None) -> Solution:
    """Optimal finite burn for ``prob``, verified by re-propagation.

    Parameters
    ----------
    prob : BurnProblem
    meshes : sequence of Mesh, optional
        Meshes tried in order until one passes the gate (default
        :func:`lunarcap.optim.correction.meshes_for` the problem's forces).
    guess : Guess or None
        Initial guess (default: :func:`lunarcap.optim.guess.make_guess`).
    progress : callable(str) or None
        Receives one line per attempt.
    multipliers : RawSolution or None
        A solved neighbour of this burn (the nominal of a re-planned burn): on a mesh
        where it solved the same NLP, IPOPT starts from its multipliers too
        (:func:`lunarcap.optim.nlp.solve_nlp`). Not in a field carried by corrections.

    Raises
    ------
    SolveError
        If no mesh gives a converged, verified solution.
    """
    t0 = time.perf_counter()
    meshes = meshes or meshes_for(prob.model.forces)
    try:
        return _solve_on_meshes(prob, meshes, guess, progress, t0, multipliers)
    except SolveError as exc:
        wider = widened(prob)
        if wider is None:
            raise
        if progress:
            progress(f"  ignition window widened to {wider.start_bounds_min[0]:+.1f} .. "
                     f"{wider.start_bounds_min[1]:+.1f} min")
        try:
            return _solve_on_meshes(wider, meshes[:1], None, progress, t0)
        except SolveError:
            raise exc from None


def prebuild(shapes, progress=None) -> None:
    """Build before the first solve the NLPs that solving burns of these shapes starts with.

    ``shapes``: (target kind, free start, steering, dynamics[, free end]) tuples, one per
    burn; each NLP is built on the first mesh :func:`solve_burn_problem` tries, once per
    process (here or at the first solve), carrying what it carries in that dynamics
    (:func:`lunarcap.optim.correction.nlp_shape`: a field's NLP takes corrections).
    ``progress(str)``: what is built, how long (:func:`lunarcap.optim.nlp.prebuild`).
    """
    out = []
    for kind, free_start, steering, dynamics, *free_end in shapes:
        mode, corrected = nlp_shape(dynamics)
        out.append((meshes_for(dynamics)[0], kind, free_start, steering, mode,
                    free_end[0] if free_end else False, corrected))
    _prebuild_nlps(out, progress)


def widened(prob: BurnProblem) -> BurnProblem | None:
    """The problem of an ellipse as asked with a wider free-ignition window, or None.

    The second try of :func:`solve_burn_problem`: three times as early and twice as late
    as the window that failed, within 120 min and 0.4 of the orbit the burn starts on.
    IPOPT's path depends on the bounds (its iterates may stall at one of them), so a wider
    window can succeed where the first failed. Only a failed solve gets here, and never
    one in the paper's formulation (a fixed end epoch).
    """
    if not (prob.free_start and prob.target.free_epoch):
        return None
    lo, hi = prob.start_bounds_min
    x = prob.x_ref
    lim = 120.0
    if np.hypot(x[1], x[2]) < 1:   # the orbit the burn starts on: 0.4 of its period at most
        lim = min(lim, 0.4 * float(period(x[0], x[1], x[2], prob.model.mu)) / 60.0)
    new = (max(3.0 * lo, -lim), min(2.0 * hi, lim))
    if not (new[0] < lo or new[1] > hi):
        return None
    return replace(prob, start_bounds_min=new)


def _solve_on_meshes(prob: BurnProblem, meshes, guess, progress, t0: float,
                     multipliers=None) -> Solution:
    """The mesh loop of :func:`solve_burn_problem` (see there)."""
    guess = guess or make_guess(prob)
    attempts = []
    for mesh in meshes:
        carried = nlp_shape(prob.model.forces)
        if progress and not is_built(mesh, prob, *carried):   # once per machine or process
            progress(f"  building the NLP ({describe_shape(*shape_of(mesh, prob, *carried))})")
        if multipliers is not None and not carried[1]:
            raw = solve_nlp(prob, mesh, guess, multipliers=multipliers)
        else:
            raw = solve_in_model(prob, mesh, guess)
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
            f"{start}, {prob.model.forces} dynamics)")
    detail = "; ".join(
        f"{a['mesh']}: IPOPT {a['ipopt_status']}"
        + (f", verification failed: rp error {a['rp_error_m']:.3g} m, "
           + ", ".join(a["failures"]) if "failures" in a else "")
        for a in attempts)
    raise SolveError(f"{what} failed on every mesh: {detail}", status=last["ipopt_status"],
                     details={"attempts": attempts})
