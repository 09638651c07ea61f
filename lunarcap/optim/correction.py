"""Solving in a gravity field: the NLP carries a low degree, an outer correction the rest.

A burn of a plan in a spherical-harmonic field of degree n (:mod:`lunarcap.physics.forces`)
is transcribed with the field cut to :data:`NLP_DEGREE` x :data:`NLP_ORDER` (its C20, the
J2 term about the body pole), exactly differentiated, plus,
at every collocation point, a fixed acceleration: the full field's minus the cut field's,
evaluated at that point's state and epoch of the previous solution. Solve, re-evaluate the
difference at the new solution's points, solve again from it (the same meshes, the
previous solution as the initial point), until the difference moves by less than
:data:`TOL_KMPS2` at every point: then the collocation satisfies the full field's
dynamics, and the verification (:mod:`lunarcap.optim.verify`) re-flies it in that field
as it does every solution.

The all-burns NLP (:mod:`lunarcap.optim.joint`) is corrected the same way, at every
collocation point of every leg.

What the correction's optimum is: a point that satisfies the whole field's dynamics and
every target (the verification re-flies it there), optimal for the NLP in which the
higher-degree acceleration is a fixed table. The table is a parameter, so the NLP's
multipliers never see its gradient: the optimum is a feasible point of the whole field,
not shown to be its optimum. The gap is bounded where a field fits in the NLP whole
(:func:`whole`): LP165P 4x4 carried whole and 2x0 plus the correction give the same burn
within 1 mm/s (tests/optim/test_field_gap.py).

Why not the whole field in the NLP: the exact Hessian of the expanded NLP grows with the
square of the field's terms. Measured on the first burn of the paper's arrival as asked
(mesh 8x16 LGR-5, free ignition, this machine, CPU seconds of build + solve and peak
memory): J2 of date 2.3 s, 239 MB; 2x2 3.8 s, 358 MB; 4x4 4.4 s, 485 MB; 8x8 11.4 s,
944 MB; 20x20 had not finished building after 4 min of CPU and 13.7 GB. With the
correction, every degree costs the 2x2 NLP plus a few warm re-solves and the evaluation
of the field at the points (see the book for the timings of whole plans).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from lunarcap.optim.collocation import DEFAULT_MESHES, Mesh
from lunarcap.optim.guess import Guess
from lunarcap.optim.nlp import BurnNLP, RawSolution, nlp_for, solve_nlp
from lunarcap.optim.problem import BurnProblem
from lunarcap.physics.forces import ForceModel, force_model, perturbation_rtn

#: Degree and order of a field the NLP differentiates exactly: its C20 (the J2 term about
#: the body's pole). With 2x2 (C21, S21, C22, S22 too) the corrections converged in as
#: many solves to the same burn (366.8436 m/s, 0.1 mm/s apart) at 1.5x the CPU time (8x32
#: mesh, 20x20 field: 7.9 s against 5.1 s, build and solves).
NLP_DEGREE = 2
NLP_ORDER = 0
#: The correction has converged when no point's moves by more than this, km/s^2 (1e-13
#: km/s^2 acting for a whole 12 h orbit would move the spacecraft by 0.1 m).
TOL_KMPS2 = 1e-13
#: Most re-solves before the correction is declared not converged.
MAX_ITERATIONS = 10
#: Meshes of a burn in a field above the NLP's degree: twice the coast intervals of
#: :data:`lunarcap.optim.collocation.DEFAULT_MESHES`. The field's shortest wavelength
#: passes under a 100 km perilune in 4 min (degree 20); 16 coast intervals (points 2.7
#: min apart there) missed the apolune asked by 169 m and the end speed by 2 mm/s, 24 by
#: 2.5 m but gamma by 2.6e-4 deg; 32 met every gate (apolune 0.6 m, period 3 ms).
FIELD_MESHES = (Mesh(8, 32, 5), Mesh(12, 48, 5), Mesh(18, 72, 6))


@dataclass(frozen=True)
class Carried:
    """What an NLP carries, decided: these forces, and whether it takes corrections.

    Hashable, so a compiled NLP is shared by every model whose NLP is the same (LP165P of
    any degree above 2x0 carries the same 2x0 plus corrections): :func:`carried` gives it
    for a model, :func:`whole` for a field carried whole (no correction, whatever its
    degree: its exact optimum, at a build cost that grows with the square of the field's
    terms; what bounds the correction's gap, see the module docstring).
    """

    forces: ForceModel
    correction: bool = False


def carried(forces) -> Carried:
    """What the NLP of ``forces`` (a preset word, a plan's mapping, a ForceModel) carries."""
    low, corrected = nlp_shape(forces)
    return Carried(force_model(low), corrected)


def whole(forces) -> Carried:
    """``forces`` carried whole by the NLP, with no outer correction."""
    return Carried(force_model(forces), False)


def needs_correction(forces) -> bool:
    """True if a model's NLP needs the outer correction: a field beyond what the NLP carries.

    ``forces``: a preset word, a plan's ``dynamics`` mapping or a ForceModel. Only a field
    above :data:`NLP_DEGREE` x :data:`NLP_ORDER` has terms the NLP leaves to the correction;
    the callers outside the optimiser ask it where a burn may have no impulsive limit.
    """
    if isinstance(forces, Carried):
        return forces.correction
    return force_model(forces).beyond(NLP_DEGREE, NLP_ORDER)


def nlp_forces(forces) -> ForceModel | None:
    """The forces the NLP carries for a model, or None if it carries the model itself."""
    if isinstance(forces, Carried):
        return forces.forces if forces.correction else None
    if not needs_correction(forces):
        return None
    return force_model(forces).truncated(NLP_DEGREE, NLP_ORDER)


def nlp_of(prob: BurnProblem, mesh: Mesh) -> BurnNLP:
    """The NLP :func:`solve_in_model` solves for ``prob`` on ``mesh`` (built on first use)."""
    low = nlp_forces(prob.model.forces)
    return nlp_for(prob, mesh) if low is None else nlp_for(prob, mesh, low, True)


def nlp_shape(forces) -> tuple:
    """(the forces the NLP carries, whether it takes corrections) for a model's NLPs.

    ``forces``: a preset word, a plan's mapping, a ForceModel, or a :class:`Carried`.
    """
    if isinstance(forces, Carried):
        return forces.forces, forces.correction
    low = nlp_forces(forces)
    return (forces, False) if low is None else (low, True)


def meshes_for(forces) -> tuple:
    """The meshes tried in turn for a burn in these forces."""
    return FIELD_MESHES if needs_correction(forces) else DEFAULT_MESHES


def field_mesh(mesh: Mesh, forces) -> Mesh:
    """``mesh`` as a leg in these forces needs it: twice the coast intervals in a corrected field.

    The reason of :data:`FIELD_MESHES` (the field's short wavelengths under the perilune),
    for a caller that names a mesh of :data:`~lunarcap.optim.collocation.DEFAULT_MESHES`.
    """
    if not needs_correction(forces):
        return mesh
    return Mesh(mesh.n_burn, 2 * mesh.n_coast, mesh.degree)


def _phases(raw: RawSolution) -> dict:
    """(epochs, states) at the collocation points of each phase of a solution."""
    out = {"accel_burn": (raw.t_burn[1:], raw.x_burn[:, 1:]),
           "accel_coast": (raw.t_coast[1:], raw.x_coast[:, 1:])}
    if raw.t_pre is not None:
        out["accel_pre"] = (raw.t_pre[1:], raw.x_pre[:, 1:])
    return out


def _accel(forces: ForceModel, prm, t, x) -> np.ndarray:
    """The forces' perturbation in RTN at states x (7, N) and epochs t (N,), km/s^2."""
    a = perturbation_rtn(forces, [x[i] for i in range(6)], np.asarray(t, float), prm)
    return np.vstack([np.broadcast_to(np.asarray(c, float), (np.size(t),)) for c in a])


def field_difference(forces: ForceModel, low: ForceModel, prm, phases: dict) -> dict:
    """Per phase, the acceleration of ``forces`` minus that of ``low``, RTN km/s^2.

    ``phases``: ``{name: (epochs (N,) s, states (7, N))}`` at the collocation points;
    ``prm``: the model's parameter vector (the ephemeris fit the body frame reads).
    """
    return {name: _accel(forces, prm, t, x) - _accel(low, prm, t, x)
            for name, (t, x) in phases.items()}


def corrections(raw: RawSolution, prob: BurnProblem, low: ForceModel) -> dict:
    """Per phase, the full field's acceleration minus the NLP's at the solution's points."""
    return field_difference(prob.model.forces, low, prob.model.params(), _phases(raw))


def largest_change(new: dict, old: dict) -> float:
    """The largest change of a correction between two solves, km/s^2."""
    return max(float(np.abs(new[n] - old[n]).max()) for n in new)


def zero_corrections(prob: BurnProblem, mesh: Mesh) -> dict:
    """The corrections of a first solve (none), shaped for the NLP of ``prob`` on ``mesh``."""
    from lunarcap.optim.collocation import N_PRE

    out = {"accel_burn": np.zeros((3, mesh.n_burn * mesh.degree)),
           "accel_coast": np.zeros((3, mesh.n_coast * mesh.degree))}
    if prob.free_start:
        out["accel_pre"] = np.zeros((3, N_PRE * mesh.degree))
    return out


def solve_corrected(prob: BurnProblem, mesh: Mesh, guess: Guess) -> RawSolution:
    """The burn's NLP in its field, by outer corrections (see the module docstring).

    Returns the last solution, its ``corrections`` (re-solves) and ``correction_change``
    (the last largest change, km/s^2); ``solve_s`` and ``iterations`` are the sums over
    the solves. A correction that has not converged after :data:`MAX_ITERATIONS` leaves
    ``success`` False with the status ``Correction_Not_Converged``.
    """
    low = nlp_forces(prob.model.forces)
    accel = zero_corrections(prob, mesh)
    w0 = fractions = None
    solve_s, iterations, change = 0.0, 0, np.inf
    for k in range(1, MAX_ITERATIONS + 1):
        raw = solve_nlp(prob, mesh, guess, mode=low, accel=accel, w0=w0, fractions=fractions)
        solve_s, iterations = solve_s + raw.solve_s, iterations + raw.iterations
        if not raw.success:
            break
        new = corrections(raw, prob, low)
        change = largest_change(new, accel)
        accel, w0, fractions = new, raw.w, (raw.mesh_burn, raw.mesh_coast)
        if change < TOL_KMPS2:
            break
    raw.corrections, raw.correction_change = k, change
    raw.solve_s, raw.iterations = solve_s, iterations
    if raw.success and not change < TOL_KMPS2:
        raw.success, raw.status = False, "Correction_Not_Converged"
    return raw


def solve_in_model(prob: BurnProblem, mesh: Mesh, guess: Guess) -> RawSolution:
    """The burn's NLP: directly, or by outer corrections for a field above the NLP's degree."""
    if not needs_correction(prob.model.forces):
        return solve_nlp(prob, mesh, guess)
    return solve_corrected(prob, mesh, guess)
