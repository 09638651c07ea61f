"""The recovery after a cut-off or a late ignition: the rest of the capture, re-planned.

Split from :mod:`lunarcap.studies.missed.cases` (which re-exports its names). From the state a
fault leaves at ``t_r`` (burn n cut off, after the delay; or burn n's late ignition),
:func:`recovery` answers in one of three ways, in this order:

1. **Nothing to make up** (:func:`nothing_to_make_up`): coasting from that state, the
   spacecraft meets burn n's target where the nominal met it, within the verification
   gate's own tolerances (:mod:`lunarcap.optim.verify`: perilune radius 10 m,
   inclination and flight-path angle 1e-4 deg; apolune 50 m and period 0.5 s for an
   ellipse as asked; a circle's radii 10 m). The make-up burn vanishes and is **not
   flown**: the recovery is the nominal's later burns, as verified (a cut-off at the
   planned end, f = 1, after any delay). Skipping it is the honest answer, not gating a
   burn of next to nothing with tolerances scaled down to it: the orbit left is checked
   with the full gate, and a burn that is not needed is no burn (the transcription
   resolves burns of 0.5 s and more, :data:`lunarcap.mission.plan.MIN_BURN_S`).
2. **A make-up burn in the window** (:func:`recover`): igniting within ``window_min``
   after ``t_r`` (a late ignition: exactly then), with burn n's target, then burns n+1,
   ... with free ignitions, to the same final orbit, re-optimised as one NLP (total
   delta-V) and verified leg by leg. The orbit after an intermediate burn is free up to
   ``max_period_s`` (as in the nominal, :func:`lunarcap.studies.missed.cases.freed`); the make-up
   may still be small (its duration bounded below by :data:`MIN_MAKE_UP_S`, not by
   Eq. 10).
3. **The make-up burn at the next perilune** (a cut-off only, when 2 found no verified
   recovery and the orbit is bound): the same re-plan with the make-up window around the
   spacecraft's next perilune (:func:`next_perilune_window`). The last burn's target (the
   final circle or ellipse) passes only through radii between its perilune and apolune:
   a cut-off of it followed by a delay leaves the spacecraft above them until it comes
   back to perilune, where the burn is done again.

The NLP starts from guesses, not from a burn-by-burn solve: the make-up burn sized from
the two-body delta-V actually needed (:func:`make_up_estimate`, or for the final orbit
the tangential impulse to its energy), each later burn the plan's anti-velocity guess
chained from the one before. If IPOPT fails from there, once more from the nominal's: a
make-up of the delta-V the nominal burn had left, its orbit reaching the nominal's next
perilune, the later burns flying the nominal's steering. If neither finds a verified
recovery, the plan's guesses again with the make-up orbit's coast ending at the nominal's
next perilune. In full dynamics the first start is the same recovery solved in two-body
dynamics (:func:`from_two_body`), and the meshes begin at the second
(:func:`recovery_meshes`). A solution that converged but failed verification is the next
mesh's start. The free orbit after an
intermediate burn is bounded below too, so that the next burn keeps a burn to do
(:func:`lunarcap.studies.missed.orbits.shortest_free_period_s`).
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from lunarcap.errors import SolveError
from lunarcap.mission.plan import MAX_START_MIN, CapturePlan, PlanError
from lunarcap.mission.targets import CIRCULAR, PERILUNE
from lunarcap.optim import flight
from lunarcap.optim.collocation import DEFAULT_MESHES, Mesh, sundman_fractions
from lunarcap.optim.gate import TOL_PERIOD_S, state_failures
from lunarcap.optim.guess import guess_arcs, make_guess
from lunarcap.optim.joint import solve_joint
from lunarcap.optim.problem import MIN_ORBIT_WINDOW_MIN, burn_problem
from lunarcap.physics import constants as C
from lunarcap.physics.dynamics import Model
from lunarcap.physics.elements import mean_motion_and_anomaly
from lunarcap.physics.propagate import propagate
from lunarcap.physics.rocket import burn_duration_estimate_s
from lunarcap.physics.state import State
from lunarcap.studies.missed.orbits import (
    after_free_orbit,
    make_up_estimate,
    period_s,
    physical_bound,
    shortest_free_period_s,
    time_to_perilune_after_impulse_s,
)

#: Shortest coast from the fault's end to the make-up orbit's perilune, s.
MIN_FIRST_COAST_S = 600.0
#: Lower bound of the make-up burn's duration, s: about nothing (0.003 m/s at 150 N and
#: 525 kg), so the optimiser may drop the burn; nonzero so the burn's mesh keeps its size.
MIN_MAKE_UP_S = 0.01
#: Sizing period of the make-up orbit over the shortest free one (:func:`_sized`): a
#: little above it, so that the next burn's Eq. (19) duration is not at the edge.
SHORTEST_PERIOD_MARGIN = 1.001
#: A full-dynamics recovery started from the two-body one (:func:`from_two_body`) is taken
#: as found if it costs at most this fraction more than the two-body recovery; otherwise
#: the other starts are solved too and the cheapest verified is kept. Where both are the
#: same optimum they differ by the Earth's and the Sun's effect: 0.2-0.3 % on the book's
#: grid (150 N), 0.6 % for family-0 of the seed-24 family (730.59 vs 726.57 m/s), 1.1-1.2 %
#: for family-3's cut-offs without delay, 2.1-2.5 % for its cut-offs with a 30 min delay
#: (at 2 % every other start was solved for them, up to 414 s, and none found a cheaper
#: one). At 5 % a costlier optimum passed: family-5 (444 N), cut off after 0.9 with no
#: delay, +15.4 m/s at 4.5 % above the two-body recovery, where the other starts find
#: +0.017 m/s. Family-0's half-way cut-off with a 30 min delay was recovered only far above
#: it (+280.2 m/s, 20 % above; the same case in two-body dynamics +74.2) until the next
#: burn's bound was widened (:func:`~lunarcap.studies.missed.orbits.after_free_orbit`): now
#: +41.30 m/s within the margin. The margin is one for every plan: family-5's own nominal
#: costs 3.5 % more in full dynamics than in two-body, and 4 of its 20 rows are labelled.
CONTINUATION_MARGIN = 0.03
#: Longest half-width of the make-up window around the next perilune, as a fraction of
#: the orbit's period (as the plan's free ignitions, :data:`lunarcap.mission.plan_checks`).
MAX_WINDOW_FRACTION = 0.4


#: Meshes of a recovery, tried in turn (:func:`on_meshes`): the solver's, then one with
#: twice the finest's burn intervals. A make-up burn may be long and steered hard (family-11
#: of the seed-24 family, two-body: its final burn 5 min late, 34.5 min at 239 N, 112 m/s
#: more than the nominal's; on Mesh(18, 36, 6) its re-flown end missed by 73 m and 3.5e-4
#: deg of flight-path angle, on Mesh(36, 36, 6) it passes the gate).
RECOVERY_MESHES = DEFAULT_MESHES + (Mesh(36, 36, 6), Mesh(36, 72, 6))


def recovery_meshes(nplan: CapturePlan) -> tuple:
    """The meshes a recovery of ``nplan`` tries (:data:`RECOVERY_MESHES`).

    Beyond two-body dynamics, from the second: with the Earth, the Sun and J2 the
    coarsest mesh's recoveries mostly fail verification, and each failure costs that
    mesh's NLP build in every worker (the book's grid, 150 N, full dynamics: 3 of its 6
    solved cases failed on 8x16 LGR-5 and passed on 12x24; starting there, the same
    penalties to 0.1 mm/s, and the study's CPU 72 -> 60 s on 2 workers).
    """
    return RECOVERY_MESHES if nplan.dynamics == "two-body" else RECOVERY_MESHES[1:]


def on_meshes(solve, meshes=RECOVERY_MESHES):
    """``solve(mesh)`` on each mesh in turn until its solution passes verification.

    A finer mesh is tried only when the coarse one converged but failed verification
    (a long free coast or a long burn resolved too coarsely: in full dynamics the
    nominal's 24 h orbit passes only on the finest); any other failure is raised at once.
    """
    for j, mesh in enumerate(meshes):
        try:
            return solve(mesh)
        except SolveError as exc:
            if exc.status != "verification failed" or j == len(meshes) - 1:
                raise


# ---------------------------------------------------------------------- 1. nothing to do
def target_misses(target, x_end, max_period_s: float | None = None) -> list[str]:
    """How the state ``x_end`` misses ``target``, against the verification gate's tolerances.

    The gate's target part (:func:`lunarcap.optim.gate.state_failures`), on a state the
    fault left rather than a solution; with ``max_period_s`` also the period bound of a
    free orbit. Empty if none.
    """
    x = np.asarray(x_end, float)
    out = state_failures(target, x[:6])
    if max_period_s is not None:
        e2 = x[1] ** 2 + x[2] ** 2
        a = x[0] / (1 - e2) if e2 < 1 else math.inf
        if not (math.isfinite(a) and period_s(a) <= max_period_s + TOL_PERIOD_S):
            out.append(f"the orbit is longer than {max_period_s / 3600:g} h")
    return out


def nothing_to_make_up(legs: list, i: int, t_r: float, x_r, max_period_s: float) -> bool:
    """True if ``x_r`` at ``t_r``, coasting, meets burn ``i``'s target as the nominal did.

    Flown in the nominal leg's dynamics to the end of its coast (the perilune where its
    target held) and checked with :func:`target_misses` (the orbit of an intermediate burn
    also within ``max_period_s``, the bound the nominal had).
    """
    prob = legs[i].problem
    if not t_r < prob.t_end_s:
        return False
    end = flight.coast(prob.model, State(t_r, np.asarray(x_r, float)), prob.t_end_s).end
    bound = max_period_s if i + 1 < len(legs) else None
    return not target_misses(prob.target, end.x, bound)


# ---------------------------------------------------------------------- 2. the make-up
def _sized(nplan: CapturePlan, i: int) -> CapturePlan:
    """The plan with burn ``i``'s period between its own and the next orbit's (geometric mean).

    A resumed plan's first burn needs a nonzero impulsive delta-V from the start state to
    pass the plan's engine checks (its Eq. 19 duration), but the make-up orbit is free in
    the NLP, so that period only sizes the checks: with the nominal's own period, a
    cut-off at the planned end (nothing to make up) would be refused. Never shorter than
    :func:`~lunarcap.studies.missed.orbits.shortest_free_period_s` (the bound the NLP puts on
    that orbit): in full dynamics the nominal's coast after burn ``i`` may be little
    longer than the next orbit's (family-5 of the seed-24 family, 444 N: the two means
    sized burn 2 at 0.3 m/s, 0.46 s by Eq. 19, and the checks refused every recovery as
    "444 N is too strong").
    """
    if nplan.targets[i].kind != PERILUNE or i + 1 >= nplan.n_burns:
        return nplan
    period = max(math.sqrt(nplan.coast_s(i) * nplan.coast_s(i + 1)),
                 SHORTEST_PERIOD_MARGIN * shortest_free_period_s(nplan, i))
    burn = replace(nplan.burns[i], period_s=period, apolune_altitude_km=None)
    return replace(nplan, burns=nplan.burns[:i] + (burn,) + nplan.burns[i + 1:])


def _make_up_dv_mps(rec_plan: CapturePlan, x, max_period_s: float) -> float:
    """Two-body delta-V the make-up burn needs at ``x`` (see :func:`recovery_warm_start`)."""
    if rec_plan.targets[0].kind == PERILUNE:   # a free orbit: down to the period bound
        return make_up_estimate(x, rec_plan.perilune_radius_km, max_period_s)["delta_v_mps"]
    return rec_plan.impulsive()[0].delta_v_mps   # the final orbit's energy


def recovery_warm_start(rec_plan: CapturePlan, eph, fit, max_period_s: float,
                        mesh_n_coast: int, nominal: list | None = None,
                        late: bool = False, dv_mps: float | None = None,
                        ignition_min: float | None = None) -> tuple:
    """Problems and guesses of a recovery's legs, without solving any (see the module).

    The make-up leg ignites at the window's opening, thrusts opposite the velocity for the
    duration of the two-body delta-V it needs (a free orbit: :func:`make_up_estimate`, to
    the period bound; the final orbit: the tangential impulse to its energy; at least
    1 s), its lower duration bound :data:`MIN_MAKE_UP_S`; each later leg is the plan's
    guess (anti-velocity, tuned to reach its perilune on time) from the end of the leg
    before. With ``nominal`` (Solutions or RawSolutions of the same burns: the nominal's,
    or another solve's), each later leg flies that steering from there instead, igniting
    as it did after its perilune (:func:`lunarcap.optim.flight.flown_guess`), and with
    ``late`` so does the make-up (a late ignition: the whole burn, ignited late; a
    recovery solved in two-body dynamics, or one that failed verification);
    ``dv_mps``: the make-up's delta-V instead of the estimate's, m/s; ``ignition_min``:
    the make-up's guessed ignition, min after the start (default the window's opening).
    Returns (warm list, estimate dict).
    """
    x_r = np.array(rec_plan.start.state)
    lo_min = rec_plan.burns[0].start_bounds_min[0] if ignition_min is None else ignition_min
    prob = burn_problem(rec_plan, 0, x_r, eph, fit=fit, guess_start_min=lo_min)
    est = {"delta_v_mps": _make_up_dv_mps(rec_plan, prob.x0, max_period_s)
           if dv_mps is None else float(dv_mps)}
    t1 = max(burn_duration_estimate_s(prob.x0[6], est["delta_v_mps"], prob.model.thrust_N,
                                      prob.model.isp_s), 1.0)
    span = prob.t_end_s - prob.t_ign_s
    prob = replace(prob, t1_min_s=MIN_MAKE_UP_S,
                   t1_max_s=min(max(3 * t1, prob.burn_bounds_s[1]), 0.9 * span))
    raws = None if nominal is None else [getattr(s, "raw", s) for s in nominal]
    if raws is not None and late:
        guess = flight.flown_guess(raws[0], prob)
    else:
        guess = make_guess(prob, t1) if est["delta_v_mps"] > 1.0 else guess_arcs(prob, t1)
    warm = [(prob, guess, sundman_fractions(guess.coast.t, guess.coast.x, mesh_n_coast))]
    for k in range(1, rec_plan.n_burns):
        x_peri = guess.coast.x[:, -1]
        prob = burn_problem(rec_plan, k, x_peri, eph, fit=fit, guess_start_min=None
                            if raws is None else raws[k].prob.start_min)
        if k == 1 and rec_plan.targets[0].kind == PERILUNE:   # after the free make-up orbit
            prob = after_free_orbit(prob, rec_plan, 0, max_period_s)
        guess = make_guess(prob) if raws is None else flight.flown_guess(raws[k], prob)
        warm.append((prob, guess, sundman_fractions(guess.coast.t, guess.coast.x,
                                                    mesh_n_coast)))
    return warm, est


def _nearest_perilune_s(x, t_s: float, mu: float = C.MU_MOON) -> float:
    """Epoch of the two-body perilune of state ``x`` nearest to ``t_s`` (past or next), s."""
    n, M = mean_motion_and_anomaly(np.asarray(x, float), mu)
    return t_s - float(M) / float(n)


def first_coast_guess_s(nplan: CapturePlan, i: int, t_r: float, x_r, window_min: tuple,
                        max_period_s: float, coast: Model, dv_mps: float | None = None
                        ) -> float:
    """The make-up leg's coast (from ``t_r`` to where its target holds) the NLP starts from, s.

    A free orbit: the two-body time to the perilune after the make-up impulse of
    :func:`make_up_estimate` at the window's opening (at least past the window and the
    burn). The final orbit: a circle, the window, twice the Eq. (19) duration and the
    plan's coast after the circle; an ellipse as asked, one of its periods after the
    perilune nearest the burn (its perilune is where the burn leaves it), past the burn.
    ``dv_mps``: the make-up's delta-V instead of the estimate's, m/s.
    """
    t_ig = t_r + 60.0 * window_min[0]
    x_ig = propagate(coast, t_r, x_r, t_ig).final if t_ig > t_r else np.asarray(x_r, float)
    dv = make_up_estimate(x_ig, nplan.perilune_radius_km, max_period_s)["delta_v_mps"] \
        if dv_mps is None else dv_mps
    accel = nplan.engine.thrust_N / x_ig[6]   # m/s^2
    target = nplan.targets[i]
    if target.kind == PERILUNE:
        after = 60.0 * (window_min[1] - window_min[0]) + 2 * dv / accel
        t = time_to_perilune_after_impulse_s(x_ig, dv, after)
        t = min(t, max_period_s) if math.isfinite(t) else max_period_s
        return max(t + t_ig - t_r, 60.0 * window_min[1] + MIN_FIRST_COAST_S)
    t19 = 2 * nplan.resumed(i, t_ig, x_ig, window_min=(0.0, 0.0), first_coast_s=1e4,
                            make_up=True).impulsive()[0].delta_v_mps / accel
    if target.kind == CIRCULAR:
        return 60.0 * window_min[1] + t19 + nplan.coast_s(i)
    end_burn = t_ig + t19
    t = _nearest_perilune_s(x_ig, t_ig + t19 / 2) if np.hypot(x_ig[1], x_ig[2]) < 1 \
        else end_burn
    t += target.period_s()
    while t < end_burn + MIN_FIRST_COAST_S:
        t += target.period_s()
    return t - t_r


def recover(nplan: CapturePlan, i: int, t_r: float, x_r, window_min: tuple,
            max_period_s: float, fit, coast: Model, nominal: list | None = None,
            late: bool = False, dv_mps: float | None = None,
            first_coast_s: float | None = None, ignition_min: float | None = None):
    """Re-plan the capture from burn ``i`` (0-based) at ``t_r`` from ``x_r`` (see the module).

    ``nominal``, ``late``, ``dv_mps``, ``ignition_min``: the guesses'
    (:func:`recovery_warm_start`);
    ``first_coast_s``: the make-up leg's coast the NLP starts from (default
    :func:`first_coast_guess_s`), s. A solution that converged on a mesh but failed
    verification is the next mesh's start (its flight: the coasts' mesh spaced for the
    orbits it found, not the guess's; family-0 of the seed-24 family, full dynamics, cut
    off half-way, 30 min: from the nominal's start leg 2 missed by 4.7 km on every mesh,
    each started from the same guess). Returns the
    :class:`~lunarcap.optim.joint.JointResult` (verified) and the make-up estimate; raises
    SolveError (IPOPT or verification) or PlanError (no such plan).
    """
    first_coast = first_coast_s or first_coast_guess_s(nplan, i, t_r, x_r, window_min,
                                                       max_period_s, coast, dv_mps)
    rec_plan = _sized(nplan, i).resumed(i, t_r, x_r, first_coast_s=first_coast,
                                        window_min=window_min, make_up=True)
    eph = nplan.ephemeris_model()
    est = {}
    last = []   # the last converged solution that failed verification

    def solve(mesh):
        if last:   # the next mesh starts from its flight (its coasts Sundman-spaced)
            p, raws = last[-1]
            plan = _sized(nplan, i).resumed(i, t_r, x_r, first_coast_s=p.coast_s(0),
                                            window_min=window_min, make_up=True)
            warm, _ = recovery_warm_start(plan, eph, fit, max_period_s, mesh.n_coast, raws,
                                          True, raws[0].delta_v_mps,
                                          (raws[0].prob.t_ign_s - t_r) / 60.0)
        else:   # (the make-up's estimate is this first start's)
            plan = rec_plan
            warm, e = recovery_warm_start(plan, eph, fit, max_period_s, mesh.n_coast,
                                          nominal, late, dv_mps, ignition_min)
            est.update(e)
        try:
            return _solve_recovery(plan, nplan.targets[i].kind, i, nplan, eph, mesh, fit,
                                   warm, window_min, max_period_s)
        except SolveError as exc:
            if exc.unverified is not None:
                last.append(exc.unverified)
            raise
    res = on_meshes(solve, recovery_meshes(nplan))
    est["first_coast_guess_s"] = first_coast
    return res, est


def from_two_body(nplan: CapturePlan, i: int, t_r: float, x_r, window_min: tuple,
                  max_period_s: float, fit, coast: Model, starts: tuple,
                  late: bool = False) -> tuple:
    """:func:`recover` in the plan's dynamics, started from the same recovery in two-body.

    The first start in full dynamics, before the plan's guesses and the nominal's (a
    continuation in the forces, as :func:`lunarcap.studies.missed.cases.nominal` starts from the
    two-body optimum): the same state re-planned without the Earth, the Sun and J2, then
    every leg of that recovery (the make-up's ignition, delta-V and steering, its coast,
    the later burns' steering) flown in the plan's dynamics as the guess. Family-0 of the
    seed-24 family (537 N, 538 kg, full dynamics), burn 1 cut off after a quarter, no
    delay: from the plan's guesses a verified local optimum 63.2 m/s above the nominal
    (in two-body dynamics the same case costs nothing); from the two-body recovery
    +2.65 m/s, in 14 s of solves (+0.80 m/s since the next burn's bound was widened,
    :func:`~lunarcap.studies.missed.orbits.after_free_orbit`); a 1 min late ignition ended in
    IPOPT's Restoration_Failed from the plan's guesses and failed verification from the
    nominal's. ``starts``: the (nominal, its delta-V, its first coast) the two-body recovery
    starts from, in turn (:func:`recovery`'s); ``late``: a late ignition. Returns what
    :func:`recover` returns; raises what it raises (the first two-body solve's error if none
    converged).
    """
    two, error = nplan.with_dynamics("two-body"), None
    for nominal, dv, first_coast_s in starts:
        try:
            res2, _ = recover(two, i, t_r, x_r, window_min, max_period_s, fit,
                              replace(coast, mode="two-body"), nominal, late, dv,
                              first_coast_s)
            break
        except (SolveError, PlanError, RuntimeError) as exc:
            error = error or exc
    else:
        raise error
    ign_min = (res2.legs[0].problem.t_ign_s - t_r) / 60.0
    try:
        res, est = recover(nplan, i, t_r, x_r, window_min, max_period_s, fit, coast,
                           res2.legs, True, res2.legs[0].delta_v_mps, res2.plan.coast_s(0),
                           ign_min)
    except (SolveError, PlanError, RuntimeError) as exc:   # what the two-body one cost
        exc.two_body_delta_v_mps = res2.total_delta_v_mps
        raise
    est["two_body_delta_v_mps"] = res2.total_delta_v_mps
    return res, est


def _plausible(res, est) -> bool:
    """True if a recovery from the two-body one is that recovery's optimum.

    That is, if it costs at most :data:`CONTINUATION_MARGIN` more than the two-body
    recovery (the same optimum, the Earth and the Sun aside).
    """
    return res.total_delta_v_mps <= (1.0 + CONTINUATION_MARGIN) * est["two_body_delta_v_mps"]


def _solve_recovery(rec_plan: CapturePlan, kind: str, i: int, nplan: CapturePlan, eph, mesh,
                    fit, warm: list, window_min: tuple, max_period_s: float):
    """The all-burns NLP of a recovery (:func:`recover`) on ``mesh`` from ``warm``."""
    if kind != PERILUNE:   # the final orbit: its coast the plan's
        return solve_joint(rec_plan, None, eph, mesh, fit=fit, warm=warm, expand=True)
    free = (True,) + (False,) * (rec_plan.n_burns - 1)
    hi = 60.0 * window_min[1] + max_period_s + 7200.0
    return solve_joint(rec_plan, None, eph, mesh, free_coasts=free,
                       coast_bounds_s=(MIN_FIRST_COAST_S, hi), fit=fit,
                       max_period_s=max_period_s, warm=warm, expand=True,
                       min_period_s=shortest_free_period_s(nplan, i))


def _with_two_body(exc: Exception, two_body_mps: float | None) -> Exception:
    """A solver's failure in full dynamics, with what the two-body recovery cost if it had one.

    No start converged to a verified recovery in the plan's dynamics, but the same
    recovery without the Earth, the Sun and J2 was solved and verified: its delta-V is the
    reader's estimate of the answer.
    """
    if two_body_mps is None or not isinstance(exc, SolveError):
        return exc
    return SolveError(f"{str(exc).splitlines()[0]}; the same recovery in two-body dynamics "
                      f"was solved and verified: {two_body_mps:.1f} m/s", status=exc.status,
                      details=exc.details)


# ---------------------------------------------------------------------- 3. next perilune
def next_perilune_window(x, after_s: float, half_width_s: float) -> tuple | None:
    """The window (min after the state's epoch) around its next two-body perilune.

    The first perilune later than ``after_s`` of the orbit of ``x``; half-width
    ``half_width_s``, at most :data:`MAX_WINDOW_FRACTION` of the period and never before
    ``after_s``. None if the orbit is open.
    """
    t = time_to_perilune_after_impulse_s(x, 0.0, after_s)
    if not math.isfinite(t):
        return None
    xx = np.asarray(x, float)
    a = xx[0] / (1 - xx[1] ** 2 - xx[2] ** 2)
    w = min(half_width_s, MAX_WINDOW_FRACTION * period_s(a), t - after_s)
    return ((t - w) / 60.0, (t + w) / 60.0)


def recovery(nplan: CapturePlan, legs: list, i: int, t_r: float, x_r, window_min: tuple,
             max_period_s: float, fit_for, coast: Model, later: bool = True,
             remaining_mps: float | None = None) -> tuple:
    """The recovery from ``x_r`` at ``t_r`` (see the module): ``(how, result, estimate)``.

    ``how``: "none" (nothing to make up: ``result`` None), "window" or "next perilune"
    (``result`` the verified JointResult), or "no recovery" (``result`` the physical
    reason of :func:`physical_bound` for the window). ``fit_for(window)``: the ephemeris
    fit of a recovery whose make-up ignites in ``window`` (min after ``t_r``). ``later``:
    the make-up at the next perilune may be tried (a cut-off, not a late ignition), if
    that perilune comes within ``max_period_s``: when the window gives no verified
    recovery, and when the window's costs more than the nominal burn itself
    (:func:`dearer_than_the_burn`), the cheaper kept (then the estimate's
    ``window_delta_v_mps``: the window's recovery burns, m/s). ``remaining_mps``: the delta-V of the
    nominal burn not flown (m/s; default all of it): when the plan's guesses fail, the
    recovery starts from the nominal's, a make-up of that delta-V then the nominal's
    steering of the later burns; when both fail and the nominal's perilune after burn n is
    still ahead, the plan's guesses again with the make-up orbit's coast ending there
    (family-5 of the seed-24 family, 444 N, burn 1 ignited 5 min late: the make-up
    estimate's 24 h orbit was infeasible from either start, in two-body and full dynamics;
    from the nominal's 12 h coast it is recovered, +0.25 m/s). Raises what
    :func:`recover` raises (the window's SolveError, PlanError or RuntimeError, if the next
    perilune fails too).
    """
    if nothing_to_make_up(legs, i, t_r, x_r, max_period_s):
        return "none", None, None
    why = physical_bound(nplan, i, t_r, x_r, window_min, max_period_s, coast)
    if why:
        return "no recovery", why, None
    remaining = legs[i].delta_v_mps if remaining_mps is None else remaining_mps
    starts = ((None, None), (legs[i:], remaining))   # the plan's guesses, then the nominal's

    def attempt(t, x, window, fit):
        error = two_body_error = None
        # the nominal's: its perilune after burn i, where it is still ahead (a free orbit)
        coast_s = nplan.nominal_perilunes_s[i + 1] - t
        if nplan.targets[i].kind != PERILUNE or coast_s < 60.0 * window[1] + MIN_FIRST_COAST_S:
            coast_s = None
        tries = tuple((nominal, dv, None if nominal is None else coast_s)
                      for nominal, dv in starts)
        if coast_s is not None:   # last, the plan's guesses on the nominal's coast
            tries += ((None, None, coast_s),)
        found = []   # verified recoveries, when the first is not plausible
        two_body = None   # the two-body recovery's delta-V, m/s, where one was verified
        if nplan.dynamics != "two-body":   # first from the two-body recovery
            try:
                found.append(from_two_body(nplan, i, t, x, window, max_period_s, fit, coast,
                                           tries, not later))
                two_body = found[0][1]["two_body_delta_v_mps"]
                if _plausible(*found[0]):
                    return found[0]
            except (SolveError, PlanError, RuntimeError) as exc:
                two_body_error = exc
                two_body = getattr(exc, "two_body_delta_v_mps", None)
        for k, (nominal, dv, first_coast_s) in enumerate(tries):
            if k == 2 and found:   # the third start only where the others found none
                break
            try:
                found.append(recover(nplan, i, t, x, window, max_period_s, fit, coast,
                                     nominal, not later, dv, first_coast_s))
            except (SolveError, PlanError, RuntimeError) as exc:   # RuntimeError: a guess's
                error = error or exc                                  # coast
            if len(found) == 1 and nplan.dynamics == "two-body":
                return found[0]
        if found:   # the cheapest verified
            res, est = min(found, key=lambda r: r[0].total_delta_v_mps)
            if two_body is not None:
                est["two_body_delta_v_mps"] = two_body
                if not _plausible(res, est):
                    est["doubtful"] = (
                        f"verified, but perhaps a local optimum: the recovery's burns need "
                        f"{res.total_delta_v_mps:.1f} m/s, "
                        f"{100 * (res.total_delta_v_mps / two_body - 1):.1f} % more than "
                        f"the same recovery in two-body dynamics ({two_body:.1f} m/s), "
                        f"where the Earth, the Sun and J2 are allowed "
                        f"{100 * CONTINUATION_MARGIN:.0f} %; no start found a cheaper one, "
                        f"so the penalty is an upper bound")
            return res, est
        raise _with_two_body(error if error is not None else two_body_error, two_body)

    found, first = None, None
    try:
        found = ("window",) + attempt(t_r, x_r, window_min, fit_for(window_min))
    except (SolveError, PlanError, RuntimeError) as exc:
        first = exc
    if found is not None and not (later and dearer_than_the_burn(found[1], legs, i, remaining)):
        return found
    # +-2 burn durations (at least 30 min), within the 2 h a plan's window may span
    half = min(max(60.0 * MIN_ORBIT_WINDOW_MIN, 2.0 * legs[i].raw.t1_s),
               30.0 * MAX_START_MIN)
    window = next_perilune_window(x_r, 60.0 * window_min[1], half) if later else None
    if window is None or 60.0 * window[1] > max_period_s:
        return _found_or_raise(found, first)
    # resumed where that window opens (a plan's ignition window lies within 2 h of its
    # epoch): the coast to there is the same coast
    t_b = t_r + 60.0 * window[0]
    x_b = propagate(coast, t_r, np.asarray(x_r, float)[:7], t_b).final
    w_b = from_opening(window)
    if physical_bound(nplan, i, t_b, x_b, w_b, max_period_s, coast):
        return _found_or_raise(found, first)
    try:
        res, est = attempt(t_b, x_b, w_b, fit_for(window))
    except (SolveError, PlanError, RuntimeError):
        return _found_or_raise(found, first)
    if found is not None:
        if found[1].total_delta_v_mps <= res.total_delta_v_mps:
            return found
        est["window_delta_v_mps"] = found[1].total_delta_v_mps
    est["first_coast_guess_s"] += t_b - t_r
    return "next perilune", res, est


def from_opening(window: tuple) -> tuple:
    """A window (min) counted from its opening, at most the 2 h a plan's window may span.

    (Two half-widths of 60 min make 120.00000000000003 min, which the plan's checks refuse:
    the last burn of family-2 of the seed-24 family, a quarter and 30 min, stayed in the
    window at +829 m/s; at the next perilune it costs -0.33 m/s.)
    """
    return (0.0, min(window[1] - window[0], MAX_START_MIN))


def _found_or_raise(found, first):
    """The window's recovery if there is one, else its error (raised)."""
    if found is None:
        raise first
    return found


def dearer_than_the_burn(res, legs: list, i: int, remaining_mps: float) -> bool:
    """Whether a recovery's penalty exceeds the nominal burn's own delta-V (m/s).

    A make-up that costs more than flying the whole burn again is made where the orbit
    does not suit it, and the next perilune is tried as well. Family-2 and family-4 of
    the seed-24 family (full dynamics), the last burn cut off after a quarter, 30 min: the
    spacecraft is above the final circle, and the make-up in the window costs 829 m/s
    more than the nominal, at the next perilune -0.33 and +0.36 m/s. The 440 N user plan,
    burn 1 cut off at 0.9, 720 min: +666 m/s in the window, 1.7 h before a perilune.
    ``remaining_mps``: the delta-V of the nominal burn not flown.
    """
    later = sum(s.delta_v_mps for s in legs[i + 1:])
    return res.total_delta_v_mps - remaining_mps - later > legs[i].delta_v_mps
